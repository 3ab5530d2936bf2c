//! Outline skeletons (seed 003): an animatable skeleton from a closed 2D outline in real time.
//!
//! ```text
//! CSV / SVG ──read_outline──▶ Outline (simple, counter-clockwise)
//!   ──resample──▶ uniform stroke ──douglas_peucker_closed──▶ polygon
//!   ──straight_skeleton──▶ StraightSkeleton (edge and split events, priority queue)
//!   ──axis_graph──▶ AxisGraph (no peripheral arcs, short arcs collapsed)
//!   ──spline_samples / slices / bounded_dp──▶ joints ──▶ OutlineSkeleton (Skeleton + radii)
//!   ──inflate──▶ closed Mesh (Poisson height field)      [outline_part]
//! several parts ──assemble──▶ one Skeleton + Mesh (intersection test, attachment rule)
//! ```
//!
//! The outline lies in the XY plane with +Y up; skeletons and meshes are in outline units
//! with the outline at z = 0 and the thickness along ±Z.

mod assemble;
mod axis;
mod bounded_dp;
mod douglas_peucker;
mod error;
mod inflate;
mod input;
mod options;
mod part;
mod resample;
mod simple;
mod straight_skeleton;
mod svg;
mod svg_path;

pub use assemble::{assemble, attach_point, bone_distance, Assembly, PartPlacement};
pub use axis::{axis_graph, AxisGraph};
pub use bounded_dp::{bounded_dp, slices, spline_samples, Slice};
pub use douglas_peucker::{douglas_peucker, douglas_peucker_closed, point_segment_distance};
pub use error::OutlineError;
pub use inflate::{inflate, outline_part, OutlinePart};
pub use input::{parse_csv, parse_svg, read_outline, Outline};
pub use options::{BoundedDpOptions, InflateOptions, OutlineOptions};
pub use part::{outline_skeleton, OutlineSkeleton};
pub use resample::resample;
pub use straight_skeleton::{straight_skeleton, SkeletonNode, StraightSkeleton};
pub use svg::outline_svg;

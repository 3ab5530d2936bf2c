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
//!
//! ## Example
//!
//! ```
//! use glam::DVec2;
//! use skelfit::outline::{outline_skeleton, Outline, OutlineOptions};
//!
//! // A plus sign with arms of width 2 and length 3 around the origin.
//! let corners = [
//!     (1.0, -4.0), (1.0, -1.0), (4.0, -1.0), (4.0, 1.0), (1.0, 1.0), (1.0, 4.0),
//!     (-1.0, 4.0), (-1.0, 1.0), (-4.0, 1.0), (-4.0, -1.0), (-1.0, -1.0), (-1.0, -4.0),
//! ];
//! let points: Vec<DVec2> = corners.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
//! let options = OutlineOptions::default();
//! let outline = Outline::new(points, &options)?;
//! let part = outline_skeleton(&outline, &options)?;
//! // One root at the centre and one terminal joint per arm.
//! let degrees = skelfit::lod::degrees(&part.skeleton);
//! assert_eq!(degrees.iter().filter(|&&d| d == 1).count(), 4);
//! assert!(part.skeleton.joints[0].position.length() < 1e-6);
//! # Ok::<(), skelfit::outline::OutlineError>(())
//! ```

mod assemble;
mod axis;
mod bounded_dp;
mod error;
mod inflate;
pub(crate) mod input;
mod options;
mod part;
mod resample;
mod simple;
mod straight_skeleton;
mod svg;
mod svg_path;

pub use crate::math::{douglas_peucker, douglas_peucker_closed, point_segment_distance};
pub use assemble::{assemble, attach_point, bone_distance, Assembly, PartPlacement};
pub use axis::{axis_graph, AxisGraph};
pub use bounded_dp::{bounded_dp, slices, spline_samples, Slice, MAX_THRESHOLD_STEPS};
pub use error::OutlineError;
pub use inflate::{inflate, outline_part, OutlinePart};
pub use input::{parse_csv, parse_svg, read_outline, Outline};
pub use options::{BoundedDpOptions, InflateOptions, OutlineOptions};
pub use part::{outline_skeleton, OutlineSkeleton};
pub use resample::{resample, MAX_RESAMPLED_POINTS};
pub use straight_skeleton::{straight_skeleton, SkeletonNode, StraightSkeleton};
pub use svg::outline_svg;

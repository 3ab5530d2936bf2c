//! Slicing-based refinement of a roughly aligned humanoid skeleton (seed 004): the mesh is cut by
//! planes and spheres to place the joints where a human's joints are.
//!
//! ```text
//! rough skeleton + canonical map
//!   ─▶ body frame: transverse normal from ankle→hip vectors; head slices from the top down
//!      (diameter shrink / principal axes turning); frontal and sagittal normals from the head
//!   ─▶ head joint: perimeter-weighted head centroid at nose level, averaged with the occipital
//!      circle's centre
//!   ─▶ torso: median-plane silhouette (cubic B-spline) → neck, back, lumbar, sacroiliac,
//!      throat, crotch points
//!   ─▶ hips: transverse slice between crotch and sacroiliac heights, halves' centroids
//!   ─▶ limbs: Plumber sphere slices (barycentres, perimeters, diameters, B-splines) →
//!      ankles (curvature), wrists (thickness/width minima), knees and elbows (smallest angle or
//!      limb ratio + minimal perimeter), shoulders (armpit + half-rotated sagittal plane)
//!   ─▶ spine: Catmull-Rom curve through head, C7/T1, T6/T7, L3/L4, sacrum; 24 inter-vertebral
//!      joints + sacrum by equation (1) (closed form)
//!   ─▶ skeleton: refined joints moved, the rest carried along, frames turned
//! ```
//!
//! [`symmetrize`] (`symmetry.rs`, any template): the paired joints of a bilaterally symmetric
//! figure are made to mirror each other across its median plane.
//!
//! Anything that cannot be found keeps its rough position with a warning naming the joint.

mod arm_pieces;
mod arms;
mod carry;
mod driver;
mod error;
mod frame;
mod full_spine;
mod geometry;
mod head;
mod joint_pieces;
mod legs;
mod limb;
mod limb_joints;
mod options;
mod shoulder;
mod spine;
mod symmetry;
mod torso;
mod warning;

pub use carry::carry;
pub use driver::{refine, refine_fit, Refinement, NECK_MAX_LEAN_DEGREES, REFINED, REFINED_KEYS};
pub use error::RefineError;
pub use frame::{frame_from_head, head_slices, BodyFrame, HeadSlices};
pub use full_spine::{
    along_chain, full_spine, pull_inside, NoFullSpine, SpineDetail, GIRDLE_VERTEBRA,
};
pub use head::{head_joint, HeadJoint, CONDYLES_BEHIND_CENTROID};
pub use joint_pieces::{joint_balls, JointBall};
pub use limb::{trace_limb, LimbProfile, LimbSlice};
pub use limb_joints::{ankle, arc_near, bend, on_axis, wrist, BendRule};
pub use options::{HeadLevel, RefineOptions};
pub use shoulder::{armpit, shoulder, upper_arm_line};
pub use spine::{spine, Spine, SPINE_JOINTS};
pub use symmetry::{symmetrize, Symmetry, SYMMETRIC_SHARE};
pub use torso::{
    hips, leg_split_height, split_flare, torso_points, TorsoBounds, TorsoPoints, HEM_FLARE,
};
pub use warning::RefineWarning;

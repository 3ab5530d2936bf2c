//! Skinning: regions of influence, per-vertex weights and deformation for posing
//! (dissertation 5.2.5 "Anchoring Skin Vertices to the Control Skeleton" and 8.3 "Attachment").
//!
//! ```text
//! SegmentVoxels (chain voxels per segment, from the skeleton builder or bone_segments)
//!      │  influence: distance-map spheres of every chain voxel mark the voxels a segment
//!      │             covers; breadth-first propagation fills uncovered interior voxels and
//!      ▼             the surface voxels holding mesh vertices
//! Influence (a set of segments per voxel)
//!      │  anchor_weights: w_i = (total - d_i) / ((n - 1) total) per vertex
//!      ▼  engine_weights: the four largest, renormalised, as glTF-ready f32
//! Skin ──deform(pose)──▶ posed Mesh (linear blend skinning)
//! ```
//!
//! [`skin`] runs the whole stage for segments handed over by the skeleton builder;
//! [`skin_from_bones`] needs only a skeleton and derives the segments from its bones.
//!
//! ```
//! use glam::{DQuat, DVec3};
//! use skelfit::distance::edt;
//! use skelfit::mesh::Mesh;
//! use skelfit::skeleton::{Joint, JointId, Skeleton};
//! use skelfit::skin::{deform, skin_from_bones, SkinOptions};
//! use skelfit::voxel::{voxelize, VoxelOptions, VoxelSize};
//!
//! let mesh = Mesh::capsule(DVec3::ZERO, 0.5, 1.5, 8, 16);
//! let options = VoxelOptions { size: VoxelSize::Fraction(1.0 / 40.0), ..Default::default() };
//! let solid = voxelize(&mesh, &options).unwrap();
//! let distance = edt(&solid);
//! let skeleton = Skeleton { joints: vec![
//!     Joint::new("root", None, DVec3::new(0.0, -1.5, 0.0)),
//!     Joint::new("mid", Some(JointId(0)), DVec3::ZERO),
//!     Joint::new("tip", Some(JointId(1)), DVec3::new(0.0, 1.5, 0.0)),
//! ] };
//! let skin = skin_from_bones(&mesh, &skeleton, &solid, &distance, &SkinOptions::default()).unwrap();
//! for weights in &skin.weights {
//!     let sum: f64 = weights.iter().map(|(_, w)| w).sum();
//!     assert!((sum - 1.0).abs() < 1e-12);
//! }
//! let rest = deform(&mesh, &skeleton, &skin, &skeleton.rest_pose()).unwrap();
//! assert_eq!(rest, mesh);
//! ```

mod bind;
pub mod check;
mod coarse;
pub mod compare;
mod deform;
mod digits;
mod enclosed;
mod error;
mod geodesic;
mod given;
mod influence;
mod neighbourhood;
mod options;
mod placement;
mod props;
mod segments;
mod weights;

pub use bind::{skin, skin_from_bones, Skin};
pub use deform::deform;
pub use digits::digit_weights;
pub use error::{SkinError, SkinWarning};
pub use given::{skin_skeleton, SkeletonSkinOptions, SkinnedSkeleton};
pub use influence::{influence, Influence};
pub use options::{SkinMethod, SkinOptions};
pub use placement::{placement, Placement, PlacementOptions};
pub(crate) use props::bind_props;
pub use segments::{bone_segments, SegmentVoxels};
pub use weights::{anchor_weights, engine_weights, EngineWeights, MAX_ENGINE_INFLUENCES};

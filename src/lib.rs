//! # skelfit
//!
//! skelfit fits anatomical control skeletons into polygon meshes of humanoids, quadrupeds and
//! other vertebrate-like figures, skins the mesh to them, builds bone meshes, and validates every
//! joint against reference rigs.
//!
//! The pipeline flows one way; every stage is a public function over plain data:
//!
//! ```text
//! mesh file ──mesh::load──▶ Mesh ──voxel::voxelize──▶ Solid (inside mask on a Grid)
//!                                   └─distance::edt──▶ DistanceMap (exact squared EDT)
//!                                   └─medial::dms────▶ MedialSurface
//!                                   └─paths::path_tree─▶ PathTree (heart, extreme points, chains)
//!                                   └─general::control_skeleton─▶ GeneralSkeleton (Skeleton + segments)
//! MedialSurface ──anatomy::label_pieces──▶ Labelling ──fit::fit_input──▶ FitInput (labelled paths)
//! FitInput + template::Template ──fit::fit──▶ Fit (anatomical Skeleton + canonical map)
//! Skeleton + SegmentVoxels ──skin::skin──▶ Skin (per-vertex weights) ──skin::deform──▶ posed Mesh
//! Fit + DistanceMap ──bones::bones──▶ Bones (procedural bone meshes attached to joints)
//! Mesh + Skeleton + Skin ──export::write_glb / write_bvh / write_skeleton_json──▶ files
//! ```
//!
//! [`pipeline::general_skeleton`] runs the whole chain from a mesh to a general control
//! skeleton (dissertation ch.5); [`pipeline::rig`] from a mesh to a skinned anatomical skeleton
//! from a template (ch.7-8).
//!
//! See `ARCHITECTURE.md` in the repository for the whole map, the conventions (units, axes,
//! determinism, errors) and the seed sections each module implements.
//!
//! ## Example
//!
//! ```
//! use skelfit::mesh::Mesh;
//! use skelfit::voxel::{voxelize, VoxelOptions, VoxelSize};
//! use skelfit::distance::edt;
//!
//! // A closed unit cube (12 triangles).
//! let mesh = Mesh::cuboid(glam::DVec3::ZERO, glam::DVec3::ONE);
//! let options = VoxelOptions { size: VoxelSize::Fraction(1.0 / 32.0), ..Default::default() };
//! let solid = voxelize(&mesh, &options).unwrap();
//! let volume = solid.interior_volume();
//! assert!((volume - 1.0).abs() < 0.03, "volume {volume}");
//! let dist = edt(&solid);
//! // The deepest voxel of a 32-voxel cube lies ~16 voxels from the outside.
//! assert!(dist.max_distance() > 15.0 && dist.max_distance() < 17.5);
//! ```
#![warn(missing_docs)]

pub mod anatomy;
pub mod bones;
pub mod digits;
pub mod distance;
pub mod error;
pub mod eval;
pub mod export;
pub mod fit;
pub mod general;
pub mod lod;
mod math;
pub mod medial;
pub mod mesh;
pub mod options;
pub mod outline;
pub mod output;
pub mod paths;
pub mod pipeline;
pub mod refine;
pub mod report;
pub mod skeleton;
pub mod skin;
pub mod template;
pub mod voxel;
pub mod warning;

pub use error::{Error, Result};

//! The path tree of a discrete medial surface (dissertation ch.5.2.4).
//!
//! [`path_tree`] simplifies a [`MedialSurface`](crate::medial::MedialSurface) to a tree of 1D
//! voxel pathways (*chains*) reaching from a central voxel into every significant protrusion:
//!
//! - [`DmsGraph`] (`graph.rs`): the 26-connected adjacency of the DMS voxels as flat arrays;
//! - [`Search`] (`dijkstra.rs`): multi-source, incremental Dijkstra searches over it, by path
//!   length (voxel units) or by the weighted measure `1/d^3`;
//! - [`heart`] (`heart.rs`): the heart (minimum depth sum) and the heart radius;
//! - [`extreme_points`] (`extreme.rs`): local depth maxima seen from the heart, grouped;
//! - [`Coverage`] (`coverage.rs`): DMS voxels inside the distance-map spheres of the tree;
//! - [`path_tree`] (`tree.rs`): the growth loop with the closeness-of-fit threshold;
//! - [`chains`] (`chains.rs`): endpoint/junction classification, chains and their smoothing.
//!
//! ```
//! use skelfit::distance::edt;
//! use skelfit::medial::{dms, MedialOptions};
//! use skelfit::mesh::Mesh;
//! use skelfit::paths::{path_tree, PathOptions};
//! use skelfit::voxel::{voxelize, VoxelOptions};
//!
//! let mesh = Mesh::capsule(glam::DVec3::ZERO, 0.2, 0.6, 8, 16);
//! let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
//! let surface = dms(&edt(&solid), &MedialOptions::default()).unwrap();
//! let tree = path_tree(&surface, &PathOptions::default()).unwrap();
//! // A capsule's path tree is one chain along its axis.
//! assert_eq!(tree.chains.len(), 1);
//! ```

mod chains;
mod coverage;
mod dijkstra;
mod error;
mod extreme;
mod graph;
mod heart;
mod options;
#[cfg(test)]
pub(crate) mod testing;
mod tree;

pub use chains::{chains, Chain};
pub use coverage::Coverage;
pub use dijkstra::{path_lengths, Search};
pub use error::PathError;
pub use extreme::{extreme_points, ExtremePoint};
pub use graph::DmsGraph;
pub use heart::{heart, Heart};
pub use options::PathOptions;
pub use tree::{path_tree, PathTree, PathWarning};

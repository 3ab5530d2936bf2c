//! Voxelization: the [`Grid`], triangle rasterisation into surface voxels and the robust
//! inside/outside classification that turns a [`Mesh`](crate::mesh::Mesh) into a [`Solid`].

mod boundary;
mod components;
mod duplicates;
mod error;
mod figure;
mod grid;
mod join;
mod options;
mod outlier;
mod sizing;
mod solid;
mod surface;
mod voxelize;
mod warning;
mod winding;

pub use boundary::boundary_mesh;
pub use error::VoxelError;
pub use figure::Prop;
pub use grid::{Connectivity, Grid, Neighbour, NEIGHBOURS_26};
pub use join::DroppedPiece;
pub use options::{VoxelOptions, VoxelSize};
pub use solid::{Solid, VoxelReport};

pub use voxelize::{grid_for, voxelize, voxelize_figure};
pub use warning::VoxelWarning;

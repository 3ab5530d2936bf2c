//! Voxelization: the [`Grid`], triangle rasterisation into surface voxels and the robust
//! inside/outside classification that turns a [`Mesh`](crate::mesh::Mesh) into a [`Solid`].

mod error;
mod grid;
mod options;
mod solid;

pub use error::VoxelError;
pub use grid::{Connectivity, Grid, Neighbour, NEIGHBOURS_26};
pub use options::{VoxelOptions, VoxelSize};
pub use solid::{Solid, VoxelReport};

use crate::mesh::Mesh;

/// Voxelizes `mesh` into a [`Solid`].
///
/// # Errors
/// See [`VoxelError`].
pub fn voxelize(mesh: &Mesh, options: &VoxelOptions) -> Result<Solid, VoxelError> {
    let _ = (mesh, options);
    todo!("implemented in the foundation change")
}

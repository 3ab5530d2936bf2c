use thiserror::Error;

/// Errors from voxelizing a mesh.
#[derive(Debug, Error, PartialEq)]
pub enum VoxelError {
    /// The mesh has no triangles.
    #[error("the mesh has no triangles: nothing to voxelize")]
    NoTriangles,
    /// The voxel size is not a positive finite number (or a fraction not in (0, 1]).
    #[error("invalid voxel size {value}: give a positive size in mesh units, or a fraction in (0, 1] of the longest side")]
    InvalidSize {
        /// The size given.
        value: f64,
    },
    /// The mesh's bounding box is flat or a point.
    #[error("the mesh is flat (bounding box {extent:?}): a figure needs volume to be voxelized")]
    Flat {
        /// Bounding-box extent along x, y and z.
        extent: [f64; 3],
    },
    /// The grid would exceed the voxel budget.
    #[error("a grid of {dims:?} = {voxels} voxels exceeds the budget of {budget}: use a voxel size of at least {fitting_size:.6} mesh units (fraction {fitting_fraction:.5}) or raise the budget")]
    TooLarge {
        /// The grid dimensions asked for.
        dims: [usize; 3],
        /// Their product.
        voxels: usize,
        /// The budget.
        budget: usize,
        /// The smallest absolute voxel size that fits the budget.
        fitting_size: f64,
        /// The same as a fraction of the longest bounding-box side.
        fitting_fraction: f64,
    },
    /// No voxel centre lies inside the mesh.
    #[error("no voxel lies inside the mesh at voxel size {voxel_size}: the mesh is open, flat or thinner than a voxel; use a smaller voxel size or close the mesh")]
    EmptyInterior {
        /// The voxel size used, mesh units.
        voxel_size: f64,
    },
}

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
    /// The voxel budget is below the smallest grid any mesh gets.
    #[error("a voxel budget of {budget} is too small: the smallest grid (one voxel plus the padding on every side) has {minimum} voxels; raise the budget to at least {minimum}")]
    BudgetTooSmall {
        /// The budget given.
        budget: usize,
        /// The smallest possible grid, [`VoxelOptions::minimum_voxels`](super::VoxelOptions::minimum_voxels).
        minimum: usize,
    },
    /// The winding-number threshold is not in [0, 1).
    #[error("invalid inside threshold {value}: give a winding number in [0, 1)")]
    InvalidThreshold {
        /// The threshold given.
        value: f64,
    },
    /// The gap within which pieces are joined is not in [0, 1].
    #[error("invalid join gap {value}: give a fraction of the longest side in [0, 1] (0 keeps only the largest piece of the interior)")]
    InvalidJoinGap {
        /// The fraction given.
        value: f64,
    },
    /// The grid's working memory exceeds the memory available.
    #[error("a grid of {dims:?} = {voxels} voxels needs about {} MiB of working memory but only {} MiB are available: use a voxel size of at least {fitting_size} mesh units (fraction {fitting_fraction}) or free memory", needed_bytes >> 20, available_bytes >> 20)]
    OutOfMemory {
        /// The grid dimensions asked for.
        dims: [usize; 3],
        /// Their product.
        voxels: usize,
        /// Estimated working memory of the voxel and distance stages, bytes.
        needed_bytes: u64,
        /// Memory available on this machine, bytes.
        available_bytes: u64,
        /// The smallest absolute voxel size whose grid fits the memory available.
        fitting_size: f64,
        /// The same as a fraction of the longest bounding-box side.
        fitting_fraction: f64,
    },
    /// The mesh's bounding box is flat or a point.
    #[error("the mesh is flat (bounding box {extent:?}): a figure needs volume to be voxelized")]
    Flat {
        /// Bounding-box extent along x, y and z.
        extent: [f64; 3],
    },
    /// The grid would exceed the voxel budget.
    #[error("a grid of {} exceeds the budget of {budget} voxels: use a voxel size of at least {fitting_size} mesh units (fraction {fitting_fraction}) or raise the budget", grid_text(dims, *voxels))]
    TooLarge {
        /// The grid dimensions asked for (saturated at `usize::MAX` when they overflow).
        dims: [usize; 3],
        /// Their product (`usize::MAX` when it overflows).
        voxels: usize,
        /// The budget.
        budget: usize,
        /// An absolute voxel size that fits the budget (the smallest, rounded up to four
        /// significant digits).
        fitting_size: f64,
        /// A fraction of the longest bounding-box side that fits the budget (rounded up to
        /// four significant digits; at most 1).
        fitting_fraction: f64,
    },
    /// No voxel centre lies inside because one vertex far outside the rest of the mesh
    /// stretched the bounding box (and so the voxels).
    #[error("vertex {vertex} at {position:?} lies far outside the rest of the mesh (which spans {core_size:.6}), so the voxels ({voxel_size:.6}) are too coarse to find an inside: remove or fix that vertex in the modelling tool")]
    Outlier {
        /// Index of the vertex in the (welded) mesh.
        vertex: usize,
        /// Its position, mesh units.
        position: [f64; 3],
        /// Longest side of the box holding the other vertices (1st to 99th percentile).
        core_size: f64,
        /// The voxel size used, mesh units.
        voxel_size: f64,
    },
    /// No voxel centre lies inside the mesh.
    #[error("no voxel lies inside the mesh at voxel size {voxel_size}: the mesh is open, flat or thinner than a voxel; use a smaller voxel size or close the mesh")]
    EmptyInterior {
        /// The voxel size used, mesh units.
        voxel_size: f64,
    },
}

/// `[x, y, z] = n voxels`, or "more than" the largest count for sizes that overflow.
fn grid_text(dims: &[usize; 3], voxels: usize) -> String {
    if voxels == usize::MAX {
        let axes = dims.map(|d| match d {
            usize::MAX => "overflow".to_string(),
            d => d.to_string(),
        });
        format!("[{}] (more than {} voxels)", axes.join(", "), usize::MAX)
    } else {
        format!("{dims:?} = {voxels} voxels")
    }
}

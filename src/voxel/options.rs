//! Voxelization parameters.

use serde::Serialize;

/// How large a voxel is.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum VoxelSize {
    /// Absolute edge length in mesh units.
    Absolute(f64),
    /// Fraction of the longest side of the mesh's bounding box (dissertation Table 5.2: voxel
    /// size is given relative to the model's largest dimension).
    Fraction(f64),
}

/// Options of [`voxelize`](super::voxelize).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct VoxelOptions {
    /// Voxel size. Default: 0.01 of the longest bounding-box side (dissertation Table 5.2).
    pub size: VoxelSize,
    /// Largest number of voxels (padding included) the grid may have. Default 64 M voxels
    /// (~0.5 GiB of working memory across the voxel and distance stages).
    pub max_voxels: usize,
    /// Empty voxels added on every side of the bounding box. Default 2: one guarantees an
    /// exterior voxel next to every interior one, the second keeps the surface rasterisation of
    /// triangles lying exactly on the bounding box inside the grid.
    pub padding: usize,
    /// Winding-number threshold above which a voxel centre counts as inside. Default 0.5, the
    /// usual choice for generalised winding numbers (Jacobson et al. 2013).
    pub inside_threshold: f64,
}

impl Default for VoxelOptions {
    fn default() -> Self {
        Self {
            size: VoxelSize::Fraction(0.01),
            max_voxels: 64 << 20,
            padding: 2,
            inside_threshold: 0.5,
        }
    }
}

//! The voxelized figure.

use super::Grid;
use serde::Serialize;

/// A voxelized figure: which voxels of a [`Grid`] are inside the mesh.
///
/// The grid always has at least one layer of outside voxels on every side, so every interior
/// voxel has an exterior voxel to measure distance to.
#[derive(Debug, Clone)]
pub struct Solid {
    /// The grid the masks live on.
    pub grid: Grid,
    /// `inside[i]`: voxel `i`'s centre is inside the figure (after keeping only the largest
    /// 26-connected component).
    pub inside: Vec<bool>,
    /// `surface[i]`: voxel `i` is touched by at least one triangle.
    pub surface: Vec<bool>,
    /// What the classification found and dropped.
    pub report: VoxelReport,
}

/// Diagnostics of a voxelization, for reports and warnings.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct VoxelReport {
    /// Number of interior voxels kept.
    pub interior_voxels: usize,
    /// Number of voxels touched by triangles.
    pub surface_voxels: usize,
    /// Number of 26-connected interior components found before keeping the largest.
    pub components: usize,
    /// Interior voxels dropped with the smaller components.
    pub dropped_voxels: usize,
    /// Voxels whose inside/outside votes disagreed (a sign of holes or self-intersections).
    pub ambiguous_voxels: usize,
}

impl Solid {
    /// Number of interior voxels.
    pub fn interior_count(&self) -> usize {
        self.report.interior_voxels
    }

    /// Interior volume in mesh units cubed (interior voxels times voxel volume).
    pub fn interior_volume(&self) -> f64 {
        self.interior_count() as f64 * self.grid.voxel_volume()
    }

    /// Linear indices of the interior voxels, ascending.
    pub fn interior_indices(&self) -> Vec<usize> {
        (0..self.inside.len()).filter(|&i| self.inside[i]).collect()
    }
}

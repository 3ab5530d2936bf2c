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
    /// Connected pieces of the mesh left out of the voxelization because they lie apart from
    /// the figure (see [`voxelize`](super::voxelize)).
    pub left_out_pieces: usize,
    /// Their triangles.
    pub left_out_triangles: usize,
    /// Their share of the mesh's surface area, 0-1.
    pub left_out_area_share: f64,
}

/// Dropped interior components are worth a warning from this share of the interior on (a
/// pinched finger tip drops a voxel or two).
const DROPPED_WARNING: f64 = 0.005;

impl VoxelReport {
    /// What the voxelization left out, as warning sentences: loose pieces apart from the
    /// figure, and interior components smaller than the largest when they hold at least 0.5 %
    /// of the interior.
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.left_out_pieces > 0 {
            out.push(format!(
                "{} loose piece{} of the mesh ({} triangles, {:.2} % of the surface area) {} apart \
                 from the figure and {} left out of the voxels (delete them from the mesh if they \
                 are not part of the figure)",
                self.left_out_pieces,
                if self.left_out_pieces == 1 { "" } else { "s" },
                self.left_out_triangles,
                100.0 * self.left_out_area_share,
                if self.left_out_pieces == 1 { "lies" } else { "lie" },
                if self.left_out_pieces == 1 { "was" } else { "were" }
            ));
        }
        let all = self.interior_voxels + self.dropped_voxels;
        if self.dropped_voxels as f64 >= DROPPED_WARNING * all as f64 && self.dropped_voxels > 0 {
            out.push(format!(
                "the figure's interior has {} separate parts: the largest was kept, the others \
                 ({} voxels, {:.1} % of the interior) were dropped",
                self.components,
                self.dropped_voxels,
                100.0 * self.dropped_voxels as f64 / all.max(1) as f64
            ));
        }
        out
    }
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

//! The voxelized figure.

use super::{DroppedPiece, Grid, Prop, VoxelWarning};
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
    /// Number of 26-connected interior components found (before joining).
    pub components: usize,
    /// Components joined to the figure across a gap (separate shells: a head, hands, clothes).
    pub joined_pieces: usize,
    /// The widest gap crossed by a join, in mesh units.
    pub widest_gap: f64,
    /// Outside voxels made inside to bridge the gaps.
    pub bridge_voxels: usize,
    /// Interior voxels dropped with the components lying apart from the figure.
    pub dropped_voxels: usize,
    /// The components dropped, largest first.
    pub dropped_pieces: Vec<DroppedPiece>,
    /// Voxels whose inside/outside votes disagreed (a sign of holes or self-intersections).
    pub ambiguous_voxels: usize,
    /// Connected pieces of the mesh left out of the voxelization because they lie apart from
    /// the figure (see [`voxelize`](super::voxelize)).
    pub left_out_pieces: usize,
    /// Their triangles.
    pub left_out_triangles: usize,
    /// Their share of the mesh's surface area, 0-1.
    pub left_out_area_share: f64,
    /// The grid was refined by [`voxelize_figure`](super::voxelize_figure): the fraction of
    /// the longest side first tried and the interior voxels it held.
    pub refined_from: Option<(f64, usize)>,
    /// Triangles left out of the inside/outside vote because they repeat another one (same
    /// three vertices; see [`voxelize`](super::voxelize)).
    pub duplicate_triangles: usize,
    /// Thin, long pieces the figure holds (a sword, a staff), left out of the voxels so that
    /// they make no limb ([`Prop`]); the skin binds each rigidly to the joint it touches.
    pub props: Vec<Prop>,
    /// Small open sheets left out of the voxels: hair cards, lashes, brows (at most 1 % of the
    /// area each, a voxel thick, with a boundary edge): they enclose nothing, and stacked they
    /// turned the inside/outside vote around a head.
    pub sheets: usize,
    /// The sheets' vertices, ascending (not serialized).
    #[serde(skip)]
    pub sheet_vertices: Vec<u32>,
}

/// Dropped interior components are worth a warning from this share of the interior on (a
/// pinched finger tip drops a voxel or two).
const DROPPED_WARNING: f64 = 0.005;

impl VoxelReport {
    /// What the voxelization left out: loose pieces apart from the figure, and interior
    /// components smaller than the largest when they hold at least 0.5 % of the interior.
    pub fn warnings(&self) -> Vec<VoxelWarning> {
        let mut out = Vec::new();
        if self.left_out_pieces > 0 {
            out.push(VoxelWarning::LooseMeshPieces {
                pieces: self.left_out_pieces,
                triangles: self.left_out_triangles,
                area_share: self.left_out_area_share,
            });
        }
        let all = self.interior_voxels + self.dropped_voxels;
        if self.dropped_voxels as f64 >= DROPPED_WARNING * all as f64 && self.dropped_voxels > 0 {
            out.push(VoxelWarning::DroppedInterior {
                pieces: self.dropped_pieces.clone(),
                dropped_voxels: self.dropped_voxels,
                interior_voxels: all,
            });
        }
        if !self.props.is_empty() {
            out.push(VoxelWarning::HeldProps {
                props: self.props.clone(),
            });
        }
        if self.duplicate_triangles > 0 {
            out.push(VoxelWarning::DuplicateTriangles {
                triangles: self.duplicate_triangles,
            });
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

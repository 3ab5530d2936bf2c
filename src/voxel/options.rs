//! Voxelization parameters.

use super::VoxelError;
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
    /// Interior pieces (separate shells: a head, hands, clothing) lying within this fraction of
    /// the grid's longest side of the figure are joined to it by a bridge across the gap;
    /// pieces farther away are dropped with a warning naming them. Default 0.1, the margin
    /// within which the voxelization keeps a loose piece of the mesh as part of the figure.
    /// 0 keeps only the largest piece.
    pub join_gap: f64,
    /// [`voxelize_figure`](super::voxelize_figure) refines a grid sized by a fraction of the
    /// longest side until the figure holds at least this many interior voxels (one finer try).
    /// Default 8,000: the stages' thresholds were measured on human bodies holding about 12,000
    /// at the default size; a long-necked, long-tailed animal at 1 % of its length holds 2,000,
    /// its legs two voxels thick, too thin for a medial surface. 0 keeps the first grid.
    pub min_interior: usize,
}

impl Default for VoxelOptions {
    fn default() -> Self {
        Self {
            size: VoxelSize::Fraction(0.01),
            max_voxels: 64 << 20,
            padding: 2,
            inside_threshold: 0.5,
            join_gap: 0.1,
            min_interior: 8000,
        }
    }
}

impl VoxelOptions {
    /// The smallest grid any mesh gets: one voxel per axis plus the padding on both sides,
    /// `(1 + 2 · max(padding, 1))³` voxels (saturating).
    pub fn minimum_voxels(&self) -> usize {
        let side = self.padding.max(1).saturating_mul(2).saturating_add(1);
        side.saturating_mul(side).saturating_mul(side)
    }

    /// Checks the options before any work.
    ///
    /// # Errors
    /// [`VoxelError::InvalidSize`] for a size that is not a positive finite number (a fraction
    /// not in (0, 1]), [`VoxelError::BudgetTooSmall`] when `max_voxels` is below
    /// [`VoxelOptions::minimum_voxels`] (no mesh could ever be voxelized), and
    /// [`VoxelError::InvalidThreshold`] for an `inside_threshold` outside [0, 1), and
    /// [`VoxelError::InvalidJoinGap`] for a `join_gap` outside [0, 1].
    ///
    /// # Example
    /// ```
    /// use skelfit::voxel::{VoxelError, VoxelOptions};
    /// assert!(VoxelOptions::default().validate().is_ok());
    /// let tiny = VoxelOptions { max_voxels: 100, ..Default::default() };
    /// assert!(matches!(tiny.validate(), Err(VoxelError::BudgetTooSmall { minimum: 125, .. })));
    /// ```
    pub fn validate(&self) -> Result<(), VoxelError> {
        match self.size {
            VoxelSize::Absolute(h) if h > 0.0 && h.is_finite() => {}
            VoxelSize::Fraction(f) if f > 0.0 && f <= 1.0 => {}
            VoxelSize::Absolute(value) | VoxelSize::Fraction(value) => {
                return Err(VoxelError::InvalidSize { value })
            }
        }
        let minimum = self.minimum_voxels();
        if self.max_voxels < minimum {
            return Err(VoxelError::BudgetTooSmall {
                budget: self.max_voxels,
                minimum,
            });
        }
        if !(0.0..1.0).contains(&self.inside_threshold) {
            return Err(VoxelError::InvalidThreshold {
                value: self.inside_threshold,
            });
        }
        if !(0.0..=1.0).contains(&self.join_gap) {
            return Err(VoxelError::InvalidJoinGap {
                value: self.join_gap,
            });
        }
        Ok(())
    }
}

//! The 26-neighbourhood as linear index offsets, and the checks that make them safe.

use super::MedialError;
use crate::distance::DistanceMap;
use crate::voxel::{Grid, NEIGHBOURS_26};

/// Number of neighbours of a voxel (26-neighbourhood).
pub(crate) const NEIGHBOUR_COUNT: usize = 26;

/// Index ranges of the three adjacency classes inside [`NEIGHBOURS_26`]: the 6 face neighbours
/// (distance 1), the 12 strict 18-neighbours (distance sqrt 2) and the 8 strict 26-neighbours
/// (distance sqrt 3), as partitioned for the exposure and ascent calculations (ch.4.2, ch.4.3).
pub(crate) const ADJACENCY_CLASSES: [std::ops::Range<usize>; 3] = [0..6, 6..18, 18..26];

/// Centre-to-centre distance of the neighbours of each adjacency class, voxel units.
pub(crate) const CLASS_LENGTHS: [f64; 3] = [1.0, std::f64::consts::SQRT_2, 1.732_050_807_568_877_2];

/// The 26 neighbour offsets of a grid as linear index differences, in the order of
/// [`NEIGHBOURS_26`] (faces, edges, corners; see [`ADJACENCY_CLASSES`]).
///
/// Adding a delta to the index of a voxel that is not on the grid border gives the neighbour's
/// index; [`checked_interior_count`] guarantees that no interior voxel lies on the border.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LinearNeighbours {
    /// Linear index difference of each neighbour.
    pub deltas: [isize; NEIGHBOUR_COUNT],
}

impl LinearNeighbours {
    /// The offsets for `grid`.
    pub fn new(grid: &Grid) -> Self {
        let [nx, ny, _] = grid.dims;
        let mut deltas = [0isize; NEIGHBOUR_COUNT];
        for (k, n) in NEIGHBOURS_26.iter().enumerate() {
            let [dx, dy, dz] = n.offset.map(|o| o as isize);
            deltas[k] = dx + nx as isize * (dy + ny as isize * dz);
        }
        Self { deltas }
    }

    /// Index of neighbour `k` of the non-border voxel `index`.
    #[inline]
    pub fn at(&self, index: usize, k: usize) -> usize {
        index.wrapping_add_signed(self.deltas[k])
    }
}

/// Largest grid the stage supports: voxel indices are stored as `u32`, and `u32::MAX` marks
/// "none".
pub(crate) const MAX_GRID_VOXELS: usize = u32::MAX as usize - 1;

/// Checks that `distance` is consistent and padded, and returns its number of interior voxels
/// (voxels with a positive squared distance).
///
/// # Errors
/// [`MedialError::SizeMismatch`], [`MedialError::GridTooLarge`],
/// [`MedialError::EmptyFigure`], [`MedialError::InteriorOnBorder`].
pub(crate) fn checked_interior_count(distance: &DistanceMap) -> Result<usize, MedialError> {
    let grid = &distance.grid;
    let voxels = grid.len();
    if distance.squared.len() != voxels {
        return Err(MedialError::SizeMismatch {
            values: distance.squared.len(),
            voxels,
        });
    }
    if voxels > MAX_GRID_VOXELS {
        return Err(MedialError::GridTooLarge {
            voxels,
            max: MAX_GRID_VOXELS,
        });
    }
    let mut interior = 0usize;
    for (index, &squared) in distance.squared.iter().enumerate() {
        if squared == 0 {
            continue;
        }
        interior += 1;
        let coords = grid.coords(index);
        let on_border = (0..3).any(|a| coords[a] == 0 || coords[a] + 1 == grid.dims[a]);
        if on_border {
            return Err(MedialError::InteriorOnBorder { coords });
        }
    }
    if interior == 0 {
        return Err(MedialError::EmptyFigure);
    }
    Ok(interior)
}

//! The per-voxel bookkeeping of the extraction (dissertation ch.4.3).

use super::bridging::NO_VOXEL;

/// The DMS classification field of ch.4.3: processing state and membership.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Label {
    /// Not processed yet (also every exterior voxel).
    Unprocessed,
    /// Processed, not part of the DMS.
    NonMedial,
    /// Processed, exposure at or above the threshold: a true DMS voxel.
    True,
    /// Processed, exposure below the threshold, part of the DMS to keep it connected.
    Bridging,
}

impl Label {
    /// True for true and bridging DMS voxels.
    #[inline]
    pub fn is_medial(self) -> bool {
        matches!(self, Label::True | Label::Bridging)
    }
}

/// What ch.4.3 stores with each voxel, apart from the group id (kept by the
/// [`UnionFind`](super::union_find::UnionFind) that holds these records), the exposure
/// (computed when the voxel is processed) and the contour array sub-index (kept by
/// [`ContourArrays`](super::contour::ContourArrays)).
#[derive(Debug, Clone, Copy)]
pub(crate) struct VoxelRecord {
    /// Squared distance map value, voxel units squared; 0 outside.
    pub squared: u32,
    /// Steepest-ascent neighbour once processed ([`NO_VOXEL`] for the first voxel of a group).
    pub pointer: u32,
    /// DMS classification.
    pub label: Label,
    /// Number of processed 26-neighbours while unprocessed.
    pub processed: u8,
}

impl VoxelRecord {
    /// The record of an unprocessed voxel of squared distance `squared`.
    pub fn new(squared: u32) -> Self {
        Self {
            squared,
            pointer: NO_VOXEL,
            label: Label::Unprocessed,
            processed: 0,
        }
    }
}

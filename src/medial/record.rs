//! The per-voxel bookkeeping of the extraction (dissertation ch.4.3).

use super::bridging::NO_DIRECTION;

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
    /// Direction of the steepest-ascent neighbour once processed, as an index into
    /// [`NEIGHBOURS_26`](crate::voxel::NEIGHBOURS_26) ([`NO_DIRECTION`] for the first voxel of
    /// a group). A direction rather than a voxel index keeps the record at 8 bytes.
    pub pointer: u8,
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
            pointer: NO_DIRECTION,
            label: Label::Unprocessed,
            processed: 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn record_and_union_find_node_stay_small() {
        // 8 bytes of record + 4 of parent link + 1 of rank: 16 bytes per grid voxel.
        assert_eq!(std::mem::size_of::<VoxelRecord>(), 8);
        let sets = crate::medial::union_find::UnionFind::new(std::iter::once(VoxelRecord::new(1)));
        assert_eq!(sets.node_size(), 16);
    }
}

//! The per-voxel bookkeeping of the extraction (dissertation ch.4.3), packed into 8 bytes.

/// The DMS classification field of ch.4.3: processing state and membership.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Label {
    /// Not processed yet (also every exterior voxel).
    Unprocessed = 0,
    /// Processed, not part of the DMS.
    NonMedial = 1,
    /// Processed, exposure at or above the threshold: a true DMS voxel.
    True = 2,
    /// Processed, exposure below the threshold, part of the DMS to keep it connected.
    Bridging = 3,
}

impl Label {
    /// True for true and bridging DMS voxels.
    #[inline]
    pub fn is_medial(self) -> bool {
        matches!(self, Label::True | Label::Bridging)
    }

    #[inline]
    fn from_bits(bits: u32) -> Self {
        match bits & 3 {
            0 => Label::Unprocessed,
            1 => Label::NonMedial,
            2 => Label::True,
            _ => Label::Bridging,
        }
    }
}

/// Bits of [`VoxelRecord::level`]: the stage supports fewer than `2^25` distinct distance
/// values (an exact distance map of a grid with 32-bit indices has fewer than `2^20`).
pub(crate) const LEVEL_BITS: u32 = 25;
/// Bit position of the step field (processed count or pointer).
const STEP_SHIFT: u32 = 2;
/// Mask of the 5-bit step field.
const STEP_MASK: u32 = 0x1f;
/// Bit position of the level.
const LEVEL_SHIFT: u32 = 32 - LEVEL_BITS;
/// The step field's value for "no steepest-ascent neighbour" (the first voxel of a group).
const NO_POINTER: u32 = STEP_MASK;

/// What ch.4.3 stores with each grid voxel, in 8 bytes so that the neighbourhood reads of the
/// extraction (the stage's cost: contours visit the figure in distance order, not memory
/// order) touch as few cache lines as possible.
///
/// * `link`: while the voxel waits in its contour list, its sub-index in its contour array
///   ([`ContourArrays`](super::contour::ContourArrays)); once processed, its union-find parent
///   ([`UnionFind`](super::union_find::UnionFind)). An unprocessed voxel has no group and a
///   processed one is in no contour array, so the two never coexist.
/// * `bits`: the distance level ([`Levels`](super::contour::Levels): dense rank of the squared
///   distance, 0 outside) in the top 25 bits, a 5-bit step field, and the 2-bit [`Label`]. The
///   step field is the number of processed 26-neighbours while the voxel is unprocessed, and
///   its steepest-ascent direction (index into [`NEIGHBOURS_26`](crate::voxel::NEIGHBOURS_26),
///   none for the first voxel of a group) once processed: the count is no longer needed then.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct VoxelRecord {
    /// Contour array sub-index (unprocessed) or union-find parent (processed).
    pub link: u32,
    /// Level, step field and label.
    bits: u32,
}

impl VoxelRecord {
    /// The record of an unprocessed voxel at distance level `level` (`< 2^25`).
    #[inline]
    pub fn new(level: u32) -> Self {
        debug_assert!(level < 1 << LEVEL_BITS);
        Self {
            link: 0,
            bits: level << LEVEL_SHIFT,
        }
    }

    /// Distance level: 0 outside, larger for larger squared distance.
    #[inline]
    pub fn level(self) -> u32 {
        self.bits >> LEVEL_SHIFT
    }

    /// DMS classification.
    #[inline]
    pub fn label(self) -> Label {
        Label::from_bits(self.bits)
    }

    /// Sets the DMS classification.
    #[inline]
    pub fn set_label(&mut self, label: Label) {
        self.bits = (self.bits & !3) | label as u32;
    }

    #[inline]
    fn step(self) -> u32 {
        (self.bits >> STEP_SHIFT) & STEP_MASK
    }

    #[inline]
    fn set_step(&mut self, step: u32) {
        self.bits = (self.bits & !(STEP_MASK << STEP_SHIFT)) | (step << STEP_SHIFT);
    }

    /// Number of processed 26-neighbours of an unprocessed voxel.
    #[inline]
    pub fn processed(self) -> u8 {
        debug_assert_eq!(self.label(), Label::Unprocessed);
        self.step() as u8
    }

    /// Counts one more processed neighbour of an unprocessed voxel.
    #[inline]
    pub fn count_processed(&mut self) {
        debug_assert!(self.label() == Label::Unprocessed && self.step() < 26);
        self.bits += 1 << STEP_SHIFT;
    }

    /// Steepest-ascent direction of a processed voxel, `None` for the first voxel of a group.
    #[inline]
    pub fn pointer(self) -> Option<usize> {
        debug_assert_ne!(self.label(), Label::Unprocessed);
        match self.step() {
            NO_POINTER => None,
            direction => Some(direction as usize),
        }
    }

    /// Marks the voxel processed: its label, its steepest-ascent direction (an index below
    /// 26, or `None`) and its union-find parent `link`.
    #[inline]
    pub fn process(&mut self, label: Label, pointer: Option<usize>, link: u32) {
        debug_assert!(label != Label::Unprocessed && pointer.is_none_or(|p| p < 26));
        self.set_step(pointer.map_or(NO_POINTER, |p| p as u32));
        self.set_label(label);
        self.link = link;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn record_stays_at_eight_bytes() {
        assert_eq!(std::mem::size_of::<VoxelRecord>(), 8);
    }

    #[test]
    fn fields_do_not_overlap() {
        let top = (1 << LEVEL_BITS) - 1;
        let mut record = VoxelRecord::new(top);
        assert_eq!(record.label(), Label::Unprocessed);
        for _ in 0..26 {
            record.count_processed();
        }
        assert_eq!((record.level(), record.processed()), (top, 26));
        record.process(Label::Bridging, Some(25), 7);
        assert_eq!(record.level(), top);
        assert_eq!(record.label(), Label::Bridging);
        assert_eq!(record.pointer(), Some(25));
        record.set_label(Label::NonMedial);
        record.process(Label::True, None, 9);
        assert_eq!((record.level(), record.label()), (top, Label::True));
        assert_eq!((record.pointer(), record.link), (None, 9));
    }
}

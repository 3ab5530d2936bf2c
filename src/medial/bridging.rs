//! Steepest-ascent bridging between DMS voxels of a group (dissertation ch.4.3).

use super::neighbourhood::NEIGHBOUR_COUNT;
use super::record::{Label, VoxelRecord};
use super::union_find::UnionFind;

/// Marks "no voxel" in the `u32` voxel-index arrays of the stage.
pub(crate) const NO_VOXEL: u32 = u32::MAX;

/// Slope from a voxel of squared distance `from` to a neighbour of squared distance `to` at
/// centre distance `length`: `(sqrt(d_n) - sqrt(d_i)) / |i - n|` (ch.4.3).
#[inline]
pub(crate) fn ascent(from: u32, to: u32, length: f64) -> f64 {
    ((to as f64).sqrt() - (from as f64).sqrt()) / length
}

/// The steepest-ascent neighbour found so far into one group.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    /// Group representative.
    root: u32,
    /// Voxel index of the neighbour.
    voxel: u32,
    /// Its ascent from the current voxel.
    ascent: f64,
    /// Whether it already belongs to the DMS.
    medial: bool,
}

impl Candidate {
    /// Whether `other` is a better bridging step than `self`: steeper, or equally steep and
    /// already a DMS voxel (which ends the bridging path at once). Remaining ties keep the
    /// earlier neighbour in [`NEIGHBOURS_26`](crate::voxel::NEIGHBOURS_26) order (faces first).
    #[inline]
    fn beaten_by(&self, ascent: f64, medial: bool) -> bool {
        ascent > self.ascent || (ascent == self.ascent && medial && !self.medial)
    }
}

/// The groups of processed voxels adjacent to the voxel being processed, each with its
/// steepest-ascent neighbour (the bridging direction into that group, ch.4.3).
///
/// Only processed neighbours are offered. Every neighbour with a larger distance is already
/// processed (contours run in decreasing order), so this is the steepest ascent over all
/// neighbours with ties at zero ascent resolved towards processed voxels, which keeps every
/// bridging path inside its group.
#[derive(Debug, Clone)]
pub(crate) struct AdjacentGroups {
    candidates: [Candidate; NEIGHBOUR_COUNT],
    len: usize,
}

impl AdjacentGroups {
    /// No groups.
    pub fn new() -> Self {
        Self {
            candidates: [Candidate {
                root: NO_VOXEL,
                voxel: NO_VOXEL,
                ascent: f64::NEG_INFINITY,
                medial: false,
            }; NEIGHBOUR_COUNT],
            len: 0,
        }
    }

    /// Number of distinct adjacent groups.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Records the processed neighbour `voxel` of group `root` at the given ascent.
    #[inline]
    pub fn offer(&mut self, root: usize, voxel: usize, ascent: f64, medial: bool) {
        let root = root as u32;
        let found = self.candidates[..self.len]
            .iter_mut()
            .find(|c| c.root == root);
        match found {
            Some(c) => {
                if c.beaten_by(ascent, medial) {
                    *c = Candidate {
                        root,
                        voxel: voxel as u32,
                        ascent,
                        medial,
                    };
                }
            }
            None => {
                self.candidates[self.len] = Candidate {
                    root,
                    voxel: voxel as u32,
                    ascent,
                    medial,
                };
                self.len += 1;
            }
        }
    }

    /// `(group representative, steepest-ascent neighbour in it)` for each adjacent group, in
    /// order of first contact.
    pub fn groups(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.candidates[..self.len]
            .iter()
            .map(|c| (c.root as usize, c.voxel as usize))
    }

    /// The steepest-ascent neighbour over all adjacent groups, or `None` without any.
    pub fn steepest(&self) -> Option<usize> {
        let (first, rest) = self.candidates[..self.len].split_first()?;
        let mut best = first;
        for c in rest {
            if best.beaten_by(c.ascent, c.medial) {
                best = c;
            }
        }
        Some(best.voxel as usize)
    }
}

/// Follows the steepest-ascent pointers from `start` until a DMS voxel is reached, relabelling
/// every non-DMS voxel on the way as a bridging voxel (ch.4.3). Returns the number relabelled.
///
/// Pointers always lead to voxels processed earlier in the same group, and every group holds
/// a DMS voxel (its first voxel is one), so the walk ends at a DMS voxel of `start`'s group.
pub(crate) fn bridge(start: usize, voxels: &mut UnionFind<VoxelRecord>) -> usize {
    let mut voxel = start;
    let mut relabelled = 0;
    loop {
        let record = voxels.item_mut(voxel);
        if record.label != Label::NonMedial {
            debug_assert!(record.label.is_medial());
            return relabelled;
        }
        record.label = Label::Bridging;
        relabelled += 1;
        debug_assert_ne!(
            record.pointer, NO_VOXEL,
            "non-DMS voxel {voxel} without pointer"
        );
        if record.pointer == NO_VOXEL {
            return relabelled;
        }
        voxel = record.pointer as usize;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steepest_prefers_ascent_then_medial_then_first() {
        let mut groups = AdjacentGroups::new();
        groups.offer(7, 100, 0.0, false);
        groups.offer(7, 101, 0.0, true);
        groups.offer(9, 200, 0.5, false);
        groups.offer(9, 201, 0.5, false);
        assert_eq!(groups.len(), 2);
        let found: Vec<_> = groups.groups().collect();
        assert_eq!(found, vec![(7, 101), (9, 200)]);
        assert_eq!(groups.steepest(), Some(200));
        assert_eq!(AdjacentGroups::new().steepest(), None);
    }

    #[test]
    fn bridge_relabels_until_a_medial_voxel() {
        let mut voxels = UnionFind::new((0..4).map(|_| VoxelRecord::new(1)));
        let labels = [
            Label::True,
            Label::NonMedial,
            Label::NonMedial,
            Label::Unprocessed,
        ];
        for (i, label) in labels.into_iter().enumerate() {
            voxels.item_mut(i).label = label;
            voxels.item_mut(i).pointer = if i == 1 || i == 2 {
                i as u32 - 1
            } else {
                NO_VOXEL
            };
        }
        assert_eq!(bridge(2, &mut voxels), 2);
        let after: Vec<Label> = voxels.items().map(|r| r.label).take(3).collect();
        assert_eq!(after, [Label::True, Label::Bridging, Label::Bridging]);
        assert_eq!(bridge(2, &mut voxels), 0);
    }

    #[test]
    fn ascent_divides_by_centre_distance() {
        assert!((ascent(4, 9, 1.0) - 1.0).abs() < 1e-12);
        assert!((ascent(9, 4, 2f64.sqrt()) + 1.0 / 2f64.sqrt()).abs() < 1e-12);
    }
}

//! Steepest-ascent bridging between DMS voxels of a group (dissertation ch.4.3).

use super::neighbourhood::{LinearNeighbours, NEIGHBOUR_COUNT};
use super::record::Label;
use super::union_find::UnionFind;

/// Marks "no voxel" in `u32` voxel indices.
pub(crate) const NO_VOXEL: u32 = u32::MAX;

/// Marks "no neighbour" in neighbour directions (indices into
/// [`NEIGHBOURS_26`](crate::voxel::NEIGHBOURS_26)).
pub(crate) const NO_DIRECTION: u8 = u8::MAX;

/// Slope from a voxel at distance `from` to a neighbour at distance `to` (distances, not
/// squared: `sqrt(d_i)`, `sqrt(d_n)`) at centre distance `length`:
/// `(sqrt(d_n) - sqrt(d_i)) / |i - n|` (ch.4.3).
#[inline]
pub(crate) fn ascent(from: f64, to: f64, length: f64) -> f64 {
    (to - from) / length
}

/// The steepest-ascent neighbour found so far into one group.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    /// Group representative.
    root: u32,
    /// Voxel index of the neighbour.
    voxel: u32,
    /// Its direction from the current voxel (index into `NEIGHBOURS_26`).
    direction: u8,
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
                direction: NO_DIRECTION,
                ascent: f64::NEG_INFINITY,
                medial: false,
            }; NEIGHBOUR_COUNT],
            len: 0,
        }
    }

    /// Number of distinct adjacent groups.
    /// Forgets all groups, for the next voxel.
    #[inline]
    pub fn clear(&mut self) {
        self.len = 0;
    }

    pub fn len(&self) -> usize {
        self.len
    }

    /// Records the processed neighbour `voxel`, in `direction`, of group `root` at the given
    /// ascent.
    #[inline]
    pub fn offer(
        &mut self,
        root: usize,
        voxel: usize,
        direction: usize,
        ascent: f64,
        medial: bool,
    ) {
        let root = root as u32;
        let candidate = Candidate {
            root,
            voxel: voxel as u32,
            direction: direction as u8,
            ascent,
            medial,
        };
        let found = self.candidates[..self.len]
            .iter_mut()
            .find(|c| c.root == root);
        match found {
            Some(c) => {
                if c.beaten_by(ascent, medial) {
                    *c = candidate;
                }
            }
            None => {
                self.candidates[self.len] = candidate;
                self.len += 1;
            }
        }
    }

    /// `(group representative, steepest-ascent neighbour in it, its direction)` for each
    /// adjacent group, in order of first contact.
    pub fn groups(&self) -> impl Iterator<Item = (usize, usize, u8)> + '_ {
        self.candidates[..self.len]
            .iter()
            .map(|c| (c.root as usize, c.voxel as usize, c.direction))
    }

    /// The direction of the steepest-ascent neighbour over all adjacent groups, or `None`
    /// without any.
    pub fn steepest(&self) -> Option<u8> {
        let (first, rest) = self.candidates[..self.len].split_first()?;
        let mut best = first;
        for c in rest {
            if best.beaten_by(c.ascent, c.medial) {
                best = c;
            }
        }
        Some(best.direction)
    }
}

/// Follows the steepest-ascent pointers from `start` until a DMS voxel is reached, relabelling
/// every non-DMS voxel on the way as a bridging voxel (ch.4.3). Returns the number relabelled.
///
/// Pointers always lead to voxels processed earlier in the same group, and every group holds
/// a DMS voxel (its first voxel is one), so the walk ends at a DMS voxel of `start`'s group.
pub(crate) fn bridge(start: usize, voxels: &mut UnionFind, neighbours: &LinearNeighbours) -> usize {
    let mut voxel = start;
    let mut relabelled = 0;
    loop {
        let record = voxels.item_mut(voxel);
        if record.label() != Label::NonMedial {
            debug_assert!(record.label().is_medial());
            return relabelled;
        }
        record.set_label(Label::Bridging);
        relabelled += 1;
        let pointer = record.pointer();
        debug_assert!(pointer.is_some(), "non-DMS voxel {voxel} without pointer");
        let Some(direction) = pointer else {
            return relabelled;
        };
        voxel = neighbours.at(voxel, direction);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steepest_prefers_ascent_then_medial_then_first() {
        let mut groups = AdjacentGroups::new();
        groups.offer(7, 100, 0, 0.0, false);
        groups.offer(7, 101, 1, 0.0, true);
        groups.offer(9, 200, 2, 0.5, false);
        groups.offer(9, 201, 3, 0.5, false);
        assert_eq!(groups.len(), 2);
        let found: Vec<_> = groups.groups().collect();
        assert_eq!(found, vec![(7, 101, 1), (9, 200, 2)]);
        assert_eq!(groups.steepest(), Some(2));
        assert_eq!(AdjacentGroups::new().steepest(), None);
    }

    #[test]
    fn bridge_relabels_until_a_medial_voxel() {
        use crate::voxel::{Grid, NEIGHBOURS_26};
        use rayon::prelude::*;
        let grid = Grid {
            dims: [6, 3, 3],
            origin: glam::DVec3::ZERO,
            voxel_size: 1.0,
        };
        let neighbours = LinearNeighbours::new(&grid);
        let minus_x = NEIGHBOURS_26
            .iter()
            .position(|n| n.offset == [-1, 0, 0])
            .unwrap();
        let at = |x| grid.index([x, 1, 1]);
        let mut voxels = UnionFind::new(vec![1; grid.len()].into_par_iter());
        voxels
            .item_mut(at(1))
            .process(Label::True, None, at(1) as u32);
        for x in [2, 3] {
            voxels
                .item_mut(at(x))
                .process(Label::NonMedial, Some(minus_x), at(1) as u32);
        }
        assert_eq!(bridge(at(3), &mut voxels, &neighbours), 2);
        let after: Vec<Label> = (1..5).map(|x| voxels.item(at(x)).label()).collect();
        assert_eq!(
            after,
            [
                Label::True,
                Label::Bridging,
                Label::Bridging,
                Label::Unprocessed
            ]
        );
        assert_eq!(bridge(at(3), &mut voxels, &neighbours), 0);
    }

    #[test]
    fn ascent_divides_by_centre_distance() {
        assert!((ascent(2.0, 3.0, 1.0) - 1.0).abs() < 1e-12);
        assert!((ascent(3.0, 2.0, 2f64.sqrt()) + 1.0 / 2f64.sqrt()).abs() < 1e-12);
    }
}

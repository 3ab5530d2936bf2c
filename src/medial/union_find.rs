//! Disjoint sets of voxels: the groups of processed voxels (dissertation ch.4.3, ch.4.5).

use super::record::VoxelRecord;
use rayon::prelude::*;

/// The records of all grid voxels, with the union-find of the groups of processed voxels
/// threaded through their `link` fields: a processed voxel's link is its parent, a root links
/// to itself. Unprocessed voxels belong to no group (their link is their contour array
/// sub-index).
///
/// Finds use path halving. There is no rank (the record has no room for one): a voxel joining
/// a group is linked directly under the group's root, and merged groups are linked root under
/// root, so trees stay shallow in practice and path halving keeps them so. The grouping, not
/// the choice of representatives, is what the extraction uses, so its result does not depend
/// on this.
#[derive(Debug, Clone)]
pub(crate) struct UnionFind {
    records: Vec<VoxelRecord>,
}

impl UnionFind {
    /// One unprocessed record per grid voxel, at distance level `levels[i]` (parallel).
    pub fn new(levels: impl IndexedParallelIterator<Item = u32>) -> Self {
        Self {
            records: levels.map(VoxelRecord::new).collect(),
        }
    }

    /// The record of voxel `index`.
    #[inline]
    pub fn item(&self, index: usize) -> VoxelRecord {
        self.records[index]
    }

    /// The record of voxel `index`, to change.
    #[inline]
    pub fn item_mut(&mut self, index: usize) -> &mut VoxelRecord {
        &mut self.records[index]
    }

    /// All records, in voxel index order.
    pub fn items(&self) -> &[VoxelRecord] {
        &self.records
    }

    /// The representative of the group of the processed voxel `index`.
    #[inline]
    pub fn find(&mut self, index: usize) -> usize {
        let mut i = index;
        loop {
            let p = self.records[i].link as usize;
            if p == i {
                return i;
            }
            let grandparent = self.records[p].link;
            self.records[i].link = grandparent;
            i = grandparent as usize;
        }
    }

    /// Merges the groups of the processed voxels `a` and `b`: `a`'s root is linked under
    /// `b`'s. Returns the representative.
    pub fn union(&mut self, a: usize, b: usize) -> usize {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.records[ra].link = rb as u32;
        }
        rb
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::medial::record::Label;

    fn processed_singletons(n: usize) -> UnionFind {
        let mut sets = UnionFind::new((0..n as u32).into_par_iter());
        for i in 0..n {
            sets.item_mut(i).process(Label::NonMedial, None, i as u32);
        }
        sets
    }

    #[test]
    fn unions_are_transitive_and_disjoint_sets_stay_apart() {
        let mut sets = processed_singletons(10);
        sets.union(0, 1);
        sets.union(2, 3);
        sets.union(1, 3);
        sets.union(7, 8);
        assert_eq!(sets.find(0), sets.find(2));
        assert_eq!(sets.find(7), sets.find(8));
        assert_ne!(sets.find(0), sets.find(7));
        assert_eq!(sets.find(5), 5);
        assert_eq!(sets.item(5).level(), 5);
        sets.item_mut(5).set_label(Label::True);
        assert_eq!(sets.items()[5].label(), Label::True);
    }

    #[test]
    fn a_long_chain_has_one_representative() {
        let n = 10_000;
        let mut sets = processed_singletons(n);
        for i in 1..n {
            sets.union(i - 1, i);
        }
        let root = sets.find(0);
        assert!((0..n).all(|i| sets.find(i) == root));
    }
}

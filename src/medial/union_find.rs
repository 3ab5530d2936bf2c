//! Disjoint sets of voxels: the groups of processed voxels (dissertation ch.4.3, ch.4.5).

/// One element: its parent link, its rank and the caller's per-element record, stored side by
/// side so that one cache line serves both the group lookup and the record.
#[derive(Debug, Clone, Copy)]
struct Node<T> {
    parent: u32,
    rank: u8,
    item: T,
}

/// Union-find over voxel indices with path halving and union by rank, so that a sequence of
/// `m` operations on `n` voxels costs `O(m lg* n)` (ch.4.5, after Cormen, Leiserson and
/// Rivest). Each element carries a record `T` (the per-voxel bookkeeping of ch.4.3).
#[derive(Debug, Clone)]
pub(crate) struct UnionFind<T> {
    nodes: Vec<Node<T>>,
}

impl<T: Copy> UnionFind<T> {
    /// One singleton set per record, indexed like `items`.
    pub fn new(items: impl ExactSizeIterator<Item = T>) -> Self {
        debug_assert!(items.len() <= u32::MAX as usize);
        Self {
            nodes: items
                .enumerate()
                .map(|(i, item)| Node {
                    parent: i as u32,
                    rank: 0,
                    item,
                })
                .collect(),
        }
    }

    /// The record of element `index`.
    #[inline]
    pub fn item(&self, index: usize) -> &T {
        &self.nodes[index].item
    }

    /// The record of element `index`, mutably.
    #[inline]
    pub fn item_mut(&mut self, index: usize) -> &mut T {
        &mut self.nodes[index].item
    }

    /// Every record in index order.
    pub fn items(&self) -> impl Iterator<Item = &T> {
        self.nodes.iter().map(|n| &n.item)
    }

    /// Bytes per element (link, rank and record).
    #[cfg(test)]
    pub fn node_size(&self) -> usize {
        std::mem::size_of::<Node<T>>()
    }

    /// The representative of `index`'s set.
    #[inline]
    pub fn find(&mut self, index: usize) -> usize {
        let mut i = index;
        loop {
            let p = self.nodes[i].parent as usize;
            if p == i {
                return i;
            }
            let grandparent = self.nodes[p].parent;
            self.nodes[i].parent = grandparent;
            i = grandparent as usize;
        }
    }

    /// Merges the sets of `a` and `b`; returns the new representative.
    pub fn union(&mut self, a: usize, b: usize) -> usize {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return ra;
        }
        let (rank_a, rank_b) = (self.nodes[ra].rank, self.nodes[rb].rank);
        let (child, root) = if rank_a < rank_b { (ra, rb) } else { (rb, ra) };
        self.nodes[child].parent = root as u32;
        if rank_a == rank_b {
            self.nodes[root].rank += 1;
        }
        root
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unions_are_transitive_and_disjoint_sets_stay_apart() {
        let mut sets = UnionFind::new(0..10);
        sets.union(0, 1);
        sets.union(2, 3);
        sets.union(1, 3);
        sets.union(7, 8);
        assert_eq!(sets.find(0), sets.find(2));
        assert_eq!(sets.find(7), sets.find(8));
        assert_ne!(sets.find(0), sets.find(7));
        assert_eq!(sets.find(5), 5);
        assert_eq!(*sets.item(5), 5);
        *sets.item_mut(5) = 50;
        assert_eq!(sets.items().copied().nth(5), Some(50));
    }

    #[test]
    fn a_long_chain_has_one_representative() {
        let n = 10_000;
        let mut sets = UnionFind::new(std::iter::repeat_n((), n));
        for i in 1..n {
            sets.union(i - 1, i);
        }
        let root = sets.find(0);
        assert!((0..n).all(|i| sets.find(i) == root));
    }
}

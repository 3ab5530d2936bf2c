//! Disjoint sets of voxels: the groups of processed voxels (dissertation ch.4.3, ch.4.5).

/// Union-find over voxel indices with path halving and union by rank, so that a sequence of
/// `m` operations on `n` voxels costs `O(m lg* n)` (ch.4.5, after Cormen, Leiserson and
/// Rivest).
#[derive(Debug, Clone)]
pub(crate) struct UnionFind {
    parent: Vec<u32>,
    rank: Vec<u8>,
}

impl UnionFind {
    /// `len` singleton sets, one per voxel index.
    pub fn new(len: usize) -> Self {
        debug_assert!(len <= u32::MAX as usize);
        Self {
            parent: (0..len as u32).collect(),
            rank: vec![0; len],
        }
    }

    /// The representative of `index`'s set.
    #[inline]
    pub fn find(&mut self, index: usize) -> usize {
        let mut i = index;
        loop {
            let p = self.parent[i] as usize;
            if p == i {
                return i;
            }
            let grandparent = self.parent[p];
            self.parent[i] = grandparent;
            i = grandparent as usize;
        }
    }

    /// Merges the sets of `a` and `b`; returns the new representative.
    pub fn union(&mut self, a: usize, b: usize) -> usize {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return ra;
        }
        let (child, root) = if self.rank[ra] < self.rank[rb] {
            (ra, rb)
        } else {
            (rb, ra)
        };
        self.parent[child] = root as u32;
        if self.rank[ra] == self.rank[rb] {
            self.rank[root] += 1;
        }
        root
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unions_are_transitive_and_disjoint_sets_stay_apart() {
        let mut sets = UnionFind::new(10);
        sets.union(0, 1);
        sets.union(2, 3);
        sets.union(1, 3);
        sets.union(7, 8);
        assert_eq!(sets.find(0), sets.find(2));
        assert_eq!(sets.find(7), sets.find(8));
        assert_ne!(sets.find(0), sets.find(7));
        assert_eq!(sets.find(5), 5);
    }

    #[test]
    fn a_long_chain_has_one_representative() {
        let n = 10_000;
        let mut sets = UnionFind::new(n);
        for i in 1..n {
            sets.union(i - 1, i);
        }
        let root = sets.find(0);
        assert!((0..n).all(|i| sets.find(i) == root));
    }
}

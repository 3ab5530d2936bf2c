//! Contour lists and contour arrays: the processing order of the voxels (dissertation ch.4.3).

use super::neighbourhood::NEIGHBOUR_COUNT;

/// Interior voxel indices in processing order of contour lists: decreasing squared distance,
/// ties in increasing index order (our choice, for determinism). Consecutive runs of equal
/// squared distance are the contour lists of ch.4.3.
///
/// A counting sort over the distance values gives the linear-time bound of ch.4.5; when the
/// values are too sparse for that (a hand-made map with huge values) a comparison sort is
/// used instead.
pub(crate) fn contour_order(squared: &[u32], interior: usize) -> Vec<u32> {
    let largest = squared.iter().copied().max().unwrap_or(0) as usize;
    if largest > 8 * interior + 4096 {
        let mut order: Vec<u32> = (0..squared.len() as u32)
            .filter(|&i| squared[i as usize] != 0)
            .collect();
        order.sort_by_key(|&i| (std::cmp::Reverse(squared[i as usize]), i));
        return order;
    }
    // start[v]: first position of value v, values laid out from the largest down.
    let mut start = vec![0u32; largest + 2];
    for &s in squared {
        if s != 0 {
            start[s as usize] += 1;
        }
    }
    let mut position = 0u32;
    for v in (1..=largest).rev() {
        let count = start[v];
        start[v] = position;
        position += count;
    }
    let mut order = vec![0u32; interior];
    for (index, &s) in squared.iter().enumerate() {
        if s != 0 {
            let slot = &mut start[s as usize];
            order[*slot as usize] = index as u32;
            *slot += 1;
        }
    }
    order
}

/// The contour arrays of one contour list: its unprocessed voxels partitioned by their number
/// of processed 26-neighbours (ch.4.3), so that the voxel with the most processed neighbours
/// is processed next and a voxel moves up one array in constant time when a neighbour of the
/// same contour is processed.
///
/// Within an array the most recently added voxel is taken first (our choice; ch.4.3 only says
/// the arrays are stepped through).
#[derive(Debug, Clone)]
pub(crate) struct ContourArrays {
    /// `arrays[c]`: voxels of the current contour with `c` processed neighbours.
    arrays: Vec<Vec<u32>>,
    /// Position of each queued voxel inside its array (grid-sized; the "contour array
    /// sub-index" of ch.4.3).
    slot: Vec<u32>,
    /// No array above this one is non-empty.
    level: usize,
}

impl ContourArrays {
    /// Empty arrays for a grid of `len` voxels.
    pub fn new(len: usize) -> Self {
        Self {
            arrays: vec![Vec::new(); NEIGHBOUR_COUNT + 1],
            slot: vec![0; len],
            level: 0,
        }
    }

    /// Queues the voxels of one contour list; `processed(i)` is voxel `i`'s number of
    /// processed neighbours.
    pub fn fill(&mut self, contour: &[u32], processed: impl Fn(usize) -> u8) {
        debug_assert!(self.arrays.iter().all(Vec::is_empty));
        self.level = 0;
        for &voxel in contour {
            let c = processed(voxel as usize) as usize;
            self.slot[voxel as usize] = self.arrays[c].len() as u32;
            self.arrays[c].push(voxel);
            self.level = self.level.max(c);
        }
    }

    /// Takes the next voxel to process: one with the most processed neighbours.
    pub fn pop(&mut self) -> Option<u32> {
        loop {
            if let Some(voxel) = self.arrays[self.level].pop() {
                return Some(voxel);
            }
            if self.level == 0 {
                return None;
            }
            self.level -= 1;
        }
    }

    /// Moves the queued `voxel` from array `from` to array `from + 1` (one more processed
    /// neighbour).
    pub fn promote(&mut self, voxel: u32, from: u8) {
        let from = from as usize;
        let at = self.slot[voxel as usize] as usize;
        let array = &mut self.arrays[from];
        debug_assert_eq!(array[at], voxel);
        array.swap_remove(at);
        if let Some(&moved) = array.get(at) {
            self.slot[moved as usize] = at as u32;
        }
        let to = from + 1;
        self.slot[voxel as usize] = self.arrays[to].len() as u32;
        self.arrays[to].push(voxel);
        self.level = self.level.max(to);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contour_order_is_decreasing_with_ascending_ties() {
        let squared = [0, 4, 1, 4, 0, 9, 1, 2];
        let order = contour_order(&squared, 6);
        assert_eq!(order, vec![5, 1, 3, 7, 2, 6]);
    }

    #[test]
    fn sparse_values_fall_back_to_a_comparison_sort() {
        let squared = [0, 4, u32::MAX, 4, 1];
        assert_eq!(contour_order(&squared, 4), vec![2, 1, 3, 4]);
    }

    #[test]
    fn arrays_give_most_processed_first_and_promote() {
        let mut arrays = ContourArrays::new(8);
        let processed = [0, 2, 0, 1, 0, 0, 0, 0];
        arrays.fill(&[0, 1, 2, 3], |i| processed[i]);
        assert_eq!(arrays.pop(), Some(1));
        arrays.promote(0, 0);
        arrays.promote(0, 1);
        arrays.promote(2, 0);
        assert_eq!(arrays.pop(), Some(0));
        // 3 and 2 both have one processed neighbour now; the last added goes first.
        assert_eq!(arrays.pop(), Some(2));
        assert_eq!(arrays.pop(), Some(3));
        assert_eq!(arrays.pop(), None);
    }
}

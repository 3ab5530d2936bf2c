//! Distance levels, contour lists and contour arrays: the processing order of the voxels
//! (dissertation ch.4.3).

use super::neighbourhood::NEIGHBOUR_COUNT;
use super::record::LEVEL_BITS;
use super::union_find::UnionFind;
use super::MedialError;

/// The distinct squared distances of a map, numbered: level 0 is the exterior (value 0),
/// levels `1..` the distinct positive values ascending. The extraction stores levels instead
/// of values so that a voxel's record fits in 8 bytes; comparisons of levels are comparisons
/// of values, and the values and their square roots are looked up exactly.
#[derive(Debug, Clone)]
pub(crate) struct Levels {
    /// Squared distance of each level, ascending, `values[0] == 0`.
    pub values: Vec<u32>,
    /// `sqrt(values[l])`, for the slopes of ch.4.3.
    pub roots: Vec<f64>,
    /// Voxels at each level (`counts[0]`: exterior voxels).
    counts: Vec<u32>,
    /// Level of each squared distance `0..=largest`, when the values are dense enough for a
    /// table (always for exact distance maps); otherwise levels are found in `values`.
    table: Option<Vec<u32>>,
}

impl Levels {
    /// The levels of `squared`, which has `interior` positive values.
    ///
    /// # Errors
    /// [`MedialError::TooManyDistances`] with `2^25` or more distinct values (impossible for an
    /// exact distance map of a grid with 32-bit indices: its values are below `2^20`).
    pub fn new(squared: &[u32], interior: usize) -> Result<Self, MedialError> {
        let largest = squared.iter().copied().max().unwrap_or(0) as usize;
        let (values, counts, table) = if largest <= 8 * interior + 4096 {
            let mut histogram = vec![0u32; largest + 1];
            for &s in squared {
                histogram[s as usize] += 1;
            }
            let mut table = vec![0u32; largest + 1];
            let (mut values, mut counts) = (vec![0], vec![histogram[0]]);
            for (value, &count) in histogram.iter().enumerate().skip(1) {
                if count > 0 {
                    table[value] = values.len() as u32;
                    values.push(value as u32);
                    counts.push(count);
                }
            }
            (values, counts, Some(table))
        } else {
            // A hand-made map with huge, sparse values: no table.
            let mut values: Vec<u32> = squared.to_vec();
            values.push(0);
            values.sort_unstable();
            values.dedup();
            let mut counts = vec![0u32; values.len()];
            for &s in squared {
                counts[values.binary_search(&s).expect("a value of the map")] += 1;
            }
            (values, counts, None)
        };
        if values.len() > 1 << LEVEL_BITS {
            return Err(MedialError::TooManyDistances {
                distinct: values.len() - 1,
                max: (1 << LEVEL_BITS) - 1,
            });
        }
        let roots = values.iter().map(|&v| (v as f64).sqrt()).collect();
        Ok(Self {
            values,
            roots,
            counts,
            table,
        })
    }

    /// The level of squared distance `squared` (a value of the map).
    #[inline]
    pub fn level(&self, squared: u32) -> u32 {
        match &self.table {
            Some(table) => table[squared as usize],
            None => self
                .values
                .binary_search(&squared)
                .expect("a value of the map") as u32,
        }
    }

    /// Interior voxel indices in processing order of contour lists: decreasing squared
    /// distance, ties in increasing index order (our choice, for determinism). Consecutive
    /// runs of equal squared distance are the contour lists of ch.4.3. A counting sort over
    /// the levels gives the linear-time bound of ch.4.5.
    pub fn contour_order(&self, squared: &[u32]) -> Vec<u32> {
        let mut start = vec![0u32; self.values.len()];
        let mut position = 0u32;
        for level in (1..self.values.len()).rev() {
            start[level] = position;
            position += self.counts[level];
        }
        let mut order = vec![0u32; position as usize];
        for (index, &s) in squared.iter().enumerate() {
            if s != 0 {
                let slot = &mut start[self.level(s) as usize];
                order[*slot as usize] = index as u32;
                *slot += 1;
            }
        }
        order
    }
}

/// The contour arrays of one contour list: its unprocessed voxels partitioned by their number
/// of processed 26-neighbours (ch.4.3), so that the voxel with the most processed neighbours
/// is processed next and a voxel moves up one array in constant time when a neighbour of the
/// same contour is processed.
///
/// Within an array the most recently added voxel is taken first (our choice; ch.4.3 only says
/// the arrays are stepped through). The position of each queued voxel inside its array (the
/// "contour array sub-index" of ch.4.3) is kept in its record's `link`.
#[derive(Debug, Clone)]
pub(crate) struct ContourArrays {
    /// `arrays[c]`: voxels of the current contour with `c` processed neighbours.
    arrays: Vec<Vec<u32>>,
    /// No array above this one is non-empty.
    top: usize,
}

impl ContourArrays {
    /// Empty arrays.
    pub fn new() -> Self {
        Self {
            arrays: vec![Vec::new(); NEIGHBOUR_COUNT + 1],
            top: 0,
        }
    }

    /// Queues the voxels of one contour list by their records' processed counts.
    pub fn fill(&mut self, contour: &[u32], records: &mut UnionFind) {
        debug_assert!(self.arrays.iter().all(Vec::is_empty));
        self.top = 0;
        for &voxel in contour {
            let record = records.item_mut(voxel as usize);
            let c = record.processed() as usize;
            record.link = self.arrays[c].len() as u32;
            self.arrays[c].push(voxel);
            self.top = self.top.max(c);
        }
    }

    /// Takes the next voxel to process: one with the most processed neighbours.
    pub fn pop(&mut self) -> Option<u32> {
        loop {
            if let Some(voxel) = self.arrays[self.top].pop() {
                return Some(voxel);
            }
            if self.top == 0 {
                return None;
            }
            self.top -= 1;
        }
    }

    /// Moves the queued `voxel` from array `from` to array `from + 1` (one more processed
    /// neighbour).
    pub fn promote(&mut self, voxel: u32, from: u8, records: &mut UnionFind) {
        let from = from as usize;
        let at = records.item(voxel as usize).link as usize;
        let array = &mut self.arrays[from];
        debug_assert_eq!(array[at], voxel);
        array.swap_remove(at);
        if let Some(&moved) = array.get(at) {
            records.item_mut(moved as usize).link = at as u32;
        }
        let to = from + 1;
        records.item_mut(voxel as usize).link = self.arrays[to].len() as u32;
        self.arrays[to].push(voxel);
        self.top = self.top.max(to);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayon::prelude::*;

    fn order(squared: &[u32]) -> Vec<u32> {
        let interior = squared.iter().filter(|&&s| s != 0).count();
        Levels::new(squared, interior)
            .unwrap()
            .contour_order(squared)
    }

    #[test]
    fn contour_order_is_decreasing_with_ascending_ties() {
        assert_eq!(order(&[0, 4, 1, 4, 0, 9, 1, 2]), vec![5, 1, 3, 7, 2, 6]);
    }

    #[test]
    fn sparse_values_are_found_without_a_table() {
        let squared = [0, 4, u32::MAX, 4, 1];
        let levels = Levels::new(&squared, 4).unwrap();
        assert!(levels.table.is_none());
        assert_eq!(levels.values, vec![0, 1, 4, u32::MAX]);
        assert_eq!(levels.level(u32::MAX), 3);
        assert_eq!(order(&squared), vec![2, 1, 3, 4]);
    }

    #[test]
    fn levels_number_the_distinct_values() {
        let squared = [0, 9, 2, 9, 0, 5];
        let levels = Levels::new(&squared, 4).unwrap();
        assert_eq!(levels.values, vec![0, 2, 5, 9]);
        assert_eq!(levels.counts, vec![2, 1, 1, 2]);
        assert_eq!(levels.roots[3], 3.0);
        assert_eq!(squared.map(|s| levels.level(s)), [0, 3, 1, 3, 0, 2]);
    }

    #[test]
    fn arrays_give_most_processed_first_and_promote() {
        let mut records = UnionFind::new(vec![1u32; 8].into_par_iter());
        for (voxel, processed) in [(1, 2), (3, 1)] {
            for _ in 0..processed {
                records.item_mut(voxel).count_processed();
            }
        }
        let mut arrays = ContourArrays::new();
        arrays.fill(&[0, 1, 2, 3], &mut records);
        assert_eq!(arrays.pop(), Some(1));
        // 0 gains two processed neighbours, 2 one.
        arrays.promote(0, 0, &mut records);
        arrays.promote(0, 1, &mut records);
        arrays.promote(2, 0, &mut records);
        assert_eq!(arrays.pop(), Some(0));
        // 3 and 2 both have one processed neighbour now; the last added goes first.
        assert_eq!(arrays.pop(), Some(2));
        assert_eq!(arrays.pop(), Some(3));
        assert_eq!(arrays.pop(), None);
    }
}

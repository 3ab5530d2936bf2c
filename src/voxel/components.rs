//! 26-connected components of the interior.

use super::{Connectivity, Grid};

/// Keeps only the largest 26-connected component of `inside` (ties: the one containing the
/// lowest voxel index, so the result is deterministic). Returns the number of components found
/// and the number of voxels dropped.
///
/// The outermost layer of the grid must be outside (as `voxelize` guarantees), so that every
/// neighbour of an inside voxel is in the grid and linear offsets can be used.
pub(crate) fn keep_largest_component(grid: &Grid, inside: &mut [bool]) -> (usize, usize) {
    const UNSEEN: u32 = u32::MAX;
    let mut label = vec![UNSEEN; inside.len()];
    let mut sizes: Vec<usize> = Vec::new();
    let mut stack = Vec::new();
    let [nx, ny, _] = grid.dims;
    let offsets: Vec<isize> = Connectivity::TwentySix
        .neighbours()
        .iter()
        .map(|n| {
            n.offset[0] as isize
                + nx as isize * (n.offset[1] as isize + ny as isize * n.offset[2] as isize)
        })
        .collect();
    for start in 0..inside.len() {
        if !inside[start] || label[start] != UNSEEN {
            continue;
        }
        let id = sizes.len() as u32;
        let mut size = 0;
        label[start] = id;
        stack.push(start);
        while let Some(i) = stack.pop() {
            size += 1;
            debug_assert!(on_interior(grid, i), "inside voxel on the grid border");
            for &o in &offsets {
                let j = (i as isize + o) as usize;
                if inside[j] && label[j] == UNSEEN {
                    label[j] = id;
                    stack.push(j);
                }
            }
        }
        sizes.push(size);
    }
    let Some((best, _)) = sizes
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(&a.0)))
    else {
        return (0, 0);
    };
    let mut dropped = 0;
    for (i, flag) in inside.iter_mut().enumerate() {
        if *flag && label[i] != best as u32 {
            *flag = false;
            dropped += 1;
        }
    }
    (sizes.len(), dropped)
}

/// True when voxel `i` is not on the outermost layer of the grid.
fn on_interior(grid: &Grid, i: usize) -> bool {
    let c = grid.coords(i);
    (0..3).all(|k| c[k] > 0 && c[k] + 1 < grid.dims[k])
}

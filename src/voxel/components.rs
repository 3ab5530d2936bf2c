//! 26-connected components of the interior, by union-find over row runs.
//!
//! Each row (fixed y and z) of inside voxels splits into runs. Two runs are 26-connected when
//! their rows are neighbours (|dy| <= 1, |dz| <= 1) and their x-ranges overlap after widening one
//! of them by a voxel on each side. Scanning rows in order and joining each run with the runs of
//! the four already-scanned neighbour rows ((y-1, z), (y-1, z-1), (y, z-1), (y+1, z-1)) finds
//! every connection; the work is linear in the number of runs rather than of voxels.

use super::Grid;

/// A maximal run `[start, end)` of inside voxels along x in row `row = y + ny * z`.
#[derive(Debug, Clone, Copy)]
struct Run {
    row: usize,
    start: usize,
    end: usize,
}

fn find(parent: &mut [u32], mut a: u32) -> u32 {
    while parent[a as usize] != a {
        let up = parent[parent[a as usize] as usize];
        parent[a as usize] = up;
        a = up;
    }
    a
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    // Deterministic: the smaller run index becomes the representative.
    if ra < rb {
        parent[rb as usize] = ra;
    } else if rb < ra {
        parent[ra as usize] = rb;
    }
}

/// The 26-connected components of `inside`: a component index per voxel (`u32::MAX` outside)
/// and each component's voxel count. Components are numbered in the order of their lowest
/// voxel index, so the result is deterministic.
pub(crate) fn label_components(grid: &Grid, inside: &[bool]) -> (Vec<u32>, Vec<usize>) {
    let [nx, ny, nz] = grid.dims;
    let rows = ny * nz;
    let mut runs: Vec<Run> = Vec::new();
    let mut row_start = vec![0u32; rows + 1];
    for row in 0..rows {
        let line = &inside[row * nx..(row + 1) * nx];
        let mut x = 0;
        while x < nx {
            if line[x] {
                let start = x;
                while x < nx && line[x] {
                    x += 1;
                }
                runs.push(Run { row, start, end: x });
            } else {
                x += 1;
            }
        }
        row_start[row + 1] = runs.len() as u32;
    }
    let mut label = vec![u32::MAX; inside.len()];
    if runs.is_empty() {
        return (label, Vec::new());
    }
    let mut parent: Vec<u32> = (0..runs.len() as u32).collect();
    for (k, run) in runs.iter().enumerate() {
        let (y, z) = (run.row % ny, run.row / ny);
        let neighbours = [
            (y.checked_sub(1), Some(z)),
            (y.checked_sub(1), z.checked_sub(1)),
            (Some(y), z.checked_sub(1)),
            ((y + 1 < ny).then_some(y + 1), z.checked_sub(1)),
        ];
        for (ny_, nz_) in neighbours {
            let (Some(oy), Some(oz)) = (ny_, nz_) else {
                continue;
            };
            let other = oy + ny * oz;
            for j in row_start[other]..row_start[other + 1] {
                let r = runs[j as usize];
                // Overlap of [start-1, end+1) with [r.start, r.end).
                if r.start <= run.end && run.start <= r.end {
                    union(&mut parent, k as u32, j);
                }
            }
        }
    }
    // Roots are the smallest run index of their component (see `union`), and runs are in voxel
    // order: numbering roots in run order numbers components by their lowest voxel.
    let mut number = vec![u32::MAX; runs.len()];
    let mut sizes = Vec::new();
    for (k, run) in runs.iter().enumerate() {
        let root = find(&mut parent, k as u32) as usize;
        if number[root] == u32::MAX {
            number[root] = sizes.len() as u32;
            sizes.push(0);
        }
        let c = number[root];
        sizes[c as usize] += run.end - run.start;
        label[run.row * nx + run.start..run.row * nx + run.end].fill(c);
    }
    (label, sizes)
}

/// Keeps only the largest 26-connected component of `inside` (ties: the one containing the
/// lowest voxel index, so the result is deterministic). Returns the number of components found
/// and the number of voxels dropped.
#[cfg(test)]
pub(crate) fn keep_largest_component(grid: &Grid, inside: &mut [bool]) -> (usize, usize) {
    let (label, sizes) = label_components(grid, inside);
    let Some(best) = (0..sizes.len()).max_by(|&a, &b| sizes[a].cmp(&sizes[b]).then(b.cmp(&a)))
    else {
        return (0, 0);
    };
    let mut dropped = 0;
    for (i, v) in inside.iter_mut().enumerate() {
        if *v && label[i] != best as u32 {
            *v = false;
            dropped += 1;
        }
    }
    (sizes.len(), dropped)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn grid(dims: [usize; 3]) -> Grid {
        Grid {
            dims,
            origin: DVec3::ZERO,
            voxel_size: 1.0,
        }
    }

    #[test]
    fn diagonal_corner_contact_connects_and_gaps_separate() {
        let g = grid([6, 6, 6]);
        let mut inside = vec![false; g.len()];
        // Two voxels touching only at a corner: one component.
        inside[g.index([1, 1, 1])] = true;
        inside[g.index([2, 2, 2])] = true;
        // A separate pair, two voxels away.
        inside[g.index([4, 4, 4])] = true;
        inside[g.index([4, 4, 3])] = true;
        inside[g.index([4, 3, 4])] = true;
        let mut a = inside.clone();
        assert_eq!(keep_largest_component(&g, &mut a), (2, 2));
        assert!(a[g.index([4, 4, 4])] && !a[g.index([1, 1, 1])]);
        // Corner contact across (y+1, z-1).
        let mut b = vec![false; g.len()];
        b[g.index([1, 1, 2])] = true;
        b[g.index([2, 2, 1])] = true;
        assert_eq!(keep_largest_component(&g, &mut b), (1, 0));
    }
}

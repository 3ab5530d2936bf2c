//! Air the figure encloses: outside voxels walled in by the figure along the axes, such as the
//! hollow inside of a jacket modelled as a thin shell over a skinny torso. The geodesic
//! weights may cross it, so that a garment follows the body under it rather than the bones it
//! touches at its seams.

use crate::voxel::Solid;
use rayon::prelude::*;

/// `solid` with its enclosed air made inside: every outside voxel that meets the figure in all
/// six axis directions within `reach` times the grid's longest side. `None` when there is
/// none or `reach` is 0.
pub(crate) fn with_enclosed_air(solid: &Solid, reach: f64) -> Option<Solid> {
    let longest = solid.grid.dims.iter().copied().max().unwrap_or(0) as f64;
    let steps = (reach * longest).round();
    if steps.is_nan() || steps < 1.0 {
        return None;
    }
    let counts = walls(solid, steps as usize);
    let air: Vec<usize> = (0..solid.grid.len())
        .filter(|&i| !solid.inside[i] && counts[i] == 6)
        .collect();
    if air.is_empty() {
        return None;
    }
    let mut out = solid.clone();
    for i in air {
        out.inside[i] = true;
    }
    Some(out)
}

/// Per voxel, in how many of the six axis directions an interior voxel lies within `reach`.
fn walls(solid: &Solid, reach: usize) -> Vec<u8> {
    let [nx, ny, nz] = solid.grid.dims;
    let inside = &solid.inside;
    let mut counts = vec![0u8; solid.grid.len()];
    let reach = reach as u32;
    // x and y: within each z slice.
    counts
        .par_chunks_mut(nx * ny)
        .enumerate()
        .for_each(|(z, slice)| {
            let base = z * nx * ny;
            // Rows along x (stride 1, one per y), then along y (stride nx, one per x).
            for (len, lines, along, across) in [(nx, ny, 1, nx), (ny, nx, nx, 1)] {
                for line in 0..lines {
                    let at = |k: usize| line * across + k * along;
                    scan(
                        len,
                        |k| base + at(k),
                        inside,
                        reach,
                        |k, c| slice[at(k)] += c,
                    );
                }
            }
        });
    // z: along columns.
    let columns: Vec<(usize, u8)> = (0..nx * ny)
        .into_par_iter()
        .flat_map_iter(|xy| {
            let mut hits = Vec::new();
            scan(
                nz,
                |z| z * nx * ny + xy,
                inside,
                reach,
                |z, c| hits.push((z * nx * ny + xy, c)),
            );
            hits
        })
        .collect();
    for (i, c) in columns {
        counts[i] += c;
    }
    counts
}

/// Along one line of `n` voxels (`index(k)`: the grid index of its k-th voxel): for every
/// outside voxel, how many of its two directions along the line meet an interior voxel within
/// `reach` steps, reported as `add(k, count)` where the count is positive.
fn scan(
    n: usize,
    index: impl Fn(usize) -> usize,
    inside: &[bool],
    reach: u32,
    mut add: impl FnMut(usize, u8),
) {
    let mut ahead = vec![false; n];
    let mut since = u32::MAX;
    for k in (0..n).rev() {
        if inside[index(k)] {
            since = 0;
        } else {
            since = since.saturating_add(1);
            ahead[k] = since <= reach;
        }
    }
    since = u32::MAX;
    for k in 0..n {
        if inside[index(k)] {
            since = 0;
            continue;
        }
        since = since.saturating_add(1);
        let count = u8::from(ahead[k]) + u8::from(since <= reach);
        if count > 0 {
            add(k, count);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voxel::{Grid, VoxelReport};
    use glam::DVec3;

    /// A 20³ grid of unit voxels, inside where `inside(x, y, z)`.
    fn solid(inside: impl Fn(usize, usize, usize) -> bool) -> Solid {
        let grid = Grid {
            dims: [20; 3],
            origin: DVec3::ZERO,
            voxel_size: 1.0,
        };
        let mask = (0..grid.len())
            .map(|i| {
                let [x, y, z] = grid.coords(i);
                inside(x, y, z)
            })
            .collect();
        Solid {
            grid,
            inside: mask,
            surface: vec![false; grid.len()],
            report: VoxelReport::default(),
        }
    }

    #[test]
    fn a_hollow_shell_encloses_its_inside_but_not_a_gap_between_two_walls() {
        // A box shell one voxel thick around 4..=15 on every axis, open at the bottom in the
        // middle (a hem).
        let shell = solid(|x, y, z| {
            let on = |c: usize| c == 4 || c == 15;
            let within = |c: usize| (4..=15).contains(&c);
            let hem = y == 4 && (8..=11).contains(&x) && (8..=11).contains(&z);
            within(x) && within(y) && within(z) && (on(x) || on(y) || on(z)) && !hem
        });
        let grid = shell.grid;
        let with_air = with_enclosed_air(&shell, 0.5).unwrap();
        // Inside the shell, away from the hem's column: enclosed.
        assert!(with_air.inside[grid.index([6, 10, 6])]);
        assert!(with_air.inside[grid.index([12, 6, 13])]);
        // Above the hem: open downwards.
        assert!(!with_air.inside[grid.index([9, 10, 9])]);
        // Outside the shell: not enclosed.
        assert!(!with_air.inside[grid.index([2, 10, 10])]);
        assert!(!with_air.inside[grid.index([10, 17, 10])]);
        // Beyond the reach, nothing is.
        assert!(with_enclosed_air(&shell, 0.05).is_none());
        assert!(with_enclosed_air(&shell, 0.0).is_none());
        // Two parallel walls (an arm beside the torso): the gap is open in four directions.
        let walls = solid(|x, _, _| x == 5 || x == 10);
        assert!(with_enclosed_air(&walls, 0.5).is_none());
    }
}

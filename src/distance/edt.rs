//! Separable exact squared Euclidean distance transform (Meijster et al. 2000).

use super::DistanceMap;
use crate::voxel::Solid;
use rayon::prelude::*;

/// "No exterior voxel on this line".
const INFINITE: u32 = u32::MAX;

/// Computes the exact squared Euclidean distance transform of `solid`.
///
/// Exterior voxels (`!solid.inside[i]`) get 0; interior voxels get the squared distance, in
/// voxel units, from their centre to the nearest exterior voxel centre. Phases: 1-D distances
/// along x by two scans, then the lower envelope of parabolas along y and along z.
///
/// Runs in O(voxels) time and one extra copy of the map; parallel over lines, deterministic.
pub fn edt(solid: &Solid) -> DistanceMap {
    let grid = solid.grid;
    let [nx, ny, nz] = grid.dims;
    let mut squared = vec![0u32; grid.len()];
    if grid.is_empty() {
        return DistanceMap { grid, squared };
    }
    // Phases 1 and 2 work inside one z-slice.
    squared
        .par_chunks_mut(nx * ny)
        .zip(solid.inside.par_chunks(nx * ny))
        .for_each_init(
            || Scratch::new(ny),
            |scratch, (slice, inside)| {
                for (row, inside_row) in slice.chunks_mut(nx).zip(inside.chunks(nx)) {
                    row_distances(inside_row, row);
                }
                for x in 0..nx {
                    scratch.line.clear();
                    scratch.line.extend((0..ny).map(|y| slice[x + nx * y]));
                    envelope(
                        &scratch.line,
                        &mut scratch.out,
                        &mut scratch.sites,
                        &mut scratch.starts,
                    );
                    for y in 0..ny {
                        slice[x + nx * y] = scratch.out[y];
                    }
                }
            },
        );
    // Phase 3 along z: one xz-plane per y, gathered, transformed, then scattered back.
    if nz > 1 {
        let planes: Vec<Vec<u32>> = (0..ny)
            .into_par_iter()
            .map_init(
                || Scratch::new(nz),
                |scratch, y| {
                    let mut plane = vec![0u32; nx * nz];
                    for x in 0..nx {
                        scratch.line.clear();
                        scratch
                            .line
                            .extend((0..nz).map(|z| squared[x + nx * (y + ny * z)]));
                        envelope(
                            &scratch.line,
                            &mut scratch.out,
                            &mut scratch.sites,
                            &mut scratch.starts,
                        );
                        for z in 0..nz {
                            plane[x + nx * z] = scratch.out[z];
                        }
                    }
                    plane
                },
            )
            .collect();
        squared
            .par_chunks_mut(nx * ny)
            .enumerate()
            .for_each(|(z, slice)| {
                for (y, row) in slice.chunks_mut(nx).enumerate() {
                    row.copy_from_slice(&planes[y][nx * z..nx * (z + 1)]);
                }
            });
    }
    DistanceMap { grid, squared }
}

struct Scratch {
    line: Vec<u32>,
    out: Vec<u32>,
    sites: Vec<usize>,
    starts: Vec<i64>,
}

impl Scratch {
    fn new(n: usize) -> Self {
        Self {
            line: Vec::with_capacity(n),
            out: vec![0; n],
            sites: Vec::with_capacity(n),
            starts: Vec::with_capacity(n),
        }
    }
}

/// Squared 1-D distance along a row to the nearest exterior voxel (or [`INFINITE`]).
fn row_distances(inside: &[bool], out: &mut [u32]) {
    let n = inside.len();
    let mut last: Option<usize> = None;
    for x in 0..n {
        if !inside[x] {
            last = Some(x);
        }
        out[x] = last.map_or(INFINITE, |l| (x - l) as u32);
    }
    let mut next: Option<usize> = None;
    for x in (0..n).rev() {
        if !inside[x] {
            next = Some(x);
        }
        let d = next.map_or(INFINITE, |r| (r - x) as u32).min(out[x]);
        out[x] = if d == INFINITE { INFINITE } else { d * d };
    }
}

/// Lower envelope of the parabolas `(i - j)^2 + f[j]`: `out[i] = min_j (i - j)^2 + f[j]`, with
/// sites `f[j] == INFINITE` ignored. Exact integer arithmetic (Meijster's `Sep`).
fn envelope(f: &[u32], out: &mut [u32], sites: &mut Vec<usize>, starts: &mut Vec<i64>) {
    let n = f.len();
    sites.clear();
    starts.clear();
    let value = |x: i64, j: usize| (x - j as i64).pow(2) + f[j] as i64;
    for u in 0..n {
        if f[u] == INFINITE {
            continue;
        }
        while let (Some(&s), Some(&t)) = (sites.last(), starts.last()) {
            if value(t, s) > value(t, u) {
                sites.pop();
                starts.pop();
            } else {
                break;
            }
        }
        match sites.last() {
            None => {
                sites.push(u);
                starts.push(0);
            }
            Some(&s) => {
                // First position where u is strictly better than s.
                let (i, uu) = (s as i64, u as i64);
                let sep = (uu * uu - i * i + f[u] as i64 - f[s] as i64).div_euclid(2 * (uu - i));
                let w = 1 + sep;
                if w < n as i64 {
                    sites.push(u);
                    starts.push(w);
                }
            }
        }
    }
    if sites.is_empty() {
        out[..n].fill(INFINITE);
        return;
    }
    let mut q = sites.len() - 1;
    for x in (0..n).rev() {
        let v = value(x as i64, sites[q]);
        out[x] = v.min(INFINITE as i64 - 1) as u32;
        if x as i64 == starts[q] && q > 0 {
            q -= 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brute(f: &[u32]) -> Vec<u32> {
        (0..f.len())
            .map(|i| {
                f.iter()
                    .enumerate()
                    .filter(|(_, &v)| v != INFINITE)
                    .map(|(j, &v)| (i as i64 - j as i64).pow(2) as u32 + v)
                    .min()
                    .unwrap_or(INFINITE)
            })
            .collect()
    }

    #[test]
    fn envelope_matches_brute_force_on_small_lines() {
        let cases: Vec<Vec<u32>> = vec![
            vec![0, INFINITE, INFINITE, 0],
            vec![INFINITE, 4, 1, INFINITE, 9, 0],
            vec![INFINITE; 5],
            vec![7],
            vec![3, 3, 3, 3],
            vec![0, 25, 25, 25, 25, 0],
        ];
        for f in cases {
            let mut out = vec![0; f.len()];
            envelope(&f, &mut out, &mut Vec::new(), &mut Vec::new());
            assert_eq!(out, brute(&f), "input {f:?}");
        }
    }
}

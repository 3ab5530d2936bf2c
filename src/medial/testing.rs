//! Test helpers: hand-built figures and a brute-force exact distance transform.

use crate::distance::DistanceMap;
use crate::voxel::{Grid, NEIGHBOURS_26};
use glam::DVec3;

/// The exact squared distance map of the voxels of a `dims` grid whose centres (in voxel
/// coordinates, centres at `i + 0.5`) satisfy `inside`, with the outermost layer forced
/// outside. Separable brute force: per line, `g(i) = min_j f(j) + (i - j)^2`.
pub(crate) fn distance_map(dims: [usize; 3], inside: impl Fn(DVec3) -> bool) -> DistanceMap {
    let grid = Grid {
        dims,
        origin: DVec3::ZERO,
        voxel_size: 1.0,
    };
    const FAR: u64 = u64::MAX / 4;
    let mut f: Vec<u64> = (0..grid.len())
        .map(|i| {
            let c = grid.coords(i);
            let border = (0..3).any(|a| c[a] == 0 || c[a] + 1 == dims[a]);
            if !border && inside(grid.centre(c)) {
                FAR
            } else {
                0
            }
        })
        .collect();
    for axis in 0..3 {
        let mut line = vec![0u64; dims[axis]];
        for i in 0..grid.len() {
            let c = grid.coords(i);
            if c[axis] != 0 {
                continue;
            }
            let at = |k: usize| {
                let mut d = c;
                d[axis] = k;
                grid.index(d)
            };
            for (k, value) in line.iter_mut().enumerate() {
                *value = (0..dims[axis])
                    .map(|j| f[at(j)].saturating_add((k.abs_diff(j) as u64).pow(2)))
                    .min()
                    .unwrap_or(FAR);
            }
            for (k, &value) in line.iter().enumerate() {
                f[at(k)] = value;
            }
        }
    }
    let squared = f
        .into_iter()
        .map(|v| v.min(u32::MAX as u64) as u32)
        .collect();
    DistanceMap { grid, squared }
}

/// A solid box of `size` voxels (all interior) in a grid padded by one exterior layer.
pub(crate) fn box_map(size: [usize; 3]) -> DistanceMap {
    let dims = size.map(|s| s + 2);
    distance_map(dims, |p| {
        (0..3).all(|a| p[a] > 1.0 && p[a] < size[a] as f64 + 1.0)
    })
}

/// Number of 26-connected components of the interior voxels of `distance`.
pub(crate) fn interior_components(distance: &DistanceMap) -> usize {
    let grid = distance.grid;
    let mut seen = vec![false; grid.len()];
    let mut components = 0;
    for start in 0..grid.len() {
        if distance.squared[start] == 0 || seen[start] {
            continue;
        }
        components += 1;
        seen[start] = true;
        let mut stack = vec![start];
        while let Some(i) = stack.pop() {
            for n in NEIGHBOURS_26 {
                if let Some(j) = grid.offset(grid.coords(i), n.offset) {
                    if distance.squared[j] != 0 && !seen[j] {
                        seen[j] = true;
                        stack.push(j);
                    }
                }
            }
        }
    }
    components
}

#[test]
fn distance_map_matches_a_global_brute_force() {
    let map = distance_map([9, 8, 7], |p| {
        (p - DVec3::new(4.0, 4.0, 3.5)).length() < 3.2 || (p.x > 5.0 && p.y < 5.0)
    });
    let grid = map.grid;
    let outside: Vec<usize> = (0..grid.len()).filter(|&i| map.squared[i] == 0).collect();
    for i in 0..grid.len() {
        let c = grid.coords(i);
        let expected = outside
            .iter()
            .map(|&j| {
                let d = grid.coords(j);
                (0..3)
                    .map(|a| (c[a].abs_diff(d[a]) as u32).pow(2))
                    .sum::<u32>()
            })
            .min()
            .unwrap();
        assert_eq!(map.squared[i], expected, "voxel {c:?}");
    }
}

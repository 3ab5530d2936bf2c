//! Distance-map measurements in mesh units: local thickness along segments and whether bone
//! vertices lie inside the figure.

use crate::distance::DistanceMap;
use glam::DVec3;

/// Trilinear interpolation of the distance map (voxel units) at `p` between the eight nearest
/// voxel centres (0 outside the grid). The figure's surface lies near the 0.5 level, between
/// the last interior and the first exterior voxel centres.
pub(crate) fn depth(map: &DistanceMap, p: DVec3) -> f64 {
    let g = &map.grid;
    let v = g.to_voxel(p) - DVec3::splat(0.5);
    let base = v.floor();
    let f = v - base;
    let mut sum = 0.0;
    for corner in 0..8 {
        let o = [corner & 1, (corner >> 1) & 1, (corner >> 2) & 1];
        let mut c = [0usize; 3];
        let mut w = 1.0;
        let mut ok = true;
        for a in 0..3 {
            let i = base[a] + o[a] as f64;
            if !(i >= 0.0 && i < g.dims[a] as f64) {
                ok = false;
            }
            c[a] = i.max(0.0) as usize;
            w *= if o[a] == 1 { f[a] } else { 1.0 - f[a] };
        }
        if ok && w > 0.0 {
            sum += w * map.distance(g.index(c));
        }
    }
    sum
}

/// Whether `p` lies inside the figure at least as deep as `clearance` voxels by the
/// interpolated distance ([`depth`]).
pub(crate) fn inside(map: &DistanceMap, p: DVec3, clearance: f64) -> bool {
    depth(map, p) >= clearance
}

/// Fraction of `points` inside the figure with `clearance` (1 for no points).
pub(crate) fn inside_fraction(map: &DistanceMap, points: &[DVec3], clearance: f64) -> f64 {
    if points.is_empty() {
        return 1.0;
    }
    points
        .iter()
        .filter(|p| inside(map, **p, clearance))
        .count() as f64
        / points.len() as f64
}

/// Radii at `samples` points evenly spread over the middle of segment `a → b` (from 20 % to
/// 80 %), sorted.
fn radii(map: &DistanceMap, a: DVec3, b: DVec3, samples: usize) -> Vec<f64> {
    let n = samples.max(1);
    let mut r: Vec<f64> = (0..n)
        .map(|k| {
            let t = if n == 1 {
                0.5
            } else {
                0.2 + 0.6 * k as f64 / (n - 1) as f64
            };
            map.radius_at(a.lerp(b, t))
        })
        .collect();
    r.sort_by(f64::total_cmp);
    r
}

/// Median distance-map radius along the middle of segment `a → b` (9 samples).
pub(crate) fn median_radius(map: &DistanceMap, a: DVec3, b: DVec3) -> f64 {
    let r = radii(map, a, b, 9);
    r[r.len() / 2]
}

/// Largest distance-map radius along the whole segment `a → b` (`samples` points).
pub(crate) fn max_radius(map: &DistanceMap, a: DVec3, b: DVec3, samples: usize) -> f64 {
    let n = samples.max(2);
    (0..n)
        .map(|k| map.radius_at(a.lerp(b, k as f64 / (n - 1) as f64)))
        .fold(0.0, f64::max)
}

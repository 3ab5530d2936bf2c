//! Pectoral limb roots inside the trunk: the DMS voxels of an arm or a fore leg that lie within
//! the trunk's inscribed balls, given to the trunk for the per-voxel and per-vertex labels.
//!
//! A fore limb's section starts at the heart-value bin where its DMS piece separates from the
//! trunk's, which for a limb joining the underside or side of a wide trunk is well inside the
//! body: the limb's medial line runs up through the chest to meet the trunk's medial sheet, and
//! the chest's skin around it, nearest to that line, would be labelled limb. Anatomically the
//! pectoral limb begins where it leaves the body wall; the shoulder girdle (scapula, clavicle)
//! lies along the trunk (dissertation ch.6: the girdles belong to the trunk, ch.7.3.3: the
//! trunk pieces joining a limb pair are girdle pieces).

use super::{Label, LimbPair, Part};
use crate::medial::MedialSurface;
use std::collections::HashMap;

/// DMS positions of arms and fore legs whose centre lies strictly within `scale` times the
/// inscribed radius of some trunk DMS voxel (`region_parts[q] == 0`) from that voxel's centre,
/// ascending. `region_parts` is the part of every DMS position ([`super::NO_PART`] outside the
/// labelled component); `scale` in `[0, 1]`, 0 gives nothing.
///
/// Trunk voxels are bucketed on a grid of cells as wide as the largest scaled radius, so each
/// limb voxel is tested against the trunk balls of its 27 neighbouring cells only.
pub fn pectoral_roots_in_trunk(
    surface: &MedialSurface,
    parts: &[Part],
    region_parts: &[u32],
    scale: f64,
) -> Vec<usize> {
    let pectoral = |part: u32| {
        parts.get(part as usize).is_some_and(|p| match p.label {
            Label::Arm => true,
            Label::Leg => p.limb_pair == Some(LimbPair::Fore),
            _ => false,
        })
    };
    let coords = |p: usize| {
        let c = surface.grid.coords(surface.voxels[p]);
        [c[0] as i64, c[1] as i64, c[2] as i64]
    };
    // Trunk balls in voxel units: (centre, scaled radius).
    let balls: Vec<([i64; 3], f64)> = (0..surface.len())
        .filter(|&p| region_parts[p] == 0)
        .map(|p| (coords(p), scale * surface.distance(p)))
        .filter(|&(_, r)| r > 0.0)
        .collect();
    let Some(largest) = balls.iter().map(|b| b.1).reduce(f64::max) else {
        return Vec::new();
    };
    let cell = largest.ceil().max(1.0) as i64;
    let key = |c: [i64; 3]| {
        [
            c[0].div_euclid(cell),
            c[1].div_euclid(cell),
            c[2].div_euclid(cell),
        ]
    };
    let mut buckets: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, b) in balls.iter().enumerate() {
        buckets.entry(key(b.0)).or_default().push(i);
    }
    (0..surface.len())
        .filter(|&p| pectoral(region_parts[p]))
        .filter(|&p| {
            let a = coords(p);
            let k = key(a);
            (-1..=1).any(|dz| {
                (-1..=1).any(|dy| {
                    (-1..=1).any(|dx| {
                        buckets
                            .get(&[k[0] + dx, k[1] + dy, k[2] + dz])
                            .is_some_and(|list| {
                                list.iter().any(|&i| {
                                    let (b, r) = balls[i];
                                    let d2: i64 = (0..3).map(|j| (a[j] - b[j]).pow(2)).sum();
                                    (d2 as f64) < r * r
                                })
                            })
                    })
                })
            })
        })
        .collect()
}

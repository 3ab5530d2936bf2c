//! A rib cage (dissertation 9.1: one per group of overlapping pectoral girdle spheres).
//!
//! Local frame: origin at the cage's centre, +z cranial (along the spine towards the head), +y
//! dorsal, +x the figure's left. Ribs leave the spine beside the vertebrae (never through
//! them), curve round the sides and end beside a sternum on the ventral midline.

use super::primitive::{merge, tube};
use crate::mesh::Mesh;
use glam::DVec3;
use std::f64::consts::PI;

/// Size of a rib cage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RibCage {
    /// Lateral semi-axis of the largest rib, mesh units.
    pub half_width: f64,
    /// Dorsal height of the spine above the centre (y), mesh units.
    pub spine_y: f64,
    /// Ventral depth of the sternum below the centre (as a positive distance), mesh units.
    pub sternum_y: f64,
    /// Half the cage's extent along z, mesh units.
    pub half_height: f64,
    /// Half-width of the vertebrae: ribs start clear of it.
    pub vertebra_half_width: f64,
    /// Rib tube radius, mesh units.
    pub rib_radius: f64,
    /// Number of rib pairs.
    pub pairs: usize,
    /// Vertices per ring.
    pub segments: u32,
}

/// The ribs (one tube per rib and side) and the sternum.
pub fn rib_cage(c: &RibCage) -> Mesh {
    let mut parts = Vec::new();
    let rr = c.rib_radius;
    let segments = c.segments.min(10);
    let n = c.pairs.max(1);
    for i in 0..n {
        // t from +1 (cranial) to −1 (caudal); upper ribs are shorter, the cage is a barrel.
        let t = if n == 1 {
            0.0
        } else {
            1.0 - 2.0 * i as f64 / (n - 1) as f64
        };
        let scale = (1.0 - 0.55 * t * t).sqrt() * (1.0 - 0.15 * t);
        let z = 0.9 * t * c.half_height;
        let a = c.half_width * scale;
        let b = 0.5 * (c.spine_y + c.sternum_y) * scale;
        let yc = c.spine_y - b;
        // Start clear of the vertebra and of the neighbouring rib's cap.
        let clear = c.vertebra_half_width + 2.0 * rr;
        let theta0 = (clear / a).clamp(0.0, 0.9).asin().max(0.15);
        let sternum_half = 2.0 * rr;
        let end_clear = ((sternum_half + 1.5 * rr) / a.max(f64::EPSILON))
            .clamp(0.0, 0.9)
            .asin();
        let theta1 = (PI - end_clear.max(0.1)).max(theta0 + 0.1);
        for side in [1.0, -1.0] {
            let points: Vec<DVec3> = (0..=16)
                .map(|k| {
                    let th = theta0 + (theta1 - theta0) * k as f64 / 16.0;
                    // Ribs descend ventrally (caudal slope).
                    let drop = 0.35 * c.half_height / n as f64 * 2.0 * (th / PI);
                    DVec3::new(side * a * th.sin(), yc + b * th.cos(), z - drop)
                })
                .collect();
            parts.push(tube(&points, &[rr; 17], DVec3::Z, segments));
        }
    }
    // Sternum: a flat bar along the ventral midline.
    let bottom = -c.sternum_y * 0.95;
    let sternum: Vec<DVec3> = (0..=6)
        .map(|k| {
            let t = k as f64 / 6.0;
            DVec3::new(0.0, bottom, c.half_height * (0.8 - 1.4 * t))
        })
        .collect();
    parts.push(tube(&sternum, &[1.2 * rr; 7], DVec3::Y, segments));
    merge(parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cage() -> RibCage {
        RibCage {
            half_width: 0.12,
            spine_y: 0.08,
            sternum_y: 0.1,
            half_height: 0.12,
            vertebra_half_width: 0.012,
            rib_radius: 0.005,
            pairs: 10,
            segments: 8,
        }
    }

    #[test]
    fn rib_cage_is_closed_outward_and_clear_of_the_spine() {
        let c = cage();
        let m = rib_cage(&c);
        let s = m.stats();
        assert!(s.closed && s.signed_volume.unwrap() > 0.0, "{s:?}");
        assert_eq!(s.components, 2 * c.pairs + 1);
        // No rib vertex lies within the vertebra's half-width of the spine axis (x = 0, y =
        // spine_y).
        for p in &m.positions {
            let d = (p.x * p.x + (p.y - c.spine_y).powi(2)).sqrt();
            assert!(d > c.vertebra_half_width, "{p}");
        }
        let (lo, hi) = m.bounding_box().unwrap();
        assert!(
            hi.x <= 1.03 * c.half_width + 1.01 * c.rib_radius
                && lo.y >= -c.sternum_y - 2.0 * c.rib_radius,
            "{lo} {hi}"
        );
    }
}

//! A generic vertebra (dissertation 9.1: one instance per vertebral segment).
//!
//! Local frame: +z along the segment from z = 0 to `length` (away from the root), +y dorsal,
//! +x the figure's left. The body is centred on the segment; the arch, spinous and transverse
//! processes are sized by the width, so short tail vertebrae keep their processes (9.1.1).

use super::primitive::{merge, profile_z, tube};
use crate::mesh::Mesh;
use glam::DVec3;

/// Size of a vertebra.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vertebra {
    /// Segment length, mesh units.
    pub length: f64,
    /// Overall width across the transverse processes, mesh units.
    pub width: f64,
    /// Rings along the body.
    pub rings: u32,
    /// Vertices per ring.
    pub segments: u32,
}

/// Body, neural arch, spinous process and transverse processes; the body leaves a gap of 8 %
/// of the length at each end (the intervertebral discs), so neighbours do not touch.
pub fn vertebra(v: &Vertebra) -> Mesh {
    let (l, w) = (v.length, v.width);
    let n = v.rings.clamp(4, 12);
    let body_r = 0.22 * w;
    let profile: Vec<(f64, f64, f64, f64, f64)> = (0..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            // A waisted cylinder, rounded at the end plates.
            let waist = 1.0 - 0.12 * (std::f64::consts::PI * t).sin();
            let edge = (1.0 - (2.0 * t - 1.0).powi(8)).sqrt().max(0.4);
            let r = body_r * waist * edge;
            (l * (0.08 + 0.84 * t), 0.0, -0.05 * w, r, 0.9 * r)
        })
        .collect();
    let body = profile_z(&profile, (0.02 * l, 0.02 * l), v.segments);
    let thick = (0.055 * w).min(0.18 * l).max(f64::EPSILON);
    let mid = 0.5 * l;
    let segments = v.segments.min(10);
    let arch: Vec<DVec3> = (0..=6)
        .map(|k| {
            let a = std::f64::consts::PI * k as f64 / 6.0;
            DVec3::new(0.2 * w * a.cos(), 0.1 * w + 0.14 * w * a.sin(), mid)
        })
        .collect();
    let spinous = tube(
        &[
            DVec3::new(0.0, 0.22 * w, mid),
            DVec3::new(0.0, 0.38 * w, mid - 0.1 * l),
            DVec3::new(0.0, 0.5 * w, mid - 0.2 * l),
        ],
        &[1.2 * thick, thick, 0.8 * thick],
        DVec3::X,
        segments,
    );
    let transverse = |side: f64| {
        tube(
            &[
                DVec3::new(side * 0.18 * w, 0.08 * w, mid),
                DVec3::new(side * 0.34 * w, 0.1 * w, mid),
                DVec3::new(side * 0.48 * w, 0.12 * w, mid),
            ],
            &[thick, 0.9 * thick, 0.8 * thick],
            DVec3::Z,
            segments,
        )
    };
    merge([
        body,
        tube(&arch, &[thick; 7], DVec3::Z, segments),
        spinous,
        transverse(1.0),
        transverse(-1.0),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertebrae_are_closed_outward_and_within_their_segment_and_width() {
        for (length, width) in [(0.05, 0.03), (0.01, 0.03), (0.2, 0.01)] {
            let m = vertebra(&Vertebra {
                length,
                width,
                rings: 8,
                segments: 12,
            });
            let s = m.stats();
            assert!(s.closed && s.signed_volume.unwrap() > 0.0, "{s:?}");
            let (lo, hi) = m.bounding_box().unwrap();
            assert!(hi.x - lo.x <= 1.05 * width, "{lo} {hi}");
            assert!(lo.z >= -0.01 * length && hi.z <= 1.01 * length, "{lo} {hi}");
        }
    }
}

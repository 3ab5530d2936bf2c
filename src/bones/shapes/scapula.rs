//! Scapula (dissertation 9.1: half as wide as long, tangent to the rib cage).
//!
//! Local frame: +z from the glenoid (z = 0, at the shoulder joint) to the vertebral border
//! (z = `length`), +x across the blade, +y the blade's outer normal (away from the rib cage).

use super::primitive::{ellipsoid, merge, sweep, tube, Section};
use crate::mesh::Mesh;
use glam::DVec3;

/// Size of a scapula.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scapula {
    /// Glenoid → vertebral border, mesh units.
    pub length: f64,
    /// Full width of the blade at its widest, mesh units.
    pub width: f64,
    /// Sections along the blade.
    pub rings: u32,
    /// Vertices per section.
    pub segments: u32,
}

/// A thin triangular blade widening from the glenoid neck to the vertebral border, a ridge
/// (the spine of the scapula) along its outer face, and the glenoid cup.
pub fn scapula(s: &Scapula) -> Mesh {
    let (l, w) = (s.length, s.width);
    let thick = 0.035 * l;
    let n = s.rings.max(4) as usize;
    let sections: Vec<Section> = (0..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            let half = 0.5 * w * (0.3 + 0.7 * t.powf(0.7)) * (1.0 - (t - 0.95).max(0.0) * 8.0);
            Section::at_z((0.12 + 0.86 * t) * l, 0.0, 0.0, half.max(thick), thick)
        })
        .collect();
    let blade = sweep(
        DVec3::new(0.0, 0.0, 0.08 * l),
        &sections,
        DVec3::new(0.0, 0.0, 0.995 * l),
        s.segments,
    );
    let spine = tube(
        &[
            DVec3::new(0.1 * w, thick, 0.15 * l),
            DVec3::new(0.12 * w, 2.5 * thick, 0.5 * l),
            DVec3::new(0.15 * w, 1.5 * thick, 0.95 * l),
        ],
        &[1.3 * thick, 1.1 * thick, 0.8 * thick],
        DVec3::Y,
        s.segments.min(10),
    );
    let glenoid = ellipsoid(
        DVec3::new(0.0, 0.0, 0.07 * l),
        [DVec3::X, DVec3::Y, DVec3::Z],
        DVec3::new(0.16 * w, 2.0 * thick, 0.07 * l),
        s.rings.clamp(4, 8),
        s.segments.min(12),
    );
    merge([blade, spine, glenoid])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scapula_is_closed_outward_and_half_as_wide_as_long() {
        let m = scapula(&Scapula {
            length: 0.16,
            width: 0.08,
            rings: 10,
            segments: 12,
        });
        let s = m.stats();
        assert!(s.closed && s.signed_volume.unwrap() > 0.0, "{s:?}");
        let (lo, hi) = m.bounding_box().unwrap();
        assert!((hi.x - lo.x - 0.08).abs() < 0.01, "{lo} {hi}");
        assert!(hi.z <= 0.16 && lo.z >= 0.0);
    }
}

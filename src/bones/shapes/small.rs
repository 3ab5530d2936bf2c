//! Groups of small bones: carpals (wrist) and tarsals (ankle).
//!
//! Local frame as the long bones: +z distal along the segment from z = 0 to `length`, +x
//! lateral, +y anterior (dorsal side of the hand or foot).

use super::primitive::{ellipsoid, merge};
use crate::mesh::Mesh;
use glam::DVec3;

/// Size of a group of small bones.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Block {
    /// Extent along the segment, mesh units.
    pub length: f64,
    /// Half-width across the limb (x), mesh units.
    pub width: f64,
    /// Half-depth (y), mesh units.
    pub depth: f64,
    /// Latitude bands per small bone.
    pub rings: u32,
    /// Vertices per band.
    pub segments: u32,
}

fn nugget(b: &Block, centre: DVec3, radii: DVec3) -> Mesh {
    ellipsoid(
        centre,
        [DVec3::X, DVec3::Y, DVec3::Z],
        radii,
        b.rings.clamp(4, 8),
        b.segments.min(12),
    )
}

/// Carpals: two rows of four small bones across the wrist.
pub fn carpals(b: &Block) -> Mesh {
    let cell = b.width / 4.0;
    let mut parts = Vec::new();
    for (row, z) in [(0, 0.28), (1, 0.72)] {
        for k in 0..4 {
            let x = -b.width + cell * (2 * k + 1) as f64;
            let centre = DVec3::new(x, 0.0, z * b.length);
            let radii = DVec3::new(
                0.85 * cell,
                0.7 * b.depth,
                (0.22 + 0.03 * row as f64) * b.length,
            );
            parts.push(nugget(b, centre, radii));
        }
    }
    merge(parts)
}

/// Tarsals: the talus under the ankle joint, the calcaneus reaching back to the heel, and a
/// distal row of four small bones.
pub fn tarsals(b: &Block) -> Mesh {
    let cell = b.width / 4.0;
    let mut parts = vec![
        nugget(
            b,
            DVec3::new(0.0, 0.1 * b.depth, 0.2 * b.length),
            DVec3::new(0.55 * b.width, 0.5 * b.depth, 0.2 * b.length),
        ),
        nugget(
            b,
            DVec3::new(0.1 * b.width, -0.45 * b.depth, 0.35 * b.length),
            DVec3::new(0.4 * b.width, 0.45 * b.depth, 0.3 * b.length),
        ),
    ];
    for k in 0..4 {
        let x = -b.width + cell * (2 * k + 1) as f64;
        parts.push(nugget(
            b,
            DVec3::new(x, 0.1 * b.depth, 0.8 * b.length),
            DVec3::new(0.85 * cell, 0.6 * b.depth, 0.17 * b.length),
        ));
    }
    merge(parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_bone_groups_are_closed_and_outward() {
        let b = Block {
            length: 0.05,
            width: 0.03,
            depth: 0.015,
            rings: 6,
            segments: 8,
        };
        for mesh in [carpals(&b), tarsals(&b)] {
            let s = mesh.stats();
            assert!(s.closed && s.signed_volume.unwrap() > 0.0, "{s:?}");
            let (lo, hi) = mesh.bounding_box().unwrap();
            assert!(lo.z >= -1e-9 && hi.z <= b.length + 1e-9, "{lo} {hi}");
        }
    }
}

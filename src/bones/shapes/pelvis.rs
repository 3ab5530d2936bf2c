//! Pelvis (dissertation 9.1: fixed to the nearest vertebral segment, sockets at the hips).
//!
//! Local frame: origin midway between the hip sockets, +x the figure's left (the left socket at
//! `(half_width, 0, 0)`), +y dorsal, +z cranial (along the spine towards the head).

use super::primitive::{merge, sweep, tube, Section};
use crate::mesh::Mesh;
use glam::DVec3;
use std::f64::consts::TAU;

/// Size of a pelvis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pelvis {
    /// Half the distance between the hip sockets, mesh units.
    pub half_width: f64,
    /// Cranial extent of the iliac blades above the sockets, mesh units.
    pub height: f64,
    /// Radius of the sockets (the femoral head radius), mesh units.
    pub socket: f64,
    /// Sections per blade.
    pub rings: u32,
    /// Vertices per section.
    pub segments: u32,
}

/// Per side: a rim round the socket (acetabulum), an iliac blade rising cranially and flaring
/// laterally, and the pubic and ischial bars closing the obturator ring at the midline.
pub fn pelvis(p: &Pelvis) -> Mesh {
    let (hw, h, rs) = (p.half_width, p.height, p.socket);
    let bar = (0.35 * rs).max(0.04 * hw);
    let segments = p.segments.min(10);
    let mut parts = Vec::new();
    for side in [1.0, -1.0] {
        let socket = DVec3::new(side * hw, 0.0, 0.0);
        // Acetabular rim: an open ring round the socket, opening laterally.
        let rim: Vec<DVec3> = (0..=10)
            .map(|k| {
                let a = TAU * (0.08 + 0.84 * k as f64 / 10.0);
                socket + DVec3::new(side * 0.35 * rs, 1.25 * rs * a.cos(), 1.25 * rs * a.sin())
            })
            .collect();
        parts.push(tube(&rim, &[0.35 * rs; 11], DVec3::X, segments));
        // Iliac blade: from above the socket, cranially and dorsally, flaring laterally.
        let n = p.rings.max(4) as usize;
        let sections: Vec<Section> = (0..=n)
            .map(|k| {
                let t = k as f64 / n as f64;
                let centre = DVec3::new(
                    side * hw * (1.0 + 0.2 * t),
                    0.3 * hw * t,
                    1.3 * rs + (h - 1.3 * rs) * t,
                );
                let wide = hw * (0.25 + 0.45 * (std::f64::consts::PI * t * 0.9).sin());
                Section {
                    centre,
                    x: DVec3::Y,
                    y: DVec3::X,
                    a: wide.max(bar),
                    b: bar,
                }
            })
            .collect();
        parts.push(sweep(
            socket + DVec3::new(0.0, 0.0, 1.0 * rs),
            &sections,
            DVec3::new(side * hw * 1.2, 0.3 * hw, h + bar),
            p.segments,
        ));
        // Pubis (ventral) and ischium (dorsal-caudal) bars to the symphysis.
        let symphysis = DVec3::new(side * bar * 1.5, -0.55 * hw, -1.2 * rs);
        parts.push(tube(
            &[
                socket + DVec3::new(-side * 0.9 * rs, -1.1 * rs, 0.0),
                DVec3::new(side * 0.5 * hw, -0.45 * hw, -0.5 * rs),
                symphysis,
            ],
            &[bar; 3],
            DVec3::Z,
            segments,
        ));
        parts.push(tube(
            &[
                socket + DVec3::new(-side * 0.5 * rs, 0.4 * rs, -1.2 * rs),
                DVec3::new(side * 0.75 * hw, 0.1 * hw, -2.2 * rs),
                DVec3::new(side * 0.35 * hw, -0.3 * hw, -2.4 * rs),
                symphysis,
            ],
            &[1.2 * bar, 1.3 * bar, bar, bar],
            DVec3::Z,
            segments,
        ));
    }
    merge(parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pelvis_is_closed_outward_with_sockets_at_the_hips() {
        let p = Pelvis {
            half_width: 0.09,
            height: 0.12,
            socket: 0.025,
            rings: 8,
            segments: 10,
        };
        let m = pelvis(&p);
        let s = m.stats();
        assert!(s.closed && s.signed_volume.unwrap() > 0.0, "{s:?}");
        // Each socket has pelvis material round it but none at its centre.
        for side in [1.0, -1.0] {
            let c = DVec3::new(side * p.half_width, 0.0, 0.0);
            let nearest = m
                .positions
                .iter()
                .map(|q| q.distance(c))
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest > 0.5 * p.socket && nearest < 2.0 * p.socket,
                "{nearest}"
            );
        }
    }
}

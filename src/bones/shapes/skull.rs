//! Cranium (human-like and a generalised animal skull) and mandible.
//!
//! Local frame of the cranium: +z from the head joint (z = 0) to the head's end (z = `length`:
//! the crown of an upright figure, the snout of a horizontal one), +y dorsal (the back of a
//! human head, the top of an animal's), +x the figure's left. Features (orbits, nasal aperture,
//! zygomatic arches, the snout) are placed by fractions of the length and sized by the width,
//! so the orbits stay round when the skull is stretched (9.1.1).

use super::primitive::{dent, ellipsoid, merge, sweep, tube, Section};
use crate::mesh::Mesh;
use glam::DVec3;

/// Size of a skull.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Skull {
    /// Head joint → head end, mesh units.
    pub length: f64,
    /// Half-width (x), mesh units.
    pub width: f64,
    /// Half-depth (y), mesh units.
    pub depth: f64,
    /// Bands per part.
    pub rings: u32,
    /// Vertices per band.
    pub segments: u32,
}

fn axes() -> [DVec3; 3] {
    [DVec3::X, DVec3::Y, DVec3::Z]
}

/// A human-like cranium: a round braincase above a smaller face, with orbits, a nasal
/// aperture and zygomatic arches. The face is anterior (−y).
pub fn human_cranium(s: &Skull) -> Mesh {
    let (l, w, d) = (s.length, s.width, s.depth);
    let rings = s.rings.max(8);
    let brain_c = DVec3::new(0.0, 0.12 * d, 0.6 * l);
    let brain_r = DVec3::new(w, 0.85 * d, 0.4 * l);
    let mut brain = ellipsoid(brain_c, axes(), brain_r, rings, s.segments);
    let face_c = DVec3::new(0.0, -0.42 * d, 0.4 * l);
    let face_r = DVec3::new(0.72 * w, 0.5 * d, 0.27 * l);
    let mut face = ellipsoid(face_c, axes(), face_r, rings, s.segments);
    // Orbits and the nasal aperture on the front of the face.
    let orbit = 0.26 * w;
    for side in [-1.0, 1.0] {
        let centre = DVec3::new(side * 0.36 * w, face_c.y - 0.85 * face_r.y, 0.5 * l);
        dent(&mut face, centre, orbit, 0.45 * orbit, -DVec3::Y);
        dent(&mut brain, centre, orbit, 0.45 * orbit, -DVec3::Y);
    }
    let nose = DVec3::new(0.0, face_c.y - face_r.y, 0.33 * l);
    dent(&mut face, nose, 0.14 * w, 0.3 * 0.14 * w, -DVec3::Y);
    let mut parts = vec![brain, face];
    for side in [-1.0, 1.0] {
        parts.push(tube(
            &[
                DVec3::new(side * 0.6 * w, face_c.y - 0.2 * face_r.y, 0.4 * l),
                DVec3::new(side * 0.82 * w, -0.05 * d, 0.4 * l),
                DVec3::new(side * 0.8 * w, 0.15 * d, 0.42 * l),
            ],
            &[0.06 * w; 3],
            DVec3::Y,
            s.segments.min(10),
        ));
    }
    merge(parts)
}

/// A generalised animal skull (9.1.1): a braincase at the back, a tapering snout to the end,
/// orbits on the sides, zygomatic arches and nostrils. The snout points along +z, the top is +y.
pub fn animal_cranium(s: &Skull) -> Mesh {
    let (l, w, d) = (s.length, s.width, s.depth);
    let rings = s.rings.max(8);
    let brain_c = DVec3::new(0.0, 0.1 * d, 0.3 * l);
    let brain_r = DVec3::new(0.9 * w, 0.85 * d, 0.3 * l);
    let mut brain = ellipsoid(brain_c, axes(), brain_r, rings, s.segments);
    let n = rings as usize;
    let sections: Vec<Section> = (0..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            let taper = 1.0 - 0.55 * t;
            Section::at_z(
                (0.25 + 0.72 * t) * l,
                0.0,
                (0.05 - 0.25 * t) * d,
                0.7 * w * taper,
                0.65 * d * taper,
            )
        })
        .collect();
    let mut snout = sweep(
        DVec3::new(0.0, 0.05 * d, 0.2 * l),
        &sections,
        DVec3::new(0.0, -0.2 * d, l),
        s.segments,
    );
    let orbit = 0.3 * w;
    for side in [-1.0, 1.0] {
        let outward = DVec3::new(side, 0.6, 0.0).normalize();
        let centre = DVec3::new(side * 0.72 * w, 0.35 * d, 0.5 * l);
        dent(&mut snout, centre, orbit, 0.4 * orbit, outward);
        dent(&mut brain, centre, orbit, 0.4 * orbit, outward);
        let nostril = DVec3::new(side * 0.12 * w, -0.05 * d, 0.98 * l);
        dent(&mut snout, nostril, 0.1 * w, 0.03 * w, DVec3::Z);
    }
    let mut parts = vec![brain, snout];
    for side in [-1.0, 1.0] {
        parts.push(tube(
            &[
                DVec3::new(side * 0.45 * w, -0.25 * d, 0.62 * l),
                DVec3::new(side * 0.8 * w, -0.2 * d, 0.45 * l),
                DVec3::new(side * 0.75 * w, -0.1 * d, 0.3 * l),
            ],
            &[0.07 * w; 3],
            DVec3::Y,
            s.segments.min(10),
        ));
    }
    merge(parts)
}

/// Size of a mandible.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jaw {
    /// Hinge → chin, mesh units.
    pub length: f64,
    /// Half the distance between the two hinges, mesh units.
    pub width: f64,
    /// Height of the rami (towards the cranium), mesh units.
    pub height: f64,
    /// Vertices per ring.
    pub segments: u32,
}

/// A mandible: two bodies meeting at the chin (+z, at `length`) and two rami rising (+y)
/// to the hinges beside the origin, +x left.
pub fn mandible(j: &Jaw) -> Mesh {
    let (l, w, h) = (j.length, j.width, j.height);
    let r = (0.12 * w).min(0.1 * l).max(f64::EPSILON);
    let body = |side: f64| {
        let points: Vec<DVec3> = (0..=8)
            .map(|k| {
                let t = k as f64 / 8.0;
                // A U: wide at the hinges, meeting at the chin.
                let x = side * w * (1.0 - t * t).max(0.0).sqrt().max(0.08);
                DVec3::new(x, -0.1 * h, t * l)
            })
            .collect();
        let radii: Vec<f64> = (0..=8).map(|k| r * (1.0 + 0.3 * k as f64 / 8.0)).collect();
        tube(&points, &radii, DVec3::Y, j.segments.min(10))
    };
    let ramus = |side: f64| {
        tube(
            &[
                DVec3::new(side * w, -0.1 * h, 0.05 * l),
                DVec3::new(side * w, 0.5 * h, 0.0),
                DVec3::new(side * w, h, -0.02 * l),
            ],
            &[r * 1.1, r, 0.8 * r],
            DVec3::X,
            j.segments.min(10),
        )
    };
    merge([body(1.0), body(-1.0), ramus(1.0), ramus(-1.0)])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skulls_and_mandible_are_closed_and_outward() {
        let s = Skull {
            length: 0.22,
            width: 0.07,
            depth: 0.09,
            rings: 12,
            segments: 16,
        };
        let j = Jaw {
            length: 0.1,
            width: 0.05,
            height: 0.05,
            segments: 10,
        };
        for mesh in [human_cranium(&s), animal_cranium(&s), mandible(&j)] {
            let st = mesh.stats();
            assert!(st.closed && st.signed_volume.unwrap() > 0.0, "{st:?}");
        }
    }

    #[test]
    fn orbits_are_recessed() {
        let s = Skull {
            length: 0.22,
            width: 0.07,
            depth: 0.09,
            rings: 24,
            segments: 32,
        };
        let m = human_cranium(&s);
        // The face reaches further forward (−y) beside the orbits than at their centres.
        let front = |x: f64| {
            m.positions
                .iter()
                .filter(|p| (p.x - x).abs() < 0.01 && (p.z - 0.5 * s.length).abs() < 0.01)
                .map(|p| p.y)
                .fold(f64::INFINITY, f64::min)
        };
        assert!(front(0.36 * s.width) > front(0.0) - 1e-9);
    }
}

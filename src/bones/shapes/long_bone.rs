//! Long bones of the limbs: humerus, femur, radius + ulna, tibia + fibula, metacarpals and
//! metatarsals, phalanges.
//!
//! Local frame (all limb bones): +z from the proximal joint (z = 0) to the distal joint
//! (z = `length`), +x lateral, +y anterior. Sizes scale with the shaft radius, not the length:
//! a femoral head stays a sphere of radius ∝ shaft radius however long the femur is (the
//! feature-preserving scaling 9.1.1 recommends).

use super::primitive::{ellipsoid, merge, profile_z, tube};
use crate::mesh::Mesh;
use glam::DVec3;

/// Parameters of one long bone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LongBone {
    /// Proximal to distal joint distance, mesh units.
    pub length: f64,
    /// Shaft radius, mesh units.
    pub radius: f64,
    /// Radius of the bone ends as a multiple of the shaft radius.
    pub epiphysis: f64,
    /// Sections along the profile.
    pub rings: u32,
    /// Vertices per section.
    pub segments: u32,
}

/// Profile entries from `from` to `to` (x, y offsets at both ends interpolated), with shaft
/// semi-axes `shaft` and end semi-axes `proximal`/`distal` blended over the end fifths.
fn shaft_profile(
    (z0, x0, y0): (f64, f64, f64),
    (z1, x1, y1): (f64, f64, f64),
    shaft: (f64, f64),
    proximal: (f64, f64),
    distal: (f64, f64),
    rings: u32,
) -> Vec<(f64, f64, f64, f64, f64)> {
    let n = rings.max(4);
    (0..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            let p = (1.0 - t / 0.22).max(0.0).powi(2);
            let d = (1.0 - (1.0 - t) / 0.22).max(0.0).powi(2);
            let s = 1.0 - p - d;
            // Round the very ends so the caps meet smoothly.
            let round = |u: f64| (1.0 - (1.0 - u.min(1.0)).powi(2)).sqrt().max(0.35);
            let end = round(t / 0.06) * round((1.0 - t) / 0.06);
            (
                z0 + (z1 - z0) * t,
                x0 + (x1 - x0) * t,
                y0 + (y1 - y0) * t,
                end * (shaft.0 * s + proximal.0 * p + distal.0 * d),
                end * (shaft.1 * s + proximal.1 * p + distal.1 * d),
            )
        })
        .collect()
}

fn sphere(centre: DVec3, r: f64, b: &LongBone) -> Mesh {
    ellipsoid(
        centre,
        [DVec3::X, DVec3::Y, DVec3::Z],
        DVec3::splat(r),
        b.rings.max(6),
        b.segments,
    )
}

/// Humerus: a round head centred on the shoulder joint (the origin), a shaft starting just
/// lateral of it, and a wide distal end (the condyles) at the elbow.
pub fn humerus(b: &LongBone) -> Mesh {
    let r = b.radius;
    let e = b.epiphysis * r;
    let head = (1.25 * e).min(0.2 * b.length);
    let profile = shaft_profile(
        (0.2 * head, 0.45 * head, -0.1 * head),
        (b.length, 0.0, 0.0),
        (r, r),
        (0.9 * e, 0.9 * e),
        (1.3 * e, 0.7 * e),
        b.rings,
    );
    merge([
        sphere(DVec3::ZERO, head, b),
        profile_z(&profile, (0.3 * r, 0.3 * r), b.segments),
    ])
}

/// Femur: the head centred on the hip joint (the origin), a neck running laterally and
/// distally to the greater trochanter, a shaft slanting back to the knee, wide condyles.
pub fn femur(b: &LongBone) -> Mesh {
    let r = b.radius;
    let e = b.epiphysis * r;
    let head = (1.15 * e).min(0.15 * b.length);
    let trochanter = DVec3::new(1.7 * head, 0.0, 0.9 * head);
    let neck = tube(
        &[DVec3::ZERO, trochanter * 0.5, trochanter],
        &[0.55 * head, 0.5 * head, 0.6 * head],
        DVec3::Y,
        b.segments,
    );
    let profile = shaft_profile(
        (trochanter.z - 0.4 * head, trochanter.x, 0.0),
        (b.length, 0.0, 0.0),
        (r, r),
        (0.8 * e, 0.8 * e),
        (1.2 * e, 0.85 * e),
        b.rings,
    );
    merge([
        sphere(DVec3::ZERO, head, b),
        neck,
        profile_z(&profile, (0.3 * r, 0.3 * r), b.segments),
    ])
}

/// Radius and ulna: two parallel bones; the ulna (medial, posterior) reaches behind the elbow
/// (the olecranon), the radius (lateral) widens towards the wrist.
pub fn radius_ulna(b: &LongBone) -> Mesh {
    let r = b.radius;
    let e = b.epiphysis * r;
    let ulna = shaft_profile(
        (-0.08 * b.length, -0.5 * r, -0.25 * r),
        (0.97 * b.length, -0.5 * r, 0.0),
        (0.5 * r, 0.5 * r),
        (0.5 * e, 0.45 * e),
        (0.35 * e, 0.35 * e),
        b.rings,
    );
    let radius = shaft_profile(
        (0.04 * b.length, 0.55 * r, 0.1 * r),
        (b.length, 0.45 * r, 0.0),
        (0.45 * r, 0.45 * r),
        (0.35 * e, 0.35 * e),
        (0.55 * e, 0.4 * e),
        b.rings,
    );
    merge([
        profile_z(&ulna, (0.2 * r, 0.2 * r), b.segments),
        profile_z(&radius, (0.2 * r, 0.2 * r), b.segments),
    ])
}

/// Tibia and fibula: a thick medial tibia with a wide plateau at the knee and a thin lateral,
/// posterior fibula.
pub fn tibia_fibula(b: &LongBone) -> Mesh {
    let r = b.radius;
    let e = b.epiphysis * r;
    let tibia = shaft_profile(
        (0.0, -0.25 * r, 0.0),
        (b.length, -0.2 * r, 0.0),
        (0.85 * r, 0.85 * r),
        (1.1 * e, 0.8 * e),
        (0.7 * e, 0.6 * e),
        b.rings,
    );
    let fibula = shaft_profile(
        (0.1 * b.length, 0.95 * r, -0.3 * r),
        (1.0 * b.length, 0.8 * r, -0.2 * r),
        (0.28 * r, 0.28 * r),
        (0.25 * e, 0.25 * e),
        (0.25 * e, 0.25 * e),
        b.rings,
    );
    merge([
        profile_z(&tibia, (0.3 * r, 0.3 * r), b.segments),
        profile_z(&fibula, (0.15 * r, 0.15 * r), b.segments),
    ])
}

/// A metacarpal or metatarsal: a slim shaft between a square-ish base and a rounded head.
pub fn metapodial(b: &LongBone) -> Mesh {
    let r = b.radius;
    let e = b.epiphysis * r;
    let profile = shaft_profile(
        (0.03 * b.length, 0.0, 0.0),
        (0.97 * b.length, 0.0, 0.0),
        (r, r),
        (0.85 * e, 0.8 * e),
        (0.8 * e, 0.8 * e),
        b.rings,
    );
    profile_z(&profile, (0.2 * r, 0.3 * r), b.segments)
}

/// A phalanx; `distal` tapers the far end to a tip (the last phalanx of a digit).
pub fn phalanx(b: &LongBone, distal: bool) -> Mesh {
    let r = b.radius;
    let e = b.epiphysis * r;
    let tip = if distal { 0.45 * r } else { 0.75 * e };
    let profile = shaft_profile(
        (0.04 * b.length, 0.0, 0.0),
        (0.96 * b.length, 0.0, 0.0),
        (0.85 * r, 0.8 * r),
        (0.75 * e, 0.7 * e),
        (tip, 0.9 * tip),
        b.rings,
    );
    profile_z(&profile, (0.15 * r, 0.25 * r), b.segments)
}

/// Patella: a flattened oval of `width` in the local frame of the shank (anterior +y), centred
/// at the origin.
pub fn patella(width: f64, rings: u32, segments: u32) -> Mesh {
    ellipsoid(
        DVec3::ZERO,
        [DVec3::X, DVec3::Y, DVec3::Z],
        DVec3::new(0.5 * width, 0.22 * width, 0.6 * width),
        rings.max(6),
        segments,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bone(length: f64) -> LongBone {
        LongBone {
            length,
            radius: 0.02,
            epiphysis: 1.7,
            rings: 12,
            segments: 12,
        }
    }

    #[test]
    fn long_bones_are_closed_and_outward() {
        for mesh in [
            humerus(&bone(0.3)),
            femur(&bone(0.45)),
            radius_ulna(&bone(0.25)),
            tibia_fibula(&bone(0.4)),
            metapodial(&bone(0.06)),
            phalanx(&bone(0.03), true),
            patella(0.05, 8, 12),
        ] {
            let s = mesh.stats();
            assert!(s.closed && s.signed_volume.unwrap() > 0.0, "{s:?}");
        }
    }

    #[test]
    fn the_femoral_head_keeps_its_size_when_the_femur_is_stretched() {
        // Head vertices are those within the head radius of the origin; their farthest
        // distance is the head radius for a short and a long femur alike.
        let n = (12 - 1) * 12 + 2;
        let head_radius = |m: &Mesh| {
            m.positions[..n]
                .iter()
                .map(|p| p.length())
                .fold(0.0, f64::max)
        };
        let short = head_radius(&femur(&bone(0.4)));
        let long = head_radius(&femur(&bone(0.8)));
        assert!((short - long).abs() < 1e-12 && short > 0.0);
        // The head is round: every head vertex lies at the same distance from its centre.
        let m = femur(&bone(0.8));
        let d: Vec<f64> = m.positions[..n].iter().map(|p| p.length()).collect();
        let (lo, hi) = d
            .iter()
            .fold((f64::MAX, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        assert!(hi - lo < 1e-9 * hi.max(1.0), "{lo} {hi}");
    }
}

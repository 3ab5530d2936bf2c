//! Closed, outward-wound building blocks for bone shapes: swept elliptical sections with pole
//! caps, ellipsoids, tubes along curves, and shallow dents for features such as eye sockets.
//!
//! Every builder returns one closed, consistently oriented surface (each edge used by exactly
//! two triangles in opposite directions, positive signed volume). A bone is one or more such
//! parts; parts may overlap (no boolean union), which keeps each part closed.

use crate::mesh::Mesh;
use glam::DVec3;
use std::f64::consts::{PI, TAU};

/// One elliptical cross-section of a swept part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Centre of the ellipse.
    pub centre: DVec3,
    /// Unit direction of the first semi-axis.
    pub x: DVec3,
    /// Unit direction of the second semi-axis (perpendicular to `x`).
    pub y: DVec3,
    /// First semi-axis length.
    pub a: f64,
    /// Second semi-axis length.
    pub b: f64,
}

impl Section {
    /// A section perpendicular to local z at height `z`, centred at `(cx, cy, z)`, semi-axes
    /// `a` along x and `b` along y.
    pub fn at_z(z: f64, cx: f64, cy: f64, a: f64, b: f64) -> Self {
        Self {
            centre: DVec3::new(cx, cy, z),
            x: DVec3::X,
            y: DVec3::Y,
            a,
            b,
        }
    }
}

/// A closed surface through `sections` (each a ring of `segments` vertices) with a pole vertex
/// at `start` before the first ring and at `end` after the last. The winding is made outward
/// (positive signed volume).
pub fn sweep(start: DVec3, sections: &[Section], end: DVec3, segments: u32) -> Mesh {
    let segments = segments.max(3);
    let mut positions = vec![start];
    for s in sections {
        for k in 0..segments {
            let phi = TAU * k as f64 / segments as f64;
            positions.push(s.centre + s.x * (s.a * phi.cos()) + s.y * (s.b * phi.sin()));
        }
    }
    positions.push(end);
    let last = positions.len() as u32 - 1;
    let ring = |r: usize, k: u32| 1 + r as u32 * segments + k % segments;
    let mut triangles = Vec::new();
    if sections.is_empty() {
        return Mesh {
            positions: Vec::new(),
            triangles,
        };
    }
    for k in 0..segments {
        triangles.push([0, ring(0, k + 1), ring(0, k)]);
        triangles.push([
            last,
            ring(sections.len() - 1, k),
            ring(sections.len() - 1, k + 1),
        ]);
    }
    for r in 0..sections.len() - 1 {
        for k in 0..segments {
            let (a, b, c, d) = (
                ring(r, k),
                ring(r, k + 1),
                ring(r + 1, k),
                ring(r + 1, k + 1),
            );
            triangles.push([a, b, c]);
            triangles.push([b, d, c]);
        }
    }
    let mut mesh = Mesh {
        positions,
        triangles,
    };
    orient_outward(&mut mesh);
    mesh
}

/// Flips every triangle when the signed volume is negative.
pub fn orient_outward(mesh: &mut Mesh) {
    if mesh.signed_volume() < 0.0 {
        for t in &mut mesh.triangles {
            t.swap(1, 2);
        }
    }
}

/// A closed surface along local z: one section per `(z, cx, cy, a, b)` of `profile` (z
/// increasing), poles on the axis through the first and last section centres, `cap` beyond them.
pub fn profile_z(profile: &[(f64, f64, f64, f64, f64)], cap: (f64, f64), segments: u32) -> Mesh {
    let sections: Vec<Section> = profile
        .iter()
        .map(|&(z, cx, cy, a, b)| Section::at_z(z, cx, cy, a, b))
        .collect();
    let (Some(first), Some(last)) = (sections.first(), sections.last()) else {
        return Mesh {
            positions: Vec::new(),
            triangles: Vec::new(),
        };
    };
    sweep(
        first.centre - DVec3::Z * cap.0,
        &sections,
        last.centre + DVec3::Z * cap.1,
        segments,
    )
}

/// An ellipsoid about `centre` with semi-axes `radii` along `axes` (orthonormal, right-handed or
/// not: the winding is fixed either way).
pub fn ellipsoid(centre: DVec3, axes: [DVec3; 3], radii: DVec3, rings: u32, segments: u32) -> Mesh {
    let rings = rings.max(2);
    let sections: Vec<Section> = (1..rings)
        .map(|r| {
            let theta = PI * r as f64 / rings as f64;
            Section {
                centre: centre - axes[2] * (radii.z * theta.cos()),
                x: axes[0],
                y: axes[1],
                a: radii.x * theta.sin(),
                b: radii.y * theta.sin(),
            }
        })
        .collect();
    sweep(
        centre - axes[2] * radii.z,
        &sections,
        centre + axes[2] * radii.z,
        segments,
    )
}

/// A tube of varying `radii` along the polyline `points` (at least two, distinct neighbours),
/// with rounded caps. `hint` orients the rings (any direction not along the tube).
pub fn tube(points: &[DVec3], radii: &[f64], hint: DVec3, segments: u32) -> Mesh {
    let n = points.len().min(radii.len());
    if n < 2 {
        return Mesh {
            positions: Vec::new(),
            triangles: Vec::new(),
        };
    }
    let tangent = |k: usize| {
        let a = points[k.saturating_sub(1)];
        let b = points[(k + 1).min(n - 1)];
        (b - a).try_normalize().unwrap_or(DVec3::Z)
    };
    let mut sections = Vec::with_capacity(n);
    let mut previous = hint;
    for k in 0..n {
        let t = tangent(k);
        let mut x = previous - t * previous.dot(t);
        if x.length_squared() < 1e-12 {
            x = t.any_orthonormal_vector();
        }
        let x = x.normalize();
        previous = x;
        sections.push(Section {
            centre: points[k],
            x,
            y: t.cross(x),
            a: radii[k],
            b: radii[k],
        });
    }
    let start = points[0] - tangent(0) * radii[0] * 0.7;
    let end = points[n - 1] + tangent(n - 1) * radii[n - 1] * 0.7;
    sweep(start, &sections, end, segments)
}

/// Appends `parts` into one mesh (each part stays a separate closed component).
pub fn merge(parts: impl IntoIterator<Item = Mesh>) -> Mesh {
    let mut out = Mesh {
        positions: Vec::new(),
        triangles: Vec::new(),
    };
    for part in parts {
        let offset = out.positions.len() as u32;
        out.positions.extend(part.positions);
        out.triangles
            .extend(part.triangles.iter().map(|t| t.map(|i| i + offset)));
    }
    out
}

/// Pushes the vertices within `radius` of `centre` by up to `depth` along `-outward` (a smooth
/// bump profile, zero at the rim): a shallow socket such as an orbit. Topology is unchanged,
/// so the mesh stays closed.
pub fn dent(mesh: &mut Mesh, centre: DVec3, radius: f64, depth: f64, outward: DVec3) {
    if radius <= 0.0 {
        return;
    }
    for p in &mut mesh.positions {
        let d = p.distance(centre) / radius;
        if d < 1.0 {
            let w = (1.0 - d * d).powi(2);
            *p -= outward * (depth * w);
        }
    }
}

/// Places a mesh built in a local frame: `p ↦ origin + x·p.x + y·p.y + z·p.z`. A mirroring
/// frame (negative determinant) flips the winding so the result stays outward.
pub fn place(mesh: &Mesh, origin: DVec3, axes: [DVec3; 3]) -> Mesh {
    let [x, y, z] = axes;
    let mut out = Mesh {
        positions: mesh
            .positions
            .iter()
            .map(|p| origin + x * p.x + y * p.y + z * p.z)
            .collect(),
        triangles: mesh.triangles.clone(),
    };
    if x.cross(y).dot(z) < 0.0 {
        for t in &mut out.triangles {
            t.swap(1, 2);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn closed_outward(mesh: &Mesh) {
        let stats = mesh.stats();
        assert!(stats.closed, "{stats:?}");
        assert!(stats.signed_volume.unwrap() > 0.0, "{stats:?}");
    }

    #[test]
    fn ellipsoid_volume_and_closedness() {
        let e = ellipsoid(
            DVec3::ONE,
            [DVec3::X, DVec3::Y, DVec3::Z],
            DVec3::new(1.0, 2.0, 3.0),
            48,
            96,
        );
        closed_outward(&e);
        let exact = 4.0 / 3.0 * PI * 6.0;
        assert!((e.signed_volume() - exact).abs() / exact < 0.01);
        // A left-handed frame gives the same outward ellipsoid.
        let m = ellipsoid(
            DVec3::ZERO,
            [DVec3::X, DVec3::Z, DVec3::Y],
            DVec3::ONE,
            8,
            8,
        );
        closed_outward(&m);
    }

    #[test]
    fn tubes_profiles_dents_and_mirrors_stay_closed() {
        let points: Vec<DVec3> = (0..10)
            .map(|k| DVec3::new((k as f64 * 0.3).cos(), (k as f64 * 0.3).sin(), 0.0))
            .collect();
        let mut t = tube(&points, &[0.1; 10], DVec3::Z, 8);
        closed_outward(&t);
        dent(&mut t, points[5], 0.2, 0.02, DVec3::Z);
        closed_outward(&t);
        let p = profile_z(
            &[(0.0, 0.0, 0.0, 1.0, 0.5), (2.0, 0.1, 0.0, 0.5, 0.5)],
            (0.2, 0.2),
            12,
        );
        closed_outward(&p);
        let mirrored = place(&p, DVec3::ONE, [-DVec3::X, DVec3::Y, DVec3::Z]);
        closed_outward(&mirrored);
        assert!((mirrored.signed_volume() - p.signed_volume()).abs() < 1e-9);
        let both = merge([p, mirrored]);
        closed_outward(&both);
    }
}

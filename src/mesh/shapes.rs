//! Analytic meshes for tests, examples and benchmarks.

use super::Mesh;
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

impl Mesh {
    /// A closed, outward-wound axis-aligned box from `min` to `max` (8 vertices, 12 triangles).
    pub fn cuboid(min: DVec3, max: DVec3) -> Mesh {
        let positions = (0..8)
            .map(|i| {
                DVec3::new(
                    if i & 1 == 0 { min.x } else { max.x },
                    if i & 2 == 0 { min.y } else { max.y },
                    if i & 4 == 0 { min.z } else { max.z },
                )
            })
            .collect();
        let triangles = vec![
            [0, 2, 1],
            [1, 2, 3], // -z
            [4, 5, 6],
            [5, 7, 6], // +z
            [0, 1, 4],
            [1, 5, 4], // -y
            [2, 6, 3],
            [3, 6, 7], // +y
            [0, 4, 2],
            [2, 4, 6], // -x
            [1, 3, 5],
            [3, 7, 5], // +x
        ];
        Mesh {
            positions,
            triangles,
        }
    }

    /// A closed, outward-wound surface of revolution about the +Y axis through `centre`: a pole
    /// at `top` height, one ring of `segments` vertices per `(radius, height)` in `rings` (from
    /// top to bottom), and a pole at `bottom` height.
    pub fn lathe(
        centre: DVec3,
        top: f64,
        rings: &[(f64, f64)],
        bottom: f64,
        segments: u32,
    ) -> Mesh {
        let segments = segments.max(3);
        let mut positions = vec![centre + DVec3::new(0.0, top, 0.0)];
        for &(radius, height) in rings {
            for s in 0..segments {
                let phi = TAU * s as f64 / segments as f64;
                positions
                    .push(centre + DVec3::new(radius * phi.cos(), height, -radius * phi.sin()));
            }
        }
        positions.push(centre + DVec3::new(0.0, bottom, 0.0));
        let last = positions.len() as u32 - 1;
        let ring = |r: usize, s: u32| 1 + r as u32 * segments + s % segments;
        let mut triangles = Vec::new();
        if !rings.is_empty() {
            for s in 0..segments {
                triangles.push([0, ring(0, s), ring(0, s + 1)]);
                triangles.push([last, ring(rings.len() - 1, s + 1), ring(rings.len() - 1, s)]);
            }
        }
        for r in 0..rings.len().saturating_sub(1) {
            for s in 0..segments {
                let (a, b, c, d) = (
                    ring(r, s),
                    ring(r, s + 1),
                    ring(r + 1, s),
                    ring(r + 1, s + 1),
                );
                triangles.push([a, c, b]);
                triangles.push([b, c, d]);
            }
        }
        Mesh {
            positions,
            triangles,
        }
    }

    /// A closed, outward-wound UV sphere of `radius` about `centre` with `rings` latitude bands
    /// and `segments` longitude sectors.
    pub fn uv_sphere(centre: DVec3, radius: f64, rings: u32, segments: u32) -> Mesh {
        let rings = rings.max(2);
        let profile: Vec<(f64, f64)> = (1..rings)
            .map(|r| {
                let theta = PI * r as f64 / rings as f64;
                (radius * theta.sin(), radius * theta.cos())
            })
            .collect();
        Mesh::lathe(centre, radius, &profile, -radius, segments)
    }

    /// A closed capsule along +Y about `centre`: a cylinder of `radius` from height
    /// `-half_length` to `half_length`, capped by hemispheres with `rings` bands each.
    pub fn capsule(
        centre: DVec3,
        radius: f64,
        half_length: f64,
        rings: u32,
        segments: u32,
    ) -> Mesh {
        let rings = rings.max(1);
        let cap = |sign: f64| {
            (1..=rings).map(move |r| {
                let theta = FRAC_PI_2 * r as f64 / rings as f64;
                (
                    radius * theta.sin(),
                    sign * (half_length + radius * theta.cos()),
                )
            })
        };
        let mut profile: Vec<(f64, f64)> = cap(1.0).collect();
        profile.extend(cap(-1.0).collect::<Vec<_>>().into_iter().rev());
        Mesh::lathe(
            centre,
            half_length + radius,
            &profile,
            -(half_length + radius),
            segments,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn analytic_shapes_are_closed_and_outward() {
        let cube = Mesh::cuboid(DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0));
        assert!((cube.signed_volume() - 6.0).abs() < 1e-12);
        let sphere = Mesh::uv_sphere(DVec3::ONE, 2.0, 64, 128);
        let exact = 4.0 / 3.0 * PI * 8.0;
        assert!((sphere.signed_volume() - exact).abs() / exact < 0.01);
        let capsule = Mesh::capsule(DVec3::ZERO, 1.0, 2.0, 32, 128);
        let exact = PI * 4.0 + 4.0 / 3.0 * PI;
        assert!((capsule.signed_volume() - exact).abs() / exact < 0.01);
    }
}

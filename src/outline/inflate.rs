//! Inflation (seed 003, 4.1, after MonsterMash): the outline is triangulated and lifted into
//! a closed 3D mesh by a Poisson height field.

use super::{
    outline_skeleton, resample, InflateOptions, Outline, OutlineError, OutlineOptions,
    OutlineSkeleton,
};
use crate::mesh::Mesh;
use glam::{DVec2, DVec3};

/// A rigged part: the skeleton of an outline and its inflated mesh, both in outline units with
/// the outline at z = 0.
#[derive(Debug, Clone)]
pub struct OutlinePart {
    /// The skeleton and every intermediate result.
    pub skeleton: OutlineSkeleton,
    /// The closed inflated mesh.
    pub mesh: Mesh,
}

/// The skeleton ([`outline_skeleton`]) and the inflated mesh ([`inflate`]) of `outline`.
///
/// # Errors
/// As [`outline_skeleton`] and [`inflate`].
pub fn outline_part(
    outline: &Outline,
    options: &OutlineOptions,
) -> Result<OutlinePart, OutlineError> {
    let skeleton = outline_skeleton(outline, options)?;
    let mesh = inflate(outline, &options.inflate)?;
    Ok(OutlinePart { skeleton, mesh })
}

/// A closed, outward-wound mesh of the inflated outline. The outline is resampled at half the
/// interior spacing and filled with a triangular lattice of points (`options.spacing` times
/// the diagonal apart, none closer than half a spacing to the outline); the points are
/// Delaunay-triangulated (Bowyer-Watson) and triangles outside the outline dropped. The height
/// `h` solves `-Δh = 2` with `h = 0` on the outline (cotangent Laplacian, successive
/// over-relaxation); the front surface is `z = thickness · sqrt(h)`, the back its mirror, and
/// the two share the outline's vertices.
///
/// # Errors
/// [`OutlineError::InvalidOption`] for bad options, [`OutlineError::Mesh`] if the mesh is
/// invalid (non-finite input).
pub fn inflate(outline: &Outline, options: &InflateOptions) -> Result<Mesh, OutlineError> {
    options.validate()?;
    let (lo, hi) = outline.bounds();
    let diagonal = (hi - lo).length();
    let h = options.spacing * diagonal;
    let boundary = resample(&outline.points, 0.5 * h);
    let nb = boundary.len();
    let mut points = boundary.clone();
    let row = h * 3f64.sqrt() * 0.5;
    let rows = ((hi.y - lo.y) / row).ceil() as usize;
    let cols = ((hi.x - lo.x) / h).ceil() as usize + 1;
    for r in 0..=rows {
        for c in 0..=cols {
            let shift = if r % 2 == 1 { 0.5 * h } else { 0.0 };
            let p = DVec2::new(lo.x + c as f64 * h + shift, lo.y + r as f64 * row);
            if super::input::contains(&boundary, p) && boundary_distance(&boundary, p) >= 0.5 * h {
                points.push(p);
            }
        }
    }
    let triangles: Vec<[usize; 3]> = delaunay(&points)
        .into_iter()
        .filter(|t| {
            let c = (points[t[0]] + points[t[1]] + points[t[2]]) / 3.0;
            // Boundary-only triangles must lie inside; every such triangle is a chord triangle.
            super::input::contains(&boundary, c)
        })
        .collect();
    let height = poisson(&points, &triangles, nb, options);
    let n = points.len();
    let mut positions: Vec<DVec3> = points
        .iter()
        .zip(&height)
        .map(|(p, z)| DVec3::new(p.x, p.y, options.thickness * z.max(0.0).sqrt()))
        .collect();
    // Back vertices: interior points mirrored; boundary points are shared.
    let back = |i: usize| if i < nb { i } else { n + (i - nb) };
    let mirrored: Vec<DVec3> = positions[nb..n]
        .iter()
        .map(|p| DVec3::new(p.x, p.y, -p.z))
        .collect();
    positions.extend(mirrored);
    let mut tris: Vec<[u32; 3]> = Vec::with_capacity(2 * triangles.len());
    for t in &triangles {
        tris.push([t[0] as u32, t[1] as u32, t[2] as u32]);
    }
    for t in &triangles {
        tris.push([back(t[0]) as u32, back(t[2]) as u32, back(t[1]) as u32]);
    }
    Ok(Mesh::new(positions, tris)?)
}

fn boundary_distance(boundary: &[DVec2], p: DVec2) -> f64 {
    let m = boundary.len();
    (0..m)
        .map(|i| {
            crate::math::point_segment_distance(
                p.extend(0.0),
                boundary[i].extend(0.0),
                boundary[(i + 1) % m].extend(0.0),
            )
        })
        .fold(f64::INFINITY, f64::min)
}

/// Delaunay triangulation of `points` (Bowyer-Watson), counter-clockwise triangles.
fn delaunay(points: &[DVec2]) -> Vec<[usize; 3]> {
    let n = points.len();
    if n < 3 {
        return Vec::new();
    }
    let (lo, hi) = super::input::bounds(points);
    let centre = 0.5 * (lo + hi);
    let span = (hi - lo).max_element().max(f64::MIN_POSITIVE) * 20.0;
    let mut all = points.to_vec();
    all.push(centre + DVec2::new(-span, -span));
    all.push(centre + DVec2::new(span, -span));
    all.push(centre + DVec2::new(0.0, span));
    struct Tri {
        v: [usize; 3],
        centre: DVec2,
        r2: f64,
    }
    let make = |all: &[DVec2], v: [usize; 3]| -> Tri {
        let (a, b, c) = (all[v[0]], all[v[1]], all[v[2]]);
        let d = 2.0 * (b - a).perp_dot(c - a);
        let (ab, ac) = (b - a, c - a);
        let centre = a + DVec2::new(
            ac.y * ab.length_squared() - ab.y * ac.length_squared(),
            ab.x * ac.length_squared() - ac.x * ab.length_squared(),
        ) / d;
        Tri {
            v,
            centre,
            r2: centre.distance_squared(a),
        }
    };
    let mut tris = vec![make(&all, [n, n + 1, n + 2])];
    for i in 0..n {
        let p = all[i];
        let mut edges: Vec<[usize; 2]> = Vec::new();
        let mut k = 0;
        while k < tris.len() {
            if tris[k].centre.distance_squared(p) < tris[k].r2 {
                let t = tris.swap_remove(k);
                for e in [[t.v[0], t.v[1]], [t.v[1], t.v[2]], [t.v[2], t.v[0]]] {
                    if let Some(pos) = edges.iter().position(|f| f[0] == e[1] && f[1] == e[0]) {
                        edges.swap_remove(pos);
                    } else {
                        edges.push(e);
                    }
                }
            } else {
                k += 1;
            }
        }
        for e in edges {
            tris.push(make(&all, [e[0], e[1], i]));
        }
    }
    let mut out: Vec<[usize; 3]> = tris
        .into_iter()
        .filter(|t| t.v.iter().all(|&v| v < n))
        .map(|t| t.v)
        .collect();
    out.sort_unstable();
    out
}

/// Solves `-Δh = 2` with `h = 0` on the first `boundary` points (cotangent weights, lumped
/// areas, successive over-relaxation).
fn poisson(
    points: &[DVec2],
    triangles: &[[usize; 3]],
    boundary: usize,
    options: &InflateOptions,
) -> Vec<f64> {
    const SOURCE: f64 = 2.0;
    const RELAXATION: f64 = 1.8;
    let n = points.len();
    let mut weights: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    let mut area = vec![0.0; n];
    for t in triangles {
        let p = t.map(|i| points[i]);
        let a = 0.5 * (p[1] - p[0]).perp_dot(p[2] - p[0]).abs();
        for k in 0..3 {
            area[t[k]] += a / 3.0;
            let (i, j, o) = (t[(k + 1) % 3], t[(k + 2) % 3], t[k]);
            let (u, v) = (points[i] - points[o], points[j] - points[o]);
            let cot = u.dot(v) / u.perp_dot(v).abs().max(1e-300);
            let w = 0.5 * cot.max(0.0);
            weights[i].push((j, w));
            weights[j].push((i, w));
        }
    }
    let mut h = vec![0.0; n];
    for _ in 0..options.max_sweeps {
        let mut change: f64 = 0.0;
        let mut largest: f64 = 0.0;
        for i in boundary..n {
            let total: f64 = weights[i].iter().map(|(_, w)| w).sum();
            if total <= 0.0 {
                continue;
            }
            let sum: f64 = weights[i].iter().map(|&(j, w)| w * h[j]).sum();
            let target = (SOURCE * area[i] + sum) / total;
            let next = h[i] + RELAXATION * (target - h[i]);
            change = change.max((next - h[i]).abs());
            h[i] = next;
            largest = largest.max(next.abs());
        }
        if change <= options.convergence * largest.max(f64::MIN_POSITIVE) {
            break;
        }
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_disc_inflates_to_a_closed_roughly_spherical_mesh() {
        let circle: Vec<DVec2> = (0..64)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 64.0;
                DVec2::new(a.cos(), a.sin())
            })
            .collect();
        let outline = Outline::new(circle, &OutlineOptions::default()).unwrap();
        let mesh = inflate(&outline, &InflateOptions::default()).unwrap();
        let stats = mesh.stats();
        assert_eq!(stats.boundary_edges, 0, "{stats:?}");
        assert_eq!(stats.non_manifold_edges, 0);
        let volume = mesh.signed_volume();
        // -Δh = 2 on the unit disc: h = (1 - r²)/2, z = sqrt(h): volume = 2π ∫ sqrt((1-r²)/2) r dr · 2.
        let expected = 2.0 * std::f64::consts::TAU / (3.0 * 2f64.sqrt());
        assert!(
            (volume - expected).abs() < 0.1 * expected,
            "{volume} vs {expected}"
        );
    }
}

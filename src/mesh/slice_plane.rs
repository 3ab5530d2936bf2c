//! Mesh ∩ plane (seed 004, 3.1-3.2: transverse head slices, the median silhouette, hip slices).

use super::slice::{cut_and_link, SliceLoop};
use super::Mesh;
use glam::DVec3;

/// Intersects `mesh` with the plane through `point` with normal `normal` (any length, non-zero).
///
/// Returns one [`SliceLoop`] per connected piece, in mesh units and frame. Vertices exactly on
/// the plane count as lying on the normal's side, so a plane through vertices or along edges
/// still gives each piece once and closed loops stay closed; an open mesh gives open pieces.
/// A zero or non-finite normal gives no loops.
pub fn slice_plane(mesh: &Mesh, point: DVec3, normal: DVec3) -> Vec<SliceLoop> {
    let Some(n) = normal.try_normalize() else {
        return Vec::new();
    };
    let side: Vec<f64> = mesh.positions.iter().map(|p| (*p - point).dot(n)).collect();
    cut_and_link(&mesh.triangles, &side, |a, b| {
        let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
        let (da, db) = (side[a as usize], side[b as usize]);
        let t = if db - da > 0.0 { -da / (db - da) } else { 0.0 };
        pa.lerp(pb, t.clamp(0.0, 1.0))
    })
}

/// [`slice_plane`] without the closed loops that lie inside another closed loop of the same
/// slice: the outline of the figure's envelope. A body under its clothes, the inner wall of a
/// hollow head or a cavity reached through the mouth gives loops inside the outer one; a part
/// that stands apart (an arm beside the torso) keeps its own loop. Open pieces are kept.
pub fn slice_plane_outer(mesh: &Mesh, point: DVec3, normal: DVec3) -> Vec<SliceLoop> {
    let loops = slice_plane(mesh, point, normal);
    let Some(n) = normal.try_normalize() else {
        return loops;
    };
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let flat = |p: DVec3| ((p - point).dot(u), (p - point).dot(v));
    let polygons: Vec<Option<Vec<(f64, f64)>>> = loops
        .iter()
        .map(|l| {
            l.closed
                .then(|| l.points.iter().map(|&p| flat(p)).collect())
        })
        .collect();
    let inside_another = |i: usize| {
        let Some(first) = polygons[i].as_ref().and_then(|p| p.first()) else {
            return false;
        };
        polygons
            .iter()
            .enumerate()
            .any(|(j, p)| j != i && p.as_ref().is_some_and(|p| contains(p, *first)))
    };
    let keep: Vec<bool> = (0..loops.len()).map(|i| !inside_another(i)).collect();
    loops
        .into_iter()
        .zip(keep)
        .filter_map(|(l, k)| k.then_some(l))
        .collect()
}

/// Even-odd point-in-polygon test (the polygon closes from its last point to its first).
fn contains(polygon: &[(f64, f64)], (x, y): (f64, f64)) -> bool {
    let mut inside = false;
    let mut j = polygon.len().wrapping_sub(1);
    for (i, &(xi, yi)) in polygon.iter().enumerate() {
        let (xj, yj) = polygon[j];
        if (yi > y) != (yj > y) && x < xi + (y - yi) / (yj - yi) * (xj - xi) {
            inside = !inside;
        }
        j = i;
    }
    inside
}

#[cfg(test)]
mod outer_tests {
    use super::*;

    #[test]
    fn a_box_inside_a_box_slices_to_the_outer_loop_only() {
        let outer = Mesh::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0));
        let inner = Mesh::cuboid(DVec3::splat(-0.5), DVec3::splat(0.5));
        let apart = Mesh::cuboid(DVec3::new(3.0, -0.5, -0.5), DVec3::new(4.0, 0.5, 0.5));
        let mut mesh = outer.clone();
        for m in [inner, apart] {
            let base = mesh.positions.len() as u32;
            mesh.positions.extend(m.positions);
            mesh.triangles
                .extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        assert_eq!(slice_plane(&mesh, DVec3::ZERO, DVec3::Y).len(), 3);
        let outer_loops = slice_plane_outer(&mesh, DVec3::ZERO, DVec3::Y);
        assert_eq!(outer_loops.len(), 2);
        let widths: Vec<f64> = outer_loops.iter().map(|l| l.perimeter()).collect();
        assert!(widths.iter().any(|&w| (w - 8.0).abs() < 1e-9), "{widths:?}");
        assert!(widths.iter().any(|&w| (w - 4.0).abs() < 1e-9), "{widths:?}");
    }
}

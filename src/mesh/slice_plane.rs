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

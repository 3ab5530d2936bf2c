//! A vertex far outside the rest of the mesh (a stray vertex dragged away in the modelling
//! tool): it stretches the bounding box, so the voxels sized on it are far too coarse for the
//! figure. Found to name it in the error instead of blaming the figure's shape.

use crate::mesh::Mesh;
use glam::DVec3;

/// Share of the referenced vertices left out at each end of every axis when measuring the
/// "core" of the mesh (robust against a handful of outliers).
const TAIL: f64 = 0.01;

/// The bounding box must be this many times the core's longest side for its farthest vertex
/// to count as an outlier.
const STRETCH: f64 = 10.0;

/// The vertex farthest outside the mesh's core box (the 1st to 99th percentile of the
/// referenced vertices' coordinates on each axis) when the bounding box is at least
/// [`STRETCH`] times the core's longest side: `(vertex index, its position, the core's
/// longest side)`. `None` for a mesh without such an outlier or with too few vertices to tell.
pub(super) fn far_outlier(mesh: &Mesh) -> Option<(usize, DVec3, f64)> {
    let mut used = vec![false; mesh.positions.len()];
    for &i in mesh.triangles.iter().flatten() {
        used[i as usize] = true;
    }
    let points: Vec<(usize, DVec3)> = mesh
        .positions
        .iter()
        .enumerate()
        .filter(|&(i, _)| used[i])
        .map(|(i, &p)| (i, p))
        .collect();
    if points.len() < 8 {
        return None;
    }
    let skip = ((points.len() as f64 * TAIL).floor() as usize).max(1);
    let mut core_lo = DVec3::ZERO;
    let mut core_hi = DVec3::ZERO;
    for axis in 0..3 {
        let mut values: Vec<f64> = points.iter().map(|(_, p)| p[axis]).collect();
        values.sort_by(f64::total_cmp);
        core_lo[axis] = values[skip];
        core_hi[axis] = values[values.len() - 1 - skip];
    }
    let core = (core_hi - core_lo).max_element();
    let (lo, hi) = mesh.bounding_box()?;
    if core <= 0.0 || (hi - lo).max_element() < STRETCH * core {
        return None;
    }
    let outside = |p: DVec3| (core_lo - p).max(p - core_hi).max(DVec3::ZERO).length();
    points
        .iter()
        .max_by(|a, b| outside(a.1).total_cmp(&outside(b.1)))
        .map(|&(i, p)| (i, p, core))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dragged_vertex_is_found_and_a_clean_mesh_has_none() {
        let mut mesh = Mesh::uv_sphere(DVec3::ZERO, 1.0, 16, 32);
        assert_eq!(far_outlier(&mesh), None);
        mesh.positions[100] = DVec3::new(0.0, 1e6, 0.0);
        let (vertex, position, core) = far_outlier(&mesh).unwrap();
        assert_eq!(vertex, 100);
        assert_eq!(position.y, 1e6);
        assert!(core > 1.5 && core < 2.5, "{core}");
    }
}

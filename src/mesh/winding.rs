//! The generalised winding number of a mesh at a point (Jacobson, Kavan and Sorkine-Hornung
//! 2013): how many times the surface wraps around it.

use super::Mesh;
use glam::DVec3;

/// The winding number of `mesh` at `p` (mesh units and frame): the sum of the triangles'
/// signed solid angles seen from `p` (Van Oosterom and Strackee 1983) over 4π. About 1 inside
/// a closed outward-wound surface (2 where two shells overlap), 0 outside; holes blur it only
/// near them. O(triangles) per point.
///
/// ```
/// use glam::DVec3;
/// use skelfit::mesh::{winding_number, Mesh};
/// let cube = Mesh::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0));
/// assert!((winding_number(&cube, DVec3::ZERO) - 1.0).abs() < 1e-9);
/// assert!(winding_number(&cube, DVec3::splat(3.0)).abs() < 1e-9);
/// ```
pub fn winding_number(mesh: &Mesh, p: DVec3) -> f64 {
    let total: f64 = mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize] - p);
            let (la, lb, lc) = (a.length(), b.length(), c.length());
            let numerator = a.dot(b.cross(c));
            let denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
            2.0 * numerator.atan2(denominator)
        })
        .sum();
    total / (4.0 * std::f64::consts::PI)
}

//! Mesh ∩ sphere (seed 004, 3.3: Plumber-style slicing of the limbs, Mortara et al. 2004).

use super::slice::{cut_and_link, SliceLoop};
use super::Mesh;
use glam::DVec3;

/// Intersects `mesh` with the sphere of `radius` (mesh units) around `centre`.
///
/// Returns one [`SliceLoop`] per connected piece; each point lies exactly on the sphere (the
/// root of the edge's quadratic), so the loop is not flattened by the tessellation. Vertices on
/// the sphere count as outside. A non-positive or non-finite radius gives no loops.
///
/// Triangles are cut by their corners' sides, so a triangle whose corners all lie outside
/// while its interior crosses the sphere (a sphere smaller than the triangles) is missed:
/// subdivide coarse meshes ([`Mesh::subdivided`]) until edges are short against `radius`.
pub fn slice_sphere(mesh: &Mesh, centre: DVec3, radius: f64) -> Vec<SliceLoop> {
    if !(radius > 0.0 && radius.is_finite()) {
        return Vec::new();
    }
    let side: Vec<f64> = mesh
        .positions
        .iter()
        .map(|p| p.distance(centre) - radius)
        .collect();
    cut_and_link(&mesh.triangles, &side, |a, b| {
        // a inside, b outside (or on the sphere): the root of |a + t (b − a) − c| = r in [0, 1].
        let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
        let d = pb - pa;
        let f = pa - centre;
        let (qa, qb, qc) = (
            d.length_squared(),
            2.0 * f.dot(d),
            f.length_squared() - radius * radius,
        );
        let disc = qb * qb - 4.0 * qa * qc;
        let t = if qa > 0.0 && disc >= 0.0 {
            (-qb + disc.sqrt()) / (2.0 * qa)
        } else {
            0.0
        };
        pa + d * t.clamp(0.0, 1.0)
    })
}

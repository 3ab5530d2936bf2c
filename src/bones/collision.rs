//! Whether two bones overlap outside the articulations: a vertex of one inside the other
//! (winding number by signed crossings of a ray along +x, so overlapping closed parts of a bone
//! count once each and stay inside).

use super::Articulation;
use crate::mesh::Mesh;
use glam::DVec3;

/// Winding number of `p` with respect to `mesh` (closed, outward parts): signed crossings of the
/// ray from `p` towards +x, found in the (y, z) projection.
pub(crate) fn winding(mesh: &Mesh, p: DVec3) -> i32 {
    let mut count = 0;
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        let cross =
            |p: DVec3, q: DVec3, r: DVec3| (q.y - p.y) * (r.z - p.z) - (q.z - p.z) * (r.y - p.y);
        let (w0, w1, w2) = (cross(b, c, p), cross(c, a, p), cross(a, b, p));
        let total = w0 + w1 + w2;
        if total == 0.0 {
            continue;
        }
        let same = (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0) || (w0 <= 0.0 && w1 <= 0.0 && w2 <= 0.0);
        if !same {
            continue;
        }
        let x = (w0 * a.x + w1 * b.x + w2 * c.x) / total;
        if x > p.x {
            count += if (b - a).cross(c - a).x > 0.0 { 1 } else { -1 };
        }
    }
    count
}

fn bounds(mesh: &Mesh) -> Option<(DVec3, DVec3)> {
    mesh.bounding_box()
}

/// Whether a vertex of `a` outside every articulation lies inside `b`, or the other way round.
pub(crate) fn overlaps(a: &Mesh, b: &Mesh, articulations: &[Articulation]) -> bool {
    let (Some(ba), Some(bb)) = (bounds(a), bounds(b)) else {
        return false;
    };
    if ba.0.cmpgt(bb.1).any() || bb.0.cmpgt(ba.1).any() {
        return false;
    }
    let free = |p: &DVec3| {
        !articulations
            .iter()
            .any(|r| r.centre.distance(*p) < r.radius)
    };
    let into = |from: &Mesh, to: &Mesh, (lo, hi): (DVec3, DVec3)| {
        from.positions
            .iter()
            .filter(|p| p.cmpge(lo).all() && p.cmple(hi).all())
            .filter(|p| free(p))
            .any(|p| winding(to, *p) != 0)
    };
    into(a, b, bb) || into(b, a, ba)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlapping_boxes_overlap_unless_inside_an_articulation() {
        let a = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        let b = Mesh::cuboid(DVec3::splat(0.5), DVec3::splat(1.5));
        let c = Mesh::cuboid(DVec3::splat(2.0), DVec3::splat(3.0));
        assert_eq!(winding(&a, DVec3::splat(0.37)), 1);
        assert_eq!(winding(&a, DVec3::splat(1.37)), 0);
        assert!(overlaps(&a, &b, &[]));
        assert!(!overlaps(&a, &c, &[]));
        let joint = Articulation {
            centre: DVec3::ONE,
            radius: 0.9,
        };
        assert!(!overlaps(&a, &b, &[joint]));
    }
}

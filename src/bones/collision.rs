//! Whether two bones overlap outside the articulations: a vertex of one inside the other
//! (winding number by signed crossings of a ray along +x, so overlapping closed parts of a bone
//! count once each and stay inside).

use super::Articulation;
use crate::mesh::Mesh;
use glam::DVec3;

/// Winding number of `p` with respect to `mesh` (closed, outward parts): signed crossings of the
/// ray from `p` towards +x, found in the (y, z) projection.
pub(crate) fn winding(mesh: &Mesh, p: DVec3) -> i32 {
    (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            crossing(a, b, c, p)
        })
        .sum()
}

/// [`winding`] of each of `points`, testing only the triangles whose (y, z) bounds hold the
/// point: a triangle whose projection does not contain a point's cannot cross its ray, so the
/// numbers are [`winding`]'s; many points close together (a hand's digit centres) share one
/// pass over the mesh.
pub(crate) fn windings(mesh: &Mesh, points: &[DVec3]) -> Vec<i32> {
    let Some((lo, hi)) = points.iter().fold(None, |b: Option<(DVec3, DVec3)>, &p| {
        Some(b.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))))
    }) else {
        return Vec::new();
    };
    // The triangles whose (y, z) bounds meet the points', with those bounds.
    let near: Vec<([DVec3; 3], DVec3, DVec3)> = (0..mesh.triangles.len())
        .filter_map(|t| {
            let c = mesh.corners(t);
            let (tlo, thi) = (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]));
            let meets = tlo.y <= hi.y && thi.y >= lo.y && tlo.z <= hi.z && thi.z >= lo.z;
            meets.then_some((c, tlo, thi))
        })
        .collect();
    points
        .iter()
        .map(|&p| {
            near.iter()
                .filter(|(_, lo, hi)| lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z)
                .map(|&([a, b, c], _, _)| crossing(a, b, c, p))
                .sum()
        })
        .collect()
}

/// The signed crossing (-1, 0 or 1) of the triangle `a`, `b`, `c` with the ray from `p`
/// towards +x.
#[inline]
fn crossing(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> i32 {
    let cross =
        |p: DVec3, q: DVec3, r: DVec3| (q.y - p.y) * (r.z - p.z) - (q.z - p.z) * (r.y - p.y);
    let (w0, w1, w2) = (cross(b, c, p), cross(c, a, p), cross(a, b, p));
    let total = w0 + w1 + w2;
    if total == 0.0 {
        return 0;
    }
    let same = (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0) || (w0 <= 0.0 && w1 <= 0.0 && w2 <= 0.0);
    if !same {
        return 0;
    }
    let x = (w0 * a.x + w1 * b.x + w2 * c.x) / total;
    if x > p.x {
        if (b - a).cross(c - a).x > 0.0 {
            1
        } else {
            -1
        }
    } else {
        0
    }
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

    #[test]
    fn windings_of_many_points_are_the_windings_of_each() {
        let mesh = Mesh::uv_sphere(DVec3::new(0.1, 0.2, -0.1), 0.8, 9, 13);
        let points: Vec<DVec3> = (0..400)
            .map(|k| {
                let k = k as f64;
                DVec3::new(
                    (1.3 * k).sin(),
                    (0.7 * k + 1.0).cos(),
                    (2.9 * k).sin() * 0.9,
                )
            })
            .collect();
        let each: Vec<i32> = points.iter().map(|&p| winding(&mesh, p)).collect();
        assert!(each.contains(&1) && each.contains(&0));
        assert_eq!(windings(&mesh, &points), each);
        assert_eq!(windings(&mesh, &points[..3]), each[..3]);
        assert!(windings(&mesh, &[]).is_empty());
    }
}

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
    cut_and_link(
        mesh.triangles.iter(),
        |v| side[v as usize] >= 0.0,
        |a, b| crossing(mesh, side[a as usize], side[b as usize], a, b),
    )
}

/// The point where edge `a`→`b` crosses the plane, from the sides `da` (below) and `db`.
fn crossing(mesh: &Mesh, da: f64, db: f64, a: u32, b: u32) -> DVec3 {
    let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
    let t = if db - da > 0.0 { -da / (db - da) } else { 0.0 };
    pa.lerp(pb, t.clamp(0.0, 1.0))
}

/// [`slice_plane`] and [`slice_plane_outer`] for many parallel planes through one mesh (the
/// refinement's transverse slices: down the head, up the legs to the crotch): the triangles
/// bucketed by their extent along the normal, so that each slice cuts only the triangles of
/// the bucket at its level instead of every triangle. The loops are exactly
/// [`slice_plane`]'s: the same triangles are cut, in mesh order, with the same points.
#[derive(Debug, Clone)]
pub struct PlaneSlicer<'a> {
    mesh: &'a Mesh,
    /// The given normal (not normalised; [`slice_plane`] normalises it); `None` when zero or
    /// not finite.
    normal: DVec3,
    /// The buckets; `None` for a slicer of one slice ([`PlaneSlicer::once`]).
    buckets: Option<Buckets>,
}

/// Triangles bucketed by their extent along a unit normal.
#[derive(Debug, Clone)]
struct Buckets {
    /// The unit normal.
    unit: DVec3,
    /// Lowest projection of a vertex and the bucket width along `unit`.
    low: f64,
    width: f64,
    count: usize,
    /// `start[b]..start[b + 1]`: the range of `triangles` overlapping bucket `b`, ascending.
    start: Vec<u32>,
    triangles: Vec<u32>,
    /// Triangles with a non-finite projection, ascending: cut by every slice.
    unbounded: Vec<u32>,
    /// The largest coordinate magnitude of a vertex (for the rounding margin).
    scale: f64,
}

/// About this many buckets per triangle (a transverse slice of a figure cuts a small share).
const TRIANGLES_PER_BUCKET: usize = 16;

impl<'a> PlaneSlicer<'a> {
    /// A slicer of `mesh` by planes with `normal` (any length, non-zero), indexed for many
    /// slices.
    pub fn new(mesh: &'a Mesh, normal: DVec3) -> Self {
        let buckets = normal.try_normalize().map(|unit| Buckets::new(mesh, unit));
        PlaneSlicer {
            mesh,
            normal,
            buckets,
        }
    }

    /// A slicer for one or two slices: no index, [`slice_plane`] itself.
    pub fn once(mesh: &'a Mesh, normal: DVec3) -> Self {
        PlaneSlicer {
            mesh,
            normal,
            buckets: None,
        }
    }

    /// [`slice_plane`] of the slicer's mesh through `point`.
    pub fn slice(&self, point: DVec3) -> Vec<SliceLoop> {
        let Some(b) = &self.buckets else {
            return slice_plane(self.mesh, point, self.normal);
        };
        let mesh = self.mesh;
        let n = b.unit;
        let side = |v: u32| (mesh.positions[v as usize] - point).dot(n);
        // A triangle whose projections all lie beyond the margin of the plane's level has
        // every corner's side (rounded as slice_plane rounds it) on one side: not cut.
        let level = point.dot(n);
        let margin = 1e-9 * (b.scale + point.abs().max_element());
        if !level.is_finite() || !margin.is_finite() {
            return slice_plane(mesh, point, self.normal);
        }
        let candidates = b.around(level - margin, level + margin);
        cut_and_link(
            candidates.iter().map(|&t| &mesh.triangles[t as usize]),
            |v| side(v) >= 0.0,
            |a, b| crossing(mesh, side(a), side(b), a, b),
        )
    }

    /// [`slice_plane_outer`] of the slicer's mesh through `point`.
    pub fn slice_outer(&self, point: DVec3) -> Vec<SliceLoop> {
        outer(self.slice(point), point, self.normal)
    }
}

impl Buckets {
    fn new(mesh: &Mesh, unit: DVec3) -> Self {
        let projection: Vec<f64> = mesh.positions.iter().map(|p| p.dot(unit)).collect();
        let (low, high) = projection
            .iter()
            .filter(|h| h.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &h| {
                (lo.min(h), hi.max(h))
            });
        let scale = mesh
            .positions
            .iter()
            .map(|p| p.abs().max_element())
            .filter(|m| m.is_finite())
            .fold(0.0, f64::max);
        let count = (mesh.triangles.len() / TRIANGLES_PER_BUCKET).clamp(1, 1 << 16);
        let width = ((high - low) / count as f64).max(f64::MIN_POSITIVE);
        let mut buckets = Buckets {
            unit,
            low: if low.is_finite() { low } else { 0.0 },
            width: if width.is_finite() { width } else { 1.0 },
            count,
            start: vec![0; count + 1],
            triangles: Vec::new(),
            unbounded: Vec::new(),
            scale,
        };
        // Bucket of every vertex (`u32::MAX`: not finite); a triangle spans the buckets from
        // its corners' lowest to their highest (the bucket grows with the projection).
        let vertex_bucket: Vec<u32> = projection
            .iter()
            .map(|&h| {
                if h.is_finite() {
                    buckets.bucket(h) as u32
                } else {
                    u32::MAX
                }
            })
            .collect();
        let span = |tri: &[u32; 3]| {
            let b = tri.map(|v| vertex_bucket[v as usize]);
            let (lo, hi) = (b[0].min(b[1]).min(b[2]), b[0].max(b[1]).max(b[2]));
            (hi != u32::MAX).then_some((lo as usize, hi as usize))
        };
        // Counting sort of (bucket, triangle) pairs: each bucket's triangles ascending.
        let mut start = vec![0u32; count + 1];
        for tri in &mesh.triangles {
            if let Some((a, b)) = span(tri) {
                for k in a..=b {
                    start[k + 1] += 1;
                }
            }
        }
        for k in 0..count {
            start[k + 1] += start[k];
        }
        let mut next = start.clone();
        let mut triangles = vec![0u32; start[count] as usize];
        let mut unbounded = Vec::new();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            match span(tri) {
                Some((a, b)) => {
                    for k in a..=b {
                        triangles[next[k] as usize] = t as u32;
                        next[k] += 1;
                    }
                }
                None => unbounded.push(t as u32),
            }
        }
        buckets.start = start;
        buckets.triangles = triangles;
        buckets.unbounded = unbounded;
        buckets
    }

    /// The bucket of projection `h` (clamped to the buckets).
    fn bucket(&self, h: f64) -> usize {
        let k = (h - self.low) / self.width;
        if k > 0.0 {
            (k as usize).min(self.count - 1)
        } else {
            0
        }
    }

    /// The triangles whose extent may overlap `[lo, hi]`, ascending, each once.
    fn around(&self, lo: f64, hi: f64) -> Vec<u32> {
        let (a, b) = (self.bucket(lo), self.bucket(hi));
        let mut out: Vec<u32> = self.unbounded.clone();
        out.extend_from_slice(&self.triangles[self.start[a] as usize..self.start[b + 1] as usize]);
        if a != b || !self.unbounded.is_empty() {
            out.sort_unstable();
            out.dedup();
        }
        out
    }
}

/// [`slice_plane`] without the closed loops that lie inside another closed loop of the same
/// slice: the outline of the figure's envelope. A body under its clothes, the inner wall of a
/// hollow head or a cavity reached through the mouth gives loops inside the outer one; a part
/// that stands apart (an arm beside the torso) keeps its own loop. Open pieces are kept.
pub fn slice_plane_outer(mesh: &Mesh, point: DVec3, normal: DVec3) -> Vec<SliceLoop> {
    outer(slice_plane(mesh, point, normal), point, normal)
}

/// The `loops` of the slice through `point` with `normal` less the closed ones inside another
/// closed one (see [`slice_plane_outer`]).
fn outer(loops: Vec<SliceLoop>, point: DVec3, normal: DVec3) -> Vec<SliceLoop> {
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
pub(crate) fn contains(polygon: &[(f64, f64)], (x, y): (f64, f64)) -> bool {
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
    fn the_plane_slicer_cuts_the_loops_of_slice_plane() {
        // A finely cut box and an open sheet beside it, sliced along a tilted normal at levels
        // through vertices, between them, beyond the mesh and at its ends.
        let mut mesh = Mesh::cuboid(DVec3::new(-1.0, -0.3, -0.2), DVec3::new(1.0, 0.3, 0.2))
            .subdivided()
            .subdivided()
            .subdivided();
        let base = mesh.positions.len() as u32;
        mesh.positions.extend([
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
        ]);
        mesh.triangles.push([base, base + 1, base + 2]);
        for normal in [DVec3::Y, DVec3::new(0.3, 1.0, -0.2), DVec3::X * 2.0] {
            let slicer = PlaneSlicer::new(&mesh, normal);
            let mut points: Vec<DVec3> = mesh.positions.iter().step_by(7).copied().collect();
            points.extend((0..40).map(|i| DVec3::splat(-4.0 + 0.2 * f64::from(i))));
            for point in points {
                assert_eq!(
                    slicer.slice(point),
                    slice_plane(&mesh, point, normal),
                    "{point}"
                );
                assert_eq!(
                    slicer.slice_outer(point),
                    slice_plane_outer(&mesh, point, normal)
                );
                let once = PlaneSlicer::once(&mesh, normal);
                assert_eq!(once.slice(point), slice_plane(&mesh, point, normal));
            }
        }
        assert!(PlaneSlicer::new(&mesh, DVec3::ZERO)
            .slice(DVec3::ZERO)
            .is_empty());
    }

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

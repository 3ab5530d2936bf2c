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
        .map(|p| inside_by(*p, centre, radius))
        .collect();
    cut_and_link(
        mesh.triangles.iter(),
        |v| side[v as usize] >= 0.0,
        |a, b| crossing(mesh, centre, radius, a, b),
    )
}

/// How far `p` lies outside the sphere (negative inside): the side [`slice_sphere`] cuts by.
#[inline]
fn inside_by(p: DVec3, centre: DVec3, radius: f64) -> f64 {
    p.distance(centre) - radius
}

/// The point where edge `a`→`b` crosses the sphere: `a` inside, `b` outside (or on the
/// sphere), the root of |a + t (b − a) − c| = r in [0, 1].
fn crossing(mesh: &Mesh, centre: DVec3, radius: f64, a: u32, b: u32) -> DVec3 {
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
}

/// [`slice_sphere`] for many spheres through one mesh (the limb marches of the refinement cut
/// dozens): the vertices bucketed in a uniform grid and the triangles of each vertex listed
/// once, so that each slice looks only at the triangles around the vertices inside its sphere
/// (a triangle crossing the sphere has a corner inside it) instead of at every triangle. The
/// loops are exactly [`slice_sphere`]'s: the same triangles are cut, in mesh order, with the
/// same points.
#[derive(Debug, Clone)]
pub struct SphereSlicer<'a> {
    mesh: &'a Mesh,
    /// Lower corner of the grid, mesh units.
    origin: DVec3,
    /// Edge length of a cell, mesh units.
    cell: f64,
    /// Cells along x, y and z.
    dims: [usize; 3],
    /// `cell_start[c]..cell_start[c + 1]`: the range of `cell_vertices` in cell `c`.
    cell_start: Vec<u32>,
    cell_vertices: Vec<u32>,
    /// `vertex_start[v]..vertex_start[v + 1]`: the range of `vertex_triangles` using `v`.
    vertex_start: Vec<u32>,
    vertex_triangles: Vec<u32>,
    /// Vertices with a non-finite coordinate (in no cell's reach; looked at by every slice).
    unbounded: Vec<u32>,
}

/// About this many vertices per grid cell.
const VERTICES_PER_CELL: f64 = 4.0;

impl<'a> SphereSlicer<'a> {
    /// The grid and vertex-triangle lists of `mesh`.
    pub fn new(mesh: &'a Mesh) -> Self {
        let n = mesh.positions.len();
        let (min, max) = mesh
            .positions
            .iter()
            .filter(|p| p.is_finite())
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let extent = (max - min).max(DVec3::ZERO);
        let volume = extent.x.max(1e-300) * extent.y.max(1e-300) * extent.z.max(1e-300);
        let mut cell = (volume * VERTICES_PER_CELL / n.max(1) as f64).cbrt();
        // At most ~n cells along the longest side and some cells in all.
        cell = cell
            .max(extent.max_element() / (n.max(1) as f64))
            .max(1e-300);
        let finite = cell.is_finite() && min.is_finite();
        let dims = if finite {
            [extent.x, extent.y, extent.z].map(|e| ((e / cell).floor() as usize).saturating_add(1))
        } else {
            [1, 1, 1]
        };
        let cells = dims[0].saturating_mul(dims[1]).saturating_mul(dims[2]);
        let (origin, cell, dims) = if finite && cells <= 8 * n.max(1) {
            (min, cell, dims)
        } else {
            (DVec3::ZERO, f64::INFINITY, [1, 1, 1])
        };
        let mut slicer = SphereSlicer {
            mesh,
            origin,
            cell,
            dims,
            cell_start: Vec::new(),
            cell_vertices: Vec::new(),
            vertex_start: Vec::new(),
            vertex_triangles: Vec::new(),
            unbounded: (0..n as u32)
                .filter(|&v| !mesh.positions[v as usize].is_finite())
                .collect(),
        };
        let cell_of: Vec<usize> = mesh
            .positions
            .iter()
            .map(|&p| slicer.cell_index(slicer.coords(p)))
            .collect();
        (slicer.cell_start, slicer.cell_vertices) = buckets(
            dims[0] * dims[1] * dims[2],
            (0..n as u32).map(|v| (cell_of[v as usize], v)),
        );
        (slicer.vertex_start, slicer.vertex_triangles) = buckets(
            n,
            mesh.triangles
                .iter()
                .enumerate()
                .flat_map(|(t, tri)| tri.map(|v| (v as usize, t as u32))),
        );
        slicer
    }

    /// Cell coordinates of `p`, clamped to the grid (non-finite coordinates go to 0).
    fn coords(&self, p: DVec3) -> [usize; 3] {
        let c = (p - self.origin) / self.cell;
        let axis = |x: f64, d: usize| if x > 0.0 { (x as usize).min(d - 1) } else { 0 };
        [
            axis(c.x, self.dims[0]),
            axis(c.y, self.dims[1]),
            axis(c.z, self.dims[2]),
        ]
    }

    fn cell_index(&self, [x, y, z]: [usize; 3]) -> usize {
        (z * self.dims[1] + y) * self.dims[0] + x
    }

    /// [`slice_sphere`] of the slicer's mesh with the sphere of `radius` around `centre`.
    pub fn slice(&self, centre: DVec3, radius: f64) -> Vec<SliceLoop> {
        if !(radius > 0.0 && radius.is_finite()) {
            return Vec::new();
        }
        let mesh = self.mesh;
        // Inside: not on or outside the sphere (a NaN side counts inside, as in slice_sphere).
        let inside = |v: u32| {
            let side = inside_by(mesh.positions[v as usize], centre, radius);
            side < 0.0 || side.is_nan()
        };
        let mut triangles: Vec<u32> = Vec::new();
        let mut gather = |v: u32| {
            if inside(v) {
                let (s, e) = (
                    self.vertex_start[v as usize] as usize,
                    self.vertex_start[v as usize + 1] as usize,
                );
                triangles.extend_from_slice(&self.vertex_triangles[s..e]);
            }
        };
        for &v in &self.unbounded {
            gather(v);
        }
        // A vertex inside lies within the radius on every axis; the margin keeps rounding
        // from dropping one at the bounding box's edge.
        let reach = radius * (1.0 + 1e-6) + 1e-12 * centre.abs().max_element();
        let (lo, hi) = (self.coords(centre - reach), self.coords(centre + reach));
        for z in lo[2]..=hi[2] {
            for y in lo[1]..=hi[1] {
                // The cells of one row are consecutive, and so are their vertices.
                let row = self.cell_index([0, y, z]);
                let from = self.cell_start[row + lo[0]] as usize;
                let to = self.cell_start[row + hi[0] + 1] as usize;
                for &v in &self.cell_vertices[from..to] {
                    gather(v);
                }
            }
        }
        triangles.sort_unstable();
        triangles.dedup();
        cut_and_link(
            triangles.iter().map(|&t| &mesh.triangles[t as usize]),
            |v| !inside(v),
            |a, b| crossing(mesh, centre, radius, a, b),
        )
    }
}

/// `(bucket, item)` pairs grouped by bucket (a counting sort, items of a bucket in their
/// order): the start of each of the `count` buckets (plus the end) and the items.
fn buckets(
    count: usize,
    pairs: impl Iterator<Item = (usize, u32)> + Clone,
) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; count + 1];
    for (b, _) in pairs.clone() {
        start[b + 1] += 1;
    }
    for b in 0..count {
        start[b + 1] += start[b];
    }
    let mut next = start.clone();
    let mut items = vec![0u32; start[count] as usize];
    for (b, item) in pairs {
        items[next[b] as usize] = item;
        next[b] += 1;
    }
    (start, items)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_slicer_cuts_the_loops_of_slice_sphere() {
        // A finely cut box, and an arm-like tube of it: spheres of several sizes anywhere,
        // including ones that miss it, hold it whole, or pass through vertices.
        let mesh = Mesh::cuboid(DVec3::new(-1.0, -0.3, -0.2), DVec3::new(1.0, 0.3, 0.2))
            .subdivided()
            .subdivided()
            .subdivided()
            .subdivided();
        let slicer = SphereSlicer::new(&mesh);
        let mut x = 11u64;
        let mut next = || {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..200 {
            let centre = DVec3::new(2.4 * next() - 1.2, 0.8 * next() - 0.4, 0.6 * next() - 0.3);
            let radius = 0.8 * next();
            assert_eq!(
                slicer.slice(centre, radius),
                slice_sphere(&mesh, centre, radius)
            );
        }
        let corner = mesh.positions[0];
        assert_eq!(slicer.slice(corner, 0.3), slice_sphere(&mesh, corner, 0.3));
        assert_eq!(
            slicer.slice(DVec3::ZERO, 5.0),
            slice_sphere(&mesh, DVec3::ZERO, 5.0)
        );
        assert!(slicer.slice(DVec3::ZERO, 0.0).is_empty());
        assert!(slicer.slice(DVec3::ZERO, f64::NAN).is_empty());
    }
}

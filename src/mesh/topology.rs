//! Edge and vertex connectivity of a triangle mesh: shared edges, components, degeneracy.

use super::Mesh;

/// A triangle counts as degenerate when its area is at most this fraction of the squared
/// bounding-box diagonal (or it repeats a vertex index). `1e-14` sits a few orders of magnitude
/// above f64 rounding of the cross product, so only truly flat (collinear) triangles qualify.
pub const DEGENERATE_AREA_FRACTION: f64 = 1e-14;

/// One use of an undirected edge by a triangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct HalfEdge {
    /// Lower vertex index of the edge.
    pub low: u32,
    /// Higher vertex index of the edge.
    pub high: u32,
    /// The triangle using the edge.
    pub triangle: u32,
    /// Whether the triangle runs along the edge from `low` to `high`.
    pub forward: bool,
}

impl Mesh {
    /// Every triangle edge (skipping edges between equal indices), sorted so that the uses of
    /// one undirected edge are adjacent, in triangle order.
    ///
    /// A counting sort on the lower vertex (linear in the edges), then a sort of each vertex's
    /// few edges: the same order as sorting them all, several times faster on large meshes.
    pub(super) fn half_edges(&self) -> Vec<HalfEdge> {
        let each = || {
            self.triangles.iter().enumerate().flat_map(|(t, tri)| {
                (0..3).filter_map(move |k| {
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    (a != b).then(|| HalfEdge {
                        low: a.min(b),
                        high: a.max(b),
                        triangle: t as u32,
                        forward: a < b,
                    })
                })
            })
        };
        // start[v]..start[v + 1]: the edges whose lower vertex is v.
        let vertices = self.positions.len().max(
            self.triangles
                .iter()
                .flatten()
                .map(|&v| v as usize + 1)
                .max()
                .unwrap_or(0),
        );
        let mut start = vec![0usize; vertices + 1];
        let mut count = 0;
        for e in each() {
            start[e.low as usize + 1] += 1;
            count += 1;
        }
        for v in 0..vertices {
            start[v + 1] += start[v];
        }
        let mut next = start.clone();
        let mut edges = vec![
            HalfEdge {
                low: 0,
                high: 0,
                triangle: 0,
                forward: false,
            };
            count
        ];
        for e in each() {
            let slot = &mut next[e.low as usize];
            edges[*slot] = e;
            *slot += 1;
        }
        for v in 0..vertices {
            edges[start[v]..start[v + 1]].sort_unstable();
        }
        edges
    }

    /// Groups of [`HalfEdge`]s that share one undirected edge.
    pub(super) fn edge_groups(edges: &[HalfEdge]) -> impl Iterator<Item = &[HalfEdge]> {
        edges.chunk_by(|a, b| (a.low, a.high) == (b.low, b.high))
    }

    /// Per triangle, whether it is degenerate: a repeated index or an area of at most
    /// [`DEGENERATE_AREA_FRACTION`] × (bounding-box diagonal)².
    pub fn degenerate_triangles(&self) -> Vec<bool> {
        let diagonal_sq = self
            .bounding_box()
            .map_or(0.0, |(min, max)| (max - min).length_squared());
        let limit = DEGENERATE_AREA_FRACTION * diagonal_sq;
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.triangles[t];
                if a == b || b == c || a == c {
                    return true;
                }
                let [pa, pb, pc] = self.corners(t);
                (pb - pa).cross(pc - pa).length() * 0.5 <= limit
            })
            .collect()
    }

    /// The connected component of every triangle (triangles are connected when they share a
    /// vertex), numbered from 0 in order of first triangle, and the number of components.
    pub fn triangle_components(&self) -> (Vec<u32>, usize) {
        let mut sets = DisjointSets::new(self.positions.len());
        for &[a, b, c] in &self.triangles {
            sets.union(a, b);
            sets.union(b, c);
        }
        sets.numbered_at(self.triangles.iter().map(|tri| tri[0]))
    }

    /// Whether the mesh is one closed shell: triangles, every edge shared by exactly two of
    /// them, all joined across edges ([`Mesh::stats`]' `closed` with one manifold component),
    /// from one pass over the edges.
    pub fn is_one_closed_shell(&self) -> bool {
        if self.triangles.is_empty() {
            return false;
        }
        let mut sets = DisjointSets::new(self.triangles.len());
        let edges = self.half_edges();
        for group in Mesh::edge_groups(&edges) {
            let [a, b] = group else {
                return false;
            };
            sets.union(a.triangle, b.triangle);
        }
        let root = sets.find(0);
        (1..self.triangles.len() as u32).all(|t| sets.find(t) == root)
    }

    /// Like [`Mesh::triangle_components`], but triangles are connected only across manifold
    /// edges (edges used by exactly two triangles), so pieces that merely touch at a vertex or
    /// meet at a non-manifold edge count separately. This is trimesh's notion of a body
    /// (`split`, face adjacency), which refdata's README reports as "parts".
    pub fn manifold_components(&self) -> (Vec<u32>, usize) {
        let mut sets = DisjointSets::new(self.triangles.len());
        let edges = self.half_edges();
        for group in Mesh::edge_groups(&edges) {
            if let [a, b] = group {
                sets.union(a.triangle, b.triangle);
            }
        }
        sets.numbered()
    }
}

/// Union-find over `0..n` with path halving and union by lower index (deterministic roots).
pub(crate) struct DisjointSets {
    parent: Vec<u32>,
}

/// The piece (connected component over shared corners of `triangles`) of each of the `n`
/// mesh corners, numbered from 0 in corner order. Corners of no triangle are pieces of their
/// own.
pub(crate) fn vertex_pieces(n: usize, triangles: &[[u32; 3]]) -> Vec<u32> {
    let mut sets = DisjointSets::new(n);
    for &[a, b, c] in triangles {
        sets.union(a, b);
        sets.union(a, c);
    }
    sets.numbered().0
}

impl DisjointSets {
    /// `n` singleton sets.
    pub fn new(n: usize) -> Self {
        Self {
            parent: (0..n as u32).collect(),
        }
    }

    /// The root of `i`'s set.
    pub fn find(&mut self, mut i: u32) -> u32 {
        while self.parent[i as usize] != i {
            let grandparent = self.parent[self.parent[i as usize] as usize];
            self.parent[i as usize] = grandparent;
            i = grandparent;
        }
        i
    }

    /// Merges the sets of `a` and `b`.
    pub fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        let (low, high) = (ra.min(rb), ra.max(rb));
        self.parent[high as usize] = low;
    }

    /// Each element's set numbered from 0 in the order of the sets' first elements, and the
    /// number of sets.
    pub fn numbered(&mut self) -> (Vec<u32>, usize) {
        self.numbered_at(0..self.parent.len() as u32)
    }

    /// The set of each of `elements`, numbered from 0 in the order the sets are first met
    /// among them, and the number of sets met.
    pub fn numbered_at(&mut self, elements: impl Iterator<Item = u32>) -> (Vec<u32>, usize) {
        let mut number = vec![u32::MAX; self.parent.len()];
        let mut next = 0u32;
        let numbers = elements
            .map(|i| {
                let root = self.find(i) as usize;
                if number[root] == u32::MAX {
                    number[root] = next;
                    next += 1;
                }
                number[root]
            })
            .collect();
        (numbers, next as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn half_edges_come_in_the_order_of_a_full_sort() {
        // A scrambled soup: repeated, reversed and degenerate triangles, vertices in any order.
        let positions = vec![DVec3::ZERO; 9];
        let mut triangles = Vec::new();
        let mut x = 7u32;
        for _ in 0..60 {
            let mut tri = [0u32; 3];
            for v in &mut tri {
                x = x.wrapping_mul(1_103_515_245).wrapping_add(12_345);
                *v = (x >> 16) % 9;
            }
            triangles.push(tri);
        }
        let mesh = Mesh {
            positions,
            triangles,
        };
        let mut sorted: Vec<HalfEdge> = Vec::new();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if a != b {
                    sorted.push(HalfEdge {
                        low: a.min(b),
                        high: a.max(b),
                        triangle: t as u32,
                        forward: a < b,
                    });
                }
            }
        }
        sorted.sort();
        assert_eq!(mesh.half_edges(), sorted);
    }

    #[test]
    fn cube_edges_are_each_used_twice_in_opposite_directions() {
        let cube = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        let edges = cube.half_edges();
        let groups: Vec<_> = Mesh::edge_groups(&edges).collect();
        assert_eq!(groups.len(), 18);
        for g in groups {
            assert_eq!(g.len(), 2);
            assert_ne!(g[0].forward, g[1].forward);
        }
    }

    #[test]
    fn one_closed_shell_is_what_the_stats_say() {
        let cube = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        let mut b = Mesh::cuboid(DVec3::splat(2.0), DVec3::splat(3.0));
        b.triangles.iter_mut().flatten().for_each(|i| *i += 8);
        let two = Mesh {
            positions: [cube.positions.clone(), b.positions].concat(),
            triangles: [cube.triangles.clone(), b.triangles].concat(),
        };
        let mut open = cube.clone();
        open.triangles.pop();
        let empty = Mesh {
            positions: Vec::new(),
            triangles: Vec::new(),
        };
        let sphere = Mesh::uv_sphere(DVec3::ZERO, 1.0, 6, 8);
        for (mesh, one) in [
            (&cube, true),
            (&two, false),
            (&open, false),
            (&empty, false),
            (&sphere, true),
        ] {
            let stats = mesh.stats();
            assert_eq!(mesh.is_one_closed_shell(), one);
            assert_eq!(one, stats.closed && stats.manifold_components == 1);
        }
    }

    #[test]
    fn two_cubes_are_two_components() {
        let a = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        let mut b = Mesh::cuboid(DVec3::splat(2.0), DVec3::splat(3.0));
        b.triangles.iter_mut().flatten().for_each(|i| *i += 8);
        let mesh = Mesh {
            positions: [a.positions, b.positions].concat(),
            triangles: [a.triangles, b.triangles].concat(),
        };
        let (labels, count) = mesh.triangle_components();
        assert_eq!(count, 2);
        assert!(labels[..12].iter().all(|&l| l == 0));
        assert!(labels[12..].iter().all(|&l| l == 1));
    }

    #[test]
    fn cubes_sharing_an_edge_are_one_component_but_two_manifold_components() {
        let a = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        let b = Mesh::cuboid(DVec3::ONE, DVec3::splat(2.0));
        // Shift b so that its corner edge (x from 1 to 2) lies on a's edge y = z = 1.
        let b = b.transformed(|p| p - DVec3::X);
        let mesh = Mesh {
            positions: [a.positions, b.positions].concat(),
            triangles: [
                a.triangles,
                b.triangles.iter().map(|t| t.map(|i| i + 8)).collect(),
            ]
            .concat(),
        }
        .welded(0.0);
        assert_eq!(mesh.triangle_components().1, 1);
        assert_eq!(mesh.manifold_components().1, 2);
        assert_eq!(mesh.stats().non_manifold_edges, 1);
    }

    #[test]
    fn collinear_triangle_is_degenerate() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0, DVec3::Y];
        let mesh = Mesh::new(p, vec![[0, 1, 2], [0, 1, 3], [0, 0, 3]]).unwrap();
        assert_eq!(mesh.degenerate_triangles(), vec![true, false, true]);
    }
}

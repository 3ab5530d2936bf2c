//! The level graph: strata of the DMS by heart value, one vertex per connected piece of a
//! stratum, built bottom-up into a tree rooted at the heart (dissertation ch.7.3.1-7.3.2).

use super::{Frame, LevelOptions};
use crate::medial::MedialSurface;
use crate::paths::{heart, DmsGraph, PathOptions};
use crate::voxel::Solid;
use glam::DVec3;
use serde::Serialize;

/// Marks "no level-graph vertex" in [`LevelGraph::vertex_of`].
pub const NO_VERTEX: u32 = u32::MAX;

/// What the marking tests found for a vertex (ch.7.3.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Marks {
    /// A DMS voxel of the vertex lies in the top `extreme_fraction` of the figure along up.
    pub up: bool,
    /// ... in the bottom `extreme_fraction` along up.
    pub down: bool,
    /// ... in the front `extreme_fraction` along forward.
    pub forward: bool,
    /// ... in the back `extreme_fraction` along forward.
    pub backward: bool,
    /// The cross-section is linear (farthest point beyond `linear_ratio` inscribed radii)
    /// rather than rounded.
    pub linear: bool,
}

/// One vertex of the level graph: a connected piece of one heart-value stratum.
#[derive(Debug, Clone, Serialize)]
pub struct LevelVertex {
    /// Heart-value bin (0 holds the heart).
    pub bin: usize,
    /// DMS positions (indices into [`MedialSurface::voxels`]) of the piece, ascending.
    pub voxels: Vec<usize>,
    /// Centroid of the piece's voxel centres, mesh units and frame.
    pub centroid: DVec3,
    /// The vertex nearer the heart this piece joins (`None` for the root).
    pub parent: Option<usize>,
    /// Vertices distal to this one that it joined, ascending.
    pub children: Vec<usize>,
    /// DMS voxels of this vertex and of every vertex distal to it.
    pub distal_voxels: usize,
    /// `distal_voxels` over all DMS voxels of the graph (ch.7.3.2).
    pub weight: f64,
    /// Weight below [`LevelOptions::insignificant_fraction`].
    pub insignificant: bool,
    /// Merges at least two regions of weight at least [`LevelOptions::junction_fraction`].
    pub major_junction: bool,
    /// Direction and cross-section marks.
    pub marks: Marks,
    /// Inscribed radius (mesh units) of the DMS voxel of the piece nearest its centroid.
    pub radius: f64,
    /// Reach of the vertex's region of the figure (its DMS voxels and, when a solid is given,
    /// the interior voxels nearest to them), mesh units.
    pub reach: Reach,
}

/// How far a region reaches along up and forward: its highest and lowest projection on up and
/// its foremost and hindmost projection on forward, mesh units. Serialized as the array
/// `[highest, lowest, foremost, hindmost]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(into = "[f64; 4]")]
pub struct Reach {
    /// Highest projection on up.
    pub highest: f64,
    /// Lowest projection on up.
    pub lowest: f64,
    /// Highest projection on forward.
    pub foremost: f64,
    /// Lowest projection on forward.
    pub hindmost: f64,
}

impl Reach {
    /// The reach of an empty region: every bound at its identity (`-inf` for a maximum, `inf`
    /// for a minimum).
    pub const EMPTY: Reach = Reach {
        highest: f64::NEG_INFINITY,
        lowest: f64::INFINITY,
        foremost: f64::NEG_INFINITY,
        hindmost: f64::INFINITY,
    };

    /// The reach of both regions.
    pub fn union(self, other: Reach) -> Reach {
        Reach {
            highest: self.highest.max(other.highest),
            lowest: self.lowest.min(other.lowest),
            foremost: self.foremost.max(other.foremost),
            hindmost: self.hindmost.min(other.hindmost),
        }
    }

    /// This reach grown to a point whose projections on up and forward are `up` and
    /// `forward`.
    fn with(self, up: f64, forward: f64) -> Reach {
        Reach {
            highest: self.highest.max(up),
            lowest: self.lowest.min(up),
            foremost: self.foremost.max(forward),
            hindmost: self.hindmost.min(forward),
        }
    }
}

impl From<Reach> for [f64; 4] {
    fn from(r: Reach) -> Self {
        [r.highest, r.lowest, r.foremost, r.hindmost]
    }
}

/// The level graph of a DMS (ch.7.3.1): a tree whose root holds the heart.
#[derive(Debug, Clone, Serialize)]
pub struct LevelGraph {
    /// DMS position of the heart.
    pub heart: usize,
    /// Heart radius, mesh units (path length from the heart to the deepest DMS voxel).
    pub heart_radius: f64,
    /// Normalised heart value per DMS position in `[0, 1]`; `NaN` outside the heart's
    /// connected component (those voxels have no vertex).
    pub heart_values: Vec<f64>,
    /// Vertex of each DMS position, [`NO_VERTEX`] outside the heart's component.
    pub vertex_of: Vec<u32>,
    /// The vertices, in order of creation (distal before proximal); the last is the root.
    pub vertices: Vec<LevelVertex>,
    /// The root (the piece holding the heart).
    pub root: usize,
    /// Number of DMS voxels in the graph.
    pub voxels: usize,
}

impl LevelGraph {
    /// Vertices of the subtree rooted at `v` (v first, then depth-first in child order).
    pub fn subtree(&self, v: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut stack = vec![v];
        while let Some(u) = stack.pop() {
            out.push(u);
            stack.extend(self.vertices[u].children.iter().rev());
        }
        out
    }

    /// Vertices from `v` up to the root, `v` first.
    pub fn ancestors(&self, v: usize) -> Vec<usize> {
        let mut out = vec![v];
        let mut at = v;
        while let Some(p) = self.vertices[at].parent {
            out.push(p);
            at = p;
        }
        out
    }

    /// The tree path between `a` and `b` (both included).
    pub fn path(&self, a: usize, b: usize) -> Vec<usize> {
        let up_a = self.ancestors(a);
        let up_b = self.ancestors(b);
        let Some(common) = up_a.iter().copied().find(|v| up_b.contains(v)) else {
            return Vec::new();
        };
        let mut path: Vec<usize> = up_a.iter().copied().take_while(|&v| v != common).collect();
        path.push(common);
        let tail: Vec<usize> = up_b.iter().copied().take_while(|&v| v != common).collect();
        path.extend(tail.into_iter().rev());
        path
    }
}

/// Builds the level graph of `surface` (ch.7.3.1) and marks its vertices (ch.7.3.2).
///
/// Phases: the heart and per-voxel depth sums of the largest DMS component
/// ([`heart`](crate::paths::heart), deterministic sources); heart values normalised to
/// `[0, 1]` and binned into `options.bins` equal ranges; bins processed from the highest down,
/// each split into 26-connected pieces (in order of smallest DMS position, the heart's piece
/// last), each piece a vertex whose children are the current top vertices of the
/// union-find groups of already processed voxels it touches; distal fractions; insignificant
/// vertices and major junctions; direction and cross-section marks against `extent_up` and
/// `extent_forward` (the figure's `(min, max)` projections on `frame.up` / `frame.forward`).
///
/// With a `solid`, the direction marks and reaches also count the interior voxels nearest
/// (through the interior) to each vertex's DMS voxels: thin limb ends whose voxels lie one voxel
/// from the outside hold no DMS voxel (ch.4.4), so a leg's DMS can stop short of the ground
/// that its interior reaches.
pub fn level_graph(
    surface: &MedialSurface,
    solid: Option<&Solid>,
    paths: &PathOptions,
    options: &LevelOptions,
    frame: &Frame,
    extent_up: (f64, f64),
    extent_forward: (f64, f64),
) -> LevelGraph {
    LevelTree::new(surface, solid, paths, options).in_frame(
        surface,
        frame,
        extent_up,
        extent_forward,
    )
}

/// The part of [`level_graph`] that does not depend on the body frame, built once and marked
/// under as many frames as the labelling tries (the up direction's candidates, the first and
/// the guessed forward): the heart, the strata and their merge tree, and each vertex's region
/// (its DMS voxel centres and, with a solid, the centres of the interior voxels nearest to
/// them through the interior). Building it is most of the level graph's cost (the heart's
/// Dijkstra and the interior's); marking it under a frame is a pass over its voxels.
#[derive(Debug, Clone)]
pub struct LevelTree {
    /// The graph with every vertex unmarked (weights, marks, radii and reaches are set by
    /// [`LevelTree::in_frame`]).
    graph: LevelGraph,
    /// Per vertex: the centres (mesh units) of its region's voxels.
    regions: Vec<Vec<DVec3>>,
    /// With a solid: per grid voxel, the DMS position whose vertex it joins through the
    /// interior ([`super::project::interior_sources`] seeded by the graph's DMS voxels).
    sources: Option<Vec<u32>>,
    /// The options it was built with; [`LevelTree::in_frame`] marks with them.
    options: LevelOptions,
}

impl LevelTree {
    /// The frame-independent phases of [`level_graph`] over `surface` (and `solid`'s interior).
    pub fn new(
        surface: &MedialSurface,
        solid: Option<&Solid>,
        paths: &PathOptions,
        options: &LevelOptions,
    ) -> Self {
        let graph = DmsGraph::new(surface);
        let n = graph.len();
        let component = graph.largest_component().unwrap_or(0);
        let h = heart(&graph, component, paths);
        let heart_values = normalised(&h.sums);
        let bins = options.bins;
        let bin_of = |p: usize| -> Option<usize> {
            let v = heart_values[p];
            (!v.is_nan()).then(|| ((v * bins as f64) as usize).min(bins - 1))
        };
        let mut by_bin: Vec<Vec<usize>> = vec![Vec::new(); bins];
        for p in 0..n {
            if let Some(b) = bin_of(p) {
                by_bin[b].push(p);
            }
        }
        let mut merging = Merging::new(n);
        let mut piece_of = vec![u32::MAX; n];
        for b in (0..bins).rev() {
            let pieces = bin_pieces(
                &graph,
                &by_bin[b],
                |q| bin_of(q) == Some(b),
                &mut piece_of,
                h.position,
            );
            for piece in pieces {
                merging.add(&graph, surface, piece, b);
            }
        }
        let Merging {
            vertex_of,
            vertices,
            ..
        } = merging;
        let total = vertices
            .iter()
            .map(|v| v.voxels.len())
            .sum::<usize>()
            .max(1);
        let sources = solid.map(|solid| {
            super::project::interior_sources(
                solid,
                surface,
                |p| vertex_of[p] != NO_VERTEX,
                options.radius_weight,
            )
        });
        let regions = regions(&vertices, surface, solid, sources.as_deref(), &vertex_of);
        let voxel = surface.grid.voxel_size;
        let root = vertices.len().saturating_sub(1);
        LevelTree {
            graph: LevelGraph {
                heart: h.position,
                heart_radius: h.radius * voxel,
                heart_values,
                vertex_of,
                vertices,
                root,
                voxels: total,
            },
            regions,
            sources,
            options: *options,
        }
    }

    /// `anatomy::project::interior_parts` of `voxel_parts` (per DMS position) over `solid`
    /// (the tree's), from the tree's interior search when `voxel_parts` seeds the same DMS
    /// voxels as the tree's vertices (a part exactly for the inside DMS voxels that have a
    /// vertex): the search's sources do not depend on the parts. `None` when the seeds differ
    /// or the tree was built without a solid.
    pub fn interior_parts(
        &self,
        surface: &MedialSurface,
        solid: &Solid,
        voxel_parts: &[u32],
    ) -> Option<Vec<u32>> {
        let sources = self.sources.as_ref()?;
        let vertex_of = &self.graph.vertex_of;
        let same_seeds = sources.len() == solid.grid.len()
            && voxel_parts.len() == vertex_of.len()
            && surface.voxels.iter().enumerate().all(|(p, &index)| {
                !solid.inside[index]
                    || (vertex_of[p] != NO_VERTEX) == (voxel_parts[p] != super::NO_PART)
            });
        same_seeds.then(|| super::project::parts_from_sources(sources, voxel_parts))
    }

    /// The level graph marked under `frame` (ch.7.3.2), with the direction marks measured
    /// against `extent_up` and `extent_forward` (the figure's `(min, max)` projections on
    /// `frame.up` / `frame.forward`). `surface` must be the one the tree was built over.
    pub fn in_frame(
        &self,
        surface: &MedialSurface,
        frame: &Frame,
        extent_up: (f64, f64),
        extent_forward: (f64, f64),
    ) -> LevelGraph {
        let mut graph = self.graph.clone();
        let extents = Extents {
            up: extent_up,
            forward: extent_forward,
            fraction: self.options.extreme_fraction,
        };
        let total = graph.voxels;
        mark_vertices(
            &mut graph.vertices,
            surface,
            total,
            frame,
            &extents,
            &self.options,
        );
        add_reaches(&mut graph.vertices, &self.regions, frame, &extents);
        graph
    }
}

/// The merge tree while bins are processed from the highest down: union-find groups of the
/// processed voxels, each group's current top vertex, and the vertices so far.
struct Merging {
    uf: UnionFind,
    /// Per union-find root: the group's current top vertex.
    top: Vec<u32>,
    /// Per DMS position: its vertex ([`NO_VERTEX`] until processed).
    vertex_of: Vec<u32>,
    processed: Vec<bool>,
    vertices: Vec<LevelVertex>,
}

impl Merging {
    fn new(n: usize) -> Self {
        Self {
            uf: UnionFind::new(n),
            top: vec![NO_VERTEX; n],
            vertex_of: vec![NO_VERTEX; n],
            processed: vec![false; n],
            vertices: Vec::new(),
        }
    }

    /// Adds `piece` (of bin `bin`) as a vertex whose children are the current top vertices of
    /// the groups it touches, and merges them into one group topped by it.
    fn add(&mut self, graph: &DmsGraph, surface: &MedialSurface, piece: Vec<usize>, bin: usize) {
        let v = self.vertices.len();
        let mut children = Vec::new();
        for &p in &piece {
            for (q, _) in graph.neighbours(p) {
                if self.processed[q] {
                    let t = self.top[self.uf.find(q)];
                    if t != NO_VERTEX && !children.contains(&(t as usize)) {
                        children.push(t as usize);
                    }
                }
            }
        }
        children.sort_unstable();
        let first = piece[0];
        for &p in &piece {
            self.processed[p] = true;
            self.vertex_of[p] = v as u32;
            self.uf.union(first, p);
        }
        for &c in &children {
            let r = self.uf.find(self.vertices[c].voxels[0]);
            self.uf.union(first, r);
            self.vertices[c].parent = Some(v);
        }
        self.top[self.uf.find(first)] = v as u32;
        let centroid = piece.iter().map(|&p| surface.centre(p)).sum::<DVec3>() / piece.len() as f64;
        let distal_voxels = piece.len()
            + children
                .iter()
                .map(|&c| self.vertices[c].distal_voxels)
                .sum::<usize>();
        self.vertices.push(LevelVertex {
            bin,
            voxels: piece,
            centroid,
            parent: None,
            children,
            distal_voxels,
            weight: 0.0,
            insignificant: false,
            major_junction: false,
            marks: Marks::default(),
            radius: 0.0,
            reach: Reach {
                highest: 0.0,
                lowest: 0.0,
                foremost: 0.0,
                hindmost: 0.0,
            },
        });
    }
}

/// Each vertex's region: the centres of its DMS voxels and, with a `solid`, of the interior
/// voxels nearest to them (through the interior: `sources`, the DMS position each interior
/// voxel joins, [`super::project::interior_sources`]).
fn regions(
    vertices: &[LevelVertex],
    surface: &MedialSurface,
    solid: Option<&Solid>,
    sources: Option<&[u32]>,
    vertex_of: &[u32],
) -> Vec<Vec<DVec3>> {
    let mut regions: Vec<Vec<DVec3>> = vertices
        .iter()
        .map(|v| v.voxels.iter().map(|&p| surface.centre(p)).collect())
        .collect();
    if let (Some(solid), Some(sources)) = (solid, sources) {
        let interior = super::project::parts_from_sources(sources, vertex_of);
        for (index, &v) in interior.iter().enumerate() {
            if v != NO_VERTEX && surface.position(index).is_none() {
                regions[v as usize].push(solid.grid.centre(solid.grid.coords(index)));
            }
        }
    }
    regions
}

/// Each vertex's reach (highest, lowest, foremost, hindmost projection of its region, see
/// [`regions`]) and the direction marks it adds.
fn add_reaches(
    vertices: &mut [LevelVertex],
    regions: &[Vec<DVec3>],
    frame: &Frame,
    extents: &Extents,
) {
    for (v, region) in vertices.iter_mut().zip(regions) {
        let mut reach = Reach::EMPTY;
        for c in region {
            reach = reach.with(c.dot(frame.up), c.dot(frame.forward));
        }
        v.reach = reach;
        extents.mark(&mut v.marks, reach);
    }
}

/// Heart values: the finite depth `sums` scaled to `[0, 1]` (all 0 when they are equal), NaN
/// for the others.
fn normalised(sums: &[f64]) -> Vec<f64> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &s in sums.iter().filter(|s| s.is_finite()) {
        lo = lo.min(s);
        hi = hi.max(s);
    }
    let span = hi - lo;
    sums.iter()
        .map(|&s| {
            if !s.is_finite() {
                f64::NAN
            } else if span > 0.0 {
                (s - lo) / span
            } else {
                0.0
            }
        })
        .collect()
}

/// The 26-connected pieces of one bin's voxels (`members`; `in_bin` says whether a voxel is in
/// the bin), in order of smallest DMS position with the `heart`'s piece last, each sorted.
/// `piece_of` marks the voxels already in a piece.
fn bin_pieces(
    graph: &DmsGraph,
    members: &[usize],
    in_bin: impl Fn(usize) -> bool,
    piece_of: &mut [u32],
    heart: usize,
) -> Vec<Vec<usize>> {
    let mut pieces: Vec<Vec<usize>> = Vec::new();
    for &start in members {
        if piece_of[start] != u32::MAX {
            continue;
        }
        let id = pieces.len() as u32;
        piece_of[start] = id;
        let mut piece = vec![start];
        let mut i = 0;
        while i < piece.len() {
            let p = piece[i];
            i += 1;
            for (q, _) in graph.neighbours(p) {
                if piece_of[q] == u32::MAX && in_bin(q) {
                    piece_of[q] = id;
                    piece.push(q);
                }
            }
        }
        piece.sort_unstable();
        pieces.push(piece);
    }
    if let Some(k) = pieces
        .iter()
        .position(|pc| pc.binary_search(&heart).is_ok())
    {
        let heart_piece = pieces.remove(k);
        pieces.push(heart_piece);
    }
    pieces
}

/// Each vertex's weight (its distal share of the `total` voxels), insignificance, major
/// junction, direction and cross-section marks and radius (ch.7.3.2).
///
/// A major junction merges two regions that each hold [`LevelOptions::junction_fraction`] of
/// the voxels, or that each reach the ground from a vertex above it (not marked down) while
/// being significant: legs are limbs however small beside a long neck and tail (a sauropod's
/// fore legs hold under 2 % of its voxels), while toes and hoof clefts part at the ground.
fn mark_vertices(
    vertices: &mut [LevelVertex],
    surface: &MedialSurface,
    total: usize,
    frame: &Frame,
    extents: &Extents,
    options: &LevelOptions,
) {
    let voxel = surface.grid.voxel_size;
    // Whether each vertex's region (it and every vertex distal to it) reaches the ground;
    // children come before their parents.
    let mut grounded = vec![false; vertices.len()];
    for i in 0..vertices.len() {
        let weight = vertices[i].distal_voxels as f64 / total as f64;
        let v = &mut vertices[i];
        v.weight = weight;
        v.insignificant = weight < options.insignificant_fraction;
        let mut marks = Marks::default();
        let (mut nearest, mut nearest_d) = (v.voxels[0], f64::INFINITY);
        for &p in &v.voxels {
            let c = surface.centre(p);
            let u = c.dot(frame.up);
            let f = c.dot(frame.forward);
            extents.mark(&mut marks, Reach::EMPTY.with(u, f));
            let d = c.distance_squared(v.centroid);
            if d < nearest_d {
                (nearest, nearest_d) = (p, d);
            }
        }
        v.radius = surface.distance(nearest) * voxel;
        // Farthest point from the centroid, then the farthest from that one (ch.7.3.2).
        let far = |from: DVec3| {
            v.voxels
                .iter()
                .map(|&p| surface.centre(p))
                .max_by(|a, b| {
                    a.distance_squared(from)
                        .total_cmp(&b.distance_squared(from))
                })
                .unwrap_or(from)
        };
        let a = far(v.centroid);
        let b = far(a);
        let reach = a.distance(v.centroid).max(b.distance(v.centroid));
        marks.linear = reach > options.linear_ratio * v.radius.max(0.5 * voxel);
        v.marks = marks;
        let children = &vertices[i].children;
        grounded[i] = marks.down || children.iter().any(|&c| grounded[c]);
        let big = children
            .iter()
            .filter(|&&c| {
                let child = &vertices[c];
                child.weight >= options.junction_fraction
                    || (!marks.down && grounded[c] && !child.insignificant)
            })
            .count();
        vertices[i].major_junction = big >= 2;
    }
}

/// The figure's `(min, max)` projections on the up and forward axes and the fraction of
/// them near each end that marks a direction.
struct Extents {
    up: (f64, f64),
    forward: (f64, f64),
    fraction: f64,
}

impl Extents {
    /// Marks up, down, forward and backward where the reach's highest, lowest, foremost and
    /// hindmost projections lie within the fraction of the ends.
    fn mark(&self, marks: &mut Marks, reach: Reach) {
        let ((up_lo, up_hi), (fw_lo, fw_hi), e) = (self.up, self.forward, self.fraction);
        marks.up |= reach.highest >= up_hi - e * (up_hi - up_lo);
        marks.down |= reach.lowest <= up_lo + e * (up_hi - up_lo);
        marks.forward |= reach.foremost >= fw_hi - e * (fw_hi - fw_lo);
        marks.backward |= reach.hindmost <= fw_lo + e * (fw_hi - fw_lo);
    }
}

/// Union-find with path halving and union by index (deterministic).
struct UnionFind {
    parent: Vec<u32>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        Self {
            parent: (0..n as u32).collect(),
        }
    }

    fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] as usize != x {
            let grand = self.parent[self.parent[x] as usize];
            self.parent[x] = grand;
            x = grand as usize;
        }
        x
    }

    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
            self.parent[hi] = lo as u32;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::paths::testing::surface;

    /// A "T": a stem along y and a bar along x, one voxel thick.
    fn t_shape() -> MedialSurface {
        let mut coords: Vec<[usize; 3]> = (1..40).map(|x| [x, 30, 2]).collect();
        coords.extend((1..30).map(|y| [20, y, 2]));
        surface([41, 32, 5], &coords, 4)
    }

    #[test]
    fn level_graph_of_a_t_is_a_tree_rooted_at_the_heart_with_one_major_junction() {
        let s = t_shape();
        let frame = Frame::new(DVec3::Y, DVec3::Z).unwrap();
        let g = level_graph(
            &s,
            None,
            &PathOptions::default(),
            &LevelOptions::default(),
            &frame,
            (0.0, 32.0),
            (0.0, 5.0),
        );
        // A tree: every vertex but the root has a parent created after it.
        assert_eq!(g.vertices[g.root].parent, None);
        for (i, v) in g.vertices.iter().enumerate() {
            if i != g.root {
                assert!(v.parent.is_some_and(|p| p > i), "vertex {i}");
            }
        }
        assert_eq!(g.vertices[g.root].distal_voxels, s.len());
        assert!((g.vertices[g.root].weight - 1.0).abs() < 1e-12);
        assert!(g.vertices[g.root].voxels.contains(&g.heart));
        // The three arms of the T meet at one major junction near the crossing.
        let junctions: Vec<usize> = (0..g.vertices.len())
            .filter(|&v| g.vertices[v].major_junction)
            .collect();
        assert_eq!(junctions.len(), 1, "{junctions:?}");
        let c = g.vertices[junctions[0]].centroid;
        assert!(c.distance(DVec3::new(20.5, 30.5, 2.5)) < 6.0, "{c}");
        // Heart values span [0, 1]; the ends of the bar are in the top bin.
        let max = g.heart_values.iter().copied().fold(0.0, f64::max);
        assert_eq!(max, 1.0);
        // Each vertex's voxels share one bin.
        for v in &g.vertices {
            for &p in &v.voxels {
                let b = ((g.heart_values[p] * 20.0) as usize).min(19);
                assert_eq!(b, v.bin);
            }
        }
    }

    /// A plus-shaped figure of three boxes (trunk, arms, legs), voxelized with its medial
    /// surface.
    fn plus_figure() -> (Solid, MedialSurface) {
        let boxes = [
            Mesh::cuboid(DVec3::new(-0.3, 0.0, -0.2), DVec3::new(0.3, 2.0, 0.2)),
            Mesh::cuboid(DVec3::new(-1.2, 1.4, -0.1), DVec3::new(1.2, 1.6, 0.1)),
            Mesh::cuboid(DVec3::new(-0.6, -1.0, -0.1), DVec3::new(-0.3, 0.4, 0.1)),
        ];
        let mut mesh = Mesh {
            positions: Vec::new(),
            triangles: Vec::new(),
        };
        for b in boxes {
            let base = mesh.positions.len() as u32;
            mesh.positions.extend(b.positions);
            mesh.triangles
                .extend(b.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        let solid = crate::voxel::voxelize_figure(&mesh, &Default::default()).unwrap();
        let surface =
            crate::medial::dms(&crate::distance::edt(&solid), &Default::default()).unwrap();
        (solid, surface)
    }

    #[test]
    fn a_level_tree_marked_in_several_frames_gives_each_its_own_level_graph() {
        let (solid, s) = plus_figure();
        let (paths, options) = (PathOptions::default(), LevelOptions::default());
        let tree = LevelTree::new(&s, Some(&solid), &paths, &options);
        for (up, forward, extent_up, extent_forward) in [
            (DVec3::Y, DVec3::Z, (-1.0, 2.0), (-0.2, 0.2)),
            (DVec3::Z, DVec3::Y, (-0.2, 0.2), (-1.0, 2.0)),
            (DVec3::NEG_X, DVec3::Z, (-1.2, 1.2), (-0.2, 0.2)),
        ] {
            let frame = Frame::new(up, forward).unwrap();
            let marked = tree.in_frame(&s, &frame, extent_up, extent_forward);
            let built = level_graph(
                &s,
                Some(&solid),
                &paths,
                &options,
                &frame,
                extent_up,
                extent_forward,
            );
            assert_eq!(
                serde_json::to_value(&marked).unwrap(),
                serde_json::to_value(&built).unwrap(),
                "up {up}"
            );
        }
    }

    #[test]
    fn interior_parts_from_the_tree_match_a_search_of_their_own_or_are_refused() {
        use crate::anatomy::project::interior_parts;
        let (solid, s) = plus_figure();
        let options = LevelOptions::default();
        let tree = LevelTree::new(&s, Some(&solid), &PathOptions::default(), &options);
        let vertex_of = tree.graph.vertex_of.clone();
        assert!(vertex_of.iter().filter(|&&v| v != NO_VERTEX).count() > 10);
        // Any parts of the same seeds: the tree's sources give the search's answer.
        let parts: Vec<u32> = vertex_of
            .iter()
            .map(|&v| if v == NO_VERTEX { NO_VERTEX } else { v % 3 })
            .collect();
        let own = interior_parts(&solid, &s, &parts, options.radius_weight);
        assert_eq!(tree.interior_parts(&s, &solid, &parts), Some(own));
        // One seed fewer: not the tree's search.
        let mut fewer = parts.clone();
        let p = fewer
            .iter()
            .position(|&v| v != NO_VERTEX)
            .expect("a seeded DMS voxel");
        fewer[p] = NO_VERTEX;
        if solid.inside[s.voxels[p]] {
            assert_eq!(tree.interior_parts(&s, &solid, &fewer), None);
        }
    }
}

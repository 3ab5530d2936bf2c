//! The weights of the mesh's vertices: sampled from the voxel weights, spread to the vertices
//! the field did not reach, and smoothed over the mesh's edges.

use super::diffusion::{Settled, VoxelWeights};
use super::rows::{blend_few, mix, Mixer, Row, NONE};
use crate::mesh::Mesh;
use crate::voxel::Grid;
use glam::DVec3;
use rayon::prelude::*;
use std::collections::VecDeque;

/// The eight voxels whose centres surround `p` (clamped to the grid) and their trilinear
/// factors.
pub(super) fn corners(grid: &Grid, p: DVec3) -> [(usize, f64); 8] {
    let g = grid.to_voxel(p) - DVec3::splat(0.5);
    let mut base = [0usize; 3];
    let mut t = [0f64; 3];
    for a in 0..3 {
        let top = grid.dims[a].saturating_sub(1) as f64;
        let x = if g[a].is_finite() {
            g[a].clamp(0.0, top)
        } else {
            0.0
        };
        let b = x.floor().min((top - 1.0).max(0.0));
        base[a] = b as usize;
        t[a] = (x - b).clamp(0.0, 1.0);
    }
    let mut out = [(0usize, 0f64); 8];
    for (k, slot) in out.iter_mut().enumerate() {
        let mut coords = base;
        let mut factor = 1.0;
        for a in 0..3 {
            let up = (k >> a) & 1 == 1;
            if up && coords[a] + 1 < grid.dims[a] {
                coords[a] += 1;
            }
            factor *= if up { t[a] } else { 1.0 - t[a] };
        }
        *slot = (grid.index(coords), factor);
    }
    out
}

/// The weights of every vertex: the trilinear blend of the weight rows of the eight voxel
/// centres around it (clamped to the grid), pruned to four joints; empty where none of the
/// eight has weights.
pub(super) fn vertex_rows(voxels: &VoxelWeights, grid: &Grid, mesh: &Mesh) -> Vec<Row> {
    mesh.positions
        .par_iter()
        .with_min_len(1024)
        .map_init(Mixer::default, |mixer, &p| {
            let mut around = [(&Row::EMPTY, 0.0); 8];
            let mut used = 0;
            for (index, factor) in corners(grid, p) {
                if factor <= 0.0 {
                    continue;
                }
                let s = voxels.slot[index];
                if s != NONE {
                    around[used] = (&voxels.rows[s as usize], factor);
                    used += 1;
                }
            }
            let Some((&(first, factor), rest)) = around[..used].split_first() else {
                return Row::EMPTY;
            };
            // Most vertices lie where the eight voxels share at most four joints: the plain
            // normalised blend, which is what pruning leaves of it.
            if let Some(row) = blend_few(first, factor, rest.iter().copied()) {
                return row;
            }
            mixer.clear();
            for &(row, factor) in &around[..used] {
                mixer.add_row(row, factor);
            }
            mixer.pruned(0.0)
        })
        .collect()
}

/// The mesh's vertex adjacency: each vertex's neighbours ascending, vertex `v`'s in
/// `adjacent[start[v]..start[v] + len[v]]` (rows with room for every corner's two edges,
/// left uncompacted: the rounds of [`Smoothing`] copy them in their own order anyway).
pub(super) struct Adjacency {
    start: Vec<usize>,
    len: Vec<u32>,
    adjacent: Vec<u32>,
}

impl Adjacency {
    /// The vertices joined to each vertex by a triangle edge (degenerate edges left out).
    pub fn new(mesh: &Mesh) -> Self {
        let n = mesh.positions.len();
        // Every triangle corner names its two other vertices: count, place, then sort and
        // deduplicate each vertex's list.
        let mut start = vec![0usize; n + 1];
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                start[a as usize + 1] += usize::from(a != b) + usize::from(a != c);
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut listed = vec![0u32; start[n]];
        for t in &mesh.triangles {
            for k in 0..3 {
                let a = t[k];
                for b in [t[(k + 1) % 3], t[(k + 2) % 3]] {
                    if a != b {
                        listed[fill[a as usize]] = b;
                        fill[a as usize] += 1;
                    }
                }
            }
        }
        let mut lists: Vec<&mut [u32]> = Vec::with_capacity(n);
        let mut rest = listed.as_mut_slice();
        for v in 0..n {
            let (head, tail) = rest.split_at_mut(start[v + 1] - start[v]);
            lists.push(head);
            rest = tail;
        }
        let len: Vec<u32> = lists
            .into_par_iter()
            .with_min_len(4096)
            .map(|list| {
                list.sort_unstable();
                let mut kept = 0;
                for k in 0..list.len() {
                    if k == 0 || list[k] != list[kept - 1] {
                        list[kept] = list[k];
                        kept += 1;
                    }
                }
                kept as u32
            })
            .collect();
        Self {
            start,
            len,
            adjacent: listed,
        }
    }

    /// The neighbours of every vertex as compressed rows: `(start, adjacent)` with vertex
    /// `v`'s neighbours ascending in `adjacent[start[v]..start[v + 1]]`.
    fn compressed(&self) -> (Vec<usize>, Vec<u32>) {
        let n = self.len.len();
        let mut adjacent = Vec::with_capacity(self.len.iter().map(|&l| l as usize).sum());
        let mut start = Vec::with_capacity(n + 1);
        start.push(0);
        for v in 0..n {
            adjacent.extend_from_slice(self.around(v));
            start.push(adjacent.len());
        }
        (start, adjacent)
    }

    /// The neighbours of vertex `v`, ascending.
    pub fn around(&self, v: usize) -> &[u32] {
        &self.adjacent[self.start[v]..self.start[v] + self.len[v] as usize]
    }
}

/// Gives every vertex with an empty row the row of the nearest vertex with weights along the
/// mesh's edges (breadth-first, in vertex order); vertices of a piece without any weighted
/// vertex stay empty.
pub(super) fn spread_to_unreached(rows: &mut [Row], adjacency: &Adjacency) {
    if rows.iter().all(|r| !r.is_empty()) {
        return;
    }
    let mut queue: VecDeque<u32> = (0..rows.len() as u32)
        .filter(|&v| !rows[v as usize].is_empty())
        .collect();
    while let Some(v) = queue.pop_front() {
        for &u in adjacency.around(v as usize) {
            if rows[u as usize].is_empty() {
                rows[u as usize] = rows[v as usize];
                queue.push_back(u);
            }
        }
    }
}

/// Meshes whose edges are on average (root mean square, each capped at a voxel) at least this
/// fraction of a voxel long get every round of [`Smoothing`]; finer ones proportionally fewer.
const FINE_EDGE: f64 = 0.25;

/// Rounds of Laplacian smoothing of the vertices' rows over the mesh's edges: each vertex's
/// weights move towards its neighbours' by half their mean difference, each edge's share
/// scaled by (voxel size `h` / edge length)² so that meshes coarser than the voxels are barely
/// smoothed, then pruned to four joints ([`Mixer::pruned`]). Removes what is left of the voxel
/// scale in the weight field; separate pieces smooth within themselves.
///
/// A round spreads the weights by about an edge length (at most a voxel), so on a mesh much
/// finer than the voxels (a subdivided million-triangle figure) the rounds reach only a
/// fraction of a voxel while costing most of the stage: where the root mean square of the
/// edge lengths (each capped at `h`) is below [`FINE_EDGE`] `h`, the rounds are scaled down
/// by its square over [`FINE_EDGE`]² (at least one round). Meshes as coarse as the reference
/// characters (MakeHuman's 27k triangles: about 0.6 voxels) keep every round. The price,
/// measured on the MakeHuman body subdivided to 1.7M triangles (6 rounds instead of 32): 2691
/// instead of 2370 of its 2.6M edges past 2× over the humanoid sweep (3103 without
/// smoothing), at a fifth of the smoothing time.
///
/// Everything but the rounds depends on the mesh alone ([`Smoothing::new`]), so it is built
/// beside the weight field; [`Smoothing::smooth`] runs the rounds.
pub(super) struct Smoothing {
    /// The vertices in the order the rounds visit them (by position on large meshes, see
    /// [`NEAR_ORDER_MIN`]) with each vertex's position in it; `None`: vertex order.
    order: Option<(Vec<u32>, Vec<u32>)>,
    /// The neighbours in the rounds' order, compressed rows (vertex numbers in that order).
    start: Vec<usize>,
    adjacent: Vec<u32>,
    /// Each edge's share, what each vertex keeps of its own and its edges' one share where
    /// they all have the same ([`Graph`]).
    shares: Vec<f64>,
    keep: Vec<f64>,
    uniform: Vec<f64>,
    /// The rounds to run ([`rounds_for_fineness`]).
    rounds: usize,
}

impl Smoothing {
    /// The smoothing of `mesh` (adjacency `adjacency`) in `iterations` rounds for voxels of
    /// size `h`, before the rounds.
    pub fn new(mesh: &Mesh, adjacency: &Adjacency, iterations: usize, h: f64) -> Self {
        let by_position = mesh.positions.len() >= NEAR_ORDER_MIN;
        Self::in_order(mesh, adjacency, iterations, h, by_position)
    }

    /// [`Smoothing::new`], the rounds in position order or not (`by_position`).
    fn in_order(
        mesh: &Mesh,
        adjacency: &Adjacency,
        iterations: usize,
        h: f64,
        by_position: bool,
    ) -> Self {
        if iterations == 0 {
            return Self {
                order: None,
                start: Vec::new(),
                adjacent: Vec::new(),
                shares: Vec::new(),
                keep: Vec::new(),
                uniform: Vec::new(),
                rounds: 0,
            };
        }
        if !by_position {
            let (start, adjacent) = adjacency.compressed();
            let graph = Graph::new(&mesh.positions, &start, &adjacent, h);
            let rounds = rounds_for_fineness(&graph.fine, adjacent.len(), iterations, h);
            return Self {
                order: None,
                start,
                adjacent,
                shares: graph.shares,
                keep: graph.keep,
                uniform: graph.uniform,
                rounds,
            };
        }
        // A large mesh's rows do not fit in the caches: the rounds run over the vertices
        // ordered by position (slabs of voxels), so that a vertex's neighbours lie near it in
        // memory. Every vertex keeps its neighbours in their order, so each row is computed
        // as without the reordering.
        let order = near_order(mesh, h);
        let mut new_index = vec![0u32; order.len()];
        for (k, &v) in order.iter().enumerate() {
            new_index[v as usize] = k as u32;
        }
        let mut start = Vec::with_capacity(order.len() + 1);
        let mut end = 0;
        start.push(end);
        for &v in &order {
            end += adjacency.around(v as usize).len();
            start.push(end);
        }
        let mut adjacent = vec![0u32; end];
        split_rows(&mut adjacent, &start)
            .into_par_iter()
            .with_min_len(4096)
            .for_each(|(k, out)| {
                for (o, &u) in out.iter_mut().zip(adjacency.around(order[k] as usize)) {
                    *o = new_index[u as usize];
                }
            });
        let positions: Vec<DVec3> = order
            .par_iter()
            .map(|&v| mesh.positions[v as usize])
            .collect();
        let graph = Graph::new(&positions, &start, &adjacent, h);
        let rounds = rounds_for_fineness(&graph.fine, adjacent.len(), iterations, h);
        let (shares, keep, uniform) = (graph.shares, graph.keep, graph.uniform);
        Self {
            order: Some((order, new_index)),
            start,
            adjacent,
            shares,
            keep,
            uniform,
            rounds,
        }
    }

    /// Runs the rounds on `rows` (one per vertex, in vertex order).
    pub fn smooth(&self, rows: &mut Vec<Row>) {
        if self.rounds == 0 {
            return;
        }
        let Some((order, new_index)) = &self.order else {
            smoothing_rounds(rows, self);
            return;
        };
        let mut ordered: Vec<Row> = order.par_iter().map(|&v| rows[v as usize]).collect();
        smoothing_rounds(&mut ordered, self);
        rows.par_iter_mut()
            .zip(new_index)
            .for_each(|(row, &k)| *row = ordered[k as usize]);
    }
}

/// Meshes with at least this many vertices are smoothed in [`near_order`].
const NEAR_ORDER_MIN: usize = 100_000;

/// The vertices ordered by the cube of side `h` holding them (z, then y, then x; ties by
/// index).
fn near_order(mesh: &Mesh, h: f64) -> Vec<u32> {
    let (min, max) = mesh.positions.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let cells = ((max - min) / h).floor() + DVec3::ONE;
    let (nx, ny) = (cells.x.max(1.0) as u64, cells.y.max(1.0) as u64);
    let mut keyed: Vec<(u64, u32)> = mesh
        .positions
        .par_iter()
        .enumerate()
        .map(|(v, &p)| {
            let c = ((p - min) / h).floor().max(DVec3::ZERO);
            ((c.z as u64 * ny + c.y as u64) * nx + c.x as u64, v as u32)
        })
        .collect();
    keyed.par_sort_unstable();
    keyed.into_iter().map(|(_, v)| v).collect()
}

/// `values` cut into one slice per row of the compressed rows `start`, each with its row.
fn split_rows<'a, T>(mut values: &'a mut [T], start: &[usize]) -> Vec<(usize, &'a mut [T])> {
    let mut out = Vec::with_capacity(start.len().saturating_sub(1));
    for (v, w) in start.windows(2).enumerate() {
        let (head, tail) = values.split_at_mut(w[1] - w[0]);
        out.push((v, head));
        values = tail;
    }
    out
}

/// The mesh's edges as [`smoothing_rounds`] reads them: compressed rows of neighbours, each
/// edge's share (fixed over the rounds) and what each vertex keeps of its own, and per vertex
/// the sum of its edges' (length / `h`)², each capped at one ([`rounds_for_fineness`]).
struct Graph {
    /// Each edge's share.
    shares: Vec<f64>,
    keep: Vec<f64>,
    /// Per vertex, the one share of all its edges where every edge is at most a voxel long
    /// (each share is then the vertex's `0.5 / degree` times one, to the bit), NaN where
    /// they differ: on a mesh finer than the voxels (almost every vertex of a million-triangle
    /// figure) the rounds then read one number per vertex instead of one per edge.
    uniform: Vec<f64>,
    fine: Vec<f64>,
}

impl Graph {
    /// The graph of the vertices at `positions` with neighbours `adjacent[start[v]..start[v
    /// + 1]]`, for voxels of size `h`: in one pass over the vertices.
    fn new(positions: &[DVec3], start: &[usize], adjacent: &[u32], h: f64) -> Self {
        let mut shares = vec![0.0f64; adjacent.len()];
        let h2 = h * h;
        // At most a voxel long: the ratio is at least one, so capped to one without dividing.
        let capped = |len2: f64| {
            if len2 <= h2 {
                1.0
            } else {
                (h2 / len2.max(f64::MIN_POSITIVE)).min(1.0)
            }
        };
        let (keep, (uniform, fine)): (Vec<f64>, (Vec<f64>, Vec<f64>)) =
            split_rows(&mut shares, start)
                .into_par_iter()
                .with_min_len(4096)
                .map(|(v, out)| {
                    let around = &adjacent[start[v]..start[v + 1]];
                    let p = positions[v];
                    let scale = 0.5 / around.len().max(1) as f64;
                    let length2 = |u: u32| p.distance_squared(positions[u as usize]);
                    let mut shared = 0.0;
                    let mut fine = 0.0;
                    let mut uniform = true;
                    for (share, &u) in out.iter_mut().zip(around) {
                        let len2 = length2(u);
                        let factor = capped(len2);
                        uniform &= factor == 1.0;
                        *share = scale * factor;
                        shared += *share;
                        fine += (len2 / h2).min(1.0);
                    }
                    let one = if uniform { scale } else { f64::NAN };
                    (1.0 - shared, (one, fine))
                })
                .unzip();
        Self {
            shares,
            keep,
            uniform,
            fine,
        }
    }
}

/// The rounds of [`Smoothing`] on `rows` (in its order); a vertex is computed again only where
/// it or one of its neighbours changed in the round before ([`Settled`]).
fn smoothing_rounds(rows: &mut Vec<Row>, smoothing: &Smoothing) {
    let Smoothing {
        ref start,
        ref adjacent,
        ref shares,
        ref keep,
        ref uniform,
        rounds: iterations,
        ..
    } = *smoothing;
    let mut next = rows.clone();
    let mut settled = Settled::new(rows.len());
    for _ in 0..iterations {
        let current: &[Row] = rows;
        let moved = &settled.moved;
        next.par_iter_mut()
            .zip(settled.next.par_iter_mut())
            .enumerate()
            .with_min_len(1024)
            .for_each_init(Mixer::default, |mixer, (v, (out, moves))| {
                let range = start[v]..start[v + 1];
                let around = &adjacent[range.clone()];
                if !moved[v] && around.iter().all(|&u| !moved[u as usize]) {
                    *moves = false;
                    return;
                }
                let one = uniform[v];
                let row = if one.is_nan() {
                    smoothed_row(
                        current,
                        around,
                        shares[range].iter().copied(),
                        keep[v],
                        v,
                        mixer,
                    )
                } else {
                    let same = std::iter::repeat_n(one, around.len());
                    smoothed_row(current, around, same, keep[v], v, mixer)
                };
                *moves = row != current[v];
                *out = row;
            });
        std::mem::swap(rows, &mut next);
        if !settled.advance() {
            break;
        }
    }
}

/// One round of [`smoothing_rounds`] at vertex `v` with neighbours `around` and their
/// `shares`: in one pass over the neighbours, whether they all equal the row (then it is the
/// mean), whether they all have its joints and the sum of [`Row::blend_same_joints`] (the
/// same products added in the same order), else [`mix`].
#[inline]
fn smoothed_row(
    current: &[Row],
    around: &[u32],
    shares: impl Iterator<Item = f64> + Clone,
    keep: f64,
    v: usize,
    mixer: &mut Mixer,
) -> Row {
    let own = &current[v];
    let mut weights = own.weights.map(|w| keep * w);
    let mut agree = true;
    let mut same_joints = true;
    for (&u, share) in around.iter().zip(shares.clone()) {
        let row = &current[u as usize];
        let joints = row.joints == own.joints;
        same_joints &= joints;
        agree &= joints && row.weights == own.weights;
        for (w, x) in weights.iter_mut().zip(&row.weights) {
            *w += share * x;
        }
    }
    // Where every neighbour has the same weights the mean is the row.
    if agree {
        return *own;
    }
    if same_joints {
        let used = own.joints.iter().take_while(|&&j| j != NONE).count();
        let sum: f64 = weights[..used].iter().sum();
        if used > 0 && sum.is_finite() && weights[..used].iter().all(|&w| w > 0.0) {
            let mut row = *own;
            for (out, w) in row.weights[..used].iter_mut().zip(&weights) {
                *out = w / sum;
            }
            return row;
        }
    }
    let neighbours = around
        .iter()
        .zip(shares)
        .map(|(&u, share)| (&current[u as usize], share));
    mix(own, keep, neighbours, mixer)
}

/// The rounds of [`Smoothing`] for `iterations` asked, from each vertex's sum over its `edges`
/// (directed) of (edge length / voxel size `h`)², each capped at one: all of them unless the
/// mesh is much finer than the voxels (see [`Smoothing`]).
fn rounds_for_fineness(fine: &[f64], edges: usize, iterations: usize, h: f64) -> usize {
    if edges == 0 || h.is_nan() || h <= 0.0 {
        return iterations;
    }
    // Summed in vertex order: the same on any number of threads.
    let fineness = fine.iter().sum::<f64>() / edges as f64 / (FINE_EDGE * FINE_EDGE);
    if fineness >= 1.0 {
        iterations
    } else {
        ((iterations as f64 * fineness).ceil() as usize).clamp(1, iterations)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows of two to five joints varying over the vertices of a ringed tube.
    fn tube_rows(mesh: &Mesh) -> Vec<Row> {
        let mut mixer = Mixer::default();
        mesh.positions
            .iter()
            .map(|p| {
                mixer.clear();
                let t = p.y.clamp(0.0, 2.0);
                mixer.add(0, 1.0 + (2.0 - t).powi(2));
                mixer.add(1, 1.0 + t * t);
                mixer.add(2, 0.5 + (3.0 * t).sin().abs());
                if p.x > 0.0 {
                    mixer.add(3, p.x);
                }
                if p.z > 0.05 {
                    mixer.add(4, 0.3 * p.z);
                }
                mixer.pruned(0.0)
            })
            .collect()
    }

    /// A row's bits, to compare rows exactly (`Row`'s `==` takes -0 for 0).
    fn bits(row: &Row) -> ([u32; 4], [u64; 4]) {
        (row.joints, row.weights.map(f64::to_bits))
    }

    /// The one-pass round gives, to the bit, the rule it replaced: the row itself where every
    /// neighbour equals it, else [`Row::blend_same_joints`], else [`mix`]; and a vertex whose
    /// edges are all at most a voxel long has one share equal to each edge's, which gives the
    /// same row. On a tube with a band of equal rows, rows of three to five joints and edges
    /// on both sides of the voxel size.
    #[test]
    fn one_pass_round_gives_the_blend_or_mix_rule_to_the_bit() {
        let rings: Vec<(f64, f64)> = (0..=40).map(|r| (0.2, 1.0 - r as f64 / 20.0)).collect();
        let mesh = Mesh::lathe(DVec3::new(0.0, 1.0, 0.0), 1.0, &rings, -1.0, 12);
        let adjacency = Adjacency::new(&mesh);
        let (start, adjacent) = adjacency.compressed();
        let mut rows = tube_rows(&mesh);
        let band = rows[0];
        for (row, p) in rows.iter_mut().zip(&mesh.positions) {
            if p.y > 1.4 {
                *row = band;
            }
        }
        let mut mixer = Mixer::default();
        let (mut agreeing, mut uniform, mut varying) = (0, 0, 0);
        for h in [0.03, 0.08, 0.5] {
            let graph = Graph::new(&mesh.positions, &start, &adjacent, h);
            for v in 0..rows.len() {
                let range = start[v]..start[v + 1];
                let (around, shares, keep) = (
                    &adjacent[range.clone()],
                    &graph.shares[range],
                    graph.keep[v],
                );
                let own = &rows[v];
                let neighbours = || {
                    around
                        .iter()
                        .zip(shares)
                        .map(|(&u, &share)| (&rows[u as usize], share))
                };
                let expected = if around.iter().all(|&u| rows[u as usize] == *own) {
                    agreeing += 1;
                    *own
                } else {
                    own.blend_same_joints(keep, neighbours())
                        .unwrap_or_else(|| mix(own, keep, neighbours(), &mut mixer))
                };
                let row = smoothed_row(&rows, around, shares.iter().copied(), keep, v, &mut mixer);
                assert_eq!(bits(&row), bits(&expected), "vertex {v}, h {h}");
                let one = graph.uniform[v];
                if one.is_nan() {
                    varying += 1;
                    continue;
                }
                uniform += 1;
                assert!(shares.iter().all(|s| s.to_bits() == one.to_bits()));
                let same = std::iter::repeat_n(one, around.len());
                let row = smoothed_row(&rows, around, same, keep, v, &mut mixer);
                assert_eq!(bits(&row), bits(&expected), "vertex {v}, h {h}");
            }
        }
        assert!(
            agreeing > 0 && uniform > 0 && varying > 0,
            "{agreeing} {uniform} {varying}"
        );
    }

    #[test]
    fn smoothing_in_position_order_gives_the_rows_of_vertex_order_to_the_bit() {
        let rings: Vec<(f64, f64)> = (0..=40).map(|r| (0.2, 1.0 - r as f64 / 20.0)).collect();
        let mesh = Mesh::lathe(DVec3::new(0.0, 1.0, 0.0), 1.0, &rings, -1.0, 12);
        let adjacency = Adjacency::new(&mesh);
        let rows = tube_rows(&mesh);
        let (h, rounds) = (0.05, 12);
        let mut plain = rows.clone();
        Smoothing::in_order(&mesh, &adjacency, rounds, h, false).smooth(&mut plain);
        let mut ordered = rows.clone();
        let by_position = Smoothing::in_order(&mesh, &adjacency, rounds, h, true);
        assert!(by_position.order.is_some());
        by_position.smooth(&mut ordered);
        assert_ne!(plain, rows, "the rounds changed nothing");
        assert_eq!(plain, ordered);
    }
}

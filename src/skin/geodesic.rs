//! Geodesic voxel binding (after Dionne & de Lasa 2013, "Geodesic Voxel Binding for
//! Production Character Meshes"): weights that fall off with the distance from each bone
//! measured *through the solid*, so skin only follows bones it is connected to inside the
//! body (the torso under the armpit does not follow the arm lying against it), and that vary
//! continuously over the surface, so no edge is torn when a joint turns.
//!
//! ```text
//! bone voxels (SegmentVoxels, one label per joint)
//!   │ K-nearest-label Dijkstra through the interior voxels (26-neighbourhood, lengths 1, √2,
//!   │ √3, each step costing its length × depth^-depth_exponent: shallow contacts cost more)
//!   ▼
//! per interior voxel: the K nearest joints and their geodesic distances
//!   │ each voxel around a vertex → its nearest interior voxel (breadth-first), distance +
//!   │ offset; w_j = f(d_j) tapered linearly to 0 where the joint's path is `blend_ratio`
//!   ▼ times as long as the nearest joint's, f(d) = d^(−falloff)
//! per voxel (interior, and around the vertices): ≤ 4 joints
//!   │ `voxel_smoothing_iterations` rounds of diffusion between face neighbours (outside
//!   ▼ voxels only where their nearest interior voxels touch), pruned to four each round
//! per vertex: trilinear blend of the weight vectors of the 8 voxel centres around it
//!   │ every prune to four joints subtracts the fifth's weight, so a joint leaves the set
//!   ▼ with weight 0 (no jump)
//! ≤ 4 influences per vertex, normalised
//!   │ Laplacian smoothing over the mesh edges, each edge's share scaled by (voxel / length)²;
//!   ▼ weights under 1 % cut
//! weights
//! ```
//!
//! Why this and not the dissertation's anchor weights (5.2.5): those give each vertex the
//! equal-share weights of the influence set of its voxel, which changes abruptly between
//! neighbouring voxels (one vertex 100 % on one bone, its neighbour 25 % on four), and the
//! mesh tears when a joint turns. A weight field that is continuous in space cannot tear
//! under linear blend skinning, whatever the mesh's tessellation or its number of pieces;
//! measured with [`check`](super::check): `reports/deformation/`.

use super::weights::nearest_segment;
use super::{SegmentVoxels, SkinOptions};
use crate::distance::DistanceMap;
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use crate::voxel::{Connectivity, Solid};
use glam::DVec3;
use rayon::prelude::*;
use std::collections::VecDeque;

/// Nearest joints kept per interior voxel: the four influences a vertex may keep, and one
/// more whose weight is subtracted so that joints enter and leave the set smoothly.
const LABELS: usize = super::MAX_ENGINE_INFLUENCES + 1;

/// A weight this small (of a vertex's total of one) is subtracted from every weight after
/// blending and smoothing, so that what smoothing carries along long edges or across a piece
/// fades to exactly zero instead of a trace of a far bone.
const NEGLIGIBLE: f64 = 0.01;

/// No label / no voxel.
const NONE: u32 = u32::MAX;

/// The K nearest joints of every interior voxel by geodesic distance through the interior.
struct Field {
    /// Interior voxel → compact index, `NONE` elsewhere.
    compact: Vec<u32>,
    /// Compact index → grid index.
    interior: Vec<usize>,
    /// `LABELS` joint ids per compact voxel, nearest first, `NONE` for unused slots.
    labels: Vec<u32>,
    /// The depth-weighted geodesic distances of `labels` (the Dijkstra's order).
    distances: Vec<f32>,
    /// The lengths (voxel units) of the same shortest paths, for the blend ratio.
    lengths: Vec<f32>,
    /// For every grid voxel, the compact index of its nearest interior voxel (breadth-first
    /// over the 26-neighbourhood), `NONE` when the grid has no interior voxel.
    nearest: Vec<u32>,
}

/// Geodesic weights of every vertex of `mesh` (at most [`MAX_ENGINE_INFLUENCES`] joints,
/// positive, summing to one), and the vertices that no bone reached through the interior
/// (bound to the nearest segment's joint instead).
///
/// [`MAX_ENGINE_INFLUENCES`]: super::MAX_ENGINE_INFLUENCES
pub(crate) fn geodesic_weights(
    mesh: &Mesh,
    skeleton: &Skeleton,
    solid: &Solid,
    distance: &DistanceMap,
    segments: &[SegmentVoxels],
    options: &SkinOptions,
) -> (Vec<Vec<(JointId, f64)>>, Vec<usize>) {
    let mut needed = vec![false; solid.grid.len()];
    for &p in &mesh.positions {
        for (index, _) in corners(&solid.grid, p) {
            needed[index] = true;
        }
    }
    let field = field(solid, distance, segments, options, &needed);
    let grid = solid.grid;
    let voxels = smoothed_voxel_weights(&field, &grid, &needed, options);
    let lines: Vec<_> = segments.iter().map(|s| s.line(skeleton)).collect();
    let mut weights: Vec<Vec<(JointId, f64)>> = mesh
        .positions
        .par_iter()
        .map(|&p| vertex_weights(&voxels, &grid, p))
        .collect();
    let adjacency = Adjacency::new(mesh);
    // A vertex the field does not reach (no joint reached any interior voxel near it) takes
    // the weights of the nearest weighted vertex of the same piece along the mesh's edges; a
    // piece with no weighted vertex at all follows the joint of its nearest bone.
    let mut queue: VecDeque<u32> = (0..weights.len() as u32)
        .filter(|&v| !weights[v as usize].is_empty())
        .collect();
    while let Some(v) = queue.pop_front() {
        for &u in adjacency.around(v as usize) {
            if weights[u as usize].is_empty() {
                weights[u as usize] = weights[v as usize].clone();
                queue.push_back(u);
            }
        }
    }
    let mut isolated = Vec::new();
    for (v, w) in weights.iter_mut().enumerate() {
        if w.is_empty() {
            let p = mesh.positions[v];
            let nearest = nearest_segment(p, &lines).map_or(JointId(0), |s| segments[s].joint);
            *w = vec![(nearest, 1.0)];
            isolated.push(v);
        }
    }
    smooth(
        mesh,
        &adjacency,
        &mut weights,
        options.smoothing_iterations,
        solid.grid.voxel_size,
    );
    (weights, isolated)
}

/// The mesh's vertex adjacency (compressed rows).
struct Adjacency {
    start: Vec<usize>,
    adjacent: Vec<u32>,
}

impl Adjacency {
    fn new(mesh: &Mesh) -> Self {
        let n = mesh.positions.len();
        let edges = super::check::mesh_edges(mesh);
        let mut start = vec![0usize; n + 1];
        for &(a, b) in &edges {
            start[a as usize + 1] += 1;
            start[b as usize + 1] += 1;
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut next = start.clone();
        let mut adjacent = vec![0u32; start[n]];
        for &(a, b) in &edges {
            adjacent[next[a as usize]] = b;
            next[a as usize] += 1;
            adjacent[next[b as usize]] = a;
            next[b as usize] += 1;
        }
        Self { start, adjacent }
    }

    fn around(&self, v: usize) -> &[u32] {
        &self.adjacent[self.start[v]..self.start[v + 1]]
    }
}

/// `iterations` rounds of Laplacian smoothing over the mesh's edges: each vertex's weights
/// move towards its neighbours' by half their mean difference, each edge's share scaled by
/// (voxel size / edge length)² so that meshes coarser than the voxels are barely smoothed,
/// then pruned to four joints as in [`prune`]; at the end, weights under [`NEGLIGIBLE`] are
/// cut. Removes what is left of the voxel scale in the weight field; separate pieces smooth
/// within themselves.
fn smooth(
    mesh: &Mesh,
    adjacency: &Adjacency,
    weights: &mut [Vec<(JointId, f64)>],
    iterations: usize,
    h: f64,
) {
    // Each edge's share, fixed over the iterations.
    let shares: Vec<f64> = (0..weights.len())
        .into_par_iter()
        .flat_map_iter(|v| {
            let around = adjacency.around(v);
            let p = mesh.positions[v];
            let scale = 0.5 / around.len().max(1) as f64;
            around.iter().map(move |&u| {
                let len2 = p.distance_squared(mesh.positions[u as usize]);
                scale * (h * h / len2.max(f64::MIN_POSITIVE)).min(1.0)
            })
        })
        .collect();
    let mut rows: Vec<Row> = weights
        .iter()
        .map(|w| {
            let w: Vec<(u32, f64)> = w.iter().map(|&(j, x)| (j.0 as u32, x)).collect();
            to_row(&w)
        })
        .collect();
    for _ in 0..iterations {
        rows = (0..rows.len())
            .into_par_iter()
            .map_init(Vec::new, |mixed: &mut Vec<(u32, f64)>, v| {
                let range = adjacency.start[v]..adjacency.start[v + 1];
                if range.is_empty() {
                    return rows[v];
                }
                let keep = 1.0 - shares[range.clone()].iter().sum::<f64>();
                mixed.clear();
                mixed.extend(
                    rows[v]
                        .iter()
                        .filter(|e| e.0 != NONE)
                        .map(|&(j, w)| (j, keep * w)),
                );
                for (&u, &share) in adjacency.adjacent[range.clone()].iter().zip(&shares[range]) {
                    for &(j, w) in rows[u as usize].iter().filter(|e| e.0 != NONE) {
                        match mixed.iter_mut().find(|(k, _)| *k == j) {
                            Some(entry) => entry.1 += share * w,
                            None => mixed.push((j, share * w)),
                        }
                    }
                }
                prune(mixed, 0.0);
                to_row(mixed)
            })
            .collect();
    }
    weights.par_iter_mut().zip(&rows).for_each(|(w, row)| {
        let mut pruned: Vec<(u32, f64)> = row.iter().filter(|e| e.0 != NONE).copied().collect();
        prune(&mut pruned, NEGLIGIBLE);
        *w = pruned
            .into_iter()
            .map(|(j, x)| (JointId(j as usize), x))
            .collect();
    });
}

/// The labelled distance field: a Dijkstra from every joint's bone voxels at once in which
/// each interior voxel accepts the first `LABELS` distinct joints that reach it (the nearest
/// ones), then the nearest interior voxel of every grid voxel.
fn field(
    solid: &Solid,
    distance: &DistanceMap,
    segments: &[SegmentVoxels],
    options: &SkinOptions,
    needed: &[bool],
) -> Field {
    let connectivity = options.connectivity;
    let grid = solid.grid;
    let mut compact = vec![NONE; grid.len()];
    let mut interior = Vec::new();
    for (index, &inside) in solid.inside.iter().enumerate() {
        if inside {
            compact[index] = interior.len() as u32;
            interior.push(index);
        }
    }
    let n = interior.len();
    // Shallow voxels cost more to cross, so a bone's distance does not leak through a thin
    // contact (an arm lying against the torso) as cheaply as through the body's core.
    let step_cost: Vec<f64> = interior
        .iter()
        .map(|&i| distance.distance(i).max(1.0).powf(-options.depth_exponent))
        .collect();
    let mut labels = vec![NONE; n * LABELS];
    let mut distances = vec![f32::INFINITY; n * LABELS];
    let mut lengths = vec![f32::INFINITY; n * LABELS];
    let mut count = vec![0u8; n];
    // A bucket queue (Dial's algorithm) over distances rounded down to `BUCKET`: entries
    // leave in distance order up to one bucket's width, each in O(1); within a bucket, in
    // the order pushed, so the result does not depend on timing or threads.
    let mut queue = BucketQueue::default();
    for s in segments {
        for &v in &s.voxels {
            if let Some(&c) = compact.get(v) {
                if c != NONE {
                    queue.push(0.0, 0.0, c, s.joint.0 as u32);
                }
            }
        }
    }
    let neighbours = connectivity.neighbours();
    while let Some((d, length, c, joint)) = queue.pop() {
        let slot = c as usize * LABELS;
        let k = usize::from(count[c as usize]);
        if k == LABELS || labels[slot..slot + k].contains(&joint) {
            continue;
        }
        labels[slot + k] = joint;
        distances[slot + k] = d as f32;
        lengths[slot + k] = length as f32;
        count[c as usize] += 1;
        let coords = grid.coords(interior[c as usize]);
        for nb in neighbours {
            let Some(next) = grid.offset(coords, nb.offset) else {
                continue;
            };
            let m = compact[next];
            if m == NONE {
                continue;
            }
            let ms = m as usize * LABELS;
            let mk = usize::from(count[m as usize]);
            if mk == LABELS || labels[ms..ms + mk].contains(&joint) {
                continue;
            }
            queue.push(
                d + nb.distance * step_cost[m as usize],
                length + nb.distance,
                m,
                joint,
            );
        }
    }
    // Nearest interior voxel of the `needed` grid voxels (those around the vertices),
    // breadth-first: pieces apart from the solid (a head modelled as a separate shell whose
    // interior was not kept, a hat, a sword) take the field of the solid nearest to them,
    // continuously. The search stops once every needed voxel has its answer.
    let mut nearest = compact.clone();
    let mut missing = (0..grid.len())
        .filter(|&i| needed[i] && nearest[i] == NONE)
        .count();
    let mut queue: VecDeque<usize> = interior.iter().copied().collect();
    while let Some(index) = queue.pop_front() {
        if missing == 0 {
            break;
        }
        let coords = grid.coords(index);
        for nb in Connectivity::TwentySix.neighbours() {
            if let Some(next) = grid.offset(coords, nb.offset) {
                if nearest[next] == NONE {
                    nearest[next] = nearest[index];
                    missing -= usize::from(needed[next]);
                    queue.push_back(next);
                }
            }
        }
    }
    Field {
        compact,
        interior,
        labels,
        distances,
        lengths,
        nearest,
    }
}

/// Width of a bucket of [`BucketQueue`], in voxel lengths: the distance error it allows.
const BUCKET: f64 = 1.0 / 32.0;

/// A monotone priority queue of `(distance, voxel, joint)` with buckets [`BUCKET`] wide.
#[derive(Default)]
struct BucketQueue {
    buckets: Vec<Vec<(f64, f64, u32, u32)>>,
    current: usize,
}

impl BucketQueue {
    /// Queues `voxel` reached from `joint` at weighted distance `d` by a path `length` long.
    fn push(&mut self, d: f64, length: f64, voxel: u32, joint: u32) {
        let b = ((d / BUCKET) as usize).max(self.current);
        if b >= self.buckets.len() {
            self.buckets.resize_with(b + 1, Vec::new);
        }
        self.buckets[b].push((d, length, voxel, joint));
    }

    fn pop(&mut self) -> Option<(f64, f64, u32, u32)> {
        while self.current < self.buckets.len() {
            if let Some(entry) = self.buckets[self.current].pop() {
                return Some(entry);
            }
            self.current += 1;
        }
        None
    }
}

/// The weight of a joint at geodesic distance `d` (voxel units), before normalisation.
fn falloff(d: f64, power: f64) -> f64 {
    d.max(0.5).powf(-power)
}

/// Keeps the `LABELS` largest of `weights` (joint id, weight), subtracts the smallest of them
/// from the others (so that a joint whose rank crosses the cut enters or leaves with weight
/// zero), drops what is left at zero and normalises. Sorted by joint id.
fn prune(weights: &mut Vec<(u32, f64)>, cut: f64) {
    weights.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
    let floor = if weights.len() >= LABELS {
        weights[LABELS - 1].1
    } else {
        0.0
    }
    .max(cut.min(weights.first().map_or(0.0, |w| w.1)));
    weights.truncate(LABELS - 1);
    let mut sum = 0.0;
    for w in weights.iter_mut() {
        w.1 = (w.1 - floor).max(0.0);
        sum += w.1;
    }
    if sum > 0.0 && sum.is_finite() {
        weights.retain(|w| w.1 > 0.0);
        for w in weights.iter_mut() {
            w.1 /= sum;
        }
    } else {
        // Every kept joint ties with the cut: share equally.
        let share = 1.0 / weights.len().max(1) as f64;
        for w in weights.iter_mut() {
            w.1 = share;
        }
    }
    weights.sort_by_key(|w| w.0);
}

/// The weights of the grid voxel `index`: those of its nearest interior voxel, with the
/// distance between the two centres added to every geodesic distance.
fn voxel_weights(
    field: &Field,
    grid: &crate::voxel::Grid,
    index: usize,
    power: f64,
    blend_ratio: f64,
    out: &mut Vec<(u32, f64)>,
) {
    out.clear();
    let c = field.nearest[index];
    if c == NONE {
        return;
    }
    let extra = if field.compact[index] == NONE {
        let here = grid.coords(index);
        let there = grid.coords(field.interior[c as usize]);
        let d: f64 = (0..3)
            .map(|a| (here[a] as f64 - there[a] as f64).powi(2))
            .sum();
        d.sqrt()
    } else {
        0.0
    };
    let slot = c as usize * LABELS;
    for k in 0..LABELS {
        let joint = field.labels[slot + k];
        if joint == NONE {
            break;
        }
        let d = f64::from(field.distances[slot + k]) + extra;
        // Joints whose path is `blend_ratio` times as long as the nearest joint's get nothing,
        // fading linearly from the nearest's length.
        let ratio = (f64::from(field.lengths[slot + k]) + extra)
            / (f64::from(field.lengths[slot]) + extra).max(0.5);
        let taper = ((blend_ratio - ratio) / (blend_ratio - 1.0)).clamp(0.0, 1.0);
        if taper > 0.0 {
            out.push((joint, taper * falloff(d, power)));
        }
    }
    if !out.is_empty() {
        prune(out, 0.0);
    }
}

/// The eight voxels whose centres surround `p` (clamped to the grid) and their trilinear
/// factors.
fn corners(grid: &crate::voxel::Grid, p: DVec3) -> [(usize, f64); 8] {
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

/// A joint's weight row of a voxel: at most four `(joint, weight)`, `NONE` in unused slots.
type Row = [(u32, f64); LABELS - 1];

/// An empty [`Row`] slot.
const EMPTY: (u32, f64) = (NONE, 0.0);

/// `weights` (at most four entries) as a [`Row`].
fn to_row(weights: &[(u32, f64)]) -> Row {
    let mut row = [EMPTY; LABELS - 1];
    for (slot, &entry) in row.iter_mut().zip(weights) {
        *slot = entry;
    }
    row
}

/// The weight rows of the interior voxels and of the voxels around the vertices, smoothed
/// through the figure.
struct VoxelWeights {
    /// Grid voxel → row, `NONE` for voxels without weights.
    slot: Vec<u32>,
    rows: Vec<Row>,
}

/// The weights of every interior voxel and of every voxel around a vertex ([`voxel_weights`]),
/// then rounds of diffusion between face neighbours: each voxel's row moves halfway towards
/// the mean of its neighbours' and is pruned to four joints. Two voxels outside the figure, or
/// one outside and one inside, are neighbours only where their nearest interior voxels touch,
/// so weights do not cross a gap between two parts (an arm hanging beside the torso). The
/// blend between bones then spreads over a few voxels wherever the bones meet (the crotch
/// between the thighs, the armpit), at the same width on any tessellation: the weight field
/// has no steeper slope than the voxels allow, which a fine mesh's short edges would
/// otherwise stretch.
fn smoothed_voxel_weights(
    field: &Field,
    grid: &crate::voxel::Grid,
    needed: &[bool],
    options: &SkinOptions,
) -> VoxelWeights {
    let mut slot = vec![NONE; grid.len()];
    let mut voxels: Vec<usize> = field.interior.clone();
    for (index, &nearest) in field.nearest.iter().enumerate() {
        if nearest != NONE && field.compact[index] == NONE && needed[index] {
            voxels.push(index);
        }
    }
    for (k, &index) in voxels.iter().enumerate() {
        slot[index] = k as u32;
    }
    let mut rows: Vec<Row> = voxels
        .par_iter()
        .map_init(Vec::new, |out, &index| {
            voxel_weights(
                field,
                grid,
                index,
                options.falloff,
                options.blend_ratio,
                out,
            );
            to_row(out)
        })
        .collect();
    let iterations = options.voxel_smoothing_iterations;
    if iterations == 0 {
        return VoxelWeights { slot, rows };
    }
    // Face neighbours whose nearest interior voxels touch.
    let linked: Vec<[u32; 6]> = voxels
        .par_iter()
        .map(|&index| {
            let coords = grid.coords(index);
            let home = grid.coords(field.interior[field.nearest[index] as usize]);
            let mut out = [NONE; 6];
            for (slot_out, nb) in out.iter_mut().zip(Connectivity::Six.neighbours()) {
                let Some(next) = grid.offset(coords, nb.offset) else {
                    continue;
                };
                let s = slot[next];
                if s == NONE {
                    continue;
                }
                let there = grid.coords(field.interior[field.nearest[next] as usize]);
                if (0..3).all(|a| home[a].abs_diff(there[a]) <= 1) {
                    *slot_out = s;
                }
            }
            out
        })
        .collect();
    for _ in 0..iterations {
        rows = (0..rows.len())
            .into_par_iter()
            .map_init(Vec::new, |mixed: &mut Vec<(u32, f64)>, v| {
                let count = linked[v].iter().filter(|&&u| u != NONE).count();
                // Where every neighbour agrees (most of a limb's core), the mean is the row.
                if linked[v]
                    .iter()
                    .all(|&u| u == NONE || rows[u as usize] == rows[v])
                {
                    return rows[v];
                }
                let share = 0.5 / count as f64;
                mixed.clear();
                mixed.extend(
                    rows[v]
                        .iter()
                        .filter(|e| e.0 != NONE)
                        .map(|&(j, w)| (j, 0.5 * w)),
                );
                for &u in linked[v].iter().filter(|&&u| u != NONE) {
                    for &(j, w) in rows[u as usize].iter().filter(|e| e.0 != NONE) {
                        match mixed.iter_mut().find(|(k, _)| *k == j) {
                            Some(entry) => entry.1 += share * w,
                            None => mixed.push((j, share * w)),
                        }
                    }
                }
                prune(mixed, 0.0);
                to_row(mixed)
            })
            .collect();
    }
    VoxelWeights { slot, rows }
}

/// The weights of a vertex at `p`: the trilinear blend of the weight rows of the eight voxel
/// centres around it (clamped to the grid), pruned to four joints.
fn vertex_weights(
    voxels: &VoxelWeights,
    grid: &crate::voxel::Grid,
    p: DVec3,
) -> Vec<(JointId, f64)> {
    let mut blended: Vec<(u32, f64)> = Vec::with_capacity(4 * LABELS);
    for (index, factor) in corners(grid, p) {
        if factor <= 0.0 {
            continue;
        }
        let s = voxels.slot[index];
        if s == NONE {
            continue;
        }
        for &(joint, w) in voxels.rows[s as usize].iter().filter(|e| e.0 != NONE) {
            match blended.iter_mut().find(|(j, _)| *j == joint) {
                Some(entry) => entry.1 += factor * w,
                None => blended.push((joint, factor * w)),
            }
        }
    }
    if blended.is_empty() {
        return Vec::new();
    }
    prune(&mut blended, 0.0);
    blended
        .into_iter()
        .map(|(j, w)| (JointId(j as usize), w))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distance::edt;
    use crate::skeleton::Joint;
    use crate::skin::check::{check_deformation, sweep, SweepKind};
    use crate::skin::{deform, skin_from_bones};
    use crate::voxel::{voxelize, VoxelOptions, VoxelSize};
    use std::collections::BTreeMap;

    /// A leg: a finely ringed tube from y = 0 to y = 2, hip at the top, knee in the middle,
    /// plus optional loose pieces.
    fn leg(pieces: &[Mesh]) -> (Mesh, Skeleton) {
        let rings: Vec<(f64, f64)> = (0..=60).map(|r| (0.2, 1.0 - r as f64 / 30.0)).collect();
        let mut mesh = Mesh::lathe(DVec3::new(0.0, 1.0, 0.0), 1.0, &rings, -1.0, 16);
        for piece in pieces {
            let offset = mesh.positions.len() as u32;
            mesh.positions.extend(&piece.positions);
            mesh.triangles
                .extend(piece.triangles.iter().map(|t| t.map(|i| i + offset)));
        }
        let skeleton = Skeleton {
            joints: vec![
                Joint::new("hip_L", None, DVec3::new(0.0, 1.95, 0.0)),
                Joint::new("knee_L", Some(JointId(0)), DVec3::new(0.0, 1.0, 0.0)),
                Joint::new("ankle_L", Some(JointId(1)), DVec3::new(0.0, 0.05, 0.0)),
            ],
        };
        (mesh, skeleton)
    }

    fn skin_of(mesh: &Mesh, skeleton: &Skeleton, fraction: f64) -> crate::skin::Skin {
        let options = VoxelOptions {
            size: VoxelSize::Fraction(fraction),
            ..Default::default()
        };
        let solid = voxelize(mesh, &options).unwrap();
        let distance = edt(&solid);
        skin_from_bones(mesh, skeleton, &solid, &distance, &SkinOptions::default()).unwrap()
    }

    #[test]
    fn the_weights_change_gradually_along_the_leg_and_the_knee_bends_cleanly() {
        let (mesh, skeleton) = leg(&[]);
        let skin = skin_of(&mesh, &skeleton, 1.0 / 40.0);
        let weight = |v: usize, j: usize| {
            skin.weights[v]
                .iter()
                .find(|(k, _)| k.0 == j)
                .map_or(0.0, |w| w.1)
        };
        let mut worst_jump = 0.0f64;
        for (a, b) in crate::skin::check::mesh_edges(&mesh) {
            for j in 0..3 {
                worst_jump = worst_jump.max((weight(a as usize, j) - weight(b as usize, j)).abs());
            }
        }
        assert!(
            worst_jump < 0.25,
            "a weight jumps by {worst_jump} across one edge"
        );
        // Far from the knee the leg follows one bone; at the knee both share.
        let near = |y: f64| {
            (0..mesh.positions.len())
                .min_by(|&a, &b| {
                    let da = (mesh.positions[a] - DVec3::new(0.2, y, 0.0)).length();
                    let db = (mesh.positions[b] - DVec3::new(0.2, y, 0.0)).length();
                    da.total_cmp(&db)
                })
                .unwrap()
        };
        assert!(weight(near(1.7), 0) > 0.9, "{:?}", skin.weights[near(1.7)]);
        // The ankle's blend spreads about 4.6 voxels (0.23) up the shin
        // (`voxel_smoothing_iterations`): mid-shin follows the knee's bone alone.
        assert!(weight(near(0.5), 1) > 0.9, "{:?}", skin.weights[near(0.5)]);
        let knee = skin.weights[near(1.0)].clone();
        assert!(
            weight(near(1.0), 0) > 0.2 && weight(near(1.0), 1) > 0.2,
            "{knee:?}"
        );
        let canonical: BTreeMap<String, JointId> = skeleton
            .joints
            .iter()
            .enumerate()
            .map(|(k, j)| (j.name.clone(), JointId(k)))
            .collect();
        let (poses, missing) = sweep(
            &skeleton,
            &canonical,
            SweepKind::Humanoid,
            DVec3::Y,
            DVec3::Z,
        );
        let check = check_deformation(
            &mesh,
            &skeleton,
            &skin.weights,
            SweepKind::Humanoid,
            &poses,
            missing,
        )
        .unwrap();
        assert_eq!(check.total_over_2(), 0, "{check:?}");
    }

    #[test]
    fn the_dissertation_anchor_weights_tear_the_same_knee() {
        let (mesh, skeleton) = leg(&[]);
        let options = VoxelOptions {
            size: VoxelSize::Fraction(1.0 / 40.0),
            ..Default::default()
        };
        let solid = voxelize(&mesh, &options).unwrap();
        let distance = edt(&solid);
        let anchor = SkinOptions {
            method: crate::skin::SkinMethod::Anchor,
            ..Default::default()
        };
        let skin = skin_from_bones(&mesh, &skeleton, &solid, &distance, &anchor).unwrap();
        let canonical: BTreeMap<String, JointId> = [
            ("knee_L".to_string(), JointId(1)),
            ("ankle_L".to_string(), JointId(2)),
        ]
        .into();
        let (poses, missing) = sweep(
            &skeleton,
            &canonical,
            SweepKind::Humanoid,
            DVec3::Y,
            DVec3::Z,
        );
        let anchor_check = check_deformation(
            &mesh,
            &skeleton,
            &skin.weights,
            SweepKind::Humanoid,
            &poses,
            missing.clone(),
        )
        .unwrap();
        let geodesic = skin_of(&mesh, &skeleton, 1.0 / 40.0);
        let geodesic_check = check_deformation(
            &mesh,
            &skeleton,
            &geodesic.weights,
            SweepKind::Humanoid,
            &poses,
            missing,
        )
        .unwrap();
        assert!(
            geodesic_check.worst() < anchor_check.worst(),
            "geodesic {geodesic_check:?} anchor {anchor_check:?}"
        );
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(16))]
        #[test]
        fn weights_are_a_partition_of_one_on_every_vertex(
            fraction in 1.0f64 / 48.0..1.0 / 16.0,
            knee_x in -0.1f64..0.1,
            piece in proptest::option::of((-1.0f64..1.0, -0.5f64..2.5, 0.02f64..0.2)),
        ) {
            let pieces: Vec<Mesh> = piece
                .map(|(x, y, r)| Mesh::uv_sphere(DVec3::new(x, y, 0.3), r, 6, 8))
                .into_iter()
                .collect();
            let (mesh, mut skeleton) = leg(&pieces);
            skeleton.joints[1].position.x = knee_x;
            let skin = skin_of(&mesh, &skeleton, fraction);
            proptest::prop_assert_eq!(skin.weights.len(), mesh.positions.len());
            for w in &skin.weights {
                proptest::prop_assert!(!w.is_empty() && w.len() <= crate::skin::MAX_ENGINE_INFLUENCES);
                proptest::prop_assert!(w.iter().all(|&(j, x)| x > 0.0 && x.is_finite() && j.0 < 3));
                proptest::prop_assert!((w.iter().map(|x| x.1).sum::<f64>() - 1.0).abs() < 1e-9);
            }
            let rest = deform(&mesh, &skeleton, &skin, &skeleton.rest_pose()).unwrap();
            proptest::prop_assert_eq!(rest, mesh);
        }
    }
}

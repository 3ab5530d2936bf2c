//! The labelled distance field: the K nearest joints of every interior voxel by
//! depth-weighted geodesic distance through the interior, and the nearest interior voxel of
//! the voxels around the mesh's vertices.

use super::rows::NONE;
use super::LABELS;
use crate::distance::DistanceMap;
use crate::skin::neighbourhood::Neighbourhood;
use crate::skin::{SegmentVoxels, SkinOptions};
use crate::voxel::{Connectivity, Grid, Solid};
use rayon::prelude::*;
use std::collections::VecDeque;

/// The K nearest joints of every interior voxel by geodesic distance through the interior.
pub(super) struct Field {
    /// Interior voxel → compact index, `NONE` elsewhere.
    pub compact: Vec<u32>,
    /// Compact index → grid index.
    pub interior: Vec<usize>,
    /// `LABELS` joint ids per compact voxel, nearest first, `NONE` for unused slots.
    pub labels: Vec<u32>,
    /// The depth-weighted geodesic distances of `labels` (the Dijkstra's order).
    pub distances: Vec<f32>,
    /// The lengths (voxel units) of the same shortest paths, for the blend ratio.
    pub lengths: Vec<f32>,
    /// For every grid voxel, the compact index of its nearest interior voxel (breadth-first
    /// over the 26-neighbourhood), `NONE` when the grid has no interior voxel or the voxel
    /// was not needed.
    pub nearest: Vec<u32>,
}

/// The labelled distance field of `segments` on `solid`: a Dijkstra from every joint's bone
/// voxels at once in which each interior voxel accepts the first `LABELS` distinct joints
/// that reach it (the nearest ones), then the nearest interior voxel of every `needed` grid
/// voxel (`needed`: one flag per grid voxel).
pub(super) fn field(
    solid: &Solid,
    distance: &DistanceMap,
    segments: &[SegmentVoxels],
    options: &SkinOptions,
    needed: &[bool],
) -> Field {
    let grid = solid.grid;
    let (compact, interior) = interior_index(solid);
    // Independent searches: the labelled Dijkstra (the long one) beside the breadth-first one.
    let (labelled, nearest) = rayon::join(
        || nearest_joints(&grid, &compact, &interior, distance, segments, options),
        || nearest_interior(&grid, &compact, &interior, needed),
    );
    Field {
        compact,
        interior,
        labels: labelled.labels,
        distances: labelled.distances,
        lengths: labelled.lengths,
        nearest,
    }
}

/// Grid voxel → compact index of the interior voxels (`NONE` elsewhere), and compact index →
/// grid voxel.
fn interior_index(solid: &Solid) -> (Vec<u32>, Vec<usize>) {
    let mut compact = vec![NONE; solid.grid.len()];
    let mut interior = Vec::new();
    for (index, &inside) in solid.inside.iter().enumerate() {
        if inside {
            compact[index] = interior.len() as u32;
            interior.push(index);
        }
    }
    (compact, interior)
}

/// The `LABELS` nearest joints of each compact voxel with their distances and path lengths.
struct Labelled {
    labels: Vec<u32>,
    distances: Vec<f32>,
    lengths: Vec<f32>,
}

/// Joints remembered per voxel with the earliest bucket they are queued in, so that a joint is
/// queued again for a voxel only where the entry could leave first (the Dijkstra's
/// decrease-key; entries of one bucket leave last in, first out, so a later entry of the same
/// bucket is still queued). Leaves the result exactly as without the check. A joint that
/// finds every slot taken is queued without it.
const TENTATIVE: usize = 4;

/// What the Dijkstra reads and writes of one interior voxel each time a neighbour is relaxed,
/// in one cache line: its labels so far, their count, the cost of a step into it and its
/// [`TENTATIVE`] queued joints (joint ids fit in `u16`: skeletons are checked to have fewer
/// than `u16::MAX` joints before skinning; `u16::MAX` marks a free slot).
#[derive(Clone, Copy)]
#[repr(C, align(64))]
struct Node {
    step_cost: f64,
    labels: [u32; LABELS],
    count: u8,
    queued_joints: [u16; TENTATIVE],
    queued_buckets: [u32; TENTATIVE],
}

/// The multi-label Dijkstra: every joint's bone voxels start at distance 0; a step into a
/// voxel at depth `d` (voxels from the outside) costs its length times `d^-depth_exponent`,
/// so shallow contacts of two body parts cost more to cross than the core.
fn nearest_joints(
    grid: &Grid,
    compact: &[u32],
    interior: &[usize],
    distance: &DistanceMap,
    segments: &[SegmentVoxels],
    options: &SkinOptions,
) -> Labelled {
    let n = interior.len();
    let mut nodes: Vec<Node> = interior
        .iter()
        .map(|&i| Node {
            step_cost: distance.distance(i).max(1.0).powf(-options.depth_exponent),
            labels: [NONE; LABELS],
            count: 0,
            queued_joints: [u16::MAX; TENTATIVE],
            queued_buckets: [u32::MAX; TENTATIVE],
        })
        .collect();
    let mut distances = vec![f32::INFINITY; n * LABELS];
    let mut lengths = vec![f32::INFINITY; n * LABELS];
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
    // Each interior voxel's neighbours as compact indices (`NONE` outside), found once in
    // parallel: the search then reads them in order instead of the whole grid's index.
    // Slot `k` holds the neighbour at `steps[k]`, also on the grid's border.
    let steps = options.connectivity.neighbours();
    let stride = steps.len();
    let mut adjacent = vec![NONE; n * stride];
    adjacent
        .par_chunks_mut(stride)
        .zip(interior.par_iter())
        .with_min_len(512)
        .for_each(|(out, &i)| {
            let coords = grid.coords(i);
            for (slot, step) in out.iter_mut().zip(steps) {
                if let Some(next) = grid.offset(coords, step.offset) {
                    *slot = compact[next];
                }
            }
        });
    while let Some((d, length, c, joint)) = queue.pop() {
        let node = &mut nodes[c as usize];
        let k = usize::from(node.count);
        if k == LABELS || node.labels[..k].contains(&joint) {
            continue;
        }
        node.labels[k] = joint;
        node.count += 1;
        let slot = c as usize * LABELS;
        distances[slot + k] = d as f32;
        lengths[slot + k] = length as f32;
        // Joint ids are below `u16::MAX` (checked before skinning).
        let short = joint as u16;
        let start = c as usize * stride;
        for (&m, step) in adjacent[start..start + stride].iter().zip(steps) {
            if m == NONE {
                continue;
            }
            let node = &mut nodes[m as usize];
            let mk = usize::from(node.count);
            if mk == LABELS || node.labels[..mk].contains(&joint) {
                continue;
            }
            let d = d + step.distance * node.step_cost;
            let bucket = u32::try_from(queue.bucket(d)).unwrap_or(u32::MAX);
            match node
                .queued_joints
                .iter()
                .position(|&e| e == short || e == u16::MAX)
            {
                // Leaves in an earlier bucket: this entry would only be turned away.
                Some(e) if node.queued_joints[e] == short && node.queued_buckets[e] < bucket => {
                    continue
                }
                Some(e) => {
                    node.queued_joints[e] = short;
                    node.queued_buckets[e] = bucket;
                }
                None => {}
            }
            queue.push(d, length + step.distance, m, joint);
        }
    }
    let mut labels = vec![NONE; n * LABELS];
    for (out, node) in labels.chunks_exact_mut(LABELS).zip(&nodes) {
        out.copy_from_slice(&node.labels);
    }
    Labelled {
        labels,
        distances,
        lengths,
    }
}

/// Nearest interior voxel (compact index) of the `needed` grid voxels, breadth-first over
/// the 26-neighbourhood: pieces apart from the solid (a head modelled as a separate shell
/// whose interior was not kept, a hat, a sword) take the field of the solid nearest to them,
/// continuously. The search stops once every needed voxel has its answer.
fn nearest_interior(grid: &Grid, compact: &[u32], interior: &[usize], needed: &[bool]) -> Vec<u32> {
    let mut nearest = compact.to_vec();
    let mut missing = (0..grid.len())
        .filter(|&i| needed[i] && nearest[i] == NONE)
        .count();
    let around = Neighbourhood::new(*grid, Connectivity::TwentySix.neighbours());
    let mut queue: VecDeque<usize> = interior.iter().copied().collect();
    while let Some(index) = queue.pop_front() {
        if missing == 0 {
            break;
        }
        around.for_each(index, |next| {
            if nearest[next] == NONE {
                nearest[next] = nearest[index];
                missing -= usize::from(needed[next]);
                queue.push_back(next);
            }
        });
    }
    nearest
}

/// Width of a bucket of [`BucketQueue`], in voxel lengths: the distance error it allows.
const BUCKET: f64 = 1.0 / 32.0;

/// A monotone priority queue of `(distance, length, voxel, joint)` with buckets [`BUCKET`]
/// wide.
#[derive(Default)]
struct BucketQueue {
    buckets: Vec<Vec<(f64, f64, u32, u32)>>,
    current: usize,
    /// Emptied buckets' storage, handed to buckets filled later (the queue holds a few
    /// buckets' entries at a time instead of every entry ever pushed).
    spare: Vec<Vec<(f64, f64, u32, u32)>>,
}

impl BucketQueue {
    /// The bucket an entry at weighted distance `d` goes into.
    fn bucket(&self, d: f64) -> usize {
        ((d / BUCKET) as usize).max(self.current)
    }

    /// Queues `voxel` reached from `joint` at weighted distance `d` by a path `length` long.
    fn push(&mut self, d: f64, length: f64, voxel: u32, joint: u32) {
        let b = self.bucket(d);
        if b >= self.buckets.len() {
            self.buckets.resize_with(b + 1, Vec::new);
        }
        let bucket = &mut self.buckets[b];
        if bucket.capacity() == 0 {
            if let Some(spare) = self.spare.pop() {
                *bucket = spare;
            }
        }
        bucket.push((d, length, voxel, joint));
    }

    fn pop(&mut self) -> Option<(f64, f64, u32, u32)> {
        while self.current < self.buckets.len() {
            if let Some(entry) = self.buckets[self.current].pop() {
                return Some(entry);
            }
            let emptied = std::mem::take(&mut self.buckets[self.current]);
            if emptied.capacity() > 0 {
                self.spare.push(emptied);
            }
            self.current += 1;
        }
        None
    }
}

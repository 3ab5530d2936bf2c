//! The skeletal graph: path-tree chains approximated by straight edges, split by a global heap
//! (dissertation ch.5.2.5, Figure 5.8).

use super::{GeneralOptions, GeneralWarning};
use crate::math::point_segment_distance;
use crate::paths::{Chain, PathTree};
use serde::Serialize;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// An edge of the skeletal graph: the straight segment between two vertices of one chain,
/// approximating the chain section between them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SkeletalEdge {
    /// Index into [`PathTree::chains`].
    pub chain: usize,
    /// First chain vertex of the section (index into the chain's vertices).
    pub start: usize,
    /// Last chain vertex of the section.
    pub end: usize,
    /// Largest distance from the edge to the section's smoothed vertices, voxel units.
    pub error: f64,
    /// Path length of the section, voxel units.
    pub length: f64,
}

/// The skeletal graph of a path tree.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SkeletalGraph {
    /// The edges, ordered by chain, then along the chain.
    pub edges: Vec<SkeletalEdge>,
    /// Things worth telling the user (a segment limit below the number of chains...).
    #[serde(serialize_with = "crate::warning::serialize_records")]
    pub warnings: Vec<GeneralWarning>,
}

/// Largest distance (voxel units) from the edge between chain vertices `a` and `b` to the
/// smoothed vertices between them.
fn section_error(chain: &Chain, a: usize, b: usize, voxel_size: f64) -> f64 {
    let (pa, pb) = (chain.smoothed[a], chain.smoothed[b]);
    chain.smoothed[a..=b]
        .iter()
        .map(|&p| point_segment_distance(p, pa, pb))
        .fold(0.0, f64::max)
        / voxel_size
}

/// The vertex strictly between `a` and `b` minimising the larger error of the two halves (the
/// first among equals), with that error; `None` when there is no vertex between.
fn best_split(chain: &Chain, a: usize, b: usize, voxel_size: f64) -> Option<usize> {
    let mut best: Option<(f64, usize)> = None;
    for k in a + 1..b {
        let e = section_error(chain, a, k, voxel_size).max(section_error(chain, k, b, voxel_size));
        if best.is_none_or(|(be, _)| e < be) {
            best = Some((e, k));
        }
    }
    best.map(|(_, k)| k)
}

/// Builds the skeletal graph of `tree` (ch.5.2.5): one edge per chain, then repeatedly the edge
/// of largest error is split at its best vertex (the chain vertex minimising the larger error
/// of the two halves, Figure 5.8): always when its section is longer than
/// `max_fraction * heart_radius`, else while its error exceeds `approximation_error` (voxel
/// units); sections shorter than `min_fraction * heart_radius` are never split; splitting stops
/// early at [`GeneralOptions::segments`] edges. The heap pops the largest error first, the
/// lowest edge slot among equals, so the result is deterministic.
pub fn skeletal_graph(tree: &PathTree, options: &GeneralOptions) -> SkeletalGraph {
    let voxel_size = tree.grid.voxel_size;
    let min_length = options.min_fraction * tree.heart_radius_voxels;
    let max_length = options.max_fraction * tree.heart_radius_voxels;
    let mut warnings = Vec::new();
    let edge = |chain: usize, start: usize, end: usize| {
        let c = &tree.chains[chain];
        SkeletalEdge {
            chain,
            start,
            end,
            error: section_error(c, start, end, voxel_size),
            length: c.cumulative[end] - c.cumulative[start],
        }
    };
    // Edges live in a slot vector; a split replaces one slot and appends one.
    let mut edges: Vec<SkeletalEdge> = (0..tree.chains.len())
        .map(|c| edge(c, 0, tree.chains[c].nodes.len() - 1))
        .collect();
    if let Some(limit) = options.segments {
        if limit < edges.len() {
            warnings.push(GeneralWarning::SegmentLimitBelowChains {
                limit,
                chains: edges.len(),
            });
        }
    }
    let splittable = |e: &SkeletalEdge| e.length > min_length && e.end >= e.start + 2;
    let mut heap: BinaryHeap<(u64, Reverse<usize>)> = BinaryHeap::new();
    for (i, e) in edges.iter().enumerate() {
        if splittable(e) {
            heap.push((e.error.to_bits(), Reverse(i)));
        }
    }
    while let Some((_, Reverse(i))) = heap.pop() {
        if options.segments.is_some_and(|limit| edges.len() >= limit) {
            break;
        }
        let e = edges[i];
        if !(e.length > max_length || e.error > options.approximation_error) {
            continue;
        }
        let Some(k) = best_split(&tree.chains[e.chain], e.start, e.end, voxel_size) else {
            continue;
        };
        edges[i] = edge(e.chain, e.start, k);
        edges.push(edge(e.chain, k, e.end));
        for j in [i, edges.len() - 1] {
            if splittable(&edges[j]) {
                heap.push((edges[j].error.to_bits(), Reverse(j)));
            }
        }
    }
    edges.sort_by_key(|e| (e.chain, e.start));
    SkeletalGraph { edges, warnings }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn chain(points: Vec<DVec3>) -> Chain {
        let mut cumulative = vec![0.0];
        for w in points.windows(2) {
            cumulative.push(cumulative.last().unwrap() + w[0].distance(w[1]));
        }
        Chain {
            nodes: (0..points.len()).collect(),
            voxels: (0..points.len()).collect(),
            length: *cumulative.last().unwrap(),
            cumulative,
            smoothed: points,
        }
    }

    #[test]
    fn an_l_shaped_chain_splits_at_its_corner() {
        let mut points: Vec<DVec3> = (0..=10).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
        points.extend((1..=10).map(|i| DVec3::new(10.0, i as f64, 0.0)));
        let c = chain(points);
        assert!((section_error(&c, 0, 20, 1.0) - 50f64.sqrt()).abs() < 1e-9);
        assert_eq!(best_split(&c, 0, 20, 1.0), Some(10));
    }
}

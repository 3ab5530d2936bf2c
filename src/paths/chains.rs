//! Chains of the path tree and their smoothing (dissertation ch.5.2.4, Figure 5.6).

use crate::math::{moving_average, Ends};
use crate::medial::MedialSurface;
use glam::DVec3;
use serde::Serialize;

/// A chain: a maximal path of the path tree between two non-intermediate vertices (endpoints,
/// junctions, or the tree's root), ordered away from the tree's root.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Chain {
    /// Path-tree nodes along the chain (indices into [`PathTree::voxels`](super::PathTree)).
    pub nodes: Vec<usize>,
    /// Linear grid indices of the chain's voxels, in chain order.
    pub voxels: Vec<usize>,
    /// Smoothed vertex positions, mesh units and frame; the two ends are the unsmoothed voxel
    /// centres, so chains meeting at a junction share its position exactly.
    pub smoothed: Vec<DVec3>,
    /// Path length from the first vertex to each vertex along the unsmoothed voxel centres,
    /// voxel units (`cumulative[0] == 0`).
    pub cumulative: Vec<f64>,
    /// Total path length, mesh units.
    pub length: f64,
}

/// Splits the path tree given by DMS `positions` and `parents` (indices into `positions`,
/// parents before children) into chains and smooths each with a box filter of `radius` edges,
/// the radius limited at chain ends: `s_i` averages `p_(i-k)..=p_(i+k)` with
/// `k = min(radius, i, n - 1 - i)` (Figure 5.6).
///
/// Chains start at the tree's root or at a vertex with other than two incident edges and are
/// listed in order of their first node, then of their second.
pub fn chains(
    surface: &MedialSurface,
    positions: &[usize],
    parents: &[Option<usize>],
    radius: usize,
) -> Vec<Chain> {
    let n = positions.len();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (node, parent) in parents.iter().enumerate() {
        if let Some(parent) = *parent {
            children[parent].push(node);
        }
    }
    let degree = |v: usize| children[v].len() + usize::from(parents[v].is_some());
    let mut out = Vec::new();
    for start in 0..n {
        if parents[start].is_some() && degree(start) == 2 {
            continue;
        }
        for &first in &children[start] {
            let mut nodes = vec![start, first];
            let mut at = first;
            while degree(at) == 2 {
                at = children[at][0];
                nodes.push(at);
            }
            out.push(chain(surface, positions, nodes, radius));
        }
    }
    out
}

fn chain(surface: &MedialSurface, positions: &[usize], nodes: Vec<usize>, radius: usize) -> Chain {
    let voxels: Vec<usize> = nodes
        .iter()
        .map(|&v| surface.voxels[positions[v]])
        .collect();
    let centres: Vec<DVec3> = nodes
        .iter()
        .map(|&v| surface.centre(positions[v]))
        .collect();
    // Box filter of `radius` edges, limited at the ends (Figure 5.6).
    let smoothed = moving_average(&centres, radius, Ends::Shrink);
    let mut cumulative = Vec::with_capacity(nodes.len());
    let mut total = 0.0;
    cumulative.push(0.0);
    for pair in nodes.windows(2) {
        let a = surface.coords(positions[pair[0]]);
        let b = surface.coords(positions[pair[1]]);
        let d2: f64 = (0..3).map(|k| (a[k] as f64 - b[k] as f64).powi(2)).sum();
        total += d2.sqrt();
        cumulative.push(total);
    }
    Chain {
        nodes,
        voxels,
        smoothed,
        cumulative,
        length: total * surface.grid.voxel_size,
    }
}

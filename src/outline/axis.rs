//! The axis graph: the straight skeleton without its peripheral arcs and with its short arcs
//! collapsed (seed 003, 3.1, "straight-skeleton simplification").

use super::StraightSkeleton;
use glam::DVec2;

/// An undirected tree of axis nodes in the outline plane.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisGraph {
    /// Node positions, outline units.
    pub nodes: Vec<DVec2>,
    /// Offset time of each node (its distance to the outline edges that define it), outline
    /// units: a local thickness measure.
    pub radii: Vec<f64>,
    /// Edges between nodes (lower index first), no duplicates or loops.
    pub edges: Vec<[usize; 2]>,
}

impl AxisGraph {
    /// Neighbour lists in edge order.
    pub fn neighbours(&self) -> Vec<Vec<usize>> {
        let mut adj = vec![Vec::new(); self.nodes.len()];
        for &[a, b] in &self.edges {
            adj[a].push(b);
            adj[b].push(a);
        }
        adj
    }

    /// Maximal chains of nodes whose inner nodes have two neighbours, each from one
    /// non-sleeve node to another and listed once.
    pub fn branches(&self) -> Vec<Vec<usize>> {
        let adj = self.neighbours();
        let mut out = Vec::new();
        for start in 0..self.nodes.len() {
            if adj[start].len() == 2 {
                continue;
            }
            for &first in &adj[start] {
                let mut chain = vec![start, first];
                let (mut prev, mut at) = (start, first);
                while adj[at].len() == 2 && chain.len() <= self.nodes.len() {
                    let next = if adj[at][0] == prev {
                        adj[at][1]
                    } else {
                        adj[at][0]
                    };
                    prev = at;
                    at = next;
                    chain.push(at);
                }
                if start < at || (start == at && chain[1] < chain[chain.len() - 2]) {
                    out.push(chain);
                }
            }
        }
        out
    }
}

/// Removes the peripheral arcs (those touching a polygon corner) of `skeleton` and collapses
/// the remaining arcs shorter than `collapse_ratio` times their mean length into single nodes
/// (at the mean position of the collapsed nodes, with their largest radius). The result is a
/// tree; an arc that would close a cycle (degenerate input only) is dropped.
pub fn axis_graph(skeleton: &StraightSkeleton, collapse_ratio: f64) -> AxisGraph {
    let first = skeleton.corners;
    let count = skeleton.nodes.len() - first;
    let arcs: Vec<[usize; 2]> = skeleton
        .arcs
        .iter()
        .filter(|a| a[0] >= first && a[1] >= first)
        .map(|a| [a[0] - first, a[1] - first])
        .collect();
    let position = |k: usize| skeleton.nodes[k + first].position;
    let length = |a: &[usize; 2]| position(a[0]).distance(position(a[1]));
    let mean = if arcs.is_empty() {
        0.0
    } else {
        arcs.iter().map(length).sum::<f64>() / arcs.len() as f64
    };
    let mut uf: Vec<usize> = (0..count).collect();
    fn find(uf: &mut [usize], mut x: usize) -> usize {
        while uf[x] != x {
            uf[x] = uf[uf[x]];
            x = uf[x];
        }
        x
    }
    for a in &arcs {
        if length(a) < collapse_ratio * mean {
            let (ra, rb) = (find(&mut uf, a[0]), find(&mut uf, a[1]));
            if ra != rb {
                uf[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    let mut id = vec![usize::MAX; count];
    let mut sums: Vec<(DVec2, f64, f64)> = Vec::new();
    for k in 0..count {
        let r = find(&mut uf, k);
        if id[r] == usize::MAX {
            id[r] = sums.len();
            sums.push((DVec2::ZERO, 0.0, 0.0));
        }
        let s = &mut sums[id[r]];
        s.0 += position(k);
        s.1 += 1.0;
        s.2 = s.2.max(skeleton.nodes[k + first].time);
    }
    let mut graph = AxisGraph {
        nodes: sums.iter().map(|s| s.0 / s.1).collect(),
        radii: sums.iter().map(|s| s.2).collect(),
        edges: Vec::new(),
    };
    let mut forest: Vec<usize> = (0..graph.nodes.len()).collect();
    for a in &arcs {
        let (x, y) = (id[find(&mut uf, a[0])], id[find(&mut uf, a[1])]);
        let (rx, ry) = (find(&mut forest, x), find(&mut forest, y));
        if rx != ry {
            forest[rx.max(ry)] = rx.min(ry);
            graph.edges.push([x.min(y), x.max(y)]);
        }
    }
    graph
}

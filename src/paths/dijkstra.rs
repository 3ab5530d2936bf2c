//! Multi-source, incremental Dijkstra searches over the DMS (dissertation ch.5.2.4) and
//! other voxel graphs.

use super::DmsGraph;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Marks "no parent" in [`Search::parent`].
const NO_PARENT: u32 = u32::MAX;

/// A multi-source shortest-path search (Dijkstra) from a growing set of sources: the one
/// search of the crate, over the DMS ([`Search::add_sources`]) or any graph given by a
/// neighbour function ([`Search::seed`], [`Search::relax`]: interior voxels, a window of them).
///
/// Costs only ever decrease as sources are added, so a search is updated in place: adding
/// sources relaxes outward from them and stops where the old costs are already lower. This is
/// how the path tree keeps its distance to the covered region and its weighted distance to the
/// tree current while it grows ("the coverage can simply be updated in the area surrounding the
/// new extension", ch.5.2.4).
///
/// The heap is ordered by `(cost, position)`, and a cost is replaced only by a strictly lower
/// one, so results are deterministic.
#[derive(Debug, Clone)]
pub struct Search {
    /// Cost per position (`f64::INFINITY` when unreached).
    pub cost: Vec<f64>,
    /// Predecessor on a cheapest path to the sources, [`NO_PARENT`] for sources and unreached;
    /// empty for a search that keeps no paths ([`Search::costs_only`]).
    parent: Vec<u32>,
    heap: BinaryHeap<Reverse<(u64, usize)>>,
}

/// Heap key of a non-negative cost: for non-negative finite floats the IEEE bit patterns sort
/// like the numbers.
#[inline]
fn key(cost: f64) -> u64 {
    cost.to_bits()
}

impl Search {
    /// A search over `n` positions (at most `u32::MAX`) with no sources yet.
    pub fn new(n: usize) -> Self {
        Self {
            cost: vec![f64::INFINITY; n],
            parent: vec![NO_PARENT; n],
            heap: BinaryHeap::new(),
        }
    }

    /// A search over `n` positions that keeps only the costs, not the paths
    /// ([`Search::path_to_source`] and [`Search::parent`] find nothing): for large graphs
    /// such as every voxel of a grid.
    pub fn costs_only(n: usize) -> Self {
        Self {
            cost: vec![f64::INFINITY; n],
            parent: Vec::new(),
            heap: BinaryHeap::new(),
        }
    }

    /// Adds zero-cost `sources` and relaxes outward over the DMS. Entering position `q` from
    /// `p` over a step of length `step` (voxel units) costs `weight(q, step)`, which must be
    /// non-negative.
    pub fn add_sources(
        &mut self,
        graph: &DmsGraph,
        sources: impl IntoIterator<Item = usize>,
        weight: impl Fn(usize, f64) -> f64,
    ) {
        for s in sources {
            self.seed(s, 0.0);
        }
        self.relax(
            |p| graph.neighbours(p).map(|(q, step)| (q, weight(q, step))),
            |_, _| {},
        );
    }

    /// Makes `p` a source of cost `cost` (non-negative) when that is lower than its cost so
    /// far; the search goes on from it at the next [`Search::relax`]. Returns whether it did.
    pub fn seed(&mut self, p: usize, cost: f64) -> bool {
        if cost < self.cost[p] {
            self.cost[p] = cost;
            if let Some(parent) = self.parent.get_mut(p) {
                *parent = NO_PARENT;
            }
            self.heap.push(Reverse((key(cost), p)));
            true
        } else {
            false
        }
    }

    /// Relaxes outward from the positions seeded or lowered since the last call, cheapest
    /// first. `neighbours(p)` gives each position `q` reachable from `p` with the cost of the
    /// step (non-negative); `lowered(p, q)` is called each time `q`'s cost is lowered through
    /// `p` (the last call for `q` names its predecessor on a cheapest path).
    pub fn relax<I>(
        &mut self,
        mut neighbours: impl FnMut(usize) -> I,
        mut lowered: impl FnMut(usize, usize),
    ) where
        I: IntoIterator<Item = (usize, f64)>,
    {
        while let Some(Reverse((k, p))) = self.heap.pop() {
            let cost = self.cost[p];
            if key(cost) != k {
                continue;
            }
            for (q, step) in neighbours(p) {
                let candidate = cost + step;
                if candidate < self.cost[q] {
                    self.cost[q] = candidate;
                    if let Some(parent) = self.parent.get_mut(q) {
                        *parent = p as u32;
                    }
                    lowered(p, q);
                    self.heap.push(Reverse((key(candidate), q)));
                }
            }
        }
    }

    /// The predecessor of `p` on a cheapest path to the sources; `None` for sources, unreached
    /// positions and searches that keep no paths.
    pub fn parent(&self, p: usize) -> Option<usize> {
        self.parent
            .get(p)
            .filter(|&&q| q != NO_PARENT)
            .map(|&q| q as usize)
    }

    /// The cheapest path from `p` back to a source: `p` first, the source last. Empty when `p`
    /// is unreached.
    pub fn path_to_source(&self, p: usize) -> Vec<usize> {
        if !self.cost[p].is_finite() {
            return Vec::new();
        }
        let mut path = vec![p];
        let mut at = p;
        while let Some(q) = self.parent(at) {
            at = q;
            path.push(at);
        }
        path
    }
}

/// Path lengths (voxel units: steps of 1, sqrt 2, sqrt 3) over the DMS from the nearest of
/// `sources`; `f64::INFINITY` where unreachable. The "depth labelling" of ch.5.2.4.
pub fn path_lengths(graph: &DmsGraph, sources: &[usize]) -> Vec<f64> {
    let mut search = Search::new(graph.len());
    search.add_sources(graph, sources.iter().copied(), |_, step| step);
    search.cost
}

#[cfg(test)]
mod tests {
    use super::super::testing::surface;
    use super::*;

    #[test]
    fn path_lengths_along_a_diagonal_line_use_step_lengths() {
        let coords: Vec<[usize; 3]> = (1..6).map(|i| [i, i, 1]).collect();
        let s = surface([8, 8, 3], &coords, 4);
        let graph = DmsGraph::new(&s);
        let d = path_lengths(&graph, &[0]);
        assert!((d[4] - 4.0 * std::f64::consts::SQRT_2).abs() < 1e-12);
        let mut search = Search::new(graph.len());
        search.add_sources(&graph, [4], |_, step| step);
        assert_eq!(search.path_to_source(0), vec![0, 1, 2, 3, 4]);
        // Adding a closer source lowers costs in place.
        search.add_sources(&graph, [0], |_, step| step);
        assert_eq!(search.cost[1], std::f64::consts::SQRT_2);
    }

    #[test]
    fn seeded_costs_spread_over_any_graph_and_report_each_lowering() {
        // A path 0 - 1 - 2 - 3 with unit steps; sources 0 (cost 5) and 3 (cost 0).
        let neighbours = |p: usize| {
            [p.checked_sub(1), (p < 3).then_some(p + 1)]
                .into_iter()
                .flatten()
                .map(|q| (q, 1.0))
        };
        let mut search = Search::costs_only(4);
        assert!(search.seed(0, 5.0));
        assert!(search.seed(3, 0.0));
        assert!(!search.seed(3, 1.0));
        let mut from = [usize::MAX; 4];
        search.relax(neighbours, |p, q| from[q] = p);
        assert_eq!(search.cost, vec![3.0, 2.0, 1.0, 0.0]);
        assert_eq!(from, [1, 2, 3, usize::MAX]);
        assert_eq!(search.parent(0), None);
        assert_eq!(search.path_to_source(0), vec![0]);
    }
}

//! The heart of the DMS and the heart radius (dissertation ch.5.2.4).

use super::{path_lengths, DmsGraph, PathOptions};
use rayon::prelude::*;

/// Number of depth labellings run in parallel before their sums are added (bounds memory).
const BATCH: usize = 16;

/// The heart: a DMS voxel centrally located with respect to the connectivity of the DMS.
#[derive(Debug, Clone)]
pub struct Heart {
    /// DMS position of the heart.
    pub position: usize,
    /// Depth (path length over the DMS, voxel units) of every DMS position from the heart;
    /// `f64::INFINITY` outside the heart's component.
    pub depth: Vec<f64>,
    /// The heart radius: path length from the heart to the deepest DMS voxel, voxel units.
    pub radius: f64,
    /// DMS position of the deepest voxel (the lowest position among equals).
    pub deepest: usize,
    /// Number of depth labellings whose sums chose the heart.
    pub sources: usize,
    /// Whether every voxel of the component was a source (the exact heart).
    pub exact: bool,
    /// Depth sum of every DMS position over the depth labellings (voxel units; the heart has
    /// the minimum); `f64::INFINITY` outside the heart's component. Normalised between its
    /// minimum and maximum it is the *heart value* of the level graph (ch.7.3.1).
    pub sums: Vec<f64>,
}

/// The heart of component `component` of `graph`: the voxel of minimum depth sum over depth
/// labellings from a set of sources (ch.5.2.4), the lowest position among equals.
///
/// Sources: every voxel of the component when it has at most
/// [`PathOptions::exact_heart_max`] voxels, else [`PathOptions::heart_samples`] voxels evenly
/// spaced through the component in grid order. Deterministic: the labellings run in parallel
/// but their sums are added in source order.
pub fn heart(graph: &DmsGraph, component: u32, options: &PathOptions) -> Heart {
    let members: Vec<usize> = (0..graph.len())
        .filter(|&p| graph.component(p) == component)
        .collect();
    let exact = members.len() <= options.exact_heart_max;
    let sources: Vec<usize> = if exact {
        members.clone()
    } else {
        let k = options.heart_samples.clamp(1, members.len());
        (0..k).map(|i| members[i * members.len() / k]).collect()
    };
    let mut sums = vec![0.0f64; graph.len()];
    for batch in sources.chunks(BATCH) {
        let depths: Vec<Vec<f64>> = batch
            .par_iter()
            .map(|&s| path_lengths(graph, &[s]))
            .collect();
        for depth in &depths {
            for &p in &members {
                sums[p] += depth[p];
            }
        }
    }
    let mut position = members[0];
    for &p in &members {
        if sums[p] < sums[position] {
            position = p;
        }
    }
    let depth = path_lengths(graph, &[position]);
    let mut in_component = vec![false; graph.len()];
    for &p in &members {
        in_component[p] = true;
    }
    for (p, sum) in sums.iter_mut().enumerate() {
        if !in_component[p] {
            *sum = f64::INFINITY;
        }
    }
    let mut deepest = position;
    for &p in &members {
        if depth[p] > depth[deepest] {
            deepest = p;
        }
    }
    Heart {
        position,
        radius: depth[deepest],
        depth,
        deepest,
        sources: sources.len(),
        exact,
        sums,
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::surface;
    use super::*;

    #[test]
    fn heart_of_a_line_is_its_middle_exact_and_sampled() {
        let coords: Vec<[usize; 3]> = (1..12).map(|i| [i, 2, 2]).collect();
        let s = surface([13, 5, 5], &coords, 4);
        let graph = DmsGraph::new(&s);
        let h = heart(&graph, 0, &PathOptions::default());
        assert!(h.exact);
        assert_eq!(h.position, 5);
        assert_eq!(h.radius, 5.0);
        let sampled = PathOptions {
            exact_heart_max: 0,
            heart_samples: 5,
            ..Default::default()
        };
        // Sources 0, 2, 4, 6, 8: the median is 4.
        let h = heart(&graph, 0, &sampled);
        assert!(!h.exact);
        assert_eq!(h.sources, 5);
        assert_eq!(h.position, 4);
    }
}

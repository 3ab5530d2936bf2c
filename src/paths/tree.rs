//! Growth of the path tree (dissertation ch.5.2.4).

use super::{
    chains, extreme_points, heart, Chain, Coverage, DmsGraph, ExtremePoint, PathError, PathOptions,
    Search,
};
use crate::medial::MedialSurface;
use crate::voxel::Grid;
use glam::DVec3;
use serde::Serialize;

/// Marks "not a path-tree voxel" in the per-position node table.
const NOT_IN_TREE: u32 = u32::MAX;

/// The path tree of a DMS: a tree of voxel pathways from the heart region into every
/// significant protrusion, with its chains smoothed (ch.5.2.4).
#[derive(Debug, Clone, Serialize)]
pub struct PathTree {
    /// The grid of the medial surface.
    pub grid: Grid,
    /// Linear grid indices of the path-tree voxels, in order of addition (the first is the
    /// deepest extreme point, the tree's root).
    pub voxels: Vec<usize>,
    /// Parent of each voxel (index into `voxels`, always lower); `None` for the root.
    pub parents: Vec<Option<usize>>,
    /// Squared distance-map value of each voxel, voxel units squared (its sphere's radius is the
    /// square root).
    pub squared: Vec<u32>,
    /// The chains, ordered away from the root.
    pub chains: Vec<Chain>,
    /// Linear grid index of the heart voxel.
    pub heart: usize,
    /// World centre of the heart voxel, mesh units.
    pub heart_centre: DVec3,
    /// Heart radius (path length from the heart to the deepest DMS voxel), mesh units.
    pub heart_radius: f64,
    /// Heart radius, voxel units.
    pub heart_radius_voxels: f64,
    /// Whether the heart is exact (all voxels as sources) or from a deterministic sample.
    pub heart_exact: bool,
    /// The extreme points, ordered by DMS position.
    pub extreme_points: Vec<ExtremePoint>,
    /// Indices into `extreme_points` of the points branches were grown to, in growth order.
    pub branch_ends: Vec<usize>,
    /// DMS voxels covered by the tree's spheres when growth stopped.
    pub covered_voxels: usize,
    /// Things worth telling the user (a disconnected DMS, a single-voxel tree...).
    pub warnings: Vec<String>,
}

impl PathTree {
    /// World centre of path-tree voxel `node`, mesh units.
    pub fn centre(&self, node: usize) -> DVec3 {
        self.grid.centre(self.grid.coords(self.voxels[node]))
    }
}

/// Grows the path tree of `surface` (ch.5.2.4).
///
/// Phases: the heart and heart radius ([`heart`]); the extreme points and their groups
/// ([`extreme_points`]); growth from the deepest extreme point, each step covering the DMS with
/// the new voxels' spheres ([`Coverage`]), choosing the uncovered extreme point of an unreached
/// group farthest (path length) from the covered region, stopping when that distance is below
/// `closeness * heart_radius`, and appending the path of minimum weight `sum 1/d^3` (`d` the
/// squared distance-map value) to the tree; finally the chains and their smoothing ([`chains`]).
/// When the DMS is disconnected, only its largest component is used (with a warning).
///
/// # Errors
/// [`PathError`] for out-of-range options or an empty surface.
pub fn path_tree(surface: &MedialSurface, options: &PathOptions) -> Result<PathTree, PathError> {
    options.validate()?;
    if surface.is_empty() {
        return Err(PathError::EmptySurface);
    }
    let mut warnings = Vec::new();
    let graph = DmsGraph::new(surface);
    let component = graph.largest_component().ok_or(PathError::EmptySurface)?;
    if graph.components() > 1 {
        warnings.push(format!(
            "the medial surface has {} connected parts: the path tree covers the largest ({} of {} voxels)",
            graph.components(),
            graph.component_size(component),
            graph.len()
        ));
    }
    let heart = heart(&graph, component, options);
    let extremes = extreme_points(surface, &graph, &heart.depth, options);

    // The root: the extreme point deepest from the heart (the heart itself if there is none).
    let mut root = heart.position;
    let mut root_extreme = None;
    for (i, e) in extremes.iter().enumerate() {
        if root_extreme.is_none() || e.depth > heart.depth[root] {
            root = e.position;
            root_extreme = Some(i);
        }
    }
    let groups = extremes.iter().map(|e| e.group + 1).max().unwrap_or(0);
    let mut reached = vec![false; groups];
    let mut branch_ends = Vec::new();
    if let Some(i) = root_extreme {
        reached[extremes[i].group] = true;
        branch_ends.push(i);
    }

    let n = graph.len();
    let mut node_of = vec![NOT_IN_TREE; n];
    let mut positions = Vec::new();
    let mut parents: Vec<Option<usize>> = Vec::new();
    let mut coverage = Coverage::new(surface);
    let mut to_covered = Search::new(n);
    let mut to_tree = Search::new(n);
    let weight = |q: usize, _step: f64| (surface.squared[q] as f64).powi(3).recip();
    let mut newly = Vec::new();
    let mut grow = |path: &[usize],
                    attach: Option<usize>,
                    node_of: &mut Vec<u32>,
                    positions: &mut Vec<usize>,
                    parents: &mut Vec<Option<usize>>,
                    to_covered: &mut Search,
                    to_tree: &mut Search| {
        let mut parent = attach;
        newly.clear();
        for &p in path {
            node_of[p] = positions.len() as u32;
            parents.push(parent);
            parent = Some(positions.len());
            positions.push(p);
            coverage.cover(surface, p, &mut newly);
        }
        to_tree.add_sources(&graph, path.iter().copied(), weight);
        to_covered.add_sources(&graph, newly.iter().copied(), |_, step| step);
        coverage.count()
    };
    let mut covered_voxels = grow(
        &[root],
        None,
        &mut node_of,
        &mut positions,
        &mut parents,
        &mut to_covered,
        &mut to_tree,
    );

    let threshold = options.closeness * heart.radius;
    loop {
        // Step 2: the uncovered extreme point of an unreached group farthest from coverage.
        let mut best: Option<usize> = None;
        for (i, e) in extremes.iter().enumerate() {
            let d = to_covered.cost[e.position];
            if reached[e.group] || !d.is_finite() || d == 0.0 {
                continue;
            }
            if best.is_none_or(|b| d > to_covered.cost[extremes[b].position]) {
                best = Some(i);
            }
        }
        let Some(best) = best else { break };
        let target = extremes[best].position;
        if to_covered.cost[target] < threshold {
            break;
        }
        // Steps 3 and 4: the minimum-weight path to the tree, appended from the tree outward.
        let mut path = to_tree.path_to_source(target);
        let Some(attach) = path.pop().map(|p| node_of[p] as usize) else {
            break;
        };
        path.reverse();
        reached[extremes[best].group] = true;
        branch_ends.push(best);
        covered_voxels = grow(
            &path,
            Some(attach),
            &mut node_of,
            &mut positions,
            &mut parents,
            &mut to_covered,
            &mut to_tree,
        );
    }

    let chains = chains(surface, &positions, &parents, options.smoothing_radius);
    if chains.is_empty() {
        warnings.push(
            "the path tree is a single voxel: the figure is too small for its voxel size, use a smaller voxel size"
                .to_string(),
        );
    }
    let voxel_size = surface.grid.voxel_size;
    Ok(PathTree {
        grid: surface.grid,
        voxels: positions.iter().map(|&p| surface.voxels[p]).collect(),
        squared: positions.iter().map(|&p| surface.squared[p]).collect(),
        parents,
        chains,
        heart: surface.voxels[heart.position],
        heart_centre: surface.centre(heart.position),
        heart_radius: heart.radius * voxel_size,
        heart_radius_voxels: heart.radius,
        heart_exact: heart.exact,
        extreme_points: extremes,
        branch_ends,
        covered_voxels,
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::super::testing::surface;
    use super::*;

    #[test]
    fn a_plus_shape_grows_four_branches_and_four_chains() {
        let mut coords = Vec::new();
        for i in 1..30 {
            coords.push([i, 15, 2]);
            coords.push([15, i, 2]);
        }
        let s = surface([31, 31, 5], &coords, 1);
        let tree = path_tree(&s, &PathOptions::default()).unwrap();
        // The centre voxel may be skipped by a diagonal step between two arms.
        assert!(tree.voxels.len() >= s.len() - 1);
        assert_eq!(tree.branch_ends.len(), 4);
        let mut degree = vec![0; tree.voxels.len()];
        for (node, parent) in tree.parents.iter().enumerate() {
            if let Some(parent) = *parent {
                degree[node] += 1;
                degree[parent] += 1;
            }
        }
        assert_eq!(degree.iter().filter(|&&d| d == 1).count(), 4);
        assert!(tree.chains.len() >= 4);
        assert!(tree.warnings.is_empty());
    }

    #[test]
    fn a_single_voxel_gives_a_single_node_tree_with_a_warning() {
        let s = surface([3, 3, 3], &[[1, 1, 1]], 1);
        let tree = path_tree(&s, &PathOptions::default()).unwrap();
        assert_eq!(tree.voxels.len(), 1);
        assert!(tree.chains.is_empty());
        assert_eq!(tree.warnings.len(), 1);
    }
}

//! Growth of the path tree (dissertation ch.5.2.4).

use super::{
    chains, extreme_points, heart, Chain, Coverage, DmsGraph, ExtremePoint, PathError, PathOptions,
    Search,
};
use crate::medial::MedialSurface;
use crate::voxel::Grid;
use crate::warning::Severity;
use glam::DVec3;
use serde::Serialize;
use std::fmt;

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
    #[serde(serialize_with = "crate::warning::serialize_records")]
    pub warnings: Vec<PathWarning>,
}

impl PathTree {
    /// World centre of path-tree voxel `node`, mesh units.
    pub fn centre(&self, node: usize) -> DVec3 {
        self.grid.centre(self.grid.coords(self.voxels[node]))
    }
}

/// The path tree while it grows: its voxels and parents, the coverage of the DMS by their
/// spheres, and the searches from the covered region and from the tree.
struct Growth<'a> {
    surface: &'a MedialSurface,
    graph: &'a DmsGraph,
    /// Per DMS position, its node in the tree ([`NOT_IN_TREE`] if none).
    node_of: Vec<u32>,
    /// DMS position of each tree node, in order of addition.
    positions: Vec<usize>,
    /// Parent node of each tree node.
    parents: Vec<Option<usize>>,
    coverage: Coverage,
    /// Path length from the covered region.
    to_covered: Search,
    /// Minimum path weight (`sum 1/d^3`) to the tree.
    to_tree: Search,
    /// Scratch: the voxels the last step covered.
    newly: Vec<usize>,
}

impl<'a> Growth<'a> {
    fn new(surface: &'a MedialSurface, graph: &'a DmsGraph) -> Self {
        let n = graph.len();
        Self {
            surface,
            graph,
            node_of: vec![NOT_IN_TREE; n],
            positions: Vec::new(),
            parents: Vec::new(),
            coverage: Coverage::new(surface),
            to_covered: Search::new(n),
            to_tree: Search::new(n),
            newly: Vec::new(),
        }
    }

    /// Appends `path` (DMS positions, from the tree outward) below node `attach`, covers
    /// its spheres and extends both searches; returns the covered voxel count.
    fn grow(&mut self, path: &[usize], attach: Option<usize>) -> usize {
        let surface = self.surface;
        let weight = |q: usize, _step: f64| (surface.squared[q] as f64).powi(3).recip();
        let mut parent = attach;
        self.newly.clear();
        for &p in path {
            self.node_of[p] = self.positions.len() as u32;
            self.parents.push(parent);
            parent = Some(self.positions.len());
            self.positions.push(p);
            self.coverage.cover(surface, p, &mut self.newly);
        }
        self.to_tree
            .add_sources(self.graph, path.iter().copied(), weight);
        self.to_covered
            .add_sources(self.graph, self.newly.iter().copied(), |_, step| step);
        self.coverage.count()
    }
}

/// Step 2: the uncovered extreme point of an unreached group farthest (`cost`: path length)
/// from the covered region; `None` when every group is reached or out of reach.
fn farthest_unreached(extremes: &[ExtremePoint], reached: &[bool], cost: &[f64]) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (i, e) in extremes.iter().enumerate() {
        let d = cost[e.position];
        if reached[e.group] || !d.is_finite() || d == 0.0 {
            continue;
        }
        if best.is_none_or(|b| d > cost[extremes[b].position]) {
            best = Some(i);
        }
    }
    best
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
        warnings.push(PathWarning::SeveralParts {
            parts: graph.components(),
            covered: graph.component_size(component),
            voxels: graph.len(),
        });
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

    let mut tree = Growth::new(surface, &graph);
    let mut covered_voxels = tree.grow(&[root], None);

    let threshold = options.closeness * heart.radius;
    // Step 2: the uncovered extreme point of an unreached group farthest from coverage.
    while let Some(best) = farthest_unreached(&extremes, &reached, &tree.to_covered.cost) {
        let target = extremes[best].position;
        if tree.to_covered.cost[target] < threshold {
            break;
        }
        // Steps 3 and 4: the minimum-weight path to the tree, appended from the tree outward.
        let mut path = tree.to_tree.path_to_source(target);
        let Some(attach) = path.pop().map(|p| tree.node_of[p] as usize) else {
            break;
        };
        path.reverse();
        reached[extremes[best].group] = true;
        branch_ends.push(best);
        covered_voxels = tree.grow(&path, Some(attach));
    }

    let Growth {
        positions, parents, ..
    } = tree;
    let chains = chains(surface, &positions, &parents, options.smoothing_radius);
    if chains.is_empty() {
        warnings.push(PathWarning::SingleVoxel);
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

/// Something about a path tree the user should know.
#[derive(Debug, Clone, PartialEq)]
pub enum PathWarning {
    /// The medial surface is disconnected: the tree covers its largest part only.
    SeveralParts {
        /// Connected parts of the medial surface.
        parts: usize,
        /// Voxels of the largest part.
        covered: usize,
        /// Voxels of the medial surface.
        voxels: usize,
    },
    /// The tree is a single voxel: the figure is too small for its voxel size.
    SingleVoxel,
}

impl PathWarning {
    /// How much it matters.
    pub fn severity(&self) -> Severity {
        Severity::Degraded
    }

    /// A stable snake_case id of the variant.
    pub fn code(&self) -> &'static str {
        match self {
            Self::SeveralParts { .. } => "several_parts",
            Self::SingleVoxel => "single_voxel",
        }
    }
}

impl fmt::Display for PathWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::SeveralParts {
                parts,
                covered,
                voxels,
            } => write!(
                f,
                "the medial surface has {parts} connected parts: the path tree covers the largest ({covered} of {voxels} voxels)"
            ),
            Self::SingleVoxel => write!(
                f,
                "the path tree is a single voxel: the figure is too small for its voxel size, use a smaller voxel size"
            ),
        }
    }
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
        assert_eq!(tree.warnings, [PathWarning::SingleVoxel]);
    }
}

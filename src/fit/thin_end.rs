//! A thin part's end past its medial surface: a tail a few voxels across has no medial voxels
//! over its last stretch (squared-distance-1 voxels are never DMS voxels), so its medial path
//! stops far short of the mesh's tip (a rat's tail: half its length). The part's interior
//! voxels ([`Labelling::interior_parts`]) still reach the tip; the path is carried on through
//! them.

use crate::anatomy::Labelling;
use crate::paths::Search;
use crate::voxel::NEIGHBOURS_26;

/// The part's interior voxels (grid indices, ascending) and their 26-neighbours among them
/// (local indices, with step lengths).
struct PartVoxels<'a> {
    labelling: &'a Labelling,
    part: u32,
    voxels: Vec<usize>,
}

impl PartVoxels<'_> {
    fn local(&self, index: usize) -> Option<usize> {
        self.voxels.binary_search(&index).ok()
    }

    /// Grid neighbours of local voxel `i`: `(grid index, step length)`.
    fn grid_neighbours(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let grid = self.labelling.grid;
        let coords = grid.coords(self.voxels[i]);
        NEIGHBOURS_26
            .iter()
            .filter_map(move |n| Some((grid.offset(coords, n.offset)?, n.distance)))
    }

    /// Neighbours of local voxel `i` in the part: `(local index, step length)`.
    fn neighbours(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        self.grid_neighbours(i)
            .filter_map(|(q, d)| Some((self.local(q)?, d)))
    }

    /// Whether local voxel `i` touches an interior voxel of another part (the part's base).
    fn at_base(&self, i: usize) -> bool {
        let interior = &self.labelling.interior_parts;
        self.grid_neighbours(i).any(|(q, _)| {
            let other = interior[q];
            other != u32::MAX && other != self.part
        })
    }

    fn search(&self, sources: impl IntoIterator<Item = usize>) -> Search {
        let mut search = Search::new(self.voxels.len());
        for s in sources {
            search.seed(s, 0.0);
        }
        search.relax(|p| self.neighbours(p), |_, _| {});
        search
    }
}

/// The voxel path (grid indices, `end` excluded, the tip last) that carries a path ending at
/// grid voxel `end` of part `part` on to the part's tip: the part's interior voxel farthest
/// from its base (where it touches the rest of the figure) through the part, when that is
/// farther from the base than `end`. `None` without interior labels, when `end` is not in the
/// part, or when the medial path already reaches the tip.
pub(super) fn thin_end(labelling: &Labelling, part: usize, end: usize) -> Option<Vec<usize>> {
    let part = u32::try_from(part).ok()?;
    let voxels: Vec<usize> = (labelling.interior_parts.iter().enumerate())
        .filter_map(|(i, &p)| (p == part).then_some(i))
        .collect();
    let voxels = PartVoxels {
        labelling,
        part,
        voxels,
    };
    let end = voxels.local(end)?;
    let base: Vec<usize> = (0..voxels.voxels.len())
        .filter(|&i| voxels.at_base(i))
        .collect();
    let from_base = voxels.search(base);
    let tip = (0..voxels.voxels.len())
        .filter(|&i| from_base.cost[i].is_finite())
        .max_by(|&a, &b| {
            from_base.cost[a]
                .total_cmp(&from_base.cost[b])
                .then(b.cmp(&a))
        })?;
    if from_base.cost[tip] <= from_base.cost[end] {
        return None;
    }
    let from_end = voxels.search([end]);
    let mut path = from_end.path_to_source(tip);
    path.pop(); // `end` itself
    path.reverse();
    (!path.is_empty()).then(|| path.into_iter().map(|i| voxels.voxels[i]).collect())
}

//! The discrete medial surface: plain data for the path stages.

use super::MedialWarning;
use crate::voxel::{Grid, NEIGHBOURS_26};
use glam::DVec3;
use serde::Serialize;

/// Why a voxel belongs to the discrete medial surface (ch.4.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum DmsKind {
    /// Its local exposure meets the threshold (and it is not an ignored "1" voxel).
    True,
    /// Its exposure is insufficient, but it connects true DMS voxels: a voxel on a
    /// steepest-ascent bridging path or a saddle point.
    Bridging,
}

/// Marks "not a DMS voxel" in [`MedialSurface::slots`].
pub const NOT_MEDIAL: u32 = u32::MAX;

/// The discrete medial surface (DMS) of a voxelized figure (dissertation ch.4).
///
/// Struct of arrays: the per-voxel fields (`voxels`, `kinds`, `exposure`, `squared`,
/// `component`) are parallel, indexed by a voxel's *position* in `voxels`.
#[derive(Debug, Clone, Serialize)]
pub struct MedialSurface {
    /// The grid of the distance map the surface was extracted from.
    pub grid: Grid,
    /// Linear grid indices of the DMS voxels, ascending.
    pub voxels: Vec<usize>,
    /// Per DMS voxel: true or bridging.
    pub kinds: Vec<DmsKind>,
    /// Per DMS voxel: local exposure (ch.4.2), voxel units, in `[0, 2]`.
    pub exposure: Vec<f64>,
    /// Per DMS voxel: squared distance to the outside, voxel units squared (the radius of its
    /// inscribed sphere is the square root).
    pub squared: Vec<u32>,
    /// Per DMS voxel: its connected component, numbered from 0 in order of the components'
    /// smallest voxel index. The DMS of each 26-connected part of the figure is one
    /// 26-connected component (the invariant of ch.4.3), so a connected figure gives 0
    /// everywhere.
    pub component: Vec<u32>,
    /// Number of components (26-connected parts of the figure).
    pub components: usize,
    /// Linear grid indices of the saddle points (voxels that merged two or more groups of
    /// processed voxels, ch.4.3), ascending. Every saddle point is a DMS voxel.
    pub saddles: Vec<usize>,
    /// Grid-sized lookup: `slots[i]` is voxel `i`'s position in `voxels`, or [`NOT_MEDIAL`].
    /// Derived from `voxels`; keep the two consistent when editing.
    #[serde(skip)]
    pub slots: Vec<u32>,
    /// The exposure threshold used.
    pub exposure_threshold: f64,
    /// Number of interior voxels of the figure.
    pub interior_voxels: usize,
    /// Things worth telling the user (a degenerate DMS, a disconnected figure...).
    #[serde(serialize_with = "crate::warning::serialize_records")]
    pub warnings: Vec<MedialWarning>,
}

impl MedialSurface {
    /// Number of DMS voxels.
    pub fn len(&self) -> usize {
        self.voxels.len()
    }

    /// True when the surface has no voxel ([`dms`](super::dms) never returns one).
    pub fn is_empty(&self) -> bool {
        self.voxels.is_empty()
    }

    /// Whether grid voxel `index` belongs to the DMS. `O(1)`.
    #[inline]
    pub fn contains(&self, index: usize) -> bool {
        self.position(index).is_some()
    }

    /// Position of grid voxel `index` in [`voxels`](Self::voxels), or `None` when it is not a
    /// DMS voxel (or outside the grid). `O(1)`.
    #[inline]
    pub fn position(&self, index: usize) -> Option<usize> {
        match self.slots.get(index) {
            Some(&slot) if slot != NOT_MEDIAL => Some(slot as usize),
            _ => None,
        }
    }

    /// Distance of the DMS voxel at `position` to the outside, voxel units.
    #[inline]
    pub fn distance(&self, position: usize) -> f64 {
        (self.squared[position] as f64).sqrt()
    }

    /// Grid coordinates of the DMS voxel at `position`.
    pub fn coords(&self, position: usize) -> [usize; 3] {
        self.grid.coords(self.voxels[position])
    }

    /// World position (mesh units and frame) of the centre of the DMS voxel at `position`.
    pub fn centre(&self, position: usize) -> DVec3 {
        self.grid.centre(self.coords(position))
    }

    /// The 26-neighbours of the DMS voxel at `position` that belong to the DMS, as
    /// `(position, centre distance in voxel units)`, in
    /// [`NEIGHBOURS_26`](crate::voxel::NEIGHBOURS_26) order.
    pub fn neighbours(&self, position: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let coords = self.coords(position);
        NEIGHBOURS_26.iter().filter_map(move |n| {
            let index = self.grid.offset(coords, n.offset)?;
            Some((self.position(index)?, n.distance))
        })
    }

    /// Number of true DMS voxels.
    pub fn true_count(&self) -> usize {
        self.kinds.iter().filter(|&&k| k == DmsKind::True).count()
    }

    /// Number of bridging DMS voxels (saddle points below the threshold included).
    pub fn bridging_count(&self) -> usize {
        self.len() - self.true_count()
    }

    /// Sizes of the 26-connected components of the DMS voxels, counted by a breadth-first
    /// search over [`neighbours`](Self::neighbours) (independently of
    /// [`component`](Self::component)), largest first. A check for tests and reports.
    pub fn connected_component_sizes(&self) -> Vec<usize> {
        let mut seen = vec![false; self.len()];
        let mut sizes = Vec::new();
        let mut queue = Vec::new();
        for start in 0..self.len() {
            if seen[start] {
                continue;
            }
            seen[start] = true;
            queue.push(start);
            let mut size = 0;
            while let Some(p) = queue.pop() {
                size += 1;
                for (q, _) in self.neighbours(p) {
                    if !seen[q] {
                        seen[q] = true;
                        queue.push(q);
                    }
                }
            }
            sizes.push(size);
        }
        sizes.sort_unstable_by(|a, b| b.cmp(a));
        sizes
    }
}

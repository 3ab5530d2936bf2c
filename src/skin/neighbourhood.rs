//! The neighbours of a voxel by linear index, for the breadth-first and shortest-path sweeps
//! of the skinning stage.

use crate::voxel::{Grid, Neighbour};

/// The neighbours of a voxel in one connectivity: linear index deltas away from the grid
/// border, checked offsets on it (padding keeps mesh voxels off the border, so the slow path
/// is rare).
pub(super) struct Neighbourhood {
    grid: Grid,
    neighbours: &'static [Neighbour],
    deltas: Vec<isize>,
}

impl Neighbourhood {
    /// The neighbourhood `neighbours` (a [`Connectivity`](crate::voxel::Connectivity)'s) on
    /// `grid`.
    pub fn new(grid: Grid, neighbours: &'static [Neighbour]) -> Self {
        let [nx, ny, _] = grid.dims.map(|d| d as isize);
        let deltas = neighbours
            .iter()
            .map(|n| {
                let [ox, oy, oz] = n.offset.map(|o| o as isize);
                ox + nx * (oy + ny * oz)
            })
            .collect();
        Self {
            grid,
            neighbours,
            deltas,
        }
    }

    /// Calls `f` with each neighbour index of voxel `u`, in the connectivity's order.
    #[inline]
    pub fn for_each(&self, u: usize, mut f: impl FnMut(usize)) {
        self.for_each_step(u, |w, _| f(w));
    }

    /// Calls `f` with each neighbour index of voxel `u` and the step to it (its offset and
    /// length), in the connectivity's order.
    #[inline]
    pub fn for_each_step(&self, u: usize, mut f: impl FnMut(usize, &Neighbour)) {
        let [x, y, z] = self.grid.coords(u);
        let [nx, ny, nz] = self.grid.dims;
        if x > 0 && y > 0 && z > 0 && x + 1 < nx && y + 1 < ny && z + 1 < nz {
            for (&d, n) in self.deltas.iter().zip(self.neighbours) {
                f(u.wrapping_add_signed(d), n);
            }
        } else {
            for n in self.neighbours {
                if let Some(w) = self.grid.offset([x, y, z], n.offset) {
                    f(w, n);
                }
            }
        }
    }

    /// Whether `pred` holds for some neighbour of voxel `u`.
    #[inline]
    pub fn any(&self, u: usize, mut pred: impl FnMut(usize) -> bool) -> bool {
        let mut found = false;
        self.for_each(u, |w| found = found || pred(w));
        found
    }
}

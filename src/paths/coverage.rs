//! Coverage of the DMS by the distance-map spheres of path-tree voxels (dissertation ch.5.2.4).

use crate::medial::MedialSurface;

/// Which DMS voxels lie inside the sphere of some path-tree voxel.
///
/// The sphere of a voxel with squared distance `d` has radius `sqrt(d)` (Figure 5.3); a voxel is
/// covered when its centre lies inside or on the sphere, tested exactly on integers
/// (`dx^2 + dy^2 + dz^2 <= d`). Updated incrementally as branches are added.
///
/// The DMS is sparse in the grid, so a sphere is not scanned voxel by voxel: each of its grid
/// rows looks up the DMS voxels of that row (a row index over the surface's ascending voxels).
#[derive(Debug, Clone)]
pub struct Coverage {
    covered: Vec<bool>,
    count: usize,
    /// Per grid row `y + ny z`, the first DMS position at or after the row's first voxel; one
    /// more entry closes the last row.
    rows: Vec<u32>,
}

impl Coverage {
    /// No DMS voxel of `surface` covered.
    pub fn new(surface: &MedialSurface) -> Self {
        let [nx, ny, nz] = surface.grid.dims;
        let mut rows = Vec::with_capacity(ny * nz + 1);
        let mut p = 0;
        for row in 0..=ny * nz {
            while p < surface.voxels.len() && surface.voxels[p] < row * nx {
                p += 1;
            }
            rows.push(p as u32);
        }
        Self {
            covered: vec![false; surface.len()],
            count: 0,
            rows,
        }
    }

    /// Whether DMS position `p` is covered.
    #[inline]
    pub fn is_covered(&self, p: usize) -> bool {
        self.covered[p]
    }

    /// Number of covered DMS voxels.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Covers the DMS voxels inside the sphere of DMS position `p`, appending the positions
    /// newly covered to `newly`, in voxel order. `O(d)` rows for squared distance `d`.
    pub fn cover(&mut self, surface: &MedialSurface, p: usize, newly: &mut Vec<usize>) {
        let d = surface.squared[p] as i64;
        let r = (d as f64).sqrt().floor() as i64;
        let c = surface.coords(p);
        let grid = &surface.grid;
        let lo = |a: usize| (c[a] as i64 - r).max(0) as usize;
        let hi = |a: usize| (c[a] as i64 + r).min(grid.dims[a] as i64 - 1) as usize;
        for z in lo(2)..=hi(2) {
            let dz = z as i64 - c[2] as i64;
            for y in lo(1)..=hi(1) {
                let dy = y as i64 - c[1] as i64;
                let rest = d - dz * dz - dy * dy;
                if rest < 0 {
                    continue;
                }
                let half = (rest as f64).sqrt().floor() as i64;
                let x0 = (c[0] as i64 - half).max(0) as usize;
                let x1 = (c[0] as i64 + half).min(grid.dims[0] as i64 - 1) as usize;
                let row = y + grid.dims[1] * z;
                let (first, end) = (row * grid.dims[0] + x0, row * grid.dims[0] + x1);
                for q in self.rows[row] as usize..self.rows[row + 1] as usize {
                    let i = surface.voxels[q];
                    if i >= first && i <= end && !self.covered[q] {
                        self.covered[q] = true;
                        self.count += 1;
                        newly.push(q);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::surface;
    use super::*;

    #[test]
    fn a_sphere_covers_exactly_the_voxels_within_its_radius() {
        let coords: Vec<[usize; 3]> = (1..20).map(|i| [i, 5, 5]).collect();
        let s = surface([21, 11, 11], &coords, 9);
        let mut coverage = Coverage::new(&s);
        let mut newly = Vec::new();
        coverage.cover(&s, 9, &mut newly);
        // Centre x = 10, radius 3: x in 7..=13.
        newly.sort_unstable();
        assert_eq!(newly, (6..=12).collect::<Vec<_>>());
        newly.clear();
        coverage.cover(&s, 10, &mut newly);
        assert_eq!(newly, vec![13]);
        assert_eq!(coverage.count(), 8);
    }
}

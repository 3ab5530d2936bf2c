//! Coverage of the DMS by the distance-map spheres of path-tree voxels (dissertation ch.5.2.4).

use crate::medial::MedialSurface;

/// Which DMS voxels lie inside the sphere of some path-tree voxel.
///
/// The sphere of a voxel with squared distance `d` has radius `sqrt(d)` (Figure 5.3); a voxel is
/// covered when its centre lies inside or on the sphere, tested exactly on integers
/// (`dx^2 + dy^2 + dz^2 <= d`). Updated incrementally as branches are added.
#[derive(Debug, Clone)]
pub struct Coverage {
    covered: Vec<bool>,
    count: usize,
}

impl Coverage {
    /// No DMS voxel covered, for a surface of `n` voxels.
    pub fn new(n: usize) -> Self {
        Self {
            covered: vec![false; n],
            count: 0,
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
    /// newly covered to `newly`. `O(d^(3/2))` for squared distance `d`.
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
                let row = grid.index([x0, y, z]);
                for i in row..=row + (x1 - x0) {
                    if let Some(q) = surface.position(i) {
                        if !self.covered[q] {
                            self.covered[q] = true;
                            self.count += 1;
                            newly.push(q);
                        }
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
        let mut coverage = Coverage::new(s.len());
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

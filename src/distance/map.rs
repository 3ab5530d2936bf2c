//! The distance map type.

use crate::voxel::Grid;

/// Exact squared Euclidean distance, in voxel units, from each voxel centre to the nearest
/// exterior voxel centre (0 for exterior voxels).
#[derive(Debug, Clone)]
pub struct DistanceMap {
    /// The grid the distances live on.
    pub grid: Grid,
    /// Squared distance per voxel (linear index), voxel units squared.
    pub squared: Vec<u32>,
}

impl DistanceMap {
    /// Distance of voxel `index` to the nearest exterior voxel centre, voxel units.
    #[inline]
    pub fn distance(&self, index: usize) -> f64 {
        (self.squared[index] as f64).sqrt()
    }

    /// Distance (mesh units) from `p` to the figure's outside: the distance-map value of the
    /// voxel holding `p` (the local inscribed radius), 0 outside the figure or the grid.
    pub fn radius_at(&self, p: glam::DVec3) -> f64 {
        self.grid.voxel_at(p).map_or(0.0, |c| {
            self.distance(self.grid.index(c)) * self.grid.voxel_size
        })
    }

    /// The largest distance, voxel units (the radius of the largest inscribed ball).
    pub fn max_distance(&self) -> f64 {
        (self.squared.iter().copied().max().unwrap_or(0) as f64).sqrt()
    }

    /// Linear index of a voxel with the largest distance (the lowest such index).
    pub fn deepest(&self) -> usize {
        let max = self.squared.iter().copied().max().unwrap_or(0);
        self.squared.iter().position(|&d| d == max).unwrap_or(0)
    }
}

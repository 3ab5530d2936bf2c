//! Regular voxel grid geometry and neighbourhoods.

use glam::DVec3;
use serde::Serialize;

/// A regular axis-aligned grid of cubic voxels.
///
/// Voxel `(x, y, z)` occupies `[origin + h*(x,y,z), origin + h*(x+1,y+1,z+1))` with `h` the voxel
/// size in mesh units; its centre is `origin + h*(x+0.5, y+0.5, z+0.5)`. Linear indices run x
/// fastest: `x + dims[0] * (y + dims[1] * z)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Grid {
    /// Number of voxels along x, y and z.
    pub dims: [usize; 3],
    /// World position (mesh units) of the minimum corner of voxel (0, 0, 0).
    pub origin: DVec3,
    /// Edge length of one voxel, mesh units.
    pub voxel_size: f64,
}

/// One neighbour offset with its Euclidean length in voxel units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neighbour {
    /// Offset in voxels.
    pub offset: [i32; 3],
    /// Length of the offset: 1, sqrt 2 or sqrt 3.
    pub distance: f64,
}

/// The 6-, 18- or 26-neighbourhood of a voxel (face, face+edge, face+edge+vertex neighbours).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Connectivity {
    /// Face neighbours (distance 1).
    Six,
    /// Face and edge neighbours (distances 1 and sqrt 2).
    Eighteen,
    /// Face, edge and vertex neighbours (distances 1, sqrt 2 and sqrt 3).
    TwentySix,
}

const fn neighbour_table<const N: usize>(max_nonzero: i32) -> [Neighbour; N] {
    let mut out = [Neighbour {
        offset: [0, 0, 0],
        distance: 0.0,
    }; N];
    let mut n = 0;
    // Order: all faces first, then edges, then corners, so prefixes are the smaller sets.
    let mut k = 1;
    while k <= max_nonzero {
        let mut z = -1;
        while z <= 1 {
            let mut y = -1;
            while y <= 1 {
                let mut x = -1;
                while x <= 1 {
                    let nonzero = (x != 0) as i32 + (y != 0) as i32 + (z != 0) as i32;
                    if nonzero == k {
                        out[n] = Neighbour {
                            offset: [x, y, z],
                            distance: match k {
                                1 => 1.0,
                                2 => std::f64::consts::SQRT_2,
                                _ => 1.732_050_807_568_877_2,
                            },
                        };
                        n += 1;
                    }
                    x += 1;
                }
                y += 1;
            }
            z += 1;
        }
        k += 1;
    }
    out
}

/// All 26 neighbours: the 6 face neighbours first, then the 12 edge neighbours, then the 8
/// corner neighbours, so `&NEIGHBOURS_26[..6]` and `&NEIGHBOURS_26[..18]` are the smaller sets.
pub const NEIGHBOURS_26: [Neighbour; 26] = neighbour_table::<26>(3);

impl Connectivity {
    /// The neighbour offsets of this connectivity with their lengths.
    pub fn neighbours(self) -> &'static [Neighbour] {
        match self {
            Connectivity::Six => &NEIGHBOURS_26[..6],
            Connectivity::Eighteen => &NEIGHBOURS_26[..18],
            Connectivity::TwentySix => &NEIGHBOURS_26[..],
        }
    }
}

impl Grid {
    /// Total number of voxels.
    pub fn len(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    /// True when the grid has no voxels.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Linear index of voxel `(x, y, z)`; the coordinates must be inside the grid.
    #[inline]
    pub fn index(&self, [x, y, z]: [usize; 3]) -> usize {
        debug_assert!(x < self.dims[0] && y < self.dims[1] && z < self.dims[2]);
        x + self.dims[0] * (y + self.dims[1] * z)
    }

    /// Voxel coordinates of a linear index.
    #[inline]
    pub fn coords(&self, index: usize) -> [usize; 3] {
        let x = index % self.dims[0];
        let yz = index / self.dims[0];
        [x, yz % self.dims[1], yz / self.dims[1]]
    }

    /// Linear index of the voxel at `coords + offset`, or `None` outside the grid.
    #[inline]
    pub fn offset(&self, coords: [usize; 3], offset: [i32; 3]) -> Option<usize> {
        let mut c = [0usize; 3];
        for a in 0..3 {
            let v = coords[a] as i64 + offset[a] as i64;
            if v < 0 || v >= self.dims[a] as i64 {
                return None;
            }
            c[a] = v as usize;
        }
        Some(self.index(c))
    }

    /// World position (mesh units) of the centre of voxel `coords`.
    pub fn centre(&self, coords: [usize; 3]) -> DVec3 {
        self.origin
            + self.voxel_size
                * DVec3::new(
                    coords[0] as f64 + 0.5,
                    coords[1] as f64 + 0.5,
                    coords[2] as f64 + 0.5,
                )
    }

    /// Continuous voxel coordinates of a world point: voxel centres sit at `i + 0.5`.
    pub fn to_voxel(&self, world: DVec3) -> DVec3 {
        (world - self.origin) / self.voxel_size
    }

    /// World point of continuous voxel coordinates (inverse of [`Grid::to_voxel`]).
    pub fn to_world(&self, voxel: DVec3) -> DVec3 {
        self.origin + voxel * self.voxel_size
    }

    /// The voxel containing a world point, or `None` outside the grid.
    pub fn voxel_at(&self, world: DVec3) -> Option<[usize; 3]> {
        let v = self.to_voxel(world).floor();
        let mut c = [0usize; 3];
        for a in 0..3 {
            if !(v[a] >= 0.0 && v[a] < self.dims[a] as f64) {
                return None;
            }
            c[a] = v[a] as usize;
        }
        Some(c)
    }

    /// Volume of one voxel, mesh units cubed.
    pub fn voxel_volume(&self) -> f64 {
        self.voxel_size.powi(3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbourhoods_have_expected_sizes_and_distances() {
        assert_eq!(Connectivity::Six.neighbours().len(), 6);
        assert_eq!(Connectivity::Eighteen.neighbours().len(), 18);
        assert_eq!(Connectivity::TwentySix.neighbours().len(), 26);
        for n in NEIGHBOURS_26 {
            let len = (n.offset.iter().map(|&o| (o * o) as f64).sum::<f64>()).sqrt();
            assert!((len - n.distance).abs() < 1e-12);
        }
    }

    #[test]
    fn index_coords_and_world_round_trip() {
        let grid = Grid {
            dims: [5, 7, 3],
            origin: DVec3::new(-1.0, 2.0, 0.5),
            voxel_size: 0.25,
        };
        for i in 0..grid.len() {
            let c = grid.coords(i);
            assert_eq!(grid.index(c), i);
            assert_eq!(grid.voxel_at(grid.centre(c)), Some(c));
        }
        assert_eq!(grid.voxel_at(DVec3::new(-1.01, 2.1, 0.6)), None);
        let p = DVec3::new(0.1, 2.3, 1.0);
        assert!((grid.to_world(grid.to_voxel(p)) - p).length() < 1e-12);
    }
}

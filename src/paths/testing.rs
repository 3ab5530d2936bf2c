//! Test helpers: hand-built medial surfaces.

use crate::medial::{DmsKind, MedialSurface, NOT_MEDIAL};
use crate::voxel::Grid;
use glam::DVec3;

/// A hand-built DMS of the given grid coordinates on a unit-voxel grid at the origin, with the
/// same squared distance everywhere.
pub(crate) fn surface(dims: [usize; 3], coords: &[[usize; 3]], squared: u32) -> MedialSurface {
    let grid = Grid {
        dims,
        origin: DVec3::ZERO,
        voxel_size: 1.0,
    };
    let mut voxels: Vec<usize> = coords.iter().map(|&c| grid.index(c)).collect();
    voxels.sort_unstable();
    voxels.dedup();
    let mut slots = vec![NOT_MEDIAL; grid.len()];
    for (p, &v) in voxels.iter().enumerate() {
        slots[v] = p as u32;
    }
    let n = voxels.len();
    MedialSurface {
        grid,
        voxels,
        kinds: vec![DmsKind::True; n],
        exposure: vec![1.0; n],
        squared: vec![squared; n],
        component: vec![0; n],
        components: 1,
        saddles: Vec::new(),
        slots,
        exposure_threshold: 0.5,
        interior_voxels: n,
        warnings: Vec::new(),
    }
}

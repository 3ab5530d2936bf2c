//! The grid the geodesic weights are computed on when the rig's grid is finer than the
//! default resolution.
//!
//! The geodesic binding's blend widths are set in voxels (`voxel_smoothing_iterations` rounds
//! of diffusion spread a blend by a fixed number of voxels), and they were measured, against
//! the artists' own weights, at the default resolution: a voxel of about 1 % of the figure's
//! longest side (`reports/deformation/`). On a finer grid the same rounds spread a narrower
//! blend, which tears more when a joint turns (the bundled body rigged with `--voxel-size
//! 0.006`: 21 edges past 2x over the sweep instead of 14 at the default size), and the rounds
//! cost as many times more as there are more voxels (the skin of 917,660 interior voxels took
//! 23 s). So the weights of a figure rigged on a fine grid are computed on a copy of its solid
//! resampled to the default resolution, and joint placement keeps the fine grid.

use super::SegmentVoxels;
use crate::distance::DistanceMap;
use crate::voxel::{Grid, Solid};
use glam::DVec3;

/// The voxel edge the weights are measured at, as a fraction of the figure's longest side:
/// [`VoxelOptions`](crate::voxel::VoxelOptions)'s default size.
const SKIN_FRACTION: f64 = 0.01;

/// Coarsening by less than this leaves the grid as it is (a fifth more voxels per edge, about
/// twice the voxels, is worth resampling for). The default grid of a figure that
/// [`voxelize_figure`](crate::voxel::voxelize_figure) refined because it holds too few voxels at
/// the default size is either within this of the default edge or would hold fewer than
/// [`MIN_INTERIOR`] voxels coarsened, so it is never coarsened.
const MIN_FACTOR: f64 = 1.2;

/// The fewest interior voxels the coarse copy may hold:
/// [`VoxelOptions::min_interior`](crate::voxel::VoxelOptions::min_interior)'s default, the
/// resolution the default grid never goes below.
const MIN_INTERIOR: usize = 8000;

/// Padding of the rig's grid (voxels on every side outside the figure's bounding box): the
/// voxelizer's default; the figure's longest side is the grid's longest side without it.
const PADDING: usize = 2;

/// How many times coarser than `solid`'s grid the weights' grid is, or `None` to compute them
/// on `solid` itself: the ratio of the default voxel edge (1 % of the figure's longest side)
/// to the grid's, when it is at least [`MIN_FACTOR`] and the coarser grid still holds about
/// [`MIN_INTERIOR`] interior voxels. A rig at the default size never coarsens.
pub(super) fn coarsening(solid: &Solid) -> Option<f64> {
    let longest = solid.grid.dims.iter().copied().max()?;
    let figure = longest.saturating_sub(2 * PADDING) as f64;
    let factor = SKIN_FRACTION * figure;
    let interior = solid.report.interior_voxels as f64;
    (factor >= MIN_FACTOR && interior / factor.powi(3) >= MIN_INTERIOR as f64).then_some(factor)
}

/// `solid` resampled to voxels `factor` times as large: a coarse voxel is inside when the fine
/// voxel holding its centre is (the voxelizer's own rule, a voxel centre inside the figure,
/// read off the fine grid, so the pieces it joined stay joined), with one outside voxel of
/// padding on every side.
pub(super) fn coarse_solid(solid: &Solid, factor: f64) -> Solid {
    let fine = solid.grid;
    let size = fine.voxel_size * factor;
    let dims = fine
        .dims
        .map(|d| ((d as f64 / factor).ceil() as usize).max(1) + 2);
    let grid = Grid {
        dims,
        origin: fine.origin - DVec3::splat(size),
        voxel_size: size,
    };
    let mut inside = vec![false; grid.len()];
    let mut surface = vec![false; grid.len()];
    for (index, (inside, surface)) in inside.iter_mut().zip(&mut surface).enumerate() {
        if let Some(at) = fine.voxel_at(grid.centre(grid.coords(index))) {
            let at = fine.index(at);
            *inside = solid.inside[at];
            *surface = solid.surface.get(at).copied().unwrap_or(false);
        }
    }
    let mut report = solid.report.clone();
    report.interior_voxels = inside.iter().filter(|&&i| i).count();
    report.surface_voxels = surface.iter().filter(|&&s| s).count();
    Solid {
        grid,
        inside,
        surface,
        report,
    }
}

/// [`coarse_solid`] and its distance map.
pub(super) fn coarse_grid(solid: &Solid, factor: f64) -> (Solid, DistanceMap) {
    let coarse = coarse_solid(solid, factor);
    let distance = crate::distance::edt(&coarse);
    (coarse, distance)
}

/// `segments` (chain voxels of `fine`) on `coarse`: each voxel becomes the coarse voxel holding
/// its centre, ascending, without repeats.
pub(super) fn coarse_segments(
    segments: &[SegmentVoxels],
    fine: &Grid,
    coarse: &Grid,
) -> Vec<SegmentVoxels> {
    segments
        .iter()
        .map(|s| {
            let mut voxels: Vec<usize> = s
                .voxels
                .iter()
                .filter(|&&v| v < fine.len())
                .filter_map(|&v| coarse.voxel_at(fine.centre(fine.coords(v))))
                .map(|c| coarse.index(c))
                .collect();
            voxels.sort_unstable();
            voxels.dedup();
            SegmentVoxels {
                voxels,
                ..s.clone()
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voxel::VoxelReport;

    /// A solid ball of `radius` voxels in the middle of an `n`³ grid of voxels of `size`.
    fn ball(n: usize, radius: f64, size: f64) -> Solid {
        let grid = Grid {
            dims: [n; 3],
            origin: DVec3::ZERO,
            voxel_size: size,
        };
        let centre = DVec3::splat(n as f64 / 2.0);
        let inside: Vec<bool> = (0..grid.len())
            .map(|i| {
                let [x, y, z] = grid.coords(i);
                (DVec3::new(x as f64, y as f64, z as f64) + 0.5 - centre).length() < radius
            })
            .collect();
        let interior_voxels = inside.iter().filter(|&&i| i).count();
        Solid {
            grid,
            surface: vec![false; grid.len()],
            inside,
            report: VoxelReport {
                interior_voxels,
                ..Default::default()
            },
        }
    }

    #[test]
    fn a_default_grid_is_kept_and_a_fine_one_coarsened_to_the_default_edge() {
        // 100 voxels across the figure plus padding: the default size.
        assert_eq!(coarsening(&ball(104, 50.0, 0.01)), None);
        // 200 across: twice as fine, ~524k interior voxels, well above the minimum.
        let fine = ball(204, 100.0, 0.005);
        let factor = coarsening(&fine).expect("a fine grid is coarsened");
        assert!((factor - 2.0).abs() < 1e-12);
        // Twice as fine but too few voxels to coarsen (a thin figure the voxelizer refined).
        let mut thin = ball(204, 20.0, 0.005);
        thin.report.interior_voxels = 30_000;
        assert_eq!(coarsening(&thin), None);
    }

    #[test]
    fn the_coarse_ball_keeps_its_volume_and_padding() {
        let fine = ball(204, 100.0, 0.005);
        let coarse = coarse_solid(&fine, 2.0);
        assert_eq!(coarse.grid.voxel_size, 0.01);
        let volume = |s: &Solid| s.report.interior_voxels as f64 * s.grid.voxel_volume();
        let (a, b) = (volume(&fine), volume(&coarse));
        assert!((a - b).abs() < 0.03 * a, "fine {a} coarse {b}");
        // Every voxel on the border of the coarse grid is outside.
        let [nx, ny, nz] = coarse.grid.dims;
        for (i, &inside) in coarse.inside.iter().enumerate() {
            let [x, y, z] = coarse.grid.coords(i);
            if x == 0 || y == 0 || z == 0 || x + 1 == nx || y + 1 == ny || z + 1 == nz {
                assert!(!inside);
            }
        }
    }

    #[test]
    fn segment_voxels_land_in_the_coarse_voxels_holding_them() {
        let fine = ball(204, 100.0, 0.005);
        let coarse = coarse_solid(&fine, 2.0);
        let along: Vec<usize> = (60..140).map(|x| fine.grid.index([x, 102, 102])).collect();
        let segments = vec![SegmentVoxels {
            joint: crate::skeleton::JointId(0),
            child: None,
            tip: None,
            voxels: along,
        }];
        let out = coarse_segments(&segments, &fine.grid, &coarse.grid);
        // 80 fine voxels in a row are 40 coarse ones, each inside.
        assert_eq!(out[0].voxels.len(), 40);
        assert!(out[0].voxels.windows(2).all(|w| w[0] < w[1]));
        assert!(out[0].voxels.iter().all(|&v| coarse.inside[v]));
    }
}

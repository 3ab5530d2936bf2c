//! The voxelization driver: grid sizing, classification, component filtering.

use super::components::keep_largest_component;
use super::figure::{figure_mesh, LeftOut};
use super::surface::surface_voxels;
use super::winding::winding_votes;
use super::{Grid, Solid, VoxelError, VoxelOptions, VoxelReport, VoxelSize};
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// Voxelizes `mesh` into a [`Solid`].
///
/// Phases: leave out connected pieces lying apart from the figure (pieces whose bounding box
/// does not meet the largest piece's, enlarged by a tenth of its longest side, when that piece
/// holds at least 60 % of the surface area; [`VoxelReport::left_out_pieces`]); size the grid
/// around the bounding box (padded by `options.padding` outside voxels);
/// classify every voxel centre by the six-direction winding-number vote (see the module docs of
/// `voxel::winding`: exact for closed meshes, robust to holes, non-manifold edges and
/// overlapping parts; the absolute winding is used, so inward-wound meshes work too); mark the
/// voxels the triangles touch; keep the largest 26-connected interior component.
///
/// # Errors
/// [`VoxelError::NoTriangles`] for a mesh without triangles, [`VoxelError::InvalidSize`],
/// [`VoxelError::Flat`] for a bounding box without volume, [`VoxelError::TooLarge`] when the grid
/// would exceed `options.max_voxels` (the error names a voxel size that fits), and
/// [`VoxelError::EmptyInterior`] when no voxel centre is inside.
pub fn voxelize(mesh: &Mesh, options: &VoxelOptions) -> Result<Solid, VoxelError> {
    let figure = figure_mesh(mesh);
    let (mesh, left_out) = match &figure {
        Some((figure, left_out)) => (figure, *left_out),
        None => (mesh, LeftOut::default()),
    };
    let grid = grid_of(mesh, options)?;
    let h = grid.voxel_size;
    let corners: Vec<[DVec3; 3]> = (0..mesh.triangles.len())
        .map(|t| mesh.corners(t).map(|p| (p - grid.origin) / h))
        .collect();

    let votes = winding_votes(&grid, &corners);
    let threshold = 6.0 * options.inside_threshold;
    let [nx, ny, nz] = grid.dims;
    // Classify slice by slice; the outermost layer of the grid stays outside whatever the votes
    // (open sheets can push a few votes outside the bounding box).
    let classified: Vec<(Vec<bool>, usize)> = (0..nz)
        .into_par_iter()
        .map(|z| {
            let mut slice = vec![false; nx * ny];
            let mut ambiguous = 0;
            if z == 0 || z + 1 == nz {
                return (slice, 0);
            }
            for y in 1..ny - 1 {
                for x in 1..nx - 1 {
                    let counts = votes.counts([x, y, z]);
                    let sum: i32 = counts.iter().map(|&c| c as i32).sum();
                    if (sum as f64).abs() > threshold {
                        slice[x + nx * y] = true;
                        if counts.iter().any(|&c| c != counts[0]) {
                            ambiguous += 1;
                        }
                    }
                }
            }
            (slice, ambiguous)
        })
        .collect();
    let ambiguous_voxels = classified.iter().map(|c| c.1).sum();
    let mut inside: Vec<bool> = Vec::with_capacity(grid.len());
    for (slice, _) in classified {
        inside.extend(slice);
    }
    drop(votes);
    let surface = surface_voxels(&grid, &corners);
    let (components, dropped_voxels) = keep_largest_component(&grid, &mut inside);
    let interior_voxels = inside.iter().filter(|&&b| b).count();
    if interior_voxels == 0 {
        return Err(VoxelError::EmptyInterior { voxel_size: h });
    }
    let report = VoxelReport {
        interior_voxels,
        surface_voxels: surface.iter().filter(|&&b| b).count(),
        components,
        dropped_voxels,
        ambiguous_voxels,
        left_out_pieces: left_out.pieces,
        left_out_triangles: left_out.triangles,
        left_out_area_share: left_out.area_share,
    };
    Ok(Solid {
        grid,
        inside,
        surface,
        report,
    })
}

/// The grid `voxelize` would use for `mesh`, without voxelizing.
///
/// # Errors
/// As [`voxelize`], except `EmptyInterior`.
pub fn grid_for(mesh: &Mesh, options: &VoxelOptions) -> Result<Grid, VoxelError> {
    let figure = figure_mesh(mesh);
    grid_of(figure.as_ref().map_or(mesh, |f| &f.0), options)
}

fn grid_of(mesh: &Mesh, options: &VoxelOptions) -> Result<Grid, VoxelError> {
    let (min, max) = mesh.bounding_box().ok_or(VoxelError::NoTriangles)?;
    let extent = max - min;
    let longest = extent.max_element();
    if !extent.is_finite() || extent.min_element() <= 0.0 {
        return Err(VoxelError::Flat {
            extent: extent.to_array(),
        });
    }
    let h = match options.size {
        VoxelSize::Absolute(h) if h > 0.0 && h.is_finite() => h,
        VoxelSize::Fraction(f) if f > 0.0 && f <= 1.0 => f * longest,
        VoxelSize::Absolute(value) | VoxelSize::Fraction(value) => {
            return Err(VoxelError::InvalidSize { value })
        }
    };
    let pad = options.padding.max(1);
    let dims_for = |h: f64| -> [usize; 3] {
        let d = |k: usize| (extent[k] / h).ceil().max(1.0) as usize + 2 * pad;
        [d(0), d(1), d(2)]
    };
    let dims = dims_for(h);
    let voxels = dims.iter().try_fold(1usize, |acc, &d| acc.checked_mul(d));
    if voxels.is_none_or(|v| v > options.max_voxels) {
        // Smallest size that fits: start from the volume ratio and grow by 0.5 % steps.
        let ratio =
            dims.iter().map(|&d| d as f64).product::<f64>() / options.max_voxels.max(1) as f64;
        let mut fit = h * ratio.cbrt().max(1.0);
        while dims_for(fit).iter().map(|&d| d as f64).product::<f64>() > options.max_voxels as f64 {
            fit *= 1.005;
        }
        return Err(VoxelError::TooLarge {
            dims,
            voxels: voxels.unwrap_or(usize::MAX),
            budget: options.max_voxels,
            fitting_size: fit,
            fitting_fraction: fit / longest,
        });
    }
    // Align voxel boundaries with the minimum corner: a flat face there is then sampled exactly,
    // and each axis rounds to the nearest voxel rather than up to a whole extra one.
    Ok(Grid {
        dims,
        origin: min - DVec3::splat(pad as f64 * h),
        voxel_size: h,
    })
}

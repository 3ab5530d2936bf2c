//! The voxelization driver: grid sizing, classification, component filtering.

use super::duplicates::redundant_triangles;
use super::figure::{figure_mesh, LeftOut};
use super::join::join_pieces;
use super::outlier::far_outlier;
use super::sizing::grid_of;
use super::surface::surface_voxels;
use super::winding::winding_votes;
use super::{Grid, Solid, VoxelError, VoxelOptions, VoxelReport, VoxelSize};
use crate::mesh::Mesh;
use glam::DVec3;
use rayon::prelude::*;

/// [`voxelize_figure`] shrinks the voxel edge at most to this fraction.
const MAX_REFINE: f64 = 0.5;

/// Voxelizes a figure to be rigged: [`voxelize`], then, when the size is a fraction of the
/// longest side and the figure holds fewer than [`VoxelOptions::min_interior`] interior voxels,
/// once more with the voxel edge shrunk by the cube root of the shortfall, at most to half
/// (within `max_voxels`; the first grid stands when the finer one fails). The solid's
/// [`VoxelReport::refined_from`] gives the size first tried.
///
/// # Errors
/// As [`voxelize`] on the first grid.
pub fn voxelize_figure(mesh: &Mesh, options: &VoxelOptions) -> Result<Solid, VoxelError> {
    let solid = voxelize(mesh, options)?;
    let interior = solid.report.interior_voxels;
    let VoxelSize::Fraction(fraction) = options.size else {
        return Ok(solid);
    };
    if interior == 0 || interior >= options.min_interior {
        return Ok(solid);
    }
    // A little finer than the cube root (the interior grows a little slower than the volume:
    // fewer boundary voxels count as inside on a coarse grid), and at most twice as fine
    // (eight times the voxels): a figure holding a few dozen voxels is degenerate or flat, and
    // a grid sized to its shortfall would run into `max_voxels`.
    let shrink = (0.97 * (interior as f64 / options.min_interior as f64).cbrt()).max(MAX_REFINE);
    let finer = VoxelOptions {
        size: VoxelSize::Fraction(fraction * shrink),
        ..*options
    };
    match voxelize(mesh, &finer) {
        Ok(mut refined) => {
            refined.report.refined_from = Some((fraction, interior));
            Ok(refined)
        }
        Err(_) => Ok(solid),
    }
}

/// Voxelizes `mesh` into a [`Solid`].
///
/// Phases: leave out connected pieces lying apart from the figure (the figure grows from the
/// largest piece by the pieces whose bounding box meets its own, enlarged by a tenth of the
/// largest piece's longest side; the rest is left out when the figure holds at least 60 % of
/// the surface area; [`VoxelReport::left_out_pieces`]); size the grid
/// around the bounding box (padded by `options.padding` outside voxels);
/// leave repeated triangles out of the vote (the same three vertices twice with the same
/// winding, or the reversed twins of a closed double-sided shell: see `voxel::duplicates`;
/// [`VoxelReport::duplicate_triangles`]);
/// classify every voxel centre by the six-direction winding-number vote (see the module docs of
/// `voxel::winding`: exact for closed meshes, robust to holes, non-manifold edges and
/// overlapping parts; the absolute winding is used, so inward-wound meshes work too; each
/// direction adds at most one, `MAX_COUNT_PER_DIRECTION`, so stacked open sheets do not outvote
/// the other directions); mark the
/// voxels the triangles touch; keep the largest 26-connected interior component.
///
/// # Errors
/// What [`VoxelOptions::validate`] reports for invalid options,
/// [`VoxelError::NoTriangles`] for a mesh without triangles, [`VoxelError::Flat`] for a
/// bounding box without volume, [`VoxelError::TooLarge`] when the grid would exceed
/// `options.max_voxels` (the error names a voxel size that fits), [`VoxelError::OutOfMemory`]
/// when the grid's working memory exceeds the memory available, [`VoxelError::Outlier`] when no
/// voxel centre is inside because a vertex far outside the rest stretched the grid, and
/// [`VoxelError::EmptyInterior`] when no voxel centre is inside otherwise.
pub fn voxelize(mesh: &Mesh, options: &VoxelOptions) -> Result<Solid, VoxelError> {
    let figure = figure_mesh(mesh);
    let (mesh, left_out) = match figure {
        Some((ref figure, ref left_out)) => (figure, left_out.clone()),
        None => (mesh, LeftOut::default()),
    };
    let grid = grid_of(mesh, options)?;
    let h = grid.voxel_size;
    let (redundant, duplicate_triangles) = redundant_triangles(mesh);
    let mut corners: Vec<[DVec3; 3]> =
        Vec::with_capacity(mesh.triangles.len().saturating_sub(duplicate_triangles));
    corners.extend(
        (0..mesh.triangles.len())
            .filter(|&t| !redundant[t])
            .map(|t| mesh.corners(t).map(|p| (p - grid.origin) / h)),
    );

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
                    let sum: i32 = counts.iter().map(|&c| clamp_count(c)).sum();
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
    let longest = grid.dims.iter().max().copied().unwrap_or(0);
    let reach = (options.join_gap * longest.saturating_sub(2 * options.padding) as f64).round();
    let joining = join_pieces(&grid, &mut inside, reach as usize);
    if std::env::var_os("SKELFIT_DEBUG_JOIN").is_some() {
        eprintln!("join: {joining:?} reach {reach}");
    }
    let interior_voxels = inside.iter().filter(|&&b| b).count();
    if interior_voxels == 0 {
        if let Some((vertex, position, core)) = far_outlier(mesh) {
            return Err(VoxelError::Outlier {
                vertex,
                position: position.to_array(),
                core_size: core,
                voxel_size: h,
            });
        }
        return Err(VoxelError::EmptyInterior { voxel_size: h });
    }
    let report = VoxelReport {
        interior_voxels,
        surface_voxels: surface.iter().filter(|&&b| b).count(),
        components: joining.components,
        joined_pieces: joining.joined,
        widest_gap: joining.widest_gap as f64 * h,
        bridge_voxels: joining.bridge_voxels,
        dropped_voxels: joining.dropped_voxels,
        dropped_pieces: joining.dropped,
        ambiguous_voxels,
        left_out_pieces: left_out.pieces,
        left_out_triangles: left_out.triangles,
        left_out_area_share: left_out.area_share,
        refined_from: None,
        duplicate_triangles,
        props: left_out.props,
        sheets: left_out.sheets,
        sheet_vertices: left_out.sheet_vertices,
    };
    Ok(Solid {
        grid,
        inside,
        surface,
        report,
    })
}

/// The most one direction's crossing count adds to the vote, either sign: each of the six
/// directions says once whether it sees the point enclosed. Two closed shells overlapping (an
/// eye pushed into a head) are inside as one shell is, and a larger count is a stack of open
/// sheets crossed the same way (hair cards, layered skirt panels), not a deeper inside.
/// Summed unclamped, one ray through five cards outvoted the other five directions: every
/// voxel of the column behind them, far outside the figure, was inside (a bundled body with
/// 150 hair cards grew bars of voxels across the grid and was rigged as no humanoid at all).
/// Clamped to two, the space between the cards of a hanging curtain of hair still voted
/// inside, and the head's slices ran on down the back.
const MAX_COUNT_PER_DIRECTION: i32 = 1;

/// One direction's crossing count as it enters the vote ([`MAX_COUNT_PER_DIRECTION`]).
fn clamp_count(count: i8) -> i32 {
    i32::from(count).clamp(-MAX_COUNT_PER_DIRECTION, MAX_COUNT_PER_DIRECTION)
}

/// The grid `voxelize` would use for `mesh`, without voxelizing.
///
/// # Errors
/// As [`voxelize`], except `EmptyInterior`.
pub fn grid_for(mesh: &Mesh, options: &VoxelOptions) -> Result<Grid, VoxelError> {
    let figure = figure_mesh(mesh);
    grid_of(figure.as_ref().map_or(mesh, |f| &f.0), options)
}

//! Per-voxel and per-mesh-vertex labels from the labelled DMS voxels.

use crate::medial::MedialSurface;
use crate::mesh::Mesh;
use crate::paths::Search;
use crate::voxel::{Solid, NEIGHBOURS_26};
use rayon::prelude::*;

/// Marks "no part".
pub const NO_PART: u32 = u32::MAX;

/// Part of every interior voxel: the part of the DMS voxel `c` minimising the path length from
/// `c` through the interior (26-neighbour steps of length 1, sqrt 2, sqrt 3) minus
/// `radius_weight` times `c`'s inscribed radius (0: the nearest centre; 1: the nearest sphere
/// surface, which keeps the trunk's skin beside a limb from going to the limb, whose thin
/// spheres have centres near the surface). One multi-source
/// Dijkstra, ties to the lower voxel index, so the result is deterministic. Exterior voxels
/// get [`NO_PART`].
pub fn interior_parts(
    solid: &Solid,
    surface: &MedialSurface,
    voxel_parts: &[u32],
    radius_weight: f64,
) -> Vec<u32> {
    let sources = interior_sources(solid, surface, |p| voxel_parts[p] != NO_PART, radius_weight);
    parts_from_sources(&sources, voxel_parts)
}

/// The search of [`interior_parts`] with the DMS voxels for which `seeded` holds as its
/// sources: per grid voxel, the DMS position (index into the surface's voxels) whose part
/// [`interior_parts`] gives it, [`NO_PART`] for exterior and unreached voxels. The sources
/// depend only on which DMS voxels are seeded, not on their parts, so one search serves every
/// labelling of the same seeds ([`parts_from_sources`]).
pub fn interior_sources(
    solid: &Solid,
    surface: &MedialSurface,
    seeded: impl Fn(usize) -> bool,
    radius_weight: f64,
) -> Vec<u32> {
    let grid = solid.grid;
    let mut source = vec![NO_PART; grid.len()];
    let mut search = Search::costs_only(grid.len());
    // Costs are offset by the largest radius so that they stay non-negative (the heap orders
    // non-negative floats by their bits).
    let largest = (0..surface.len())
        .map(|p| radius_weight * surface.distance(p))
        .fold(0.0, f64::max);
    for (p, &index) in surface.voxels.iter().enumerate() {
        if seeded(p) && solid.inside[index] {
            let c = largest - radius_weight * surface.distance(p);
            if search.seed(index, c) {
                source[index] = p as u32;
            }
        }
    }
    search.relax(
        |index| {
            let coords = grid.coords(index);
            NEIGHBOURS_26.iter().filter_map(move |n| {
                let q = grid.offset(coords, n.offset)?;
                solid.inside[q].then_some((q, n.distance))
            })
        },
        |from, to| source[to] = source[from],
    );
    source
}

/// Per grid voxel, the part of its source ([`interior_sources`]) in `voxel_parts` (per DMS
/// position); [`NO_PART`] where it has none.
pub fn parts_from_sources(sources: &[u32], voxel_parts: &[u32]) -> Vec<u32> {
    sources
        .iter()
        .map(|&p| {
            if p == NO_PART {
                NO_PART
            } else {
                voxel_parts[p as usize]
            }
        })
        .collect()
}

/// Part of every mesh vertex: the part of the labelled voxel whose centre is nearest, searched
/// in growing cubes around the vertex's voxel (vertices lie on the surface, often in exterior
/// voxels). [`NO_PART`] only when no voxel of the grid is labelled. The vertices are looked
/// at in parallel (each on its own).
pub fn mesh_parts(mesh: &Mesh, solid: &Solid, parts: &[u32]) -> Vec<u32> {
    let grid = solid.grid;
    let max_radius = grid.dims.iter().copied().max().unwrap_or(0) as i64;
    mesh.positions
        .par_iter()
        .with_min_len(1024)
        .map(|&x| {
            let v = grid.to_voxel(x) - glam::DVec3::splat(0.5);
            let c = [v.x.round() as i64, v.y.round() as i64, v.z.round() as i64];
            let mut radius = 1i64;
            while radius <= max_radius {
                let mut best: Option<(f64, usize)> = None;
                for dz in -radius..=radius {
                    for dy in -radius..=radius {
                        for dx in -radius..=radius {
                            let q = [c[0] + dx, c[1] + dy, c[2] + dz];
                            if q.iter()
                                .zip(grid.dims)
                                .any(|(&a, d)| a < 0 || a >= d as i64)
                            {
                                continue;
                            }
                            let coords = [q[0] as usize, q[1] as usize, q[2] as usize];
                            let index = grid.index(coords);
                            if parts[index] == NO_PART {
                                continue;
                            }
                            let d = grid.centre(coords).distance_squared(x);
                            if best.is_none_or(|(bd, bi)| d < bd || (d == bd && index < bi)) {
                                best = Some((d, index));
                            }
                        }
                    }
                }
                if let Some((_, index)) = best {
                    return parts[index];
                }
                radius *= 2;
            }
            NO_PART
        })
        .collect()
}

//! The solid's boundary as a closed triangle mesh: the faces between inside and outside voxels,
//! smoothed (Taubin's λ|μ filter, "A signal processing approach to fair surface design", 1995)
//! so that slices through it are round loops rather than staircases.
//!
//! A figure made of many shells (a head, hands, eyes, clothes over a body) slices into many
//! loops per plane; its joined voxel solid slices into one loop per body part. The slicing
//! refinement uses this surface when the input is not one closed shell.

use super::Solid;
use crate::mesh::Mesh;
use glam::DVec3;

/// Taubin's shrink factor (positive pass).
const LAMBDA: f64 = 0.5;
/// Taubin's inflate factor (negative pass); |μ| > λ keeps the volume (pass band k ≈ 0.1).
const MU: f64 = -0.53;

/// The closed surface of `solid`'s inside voxels, every face between an inside voxel and an
/// outside one (or the grid's edge) as two outward-facing triangles, vertices shared at voxel
/// corners, then `smoothing` λ|μ iteration pairs. Empty for an empty solid.
pub fn boundary_mesh(solid: &Solid, smoothing: usize) -> Mesh {
    let grid = &solid.grid;
    let [dx, dy, dz] = grid.dims;
    let corner_dims = [dx + 1, dy + 1, dz + 1];
    let corner_index = |[x, y, z]: [usize; 3]| x + corner_dims[0] * (y + corner_dims[1] * z);
    let mut vertex_of: Vec<u32> = vec![u32::MAX; corner_dims[0] * corner_dims[1] * corner_dims[2]];
    let mut positions: Vec<DVec3> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let filled = without_cavities(solid);
    let inside = |c: [i64; 3]| -> bool {
        if c.iter()
            .zip(grid.dims)
            .any(|(&v, d)| v < 0 || v >= d as i64)
        {
            return false;
        }
        filled[grid.index([c[0] as usize, c[1] as usize, c[2] as usize])]
    };
    for (i, _) in filled.iter().enumerate().filter(|(_, &v)| v) {
        let c = grid.coords(i);
        let ci = c.map(|v| v as i64);
        for (axis, sign) in FACES {
            let mut n = ci;
            n[axis] += sign;
            if inside(n) {
                continue;
            }
            let quad = face_corners(c, axis, sign);
            let ids = quad.map(|corner| {
                let slot = &mut vertex_of[corner_index(corner)];
                if *slot == u32::MAX {
                    *slot = positions.len() as u32;
                    positions.push(
                        grid.origin + grid.voxel_size * DVec3::from(corner.map(|v| v as f64)),
                    );
                }
                *slot
            });
            triangles.push([ids[0], ids[1], ids[2]]);
            triangles.push([ids[0], ids[2], ids[3]]);
        }
    }
    let mut mesh = Mesh {
        positions,
        triangles,
    };
    taubin(&mut mesh, smoothing);
    mesh
}

/// The inside mask with enclosed cavities filled: every outside voxel that the grid's border
/// does not reach through face-adjacent outside voxels (the hollow of a head modelled as a thin
/// shell, gaps between a body and the clothes around it) counts as inside, so that the boundary
/// is the figure's outer surface only.
fn without_cavities(solid: &Solid) -> Vec<bool> {
    let grid = &solid.grid;
    let dims = grid.dims;
    let mut outside = vec![false; solid.inside.len()];
    let mut stack: Vec<usize> = Vec::new();
    for (i, &inside) in solid.inside.iter().enumerate() {
        let c = grid.coords(i);
        let border = (0..3).any(|k| c[k] == 0 || c[k] + 1 == dims[k]);
        if border && !inside {
            outside[i] = true;
            stack.push(i);
        }
    }
    while let Some(i) = stack.pop() {
        let c = grid.coords(i);
        for (axis, sign) in FACES {
            let v = c[axis] as i64 + sign;
            if v < 0 || v >= dims[axis] as i64 {
                continue;
            }
            let mut n = c;
            n[axis] = v as usize;
            let j = grid.index(n);
            if !solid.inside[j] && !outside[j] {
                outside[j] = true;
                stack.push(j);
            }
        }
    }
    outside.iter().map(|&o| !o).collect()
}

/// The six face directions: axis and sign.
const FACES: [(usize, i64); 6] = [(0, 1), (0, -1), (1, 1), (1, -1), (2, 1), (2, -1)];

/// The four corners of voxel `c`'s face on `axis` at side `sign`, counter-clockwise seen from
/// outside (along +`sign` on `axis`).
fn face_corners(c: [usize; 3], axis: usize, sign: i64) -> [[usize; 3]; 4] {
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let at = |du: usize, dv: usize| {
        let mut p = c;
        if sign > 0 {
            p[axis] += 1;
        }
        p[u] += du;
        p[v] += dv;
        p
    };
    // (u, v, axis) is right-handed, so u then v turns counter-clockwise about +axis.
    if sign > 0 {
        [at(0, 0), at(1, 0), at(1, 1), at(0, 1)]
    } else {
        [at(0, 0), at(0, 1), at(1, 1), at(1, 0)]
    }
}

/// `iterations` Taubin λ|μ pairs with uniform (umbrella) weights over the mesh's edges.
fn taubin(mesh: &mut Mesh, iterations: usize) {
    if iterations == 0 || mesh.positions.is_empty() {
        return;
    }
    let n = mesh.positions.len();
    let mut edges: Vec<(u32, u32)> = mesh
        .triangles
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let mut sum = vec![DVec3::ZERO; n];
    let mut count = vec![0u32; n];
    for _ in 0..iterations {
        for factor in [LAMBDA, MU] {
            sum.iter_mut().for_each(|s| *s = DVec3::ZERO);
            count.iter_mut().for_each(|c| *c = 0);
            for &(a, b) in &edges {
                let (a, b) = (a as usize, b as usize);
                sum[a] += mesh.positions[b];
                sum[b] += mesh.positions[a];
                count[a] += 1;
                count[b] += 1;
            }
            for ((p, s), &k) in mesh.positions.iter_mut().zip(&sum).zip(&count) {
                if k > 0 {
                    *p += factor * (*s / f64::from(k) - *p);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voxel::{voxelize, VoxelOptions, VoxelSize};

    #[test]
    fn a_cube_solid_gives_a_closed_outward_surface_of_its_volume() {
        let cube = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        let options = VoxelOptions {
            size: VoxelSize::Fraction(0.1),
            ..VoxelOptions::default()
        };
        let solid = voxelize(&cube, &options).unwrap();
        let surface = boundary_mesh(&solid, 0);
        let stats = surface.stats();
        assert!(stats.closed, "{stats:?}");
        assert_eq!(stats.components, 1);
        let inside = solid.inside.iter().filter(|&&v| v).count() as f64;
        let volume = stats.signed_volume.unwrap();
        let expected = inside * solid.grid.voxel_size.powi(3);
        assert!(
            (volume - expected).abs() < 1e-9 * expected.max(1.0),
            "{volume} vs {expected}"
        );
        // Smoothing rounds the corners but keeps the volume within a few percent.
        let smooth = boundary_mesh(&solid, 10).stats();
        let v = smooth.signed_volume.unwrap();
        assert!(
            v > 0.9 * expected && v < 1.05 * expected,
            "{v} vs {expected}"
        );
    }

    #[test]
    fn an_empty_solid_gives_an_empty_mesh() {
        let cube = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        let mut solid = voxelize(&cube, &VoxelOptions::default()).unwrap();
        solid.inside.iter_mut().for_each(|v| *v = false);
        let surface = boundary_mesh(&solid, 5);
        assert!(surface.positions.is_empty() && surface.triangles.is_empty());
    }
}

//! Conservative rasterisation of triangles into the voxels they touch.
//!
//! A voxel is a surface voxel when the closed triangle intersects the closed voxel cube, decided
//! by the separating-axis test of Akenine-Möller ("Fast 3D triangle-box overlap testing", 2001):
//! the three box normals, the triangle normal and the nine edge cross products.

use super::Grid;
use glam::DVec3;
use rayon::prelude::*;

/// True when triangle `tri` (voxel coordinates) overlaps the box of half-size `half` at `centre`.
pub(crate) fn triangle_box_overlap(tri: [DVec3; 3], centre: DVec3, half: f64) -> bool {
    let v = tri.map(|p| p - centre);
    let e = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
    // Nine edge-axis cross products.
    for edge in e {
        for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
            let a = axis.cross(edge);
            if a == DVec3::ZERO {
                continue;
            }
            let p = v.map(|x| x.dot(a));
            let r = half * (a.x.abs() + a.y.abs() + a.z.abs());
            let (lo, hi) = (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]));
            if lo > r || hi < -r {
                return false;
            }
        }
    }
    // Box face normals: bounding-box overlap.
    let lo = v[0].min(v[1]).min(v[2]);
    let hi = v[0].max(v[1]).max(v[2]);
    if lo.max_element() > half || hi.min_element() < -half {
        return false;
    }
    // Triangle plane.
    let n = e[0].cross(e[1]);
    let d = n.dot(v[0]);
    let r = half * (n.x.abs() + n.y.abs() + n.z.abs());
    d.abs() <= r
}

/// Marks every voxel of `grid` that a triangle touches. `corners` are in voxel coordinates.
pub(crate) fn surface_voxels(grid: &Grid, corners: &[[DVec3; 3]]) -> Vec<bool> {
    let dims = grid.dims;
    let mut touched: Vec<usize> = corners
        .par_chunks(1024)
        .flat_map_iter(|chunk| {
            let mut out = Vec::new();
            for &tri in chunk {
                let lo = tri[0].min(tri[1]).min(tri[2]).floor();
                let hi = tri[0].max(tri[1]).max(tri[2]).floor();
                let clamp = |x: f64, k: usize| x.clamp(0.0, dims[k] as f64 - 1.0) as usize;
                let (x0, y0, z0) = (clamp(lo.x, 0), clamp(lo.y, 1), clamp(lo.z, 2));
                let (x1, y1, z1) = (clamp(hi.x, 0), clamp(hi.y, 1), clamp(hi.z, 2));
                let single = x0 == x1 && y0 == y1 && z0 == z1;
                for z in z0..=z1 {
                    for y in y0..=y1 {
                        for x in x0..=x1 {
                            let centre = DVec3::new(x as f64 + 0.5, y as f64 + 0.5, z as f64 + 0.5);
                            if single || triangle_box_overlap(tri, centre, 0.5) {
                                out.push(x + dims[0] * (y + dims[1] * z));
                            }
                        }
                    }
                }
            }
            out
        })
        .collect();
    touched.par_sort_unstable();
    touched.dedup();
    let mut surface = vec![false; grid.len()];
    for i in touched {
        surface[i] = true;
    }
    surface
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlap_test_separates_and_touches() {
        let tri = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        assert!(triangle_box_overlap(tri, DVec3::new(0.2, 0.2, 0.4), 0.5));
        assert!(!triangle_box_overlap(tri, DVec3::new(0.2, 0.2, 0.6), 0.5));
        // Beyond the hypotenuse but inside the bounding box.
        assert!(!triangle_box_overlap(tri, DVec3::new(1.3, 1.3, 0.0), 0.25));
        assert!(triangle_box_overlap(tri, DVec3::new(0.6, 0.6, 0.0), 0.25));
    }
}

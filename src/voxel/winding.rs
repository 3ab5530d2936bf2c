//! Inside/outside classification by ray-crossing winding numbers along six axis directions.
//!
//! For a voxel centre `p` and a ray direction `r`, the signed crossing count (exits minus
//! entries of an outward-wound surface along the ray) is the winding number of the surface
//! around `p` whenever the surface is closed. The *generalised* winding number of an open,
//! non-manifold or multi-part surface is the average of that count over all ray directions
//! (Jacobson, Kavan and Sorkine-Hornung 2013, "Robust inside-outside segmentation using
//! generalized winding numbers"). We estimate it with the six axis directions +x, -x, +y, -y,
//! +z, -z: exact for closed surfaces (every direction gives the same integer), while a hole
//! disturbs only the rays that pass through it, so `mean > 0.5` still classifies the voxel
//! correctly as long as most of the six rays see a closed surface. Overlapping parts (an eye
//! pushed into a head) add up to winding 2 and stay inside, which a parity (even-odd) test
//! would get wrong. Each direction's count enters the mean clamped to ±1 (`voxelize`): a ray
//! through a stack of open sheets wound the same way (hair cards) counts one per sheet, and
//! would otherwise outvote the five directions that see nothing.
//!
//! All six counts come from one scan per axis: the crossings of every grid column (a line
//! through voxel centres parallel to the axis) with every triangle. Columns hit a shared edge
//! or vertex exactly once thanks to a symbolic perturbation of the column point (the
//! rasterisers' top-left rule), so closed meshes give exact integer counts.

use super::Grid;
use glam::DVec3;
use rayon::prelude::*;

/// One crossing of a column with a triangle.
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd)]
struct Crossing {
    column: u32,
    /// Position of the crossing along the column, continuous voxel coordinates.
    depth: f64,
    /// +1 when the ray towards +axis enters the surface there, -1 when it exits.
    entering: i8,
}

/// The six signed crossing counts of every voxel centre: `[towards -axis, towards +axis]` for
/// each axis. The x and y arrays use the grid's layout (`x + nx (y + ny z)`); the z array is
/// stored y-major (`x + nx (z + nz y)`) so that each y owns a contiguous block while it is filled.
/// Reading all three for consecutive x is contiguous in every array.
pub(crate) struct WindingVotes {
    dims: [usize; 3],
    x: Vec<[i8; 2]>,
    y: Vec<[i8; 2]>,
    z: Vec<[i8; 2]>,
}

impl WindingVotes {
    /// The six counts of voxel `[x, y, z]`.
    #[inline]
    pub fn counts(&self, [x, y, z]: [usize; 3]) -> [i8; 6] {
        let [nx, ny, nz] = self.dims;
        let i = x + nx * (y + ny * z);
        let a = self.x[i];
        let b = self.y[i];
        let c = self.z[x + nx * (z + nz * y)];
        [a[0], a[1], b[0], b[1], c[0], c[1]]
    }
}

/// Sign of the canonical edge function of edge (p, q) at point x, with the symbolic
/// perturbation x + eps*(1, eps^2) that breaks ties consistently between the two triangles
/// that share the edge: both compute exactly the same (negated) value.
#[inline]
fn edge_side(p: [f64; 2], q: [f64; 2], x: [f64; 2]) -> f64 {
    let (a, b, flip) = if (p[0], p[1]) <= (q[0], q[1]) {
        (p, q, 1.0)
    } else {
        (q, p, -1.0)
    };
    let d = [b[0] - a[0], b[1] - a[1]];
    let value = d[0] * (x[1] - a[1]) - d[1] * (x[0] - a[0]);
    let side = if value != 0.0 {
        value.signum()
    } else if d[1] != 0.0 {
        -d[1].signum()
    } else {
        d[0].signum()
    };
    side * flip
}

/// Crossings of all columns parallel to `axis` with triangle `t`.
fn triangle_crossings(corners: [DVec3; 3], axis: usize, dims: [usize; 3], out: &mut Vec<Crossing>) {
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let proj = corners.map(|c| [c[u], c[v]]);
    let [a, b, c] = proj;
    let orientation = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if orientation == 0.0 || !orientation.is_finite() {
        return; // parallel to the axis: no column crosses it transversally
    }
    let o = orientation.signum();
    let umin = a[0].min(b[0]).min(c[0]);
    let umax = a[0].max(b[0]).max(c[0]);
    let vmin = a[1].min(b[1]).min(c[1]);
    let vmax = a[1].max(b[1]).max(c[1]);
    // Column (i, j) passes through (i + 0.5, j + 0.5).
    let i0 = ((umin - 0.5).ceil().max(0.0)) as usize;
    let i1 = ((umax - 0.5).floor().min(dims[u] as f64 - 1.0)) as i64;
    let j0 = ((vmin - 0.5).ceil().max(0.0)) as usize;
    let j1 = ((vmax - 0.5).floor().min(dims[v] as f64 - 1.0)) as i64;
    if i1 < i0 as i64 || j1 < j0 as i64 {
        return;
    }
    let entering: i8 = if o < 0.0 { 1 } else { -1 };
    for j in j0..=j1 as usize {
        for i in i0..=i1 as usize {
            let x = [i as f64 + 0.5, j as f64 + 0.5];
            if edge_side(a, b, x) != o || edge_side(b, c, x) != o || edge_side(c, a, x) != o {
                continue;
            }
            // Barycentric interpolation of the depth along the axis.
            let wa = (b[0] - x[0]) * (c[1] - x[1]) - (b[1] - x[1]) * (c[0] - x[0]);
            let wb = (c[0] - x[0]) * (a[1] - x[1]) - (c[1] - x[1]) * (a[0] - x[0]);
            let wc = orientation - wa - wb;
            let depth = (wa * corners[0][axis] + wb * corners[1][axis] + wc * corners[2][axis])
                / orientation;
            out.push(Crossing {
                column: (i + dims[u] * j) as u32,
                depth,
                entering,
            });
        }
    }
}

/// Runs the six-direction vote for every voxel centre of `grid`.
///
/// `corners` are the triangles' corners in continuous voxel coordinates.
pub(crate) fn winding_votes(grid: &Grid, corners: &[[DVec3; 3]]) -> WindingVotes {
    let [nx, ny, nz] = grid.dims;
    let columns = [0, 1, 2].map(|axis| ColumnCrossings::new(grid.dims, axis, corners));
    // Axis x: column (y, z) is row y + ny z.
    let mut x = vec![[0i8; 2]; grid.len()];
    x.par_chunks_mut(nx)
        .enumerate()
        .for_each(|(row, out)| columns[0].fill(row, out.iter_mut()));
    // Axis y: column (z, x) lives in z-slice z at stride nx.
    let mut y = vec![[0i8; 2]; grid.len()];
    y.par_chunks_mut(nx * ny)
        .enumerate()
        .for_each(|(z, slice)| {
            for x in 0..nx {
                columns[1].fill(z + nz * x, slice.iter_mut().skip(x).step_by(nx));
            }
        });
    // Axis z: column (x, y), stored in y's block at stride nx.
    let mut zs = vec![[0i8; 2]; grid.len()];
    zs.par_chunks_mut(nx * nz)
        .enumerate()
        .for_each(|(y, block)| {
            for x in 0..nx {
                columns[2].fill(x + nx * y, block.iter_mut().skip(x).step_by(nx));
            }
        });
    WindingVotes {
        dims: grid.dims,
        x,
        y,
        z: zs,
    }
}

/// The crossings of all columns parallel to one axis, bucketed by column.
struct ColumnCrossings {
    /// `starts[c]..starts[c + 1]` indexes column `c`'s crossings in `crossings`.
    starts: Vec<usize>,
    /// `(depth, entering)` pairs, grouped by column (unsorted within a column).
    crossings: Vec<(f64, i8)>,
}

impl ColumnCrossings {
    fn new(dims: [usize; 3], axis: usize, corners: &[[DVec3; 3]]) -> Self {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        let columns = dims[u] * dims[v];
        let found: Vec<Vec<Crossing>> = corners
            .par_chunks(2048)
            .map(|chunk| {
                let mut out = Vec::new();
                for &tri in chunk {
                    triangle_crossings(tri, axis, dims, &mut out);
                }
                out
            })
            .collect();
        // Counting sort by column; chunks are visited in order, so the result is deterministic.
        let mut starts = vec![0usize; columns + 1];
        for c in found.iter().flatten() {
            starts[c.column as usize + 1] += 1;
        }
        for c in 0..columns {
            starts[c + 1] += starts[c];
        }
        let mut fill = starts.clone();
        let mut crossings = vec![(0.0f64, 0i8); starts[columns]];
        for c in found.iter().flatten() {
            let k = &mut fill[c.column as usize];
            crossings[*k] = (c.depth, c.entering);
            *k += 1;
        }
        Self { starts, crossings }
    }

    /// Writes the two counts of every voxel centre along `column` into `out` (in axis order).
    fn fill<'a>(&self, column: usize, out: impl Iterator<Item = &'a mut [i8; 2]>) {
        let list = &self.crossings[self.starts[column]..self.starts[column + 1]];
        if list.is_empty() {
            return;
        }
        let mut list = list.to_vec();
        list.sort_unstable_by(|p, q| p.partial_cmp(q).unwrap_or(std::cmp::Ordering::Equal));
        let total: i32 = list.iter().map(|c| c.1 as i32).sum();
        let mut k = 0;
        let mut before = 0i32;
        for (s, slot) in out.enumerate() {
            let centre = s as f64 + 0.5;
            while k < list.len() && list[k].0 < centre {
                before += list[k].1 as i32;
                k += 1;
            }
            *slot = [clamp_i8(before), clamp_i8(before - total)];
        }
    }
}

fn clamp_i8(v: i32) -> i8 {
    v.clamp(-16, 16) as i8
}

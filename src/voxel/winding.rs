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
//! would get wrong.
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

/// Per-voxel results of the six-direction vote.
pub(crate) struct WindingVotes {
    /// Sum of the six signed crossing counts (six times the winding-number estimate).
    pub sum: Vec<i16>,
    /// Sum of the squares of the six counts: all six agree exactly when `6 * squares == sum^2`.
    pub squares: Vec<i16>,
}

impl WindingVotes {
    /// True where the six counts were not all equal (a hole or a self-intersection nearby).
    pub fn ambiguous(&self, i: usize) -> bool {
        6 * self.squares[i] as i32 != (self.sum[i] as i32).pow(2)
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

/// Index into the voxel array of position `s` along column `column` of `axis`.
#[inline]
fn voxel_of(dims: [usize; 3], axis: usize, column: usize, s: usize) -> usize {
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut c = [0usize; 3];
    c[axis] = s;
    c[u] = column % dims[u];
    c[v] = column / dims[u];
    c[0] + dims[0] * (c[1] + dims[1] * c[2])
}

/// Runs the six-direction vote for every voxel centre of `grid`.
///
/// `corners` are the triangles' corners in continuous voxel coordinates.
pub(crate) fn winding_votes(grid: &Grid, corners: &[[DVec3; 3]]) -> WindingVotes {
    let dims = grid.dims;
    let len = grid.len();
    let mut sum = vec![0i16; len];
    let mut squares = vec![0i16; len];
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        let columns = dims[u] * dims[v];
        let mut crossings: Vec<Crossing> = corners
            .par_chunks(1024)
            .flat_map_iter(|chunk| {
                let mut out = Vec::new();
                for &tri in chunk {
                    triangle_crossings(tri, axis, dims, &mut out);
                }
                out
            })
            .collect();
        crossings.par_sort_unstable_by(|p, q| {
            (p.column, p.depth, p.entering)
                .partial_cmp(&(q.column, q.depth, q.entering))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        let starts = column_starts(&crossings, columns);
        let n = dims[axis];
        // Per column and voxel: the count seen from the -axis side (entries minus exits before
        // the centre) and from the +axis side (exits minus entries after it).
        let per_column: Vec<(usize, Vec<[i8; 2]>)> = (0..columns)
            .into_par_iter()
            .filter(|&col| starts[col] != starts[col + 1])
            .map(|col| {
                let list = &crossings[starts[col]..starts[col + 1]];
                let total: i32 = list.iter().map(|c| c.entering as i32).sum();
                let mut votes = Vec::with_capacity(n);
                let mut k = 0;
                let mut before = 0i32;
                for s in 0..n {
                    let centre = s as f64 + 0.5;
                    while k < list.len() && list[k].depth < centre {
                        before += list[k].entering as i32;
                        k += 1;
                    }
                    votes.push([clamp_i8(before), clamp_i8(before - total)]);
                }
                (col, votes)
            })
            .collect();
        for (col, votes) in per_column {
            for (s, pair) in votes.into_iter().enumerate() {
                let i = voxel_of(dims, axis, col, s);
                for w in pair {
                    sum[i] += w as i16;
                    squares[i] += (w as i16) * (w as i16);
                }
            }
        }
    }
    WindingVotes { sum, squares }
}

fn clamp_i8(v: i32) -> i8 {
    v.clamp(-16, 16) as i8
}

/// `starts[c]..starts[c + 1]` is the range of column `c` in the sorted crossings.
fn column_starts(crossings: &[Crossing], columns: usize) -> Vec<usize> {
    let mut starts = vec![0usize; columns + 1];
    for c in crossings {
        starts[c.column as usize + 1] += 1;
    }
    for c in 0..columns {
        starts[c + 1] += starts[c];
    }
    starts
}

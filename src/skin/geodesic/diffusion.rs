//! The weights of the voxels: the geodesic falloff of each voxel's nearest joints, then
//! rounds of diffusion between face neighbours.

use super::field::Field;
use super::rows::{Mixer, Row, NONE};
use super::LABELS;
use crate::skin::SkinOptions;
use crate::voxel::{Connectivity, Grid};
use rayon::prelude::*;

/// The weight rows of the interior voxels and of the voxels around the vertices, smoothed
/// through the figure.
pub(super) struct VoxelWeights {
    /// Grid voxel → row, `NONE` for voxels without weights.
    pub slot: Vec<u32>,
    /// One row per weighted voxel.
    pub rows: Vec<Row>,
}

/// The weights of every interior voxel and of every `needed` voxel (one flag per grid voxel:
/// those around a vertex) from the geodesic field ([`voxel_row`]), then
/// [`SkinOptions::voxel_smoothing_iterations`] rounds of diffusion ([`diffuse`]).
pub(super) fn smoothed_voxel_weights(
    field: &Field,
    grid: &Grid,
    needed: &[bool],
    options: &SkinOptions,
) -> VoxelWeights {
    let mut slot = vec![NONE; grid.len()];
    let mut voxels: Vec<usize> = field.interior.clone();
    voxels.extend(
        (0..grid.len())
            .filter(|&i| field.nearest[i] != NONE && field.compact[i] == NONE && needed[i]),
    );
    for (k, &index) in voxels.iter().enumerate() {
        slot[index] = k as u32;
    }
    let mut rows: Vec<Row> = voxels
        .par_iter()
        .map_init(Mixer::default, |mixer, &index| {
            voxel_row(field, grid, index, options, mixer)
        })
        .collect();
    if options.voxel_smoothing_iterations > 0 {
        let linked = links(field, grid, &voxels, &slot);
        diffuse(&mut rows, &linked, options.voxel_smoothing_iterations);
    }
    VoxelWeights { slot, rows }
}

/// The weights of the grid voxel `index`: those of its nearest interior voxel, with the
/// distance between the two centres added to every geodesic distance; a joint's weight is
/// [`falloff`] of its distance, tapered linearly to zero where its path is
/// [`SkinOptions::blend_ratio`] times as long as the nearest joint's, pruned to four joints.
fn voxel_row(
    field: &Field,
    grid: &Grid,
    index: usize,
    options: &SkinOptions,
    mixer: &mut Mixer,
) -> Row {
    mixer.clear();
    let c = field.nearest[index];
    if c == NONE {
        return Row::EMPTY;
    }
    let extra = if field.compact[index] == NONE {
        let here = grid.coords(index);
        let there = grid.coords(field.interior[c as usize]);
        let d: f64 = (0..3)
            .map(|a| (here[a] as f64 - there[a] as f64).powi(2))
            .sum();
        d.sqrt()
    } else {
        0.0
    };
    let blend_ratio = options.blend_ratio;
    let slot = c as usize * LABELS;
    for k in 0..LABELS {
        let joint = field.labels[slot + k];
        if joint == NONE {
            break;
        }
        let d = f64::from(field.distances[slot + k]) + extra;
        // Joints whose path is `blend_ratio` times as long as the nearest joint's get nothing,
        // fading linearly from the nearest's length.
        let ratio = (f64::from(field.lengths[slot + k]) + extra)
            / (f64::from(field.lengths[slot]) + extra).max(0.5);
        let taper = ((blend_ratio - ratio) / (blend_ratio - 1.0)).clamp(0.0, 1.0);
        if taper > 0.0 {
            mixer.add(joint, taper * falloff(d, options.falloff));
        }
    }
    mixer.pruned(0.0)
}

/// The weight of a joint at geodesic distance `d` (voxel units), before normalisation.
fn falloff(d: f64, power: f64) -> f64 {
    d.max(0.5).powf(-power)
}

/// Per weighted voxel (`voxels`, grid indices), the rows (`slot`) of its face neighbours
/// that diffusion links it to, `NONE` for the rest: two voxels outside the figure, or one
/// outside and one inside, are linked only where their nearest interior voxels touch, so
/// weights do not cross a gap between two parts (an arm hanging beside the torso).
fn links(field: &Field, grid: &Grid, voxels: &[usize], slot: &[u32]) -> Vec<[u32; 6]> {
    voxels
        .par_iter()
        .map(|&index| {
            let coords = grid.coords(index);
            let home = grid.coords(field.interior[field.nearest[index] as usize]);
            let mut out = [NONE; 6];
            for (slot_out, nb) in out.iter_mut().zip(Connectivity::Six.neighbours()) {
                let Some(next) = grid.offset(coords, nb.offset) else {
                    continue;
                };
                let s = slot[next];
                if s == NONE {
                    continue;
                }
                let there = grid.coords(field.interior[field.nearest[next] as usize]);
                if (0..3).all(|a| home[a].abs_diff(there[a]) <= 1) {
                    *slot_out = s;
                }
            }
            out
        })
        .collect()
}

/// The diffusion of `rows` between `linked` neighbours equivalent to `iterations` rounds of
/// moving every row halfway towards the mean of its face neighbours' (a lazy random walk,
/// variance `iterations / 6` voxels² along each axis), done as three passes of a Gaussian of
/// that variance, one along each axis, each followed by pruning to four joints
/// ([`Mixer::pruned`]). A pass follows the links from each voxel along its axis, so weights
/// do not cross where the links stop (a gap between two parts, the figure's surface) and the
/// kernel is renormalised over the voxels it reaches. Three passes of about `6 sqrt(variance)`
/// taps each cost a tenth of the rounds (`iterations` × 7 rows) at the default.
///
/// The blend between bones then spreads over a few voxels wherever the bones meet (the
/// crotch between the thighs, the armpit), at the same width on any tessellation: the
/// weight field has no steeper slope than the voxels allow, which a fine mesh's short edges
/// would otherwise stretch.
fn diffuse(rows: &mut Vec<Row>, linked: &[[u32; 6]], iterations: usize) {
    let kernel = gaussian(iterations as f64 / 6.0);
    let mut next = vec![Row::EMPTY; rows.len()];
    for axis in 0..3 {
        let [down, up] = axis_links(axis);
        let current: &[Row] = rows;
        next.par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .for_each_init(Mixer::default, |mixer, (v, out)| {
                *out = line_row(current, linked, v, [down, up], &kernel, mixer);
            });
        std::mem::swap(rows, &mut next);
    }
}

/// The taps of a discrete Gaussian of `variance` (voxels²) from the centre outwards,
/// unnormalised (centre 1), out to three standard deviations.
fn gaussian(variance: f64) -> Vec<f64> {
    let reach = (3.0 * variance.sqrt()).ceil() as usize;
    (0..=reach)
        .map(|k| (-((k * k) as f64) / (2.0 * variance)).exp())
        .collect()
}

/// The indices into a voxel's links of its face neighbours below and above it along `axis`.
fn axis_links(axis: usize) -> [usize; 2] {
    let mut out = [0; 2];
    for (k, nb) in Connectivity::Six.neighbours().iter().enumerate() {
        if nb.offset[axis] != 0 {
            out[usize::from(nb.offset[axis] > 0)] = k;
        }
    }
    out
}

/// One pass of [`diffuse`] at row `v`: the `kernel`-weighted sum of the rows reached from `v`
/// along the links `directions` (at most `kernel.len() - 1` steps each way), pruned.
#[inline]
fn line_row(
    rows: &[Row],
    linked: &[[u32; 6]],
    v: usize,
    directions: [usize; 2],
    kernel: &[f64],
    mixer: &mut Mixer,
) -> Row {
    let own = &rows[v];
    // The taps reached: (row, kernel weight).
    let mut taps = [(0u32, 0f64); 2 * MAX_REACH];
    let mut count = 0;
    let mut agree = true;
    let mut same_joints = true;
    for direction in directions {
        let mut at = v;
        for &weight in kernel.iter().skip(1).take(MAX_REACH) {
            let next = linked[at][direction];
            if next == NONE {
                break;
            }
            at = next as usize;
            let row = &rows[at];
            agree &= row == own;
            same_joints &= row.joints == own.joints;
            taps[count] = (next, weight);
            count += 1;
        }
    }
    if agree {
        return *own;
    }
    let taps = &taps[..count];
    let neighbours = || taps.iter().map(|&(u, weight)| (&rows[u as usize], weight));
    if same_joints {
        if let Some(row) = own.blend_same_joints(kernel[0], neighbours()) {
            return row;
        }
    }
    mixer.clear();
    mixer.add_row(own, kernel[0]);
    for (row, weight) in neighbours() {
        mixer.add_row(row, weight);
    }
    mixer.pruned(0.0)
}

/// Most steps a pass of [`diffuse`] takes each way (`voxel_smoothing_iterations` of 10,000,
/// the most [`SkinOptions::validate`] allows, needs 123).
const MAX_REACH: usize = 128;

//! The weights of the voxels: the geodesic falloff of each voxel's nearest joints, then
//! rounds of diffusion between face neighbours.

use super::cell::{blend, Cell, Scratch};
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
/// [`SkinOptions::voxel_smoothing_iterations`] rounds of diffusion ([`diffuse`]) at the rates
/// of [`rates`] (`radius`: each joint's bone radius, voxels).
pub(super) fn smoothed_voxel_weights(
    field: &Field,
    grid: &Grid,
    needed: &[bool],
    options: &SkinOptions,
    radius: &[f64],
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
        let rates = rates(field, &voxels, radius, options.blend_radius);
        diffuse(
            &mut rows,
            &linked,
            &rates,
            options.voxel_smoothing_iterations,
        );
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

/// The diffusion rate of each of `voxels` (grid indices): `(r / blend_radius)²` of its nearest
/// joint's bone radius `r` (voxels), between [`MIN_RATE`] and 1; 1 everywhere when
/// `blend_radius` is 0. A round at rate `a` moves a voxel's weights the fraction `a` of the way
/// to the mean of itself and its neighbours, so the blend spreads `sqrt(a)` times as far: in
/// proportion to the thickness of the body part where it is thinner than `blend_radius`, as
/// bone heat's blend scales with the distance to the bones.
fn rates(field: &Field, voxels: &[usize], radius: &[f64], blend_radius: f64) -> Vec<f64> {
    voxels
        .par_iter()
        .with_min_len(4096)
        .map(|&index| {
            let joint = field.labels[field.nearest[index] as usize * LABELS];
            match radius.get(joint as usize) {
                Some(&r) if blend_radius > 0.0 => (r / blend_radius).powi(2).clamp(MIN_RATE, 1.0),
                _ => 1.0,
            }
        })
        .collect()
}

/// The smallest diffusion rate of [`rates`]: a finger's or a hoof's blend still spreads about
/// a fifth as far as a torso's.
const MIN_RATE: f64 = 0.05;

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

/// `iterations` rounds of diffusion of `rows` between `linked` neighbours: each row becomes
/// the plain mean of itself and its neighbours and is pruned to four joints (the rule of
/// [`Mixer::pruned`]). The blend between bones then spreads over a few voxels wherever the
/// bones meet (the crotch between the thighs, the armpit), at the same width on any
/// tessellation: the weight field has no steeper slope than the voxels allow, which a fine
/// mesh's short edges would otherwise stretch. A round of the plain mean of seven spreads a
/// blend by a variance of 2/7 voxel² per axis (a half step towards the neighbours' mean only
/// 1/6), so 75 rounds spread as far as 128 half steps at 0.59 times the work.
///
/// The rounds run in single precision ([`Cell`]: 32 bytes a row instead of 48; the weights
/// end within about 1e-6 of double precision's). Each round reads the previous round's rows
/// and writes into a second buffer (no allocation per round); a row whose neighbours all
/// equal it stays, one whose neighbours have its joints is blended lane by lane, the others
/// are summed on the stack and pruned ([`blend`]). A row is computed again only where it or
/// one of its neighbours changed in the round before ([`Settled`]); the others keep their
/// value, which both buffers already hold.
///
/// A row whose rate (`rates[v]`, see [`rates`]) is below 1 moves only that fraction of the way
/// to the mean each round.
fn diffuse(rows: &mut [Row], linked: &[[u32; 6]], rates: &[f64], iterations: usize) {
    let joints = rows
        .iter()
        .flat_map(|r| r.entries().map(|(j, _)| j as usize + 1))
        .max()
        .unwrap_or(0);
    let mut cells: Vec<Cell> = rows.iter().map(Cell::of).collect();
    let mut next = cells.clone();
    let mut settled = Settled::new(cells.len());
    for _ in 0..iterations {
        let current: &[Cell] = &cells;
        let moved = &settled.moved;
        next.par_iter_mut()
            .zip(settled.next.par_iter_mut())
            .enumerate()
            .with_min_len(256)
            .for_each_init(
                || Scratch::new(joints),
                |scratch, (v, (out, moves))| {
                    let link = &linked[v];
                    if !moved[v] && link.iter().all(|&u| u == NONE || !moved[u as usize]) {
                        *moves = false;
                        return;
                    }
                    let own = &current[v];
                    let mut others: [&Cell; 6] = [own; 6];
                    let mut count = 0;
                    let mut agree = true;
                    let mut same_joints = true;
                    for &u in link.iter().filter(|&&u| u != NONE) {
                        let c = &current[u as usize];
                        others[count] = c;
                        count += 1;
                        agree &= c == own;
                        same_joints &= c.joints == own.joints;
                    }
                    if agree {
                        *moves = false;
                        return;
                    }
                    let rate = rates[v] as f32;
                    let share = rate / (count + 1) as f32;
                    let keep = 1.0 - rate + share;
                    let cell = blend(own, keep, share, &others[..count], same_joints, scratch);
                    *moves = cell != *own;
                    *out = cell;
                },
            );
        std::mem::swap(&mut cells, &mut next);
        if !settled.advance() {
            break;
        }
    }
    for (row, cell) in rows.iter_mut().zip(&cells) {
        *row = cell.row();
    }
}

/// Which rows changed in the last round of an iteration (every row before the first), and
/// the flags being written in the current one. A row is a function of its own and its
/// neighbours' rows of the round before, so where none of them changed it is the same as
/// before: the same value to the bit, without computing it.
pub(super) struct Settled {
    pub moved: Vec<bool>,
    pub next: Vec<bool>,
}

impl Settled {
    /// `n` rows, all to be computed in the first round.
    pub fn new(n: usize) -> Self {
        Self {
            moved: vec![true; n],
            next: vec![false; n],
        }
    }

    /// Makes the flags written this round the ones read in the next; whether any row moved
    /// (if none did, no later round changes anything).
    pub fn advance(&mut self) -> bool {
        std::mem::swap(&mut self.moved, &mut self.next);
        self.moved.contains(&true)
    }
}

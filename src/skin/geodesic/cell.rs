//! The voxel diffusion's weight rows in single precision: four joints and four `f32` weights
//! in 32 bytes (two SSE registers), half a [`Row`], so that a round of [`diffuse`] over the
//! figure's voxels reads half the memory and blends four weights per instruction. The
//! diffusion averages weights that lie between 0 and 1 and sum to one; `f32`'s seven digits
//! are far below the 1 % at which a weight is dropped ([`NEGLIGIBLE`]).
//!
//! [`diffuse`]: super::diffusion
//! [`NEGLIGIBLE`]: super::NEGLIGIBLE

use super::rows::{pruned, ranks_before, Row, KEPT, NONE};

/// The weights of one voxel during diffusion: at most [`KEPT`] joints, ascending, then
/// [`NONE`] (weight 0).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub(super) struct Cell {
    pub joints: [u32; KEPT],
    pub weights: [f32; KEPT],
}

impl Cell {
    /// The row in single precision.
    pub fn of(row: &Row) -> Cell {
        Cell {
            joints: row.joints,
            weights: row.weights.map(|w| w as f32),
        }
    }

    /// The row in double precision, renormalised so that its weights sum to one there too.
    pub fn row(&self) -> Row {
        let mut row = Row {
            joints: self.joints,
            weights: self.weights.map(f64::from),
        };
        let sum: f64 = row.weights.iter().sum();
        if sum > 0.0 && sum.is_finite() {
            for w in &mut row.weights {
                *w /= sum;
            }
        }
        row
    }

    /// Joints in use.
    #[inline]
    fn used(&self) -> usize {
        self.joints.iter().take_while(|&&j| j != NONE).count()
    }
}

/// Distinct joints [`blend`] sums on the stack; a sum of more goes to the heap.
const STACK: usize = 16;

/// Per-thread scratch of [`blend`]: joint id → position in the sum (`u8::MAX`: not in it).
pub(super) struct Scratch {
    slot: Vec<u8>,
}

impl Scratch {
    /// Scratch for joint ids below `joints`.
    pub fn new(joints: usize) -> Self {
        Self {
            slot: vec![u8::MAX; joints],
        }
    }
}

/// `keep` times `own` plus `share` times each of `others`, pruned to four joints the way
/// [`prune`] does: where every cell has `own`'s joints (most of a limb: the same bones on every
/// side), the four weights are blended lane by lane; where `own` has four joints and the
/// neighbours bring others besides (where bones meet: a fifth joint at the edge of the row's
/// set), `own`'s four are summed lane by lane and the others beside them ([`own_lanes`]);
/// elsewhere the joints are summed on the stack through `scratch`'s table.
#[inline]
pub(super) fn blend(
    own: &Cell,
    keep: f32,
    share: f32,
    others: &[&Cell],
    same_joints: bool,
    scratch: &mut Scratch,
) -> Cell {
    if same_joints {
        let mut weights = own.weights.map(|w| keep * w);
        for other in others {
            for (w, x) in weights.iter_mut().zip(&other.weights) {
                *w += share * x;
            }
        }
        let used = own.used();
        let sum: f32 = weights[..used].iter().sum();
        if used > 0 && sum.is_finite() && weights[..used].iter().all(|&w| w > 0.0) {
            let mut cell = *own;
            for (out, w) in cell.weights[..used].iter_mut().zip(&weights) {
                *out = w / sum;
            }
            return cell;
        }
    } else if let Some(cell) = own_lanes(own, keep, share, others) {
        return cell;
    }
    by_table(own, keep, share, others, scratch)
}

/// [`blend`]'s general case: the joints summed on the stack through `scratch`'s table, then
/// [`prune`]d.
fn by_table(own: &Cell, keep: f32, share: f32, others: &[&Cell], scratch: &mut Scratch) -> Cell {
    let mut joints = [NONE; STACK];
    let mut weights = [0.0f32; STACK];
    let mut used = 0;
    let table = &mut scratch.slot;
    let mut overflow: Vec<(u32, f32)> = Vec::new();
    let mut add = |j: u32, w: f32, used: &mut usize| match table[j as usize] {
        u8::MAX if *used < STACK => {
            joints[*used] = j;
            weights[*used] = w;
            table[j as usize] = *used as u8;
            *used += 1;
        }
        u8::MAX => match overflow.iter_mut().find(|e| e.0 == j) {
            Some(e) => e.1 += w,
            None => overflow.push((j, w)),
        },
        at => weights[at as usize] += w,
    };
    for (&j, &w) in own.joints.iter().zip(&own.weights) {
        if j == NONE {
            break;
        }
        add(j, keep * w, &mut used);
    }
    for other in others {
        for (&j, &w) in other.joints.iter().zip(&other.weights) {
            if j == NONE {
                break;
            }
            add(j, share * w, &mut used);
        }
    }
    for &j in &joints[..used] {
        table[j as usize] = u8::MAX;
    }
    if !overflow.is_empty() {
        let mut all: Vec<(u32, f32)> = joints[..used]
            .iter()
            .copied()
            .zip(weights[..used].iter().copied())
            .collect();
        all.extend(overflow);
        let (j, w): (Vec<u32>, Vec<f32>) = all.into_iter().unzip();
        return prune(&j, &w);
    }
    prune(&joints[..used], &weights[..used])
}

/// Joints besides `own`'s four that [`own_lanes`] sums on the stack.
const EXTRA: usize = 8;

/// [`blend`] where `own` has four joints: `own`'s weights summed lane by lane, the
/// neighbours' other joints beside them, each joint's terms added in the same order as
/// [`blend`]'s table (`own` first, then `others` in order), so the sums are the same to the
/// bit. Where the largest other joint ranks below all four of `own`'s (by weight, then
/// joint, as [`pruned`] ranks them), the result is [`pruned`]'s written out for that case:
/// the fifth joint's weight subtracted from `own`'s four, summed largest first and
/// normalised; otherwise the entries go to [`prune`]. `None` where `own` has fewer than four
/// joints or the neighbours bring more than [`EXTRA`] others (then [`blend`]'s table).
#[inline]
fn own_lanes(own: &Cell, keep: f32, share: f32, others: &[&Cell]) -> Option<Cell> {
    if own.joints[KEPT - 1] == NONE {
        return None;
    }
    let mut lanes = own.weights.map(|w| keep * w);
    let mut extra_joints = [NONE; EXTRA];
    let mut extra_weights = [0.0f32; EXTRA];
    let mut extras = 0;
    for other in others {
        for (&j, &x) in other.joints.iter().zip(&other.weights) {
            if j == NONE {
                break;
            }
            let w = share * x;
            if let Some(lane) = own.joints.iter().position(|&o| o == j) {
                lanes[lane] += w;
            } else if let Some(e) = extra_joints[..extras].iter().position(|&e| e == j) {
                extra_weights[e] += w;
            } else if extras < EXTRA {
                extra_joints[extras] = j;
                extra_weights[extras] = w;
                extras += 1;
            } else {
                return None;
            }
        }
    }
    // `pruned`'s order (`ranks_before`).
    let before = ranks_before::<f32>;
    let largest_extra = (0..extras)
        .map(|e| (extra_joints[e], extra_weights[e]))
        .reduce(|a, b| if before(b, a) { b } else { a });
    let fifth = match largest_extra {
        Some(fifth) if (0..KEPT).all(|lane| before((own.joints[lane], lanes[lane]), fifth)) => {
            fifth
        }
        _ => {
            let mut joints = [NONE; KEPT + EXTRA];
            let mut weights = [0.0f32; KEPT + EXTRA];
            joints[..KEPT].copy_from_slice(&own.joints);
            weights[..KEPT].copy_from_slice(&lanes);
            joints[KEPT..KEPT + extras].copy_from_slice(&extra_joints[..extras]);
            weights[KEPT..KEPT + extras].copy_from_slice(&extra_weights[..extras]);
            return Some(prune(&joints[..KEPT + extras], &weights[..KEPT + extras]));
        }
    };
    // `own`'s lanes largest first (insertion sort of four).
    let mut order = [0, 1, 2, 3];
    for k in 1..KEPT {
        let mut at = k;
        while at > 0
            && before(
                (own.joints[order[at]], lanes[order[at]]),
                (own.joints[order[at - 1]], lanes[order[at - 1]]),
            )
        {
            order.swap(at - 1, at);
            at -= 1;
        }
    }
    // `pruned` with cut 0: the floor is the fifth weight, or the largest if that is negative.
    let floor = fifth.1.max(0.0f32.min(lanes[order[0]]));
    let reduced = lanes.map(|w| (w - floor).max(0.0));
    let mut sum = 0.0f32;
    for &lane in &order {
        sum += reduced[lane];
    }
    let mut cell = Cell {
        joints: [NONE; KEPT],
        weights: [0.0; KEPT],
    };
    if sum > 0.0 && sum.is_finite() {
        let mut used = 0;
        for (&joint, &w) in own.joints.iter().zip(&reduced) {
            if w > 0.0 {
                cell.joints[used] = joint;
                cell.weights[used] = w / sum;
                used += 1;
            }
        }
    } else {
        cell.joints = own.joints;
        cell.weights = [0.25; KEPT];
    }
    Some(cell)
}

/// The sum `weights` of `joints` (distinct) pruned to four joints by the rule of
/// [`prune`](super::rows::prune) with cut 0, in single precision.
pub(super) fn prune(joints: &[u32], weights: &[f32]) -> Cell {
    let (joints, weights) = pruned(joints, weights, 0.0);
    Cell { joints, weights }
}

#[cfg(test)]
mod tests {
    use super::super::rows::tests::pruned_by_sorting;
    use super::*;

    fn entries(cell: &Cell) -> Vec<(u32, f32)> {
        cell.joints
            .iter()
            .zip(&cell.weights)
            .take_while(|(&j, _)| j != NONE)
            .map(|(&j, &w)| (j, w))
            .collect()
    }

    fn cell(entries: &[(u32, f32)]) -> Cell {
        let mut sorted = entries.to_vec();
        sorted.sort_by_key(|e| e.0);
        sorted.dedup_by_key(|e| e.0);
        let mut c = Cell {
            joints: [NONE; KEPT],
            weights: [0.0; KEPT],
        };
        for (k, &(j, w)) in sorted.iter().take(KEPT).enumerate() {
            c.joints[k] = j;
            c.weights[k] = w;
        }
        c
    }

    proptest::proptest! {
        #[test]
        fn blending_matches_summing_then_the_sorting_rule(
            own in proptest::collection::vec((0u32..40, 0.01f32..1.0), 1..5),
            others in proptest::collection::vec(
                proptest::collection::vec((0u32..40, 0.01f32..1.0), 1..5), 0..7),
            keep in 0.1f32..1.0,
        ) {
            let own = cell(&own);
            let others: Vec<Cell> = others.iter().map(|o| cell(o)).collect();
            let share = (1.0 - keep) / others.len().max(1) as f32;
            let refs: Vec<&Cell> = others.iter().collect();
            let same = others.iter().all(|o| o.joints == own.joints);
            let mut scratch = Scratch::new(40);
            let got = entries(&blend(&own, keep, share, &refs, same, &mut scratch));
            let mut summed: Vec<(u32, f32)> = Vec::new();
            for (c, f) in std::iter::once((&own, keep)).chain(others.iter().map(|o| (o, share))) {
                for (j, w) in entries(c) {
                    match summed.iter_mut().find(|e| e.0 == j) {
                        Some(e) => e.1 += f * w,
                        None => summed.push((j, f * w)),
                    }
                }
            }
            // The rule written plainly, in double precision.
            let summed = summed.into_iter().map(|(j, w)| (j, f64::from(w))).collect();
            let want = pruned_by_sorting(summed, 0.0);
            proptest::prop_assert_eq!(got.len(), want.len());
            for (g, w) in got.iter().zip(&want) {
                proptest::prop_assert_eq!(g.0, w.0);
                proptest::prop_assert!((f64::from(g.1) - w.1).abs() < 1e-5, "{:?} vs {:?}", got, want);
            }
            // The scratch table is left clean.
            proptest::prop_assert!(scratch.slot.iter().all(|&s| s == u8::MAX));
        }

        #[test]
        fn own_lanes_equal_the_table_to_the_bit(
            own in proptest::collection::vec((0u32..12, 0.01f32..1.0), 4..8),
            others in proptest::collection::vec(
                proptest::collection::vec((0u32..12, 0.01f32..1.0), 1..5), 1..7),
            keep in 0.1f32..1.0,
            ties in proptest::bool::ANY,
        ) {
            let mut own = cell(&own);
            if ties {
                // Equal weights, so that ranking falls to the joints.
                own.weights = [0.25; KEPT];
            }
            proptest::prop_assume!(own.used() == KEPT);
            let others: Vec<Cell> = others.iter().map(|o| cell(o)).collect();
            let share = (1.0 - keep) / others.len() as f32;
            let refs: Vec<&Cell> = others.iter().collect();
            let mut scratch = Scratch::new(12);
            let table = by_table(&own, keep, share, &refs, &mut scratch);
            if let Some(lanes) = own_lanes(&own, keep, share, &refs) {
                proptest::prop_assert_eq!(lanes.joints, table.joints);
                proptest::prop_assert_eq!(lanes.weights.map(f32::to_bits), table.weights.map(f32::to_bits));
            }
        }
    }
}

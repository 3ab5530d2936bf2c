//! Sparse weight rows: at most four `(joint, weight)` per voxel or vertex, and the kernel that
//! mixes rows and prunes the mix back to four joints without a jump.

use super::LABELS;

/// No joint / no voxel.
pub(super) const NONE: u32 = u32::MAX;

/// Joints a [`Row`] holds: the four influences a vertex may keep.
pub(super) const KEPT: usize = LABELS - 1;

/// The weights of one voxel or vertex: at most [`KEPT`] joints, ascending, [`NONE`] (weight 0)
/// in the unused slots after the used ones.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Row {
    /// Joint ids, ascending, then [`NONE`].
    pub joints: [u32; KEPT],
    /// Their weights.
    pub weights: [f64; KEPT],
}

impl Row {
    /// A row without joints.
    pub const EMPTY: Row = Row {
        joints: [NONE; KEPT],
        weights: [0.0; KEPT],
    };

    /// Whether the row has no joint.
    pub fn is_empty(&self) -> bool {
        self.joints[0] == NONE
    }

    /// The used `(joint, weight)` entries, joints ascending.
    pub fn entries(&self) -> impl Iterator<Item = (u32, f64)> + '_ {
        self.joints
            .iter()
            .zip(&self.weights)
            .take_while(|(&j, _)| j != NONE)
            .map(|(&j, &w)| (j, w))
    }

    /// `keep` times this row plus `share` times each of `others`, normalised, when every
    /// one of `others` has this row's joints and every sum is positive; `None` otherwise.
    /// The same as [`Mixer::pruned`] of the same sum (up to rounding: fewer than five joints
    /// have nothing to subtract), without the search and sort. The plain statement of the
    /// rule that the mesh smoothing's one-pass round (`surface.rs`) is tested against to the
    /// bit; the rounds themselves fold it into their single read of the neighbours.
    #[cfg_attr(not(test), allow(dead_code))]
    #[inline]
    pub fn blend_same_joints<'a>(
        &self,
        keep: f64,
        others: impl Iterator<Item = (&'a Row, f64)>,
    ) -> Option<Row> {
        let mut weights = self.weights.map(|w| keep * w);
        for (row, share) in others {
            if row.joints != self.joints {
                return None;
            }
            for (w, x) in weights.iter_mut().zip(&row.weights) {
                *w += share * x;
            }
        }
        let used = self.joints.iter().take_while(|&&j| j != NONE).count();
        let sum: f64 = weights[..used].iter().sum();
        if used == 0 || !sum.is_finite() || weights[..used].iter().any(|&w| w <= 0.0) {
            return None;
        }
        let mut row = *self;
        for (out, w) in row.weights[..used].iter_mut().zip(&weights) {
            *out = w / sum;
        }
        Some(row)
    }
}

/// `keep` times `own` plus each of `others` (row, factor), normalised, when together they
/// have at most four joints and every sum is positive; `None` otherwise. The same as
/// [`Mixer::pruned`] of the same sum up to rounding (four joints or fewer have nothing to
/// subtract), without its search and sort.
#[inline]
pub(super) fn blend_few<'a>(
    own: &Row,
    keep: f64,
    others: impl Iterator<Item = (&'a Row, f64)>,
) -> Option<Row> {
    let mut row = Row::EMPTY;
    let mut used = 0;
    for (j, w) in own.entries() {
        row.joints[used] = j;
        row.weights[used] = keep * w;
        used += 1;
    }
    for (other, factor) in others {
        for (j, w) in other.entries() {
            match row.joints[..used].iter().position(|&k| k == j) {
                Some(k) => row.weights[k] += factor * w,
                None if used < KEPT => {
                    row.joints[used] = j;
                    row.weights[used] = factor * w;
                    used += 1;
                }
                None => return None,
            }
        }
    }
    let sum: f64 = row.weights[..used].iter().sum();
    if used == 0 || !sum.is_finite() || row.weights[..used].iter().any(|&w| w <= 0.0) {
        return None;
    }
    for w in &mut row.weights[..used] {
        *w /= sum;
    }
    // Joints ascending (insertion sort of at most four).
    for k in 1..used {
        let mut at = k;
        while at > 0 && row.joints[at - 1] > row.joints[at] {
            row.joints.swap(at - 1, at);
            row.weights.swap(at - 1, at);
            at -= 1;
        }
    }
    Some(row)
}

/// Distinct joints [`mix`] sums on the stack before it hands the sum to a [`Mixer`].
const STACK: usize = 16;

/// `keep` times `own` plus each of `others` (row, factor), pruned to four joints: what
/// [`blend_few`] gives where it has an answer, else what [`Mixer::pruned`] (cut 0) gives of
/// the same sum, to the bit (each joint's sum is taken in the same order), in one pass over
/// the rows without the mixer's table.
#[inline]
pub(super) fn mix<'a>(
    own: &Row,
    keep: f64,
    others: impl Iterator<Item = (&'a Row, f64)> + Clone,
    mixer: &mut Mixer,
) -> Row {
    let mut joints = [NONE; STACK];
    let mut weights = [0.0f64; STACK];
    let mut used = 0;
    for (j, w) in own.entries() {
        joints[used] = j;
        weights[used] = keep * w;
        used += 1;
    }
    for (other, factor) in others.clone() {
        for (j, w) in other.entries() {
            match joints[..used].iter().position(|&k| k == j) {
                Some(k) => weights[k] += factor * w,
                None if used < STACK => {
                    joints[used] = j;
                    weights[used] = factor * w;
                    used += 1;
                }
                None => {
                    mixer.clear();
                    mixer.add_row(own, keep);
                    for (row, factor) in others {
                        mixer.add_row(row, factor);
                    }
                    return mixer.pruned(0.0);
                }
            }
        }
    }
    let (joints, weights) = (&joints[..used], &weights[..used]);
    if used <= KEPT {
        let sum: f64 = weights.iter().sum();
        if used > 0 && sum.is_finite() && weights.iter().all(|&w| w > 0.0) {
            let mut row = Row::EMPTY;
            for k in 0..used {
                // Joints ascending (insertion of at most four).
                let mut at = k;
                while at > 0 && row.joints[at - 1] > joints[k] {
                    row.joints[at] = row.joints[at - 1];
                    row.weights[at] = row.weights[at - 1];
                    at -= 1;
                }
                row.joints[at] = joints[k];
                row.weights[at] = weights[k] / sum;
            }
            return row;
        }
    }
    prune(joints, weights, 0.0)
}

/// A weighted sum of rows (any number of joints), pruned back to a [`Row`] by
/// [`Mixer::pruned`]. Reused across voxels and vertices so that mixing allocates nothing.
#[derive(Debug, Default)]
pub(super) struct Mixer {
    joints: Vec<u32>,
    weights: Vec<f64>,
    /// Joint id → its position in `joints` plus one (0: not in the sum), grown on demand
    /// (skeletons have fewer than `u16::MAX` joints, checked before skinning), so that adding
    /// a joint needs no search where many bones meet.
    at: Vec<u32>,
}

impl Mixer {
    /// Empties the sum.
    #[inline]
    pub fn clear(&mut self) {
        for &j in &self.joints {
            self.at[j as usize] = 0;
        }
        self.joints.clear();
        self.weights.clear();
    }

    /// Adds `weight` to `joint`'s sum.
    #[inline(always)]
    pub fn add(&mut self, joint: u32, weight: f64) {
        let j = joint as usize;
        if j >= self.at.len() {
            self.at.resize(j + 1, 0);
        }
        match self.at[j] {
            0 => {
                self.joints.push(joint);
                self.weights.push(weight);
                self.at[j] = self.joints.len() as u32;
            }
            k => self.weights[k as usize - 1] += weight,
        }
    }

    /// Adds `factor` times every entry of `row`.
    #[inline(always)]
    pub fn add_row(&mut self, row: &Row, factor: f64) {
        for (j, w) in row.entries() {
            self.add(j, factor * w);
        }
    }

    /// The sum pruned to four joints ([`prune`]).
    pub fn pruned(&self, cut: f64) -> Row {
        prune(&self.joints, &self.weights, cut)
    }
}

/// The sum `weights` of `joints` (distinct) pruned to four joints: keeps the [`LABELS`] largest (ties: lower joint id),
/// subtracts the smallest of them (or `cut`, whichever is larger, but never more than the
/// largest) from the others, so that a joint whose rank crosses the cut enters or leaves
/// with weight zero, drops what is left at zero and normalises. When every kept weight
/// ties with the cut, the kept joints share equally.
pub(super) fn prune(joints: &[u32], weights: &[f64], cut: f64) -> Row {
    let (joints, weights) = pruned(joints, weights, cut);
    Row { joints, weights }
}

/// A weight of [`pruned`]: `f64` for the rows, `f32` for the diffusion's
/// [`Cell`](super::cell::Cell)s.
pub(super) trait Weight:
    Copy
    + PartialOrd
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Div<Output = Self>
    + std::ops::AddAssign
{
    const ZERO: Self;
    fn total_order(&self, other: &Self) -> std::cmp::Ordering;
    fn larger(self, other: Self) -> Self;
    fn smaller(self, other: Self) -> Self;
    fn finite(self) -> bool;
    fn share(count: usize) -> Self;
}

macro_rules! weight {
    ($t:ty) => {
        impl Weight for $t {
            const ZERO: Self = 0.0;
            #[inline]
            fn total_order(&self, other: &Self) -> std::cmp::Ordering {
                self.total_cmp(other)
            }
            #[inline]
            fn larger(self, other: Self) -> Self {
                self.max(other)
            }
            #[inline]
            fn smaller(self, other: Self) -> Self {
                self.min(other)
            }
            #[inline]
            fn finite(self) -> bool {
                self.is_finite()
            }
            #[inline]
            fn share(count: usize) -> Self {
                1.0 / count as $t
            }
        }
    };
}
weight!(f64);
weight!(f32);

/// Whether joint `a` ranks before joint `b` when a row is pruned: the larger weight first, then
/// the smaller joint id.
#[inline]
pub(super) fn ranks_before<W: Weight>((ja, wa): (u32, W), (jb, wb): (u32, W)) -> bool {
    wa.total_order(&wb).reverse().then(ja.cmp(&jb)).is_lt()
}

/// [`prune`] in either precision: the kept joints ascending, then [`NONE`] (weight 0).
pub(super) fn pruned<W: Weight>(joints: &[u32], weights: &[W], cut: W) -> ([u32; KEPT], [W; KEPT]) {
    // The LABELS largest, largest first: insertion into a short sorted list.
    let mut top = [usize::MAX; LABELS];
    let mut count = 0;
    let before =
        |a: usize, b: usize| ranks_before((joints[a], weights[a]), (joints[b], weights[b]));
    for k in 0..joints.len() {
        let mut at = count;
        while at > 0 && before(k, top[at - 1]) {
            at -= 1;
        }
        if at < LABELS {
            let end = count.min(LABELS - 1);
            top.copy_within(at..end, at + 1);
            top[at] = k;
            count = (count + 1).min(LABELS);
        }
    }
    let mut out = ([NONE; KEPT], [W::ZERO; KEPT]);
    if count == 0 {
        return out;
    }
    let floor = if count == LABELS {
        weights[top[LABELS - 1]]
    } else {
        W::ZERO
    }
    .larger(cut.smaller(weights[top[0]]));
    let kept = count.min(KEPT);
    let mut entries = [(NONE, W::ZERO); KEPT];
    let mut sum = W::ZERO;
    for (slot, &k) in entries.iter_mut().zip(&top[..kept]) {
        let w = (weights[k] - floor).larger(W::ZERO);
        *slot = (joints[k], w);
        sum += w;
    }
    let mut used = kept;
    if sum > W::ZERO && sum.finite() {
        used = 0;
        for k in 0..kept {
            if entries[k].1 > W::ZERO {
                entries[used] = (entries[k].0, entries[k].1 / sum);
                used += 1;
            }
        }
    } else {
        let share = W::share(kept);
        for entry in &mut entries[..kept] {
            entry.1 = share;
        }
    }
    // Joints ascending (insertion sort of at most four distinct joints).
    for k in 1..used {
        let mut at = k;
        while at > 0 && entries[at - 1].0 > entries[at].0 {
            entries.swap(at - 1, at);
            at -= 1;
        }
    }
    for (k, &(j, w)) in entries[..used].iter().enumerate() {
        out.0[k] = j;
        out.1[k] = w;
    }
    out
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// The pruning rule written plainly (sort, cut, normalise), to check [`Mixer::pruned`].
    pub(in crate::skin::geodesic) fn pruned_by_sorting(
        mut weights: Vec<(u32, f64)>,
        cut: f64,
    ) -> Vec<(u32, f64)> {
        weights.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        let floor = if weights.len() >= LABELS {
            weights[LABELS - 1].1
        } else {
            0.0
        }
        .max(cut.min(weights.first().map_or(0.0, |w| w.1)));
        weights.truncate(KEPT);
        let mut sum = 0.0;
        for w in weights.iter_mut() {
            w.1 = (w.1 - floor).max(0.0);
            sum += w.1;
        }
        if sum > 0.0 && sum.is_finite() {
            weights.retain(|w| w.1 > 0.0);
            for w in weights.iter_mut() {
                w.1 /= sum;
            }
        } else {
            let share = 1.0 / weights.len().max(1) as f64;
            for w in weights.iter_mut() {
                w.1 = share;
            }
        }
        weights.sort_by_key(|w| w.0);
        weights
    }

    proptest::proptest! {
        #[test]
        fn pruning_matches_the_sorting_rule(
            entries in proptest::collection::vec((0u32..12, 0.0f64..1.0), 0..20),
            cut in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.0f64..0.3],
        ) {
            let mut mixer = Mixer::default();
            for &(j, w) in &entries {
                mixer.add(j, w);
            }
            let mut summed: Vec<(u32, f64)> = Vec::new();
            for &(j, w) in &entries {
                match summed.iter_mut().find(|e| e.0 == j) {
                    Some(e) => e.1 += w,
                    None => summed.push((j, w)),
                }
            }
            let row: Vec<(u32, f64)> = mixer.pruned(cut).entries().collect();
            proptest::prop_assert_eq!(row, pruned_by_sorting(summed, cut));
        }
    }
}

//! Per-vertex weights: the dissertation's anchor weights and their engine-ready form.

use crate::skeleton::JointId;
use glam::DVec3;
use rayon::prelude::*;

/// Most influences per vertex in [`EngineWeights`] (one glTF `JOINTS_0`/`WEIGHTS_0` set; the
/// limit of most game engines).
pub const MAX_ENGINE_INFLUENCES: usize = 4;

/// The anchor weights of one vertex over the segments influencing it (dissertation 5.2.5).
///
/// `distances[i]` is the shortest distance from the vertex to segment `i` (mesh units, `n`
/// entries). One segment gets weight 1; with `n > 1`,
/// `w_i = (total - d_i) / ((n - 1) * total)` with `total = sum d_i`, so closer segments weigh
/// more, every weight lies in `[0, 1/(n-1)]` and the weights sum to one. When every distance is
/// zero (the vertex lies on all segments) the weights are equal, `1/n`. Empty input gives an
/// empty result.
///
/// ```
/// let w = skelfit::skin::anchor_weights(&[1.0, 3.0]);
/// assert_eq!(w, vec![0.75, 0.25]);
/// ```
pub fn anchor_weights(distances: &[f64]) -> Vec<f64> {
    let n = distances.len();
    match n {
        0 => Vec::new(),
        1 => vec![1.0],
        _ => {
            let total: f64 = distances.iter().sum();
            if total <= 0.0 || !total.is_finite() {
                return vec![1.0 / n as f64; n];
            }
            let denominator = (n - 1) as f64 * total;
            distances
                .iter()
                .map(|&d| ((total - d) / denominator).max(0.0))
                .collect()
        }
    }
}

/// The index of the segment line (`(start, end)`) nearest to `p` (ties: the lowest index), or
/// `None` without lines.
pub(crate) fn nearest_segment(p: DVec3, lines: &[(DVec3, DVec3)]) -> Option<usize> {
    (0..lines.len())
        .map(|s| (segment_distance(p, lines[s].0, lines[s].1), s))
        .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
        .map(|(_, s)| s)
}

/// Shortest distance from `p` to the line segment `a..b` (a point when `a == b`).
pub(crate) fn segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    crate::math::point_segment_distance(p, a, b)
}

/// Weights for game engines and glTF: at most [`MAX_ENGINE_INFLUENCES`] joints per vertex.
///
/// Per vertex `v`, `joints[v][k]` is a joint index (the joint's [`JointId`], which is its index
/// in the exported glTF skin) and `weights[v][k]` its weight. Relation to the anchor weights:
/// keep the four largest anchor weights of the vertex (ties: lower joint id first), divide each
/// by their sum, and round to `f32`; the largest is then set to `1 - (sum of the others)` in
/// `f32` so that the four sum to one as closely as `f32` allows (glTF requires normalised
/// weights). Entries are ordered by decreasing weight; unused entries have joint 0 and
/// weight 0. A vertex with four or fewer influences keeps its anchor weights up to `f32`
/// rounding.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EngineWeights {
    /// Joint indices per vertex.
    pub joints: Vec<[u16; MAX_ENGINE_INFLUENCES]>,
    /// Weights per vertex, each row summing to one in `f32`.
    pub weights: Vec<[f32; MAX_ENGINE_INFLUENCES]>,
}

/// Converts per-vertex anchor weights (`(joint, weight)` lists) into [`EngineWeights`]; also
/// returns, per vertex, the total anchor weight that was dropped (zero with four or fewer
/// influences). Joint ids must fit in `u16`.
pub fn engine_weights(anchor: &[Vec<(JointId, f64)>]) -> (EngineWeights, Vec<f64>) {
    let (joints, (weights, dropped)) = anchor
        .par_iter()
        .with_min_len(1024)
        .map(|v| {
            let (joints, weights, dropped) = engine_row(v);
            (joints, (weights, dropped))
        })
        .unzip();
    (EngineWeights { joints, weights }, dropped)
}

/// One vertex of [`engine_weights`]: its joints, weights and the weight dropped.
fn engine_row(
    vertex: &[(JointId, f64)],
) -> (
    [u16; MAX_ENGINE_INFLUENCES],
    [f32; MAX_ENGINE_INFLUENCES],
    f64,
) {
    let by_weight =
        |a: &(JointId, f64), b: &(JointId, f64)| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0));
    // The four largest (ties: lower joint id), without sorting or copying the whole list.
    let mut kept = [(JointId(0), 0.0f64); MAX_ENGINE_INFLUENCES];
    let mut count = 0;
    for entry in vertex {
        let mut at = count;
        while at > 0 && by_weight(entry, &kept[at - 1]).is_lt() {
            at -= 1;
        }
        if at < MAX_ENGINE_INFLUENCES {
            let end = count.min(MAX_ENGINE_INFLUENCES - 1);
            kept.copy_within(at..end, at + 1);
            kept[at] = *entry;
            count = (count + 1).min(MAX_ENGINE_INFLUENCES);
        }
    }
    let kept = &kept[..count];
    let sum: f64 = kept.iter().map(|(_, w)| w).sum();
    // Summed largest first, as the kept ones: exactly `sum` when nothing is dropped.
    let all: f64 = if vertex.len() <= MAX_ENGINE_INFLUENCES {
        sum
    } else {
        let mut sorted = vertex.to_vec();
        sorted.sort_by(by_weight);
        sorted.iter().map(|(_, w)| w).sum()
    };
    let mut joints = [0u16; MAX_ENGINE_INFLUENCES];
    let mut weights = [0f32; MAX_ENGINE_INFLUENCES];
    for (k, &(joint, w)) in kept.iter().enumerate() {
        joints[k] = u16::try_from(joint.0).unwrap_or(u16::MAX);
        weights[k] = if sum > 0.0 { (w / sum) as f32 } else { 0.0 };
    }
    if !kept.is_empty() {
        if sum > 0.0 {
            let others: f32 = weights[1..].iter().sum();
            weights[0] = 1.0 - others;
        } else {
            weights[0] = 1.0;
        }
    }
    (joints, weights, (all - sum).max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anchor_weights_follow_the_dissertation_formula() {
        assert_eq!(anchor_weights(&[2.0]), vec![1.0]);
        let w = anchor_weights(&[1.0, 2.0, 3.0]);
        // total 6, n - 1 = 2: (6-1)/12, (6-2)/12, (6-3)/12.
        let expected = [5.0 / 12.0, 4.0 / 12.0, 3.0 / 12.0];
        for (a, b) in w.iter().zip(expected) {
            assert!((a - b).abs() < 1e-15);
        }
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert_eq!(anchor_weights(&[0.0, 0.0]), vec![0.5, 0.5]);
        assert_eq!(anchor_weights(&[0.0, 1.0]), vec![1.0, 0.0]);
    }

    #[test]
    fn engine_weights_keep_the_four_largest_and_renormalise() {
        let anchor = vec![vec![
            (JointId(0), 0.1),
            (JointId(1), 0.3),
            (JointId(2), 0.2),
            (JointId(3), 0.25),
            (JointId(4), 0.15),
        ]];
        let (engine, dropped) = engine_weights(&anchor);
        assert_eq!(engine.joints[0], [1, 3, 2, 4]);
        let sum: f32 = engine.weights[0].iter().sum();
        assert!((sum - 1.0).abs() <= f32::EPSILON);
        assert!((engine.weights[0][1] as f64 - 0.25 / 0.9).abs() < 1e-7);
        assert!((dropped[0] - 0.1).abs() < 1e-12);
    }

    proptest::proptest! {
        #[test]
        fn anchor_weights_are_a_partition_of_one(distances in proptest::collection::vec(0.0f64..10.0, 1..12)) {
            let w = anchor_weights(&distances);
            proptest::prop_assert_eq!(w.len(), distances.len());
            proptest::prop_assert!(w.iter().all(|&x| x >= 0.0));
            proptest::prop_assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            // Closer segments never weigh less.
            for i in 0..w.len() {
                for j in 0..w.len() {
                    if distances[i] < distances[j] {
                        proptest::prop_assert!(w[i] >= w[j]);
                    }
                }
            }
        }
    }

    #[test]
    fn segment_distance_handles_points_and_ends() {
        let a = DVec3::ZERO;
        let b = DVec3::Y;
        assert!((segment_distance(DVec3::new(1.0, 0.5, 0.0), a, b) - 1.0).abs() < 1e-15);
        assert!((segment_distance(DVec3::new(0.0, 3.0, 0.0), a, b) - 2.0).abs() < 1e-15);
        assert!((segment_distance(DVec3::X, a, a) - 1.0).abs() < 1e-15);
    }
}

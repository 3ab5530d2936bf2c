//! Digit weights on the hand's surface (issue 25): fingers are thinner than the body's voxels,
//! so the voxel skin blurs neighbouring fingers into each other; here each finger's vertices
//! take its own bones only.
//!
//! For each hand (a wrist joint whose children start chains of single joints, the digits):
//!
//! 1. **Hand vertices**: the vertices whose voxel weights lie mostly (over one half) on the
//!    wrist and its digits, on the wrist's distal side.
//! 2. **Owner**: each hand vertex belongs to the digit nearest over the surface (a Dijkstra
//!    over the hand's mesh edges per digit) from the vertices that clearly lie on one digit
//!    (their nearest digit bone is at most half as far as any other digit's). Touching fingers
//!    are far apart over the surface, around the web.
//! 3. **Weights**: a vertex on its digit's bones (its nearest point on the chain wrist → base
//!    → middle → last → tip lies past the base joint's blend zone) takes that chain's joints
//!    only: the bone it lies along, blended linearly with the next one within as far of each
//!    joint as the vertex is from the chain (the local finger radius, at most half a bone).
//!    A vertex in the palm keeps its voxel weights without the other digits' joints.
//! 4. **Web**: across the web between two digits the vertex blends its own digit's weights
//!    with the next nearest digit's, whose share rises linearly from nothing to one half where
//!    both are equally far over the surface, over a finger's radius (the vertex's distance from
//!    its chain) on either side: curling two neighbouring fingers about their own base joints
//!    no longer tears the web between them.

use super::weights::{engine_weights, EngineWeights};
use crate::digits::edge_geodesic;
use crate::math::{closest_on_segment, point_segment_distance};
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use glam::DVec3;

/// One digit: the wrist, then the chain's joints to its tip.
struct Chain {
    /// Joints from the wrist to the tip (`joints[0]` is the wrist).
    joints: Vec<JointId>,
    /// Their positions, mesh frame.
    points: Vec<DVec3>,
}

/// Re-weights the vertices of each hand in `wrists` (module docs) and returns the engine
/// weights of the result.
///
/// `weights`: per mesh vertex `(joint, weight)` lists (as [`super::Skin::weights`]), weights
/// summing to one; they keep that, and each vertex keeps at least one weight.
pub fn digit_weights(
    mesh: &Mesh,
    skeleton: &Skeleton,
    wrists: &[JointId],
    weights: &mut [Vec<(JointId, f64)>],
) -> EngineWeights {
    for &wrist in wrists {
        let chains = chains(skeleton, wrist);
        if chains.len() >= 2 {
            hand(mesh, skeleton, wrist, &chains, weights);
        }
    }
    engine_weights(weights).0
}

/// The digit chains hanging from `wrist`: each child followed while it has one child.
fn chains(skeleton: &Skeleton, wrist: JointId) -> Vec<Chain> {
    skeleton
        .children(wrist)
        .into_iter()
        .map(|first| {
            let mut joints = vec![wrist, first];
            loop {
                let children = skeleton.children(*joints.last().unwrap());
                match children.as_slice() {
                    [only] => joints.push(*only),
                    _ => break,
                }
            }
            let points = joints.iter().map(|&j| skeleton.joint(j).position).collect();
            Chain { joints, points }
        })
        .filter(|c| c.joints.len() >= 3)
        .collect()
}

/// One hand's vertices re-weighted.
fn hand(
    mesh: &Mesh,
    skeleton: &Skeleton,
    wrist: JointId,
    chains: &[Chain],
    weights: &mut [Vec<(JointId, f64)>],
) {
    let mut digit_of = vec![usize::MAX; skeleton.len()];
    for (d, c) in chains.iter().enumerate() {
        for &j in &c.joints[1..] {
            digit_of[j.0] = d;
        }
    }
    let in_hand = hand_vertices(mesh, skeleton, wrist, &digit_of, weights);
    let distance = digit_distances(mesh, chains, &in_hand);
    for (v, &p) in mesh.positions.iter().enumerate() {
        if !in_hand[v] {
            continue;
        }
        // The nearest digit over the surface and the next nearest.
        let mut order: Vec<usize> = (0..chains.len())
            .filter(|&d| distance[d][v].is_finite())
            .collect();
        order.sort_by(|&a, &b| distance[a][v].total_cmp(&distance[b][v]));
        let Some(&d) = order.first() else {
            continue;
        };
        let own = digit_row(&chains[d], d, wrist, &digit_of, &weights[v], p);
        // Across the web the neighbouring digit's share rises smoothly to one half where both
        // are equally far over the surface, over a finger's radius on either side.
        let radius = nearest_on_chain(&chains[d].points, p).0;
        let share = order.get(1).map_or(0.0, |&e| {
            let gap = distance[e][v] - distance[d][v];
            if radius > 0.0 {
                0.5 * (1.0 - gap / (2.0 * radius)).clamp(0.0, 1.0)
            } else {
                0.0
            }
        });
        let mut row = own;
        if share > 0.0 {
            let e = order[1];
            let other = digit_row(&chains[e], e, wrist, &digit_of, &weights[v], p);
            row = blend(&row, &other, share);
        }
        row.sort_by_key(|(j, _)| *j);
        weights[v] = row;
    }
}

/// The hand's vertices (module docs, step 1).
fn hand_vertices(
    mesh: &Mesh,
    skeleton: &Skeleton,
    wrist: JointId,
    digit_of: &[usize],
    weights: &[Vec<(JointId, f64)>],
) -> Vec<bool> {
    let w = skeleton.joint(wrist).position;
    let axis = skeleton
        .joint(wrist)
        .parent
        .map(|p| w - skeleton.joint(p).position)
        .and_then(DVec3::try_normalize)
        .unwrap_or(DVec3::ZERO);
    mesh.positions
        .iter()
        .zip(weights.iter())
        .map(|(&p, row)| {
            let share: f64 = row
                .iter()
                .filter(|(j, _)| *j == wrist || digit_of[j.0] != usize::MAX)
                .map(|(_, x)| x)
                .sum();
            share > 0.5 && (p - w).dot(axis) > 0.0
        })
        .collect()
}

/// Per digit, the distance over the hand's mesh edges of every vertex from the vertices that
/// clearly lie on that digit's bones (module docs, step 2); infinite where not reached.
fn digit_distances(mesh: &Mesh, chains: &[Chain], in_hand: &[bool]) -> Vec<Vec<f64>> {
    let mut seeds: Vec<Vec<usize>> = vec![Vec::new(); chains.len()];
    for (v, &p) in mesh.positions.iter().enumerate() {
        if !in_hand[v] {
            continue;
        }
        let near: Vec<(f64, bool)> = chains
            .iter()
            .map(|c| {
                let (dist, seg) = nearest_on_chain(&c.points, p);
                (dist, seg > 0)
            })
            .collect();
        let Some((best, &(d_best, on_digit))) = near
            .iter()
            .enumerate()
            .min_by(|a, b| a.1 .0.total_cmp(&b.1 .0))
        else {
            continue;
        };
        let second = near
            .iter()
            .enumerate()
            .filter(|(d, _)| *d != best)
            .map(|(_, n)| n.0)
            .fold(f64::INFINITY, f64::min);
        if on_digit && 2.0 * d_best <= second {
            seeds[best].push(v);
        }
    }
    let triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .filter(|t| t.iter().all(|&v| in_hand[v as usize]))
        .copied()
        .collect();
    seeds
        .into_iter()
        .map(|s| edge_geodesic(&mesh.positions, &triangles, s, |_, _| {}))
        .collect()
}

/// The weights of a vertex at `p` (voxel weights `row`) as a vertex of digit `d` (module docs,
/// step 3).
fn digit_row(
    chain: &Chain,
    d: usize,
    wrist: JointId,
    digit_of: &[usize],
    row: &[(JointId, f64)],
    p: DVec3,
) -> Vec<(JointId, f64)> {
    let chain_row = chain_weights(&chain.points, &chain.joints, p);
    let past_base = chain_row.iter().any(|(j, _)| *j != wrist);
    let kept: Vec<(JointId, f64)> = row
        .iter()
        .copied()
        .filter(|(j, _)| digit_of[j.0] == usize::MAX || digit_of[j.0] == d)
        .collect();
    let sum: f64 = kept.iter().map(|(_, x)| x).sum();
    if !past_base && sum > 0.0 {
        return kept.into_iter().map(|(j, x)| (j, x / sum)).collect();
    }
    // The share of joints outside the hand (the forearm's) stays as it was, so the digit's
    // vertices move with their palm neighbours when the wrist turns; the hand's share goes to
    // the chain.
    let mut out: Vec<(JointId, f64)> = row
        .iter()
        .copied()
        .filter(|(j, _)| *j != wrist && digit_of[j.0] == usize::MAX)
        .collect();
    let hand_share = 1.0 - out.iter().map(|(_, x)| x).sum::<f64>();
    out.extend(chain_row.into_iter().map(|(j, x)| (j, x * hand_share)));
    out.retain(|(_, x)| *x > 0.0);
    out
}

/// `(1 - share) a + share b`, joints merged.
fn blend(a: &[(JointId, f64)], b: &[(JointId, f64)], share: f64) -> Vec<(JointId, f64)> {
    let mut out: Vec<(JointId, f64)> = a.iter().map(|&(j, x)| (j, x * (1.0 - share))).collect();
    for &(j, x) in b {
        match out.iter_mut().find(|(k, _)| *k == j) {
            Some(e) => e.1 += x * share,
            None => out.push((j, x * share)),
        }
    }
    out.retain(|(_, x)| *x > 0.0);
    out
}

/// Distance from `p` to the polyline `points`, and the index of its nearest segment.
fn nearest_on_chain(points: &[DVec3], p: DVec3) -> (f64, usize) {
    points
        .windows(2)
        .enumerate()
        .map(|(k, s)| (point_segment_distance(p, s[0], s[1]), k))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap_or((f64::INFINITY, 0))
}

/// Weights of `p` over the chain's joints (module docs, step 3): segment `k` (from
/// `points[k]`) moves with `joints[k]`; across joint `k` (k >= 1) the weight passes from
/// segment `k - 1` to segment `k` linearly over `2 h` of arc length, `h` the distance from `p`
/// to the chain capped at half of each neighbouring segment. The last joint (the tip) moves
/// nothing. One or two positive weights summing to one.
fn chain_weights(points: &[DVec3], joints: &[JointId], p: DVec3) -> Vec<(JointId, f64)> {
    let lengths: Vec<f64> = points.windows(2).map(|s| s[0].distance(s[1])).collect();
    let (radius, seg) = nearest_on_chain(points, p);
    let (t, _) = closest_on_segment(p, points[seg], points[seg + 1]);
    let arc: f64 = lengths[..seg].iter().sum::<f64>() + t * lengths[seg];
    let mut at = 0.0;
    // Share past each inner joint.
    let mut past = Vec::with_capacity(lengths.len() - 1);
    for k in 1..lengths.len() {
        at += lengths[k - 1];
        let h = radius.min(0.5 * lengths[k - 1]).min(0.5 * lengths[k]);
        let f = if h > 0.0 {
            ((arc - at + h) / (2.0 * h)).clamp(0.0, 1.0)
        } else if arc >= at {
            1.0
        } else {
            0.0
        };
        past.push(f);
    }
    let mut row = Vec::with_capacity(2);
    for k in 0..lengths.len() {
        let before = if k == 0 { 1.0 } else { past[k - 1] };
        let after = past.get(k).copied().unwrap_or(0.0);
        let w = before - after;
        if w > 0.0 {
            row.push((joints[k], w));
        }
    }
    row
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::Joint;

    /// Three touching fingers (capsules of radius 0.1, 0.2 apart along x) on a wrist at the
    /// origin, each a chain of three joints and a tip, and every vertex weighted evenly to the
    /// three base joints (the voxel skin's blur at its worst).
    /// Per-vertex `(joint, weight)` lists.
    type Weights = Vec<Vec<(JointId, f64)>>;

    fn blurred_hand() -> (Mesh, Skeleton, Weights, Vec<f64>) {
        let xs = vec![-0.2, 0.0, 0.2];
        let mut mesh = Mesh {
            positions: Vec::new(),
            triangles: Vec::new(),
        };
        for &x in &xs {
            let c = Mesh::capsule(DVec3::new(x, 0.8, 0.0), 0.1, 0.4, 6, 16);
            let offset = mesh.positions.len() as u32;
            mesh.positions.extend(c.positions);
            mesh.triangles
                .extend(c.triangles.iter().map(|t| t.map(|v| v + offset)));
        }
        let mut joints = vec![
            Joint::new("forearm", None, DVec3::new(0.0, -1.0, 0.0)),
            Joint::new("wrist", Some(JointId(0)), DVec3::ZERO),
        ];
        let mut bases = Vec::new();
        for &x in &xs {
            let mut parent = JointId(1);
            bases.push(JointId(joints.len()));
            for (k, y) in [0.3, 0.6, 0.9, 1.3].into_iter().enumerate() {
                let mut j = Joint::new(format!("f{x}_{k}"), Some(parent), DVec3::new(x, y, 0.0));
                j.deform = k < 3;
                joints.push(j);
                parent = JointId(joints.len() - 1);
            }
        }
        let skeleton = Skeleton { joints };
        let weights = vec![bases.iter().map(|&b| (b, 1.0 / 3.0)).collect(); mesh.positions.len()];
        (mesh, skeleton, weights, xs)
    }

    #[test]
    fn each_finger_takes_its_own_bones_and_the_weights_stay_a_partition() {
        let (mesh, skeleton, mut weights, xs) = blurred_hand();
        let engine = digit_weights(&mesh, &skeleton, &[JointId(1)], &mut weights);
        for (v, row) in weights.iter().enumerate() {
            assert!(!row.is_empty(), "vertex {v} unweighted");
            assert!(row.iter().all(|(_, w)| *w >= 0.0), "vertex {v}: {row:?}");
            let sum: f64 = row.iter().map(|(_, w)| w).sum();
            assert!((sum - 1.0).abs() < 1e-9, "vertex {v} sums to {sum}");
            let e: f32 = engine.weights[v].iter().sum();
            assert!((e - 1.0).abs() < 1e-4 && engine.weights[v].len() <= 4);
            // The finger (capsule) this vertex lies on: its joints only (and the wrist).
            let p = mesh.positions[v];
            let finger = v / (mesh.positions.len() / xs.len());
            for (j, w) in row {
                let name = &skeleton.joint(*j).name;
                assert!(
                    name == "wrist" || name.starts_with(&format!("f{}_", xs[finger])),
                    "vertex {v} at {p:?} on finger {finger} weighs {name} by {w}"
                );
                assert!(skeleton.joint(*j).deform, "vertex {v}: {name}");
            }
        }
    }

    #[test]
    fn mid_bone_vertices_take_one_joint_and_joints_blend_two() {
        let points = [
            DVec3::ZERO,
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ];
        let joints = [JointId(0), JointId(1), JointId(2)];
        let mid = chain_weights(&points, &joints, DVec3::new(0.1, 1.5, 0.0));
        assert_eq!(mid, vec![(JointId(1), 1.0)]);
        let at_joint = chain_weights(&points, &joints, DVec3::new(0.1, 1.0, 0.0));
        assert_eq!(at_joint.len(), 2);
        assert!((at_joint[0].1 - 0.5).abs() < 1e-9, "{at_joint:?}");
    }
}

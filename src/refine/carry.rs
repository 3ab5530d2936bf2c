//! Moving a skeleton's joints to refined positions: the joints in between follow by
//! interpolated displacement, joint frames turn with their segments.

use crate::skeleton::{JointId, Skeleton};
use glam::{DQuat, DVec3};
use std::collections::BTreeMap;

/// Returns `skeleton` with the joints of `targets` at their new positions. A joint between a
/// moved ancestor and a moved descendant (spine, clavicle) is displaced like both, blended by
/// its position along the original path between them; a joint above the moved ones like its
/// nearest moved descendant; joints beyond the last moved joint of their chain (fingers, toes,
/// head and jaw ends) keep their positions. Each frame is turned by the shortest rotation taking the old
/// direction to the joint's first child onto the new one (leaves take their parent's turn).
pub fn carry(skeleton: &Skeleton, targets: &BTreeMap<JointId, DVec3>) -> Skeleton {
    let n = skeleton.len();
    let old: Vec<DVec3> = skeleton.joints.iter().map(|j| j.position).collect();
    let moved = |j: usize| targets.get(&JointId(j)).map(|t| *t - old[j]);
    let children: Vec<Vec<JointId>> = (0..n).map(|j| skeleton.children(JointId(j))).collect();
    let mut out = skeleton.clone();
    for j in 0..n {
        if let Some(d) = moved(j) {
            out.joints[j].position = old[j] + d;
            continue;
        }
        // Nearest moved ancestor, with the path length to it.
        let mut ancestor = None;
        let (mut k, mut up_length) = (j, 0.0);
        while let Some(p) = skeleton.joints[k].parent {
            up_length += old[k].distance(old[p.0]);
            if let Some(d) = moved(p.0) {
                ancestor = Some((d, up_length));
                break;
            }
            k = p.0;
        }
        // Nearest moved descendant (fewest hops, then lowest index), with its path length.
        let mut descendant = None;
        let mut frontier: Vec<(usize, f64)> = vec![(j, 0.0)];
        while descendant.is_none() && !frontier.is_empty() {
            let mut next = Vec::new();
            for &(k, length) in &frontier {
                for c in &children[k] {
                    let l = length + old[k].distance(old[c.0]);
                    if let Some(d) = moved(c.0) {
                        if descendant.is_none() {
                            descendant = Some((d, l));
                        }
                    } else {
                        next.push((c.0, l));
                    }
                }
            }
            frontier = next;
        }
        let d = match (ancestor, descendant) {
            (Some((da, la)), Some((dd, ld))) if la + ld > 0.0 => da.lerp(dd, la / (la + ld)),
            // Beyond the last moved joint (fingers, toes, head and jaw ends): kept where the
            // fit put them, inside the figure (moving them with the wrist or ankle can push
            // toes through the floor).
            (Some(_), None) => DVec3::ZERO,
            (Some((da, _)), Some(_)) => da,
            (None, Some((dd, _))) => dd,
            (None, None) => DVec3::ZERO,
        };
        out.joints[j].position = old[j] + d;
    }
    let mut turn = vec![DQuat::IDENTITY; n];
    for j in 0..n {
        let parent_turn = skeleton.joints[j]
            .parent
            .map_or(DQuat::IDENTITY, |p| turn[p.0]);
        turn[j] = children[j]
            .first()
            .and_then(|c| {
                let a = (old[c.0] - old[j]).try_normalize()?;
                let b = (out.joints[c.0].position - out.joints[j].position).try_normalize()?;
                Some(DQuat::from_rotation_arc(a, b))
            })
            .unwrap_or(parent_turn);
        out.joints[j].frame = (turn[j] * skeleton.joints[j].frame).normalize();
    }
    out
}

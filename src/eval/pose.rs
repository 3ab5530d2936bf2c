//! Re-posing a skinned figure for robustness studies: world matrices that set both upper arms
//! at an angle below the horizontal (T-pose 0°, A-poses, arms low), for linear blend skinning
//! with the figure's own weights (`skin::check::blend`). `examples/pose_study.rs` rigs real
//! characters re-posed this way by their artists' weights and scores the core joints.

use crate::skeleton::{JointId, Skeleton};
use glam::{DAffine3, DQuat, DVec3};
use std::collections::BTreeMap;

/// One world matrix per joint of `skeleton` that turns each arm (the subtree of the joint
/// `canonical` maps `shoulder_L` / `shoulder_R` to) about the shoulder joint so that its upper
/// arm (shoulder → elbow) points `degrees` below the horizontal, straight out to its side
/// (`left = up × forward`; the right arm mirrored); every other joint at rest (identity). An
/// arm whose shoulder or elbow the map lacks stays at rest.
pub fn arms_below_horizontal(
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    degrees: f64,
    up: DVec3,
    forward: DVec3,
) -> Vec<DAffine3> {
    let up = up.normalize_or(DVec3::Y);
    let left = up.cross(forward).normalize_or(DVec3::X);
    let (sin, cos) = degrees.to_radians().sin_cos();
    let mut matrices = vec![DAffine3::IDENTITY; skeleton.len()];
    for (shoulder, elbow, side) in [
        ("shoulder_L", "elbow_L", 1.0),
        ("shoulder_R", "elbow_R", -1.0),
    ] {
        let (Some(&s), Some(&e)) = (canonical.get(shoulder), canonical.get(elbow)) else {
            continue;
        };
        if s.0 >= skeleton.len() || e.0 >= skeleton.len() {
            continue;
        }
        let pivot = skeleton.joint(s).position;
        let Some(now) = (skeleton.joint(e).position - pivot).try_normalize() else {
            continue;
        };
        let target = left * (side * cos) - up * sin;
        let turn = DAffine3::from_translation(pivot)
            * DAffine3::from_quat(DQuat::from_rotation_arc(now, target))
            * DAffine3::from_translation(-pivot);
        for k in subtree(skeleton, s) {
            matrices[k] = turn;
        }
    }
    matrices
}

/// The joints of `root`'s subtree (a [`Skeleton`] lists parents before their children).
fn subtree(skeleton: &Skeleton, root: JointId) -> Vec<usize> {
    let mut inside = vec![false; skeleton.len()];
    for (k, joint) in skeleton.joints.iter().enumerate() {
        inside[k] = k == root.0 || joint.parent.is_some_and(|p| p.0 < k && inside[p.0]);
    }
    (0..skeleton.len()).filter(|&k| inside[k]).collect()
}

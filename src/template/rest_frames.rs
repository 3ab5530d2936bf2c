//! An engine's rest frames: the bone-axis convention of its skeleton (which local axis runs
//! along the bone, and the roll about it), so that animations made for the engine's rig play
//! on skelfit's. glTF animations give each joint's local rotation outright, not relative to
//! the rest pose, so a rig whose rest frames differ from the engine's poses wrongly under the
//! engine's clips even with the same names and hierarchy.
//!
//! A preset's `rest_frames` table (written by `tools/preset_rest_frames.py` from a reference
//! rig) holds, per engine joint, its rest frame's x and y axes and the direction to the child
//! its bone points at, in the figure's body axes (left, up, forward). Each frame is carried
//! onto the fitted bone by the shortest rotation taking the reference direction to the child
//! onto the fitted one: a T-posed arm gets the frame of the reference's A-posed arm turned
//! with the arm.

use crate::skeleton::{Dof, Joint, LocalAxis, Skeleton};
use glam::{DMat3, DQuat, DVec3};
use serde::Deserialize;
use std::collections::BTreeMap;

/// A preset's rest frames.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RestFrames {
    /// The reference rig they come from and how.
    pub source: String,
    /// Engine joint name → its rest frame.
    pub joints: BTreeMap<String, RestFrame>,
}

/// One engine joint's rest frame in the reference rig, in body axes `[left, up, forward]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RestFrame {
    /// The local x axis.
    pub x: [f64; 3],
    /// The local y axis.
    pub y: [f64; 3],
    /// The child the bone points at, if any.
    #[serde(default)]
    pub child: Option<String>,
    /// The unit direction from the joint to that child.
    #[serde(default)]
    pub to_child: Option<[f64; 3]>,
}

impl RestFrames {
    /// What is wrong with the table, if anything: axes that are not unit and orthogonal, or a
    /// child without its direction.
    pub(crate) fn check(&self) -> Result<(), String> {
        for (name, f) in &self.joints {
            let (x, y) = (DVec3::from(f.x), DVec3::from(f.y));
            let unit = |v: DVec3| (v.length() - 1.0).abs() < 1e-3;
            if !unit(x) || !unit(y) || x.dot(y).abs() > 1e-3 {
                return Err(format!(
                    "rest frame of {name:?}: x and y are not unit and orthogonal"
                ));
            }
            if f.child.is_some() != f.to_child.is_some() {
                return Err(format!(
                    "rest frame of {name:?}: \"child\" and \"to_child\" go together"
                ));
            }
        }
        Ok(())
    }
}

/// Gives every joint of `skeleton` named in `frames` the engine's rest frame, carried onto
/// the fitted bone: turned by the shortest rotation taking the reference direction to the
/// named child onto the direction to that child here (the parent's turn when this skeleton
/// lacks the child). Joints the table does not name (end joints such as `HeadTop_End`) take
/// their parent's frame, as in the engine's rigs. Each joint's degrees of freedom move to the
/// new local axis nearest their old one (limits negated when it points the other way). `up`
/// and `forward` are the figure's axes in the skeleton's frame.
pub fn apply_rest_frames(skeleton: &mut Skeleton, frames: &RestFrames, up: DVec3, forward: DVec3) {
    let (Some(up), Some(forward)) = (up.try_normalize(), forward.try_normalize()) else {
        return;
    };
    let Some(left) = up.cross(forward).try_normalize() else {
        return;
    };
    let forward = left.cross(up);
    let world = |v: [f64; 3]| left * v[0] + up * v[1] + forward * v[2];
    let n = skeleton.len();
    let mut turn = vec![DQuat::IDENTITY; n];
    for k in 0..n {
        let parent = skeleton.joints[k].parent.map(|p| p.0);
        let parent_turn = parent.map_or(DQuat::IDENTITY, |p| turn[p]);
        let frame = match frames.joints.get(&skeleton.joints[k].name) {
            Some(reference) => {
                turn[k] = carried(skeleton, k, reference, &world).unwrap_or(parent_turn);
                engine_frame(turn[k], world(reference.x), world(reference.y))
            }
            None => {
                turn[k] = parent_turn;
                parent.map(|p| skeleton.joints[p].frame)
            }
        };
        if let Some(frame) = frame.filter(|f| f.is_finite()) {
            let joint = &mut skeleton.joints[k];
            joint.dofs = moved_dofs(joint, frame);
            joint.frame = frame;
        }
    }
}

/// The shortest rotation taking the reference direction to `reference.child` onto the fitted
/// direction to the joint's child of that name; `None` without one.
fn carried(
    skeleton: &Skeleton,
    k: usize,
    reference: &RestFrame,
    world: &dyn Fn([f64; 3]) -> DVec3,
) -> Option<DQuat> {
    let child = skeleton.find(reference.child.as_deref()?)?;
    let joint = &skeleton.joints[k];
    if skeleton.joints[child.0].parent.map(|p| p.0) != Some(k) {
        return None;
    }
    let here = (skeleton.joints[child.0].position - joint.position).try_normalize()?;
    let there = world(reference.to_child?).try_normalize()?;
    Some(DQuat::from_rotation_arc(there, here))
}

/// The unit rotation whose local x and y are `turn` applied to `x` and `y`, made orthonormal
/// (y kept, x made perpendicular to it); `None` when they are parallel.
fn engine_frame(turn: DQuat, x: DVec3, y: DVec3) -> Option<DQuat> {
    let y = (turn * y).try_normalize()?;
    let x = turn * x;
    let x = (x - y * x.dot(y)).try_normalize()?;
    let z = x.cross(y);
    Some(DQuat::from_mat3(&DMat3::from_cols(x, y, z)).normalize())
}

/// `joint`'s degrees of freedom about the axes of `frame` nearest to the old ones.
fn moved_dofs(joint: &Joint, frame: DQuat) -> Vec<Dof> {
    let axis = |a: LocalAxis| match a {
        LocalAxis::X => DVec3::X,
        LocalAxis::Y => DVec3::Y,
        LocalAxis::Z => DVec3::Z,
    };
    joint
        .dofs
        .iter()
        .map(|dof| {
            let local = frame.inverse() * (joint.frame * axis(dof.axis));
            let (new_axis, component) = [
                (LocalAxis::X, local.x),
                (LocalAxis::Y, local.y),
                (LocalAxis::Z, local.z),
            ]
            .into_iter()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            .unwrap_or((dof.axis, 1.0));
            if component < 0.0 {
                Dof {
                    axis: new_axis,
                    min: -dof.max,
                    max: -dof.min,
                }
            } else {
                Dof {
                    axis: new_axis,
                    ..*dof
                }
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::{JointId, Skeleton};

    fn table(entries: &[(&str, RestFrame)]) -> RestFrames {
        RestFrames {
            source: "test".into(),
            joints: entries
                .iter()
                .map(|(n, f)| (n.to_string(), f.clone()))
                .collect(),
        }
    }

    /// An arm in T-pose (along +x, the figure's left, with up +y and forward +z) given the
    /// frame of a reference arm hanging down: the frame turns with the arm, the hand (not in
    /// the table) takes the arm's frame, and the hinge DOF about the old x follows its axis.
    #[test]
    fn a_reference_frame_is_carried_onto_the_fitted_bone() {
        let mut s = Skeleton::default();
        s.joints.push(Joint::new("arm", None, DVec3::ZERO));
        s.joints.push(Joint::new(
            "hand",
            Some(JointId(0)),
            DVec3::new(0.5, 0.0, 0.0),
        ));
        s.joints[0].dofs = vec![Dof {
            axis: LocalAxis::Y,
            min: -0.5,
            max: 1.5,
        }];
        let frames = table(&[(
            "arm",
            RestFrame {
                x: [0.0, 0.0, -1.0],
                y: [0.0, -1.0, 0.0],
                child: Some("hand".into()),
                to_child: Some([0.0, -1.0, 0.0]),
            },
        )]);
        apply_rest_frames(&mut s, &frames, DVec3::Y, DVec3::Z);
        let arm = s.joints[0].frame;
        // Local +y runs along the fitted arm (towards +x); x stays backward.
        assert!((arm * DVec3::Y).distance(DVec3::X) < 1e-9, "{arm:?}");
        assert!((arm * DVec3::X).distance(-DVec3::Z) < 1e-9, "{arm:?}");
        assert!(s.joints[1].frame.angle_between(arm) < 1e-9);
        // The old local y (world +y) is the new local -z: limits negated and swapped.
        assert_eq!(s.joints[0].dofs[0].axis, LocalAxis::Z);
        assert_eq!(
            (s.joints[0].dofs[0].min, s.joints[0].dofs[0].max),
            (-1.5, 0.5)
        );
    }

    #[test]
    fn a_table_with_crooked_axes_is_refused() {
        let bad = table(&[(
            "arm",
            RestFrame {
                x: [1.0, 0.0, 0.0],
                y: [0.6, 0.8, 0.0],
                child: None,
                to_child: None,
            },
        )]);
        assert!(bad.check().unwrap_err().contains("arm"));
    }
}

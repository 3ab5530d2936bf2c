//! Joint frames (dissertation 8.1): local z along the segment the joint rotates (away from the
//! root), y dorsal (axial joints) or in the bending plane (limb joints), x completing a
//! right-handed frame: lateral for axial joints, the hinge axis for limb joints.

use super::axial::perpendicular;
use super::BodyFrame;
use crate::skeleton::{JointId, Skeleton};
use glam::{DMat3, DQuat, DVec3};

/// How a joint's frame is set up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FrameKind {
    /// Head, neck, trunk, tail: y is the dorsal direction normal to the path.
    Axial,
    /// Girdles, limbs, digits: x is the bending axis (normal of the plane of the proximal and
    /// distal segments) or, for a straight limb, the figure's lateral axis.
    Limb,
}

/// Smallest sine of the angle between the proximal and distal segments that defines a bending
/// plane (5°): below it the limb counts as straight.
const MIN_BEND_SINE: f64 = 0.087;

/// Sets every joint's frame from its distal target `next` (its parent's frame direction when
/// `None`).
pub(crate) fn set_frames(
    skeleton: &mut Skeleton,
    next: &[Option<DVec3>],
    kind: &[FrameKind],
    body: &BodyFrame,
) {
    let mut z_of: Vec<DVec3> = Vec::with_capacity(skeleton.len());
    for k in 0..skeleton.len() {
        let joint = &skeleton.joints[k];
        let parent = joint.parent.map(|p| p.0);
        let incoming = parent
            .map(|p| joint.position - skeleton.joints[p].position)
            .and_then(|d| d.try_normalize());
        let z = next[k]
            .and_then(|n| (n - joint.position).try_normalize())
            .or(incoming)
            .or_else(|| parent.map(|p| z_of[p]))
            .unwrap_or(body.forward);
        let x = match kind[k] {
            FrameKind::Axial => {
                let y = [body.dorsal, body.up, body.forward]
                    .into_iter()
                    .map(|h| perpendicular(h, z))
                    .find(|v| *v != DVec3::ZERO)
                    .unwrap_or(DVec3::Y);
                y.cross(z)
            }
            FrameKind::Limb => {
                let bend = incoming
                    .map(|i| i.cross(z))
                    .filter(|n| n.length() > MIN_BEND_SINE)
                    .map(|n| {
                        let n = n.normalize();
                        if n.dot(body.left) < 0.0 {
                            -n
                        } else {
                            n
                        }
                    });
                bend.into_iter()
                    .chain([body.left, body.up, body.forward])
                    .map(|h| perpendicular(h, z))
                    .find(|v| *v != DVec3::ZERO)
                    .unwrap_or(DVec3::X)
            }
        };
        let y = z.cross(x);
        let m = DMat3::from_cols(x, y, z);
        skeleton.joints[k].frame = DQuat::from_mat3(&m).normalize();
        z_of.push(z);
    }
}

/// Largest angle between a joint's frame z and the child it aims at for the child to count as
/// the one the frame follows (45°): a frame that points between its children (a pelvis whose
/// fitted z ran to a trunk point the refinement moved) takes no child's turn.
const MIN_AIM_COSINE: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Turns every joint's frame so that its z runs exactly along its bone to the joint's final
/// positions, after the stages that move joints (refinement, symmetry, digits) and keep the
/// fit's frames: each frame turns by the shortest rotation taking its z onto the direction to
/// the child it aims at — a wrist's the middle digit's base (`wrist_middle`), else the child
/// nearest in direction to z, within 45°. Frames without such a child (leaves, fans) take
/// their parent's turn. The roll about the bone (x, the hinge or lateral axis) is kept as the
/// fit chose it.
pub(crate) fn realign_frames(skeleton: &mut Skeleton, wrist_middle: &[(JointId, JointId)]) {
    let n = skeleton.len();
    let mut turn = vec![DQuat::IDENTITY; n];
    for k in 0..n {
        let joint = &skeleton.joints[k];
        let z = joint.frame * DVec3::Z;
        let towards = |c: JointId| (skeleton.joints[c.0].position - joint.position).try_normalize();
        let aimed = wrist_middle
            .iter()
            .find(|(w, _)| w.0 == k)
            .and_then(|(_, m)| towards(*m))
            .or_else(|| {
                skeleton
                    .children(JointId(k))
                    .into_iter()
                    .filter_map(towards)
                    .map(|d| (d.dot(z), d))
                    .filter(|(c, _)| *c >= MIN_AIM_COSINE)
                    .max_by(|a, b| a.0.total_cmp(&b.0))
                    .map(|(_, d)| d)
            });
        turn[k] = match aimed {
            Some(d) => DQuat::from_rotation_arc(z, d),
            None => joint.parent.map_or(DQuat::IDENTITY, |p| turn[p.0]),
        };
        let frame = (turn[k] * joint.frame).normalize();
        if frame.is_finite() {
            skeleton.joints[k].frame = frame;
        }
    }
}

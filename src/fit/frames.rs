//! Joint frames (dissertation 8.1): local z along the segment the joint rotates (away from the
//! root), y dorsal (axial joints) or in the bending plane (limb joints), x completing a
//! right-handed frame: lateral for axial joints, the hinge axis for limb joints.

use super::axial::perpendicular;
use super::BodyFrame;
use crate::skeleton::Skeleton;
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

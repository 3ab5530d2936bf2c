//! Joint frames of the control skeleton (dissertation ch.5.2.5).

use crate::skeleton::Skeleton;
use glam::{DMat3, DQuat, DVec3};

/// Two directions span a plane when the sine of their angle exceeds this (1 degree): below it
/// the cross product's direction is dominated by rounding of the voxel positions.
const MIN_PLANE_SINE: f64 = 0.017_452_406;

/// `a x b` normalised when `a` and `b` span a plane.
fn normal(a: DVec3, b: DVec3) -> Option<DVec3> {
    let n = a.cross(b);
    (n.length() > MIN_PLANE_SINE * a.length() * b.length()).then(|| n.normalize())
}

/// Sets every joint's frame (ch.5.2.5): z along the distal segment (along the proximal one for
/// end effectors), x perpendicular to the plane of the proximal and distal segments
/// (`proximal x distal`), y completing a right-handed frame. When that plane is degenerate, the
/// nearest ancestral segment that spans a plane with z is used (proximal search), then the
/// nearest descendant segment in breadth-first order (distal search, `z x distal`), then any
/// axis perpendicular to z.
pub(crate) fn set_frames(
    skeleton: &mut Skeleton,
    incoming: &[Option<DVec3>],
    outgoing: &[Option<DVec3>],
) {
    let n = skeleton.joints.len();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (j, joint) in skeleton.joints.iter().enumerate() {
        if let Some(parent) = joint.parent {
            children[parent.0].push(j);
        }
    }
    for j in 0..n {
        let (z, mut proximal) = match (outgoing[j], incoming[j]) {
            (Some(d), _) => (d, Some(j)),
            (None, Some(p)) => (p, skeleton.joints[j].parent.map(|p| p.0)),
            (None, None) => continue,
        };
        if z.length_squared() == 0.0 {
            continue;
        }
        let mut x = None;
        while let (None, Some(k)) = (x, proximal) {
            x = incoming[k].and_then(|a| normal(a, z));
            proximal = skeleton.joints[k].parent.map(|p| p.0);
        }
        let mut queue: std::collections::VecDeque<usize> = children[j].iter().copied().collect();
        while let (None, Some(k)) = (x, queue.pop_front()) {
            x = outgoing[k].and_then(|c| normal(z, c));
            queue.extend(children[k].iter().copied());
        }
        let z = z.normalize();
        let x = x.unwrap_or_else(|| z.any_orthonormal_vector());
        let y = z.cross(x);
        skeleton.joints[j].frame = DQuat::from_mat3(&DMat3::from_cols(x, y, z)).normalize();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::{Joint, JointId};

    #[test]
    fn an_elbow_gets_z_along_the_forearm_and_x_across_the_bend() {
        let mut s = Skeleton::default();
        s.joints.push(Joint::new("root", None, DVec3::ZERO));
        s.joints.push(Joint::new(
            "elbow",
            Some(JointId(0)),
            DVec3::new(1.0, 0.0, 0.0),
        ));
        s.joints.push(Joint::new(
            "hand",
            Some(JointId(1)),
            DVec3::new(1.0, 1.0, 0.0),
        ));
        let incoming = [None, Some(DVec3::X), Some(DVec3::Y)];
        let outgoing = [Some(DVec3::X), Some(DVec3::Y), None];
        set_frames(&mut s, &incoming, &outgoing);
        let m = s.frame_matrix(JointId(1));
        assert!((m.z_axis - DVec3::Y).length() < 1e-12);
        assert!((m.x_axis - DVec3::Z).length() < 1e-12);
        assert!((m.y_axis - DVec3::X).length() < 1e-12);
        // The root's plane is degenerate proximally: the distal search finds the bend.
        let m = s.frame_matrix(JointId(0));
        assert!((m.z_axis - DVec3::X).length() < 1e-12);
        assert!((m.x_axis - DVec3::Z).length() < 1e-12);
        // The end effector: z along its proximal segment, x from its parent's plane.
        let m = s.frame_matrix(JointId(2));
        assert!((m.z_axis - DVec3::Y).length() < 1e-12);
        assert!((m.x_axis - DVec3::Z).length() < 1e-12);
    }
}

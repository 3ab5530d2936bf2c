//! Joint positions along a digit's contour path, and the digit frames.

use super::contour::Branch;
use glam::{DMat3, DQuat, DVec3};

/// A digit's joints: base (01), middle (02), last (03), and the tip (end marker).
#[derive(Debug, Clone, Copy)]
pub(super) struct DigitJoints {
    /// Base, middle and last joint, mesh frame.
    pub joints: [DVec3; 3],
    /// The tip.
    pub tip: DVec3,
}

/// The joints of `branch`: the digit is `length = free length / free_share` long from its
/// base joint to the tip; the last and middle joints sit at `from_tip` fractions of it from
/// the tip, along the path and beyond its web end along the digit's axis. A finger's base
/// continues along that axis; a thumb's (`towards = Some(wrist)`) turns from the
/// metacarpophalangeal joint towards the wrist, as the first metacarpal does.
pub(super) fn place_digit(
    branch: &Branch,
    free_share: f64,
    from_tip: [f64; 2],
    towards: Option<DVec3>,
    fallback_axis: DVec3,
) -> DigitJoints {
    let path = &branch.path;
    let mut arc = Vec::with_capacity(path.len());
    let mut total = 0.0;
    for (i, p) in path.iter().enumerate() {
        if i > 0 {
            total += p.distance(path[i - 1]);
        }
        arc.push(total);
    }
    // Direction from the tip towards the base, over the proximal third of the path.
    let n = (path.len() / 3).max(2).min(path.len());
    let axis = (path[path.len() - 1] - path[path.len() - n])
        .try_normalize()
        .unwrap_or(fallback_axis);
    let at = |s: f64| -> DVec3 {
        if s <= total {
            let i = arc
                .partition_point(|&a| a < s)
                .clamp(1, path.len().max(2) - 1);
            if path.len() < 2 {
                return path[0];
            }
            let span = (arc[i] - arc[i - 1]).max(1e-12);
            path[i - 1].lerp(path[i], ((s - arc[i - 1]) / span).clamp(0.0, 1.0))
        } else {
            path[path.len() - 1] + axis * (s - total)
        }
    };
    let length = total / free_share;
    let last = at(from_tip[0] * length);
    let middle = at(from_tip[1] * length);
    let base = match towards {
        Some(target) => {
            let dir = (target - middle).try_normalize().unwrap_or(axis);
            middle + dir * (1.0 - from_tip[1]) * length
        }
        None => at(length),
    };
    DigitJoints {
        joints: [base, middle, last],
        tip: path[0],
    }
}

/// The rest frame of a digit joint at `from` whose segment runs to `to`: z along the
/// segment, x the curl axis (`z × palm`), so that a positive rotation about x turns z towards
/// `palm` (the palm's normal on its inner side).
pub(super) fn digit_frame(from: DVec3, to: DVec3, palm: DVec3) -> DQuat {
    let Some(z) = (to - from).try_normalize() else {
        return DQuat::IDENTITY;
    };
    let x = z
        .cross(palm)
        .try_normalize()
        .unwrap_or_else(|| z.any_orthonormal_vector());
    let y = z.cross(x);
    DQuat::from_mat3(&DMat3::from_cols(x, y, z)).normalize()
}

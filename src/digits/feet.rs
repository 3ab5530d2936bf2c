//! The feet of an upright figure at their own resolution (issue 25): the toe joint at the ball
//! of the foot and the toe end at the front tip, both read from the foot's surface.

use super::surface::{hand_surface, HandSurface};
use super::{DigitOptions, DigitWarning};
use crate::fit::Fit;
use crate::math::principal_axes;
use crate::mesh::{slice_plane, Mesh};
use crate::refine::carry;
use crate::skeleton::canonical::CanonicalJoints;
use crate::skeleton::{Canonical, JointId, Side, Skeleton};
use crate::template::{Posture, Template};
use glam::DVec3;
use nalgebra::{Matrix3, Vector3};
use std::collections::BTreeMap;
use std::f64::consts::FRAC_1_SQRT_2;

/// Where one foot's joints go.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct FootJoints {
    /// The ball of the foot (metatarsophalangeal joints): the centre of the foot's widest
    /// cross-section ahead of the ankle.
    pub ball: DVec3,
    /// The front tip of the foot.
    pub tip: DVec3,
}

/// Moves each foot's toe joint (`toe_L`, `toe_R`) to the ball of the foot and the end of its
/// toe chain to the front tip of the foot, both found on the foot's surface (module docs of
/// [`super`]); the joints between the ankle and the toe and between the toe and its end keep
/// their share of the way, frames turn with their segments. Upright templates only (a
/// horizontal figure's paws and hooves keep the fit's single digit chain). Does nothing when
/// `options.feet` is off. `facing` is the figure's forward: a foot whose footprint shows no
/// direction, or was read from the heel, points there (within 45° of it).
///
/// Returns a warning per foot whose surface could not be read (it keeps the fit's chain).
pub fn fit_feet(
    mesh: &Mesh,
    template: &Template,
    fit: &mut Fit,
    up: DVec3,
    facing: DVec3,
    options: &DigitOptions,
) -> Vec<DigitWarning> {
    let readings = read_feet(mesh, template, fit, up, facing, options);
    place_feet(mesh, template, fit, up, facing, options, readings)
}

/// One foot read before any foot is placed: the knee and ankle positions it was read from and
/// where its joints go (`None`: its surface could not be read).
pub(super) struct FootReading {
    side: Side,
    from: (DVec3, DVec3),
    foot: Option<FootJoints>,
}

/// A foot chain: the joints from the ankle to the toe chain's end, and the toe's index in it
/// ([`foot_chain`]).
type FootChain = (Vec<JointId>, usize);

/// The knee and ankle positions of `side`'s foot chain, when the fit has its knee, ankle and
/// toe and the toe hangs below the ankle, with the chain.
fn leg_end(fit: &Fit, side: Side) -> Option<((DVec3, DVec3), FootChain)> {
    let key = |k: fn(Side) -> Canonical| fit.canonical.joint_of(k(side));
    let (Some(knee), Some(ankle), Some(toe)) = (
        key(Canonical::Knee),
        key(Canonical::Ankle),
        key(Canonical::Toe),
    ) else {
        return None;
    };
    let chain = foot_chain(&fit.skeleton, ankle, toe)?;
    let from = (
        fit.skeleton.joint(knee).position,
        fit.skeleton.joint(ankle).position,
    );
    Some((from, chain))
}

/// The feet of [`fit_feet`] read from the fit as it stands, both at once (on two threads):
/// reading a foot only looks at the mesh and at its leg's knee and ankle. Empty when the
/// stage does not apply.
pub(super) fn read_feet(
    mesh: &Mesh,
    template: &Template,
    fit: &Fit,
    up: DVec3,
    facing: DVec3,
    options: &DigitOptions,
) -> Vec<FootReading> {
    if !options.feet || template.posture != Posture::Upright {
        return Vec::new();
    }
    let Some(up) = up.try_normalize() else {
        return Vec::new();
    };
    let read = |side: Side| {
        let (from, _) = leg_end(fit, side)?;
        Some(FootReading {
            side,
            from,
            foot: find_foot(mesh, from.0, from.1, up, facing, options),
        })
    };
    let (left, right) = rayon::join(|| read(Side::Left), || read(Side::Right));
    left.into_iter().chain(right).collect()
}

/// Places each foot of [`fit_feet`] from its reading, left then right; a foot whose knee or
/// ankle stands elsewhere than where it was read (not the case when the readings come from
/// [`read_feet`] on this fit, also after the hands were rebuilt: placing a foot or a hand
/// moves no knee or ankle) is read again here. Returns a warning per foot whose surface could
/// not be read.
pub(super) fn place_feet(
    mesh: &Mesh,
    template: &Template,
    fit: &mut Fit,
    up: DVec3,
    facing: DVec3,
    options: &DigitOptions,
    readings: Vec<FootReading>,
) -> Vec<DigitWarning> {
    let mut warnings = Vec::new();
    if !options.feet || template.posture != Posture::Upright {
        return warnings;
    }
    let Some(up) = up.try_normalize() else {
        return warnings;
    };
    let mut readings = readings.into_iter().peekable();
    for side in Side::BOTH {
        let Some((from, chain)) = leg_end(fit, side) else {
            continue;
        };
        let foot = match readings.next_if(|r| r.side == side) {
            Some(r) if r.from == from => r.foot,
            _ => find_foot(mesh, from.0, from.1, up, facing, options),
        };
        match foot {
            Some(foot) => place_foot(&mut fit.skeleton, &chain, foot),
            None => warnings.push(DigitWarning::NoFoot { side }),
        }
    }
    warnings
}

/// The joints from `ankle` to `toe` (both included) and on from `toe` while each has a single
/// child (the toe chain to its end), with the index of `toe` in it; `None` when `toe` does not
/// hang below `ankle`.
fn foot_chain(skeleton: &Skeleton, ankle: JointId, toe: JointId) -> Option<FootChain> {
    let mut up = vec![toe];
    while *up.last()? != ankle {
        up.push(skeleton.joint(*up.last()?).parent?);
    }
    up.reverse();
    let at = up.len() - 1;
    while let [only] = skeleton.children(*up.last()?).as_slice() {
        up.push(*only);
    }
    Some((up, at))
}

/// Places the chain: the toe at the ball, its last joint (when past the toe) at the tip, the
/// joints between at their arc-length fractions of the old chain along the straight segments
/// ankle → ball and ball → tip.
fn place_foot(skeleton: &mut Skeleton, chain: &FootChain, foot: FootJoints) {
    let (joints, at) = (&chain.0, chain.1);
    let old: Vec<DVec3> = joints.iter().map(|&j| skeleton.joint(j).position).collect();
    // Every other joint stays (`carry` would move the ones above a moved joint with it).
    let mut targets: BTreeMap<JointId, DVec3> = skeleton
        .joints
        .iter()
        .enumerate()
        .map(|(i, j)| (JointId(i), j.position))
        .collect();
    let ankle = old[0];
    let mut spread = |range: std::ops::RangeInclusive<usize>, from: DVec3, to: DVec3| {
        let (s, e) = (*range.start(), *range.end());
        let total: f64 = old[s..=e].windows(2).map(|w| w[0].distance(w[1])).sum();
        let mut arc = 0.0;
        for i in s + 1..=e {
            arc += old[i - 1].distance(old[i]);
            let f = if total > 0.0 { arc / total } else { 1.0 };
            targets.insert(joints[i], from.lerp(to, f));
        }
    };
    spread(0..=at, ankle, foot.ball);
    if joints.len() > at + 1 {
        spread(at..=joints.len() - 1, foot.ball, foot.tip);
    }
    *skeleton = carry(skeleton, &targets);
}

/// The ball and tip of the foot below `ankle` (`knee` above it gives the shank's direction
/// and length), from the foot's surface below the ankle's height: the foot's direction is its
/// footprint's long axis, kept within 45° of `facing` ([`towards_facing`]); the tip is the
/// surface's extreme point along it (its lateral and vertical place the mean of the surface
/// within a small cap there); the ball is the centre of the widest cross-section normal to
/// the foot's direction between the ankle and the tip (the middle of the stretch of sections
/// at least `ball_plateau` of the widest: the forefoot is about as wide across all metatarsal
/// heads). `None` when the surface below the ankle is not found or does not reach ahead of
/// it.
pub(super) fn find_foot(
    mesh: &Mesh,
    knee: DVec3,
    ankle: DVec3,
    up: DVec3,
    facing: DVec3,
    options: &DigitOptions,
) -> Option<FootJoints> {
    let shank = ankle.distance(knee);
    let axis = (ankle - knee).try_normalize()?;
    let surface = hand_surface(
        mesh,
        ankle,
        axis,
        options.foot_reach * shank,
        options.wrist_band * shank,
    )?;
    let forward = towards_facing(foot_direction(&surface, ankle, up)?, up, facing);
    // The foot is what lies below the ankle: a coarse mesh's triangles crossing the ankle's
    // plane come whole, and a boot's shaft reaches far above it.
    let sole: Vec<DVec3> = surface
        .positions
        .iter()
        .copied()
        .filter(|&p| (p - ankle).dot(up) <= 0.0)
        .collect();
    let along = |p: DVec3| (p - ankle).dot(forward);
    let front = sole.iter().map(|&p| along(p)).fold(f64::MIN, f64::max);
    let back = sole.iter().map(|&p| along(p)).fold(f64::MAX, f64::min);
    let length = front - back;
    if sole.is_empty() || front < MIN_FOOT_REACH * shank || length <= 0.0 {
        return None;
    }
    let cap: Vec<DVec3> = sole
        .iter()
        .copied()
        .filter(|&p| along(p) >= front - options.toe_cap * length)
        .collect();
    let centre = cap.iter().sum::<DVec3>() / cap.len() as f64;
    let tip = centre + forward * (front - along(centre));
    let ball = widest_section(&surface, ankle, forward, up, front, options.ball_plateau)?;
    Some(FootJoints { ball, tip })
}

/// The foot's long axis: the major principal axis of its footprint (the surface's triangles
/// projected on the ground, weighted by area), turned towards the surface point farthest from
/// the ankle's cross-section over the surface (a toe tip, not the heel).
fn foot_direction(surface: &HandSurface, ankle: DVec3, up: DVec3) -> Option<DVec3> {
    let flat = |p: DVec3| p - up * (p - ankle).dot(up);
    let mut weighted = Vec::with_capacity(surface.triangles.len());
    for t in &surface.triangles {
        let [a, b, c] = t.map(|v| surface.positions[v as usize]);
        let area = 0.5 * (b - a).cross(c - a).length();
        weighted.push((flat((a + b + c) / 3.0), area));
    }
    let total: f64 = weighted.iter().map(|w| w.1).sum();
    if total <= 0.0 {
        return None;
    }
    let mean = weighted.iter().map(|(p, w)| *p * *w).sum::<DVec3>() / total;
    let mut covariance = Matrix3::<f64>::zeros();
    for (p, w) in &weighted {
        let d = *p - mean;
        let v = Vector3::new(d.x, d.y, d.z);
        covariance += v * v.transpose() * *w;
    }
    let major = principal_axes(covariance)[0].1;
    let far = surface
        .distance
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map(|(i, _)| surface.positions[i])?;
    let major = (major - up * major.dot(up)).try_normalize()?;
    Some(if (far - ankle).dot(major) < 0.0 {
        -major
    } else {
        major
    })
}

/// `direction` (horizontal, unit) turned to where an upright figure's feet point: within 45°
/// of `facing` (the figure's forward) it stands; pointing more than 45° backwards it is turned
/// round (the footprint's axis is right, its sign was read from the heel: a boot's shaft or a
/// heel can reach farther from the ankle than the toes); more across than along the figure
/// (a round or boxy foot, a stub) the footprint shows no direction, and the foot points where
/// the figure faces. Feet turned out by more than 45° are not a rest pose; `direction` is
/// kept when `facing` has no horizontal part.
fn towards_facing(direction: DVec3, up: DVec3, facing: DVec3) -> DVec3 {
    let Some(facing) = (facing - up * facing.dot(up)).try_normalize() else {
        return direction;
    };
    let cos = direction.dot(facing);
    if cos >= FRAC_1_SQRT_2 {
        direction
    } else if cos <= -FRAC_1_SQRT_2 {
        -direction
    } else {
        facing
    }
}

/// How far ahead of the ankle a foot reaches at least, fraction of the shank (knee to ankle):
/// a human foot reaches about 0.45 shank ahead of the ankle, a stylised one more; a leg that
/// ends at the ankle (a peg, a stump) reaches only its own radius ahead.
const MIN_FOOT_REACH: f64 = 0.2;

/// Number of cross-sections between the ankle and the tip.
const SECTIONS: usize = 64;

/// The centre of the widest cross-section of the foot (see [`find_foot`]): sections normal to
/// `forward` from the ankle to `front`, each's width across (`up × forward`) and length-
/// weighted centroid, both over the part of the section below the ankle; the middle of the
/// stretch around the widest one where every section is at least `plateau` of its width.
fn widest_section(
    surface: &HandSurface,
    ankle: DVec3,
    forward: DVec3,
    up: DVec3,
    front: f64,
    plateau: f64,
) -> Option<DVec3> {
    let mesh = Mesh {
        positions: surface.positions.clone(),
        triangles: surface.triangles.clone(),
    };
    let across = up.cross(forward);
    let sections: Vec<Option<(f64, DVec3)>> = (1..SECTIONS)
        .map(|k| {
            let at = ankle + forward * (front * k as f64 / SECTIONS as f64);
            let loops = slice_plane(&mesh, at, forward);
            // The section's segments below the ankle (a boot's shaft is no foot), each by
            // its midpoint and length.
            let segments = loops.iter().flat_map(|l| {
                let n = l.points.len();
                let count = if l.closed { n } else { n.saturating_sub(1) };
                (0..count).map(move |i| (l.points[i], l.points[(i + 1) % n]))
            });
            let (mut lo, mut hi, mut sum, mut weight) = (f64::MAX, f64::MIN, DVec3::ZERO, 0.0);
            for (a, b) in segments {
                let mid = (a + b) * 0.5;
                if (mid - ankle).dot(up) > 0.0 {
                    continue;
                }
                let x = mid.dot(across);
                (lo, hi) = (lo.min(x), hi.max(x));
                let length = a.distance(b);
                (sum, weight) = (sum + mid * length, weight + length);
            }
            (weight > 0.0).then(|| (hi - lo, sum / weight))
        })
        .collect();
    let widest = sections
        .iter()
        .enumerate()
        .filter_map(|(i, s)| s.map(|s| (i, s.0)))
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    let wide = |i: usize| sections[i].is_some_and(|s| s.0 >= plateau * widest.1);
    let mut first = widest.0;
    while first > 0 && wide(first - 1) {
        first -= 1;
    }
    let mut last = widest.0;
    while last + 1 < sections.len() && wide(last + 1) {
        last += 1;
    }
    // The section at the middle of the stretch (or the nearer of its two middle ones).
    sections[(first + last) / 2].map(|s| s.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_foot_points_where_the_figure_faces() {
        let (up, facing) = (DVec3::Y, DVec3::Z);
        let turned = |deg: f64| {
            let r = deg.to_radians();
            DVec3::new(r.sin(), 0.0, r.cos())
        };
        // Turned out 20°: kept.
        assert!(towards_facing(turned(20.0), up, facing).distance(turned(20.0)) < 1e-12);
        // Read from the heel (pointing backwards, 10° out): turned round.
        let back = -turned(10.0);
        assert!(towards_facing(back, up, facing).distance(turned(10.0)) < 1e-12);
        // Across the figure (a boxy or round foot): the figure's forward.
        assert!(towards_facing(turned(80.0), up, facing).distance(facing) < 1e-12);
        // A facing with a vertical part counts only its horizontal one.
        let tilted = DVec3::new(0.0, 0.3, 1.0);
        assert!(towards_facing(turned(-70.0), up, tilted).distance(facing) < 1e-12);
        // No horizontal facing: the footprint's own direction.
        assert_eq!(towards_facing(turned(100.0), up, up), turned(100.0));
    }
}

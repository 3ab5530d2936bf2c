//! Ankles, wrists, knees and elbows on a limb's centroid curve (seed 004, 3.3).

use super::geometry::angle_at;
use super::limb::{LimbProfile, LimbSlice};
use super::RefineOptions;
use glam::DVec3;

/// Arc length on `profile` of the slice nearest `p`.
pub fn arc_near(profile: &LimbProfile, p: DVec3) -> f64 {
    profile
        .slices
        .iter()
        .min_by(|a, b| {
            a.centre
                .distance_squared(p)
                .total_cmp(&b.centre.distance_squared(p))
        })
        .map_or(0.0, |s| s.arc)
}

/// The ankle: the point of maximal curvature on the lower part of the leg's centroid curve,
/// beyond `from` (arc length). Curvature is the turning angle between the chords `window`
/// behind and ahead, divided by the window. `None` when the curve has no part that far.
pub fn ankle(profile: &LimbProfile, from: f64, window: f64, step: f64) -> Option<DVec3> {
    let dense = profile.dense(step);
    let w = ((window / step).round() as usize).max(1);
    (w..dense.len().saturating_sub(w))
        .filter(|&i| dense[i].arc >= from)
        .map(|i| {
            let (a, q, b) = (dense[i - w].centre, dense[i].centre, dense[i + w].centre);
            (q, std::f64::consts::PI - angle_at(a, q, b))
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(q, _)| q)
}

/// The wrist: among the local minima of the arm's thickness (minor diameter) beyond `from`
/// (arc length), the one nearest the global minimum of the width (major diameter) there.
pub fn wrist(profile: &LimbProfile, from: f64, step: f64) -> Option<DVec3> {
    let dense: Vec<LimbSlice> = profile
        .dense(step)
        .into_iter()
        .filter(|s| s.arc >= from)
        .collect();
    let narrowest = dense.iter().min_by(|a, b| a.major.total_cmp(&b.major))?.arc;
    let minima = (1..dense.len().saturating_sub(1))
        .filter(|&i| dense[i].minor <= dense[i - 1].minor && dense[i].minor <= dense[i + 1].minor);
    let best = minima
        .min_by(|&i, &j| {
            (dense[i].arc - narrowest)
                .abs()
                .total_cmp(&(dense[j].arc - narrowest).abs())
        })
        .map(|i| dense[i].centre);
    best.or_else(|| dense.iter().find(|s| s.arc == narrowest).map(|s| s.centre))
}

/// Which criterion placed a knee or elbow.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BendRule {
    /// The point of smallest angle between the proximal and distal joints.
    SmallestAngle,
    /// The limb ratio point with a minimal-perimeter search around it (straight limb).
    Ratio,
}

/// The knee or elbow between the refined `proximal` and `distal` joints: the point on the
/// middle part of the centroid curve with the smallest angle; if that angle is above
/// `straight_degrees`, the curve point nearest the point at `ratio` of the way between the two
/// joints, moved to the slice of minimal perimeter within `ratio_window` of the limb's length.
pub fn bend(
    profile: &LimbProfile,
    proximal: DVec3,
    distal: DVec3,
    ratio: f64,
    step: f64,
    options: &RefineOptions,
) -> Option<(DVec3, BendRule)> {
    let (s0, s1) = (arc_near(profile, proximal), arc_near(profile, distal));
    if s1 <= s0 {
        return None;
    }
    let dense = profile.dense(step);
    let middle = |lo: f64, hi: f64| {
        dense
            .iter()
            .filter(move |s| s.arc >= s0 + lo * (s1 - s0) && s.arc <= s0 + hi * (s1 - s0))
    };
    let (q, angle) = middle(0.25, 0.75)
        .map(|s| (s.centre, angle_at(proximal, s.centre, distal)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    if angle.to_degrees() <= options.straight_degrees {
        return Some((q, BendRule::SmallestAngle));
    }
    // The ratio point on the straight line between the joints, taken to the curve (the trace
    // may start below the hip, so arc lengths from its start would shift it).
    let target = arc_near(profile, proximal.lerp(distal, ratio));
    let half = options.ratio_window * (s1 - s0);
    let best = dense
        .iter()
        .filter(|s| (s.arc - target).abs() <= half)
        .min_by(|a, b| a.perimeter.total_cmp(&b.perimeter))?;
    Some((best.centre, BendRule::Ratio))
}

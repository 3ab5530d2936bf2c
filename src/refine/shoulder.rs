//! Shoulders from the armpits (seed 004, 3.3, fig. 4b): the armpit as the apex of the gap
//! between arm and torso on the frontal-plane slice, then the arm's line cut by the sagittal
//! plane through the armpit, rotated half-way into the arm direction.

use super::frame::BodyFrame;
use super::geometry::fit_line;
use super::limb::LimbProfile;
use crate::mesh::{slice_plane_outer, Mesh};
use glam::DVec3;

/// The armpit of the side `sign` (+1 left, −1 right) on the frontal slice through `centre`:
/// over lateral offsets from `inner` to `outer` (distances from the median plane), the highest
/// point of the body's outline that bounds, from above, the empty region at height `waist`
/// (the gap between arm and torso). `samples` lateral positions are tried. `None` without
/// such a gap (arms touching the torso down to the waist).
#[allow(clippy::too_many_arguments)]
pub fn armpit(
    mesh: &Mesh,
    frame: &BodyFrame,
    centre: DVec3,
    sign: f64,
    inner: f64,
    outer: f64,
    waist: f64,
    samples: usize,
) -> Option<DVec3> {
    let loops = slice_plane_outer(mesh, centre, frame.forward);
    let lateral = |p: DVec3| (p - centre).dot(frame.left) * sign;
    let segments: Vec<((f64, f64), (f64, f64))> = loops
        .iter()
        .flat_map(|l| l.segments())
        .map(|(a, b)| ((lateral(a), frame.h(a)), (lateral(b), frame.h(b))))
        .collect();
    let mut columns: Vec<(f64, f64)> = Vec::new();
    for k in 0..=samples {
        let u = inner + (outer - inner) * k as f64 / samples.max(1) as f64;
        let mut crossings: Vec<f64> = segments
            .iter()
            .filter(|(a, b)| (a.0 < u) != (b.0 < u))
            .map(|(a, b)| a.1 + (b.1 - a.1) * (u - a.0) / (b.0 - a.0))
            .collect();
        crossings.sort_by(f64::total_cmp);
        let below = crossings.iter().filter(|&&h| h < waist).count();
        if below % 2 == 1 {
            continue; // the waist height is inside the body here
        }
        let Some(&top) = crossings.iter().find(|&&h| h >= waist) else {
            continue;
        };
        columns.push((u, top));
    }
    // Going outwards, the gap's top climbs the torso's side steeply up to the armpit, then
    // follows the arm's underside: down and out for a hanging arm, level (or slowly up as the
    // arm tapers) for a raised one. The armpit is the corner between the two: the top point
    // farthest up and in (the largest height minus lateral offset), which is the highest
    // point for a hanging arm and not the far end of a raised one's underside.
    let (u, h) = columns
        .iter()
        .copied()
        .max_by(|a, b| (a.1 - a.0).total_cmp(&(b.1 - b.0)))?;
    let origin = centre + frame.left * (sign * u);
    Some(frame.at_height(origin, h))
}

/// The line through the arm's slices between arc lengths `from` and `to` (the upper arm): a
/// point on it and its distal unit direction. `None` unless at least three slices there span
/// half of that arc: the trace leaves a gap around its seed (the first sphere slices each way
/// lie a sphere radius from it), and two slices beside the gap give a line in any direction.
pub fn upper_arm_line(arm: &LimbProfile, from: f64, to: f64) -> Option<(DVec3, DVec3)> {
    let inside: Vec<_> = arm
        .slices
        .iter()
        .filter(|s| s.arc >= from && s.arc <= to)
        .collect();
    let (first, last) = (inside.first()?, inside.last()?);
    if inside.len() < 3 || last.arc - first.arc < 0.5 * (to - from) {
        return None;
    }
    let points: Vec<DVec3> = inside.iter().map(|s| s.centre).collect();
    fit_line(&points)
}

/// Median radius (perimeter / 2π) of the arm's slices between arc lengths `from` and `to`
/// (the upper arm). `None` without slices there.
pub fn upper_arm_radius(arm: &LimbProfile, from: f64, to: f64) -> Option<f64> {
    let r: Vec<f64> = arm
        .slices
        .iter()
        .filter(|s| s.arc >= from && s.arc <= to)
        .map(|s| s.perimeter / std::f64::consts::TAU)
        .collect();
    crate::math::upper_median(r)
}

/// Distance of `p` from the line `(point, unit direction)`, mesh units.
pub fn off_axis(line: (DVec3, DVec3), p: DVec3) -> f64 {
    let d = p - line.0;
    (d - line.1 * d.dot(line.1)).length()
}

/// The shoulder from the armpit and the upper arm's line `(point, distal direction)`: the line
/// cut by the plane through `armpit` whose normal is half-way between the outward lateral
/// direction (`sign` × left) and the arm's direction.
pub fn shoulder(
    frame: &BodyFrame,
    line: (DVec3, DVec3),
    armpit: DVec3,
    sign: f64,
) -> Option<DVec3> {
    let (p0, dir) = line;
    let normal = (frame.left * sign + dir).try_normalize()?;
    let denom = dir.dot(normal);
    if denom.abs() < 1e-6 {
        return None;
    }
    let t = (armpit - p0).dot(normal) / denom;
    Some(p0 + dir * t)
}

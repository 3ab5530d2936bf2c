//! Ankles, wrists, knees and elbows on a limb's centroid curve (seed 004, 3.3).

use super::frame::BodyFrame;
use super::geometry::{angle_at, fit_line, nearest_loop};
use super::limb::{LimbProfile, LimbSlice};
use super::RefineOptions;
use crate::mesh::{slice_plane_outer, Mesh};
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

/// Whether the trace `profile` reaches out from `root` as far as the rough joint `p`, less
/// `slack` (mesh units): whether a slice's centre lies at least `|p - root| - slack` from
/// `root`. Measured as a distance from the limb's root, not to `p`, so a rough joint off the
/// limb's axis (in the top of a big hand) still counts as reached by a trace along the limb.
pub fn reaches(profile: &LimbProfile, root: DVec3, p: DVec3, slack: f64) -> bool {
    let needed = root.distance(p) - slack;
    profile
        .slices
        .iter()
        .any(|s| s.centre.distance(root) >= needed)
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

/// The point at height `h` (along `frame.up`) on the straight line fitted
/// (`geometry::fit_line`) through the centroid curve of `profile` between arc lengths `lo` and `hi`:
/// the shin's axis carried down to the ankle's height, past the foot's pull on the centroids.
/// `None` for fewer than three samples or a line that does not rise.
pub fn on_axis(
    profile: &LimbProfile,
    frame: &BodyFrame,
    lo: f64,
    hi: f64,
    step: f64,
    h: f64,
) -> Option<DVec3> {
    let samples: Vec<DVec3> = profile
        .dense(step)
        .into_iter()
        .filter(|s| s.arc >= lo && s.arc <= hi)
        .map(|s| s.centre)
        .collect();
    if samples.len() < 3 {
        return None;
    }
    let (point, dir) = fit_line(&samples)?;
    let rise = dir.dot(frame.up);
    if rise.abs() < 1e-6 {
        return None;
    }
    Some(point + dir * ((h - frame.h(point)) / rise))
}

/// The hand's flat section begins where a slice is this many times as wide as it is thick
/// (major / minor diameter): a palm is two to four times as wide as thick, a forearm's slices
/// at most about one and a half (its flat distal end, measured on the MakeHuman and game
/// bodies).
const HAND_FLATNESS: f64 = 1.6;

/// The wrist lies at most this many palm widths (the hand's widest slice) before the slice
/// where the hand turns flat ([`hand_flat_start`]): the wrist joint sits at the palm's root
/// (quaternius_women_formal's artist put it a quarter of the palm's width before the flat
/// section), so a narrowing farther back is the forearm's (a sleeve's cuff caught or missed
/// by a slice).
const WRIST_BEFORE_PALM: f64 = 0.5;

/// Walking back from the hand's flat section towards the elbow, the narrowing before it ends
/// where the perimeter has risen this fraction above its smallest value on the way (out of the
/// valley, past the B-spline's ripples).
const VALLEY_RISE: f64 = 0.1;

/// The wrist: among the local minima of the arm's thickness (minor diameter) beyond `from`
/// (arc length), the one nearest the arm's last narrowing before the hand's flat section
/// (`hand_flat_start`): the bottom of the perimeter's valley reached walking back from that
/// section (`last_narrowing`), at most `WRIST_BEFORE_PALM` palm widths back; a minimum more
/// than the narrowing's width from it is none of the wrist's (a hand thinning to its
/// fingertips has its only one there), and the narrowing itself is taken. A forearm thinner
/// in its middle than at the wrist (a jointed
/// mannequin's rod before its wrist piece) so keeps the wrist at the hand. Without a flat
/// section (a fist or a mitten, or a trace that stops short of the hand), the narrowing is the
/// narrowest width (major diameter) beyond `from` that a wider section follows
/// (`narrowest_before_widening`: the hand or fist beyond the wrist), else the narrowest width
/// there. The slices past the trace's tip (the slice farthest from its first, where spheres
/// beyond the end of the limb fold the centroid curve back) are no part of the limb.
pub fn wrist(profile: &LimbProfile, from: f64, step: f64) -> Option<DVec3> {
    let all = profile.dense(step);
    let start = all.first()?.centre;
    let tip = all
        .iter()
        .enumerate()
        .max_by(|a, b| {
            a.1.centre
                .distance_squared(start)
                .total_cmp(&b.1.centre.distance_squared(start))
        })
        .map_or(0, |(i, _)| i);
    let dense: Vec<LimbSlice> = all
        .into_iter()
        .take(tip + 1)
        .filter(|s| s.arc >= from)
        .collect();
    let flat = hand_flat_start(&dense).filter(|&i| i > 0);
    let narrowest = match flat {
        Some(i) => {
            // The wrist is at the palm's root: walking back from where the hand turns flat,
            // a narrowing farther than half the palm's width belongs to the forearm (a
            // sleeve's cuff, a bracelet), however deep.
            let palm = dense[i..].iter().map(|s| s.major).fold(0.0, f64::max);
            let back_to = dense[i].arc - WRIST_BEFORE_PALM * palm;
            let first = dense[..i]
                .iter()
                .position(|s| s.arc >= back_to)
                .unwrap_or(i);
            last_narrowing(&dense[first..=i])?
        }
        None => narrowest_before_widening(&dense)
            .or_else(|| dense.iter().min_by(|a, b| a.major.total_cmp(&b.major)))?,
    };
    // The thickness minimum refines the narrowing's place within the wrist's own width; a
    // forearm thinning all the way to the fingertips (an A-posed arm sliced obliquely, a
    // mitten) has its only minimum out at the tip, which is no wrist.
    let off = |i: usize| (dense[i].arc - narrowest.arc).abs();
    (1..dense.len().saturating_sub(1))
        .filter(|&i| dense[i].minor <= dense[i - 1].minor && dense[i].minor <= dense[i + 1].minor)
        .filter(|&i| off(i) <= narrowest.major)
        .min_by(|&i, &j| off(i).total_cmp(&off(j)))
        .map(|i| dense[i].centre)
        .or(Some(narrowest.centre))
}

/// The slice of least width (major diameter) among those that a slice further on exceeds in
/// width by [`VALLEY_RISE`]: the bottom of a valley with the hand or fist beyond it. The cap at
/// the end of a fist only narrows to the tip and has no such slice after it. `None` when no
/// slice is followed by a wider one.
fn narrowest_before_widening(slices: &[LimbSlice]) -> Option<&LimbSlice> {
    let mut widest_after = f64::NEG_INFINITY;
    let mut best: Option<&LimbSlice> = None;
    for s in slices.iter().rev() {
        if widest_after > (1.0 + VALLEY_RISE) * s.major && best.is_none_or(|b| s.major <= b.major) {
            best = Some(s);
        }
        widest_after = widest_after.max(s.major);
    }
    best
}

/// Index of the first of `slices` where the hand's flat section begins: the slices from it on
/// are all [`HAND_FLATNESS`] times as wide as thick over half its width (a palm is about as long
/// as it is wide) or to the end of the trace. A lone flat slice (a sleeve's or gauntlet's rim
/// caught by the sphere) is no hand. `None` when no section is that flat.
fn hand_flat_start(slices: &[LimbSlice]) -> Option<usize> {
    let flat = |s: &LimbSlice| s.major >= HAND_FLATNESS * s.minor;
    (0..slices.len()).find(|&i| {
        let reach = slices[i].arc + 0.5 * slices[i].major;
        slices[i..].iter().take_while(|s| s.arc <= reach).all(flat)
    })
}

/// The slice at the bottom of the last valley of the perimeter in `slices`: walking back from
/// the last slice, the thinnest one until the perimeter has risen [`VALLEY_RISE`] above it.
/// `None` for no slices.
fn last_narrowing(slices: &[LimbSlice]) -> Option<&LimbSlice> {
    let mut best = slices.last()?;
    for s in slices.iter().rev() {
        if s.perimeter < best.perimeter {
            best = s;
        } else if s.perimeter > (1.0 + VALLEY_RISE) * best.perimeter {
            break;
        }
    }
    Some(best)
}

/// A bend found within this fraction of the limb's span from the edges of its middle half is
/// taken as the edge of a kink outside it (see [`bend`]).
const BEND_EDGE: f64 = 0.05;

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
/// `straight_degrees` or lies at the middle part's edge, the curve point nearest the point at `ratio` of the way between the two
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
    // The middle half of the limb, measured along the straight line between the joints rather
    // than along the curve: a centroid curve that runs on into a foot and folds back puts its
    // arc-length middle next to the ankle, where the angle to the ankle is always small.
    let axis = distal - proximal;
    let along = |p: DVec3| (p - proximal).dot(axis) / axis.length_squared();
    let middle = |lo: f64, hi: f64| {
        dense.iter().filter(move |s| {
            let t = along(s.centre);
            (lo..=hi).contains(&t)
        })
    };
    let (q, angle) = middle(0.25, 0.75)
        .map(|s| (s.centre, angle_at(proximal, s.centre, distal)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    // A smallest angle at the window's edge is no bend of this limb: the angle still falls
    // towards the edge, to a kink outside it (where thick legs meet at the crotch, a foot).
    let inside = (0.25 + BEND_EDGE..=0.75 - BEND_EDGE).contains(&along(q));
    if inside && angle.to_degrees() <= options.straight_degrees {
        return Some((q, BendRule::SmallestAngle));
    }
    // The ratio point on the straight line between the joints, taken to the curve (the trace
    // may start below the hip, so arc lengths from its start would shift it): the sample of
    // the smoothed curve at that fraction along the line, as for the middle half above. The
    // raw slice nearest the point is not it: the B-spline runs a slice or more ahead of its
    // control points where the sphere slices zigzag (a cartoon's short arm entering its
    // trunk), which had put the elbow of quaternius_platformer_character 0.8 of the way to
    // the wrist.
    let target = dense
        .iter()
        .min_by(|a, b| {
            (along(a.centre) - ratio)
                .abs()
                .total_cmp(&(along(b.centre) - ratio).abs())
        })?
        .arc;
    let half = options.ratio_window * (s1 - s0);
    let best = dense
        .iter()
        .filter(|s| (s.arc - target).abs() <= half)
        .min_by(|a, b| a.perimeter.total_cmp(&b.perimeter))?;
    Some((best.centre, BendRule::Ratio))
}

/// Height of the sole under `ankle`: the lowest mesh vertex within `reach` of it across the
/// body (measured perpendicular to `frame.up`), so a raised foot has its own sole.
pub fn sole_under(mesh: &Mesh, frame: &BodyFrame, ankle: DVec3, reach: f64) -> Option<f64> {
    mesh.positions
        .iter()
        .filter(|p| {
            let d = **p - ankle;
            (d - frame.up * d.dot(frame.up)).length() <= reach
        })
        .map(|p| frame.h(*p))
        .min_by(f64::total_cmp)
}

/// The point inside the transverse cross-section at height `h` nearest `near`: the closed loop
/// of the slice whose centroid is nearest `near`, taken at its centroid across the body
/// (`frame.left`) and at `depth` of its back-to-front extent along `frame.forward` (0 the back,
/// 1 the front). `None` when the plane misses the mesh there.
pub fn transverse_point(
    mesh: &Mesh,
    frame: &BodyFrame,
    near: DVec3,
    h: f64,
    depth: f64,
) -> Option<DVec3> {
    let origin = frame.at_height(near, h);
    let loops = slice_plane_outer(mesh, origin, frame.up);
    let l = nearest_loop(&loops, origin).filter(|l| l.closed)?;
    let c = l.centroid()?;
    let (back, front) = l
        .points
        .iter()
        .map(|p| p.dot(frame.forward))
        .fold((f64::MAX, f64::MIN), |(lo, hi), f| (lo.min(f), hi.max(f)));
    let f = back + depth * (front - back);
    let p = c + frame.forward * (f - c.dot(frame.forward));
    Some(frame.at_height(p, h))
}

/// `p` moved along `frame.forward` to `depth` of the body's extent there (0 the back, 1 the
/// front): the sagittal slice through `p` (normal `frame.left`) is cut by the line through `p`
/// along `frame.forward`, and the interval between consecutive crossings that contains `p`
/// (or, when `p` lies outside the surface, the nearest one) is the extent. `None` when the
/// line misses the mesh.
pub fn centre_in_depth(mesh: &Mesh, frame: &BodyFrame, p: DVec3, depth: f64) -> Option<DVec3> {
    let crossings = line_crossings(mesh, p, frame.left, frame.forward);
    let f0 = p.dot(frame.forward);
    let (lo, hi) = crossings
        .chunks_exact(2)
        .map(|c| (c[0], c[1]))
        .min_by(|a, b| {
            let gap = |(lo, hi): (f64, f64)| (lo - f0).max(f0 - hi).max(0.0);
            gap(*a).total_cmp(&gap(*b))
        })?;
    Some(p + frame.forward * (lo + depth * (hi - lo) - f0))
}

/// Height (along `frame.up`) of the first surface crossing above `p` on the vertical line
/// through it, found in the sagittal slice through `p`. `None` when nothing lies above.
pub fn surface_above(mesh: &Mesh, frame: &BodyFrame, p: DVec3) -> Option<f64> {
    let h0 = p.dot(frame.up);
    line_crossings(mesh, p, frame.left, frame.up)
        .into_iter()
        .find(|&h| h > h0)
        .map(|h| h - h0 + frame.h(p))
}

/// Where the line through `p` along `along` crosses the mesh, found in the slice through `p`
/// with normal `normal` (perpendicular to `along`): the crossings' coordinates along `along`
/// (dot products with it), sorted.
fn line_crossings(mesh: &Mesh, p: DVec3, normal: DVec3, along: DVec3) -> Vec<f64> {
    let across = normal.cross(along);
    let side = |q: DVec3| (q - p).dot(across);
    let mut crossings: Vec<f64> = slice_plane_outer(mesh, p, normal)
        .iter()
        .flat_map(|l| l.segments())
        .filter(|(a, b)| (side(*a) < 0.0) != (side(*b) < 0.0))
        .map(|(a, b)| {
            let t = side(a) / (side(a) - side(b));
            a.lerp(b, t).dot(along)
        })
        .filter(|f| f.is_finite())
        .collect();
    crossings.sort_by(f64::total_cmp);
    crossings
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A straight arm along x with slices every half unit: `section(x)` gives (major, minor)
    /// diameters, the perimeter that of the ellipse's mean circle.
    fn arm(section: impl Fn(f64) -> (f64, f64)) -> LimbProfile {
        let slices = (0..=80)
            .map(|i| {
                let x = 0.5 * i as f64;
                let (major, minor) = section(x);
                LimbSlice {
                    centre: DVec3::new(x, 0.0, 0.0),
                    perimeter: PI * 0.5 * (major + minor),
                    major,
                    minor,
                    arc: x,
                }
            })
            .collect();
        LimbProfile { slices }
    }

    #[test]
    fn wrist_of_a_jointed_mannequin_is_at_its_wrist_piece_not_its_thin_forearm_rod() {
        // Forearm, a thin rod (the narrowest part), a bulge, the wrist piece's narrowing, then
        // the flat hand (three times as wide as thick). The global minimum of the width put
        // the wrist on the rod, 11 units short of the hand (gdquest_mannequiny's wrists, 4 %
        // of its height).
        let profile = arm(|x| match x {
            x if x < 10.0 => (4.0, 4.0),
            x if x < 16.0 => (2.0, 2.0),
            x if x < 22.0 => (4.0, 4.0),
            x if x < 26.0 => (3.0, 3.0),
            _ => (8.0, 2.5),
        });
        let w = wrist(&profile, 0.0, 0.25).unwrap();
        assert!((21.0..27.0).contains(&w.x), "wrist at {w}");
    }

    #[test]
    fn bend_ratio_point_is_taken_along_the_line_between_the_joints() {
        // A straight limb along x sliced unevenly: close slices near the shoulder (where a
        // cartoon's arm enters its trunk), sparse ones beyond. The smoothed curve is not at a
        // raw slice's centre at that slice's arc length, so the raw slice nearest the ratio
        // point gave a target on the curve far from it.
        let xs = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 10.0, 20.0, 30.0, 40.0];
        let slices = xs
            .iter()
            .map(|&x| LimbSlice {
                centre: DVec3::new(x, 0.0, 0.0),
                perimeter: 10.0,
                major: 3.2,
                minor: 3.2,
                arc: x,
            })
            .collect();
        let profile = LimbProfile { slices };
        let options = RefineOptions::default();
        let (e, rule) = bend(
            &profile,
            DVec3::ZERO,
            DVec3::new(40.0, 0.0, 0.0),
            0.54,
            0.1,
            &options,
        )
        .unwrap();
        assert_eq!(rule, BendRule::Ratio);
        assert!((e.x - 21.6).abs() < 1.5, "elbow at {e}");
    }

    #[test]
    fn wrist_of_a_fist_is_at_the_narrowing_before_it_not_at_its_tip() {
        // A round forearm narrowing at the wrist, a round fist (no flat section) wider than
        // the forearm, its cap tapering to the tip, and spheres beyond the tip folding the
        // centroid curve back. The global minimum of the width put the wrist on the fist's cap
        // (quaternius_platformer_character: 8 % of its height out along the arm).
        let mut profile = arm(|x| match x {
            x if x < 20.0 => (4.0, 4.0),
            x if x < 24.0 => (3.6, 3.6),
            x if x < 34.0 => (4.6, 4.6),
            x => (4.6 - 0.4 * (x - 34.0), 4.6 - 0.4 * (x - 34.0)),
        });
        // The last slices fold back towards the shoulder, narrow as the cap.
        let n = profile.slices.len();
        for k in 0..4 {
            let s = &mut profile.slices[n - 1 - k];
            s.centre.x = 37.0 - 0.5 * (4 - k) as f64;
            s.major = 2.0 + 0.5 * k as f64;
            s.minor = s.major;
        }
        let w = wrist(&profile, 10.0, 0.25).unwrap();
        assert!((20.0..24.5).contains(&w.x), "wrist at {w}");
    }

    #[test]
    fn wrist_of_a_tapering_forearm_is_at_its_narrowest_before_the_hand() {
        // A forearm tapering to the wrist, the flat hand beyond: the narrowing just before it.
        let profile = arm(|x| match x {
            x if x < 24.0 => (5.0 - 0.1 * x, 5.0 - 0.1 * x),
            _ => (8.0, 2.5),
        });
        let w = wrist(&profile, 0.0, 0.25).unwrap();
        assert!((20.0..26.0).contains(&w.x), "wrist at {w}");
    }

    #[test]
    fn wrist_is_at_the_palms_root_not_at_a_deeper_narrowing_up_the_forearm() {
        // Forearm, a deep narrowing where a sleeve's cuff ends (or was missed by the slice),
        // a sleeve barely wider than the wrist, the wrist's shallow narrowing, then the flat
        // hand. Walking back from the hand, the perimeter never rose a tenth above the wrist's
        // before the cuff, and the wrist went to the cuff, 10 units (more than a palm's width)
        // short of the hand (quaternius_women_formal turned one degree: 4-5 % of its height).
        let profile = arm(|x| match x {
            x if x < 10.0 => (4.0, 4.0),
            x if x < 13.0 => (2.6, 2.6),
            x if x < 20.0 => (3.4, 3.4),
            x if x < 22.0 => (3.2, 3.2),
            _ => (8.0, 2.5),
        });
        let w = wrist(&profile, 0.0, 0.25).unwrap();
        assert!((18.0..23.0).contains(&w.x), "wrist at {w}");
    }

    #[test]
    fn wrist_stays_at_the_narrowing_when_the_only_thickness_minimum_is_at_the_fingertips() {
        // A forearm, the wrist's narrowing, then a hand thinning all the way to the tip (an
        // A-posed arm sliced obliquely): the only local minimum of the thickness lies at the
        // fingertips, and taking the minimum nearest the narrowing put the wrist there
        // (gltf_cesium_man turned three degrees: 15 % of its height out along the hand).
        let profile = arm(|x| match x {
            x if x < 22.0 => (7.0 - 0.05 * x, 6.0 - 0.04 * x),
            x if x < 39.0 => (9.0, 5.0 - 0.2 * (x - 22.0)),
            _ => (9.0, 2.0),
        });
        let w = wrist(&profile, 0.0, 0.25).unwrap();
        assert!((18.0..24.0).contains(&w.x), "wrist at {w}");
    }

    /// A trace along the arm reaches a rough joint off its axis (in the top of a big hand) as
    /// far out from the root, but not one beyond its end by more than the slack: a trace
    /// stopped short at a seam between a jointed figure's pieces.
    #[test]
    fn a_trace_reaches_joints_as_far_out_as_its_end_only() {
        let profile = arm(|_| (4.0, 4.0));
        let root = DVec3::ZERO;
        assert!(reaches(&profile, root, DVec3::new(38.0, 8.0, 0.0), 0.0));
        assert!(reaches(&profile, root, DVec3::new(45.0, 0.0, 0.0), 6.0));
        assert!(!reaches(&profile, root, DVec3::new(45.0, 0.0, 0.0), 4.0));
        assert!(!reaches(&profile, root, DVec3::new(0.0, 60.0, 0.0), 10.0));
    }
}

//! The appendicular skeleton (dissertation 8.2): girdle spheres, human-like and animal-like
//! limb roots, Table 8.1 segmentation, digits, wing shift.

use super::axial::perpendicular;
use super::polyline::{boundaries, Polyline};
use super::{BodyFrame, DorsalProbe, FitOptions, FitWarning, LimbInput, Side};
use crate::math::{moving_average, Ends};
use crate::template::{Girdle, LimbGroup, Manus, Placement, Template};
use glam::DVec3;

/// A limb pair's girdle sphere and attachment on the spine.
pub(crate) struct GirdleSphere {
    /// Centre: the original head-to-tail path point nearest the pair's attach midpoint.
    pub centre: DVec3,
    /// Its distance-map radius.
    pub radius: f64,
    /// The adjusted (dorsal) spine point there.
    pub spine: DVec3,
    /// Unit direction towards the head along the path there.
    pub anterior: DVec3,
}

/// One fitted limb.
pub(crate) struct LimbFit {
    pub side: Side,
    /// The pectoral girdle joint (scapula/clavicle), if the group has one.
    pub girdle: Option<DVec3>,
    /// One position per template chain joint, `None` where not built.
    pub chain: Vec<Option<DVec3>>,
    /// Digits, first digit first: joint positions base → tip (the last is the end marker).
    pub digits: Vec<Vec<DVec3>>,
}

impl LimbFit {
    /// Index of the digit that stands in for chain joints at and beyond the digit row: the
    /// middle one of the digits after the first (the first when it is alone).
    pub fn central_digit(&self) -> Option<usize> {
        match self.digits.len() {
            0 => None,
            1 => Some(0),
            n => Some(1 + (n - 1) / 2),
        }
    }
}

/// `points` smoothed by the moving average of `half` neighbours each side (the window
/// shrinking at the ends, as the chains' smoothing does), as a polyline.
fn smoothed(points: &[DVec3], half: usize) -> Polyline {
    Polyline::new(moving_average(points, half, Ends::Shrink))
}

/// Fits one side of a limb pair.
#[allow(clippy::too_many_arguments)]
pub(crate) fn limb(
    input: &LimbInput,
    group: &LimbGroup,
    template: &Template,
    sphere: &GirdleSphere,
    frame: &BodyFrame,
    options: &FitOptions,
    centre_distance: &dyn Fn(DVec3) -> f64,
    probe: Option<&dyn DorsalProbe>,
    warnings: &mut Vec<FitWarning>,
) -> LimbFit {
    let side = input.side;
    let lateral = frame.left * side.sign();
    let path = smoothed(&input.path, options.limb_smoothing);
    let length = path.length();
    let ratios = template
        .ratios
        .get(&group.ratios)
        .cloned()
        .unwrap_or_default();
    let mut chain: Vec<Option<DVec3>> = vec![None; group.chain.len()];
    let mut chain_s: Vec<Option<f64>> = vec![None; group.chain.len()];
    let (from_label, s0) = limb_start(input, group, &path, sphere, options, warnings);
    let folded = fold_point(&path, input, group, sphere, frame, options, probe, s0);
    let girdle = group
        .girdle_joint
        .as_ref()
        .map(|_| sphere.spine + lateral * options.girdle_lateral * sphere.radius);
    let has_digits = !input.digits.is_empty();
    let (first_row, weights) = row_weights(group, &ratios, has_digits);
    let cuts = boundaries(&weights);
    let span = (length - s0).max(0.0);
    for (k, c) in cuts.iter().enumerate() {
        let index = if !has_digits && group.manus == Manus::Segment && k + 1 == cuts.len() {
            group.chain.len() - 1
        } else {
            first_row + k
        };
        if index < chain.len() {
            let s = s0 + c * span;
            chain[index] = Some(path.at(s));
            chain_s[index] = Some(s);
        }
    }
    if let Some(bend) = options.snap_to_bend {
        let unsnapped = chain_s.clone();
        snap_to_bends(&path, &mut chain, &mut chain_s, s0, span, &bend);
        if group.placement == Placement::Animal {
            short_row(&path, group, &ratios, &unsnapped, &mut chain, &mut chain_s);
        }
    }
    if let (Placement::Human, Some(root), Some(s_end)) = (
        group.placement,
        input.root.filter(|_| from_label.is_some()),
        chain_s.get(1).copied().flatten(),
    ) {
        // The shoulder/hip sits on the axis of the upper arm/thigh where it meets the trunk:
        // the segment's axis (fitted to its middle) at the point nearest the labelled root.
        if let Some(p) = axis_point(&path, s0, s_end, root, options.root_axis_span) {
            chain[0] = Some(p);
        }
    }
    if has_digits && group.digit_row < chain.len() {
        // The path ends at the wrist/ankle voxel: the digit bases take this joint's place.
        chain[group.digit_row] = None;
    }
    if group.placement == Placement::Animal {
        if let Some(elbow) = chain.get(1).copied().flatten() {
            // The pectoral root hangs from its scapula; a girdle without its own joint (the
            // pelvis) pivots on the trunk's centre line, not the dorsally offset spine: the
            // hip socket (acetabulum) lies ventral to the sacrum, level with the trunk's
            // middle, so the hips do not rise with the template's dorsal offset.
            let pivot = girdle.unwrap_or(sphere.centre);
            chain[0] = Some(interior_root(
                pivot,
                elbow,
                lateral,
                sphere,
                group.girdle,
                options,
            ));
        }
    }
    if let Some((s, p)) = folded {
        // Only the elbow/knee moves (after the shoulder/hip was placed from the labelled
        // root): the joints below keep their Table 8.1 places.
        let below = chain_s.get(2).copied().flatten().unwrap_or(f64::INFINITY);
        if s > s0 && s < below && chain.len() > 1 {
            chain[1] = Some(p);
            chain_s[1] = Some(s);
        }
    }
    if group.wing {
        wing_shift(&path, &input.radii, sphere, options, &mut chain, &chain_s);
    }
    let digits = digits(input, group, template, options, centre_distance, warnings);
    LimbFit {
        side,
        girdle,
        chain,
        digits,
    }
}

/// Where the limb leaves the trunk, as arc length on its `path`: at the labelled root when
/// the options take it from the labels (also returned on its own), else where the path
/// leaves the girdle sphere, else (with a warning) at the path's start.
fn limb_start(
    input: &LimbInput,
    group: &LimbGroup,
    path: &Polyline,
    sphere: &GirdleSphere,
    options: &FitOptions,
    warnings: &mut Vec<FitWarning>,
) -> (Option<f64>, f64) {
    let side = input.side;
    let from_label = input
        .root
        .filter(|_| options.root_from_labels)
        .map(|r| path.project(r));
    let s0 = from_label
        .or_else(|| path.sphere_exit(sphere.centre, sphere.radius))
        .unwrap_or_else(|| {
            warnings.push(FitWarning::InsideGirdle {
                group: group.name.clone(),
                side,
            });
            0.0
        });
    (from_label, s0)
}

/// The elbow or knee at the fold of an animal-like limb's path (`fold`), when the options
/// ask for it and a probe measures the depths; `(arc length, position)`.
#[allow(clippy::too_many_arguments)]
fn fold_point(
    path: &Polyline,
    input: &LimbInput,
    group: &LimbGroup,
    sphere: &GirdleSphere,
    frame: &BodyFrame,
    options: &FitOptions,
    probe: Option<&dyn DorsalProbe>,
    s0: f64,
) -> Option<(f64, DVec3)> {
    match (
        group.placement,
        group.girdle,
        group.wing,
        options.limb_fold,
        probe,
    ) {
        (Placement::Animal, Girdle::Pelvic, false, Some(k), Some(probe)) => {
            let towards = perpendicular(sphere.anterior, frame.up);
            fold(path, &input.radii, s0, towards, k, probe)
        }
        // The elbow stays on the limb's axis: its surface point (the olecranon) is the
        // fold's corner, but the forearm must run inside the leg.
        (Placement::Animal, Girdle::Pectoral, false, Some(k), Some(probe)) => {
            let towards = perpendicular(-sphere.anterior, frame.up);
            fold(path, &input.radii, s0, towards, k, probe).map(|(s, _)| (s, path.at(s)))
        }
        _ => None,
    }
}

/// The first Table 8.1 row segmented along the path and the rows' length weights.
fn row_weights(group: &LimbGroup, ratios: &[f64], has_digits: bool) -> (usize, Vec<f64>) {
    let rows = ratios.len();
    // Rows segmented along the path outside the sphere (8.2): all rows for human-like
    // placement, all but the humerus/femur for animal-like (that segment comes from the girdle).
    let first_row = match group.placement {
        Placement::Human => 0,
        Placement::Animal => 1,
    };
    let mut weights: Vec<f64> = match (has_digits, group.manus) {
        (true, _) => ratios[first_row..group.digit_row.min(rows)].to_vec(),
        (false, Manus::Digit) => ratios[first_row..].to_vec(),
        (false, Manus::Segment) => {
            let mut w = ratios[first_row..group.digit_row.min(rows)].to_vec();
            w.push(ratios[group.digit_row.min(rows)..].iter().sum());
            w
        }
    };
    if weights.is_empty() {
        weights.push(1.0);
    }
    (first_row, weights)
}

/// Wings: every placed joint moves forward by `wing_shift` of the path's radius there.
fn wing_shift(
    path: &Polyline,
    radii: &[f64],
    sphere: &GirdleSphere,
    options: &FitOptions,
    chain: &mut [Option<DVec3>],
    chain_s: &[Option<f64>],
) {
    for (k, p) in chain.iter_mut().enumerate() {
        if let (Some(p), Some(s)) = (p.as_mut(), chain_s[k]) {
            let forward = perpendicular(sphere.anterior, path.tangent(s));
            let r = path.value_at(radii, s);
            *p += forward * options.wing_shift * r;
        }
    }
}

/// Moves each inner chain joint (not the limb's root or tip) to the sharpest bend of the path
/// within `bend.window * span` of its Table 8.1 place when that bend turns by at least
/// `bend.min_angle` degrees, measured over the stencil and again over twice the stencil
/// ([`bend_turn`]), and peaks inside the window; joints keep their order. A turn largest at
/// the window's edge and still rising beyond it belongs to the neighbouring joint: an arm
/// hanging 30 degrees below the horizontal bends at the shoulder, and its elbow's window
/// reached the slope of that bend (quaternius_cyberpunk_character posed so: its elbows went
/// there, 8 % of the height from the artist's).
fn snap_to_bends(
    path: &Polyline,
    chain: &mut [Option<DVec3>],
    chain_s: &mut [Option<f64>],
    s0: f64,
    span: f64,
    bend: &super::options::BendSnap,
) {
    const STEPS: usize = 24;
    let placed: Vec<usize> = (0..chain.len()).filter(|&k| chain_s[k].is_some()).collect();
    let h = bend.stencil * span;
    if placed.len() < 3 || h <= 0.0 {
        return;
    }
    let turn = |s: f64| turn_over(path, s, h);
    for w in 1..placed.len() - 1 {
        let k = placed[w];
        let (Some(s), Some(prev), Some(next)) =
            (chain_s[k], chain_s[placed[w - 1]], chain_s[placed[w + 1]])
        else {
            continue;
        };
        let lo = (s - bend.window * span).max(0.5 * (prev + s)).max(s0 + h);
        let hi = (s + bend.window * span)
            .min(0.5 * (s + next))
            .min(path.length() - h);
        if hi <= lo {
            continue;
        }
        let d = (hi - lo) / STEPS as f64;
        let best = (0..=STEPS)
            .map(|i| lo + d * i as f64)
            .map(|t| (turn(t), t))
            .max_by(|a, b| a.0.total_cmp(&b.0).then(b.1.total_cmp(&a.1)));
        // A bend still rising past the window's edge peaks outside it: it is the neighbouring
        // joint's (an A-posed arm's shoulder seen from its elbow's window), not this one's.
        let peaks_here = |&(turn_at, t): &(f64, f64)| {
            (t > lo || turn(t - d) <= turn_at) && (t < hi || turn(t + d) <= turn_at)
        };
        if let Some((_, t)) = best
            .filter(peaks_here)
            .filter(|&(_, t)| bend_turn(path, t, h) >= bend.min_angle)
        {
            chain[k] = Some(path.at(t));
            chain_s[k] = Some(t);
        }
    }
}

/// The metapodial joint (`hand`, `foot`: the chain's `digit_row`) at most one carpal or
/// tarsal row beyond the wrist or ankle when the bend snapping moved that joint but not this
/// one (`unsnapped`: the arc lengths before the snapping): the row is at most the template's
/// share of the forearm or shank (carpals over radius, tarsals over tibia, in arc length on
/// the snapped joints), not a share of the path left below, so a hock snapped up to its bend
/// does not leave the tarsometatarsal joint far down a long cannon bone. The short bones keep
/// their size while the metapodials lengthen from paw to hoof (a deer's tarsus is about a
/// sixth of its tibia, as a dog's). A row already shorter (a joint snapped towards it) is left
/// alone. Animal-like limbs only: a human-like hand and foot are placed again by the
/// refinement and the digit stage.
fn short_row(
    path: &Polyline,
    group: &LimbGroup,
    ratios: &[f64],
    unsnapped: &[Option<f64>],
    chain: &mut [Option<DVec3>],
    chain_s: &mut [Option<f64>],
) {
    let row = group.digit_row;
    let (Some(&shank_ratio), Some(&row_ratio)) = (
        row.checked_sub(2).and_then(|k| ratios.get(k)),
        row.checked_sub(1).and_then(|k| ratios.get(k)),
    ) else {
        return;
    };
    let (Some(top), Some(root), Some(here)) = (
        chain_s[row - 2],
        chain_s[row - 1],
        chain_s.get(row).copied().flatten(),
    ) else {
        return;
    };
    let snapped = |k: usize| unsnapped[k] != chain_s[k];
    if !snapped(row - 1) || snapped(row) || shank_ratio <= 0.0 || root <= top {
        return;
    }
    let s = root + (root - top) * row_ratio / shank_ratio;
    if s > root && s < here {
        chain[row] = Some(path.at(s));
        chain_s[row] = Some(s);
    }
}

/// The turning angle (degrees) of `path` at arc length `s` between the chords `h` behind and
/// ahead; 0 where a chord is degenerate.
fn turn_over(path: &Polyline, s: f64, h: f64) -> f64 {
    let (a, b, c) = (path.at(s - h), path.at(s), path.at(s + h));
    let (u, v) = (b - a, c - b);
    if u.length() < 1e-12 || v.length() < 1e-12 {
        0.0
    } else {
        u.angle_between(v).to_degrees()
    }
}

/// How far `path` bends at `s` as a limb joint: the smaller of the turns over the stencil `h`
/// and over `2 h` ([`turn_over`]). A joint bends the limb's straight segments, so its turn is
/// about the same over both chords; a wiggle of the medial path no longer than the stencil (a
/// voxel's step of a straight limb's centred path, a piece's seam on a jointed figure) turns
/// the short chords only, and measures about half as much over the long ones. The short turn
/// alone moved a straight arm's wrist with a sub-voxel change of the grid's phase
/// (quaternius_cyberpunk_character turned Z-up: the left wrist 0.454 from the centre instead
/// of 0.553, the right one 0.564).
fn bend_turn(path: &Polyline, s: f64, h: f64) -> f64 {
    turn_over(path, s, h).min(turn_over(path, s, 2.0 * h))
}

/// The point nearest `target` on the straight line fitted (least squares, principal direction)
/// to `path` between arc lengths `a + (1 - span) / 2 (b - a)` and `a + (1 + span) / 2 (b - a)`;
/// `None` when that part of the path is degenerate.
fn axis_point(path: &Polyline, a: f64, b: f64, target: DVec3, span: f64) -> Option<DVec3> {
    const SAMPLES: usize = 16;
    let (lo, hi) = (
        a + 0.5 * (1.0 - span) * (b - a),
        a + 0.5 * (1.0 + span) * (b - a),
    );
    if hi - lo <= 0.0 {
        return None;
    }
    let pts: Vec<DVec3> = (0..=SAMPLES)
        .map(|k| path.at(lo + (hi - lo) * k as f64 / SAMPLES as f64))
        .collect();
    let centre = pts.iter().sum::<DVec3>() / pts.len() as f64;
    let dir = (pts[SAMPLES] - pts[0]).try_normalize()?;
    // One power iteration step on the scatter matrix refines the chord direction.
    let refined = pts
        .iter()
        .map(|p| {
            let d = *p - centre;
            d * d.dot(dir)
        })
        .sum::<DVec3>()
        .try_normalize()
        .unwrap_or(dir);
    let dir = if refined.dot(dir) < 0.0 {
        -refined
    } else {
        refined
    };
    Some(centre + dir * (target - centre).dot(dir))
}

/// An animal-like shoulder/hip inside the girdle sphere (8.2): at the elbow's/knee's lateral
/// distance (preserving the width between the outside joints), equidistant from the girdle
/// pivot and the elbow/knee (scapula/coxa and humerus/femur of about the same length), shifted
/// anteriorly for pectoral and posteriorly for pelvic girdles, and kept inside the sphere.
fn interior_root(
    pivot: DVec3,
    elbow: DVec3,
    lateral: DVec3,
    sphere: &GirdleSphere,
    girdle: Girdle,
    options: &FitOptions,
) -> DVec3 {
    let dx = (elbow - pivot).dot(lateral);
    let base = pivot + lateral * dx; // pivot moved into the elbow's sagittal plane
    let along = elbow - base;
    let d = along.length();
    let (u, a) = if d > 1e-12 {
        let a = ((d * d - dx * dx) / (2.0 * d)).clamp(0.1 * d, 0.9 * d);
        (along / d, a)
    } else {
        (DVec3::ZERO, 0.0)
    };
    let sign = match girdle {
        Girdle::Pectoral => 1.0,
        Girdle::Pelvic => -1.0,
    };
    let w = perpendicular(sphere.anterior, if u == DVec3::ZERO { lateral } else { u });
    let w = perpendicular(w, lateral);
    let mut p = base + u * a + w * sign * options.girdle_offset * sphere.radius;
    let reach = options.girdle_inside * sphere.radius;
    let off = p - sphere.centre;
    if off.length() > reach && off.length() > 0.0 {
        p = sphere.centre + off * (reach / off.length());
    }
    p
}

/// The first arc length at or after `from` (within the path's proximal two thirds) from which
/// a ray along unit `towards` leaves the figure within `k` local radii: where the limb comes
/// free of the trunk on that side ([`FitOptions::limb_fold`]); and the joint there: one local
/// radius inside the surface point the ray leaves through (the fold's corner). `None` when the
/// path never does, or `towards` is zero.
fn fold(
    path: &Polyline,
    radii: &[f64],
    from: f64,
    towards: DVec3,
    k: f64,
    probe: &dyn DorsalProbe,
) -> Option<(f64, DVec3)> {
    const STEPS: usize = 64;
    if towards == DVec3::ZERO || radii.len() != path.points.len() {
        return None;
    }
    let end = path.length() * 2.0 / 3.0;
    if end <= from {
        return None;
    }
    (0..=STEPS)
        .map(|i| from + (end - from) * i as f64 / STEPS as f64)
        .find_map(|s| {
            let r = path.value_at(radii, s);
            let p = path.at(s);
            let d = probe.depth(p, towards)?;
            (r > 0.0 && d <= k * r).then(|| (s, p + towards * (d - r).max(0.0)))
        })
}

/// Digits (8.2): first digit = the one nearest the body's centre line, divided 36:25:15
/// proximal to distal; the others ordered by distance from it, divided 36:25:15:10.
fn digits(
    input: &LimbInput,
    group: &LimbGroup,
    template: &Template,
    options: &FitOptions,
    centre_distance: &dyn Fn(DVec3) -> f64,
    warnings: &mut Vec<FitWarning>,
) -> Vec<Vec<DVec3>> {
    let paths: Vec<Polyline> = input
        .digits
        .iter()
        .filter(|d| !d.path.is_empty())
        .map(|d| smoothed(&d.path, options.limb_smoothing))
        .collect();
    if paths.is_empty() {
        return Vec::new();
    }
    if paths.len() > group.digits.len() {
        warnings.push(FitWarning::ExtraDigits {
            group: group.name.clone(),
            found: paths.len(),
        });
    }
    let first = (0..paths.len())
        .min_by(|&i, &j| {
            let di = centre_distance(paths[i].at(0.5 * paths[i].length()));
            let dj = centre_distance(paths[j].at(0.5 * paths[j].length()));
            di.total_cmp(&dj).then(i.cmp(&j))
        })
        .unwrap_or(0);
    let tip = |i: usize| paths[i].at(paths[i].length());
    let mut order: Vec<usize> = (0..paths.len()).filter(|&i| i != first).collect();
    order.sort_by(|&i, &j| {
        tip(i)
            .distance(tip(first))
            .total_cmp(&tip(j).distance(tip(first)))
            .then(i.cmp(&j))
    });
    order.insert(0, first);
    let digit = template.ratios.get("digit").cloned().unwrap_or_default();
    let first_digit = template
        .ratios
        .get("first_digit")
        .cloned()
        .unwrap_or_default();
    order
        .iter()
        .enumerate()
        .map(|(k, &i)| {
            let w = if k == 0 { &first_digit } else { &digit };
            let w = if w.is_empty() { vec![1.0] } else { w.clone() };
            let len = paths[i].length();
            boundaries(&w)
                .iter()
                .map(|c| paths[i].at(c * len))
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::options::BendSnap;

    /// A limb path of voxel centres (0.01 apart) along x from 0 to 0.6, its end `from` 0.3 on
    /// lifted by `lift` per voxel (a straight step: a corner of that slope) after a sideways
    /// jog of `jog` there.
    fn path(jog: f64, lift: f64) -> Polyline {
        Polyline::new(
            (0..=60)
                .map(|i| {
                    let x = i as f64 * 0.01;
                    let beyond = (x - 0.3).max(0.0);
                    let y = if i >= 30 { jog } else { 0.0 } + beyond * lift;
                    DVec3::new(x.min(0.3) + beyond / (1.0 + lift * lift).sqrt(), y, 0.0)
                })
                .collect(),
        )
    }

    /// Snaps the middle joint of a root–middle–tip chain placed at 0.27 of the path.
    fn snapped(path: &Polyline) -> f64 {
        let length = path.length();
        let mut chain = vec![
            Some(path.at(0.0)),
            Some(path.at(0.27)),
            Some(path.at(length)),
        ];
        let mut chain_s = vec![Some(0.0), Some(0.27), Some(length)];
        let bend = BendSnap {
            window: 0.15,
            stencil: 0.06,
            min_angle: 20.0,
        };
        snap_to_bends(path, &mut chain, &mut chain_s, 0.0, length, &bend);
        chain_s[1].unwrap()
    }

    /// Regression (quaternius_cyberpunk_character turned Z-up): a straight limb whose centred
    /// voxel path jogs sideways by a voxel and a half turns 23 degrees over the 0.036 stencil,
    /// which moved its joint onto the jog; over twice the stencil it turns 12 and the joint
    /// stays. A real bend (45 degrees) turns as much over both and still takes the joint.
    #[test]
    fn a_voxel_jog_of_a_straight_limb_is_no_bend_but_a_corner_is() {
        let jogged = path(0.015, 0.0);
        let h = 0.06 * jogged.length();
        let at_jog = (0..=60)
            .map(|i| turn_over(&jogged, 0.25 + i as f64 * 0.001, h))
            .fold(0.0, f64::max);
        assert!(at_jog > 20.0, "the short stencil sees a bend: {at_jog}");
        assert_eq!(snapped(&jogged), 0.27, "a jog moved the joint");
        let bent = path(0.0, 1.0);
        let s = snapped(&bent);
        assert!(
            (s - 0.3).abs() < 0.01,
            "the corner at 0.3 takes the joint: {s}"
        );
        assert!(bend_turn(&bent, 0.3, h) > 40.0);
    }

    /// A corner just before the joint's window (at 0.17, the window starting at 0.18) turns
    /// most at the window's edge over the stencil, but peaks outside it: the joint stays. The
    /// same corner inside the window (at 0.24) still takes it.
    #[test]
    fn a_bend_peaking_outside_the_window_belongs_to_the_neighbouring_joint() {
        let corner = |at: f64| {
            Polyline::new(
                (0..=60)
                    .map(|i| {
                        let x = i as f64 * 0.01;
                        let beyond = (x - at).max(0.0);
                        DVec3::new(
                            x.min(at) + beyond * 0.5f64.sqrt(),
                            -beyond * 0.5f64.sqrt(),
                            0.0,
                        )
                    })
                    .collect(),
            )
        };
        let early = corner(0.17);
        let h = 0.06 * early.length();
        let edge = 0.27 - 0.15 * early.length();
        assert!(
            bend_turn(&early, edge, h) >= 20.0,
            "the edge is on the corner's slope"
        );
        assert_eq!(
            snapped(&early),
            0.27,
            "the shoulder's corner took the elbow"
        );
        let s = snapped(&corner(0.24));
        assert!((s - 0.24).abs() < 0.01, "a corner inside the window: {s}");
    }

    /// The tarsal row after the hock snapped up its straight path: the foot joint one row
    /// (tarsals over tibia, 35/174 of the snapped shank) below the ankle, not left at its
    /// Table 8.1 place far down the cannon; left alone when the ankle did not move, when the
    /// foot itself snapped, or when the row is already shorter.
    #[test]
    fn a_snapped_ankle_takes_the_foot_joint_one_tarsal_row_along() {
        let template = Template::builtin("quadruped").unwrap();
        let group = template
            .limbs
            .iter()
            .find(|g| g.name == "hind_leg")
            .unwrap();
        let ratios = &template.ratios[&group.ratios];
        let path = Polyline::new(
            (0..=100)
                .map(|i| DVec3::new(0.0, -0.01 * i as f64, 0.0))
                .collect(),
        );
        // hip, knee, ankle, foot, toe, toe_02, toe_03, toe_end.
        let before = [0.0, 0.1, 0.5, 0.6, 0.8, 0.9, 0.95, 1.0].map(Some);
        let run = |after: [Option<f64>; 8]| {
            let mut chain_s = after.to_vec();
            let mut chain: Vec<Option<DVec3>> =
                chain_s.iter().map(|s| s.map(|s| path.at(s))).collect();
            short_row(&path, group, ratios, &before, &mut chain, &mut chain_s);
            (chain_s[3].unwrap(), chain[3].unwrap())
        };
        let mut snapped = before;
        snapped[2] = Some(0.4);
        let (s, p) = run(snapped);
        let expected = 0.4 + 0.3 * 35.0 / 174.0;
        assert!((s - expected).abs() < 1e-12, "{s} vs {expected}");
        assert!(p.distance(path.at(expected)) < 1e-12);
        assert_eq!(run(before).0, 0.6, "the ankle did not move");
        let mut both = snapped;
        both[3] = Some(0.55);
        assert_eq!(run(both).0, 0.55, "the foot snapped too");
        let mut down = before;
        down[2] = Some(0.58);
        assert_eq!(run(down).0, 0.6, "a row already shorter");
    }
}

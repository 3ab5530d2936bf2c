//! The refinement's arm phase: wrist, shoulder and elbow of one side (seed 004, 3.3).

use super::driver::{frame_point, Found, Rough, Scene};
use super::limb::trace_limb;
use super::limb_joints::{arc_near, bend, centre_in_depth, reaches, surface_above, wrist};
use super::shoulder::{armpit, off_axis, shoulder, upper_arm_line, upper_arm_radius};
use super::RefineWarning;
use crate::skeleton::{Canonical, Side};
use glam::DVec3;

/// Heights tried in turn as the bottom of the gap under the armpit, as fractions of the way
/// from the waist to the rough shoulder (the armpit is about 0.7 of the way up).
const ARMPIT_LEVELS: [f64; 3] = [0.0, 0.2, 0.4];

/// Lateral positions tried per side when searching the armpit.
const ARMPIT_SAMPLES: usize = 120;

/// The arm's trace must reach out from the rough shoulder to within this fraction of the
/// segment ending at a rough joint (upper arm for the elbow, forearm for the wrist) for that
/// joint to be searched on it. The wrist's search starts half a forearm before the rough
/// wrist and the elbow's ratio window is a fifth of the arm, so a trace ending more than a
/// quarter of the segment short of the joint (spheres stopped at the seams and voxel bridges
/// between the separate pieces of a jointed figure, or seeded on a strap's loop) finds no
/// joint there, and how far such a trace gets flips with a sub-voxel change of the grid
/// (quaternius_cyberpunk_character Y-up or Z-up). The joint keeps its rough place, for the
/// joint pieces to find its ball from.
const TRACE_REACH: f64 = 0.25;

/// Places the wrist, shoulder and elbow of `side` into `found`, or warns. `waist` is the height
/// half-way between the rough hips and shoulders.
pub(super) fn arm(
    scene: &Scene,
    rough: &Rough,
    side: Side,
    waist: Option<f64>,
    found: &mut Found,
    warnings: &mut Vec<RefineWarning>,
) {
    let Scene {
        mesh,
        frame,
        height,
        centre,
        options,
    } = *scene;
    let frame = &frame;
    let sign = side.sign();
    let (Some(sh), Some(el), Some(wr)) = (
        rough.at(Canonical::Shoulder(side)),
        rough.at(Canonical::Elbow(side)),
        rough.at(Canonical::Wrist(side)),
    ) else {
        warnings.push(RefineWarning::ArmJointsMissing(side));
        return;
    };
    let Some(profile) = trace_limb(mesh, &[sh, el, wr], height, options) else {
        warnings.push(RefineWarning::ArmNotSliced(side));
        return;
    };
    let step = 0.25 * options.limb_step * height;
    let (se, sw) = (arc_near(&profile, el), arc_near(&profile, wr));
    let reached = |joint: DVec3, from: DVec3| {
        reaches(&profile, sh, joint, TRACE_REACH * joint.distance(from))
    };
    if !reached(wr, el) {
        warnings.push(RefineWarning::TraceShort(Canonical::Wrist(side)));
    } else {
        // A forearm is shorter than the upper arm (0.146 and 0.186 of the height in Drillis
        // and Contini's table), so the wrist lies within an upper arm's length of the elbow:
        // a rough wrist that the fit's segmentation put far out in a big hand or fist (a
        // sub-voxel change of the grid moved quaternius_platformer_character's, turned Z-up,
        // past its wrist's narrowing) does not start the search beyond the real wrist.
        let upper = se - arc_near(&profile, sh);
        let forearm = if upper > 0.0 {
            (sw - se).min(upper)
        } else {
            sw - se
        };
        match wrist(&profile, se + options.wrist_search_from * forearm, step) {
            Some(w) => {
                found.insert(Canonical::Wrist(side), w);
            }
            None => warnings.push(RefineWarning::NoWrist(side)),
        }
    }
    let shoulder_point = waist.and_then(|w| {
        let outer = (el - centre).dot(frame.left) * sign;
        let ss = arc_near(&profile, sh);
        // The middle of the upper arm; the whole of it when the trace skipped that part
        // (a sphere that met the torso near the shoulder jumps down the arm).
        let line = [(0.2, 0.7), (0.0, 1.0)]
            .iter()
            .find_map(|&(a, b)| upper_arm_line(&profile, ss + a * (se - ss), ss + b * (se - ss)))?;
        // Arms that touch the body at the waist (heavy bodies) still leave a gap higher
        // up: the gap's reference height climbs towards the shoulder until one is found.
        let pit = ARMPIT_LEVELS.iter().find_map(|&k| {
            armpit(
                mesh,
                frame,
                frame_point(frame, line.0, centre),
                sign,
                0.0,
                outer,
                w + k * (frame.h(sh) - w),
                ARMPIT_SAMPLES,
            )
        })?;
        let radius = upper_arm_radius(&profile, ss, se)?;
        let s = shoulder(frame, line, pit, sign)? - line.1 * (options.shoulder_proximal * radius);
        // The joint is a ball on the upper arm's axis: a correction from the surface around
        // it that would put it more than an arm's radius off that axis measured a shoulder
        // pad, an armour plate or the torso's shell, not the arm, and is not taken.
        let on_ball = |moved: DVec3, kept: DVec3| {
            if off_axis(line, moved) <= radius {
                moved
            } else {
                kept
            }
        };
        let s = match options.shoulder_depth {
            Some(depth) => on_ball(centre_in_depth(mesh, frame, s, depth).unwrap_or(s), s),
            None => s,
        };
        let s = match options.shoulder_below_top {
            Some(k) => on_ball(
                surface_above(mesh, frame, s).map_or(s, |top| frame.at_height(s, top - k * radius)),
                s,
            ),
            None => s,
        };
        Some(s)
    });
    match shoulder_point {
        Some(s) => {
            found.insert(Canonical::Shoulder(side), s);
        }
        None => warnings.push(RefineWarning::NoArmpit(side)),
    }
    let proximal = found.get(&Canonical::Shoulder(side)).copied().unwrap_or(sh);
    let distal = found.get(&Canonical::Wrist(side)).copied().unwrap_or(wr);
    if !reached(el, sh) {
        warnings.push(RefineWarning::TraceShort(Canonical::Elbow(side)));
        return;
    }
    match bend(&profile, proximal, distal, options.arm_ratio, step, options) {
        Some((e, _)) => {
            found.insert(Canonical::Elbow(side), e);
        }
        None => warnings.push(RefineWarning::NoElbow(side)),
    }
}

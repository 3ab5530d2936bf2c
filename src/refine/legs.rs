//! The refinement's leg phase: ankle and knee of one side (seed 004, 3.3).

use super::driver::{Found, Rough, Scene};
use super::geometry::nearest_loop;
use super::limb::trace_limb;
use super::limb_joints::{ankle, arc_near, bend, on_axis, sole_under, transverse_point, BendRule};
use super::RefineWarning;
use crate::mesh::slice_plane_outer;
use crate::skeleton::{Canonical, Side};

/// The sole under an ankle is searched within this fraction of height across the body.
const SOLE_REACH: f64 = 0.06;

/// Places the ankle and knee of `side` into `found` (from the refined hip when there is one),
/// or warns. With the crotch hidden by clothing the thigh's slices run through the skirt, so
/// the knee goes at `leg_ratio` of the way from hip to ankle, inside the leg's slice there
/// when that slice is the leg's own.
pub(super) fn leg(
    scene: &Scene,
    rough: &Rough,
    side: Side,
    crotch_hidden: bool,
    found: &mut Found,
    warnings: &mut Vec<RefineWarning>,
) {
    let Scene {
        mesh,
        frame,
        height,
        options,
        ..
    } = *scene;
    let frame = &frame;
    let hip = found
        .get(&Canonical::Hip(side))
        .copied()
        .or_else(|| rough.at(Canonical::Hip(side)));
    let (Some(hip), Some(knee), Some(ank)) = (
        hip,
        rough.at(Canonical::Knee(side)),
        rough.at(Canonical::Ankle(side)),
    ) else {
        warnings.push(RefineWarning::LegJointsMissing(side));
        return;
    };
    let Some(profile) = trace_limb(mesh, &[hip, knee, ank], height, options) else {
        // No tube to slice (a short cartoon leg about as thick as it is long, whose rough
        // knee by adult ratios sits in the trunk): as when the trace stops short, the ankle
        // at the ankle's height above the sole and the knee by the leg's proportions from the
        // refined hip, each only inside the leg's own section; else both stay rough.
        // A coat or a robe hiding the crotch hides the knee too: when the leg shows apart
        // below it (its ankle has its own section), the knee goes on the line from hip to
        // ankle, as when the trace runs through the skirt. A blob shows no leg apart.
        let placed = ankle_above_sole(scene, side, ank);
        let by_ratio = if crotch_hidden && placed.is_some() {
            Some(knee_by_ratio(scene, side, hip, knee, placed.unwrap_or(ank)))
        } else {
            let h = knee_height(scene, hip, placed.unwrap_or(ank));
            own_section(scene, side, frame.at_height(knee, h))
        };
        if let Some(a) = placed {
            found.insert(Canonical::Ankle(side), a);
        }
        if let Some(k) = by_ratio {
            found.insert(Canonical::Knee(side), k);
        }
        if placed.is_none() && by_ratio.is_none() {
            warnings.push(RefineWarning::LegNotSliced(side));
        } else {
            warnings.push(RefineWarning::NoAnkle {
                side,
                placed: placed.is_some(),
            });
            warnings.push(RefineWarning::NoKnee {
                side,
                placed: by_ratio.is_some(),
            });
        }
        return;
    };
    let step = 0.25 * options.limb_step * height;
    let (sk, sa) = (arc_near(&profile, knee), arc_near(&profile, ank));
    let from = sk + options.ankle_search_from * (sa - sk);
    // A leg's ankle is on its own side of the median plane: sphere slices that took in both
    // shins of legs standing close together (feet side by side) centre between them, and
    // such an ankle is left for the sole rule below.
    let own_side = |a: &glam::DVec3| (*a - scene.centre).dot(frame.left) * side.sign() > 0.0;
    match ankle(&profile, from, options.curvature_window * height, step).filter(own_side) {
        Some(a) => {
            let a = match options.ankle_height {
                Some(f) => sole_under(mesh, frame, a, SOLE_REACH * height)
                    .map_or(a, |sole| frame.at_height(a, sole + f * height)),
                None => a,
            };
            // The foot pulls the sphere slices' centroids forward around the ankle: take
            // the depth from the shin's axis instead (the lower shin, above the
            // curvature window).
            let a = if options.ankle_on_shin_axis {
                let sa = arc_near(&profile, a);
                let lo = sk + 0.4 * (sa - sk);
                let hi = sa - 0.5 * options.curvature_window * height;
                on_axis(&profile, frame, lo, hi, step, frame.h(a))
                    .map_or(a, |p| a + frame.forward * (p - a).dot(frame.forward))
            } else {
                a
            };
            found.insert(Canonical::Ankle(side), a);
        }
        // The trace stopped short (a gap between armour pieces, a boot that is a separate
        // shell): the ankle stands at the ankle's height above the sole under the rough one,
        // when the leg has its own cross-section there (not on a blob with fused legs).
        None => {
            let placed = ankle_above_sole(scene, side, ank);
            if let Some(a) = placed {
                found.insert(Canonical::Ankle(side), a);
            }
            warnings.push(RefineWarning::NoAnkle {
                side,
                placed: placed.is_some(),
            });
        }
    }
    let distal = found.get(&Canonical::Ankle(side)).copied().unwrap_or(ank);
    let knee = if crotch_hidden {
        Some(knee_by_ratio(scene, side, hip, knee, distal))
    } else {
        match bend_knee(&profile, hip, distal, step, scene) {
            Some(k) => Some(k),
            // No bend on the curve (it ends above the knee's part of the leg): the surface
            // says nothing, the proportions place it, inside the leg's own section.
            None => {
                let h = knee_height(scene, hip, distal);
                let k = own_section(scene, side, frame.at_height(knee, h));
                warnings.push(RefineWarning::NoKnee {
                    side,
                    placed: k.is_some(),
                });
                k
            }
        }
    };
    if let Some(k) = knee {
        found.insert(Canonical::Knee(side), k);
    }
}

/// The ankle at the ankle's height above the sole under the rough ankle `ank`, when the leg has
/// its own cross-section there: for a trace that stopped short (a gap between armour pieces, a
/// boot that is a separate shell).
fn ankle_above_sole(scene: &Scene, side: Side, ank: glam::DVec3) -> Option<glam::DVec3> {
    let f = scene.options.ankle_height?;
    let sole = sole_under(scene.mesh, &scene.frame, ank, SOLE_REACH * scene.height)?;
    let a = scene.frame.at_height(ank, sole + f * scene.height);
    own_section(scene, side, a).map(|_| a)
}

/// The knee's height by the leg's proportions: `leg_ratio` of the way from the hip's height
/// down to the ankle's (`distal`).
fn knee_height(scene: &Scene, hip: glam::DVec3, distal: glam::DVec3) -> f64 {
    let frame = &scene.frame;
    frame.h(hip) + scene.options.leg_ratio * (frame.h(distal) - frame.h(hip))
}

/// The knee at `leg_ratio` of the way from the hip's height to the ankle's (`distal`), inside
/// the leg's slice there (near the rough `knee`) when that slice is the leg's own
/// ([`own_section`]), else on the straight line between hip and ankle (clothing hides the
/// crotch; a coat's section around both legs has its centroid between them).
fn knee_by_ratio(
    scene: &Scene,
    side: Side,
    hip: glam::DVec3,
    knee: glam::DVec3,
    distal: glam::DVec3,
) -> glam::DVec3 {
    let frame = &scene.frame;
    let h = knee_height(scene, hip, distal);
    let line = frame.at_height(hip.lerp(distal, scene.options.leg_ratio), h);
    own_section(scene, side, frame.at_height(knee, h)).unwrap_or(line)
}

/// The leg's own transverse section at the height of `p`, at its centroid across the body and
/// the knee depth: `None` unless the closed loop nearest `p` lies wholly on `side` of the
/// body's centre (a leg apart from the other one, not a blob with the legs fused).
fn own_section(scene: &Scene, side: Side, p: glam::DVec3) -> Option<glam::DVec3> {
    let Scene {
        mesh,
        frame,
        options,
        centre,
        ..
    } = *scene;
    let h = frame.h(p);
    let origin = frame.at_height(p, h);
    let loops = slice_plane_outer(mesh, origin, frame.up);
    let apart = nearest_loop(&loops, origin)
        .filter(|l| l.closed)
        .is_some_and(|l| {
            l.points
                .iter()
                .all(|q| (*q - centre).dot(frame.left) * side.sign() > 0.0)
        });
    if !apart {
        return None;
    }
    transverse_point(mesh, &frame, p, h, options.knee_depth.unwrap_or(0.5))
}

/// The knee on the leg's centroid curve (the bend, else `leg_ratio` of the way down).
fn bend_knee(
    profile: &super::limb::LimbProfile,
    hip: glam::DVec3,
    distal: glam::DVec3,
    step: f64,
    scene: &Scene,
) -> Option<glam::DVec3> {
    let Scene {
        mesh,
        frame,
        options,
        ..
    } = *scene;
    let frame = &frame;
    match bend(profile, hip, distal, options.leg_ratio, step, options) {
        Some((k, BendRule::Ratio)) => options.knee_depth.map_or(Some(k), |depth| {
            let h = knee_height(scene, hip, distal);
            transverse_point(mesh, frame, k, h, depth).or(Some(k))
        }),
        other => other.map(|(k, _)| k),
    }
}

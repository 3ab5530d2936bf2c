//! The refinement driver: body frame, head, torso, hips, legs, arms, spine, then the skeleton.

use super::carry::carry;
use super::frame::{frame_from_head, head_slices, BodyFrame};
use super::head::head_joint;
use super::limb::trace_limb;
use super::limb_joints::{
    ankle, arc_near, bend, centre_in_depth, on_axis, sole_under, surface_above, transverse_point,
    wrist, BendRule,
};
use super::shoulder::{armpit, shoulder, upper_arm_line, upper_arm_radius};
use super::spine::{spine, Spine};
use super::torso::{hips, leg_split_height, torso_points, TorsoBounds, TorsoPoints};
use super::{RefineError, RefineOptions};
use crate::mesh::{slice_plane, Mesh};
use crate::skeleton::{JointId, Skeleton};
use glam::DVec3;
use std::collections::BTreeMap;

/// The canonical joints the refinement places.
pub const REFINED_KEYS: [&str; 15] = [
    "pelvis",
    "neck",
    "head",
    "shoulder_L",
    "shoulder_R",
    "elbow_L",
    "elbow_R",
    "wrist_L",
    "wrist_R",
    "hip_L",
    "hip_R",
    "knee_L",
    "knee_R",
    "ankle_L",
    "ankle_R",
];

/// The sole under an ankle is searched within this fraction of height across the body.
const SOLE_REACH: f64 = 0.06;

/// Heights tried in turn as the bottom of the gap under the armpit, as fractions of the way
/// from the waist to the rough shoulder (the armpit is about 0.7 of the way up).
const ARMPIT_LEVELS: [f64; 3] = [0.0, 0.2, 0.4];

/// Lateral positions tried per side when searching the armpit.
const ARMPIT_SAMPLES: usize = 120;

/// A refined skeleton and what the refinement found on the way.
#[derive(Debug, Clone, PartialEq)]
pub struct Refinement {
    /// The input skeleton with the refined canonical joints moved, the joints between them
    /// carried along (spine joints onto the spine curve) and frames turned with their segments.
    pub skeleton: Skeleton,
    /// The full spine from the top: `C1`..`C7`, `T1`..`T12`, `L1`..`L5` (each the joint below
    /// that vertebra) and `sacrum`; empty when the spine was not found.
    pub spine: Vec<(String, DVec3)>,
    /// Per canonical key that moved: (rough position, refined position).
    pub moved: BTreeMap<String, (DVec3, DVec3)>,
    /// The body frame the analysis used.
    pub frame: BodyFrame,
    /// Characteristic torso points, when the median silhouette was found.
    pub torso: Option<TorsoPoints>,
    /// One line per joint that kept its rough position, naming the joint and the reason.
    pub warnings: Vec<String>,
}

/// Refines a roughly aligned humanoid skeleton by slicing its mesh (seed 004).
///
/// * `mesh`: the body surface (closed or nearly so), any units and frame.
/// * `skeleton`, `canonical`: the rough skeleton and its canonical key → joint map (keys as in
///   [`REFINED_KEYS`]; `toe_*`, `spine`, `chest` and others are carried along).
/// * `up`, `forward`: the figure's up and facing directions in the mesh frame; `up` is
///   replaced by the legs' ankle→hip direction and `forward` by the head's long axis when
///   those are found (seed 004, 3.1).
///
/// Each joint that cannot be refined keeps its rough position and adds a warning that names it;
/// nothing panics on odd input.
///
/// # Errors
/// [`RefineError::EmptyMesh`], [`RefineError::BadDirections`] for zero, non-finite or parallel
/// `up`/`forward`, [`RefineError::BadJointId`] for a canonical id outside the skeleton.
pub fn refine(
    mesh: &Mesh,
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    up: DVec3,
    forward: DVec3,
    options: &RefineOptions,
) -> Result<Refinement, RefineError> {
    if mesh.triangles.is_empty() {
        return Err(RefineError::EmptyMesh);
    }
    let bad = || RefineError::BadDirections { up, forward };
    if !up.is_finite() || !forward.is_finite() {
        return Err(bad());
    }
    for (key, id) in canonical {
        if id.0 >= skeleton.len() {
            return Err(RefineError::BadJointId {
                key: key.clone(),
                id: id.0,
                len: skeleton.len(),
            });
        }
    }
    let rough = |key: &str| canonical.get(key).map(|id| skeleton.joint(*id).position);
    let mut warnings = Vec::new();
    let given = BodyFrame::new(mesh, up, forward).ok_or_else(bad)?;
    let legs_up = ["L", "R"]
        .iter()
        .filter_map(|s| Some(rough(&format!("hip_{s}"))? - rough(&format!("ankle_{s}"))?))
        .sum::<DVec3>()
        .try_normalize()
        .filter(|n| n.dot(given.up) > std::f64::consts::FRAC_1_SQRT_2);
    let mut frame = match legs_up.and_then(|n| BodyFrame::new(mesh, n, given.forward)) {
        Some(f) => f,
        None => {
            warnings.push(
                "body frame: no upright legs in the rough skeleton, using the given up direction"
                    .into(),
            );
            given
        }
    };
    let height = frame.height();
    let fine = fine_enough(mesh, options.max_mean_edge * height);
    let mesh = fine.as_ref().unwrap_or(mesh);
    let mut found: BTreeMap<&str, DVec3> = BTreeMap::new();

    // 3.1 Head and body frame.
    let near_head = rough("head").unwrap_or_else(|| frame.at_height(DVec3::ZERO, frame.top));
    match head_slices(mesh, &frame, near_head, options) {
        Some(slices) => {
            if let Some(f) = frame_from_head(&frame, &slices, frame.forward) {
                frame = f;
            }
            match head_joint(&frame, &slices, options) {
                Some(h) => {
                    found.insert("head", h.joint);
                }
                None => warnings.push("head: no occipital circle on the nose-level slice".into()),
            }
        }
        None => warnings.push("head: no head found slicing down from the top".into()),
    }

    // 3.2 Torso points.
    let mean_height = |keys: [&str; 2]| {
        let hs: Vec<f64> = keys
            .iter()
            .filter_map(|k| rough(k))
            .map(|p| frame.h(p))
            .collect();
        (!hs.is_empty()).then(|| hs.iter().sum::<f64>() / hs.len() as f64)
    };
    let pelvis_rough = rough("pelvis").or_else(|| Some((rough("hip_L")? + rough("hip_R")?) * 0.5));
    let head_point = found.get("head").copied().or_else(|| rough("head"));
    let centre = match (pelvis_rough, head_point) {
        (Some(p), Some(h)) => p + frame.left * ((h - p).dot(frame.left) * 0.5),
        (Some(p), None) => p,
        (None, Some(h)) => h,
        (None, None) => frame.at_height(DVec3::ZERO, frame.bottom + 0.5 * height),
    };
    // The median plane passes through the waist's cross-section: the rough pelvis can sit a
    // centimetre or two off the body's middle, and the spine and neck (found in that plane)
    // moved sideways with it.
    let centre = match (
        mean_height(["hip_L", "hip_R"]),
        mean_height(["shoulder_L", "shoulder_R"]),
    ) {
        (Some(hips_h), Some(shoulders_h)) => {
            let origin = frame.at_height(centre, 0.5 * (hips_h + shoulders_h));
            slice_plane(mesh, origin, frame.up)
                .iter()
                .filter(|l| l.closed)
                .filter_map(|l| l.centroid())
                .min_by(|a, b| a.distance(origin).total_cmp(&b.distance(origin)))
                .map_or(centre, |g| {
                    centre + frame.left * (g - centre).dot(frame.left)
                })
        }
        _ => centre,
    };
    // 3.3 Arms.
    let waist = match (
        mean_height(["hip_L", "hip_R"]),
        mean_height(["shoulder_L", "shoulder_R"]),
    ) {
        (Some(h), Some(s)) => Some((h + s) * 0.5),
        _ => None,
    };
    for (side, sign) in [("L", 1.0), ("R", -1.0)] {
        let key = |joint: &str| -> &'static str {
            match (joint, side) {
                ("shoulder", "L") => "shoulder_L",
                ("shoulder", _) => "shoulder_R",
                ("elbow", "L") => "elbow_L",
                ("elbow", _) => "elbow_R",
                ("wrist", "L") => "wrist_L",
                _ => "wrist_R",
            }
        };
        let (Some(sh), Some(el), Some(wr)) = (
            rough(key("shoulder")),
            rough(key("elbow")),
            rough(key("wrist")),
        ) else {
            warnings.push(format!("shoulder_{side}, elbow_{side}, wrist_{side}: arm joints missing from the rough skeleton"));
            continue;
        };
        let Some(profile) = trace_limb(mesh, &[sh, el, wr], height, options) else {
            warnings.push(format!(
                "shoulder_{side}, elbow_{side}, wrist_{side}: the arm could not be sliced"
            ));
            continue;
        };
        let step = 0.25 * options.limb_step * height;
        let (se, sw) = (arc_near(&profile, el), arc_near(&profile, wr));
        match wrist(&profile, se + options.wrist_search_from * (sw - se), step) {
            Some(w) => {
                found.insert(key("wrist"), w);
            }
            None => warnings.push(format!("wrist_{side}: no thickness minimum on the forearm")),
        }
        let shoulder_point = waist.and_then(|w| {
            let outer = (el - centre).dot(frame.left) * sign;
            let ss = arc_near(&profile, sh);
            // The middle of the upper arm; the whole of it when the trace skipped that part
            // (a sphere that met the torso near the shoulder jumps down the arm).
            let line = [(0.2, 0.7), (0.0, 1.0)].iter().find_map(|&(a, b)| {
                upper_arm_line(&profile, ss + a * (se - ss), ss + b * (se - ss))
            })?;
            // Arms that touch the body at the waist (heavy bodies) still leave a gap higher
            // up: the gap's reference height climbs towards the shoulder until one is found.
            let pit = ARMPIT_LEVELS.iter().find_map(|&k| {
                armpit(
                    mesh,
                    &frame,
                    frame_point(&frame, line.0, centre),
                    sign,
                    0.0,
                    outer,
                    w + k * (frame.h(sh) - w),
                    ARMPIT_SAMPLES,
                )
            })?;
            let radius = upper_arm_radius(&profile, ss, se)?;
            let s =
                shoulder(&frame, line, pit, sign)? - line.1 * (options.shoulder_proximal * radius);
            let s = match options.shoulder_depth {
                Some(depth) => centre_in_depth(mesh, &frame, s, depth).unwrap_or(s),
                None => s,
            };
            let s = match options.shoulder_below_top {
                Some(k) => surface_above(mesh, &frame, s)
                    .map_or(s, |top| frame.at_height(s, top - k * radius)),
                None => s,
            };
            Some(s)
        });
        match shoulder_point {
            Some(s) => {
                found.insert(key("shoulder"), s);
            }
            None => warnings.push(format!(
                "shoulder_{side}: no armpit (arm touching the torso?)"
            )),
        }
        let proximal = found.get(key("shoulder")).copied().unwrap_or(sh);
        let distal = found.get(key("wrist")).copied().unwrap_or(wr);
        match bend(&profile, proximal, distal, options.arm_ratio, step, options) {
            Some((e, _)) => {
                found.insert(key("elbow"), e);
            }
            None => warnings.push(format!(
                "elbow_{side}: no elbow on the arm's centroid curve"
            )),
        }
    }

    let refined_shoulders = match (found.get("shoulder_L"), found.get("shoulder_R")) {
        (Some(l), Some(r)) => Some((frame.h(*l) + frame.h(*r)) * 0.5),
        _ => mean_height(["shoulder_L", "shoulder_R"]),
    };
    let bounds = match (
        head_point,
        refined_shoulders,
        mean_height(["hip_L", "hip_R"]),
    ) {
        (Some(h), Some(s), Some(p)) => Some(TorsoBounds {
            head: frame.h(h),
            shoulders: s,
            hips: p,
        }),
        _ => None,
    };
    let torso = bounds.and_then(|b| torso_points(mesh, &frame, centre, &b, options));
    if torso.is_none() {
        warnings.push("neck: no torso silhouette in the median plane (torso not upright?)".into());
    }

    // 3.3 Hips and pelvis.
    let reach = match (rough("hip_L"), rough("hip_R")) {
        (Some(l), Some(r)) => 1.5 * l.distance(r),
        _ => 0.15 * height,
    };
    let hip_height = match &torso {
        Some(t) => {
            let bottom = frame.h(t.crotch);
            let split = leg_split_height(
                mesh,
                &frame,
                centre,
                bottom - 0.02 * height,
                bottom + 0.1 * height,
                0.001 * height,
                reach,
            );
            Some(split.unwrap_or(bottom) + options.hip_above_crotch * height)
        }
        None => mean_height(["hip_L", "hip_R"]),
    };
    match hip_height.and_then(|h| hips(mesh, &frame, centre, h, reach)) {
        Some((l, r)) => {
            let in_depth = |p: DVec3| match options.hip_depth {
                Some(depth) => centre_in_depth(mesh, &frame, p, depth).unwrap_or(p),
                None => p,
            };
            let (l, r) = (in_depth(l), in_depth(r));
            found.insert("hip_L", l);
            found.insert("hip_R", r);
            found.insert(
                "pelvis",
                (l + r) * 0.5 + frame.up * (options.pelvis_above_hips * height),
            );
        }
        None => warnings.push("hip_L, hip_R, pelvis: no transverse slice at hip height".into()),
    }

    // 3.3 Legs.
    for (side, _) in [("L", 1.0), ("R", -1.0)] {
        let hip = found
            .get(format!("hip_{side}").as_str())
            .copied()
            .or_else(|| rough(&format!("hip_{side}")));
        let (Some(hip), Some(knee), Some(ank)) = (
            hip,
            rough(&format!("knee_{side}")),
            rough(&format!("ankle_{side}")),
        ) else {
            warnings.push(format!(
                "knee_{side}, ankle_{side}: leg joints missing from the rough skeleton"
            ));
            continue;
        };
        let Some(profile) = trace_limb(mesh, &[hip, knee, ank], height, options) else {
            warnings.push(format!(
                "knee_{side}, ankle_{side}: the leg could not be sliced"
            ));
            continue;
        };
        let step = 0.25 * options.limb_step * height;
        let (sk, sa) = (arc_near(&profile, knee), arc_near(&profile, ank));
        let from = sk + options.ankle_search_from * (sa - sk);
        match ankle(&profile, from, options.curvature_window * height, step) {
            Some(a) => {
                let a = match options.ankle_height {
                    Some(f) => sole_under(mesh, &frame, a, SOLE_REACH * height)
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
                    on_axis(&profile, &frame, lo, hi, step, frame.h(a))
                        .map_or(a, |p| a + frame.forward * (p - a).dot(frame.forward))
                } else {
                    a
                };
                found.insert(if side == "L" { "ankle_L" } else { "ankle_R" }, a);
            }
            None => warnings.push(format!(
                "ankle_{side}: the leg's centroid curve ends above the ankle"
            )),
        }
        let distal = found
            .get(if side == "L" { "ankle_L" } else { "ankle_R" })
            .copied()
            .unwrap_or(ank);
        let knee = match bend(&profile, hip, distal, options.leg_ratio, step, options) {
            Some((k, BendRule::Ratio)) => options.knee_depth.map_or(Some(k), |depth| {
                let h = frame.h(hip) + options.leg_ratio * (frame.h(distal) - frame.h(hip));
                transverse_point(mesh, &frame, k, h, depth).or(Some(k))
            }),
            other => other.map(|(k, _)| k),
        };
        match knee {
            Some(k) => {
                found.insert(if side == "L" { "knee_L" } else { "knee_R" }, k);
            }
            None => warnings.push(format!("knee_{side}: no knee on the leg's centroid curve")),
        }
    }

    // 3.2 Spine and neck.
    let spine_result: Option<Spine> = match (&torso, found.get("head")) {
        (Some(t), Some(&h)) => spine(&frame, centre, h, t, options),
        _ => None,
    };
    match (&spine_result, &torso) {
        (Some(s), _) => {
            if let Some(c7) = s.joint("C7") {
                found.insert("neck", c7);
            }
        }
        (None, Some(t)) => {
            found.insert("neck", t.neck.lerp(t.throat, options.neck_depth));
            warnings.push("spine: the spine curve's control points are out of order; spine joints carried along".into());
        }
        (None, None) => {
            warnings.push("spine: no spine without the head joint and the torso silhouette".into())
        }
    }

    // Accept refined positions that stay near the rough ones.
    // Joints that are not refined stay where they were (not carried by their neighbours).
    let mut targets: BTreeMap<JointId, DVec3> = REFINED_KEYS
        .iter()
        .filter_map(|key| canonical.get(*key))
        .map(|id| (*id, skeleton.joint(*id).position))
        .collect();
    let mut moved = BTreeMap::new();
    for key in REFINED_KEYS {
        if options.keep.iter().any(|k| k == key) {
            continue;
        }
        let (Some(&id), Some(&to)) = (canonical.get(key), found.get(key)) else {
            if canonical.contains_key(key) && !warnings.iter().any(|w| w.contains(key)) {
                warnings.push(format!("{key}: kept at the unrefined position"));
            }
            continue;
        };
        let from = skeleton.joint(id).position;
        if !to.is_finite() || from.distance(to) > options.max_shift * height {
            warnings.push(format!(
                "{key}: refined position {:.3} m from the rough one, kept at the unrefined position",
                from.distance(to)
            ));
            continue;
        }
        targets.insert(id, to);
        moved.insert(key.to_string(), (from, to));
    }
    let spine_ends_moved = moved.contains_key("pelvis") && moved.contains_key("neck");
    if let (Some(s), true) = (&spine_result, spine_ends_moved) {
        for (id, p) in place_spine_joints(skeleton, canonical, s) {
            targets.insert(id, p);
        }
    }
    Ok(Refinement {
        skeleton: carry(skeleton, &targets),
        spine: spine_result.map(|s| s.joints).unwrap_or_default(),
        moved,
        frame,
        torso,
        warnings,
    })
}

/// `mesh` split at edge midpoints until its mean edge is at most `max_edge` (at most three
/// rounds), or `None` when it already is: plane and sphere slices cut triangles by their
/// corners' sides, so a long triangle crossing a small sphere with all corners outside would be
/// missed.
fn fine_enough(mesh: &Mesh, max_edge: f64) -> Option<Mesh> {
    let mean_edge = |m: &Mesh| {
        let total: f64 = (0..m.triangles.len())
            .map(|t| {
                let [a, b, c] = m.corners(t);
                a.distance(b) + b.distance(c) + c.distance(a)
            })
            .sum();
        total / (3 * m.triangles.len().max(1)) as f64
    };
    let mut out: Option<Mesh> = None;
    for _ in 0..3 {
        let current = out.as_ref().unwrap_or(mesh);
        if mean_edge(current) <= max_edge {
            break;
        }
        out = Some(current.subdivided());
    }
    out
}

/// `p` moved across the body into the plane through `centre` with normal `frame.forward`.
fn frame_point(frame: &BodyFrame, centre: DVec3, p: DVec3) -> DVec3 {
    p - frame.forward * (p - centre).dot(frame.forward)
}

/// The joints strictly between pelvis and neck on the skeleton's chain, placed on the spine
/// polyline from `L5` up to `C7` at their original fractions of the chain's length.
fn place_spine_joints(
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    spine: &Spine,
) -> Vec<(JointId, DVec3)> {
    let (Some(&pelvis), Some(&neck)) = (canonical.get("pelvis"), canonical.get("neck")) else {
        return Vec::new();
    };
    let mut chain = Vec::new();
    let mut k = skeleton.joint(neck).parent;
    while let Some(p) = k {
        if p == pelvis {
            break;
        }
        chain.push(p);
        k = skeleton.joint(p).parent;
    }
    if k != Some(pelvis) || chain.is_empty() {
        return Vec::new();
    }
    chain.reverse(); // pelvis side first
    let path: Vec<DVec3> = std::iter::once(pelvis)
        .chain(chain.iter().copied())
        .chain(std::iter::once(neck))
        .map(|id| skeleton.joint(id).position)
        .collect();
    let total: f64 = path.windows(2).map(|w| w[0].distance(w[1])).sum();
    let curve: Vec<DVec3> = [
        "L5", "L4", "L3", "L2", "L1", "T12", "T11", "T10", "T9", "T8", "T7", "T6", "T5", "T4",
        "T3", "T2", "T1", "C7",
    ]
    .iter()
    .filter_map(|n| spine.joint(n))
    .collect();
    if total <= 0.0 || curve.len() < 2 {
        return Vec::new();
    }
    let lengths: Vec<f64> = curve.windows(2).map(|w| w[0].distance(w[1])).collect();
    let curve_total: f64 = lengths.iter().sum();
    let mut along = 0.0;
    let mut out = Vec::new();
    for (i, id) in chain.iter().enumerate() {
        along += path[i].distance(path[i + 1]);
        let mut s = along / total * curve_total;
        let mut p = curve[curve.len() - 1];
        for (w, l) in curve.windows(2).zip(&lengths) {
            if s <= *l {
                p = w[0].lerp(w[1], if *l > 0.0 { s / l } else { 0.0 });
                break;
            }
            s -= l;
        }
        out.push((*id, p));
    }
    out
}

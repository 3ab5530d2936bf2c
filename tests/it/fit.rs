//! Anatomical fit (dissertation 8.1-8.2) on synthetic geometry: straight and bent polylines
//! standing in for labelled humanoids and quadrupeds.

use glam::{DMat3, DVec3};
use skelfit::eval::{detect_preset, CANONICAL_KEYS};
use skelfit::fit::{
    fit, fit_with_probe, AxialPath, DigitInput, Fit, FitError, FitInput, FitOptions, FitWarning,
    LimbInput, Side,
};
use skelfit::skeleton::JointId;
use skelfit::template::{LimbKind, Preset, Template};

/// Points every `step` along the polyline through `corners`.
fn dense(corners: &[DVec3], step: f64) -> Vec<DVec3> {
    let mut out = vec![corners[0]];
    for w in corners.windows(2) {
        let n = ((w[1] - w[0]).length() / step).ceil().max(1.0) as usize;
        out.extend((1..=n).map(|k| w[0].lerp(w[1], k as f64 / n as f64)));
    }
    out
}

fn limb(kind: LimbKind, side: Side, pair: usize, attach: DVec3, corners: &[DVec3]) -> LimbInput {
    let path = dense(corners, 0.01);
    LimbInput {
        kind,
        side,
        pair,
        attach,
        radii: vec![0.04; path.len()],
        path,
        digits: Vec::new(),
        root: None,
    }
}

/// A 1.75 m humanoid in a T-pose: +Y up, +Z forward, left +X; bent legs with feet forward.
fn humanoid() -> FitInput {
    let points = dense(
        &[DVec3::new(0.0, 1.75, 0.0), DVec3::new(0.0, 0.9, 0.0)],
        0.01,
    );
    let radii = points
        .iter()
        .map(|p| {
            if p.y > 1.5 {
                0.08
            } else if p.y > 1.42 {
                0.05
            } else {
                0.13
            }
        })
        .collect();
    let mut limbs = Vec::new();
    for side in [Side::Left, Side::Right] {
        let s = side.sign();
        let shoulder = DVec3::new(0.0, 1.4, 0.0);
        limbs.push(limb(
            LimbKind::Arm,
            side,
            0,
            shoulder,
            &[shoulder, DVec3::new(s * 0.85, 1.4, 0.0)],
        ));
        let hip = DVec3::new(0.0, 0.9, 0.0);
        limbs.push(limb(
            LimbKind::Leg,
            side,
            0,
            hip,
            &[
                hip,
                DVec3::new(s * 0.1, 0.9, 0.0),
                DVec3::new(s * 0.1, 0.06, 0.0),
                DVec3::new(s * 0.1, 0.02, 0.2),
            ],
        ));
    }
    FitInput {
        up: DVec3::Y,
        forward: DVec3::Z,
        axial: AxialPath {
            points,
            radii,
            sections: None,
            tail: false,
        },
        limbs,
        jaw: None,
        ears: Vec::new(),
    }
}

/// A horse-like quadruped facing +Z with a tail.
fn quadruped() -> FitInput {
    let points = dense(
        &[
            DVec3::new(0.0, 1.0, 1.3),
            DVec3::new(0.0, 1.1, 0.9),
            DVec3::new(0.0, 0.85, 0.55),
            DVec3::new(0.0, 0.85, -0.45),
            DVec3::new(0.0, 0.5, -1.0),
        ],
        0.01,
    );
    let radii = points
        .iter()
        .map(|p| if p.z > 0.55 || p.z < -0.45 { 0.08 } else { 0.2 })
        .collect();
    let mut limbs = Vec::new();
    for side in [Side::Left, Side::Right] {
        let s = side.sign();
        for (kind, z) in [(LimbKind::ForeLeg, 0.45), (LimbKind::HindLeg, -0.35)] {
            let attach = DVec3::new(0.0, 0.85, z);
            limbs.push(limb(
                kind,
                side,
                0,
                attach,
                &[
                    attach,
                    DVec3::new(s * 0.15, 0.8, z),
                    DVec3::new(s * 0.15, 0.0, z),
                ],
            ));
        }
    }
    FitInput {
        up: DVec3::Y,
        forward: DVec3::Z,
        axial: AxialPath {
            points,
            radii,
            sections: None,
            tail: false,
        },
        limbs,
        jaw: None,
        ears: Vec::new(),
    }
}

/// Fits with the dissertation's limb rules alone: Table 8.1 without moving joints to the bends
/// of the path (those polylines have corners; `snap_to_bend` has its own test).
fn run(input: &FitInput, template: &str) -> Fit {
    let t = Template::builtin(template).unwrap();
    let options = FitOptions {
        snap_to_bend: None,
        ..Default::default()
    };
    fit(input, &t, &options).unwrap()
}

fn pos(f: &Fit, key: &str) -> DVec3 {
    f.skeleton.joint(f.canonical[key]).position
}

fn named(f: &Fit, name: &str) -> DVec3 {
    f.skeleton
        .joint(
            f.skeleton
                .find(name)
                .unwrap_or_else(|| panic!("no joint {name}")),
        )
        .position
}

/// Arc length along a polyline of the point nearest `p`.
fn arc(path: &[DVec3], p: DVec3) -> f64 {
    let mut best = (f64::INFINITY, 0.0);
    let mut s = 0.0;
    for w in path.windows(2) {
        let d = w[1] - w[0];
        let t = ((p - w[0]).dot(d) / d.length_squared()).clamp(0.0, 1.0);
        let dist = (w[0] + d * t).distance(p);
        if dist < best.0 {
            best = (dist, s + t * d.length());
        }
        s += d.length();
    }
    best.1
}

fn length(path: &[DVec3]) -> f64 {
    path.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// Checks that `names` sit at the cumulative fractions of `ratios` along `path` from the first.
fn assert_table_fractions(f: &Fit, path: &[DVec3], names: &[&str], ratios: &[f64]) {
    let total: f64 = ratios.iter().sum();
    let s0 = arc(path, named(f, names[0]));
    let span = length(path) - s0;
    let mut acc = 0.0;
    for (k, name) in names.iter().enumerate().skip(1) {
        acc += ratios[k - 1];
        let expected = s0 + span * acc / total;
        let got = arc(path, named(f, name));
        assert!(
            (got - expected).abs() < 0.01 * length(path),
            "{name}: {got:.4} along the limb, Table 8.1 gives {expected:.4}"
        );
    }
}

fn assert_frames_orthonormal(f: &Fit) {
    for (k, j) in f.skeleton.joints.iter().enumerate() {
        let m = DMat3::from_quat(j.frame);
        let id = m.transpose() * m;
        assert!(id.abs_diff_eq(DMat3::IDENTITY, 1e-9), "{}", j.name);
        assert!((m.determinant() - 1.0).abs() < 1e-9, "{}", j.name);
        // Local z points at a child along the chain when the joint has one away from it.
        let children = f.skeleton.children(JointId(k));
        if let Some(c) = children.first() {
            let d = f.skeleton.joint(*c).position - j.position;
            if d.length() > 1e-9 && children.len() == 1 {
                assert!(
                    m.z_axis.dot(d.normalize()) > 0.999,
                    "{} z not towards its child",
                    j.name
                );
            }
        }
    }
}

fn assert_left_right(f: &Fit) {
    for (key, id) in &f.canonical {
        if let Some(stem) = key.strip_suffix("_L") {
            let right = f.canonical[&format!("{stem}_R")];
            assert!(
                f.skeleton.joint(*id).position.x > f.skeleton.joint(right).position.x,
                "{key} is not left of its twin"
            );
        }
    }
}

#[test]
fn humanoid_has_every_canonical_joint_at_table_8_1_fractions() {
    let input = humanoid();
    let f = run(&input, "humanoid");
    assert!(f.skeleton.validate().is_ok());
    for key in CANONICAL_KEYS {
        assert!(
            f.canonical.contains_key(*key),
            "missing {key}: {:?}",
            f.warnings
        );
    }
    assert!(f.warnings.is_empty(), "{:?}", f.warnings);
    assert_left_right(&f);
    assert_frames_orthonormal(&f);
    let arm = &input.limbs[0].path;
    let t = Template::builtin("humanoid").unwrap();
    assert_table_fractions(
        &f,
        arm,
        &[
            "shoulder_L",
            "elbow_L",
            "wrist_L",
            "hand_L",
            "finger_01_L",
            "finger_02_L",
            "finger_03_L",
            "finger_end_L",
        ],
        &t.ratios["human_arm"],
    );
    let leg = &input.limbs[1].path;
    assert_table_fractions(
        &f,
        leg,
        &[
            "hip_L",
            "knee_L",
            "ankle_L",
            "foot_L",
            "toe_L",
            "toe_02_L",
            "toe_03_L",
            "toe_end_L",
        ],
        &t.ratios["human_leg"],
    );
    // Human-like: the shoulder just outside the girdle sphere (radius 0.13 at y = 1.4).
    assert!(
        (pos(&f, "shoulder_L").x - 0.13).abs() < 0.01,
        "{}",
        pos(&f, "shoulder_L")
    );
    // The spine runs behind the centre line (dorsal = -Z) by up to 70 % of the radius.
    let chest = pos(&f, "chest");
    assert!(chest.z < -0.05 && chest.z > -0.7 * 0.13 - 1e-9, "{chest}");
    // Order along the body.
    let y = |k: &str| pos(&f, k).y;
    assert!(y("head") > y("neck") && y("neck") > y("chest") && y("chest") > y("spine"));
    assert!(y("spine") > y("pelvis"));
    // The root is the pelvis, near the hips.
    assert_eq!(f.canonical["pelvis"], JointId(0));
    assert!(f.skeleton.joints[0].parent.is_none());
    assert!((y("pelvis") - 0.9).abs() < 0.1);
    // Hinges for knees and elbows.
    assert_eq!(f.skeleton.joint(f.canonical["knee_L"]).dofs.len(), 1);
    assert_eq!(f.skeleton.joint(f.canonical["shoulder_L"]).dofs.len(), 3);
    // Vertebral segments about a third of the head (0.425 m of path ahead of the arms, half head).
    let spine_count = f
        .skeleton
        .joints
        .iter()
        .filter(|j| j.name.starts_with("spine_"))
        .count();
    assert!((2..=5).contains(&spine_count), "{spine_count}");
}

#[test]
fn quadruped_places_elbows_outside_and_shoulders_inside_the_girdle() {
    let input = quadruped();
    let f = run(&input, "quadruped");
    assert!(f.skeleton.validate().is_ok());
    for key in CANONICAL_KEYS
        .iter()
        .copied()
        .chain(["tail_base", "tail_end"])
    {
        assert!(
            f.canonical.contains_key(key),
            "missing {key}: {:?}",
            f.warnings
        );
    }
    assert_left_right(&f);
    assert_frames_orthonormal(&f);
    let t = Template::builtin("quadruped").unwrap();
    // Girdle sphere of the fore pair: the path point at z = 0.45, radius 0.2.
    let centre = DVec3::new(0.0, 0.85, 0.45);
    let elbow = pos(&f, "elbow_L");
    assert!((elbow.distance(centre) - 0.2).abs() < 0.01, "{elbow}");
    let shoulder = pos(&f, "shoulder_L");
    assert!(shoulder.distance(centre) < 0.2, "{shoulder}");
    assert!(
        shoulder.z > 0.45,
        "pectoral interior joints shift anteriorly: {shoulder}"
    );
    assert!(
        (shoulder.x - elbow.x).abs() < 0.02,
        "width preserved: {shoulder} {elbow}"
    );
    let hip = pos(&f, "hip_L");
    assert!(
        hip.z < -0.35,
        "pelvic interior joints shift posteriorly: {hip}"
    );
    // Table 8.1 animal columns from the elbow/knee, without the humerus/femur row.
    let fore = &input.limbs[0].path;
    assert_table_fractions(
        &f,
        fore,
        &[
            "elbow_L",
            "wrist_L",
            "hand_L",
            "finger_01_L",
            "finger_02_L",
            "finger_03_L",
            "finger_end_L",
        ],
        &t.ratios["animal_forelimb"][1..],
    );
    let hind = &input.limbs[1].path;
    assert_table_fractions(
        &f,
        hind,
        &[
            "knee_L",
            "ankle_L",
            "foot_L",
            "toe_L",
            "toe_02_L",
            "toe_03_L",
            "toe_end_L",
        ],
        &t.ratios["animal_hind_limb"][1..],
    );
    // Root at the hindmost pair, tail behind it, head in front.
    let root = pos(&f, "pelvis");
    assert!((root.z + 0.35).abs() < 0.15, "{root}");
    assert!(pos(&f, "tail_base").z < root.z && pos(&f, "tail_end").z < -0.9);
    assert!(pos(&f, "head").z > pos(&f, "neck").z);
    // The trunk spine sits dorsally: above the path (y 0.85) by the template's dorsal offset
    // times the radius (0.2), tapering from full at the hips (z -0.35) to none at the
    // shoulders (z 0.45).
    assert!(t.axial.dorsal_offset > 0.0 && t.axial.dorsal_taper);
    for name in ["chest", "spine"] {
        let p = pos(&f, name);
        let share = ((0.45 - p.z) / 0.8).clamp(0.0, 1.0);
        let expected = 0.85 + share * t.axial.dorsal_offset * 0.2;
        assert!(
            (p.y - expected).abs() < 0.02,
            "{name} {p} expected y {expected}"
        );
    }
    // Scapulae hang from the trunk vertebra nearest them.
    let scapula = f.skeleton.find("scapula_L").unwrap();
    let parent = f.skeleton.joint(scapula).parent.unwrap();
    assert!(f.skeleton.joint(parent).name.starts_with("spine_"));
}

#[test]
fn a_missing_limb_gives_a_warning_and_a_skeleton_without_it() {
    let mut input = humanoid();
    input
        .limbs
        .retain(|l| !(l.kind == LimbKind::Arm && l.side == Side::Left));
    let f = run(&input, "humanoid");
    assert!(f.skeleton.validate().is_ok());
    assert!(f.warnings.contains(&FitWarning::MissingLimb {
        group: "arm".into(),
        side: Some(Side::Left),
    }));
    let text: Vec<String> = f.warnings.iter().map(|w| w.to_string()).collect();
    assert!(text.iter().any(|t| t.contains("left arm")), "{text:?}");
    assert!(f.skeleton.find("shoulder_L").is_none() && f.skeleton.find("clavicle_L").is_none());
    assert!(!f.canonical.contains_key("elbow_L"));
    assert!(f.canonical.contains_key("elbow_R"));
    // No legs at all: still a skeleton, warnings name both legs.
    input.limbs.retain(|l| l.kind != LimbKind::Leg);
    let f = run(&input, "humanoid");
    assert!(f.skeleton.validate().is_ok());
    assert!(f.warnings.contains(&FitWarning::MissingLimb {
        group: "leg".into(),
        side: None,
    }));
    // Nothing but the spine.
    input.limbs.clear();
    let f = run(&input, "quadruped");
    assert!(f.warnings.contains(&FitWarning::NoLimbs));
    assert!(f.canonical.contains_key("head") && f.canonical.contains_key("pelvis"));
}

#[test]
fn wrong_template_gives_warnings_not_panics() {
    let f = run(&quadruped(), "humanoid");
    assert!(f.skeleton.validate().is_ok());
    assert!(f
        .warnings
        .iter()
        .any(|w| matches!(w, FitWarning::KindMismatch { .. })));
    let f = run(&humanoid(), "quadruped");
    assert!(f.skeleton.validate().is_ok());
    assert!(f
        .warnings
        .iter()
        .any(|w| matches!(w, FitWarning::KindMismatch { .. })));
    let f = run(&humanoid(), "winged");
    assert!(f.skeleton.validate().is_ok());
    assert!(!f.warnings.is_empty());
}

#[test]
fn digits_follow_the_digit_ratios_with_the_thumb_nearest_the_centre() {
    let mut input = humanoid();
    for l in input.limbs.iter_mut().filter(|l| l.kind == LimbKind::Arm) {
        let s = l.side.sign();
        // The arm path ends at the wrist voxel; five digits spread in z, the thumb ahead and
        // closer to the body.
        l.path = dense(
            &[DVec3::new(0.0, 1.4, 0.0), DVec3::new(s * 0.72, 1.4, 0.0)],
            0.01,
        );
        l.radii = vec![0.04; l.path.len()];
        let wrist = DVec3::new(s * 0.72, 1.4, 0.0);
        l.digits = (0..5)
            .map(|k| {
                let z = 0.04 - 0.02 * k as f64;
                let tip = if k == 0 {
                    DVec3::new(s * 0.78, 1.4, 0.08)
                } else {
                    DVec3::new(s * 0.92, 1.4, z)
                };
                DigitInput {
                    path: dense(&[wrist, tip], 0.005),
                }
            })
            .collect();
        l.digits.rotate_left(2); // input order must not matter
    }
    let f = run(&input, "humanoid");
    assert!(f.skeleton.validate().is_ok());
    let thumb: Vec<&str> = f
        .skeleton
        .joints
        .iter()
        .map(|j| j.name.as_str())
        .filter(|n| n.starts_with("thumb_") && n.ends_with("_L"))
        .collect();
    assert_eq!(
        thumb,
        ["thumb_01_L", "thumb_02_L", "thumb_03_L", "thumb_end_L"]
    );
    assert!(named(&f, "thumb_end_L").z > 0.07);
    let index = [DVec3::new(0.72, 1.4, 0.0), named(&f, "index_end_L")];
    assert_table_fractions(
        &f,
        &index,
        &[
            "index_01_L",
            "index_02_L",
            "index_03_L",
            "index_04_L",
            "index_end_L",
        ],
        &[36.0, 25.0, 15.0, 10.0],
    );
    let thumb_path = [DVec3::new(0.72, 1.4, 0.0), DVec3::new(0.78, 1.4, 0.08)];
    assert_table_fractions(
        &f,
        &thumb_path,
        &["thumb_01_L", "thumb_02_L", "thumb_03_L", "thumb_end_L"],
        &[36.0, 25.0, 15.0],
    );
    // Two DOFs at the thumb's base, a hinge at the others.
    assert_eq!(
        f.skeleton
            .joint(f.skeleton.find("thumb_01_L").unwrap())
            .dofs
            .len(),
        2
    );
    assert_eq!(
        f.skeleton
            .joint(f.skeleton.find("ring_01_L").unwrap())
            .dofs
            .len(),
        1
    );
    // Digit bases hang from the wrist; no separate hand joint.
    let wrist = f.canonical["wrist_L"];
    assert_eq!(
        f.skeleton
            .joint(f.skeleton.find("index_01_L").unwrap())
            .parent,
        Some(wrist)
    );
    assert!(f.skeleton.find("hand_L").is_none());
}

#[test]
fn naming_presets_rename_and_stay_detectable() {
    let t = Template::builtin("humanoid").unwrap();
    for (preset, expected, detected) in [
        (Preset::Mixamo, "mixamorig:LeftArm", "mixamo"),
        (Preset::Unity, "LeftUpperArm", "unity_humanoid"),
        (Preset::MakeHuman, "upperarm_l", "makehuman_game_engine"),
        (Preset::Anatomical, "shoulder_L", "skelfit"),
    ] {
        let options = FitOptions {
            preset,
            ..Default::default()
        };
        let f = fit(&humanoid(), &t, &options).unwrap();
        assert_eq!(f.canonical_names()["shoulder_L"], expected);
        assert!(f.skeleton.validate().is_ok(), "{preset:?}");
        if preset != Preset::Anatomical {
            let (p, map) = detect_preset(&f.skeleton).unwrap();
            assert_eq!(p.preset, detected);
            assert_eq!(map["elbow_L"], f.canonical["elbow_L"]);
        }
    }
}

#[test]
fn jaw_wings_and_probe() {
    let mut input = quadruped();
    input.jaw = Some(vec![DVec3::new(0.0, 0.95, 1.0), DVec3::new(0.0, 0.9, 1.25)]);
    let f = run(&input, "quadruped");
    let jaw = f.skeleton.find("jaw").unwrap();
    assert_eq!(f.skeleton.joint(jaw).dofs.len(), 1);
    assert_eq!(
        f.skeleton.joint(f.skeleton.joint(jaw).parent.unwrap()).name,
        "head"
    );
    // The S-shaped neck: a deeper dorsal ray lifts the head/neck junction.
    let t = Template::builtin("quadruped").unwrap();
    let shallow = fit(&input, &t, &FitOptions::default()).unwrap();
    let probe = |_: DVec3, _: DVec3| Some(0.3);
    let deep = fit_with_probe(&input, &t, &FitOptions::default(), Some(&probe)).unwrap();
    assert!(pos(&deep, "head").y > pos(&shallow, "head").y + 0.05);
    // Wings: joints shifted towards the leading (anterior) edge.
    let mut bird = quadruped();
    for l in bird
        .limbs
        .iter_mut()
        .filter(|l| l.kind == LimbKind::ForeLeg)
    {
        l.kind = LimbKind::Wing;
        let s = l.side.sign();
        l.path = dense(&[l.attach, DVec3::new(s * 1.2, 0.85, 0.45)], 0.01);
        l.radii = vec![0.05; l.path.len()];
    }
    let f = run(&bird, "winged");
    assert!(f.skeleton.validate().is_ok());
    let elbow = named(&f, "wing_elbow_L");
    assert!((elbow.z - (0.45 + 0.8 * 0.05)).abs() < 1e-6, "{elbow}");
    assert!(!f
        .warnings
        .iter()
        .any(|w| matches!(w, FitWarning::MissingLimb { group, .. } if group == "wing")));
}

#[test]
fn bad_input_is_an_error_and_output_is_deterministic() {
    let t = Template::builtin("humanoid").unwrap();
    let mut input = humanoid();
    input.axial.points.truncate(1);
    input.axial.radii.truncate(1);
    assert!(matches!(
        fit(&input, &t, &FitOptions::default()),
        Err(FitError::ShortAxialPath { points: 1 })
    ));
    let mut input = humanoid();
    input.limbs[0].radii.pop();
    assert!(matches!(
        fit(&input, &t, &FitOptions::default()),
        Err(FitError::RadiiMismatch { .. })
    ));
    let mut input = humanoid();
    input.forward = DVec3::Y;
    assert!(matches!(
        fit(&input, &t, &FitOptions::default()),
        Err(FitError::BadOrientation { .. })
    ));
    let mut input = humanoid();
    input.axial.points[3].x = f64::NAN;
    assert!(matches!(
        fit(&input, &t, &FitOptions::default()),
        Err(FitError::NonFinite { .. })
    ));
    let a = run(&quadruped(), "quadruped");
    let b = run(&quadruped(), "quadruped");
    assert_eq!(a, b);
}

#[test]
fn given_sections_and_a_one_segment_manus() {
    let mut input = humanoid();
    // Head = first 20 cm, neck to 35 cm, trunk to the end.
    let n = input.axial.points.len();
    input.axial.sections = Some(skelfit::fit::AxialSections {
        head_end: 20,
        neck_end: 35,
        trunk_end: n - 1,
    });
    let text = skelfit::template::BUILTIN_TEMPLATES[0]
        .1
        .replace("manus = \"digit\"", "manus = \"segment\"");
    let t = Template::parse(&text, "segment.toml").unwrap();
    let options = FitOptions {
        snap_to_bend: None,
        ..Default::default()
    };
    let f = fit(&input, &t, &options).unwrap();
    assert!(
        (pos(&f, "head").y - 1.55).abs() < 0.01,
        "{}",
        pos(&f, "head")
    );
    // Everything distal to the metatarsal start is one segment: foot, then the tip.
    assert!(f.skeleton.find("foot_L").is_some() && f.skeleton.find("toe_end_L").is_some());
    assert!(f.skeleton.find("toe_02_L").is_none());
    let foot = f.skeleton.find("foot_L").unwrap();
    let end = f.skeleton.find("toe_end_L").unwrap();
    assert_eq!(f.skeleton.joint(end).parent, Some(foot));
    let leg = &input.limbs[1].path;
    let hip = arc(leg, pos(&f, "hip_L"));
    let r = &t.ratios["human_leg"];
    let total: f64 = r.iter().sum();
    let expected = hip + (length(leg) - hip) * (r[0] + r[1] + r[2]) / total;
    assert!((arc(leg, named(&f, "foot_L")) - expected).abs() < 0.01 * length(leg));
    assert!(f.warnings.contains(&FitWarning::MissingCanonical {
        key: "toe_L".into()
    }));
}

#[test]
fn two_unlabelled_leg_pairs_become_fore_and_hind() {
    let mut input = quadruped();
    for l in &mut input.limbs {
        l.kind = LimbKind::Leg;
        l.pair = usize::from(l.attach.z < 0.0);
    }
    let f = run(&input, "quadruped");
    assert!(f.warnings.is_empty(), "{:?}", f.warnings);
    assert!(pos(&f, "elbow_L").z > 0.0 && pos(&f, "knee_L").z < 0.0);
    assert!(f.skeleton.find("scapula_L").is_some());
}

#[test]
fn degenerate_geometry_never_panics() {
    for template in ["humanoid", "quadruped", "winged"] {
        // Every point of the spine in one place, limbs of zero length, one-point digits.
        let mut input = quadruped();
        let p = input.axial.points[0];
        input.axial.points.iter_mut().for_each(|q| *q = p);
        for l in &mut input.limbs {
            let a = l.path[0];
            l.path.iter_mut().for_each(|q| *q = a);
            l.digits = vec![DigitInput { path: vec![a] }, DigitInput { path: vec![] }];
        }
        input.jaw = Some(vec![p]);
        let f = run(&input, template);
        assert!(f.skeleton.validate().is_ok(), "{template}");
        assert!(!f.skeleton.is_empty());
        // Limbs of a single point, radii zero.
        let mut input = humanoid();
        input.axial.radii.iter_mut().for_each(|r| *r = 0.0);
        for l in &mut input.limbs {
            l.path.truncate(1);
            l.radii.truncate(1);
        }
        let f = run(&input, template);
        assert!(f.skeleton.validate().is_ok(), "{template}");
        assert!(f
            .warnings
            .iter()
            .any(|w| matches!(w, FitWarning::MissingLimb { side: Some(_), .. })));
    }
}

#[test]
fn fitted_skeleton_round_trips_through_json_with_its_canonical_map() {
    let t = Template::builtin("quadruped").unwrap();
    let options = FitOptions {
        preset: Preset::Mixamo,
        ..Default::default()
    };
    let f = fit(&quadruped(), &t, &options).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("fit.json");
    let json = skelfit::export::JsonOptions {
        canonical: f.canonical_names(),
        ..Default::default()
    };
    skelfit::export::write_skeleton_json(&path, &f.skeleton, &json).unwrap();
    let back = skelfit::eval::load_skeleton(&path).unwrap();
    assert_eq!(back.skeleton.len(), f.skeleton.len());
    for (key, id) in &f.canonical {
        assert_eq!(back.canonical[key], *id, "{key}");
    }
    // Mixamo's skeleton has no tail: the preset leaves the tail out instead of keeping it
    // under skelfit's names.
    assert!(!f.canonical.contains_key("tail_base"));
    assert!(f
        .skeleton
        .joints
        .iter()
        .all(|j| j.name.starts_with("mixamorig:")));
}

/// Oracle measurement (ignored; prints a table): FitInput built from the MakeHuman reference
/// joints (paths through them, radii from the mesh's distance map), so the errors measure only
/// the template rules of 8.1-8.2 (girdle sphere, Table 8.1, vertebrae), not labelling.
/// `SKELFIT_REFDATA=/work/shared/refdata cargo test --release --test it oracle -- --ignored --nocapture`
#[test]
#[ignore]
fn oracle_paths_on_makehuman() {
    use skelfit::distance::edt;
    use skelfit::voxel::{voxelize, VoxelOptions};
    let Some(root) = crate::common::refdata() else {
        return;
    };
    // The issue's 15-joint set (the joints refinement places).
    let set = skelfit::refine::REFINED_KEYS;
    let mut all = Vec::new();
    for model in [
        "mh_child_10y",
        "mh_female_thin_short",
        "mh_female_young_average",
        "mh_male_heavy_short",
        "mh_male_young_average",
        "mh_neutral_default",
    ] {
        let dir = root.join("humanoid").join(model);
        let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).unwrap();
        let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
        let dist = edt(&solid);
        let radius = |p: DVec3| {
            dist.grid.voxel_at(p).map_or(0.0, |c| {
                dist.distance(dist.grid.index(c)) * dist.grid.voxel_size
            })
        };
        let rig = skelfit::eval::load_skeleton(&dir.join("rig_game_engine.json")).unwrap();
        let j = |n: &str| rig.skeleton.joint(rig.skeleton.find(n).unwrap()).position;
        let top = mesh
            .positions
            .iter()
            .copied()
            .max_by(|a, b| a.y.total_cmp(&b.y))
            .unwrap();
        let crotch = (j("thigh_l") + j("thigh_r")) * 0.5;
        let axial = dense(
            &[
                DVec3::new(0.0, top.y, j("head").z),
                j("head"),
                j("neck_01"),
                j("spine_03"),
                j("spine_02"),
                j("spine_01"),
                j("pelvis"),
                crotch,
            ],
            0.005,
        );
        let radii = axial.iter().map(|p| radius(*p)).collect();
        let mut limbs = Vec::new();
        for (side, s) in [(Side::Left, "l"), (Side::Right, "r")] {
            let attach = (j("upperarm_l") + j("upperarm_r")) * 0.5;
            let m3 = j(&format!("middle_03_{s}"));
            let tip = m3 + (m3 - j(&format!("middle_02_{s}")));
            let path = dense(
                &[
                    attach,
                    j(&format!("upperarm_{s}")),
                    j(&format!("lowerarm_{s}")),
                    j(&format!("hand_{s}")),
                    j(&format!("middle_01_{s}")),
                    j(&format!("middle_02_{s}")),
                    m3,
                    tip,
                ],
                0.005,
            );
            let r = path.iter().map(|p| radius(*p)).collect();
            limbs.push(LimbInput {
                kind: LimbKind::Arm,
                side,
                pair: 0,
                attach,
                path,
                radii: r,
                digits: Vec::new(),
                root: None,
            });
            let ball = j(&format!("ball_{s}"));
            let toe = mesh
                .positions
                .iter()
                .copied()
                .filter(|v| (v.x - ball.x).abs() < 0.05 && v.y < 0.04)
                .max_by(|a, b| a.z.total_cmp(&b.z))
                .unwrap();
            let path = dense(
                &[
                    crotch,
                    j(&format!("thigh_{s}")),
                    j(&format!("calf_{s}")),
                    j(&format!("foot_{s}")),
                    ball,
                    toe,
                ],
                0.005,
            );
            let r = path.iter().map(|p| radius(*p)).collect();
            limbs.push(LimbInput {
                kind: LimbKind::Leg,
                side,
                pair: 0,
                attach: crotch,
                path,
                radii: r,
                digits: Vec::new(),
                root: None,
            });
        }
        let input = FitInput {
            up: DVec3::Y,
            forward: DVec3::Z,
            axial: AxialPath {
                points: axial,
                radii,
                sections: None,
                tail: false,
            },
            limbs,
            jaw: None,
            ears: Vec::new(),
        };
        let f = run(&input, "humanoid");
        let mut line = format!("{model:26}");
        let mut errors = Vec::new();
        for key in set {
            let e = pos(&f, key).distance(rig.skeleton.joint(rig.canonical[key]).position) * 1000.0;
            errors.push(e);
            line += &format!(
                " {}={e:.0}",
                key.trim_end_matches("_L").trim_end_matches("_R")
            );
        }
        let mean = errors.iter().sum::<f64>() / errors.len() as f64;
        println!("{line}  mean {mean:.1} mm");
        all.extend(errors);
    }
    println!(
        "overall mean {:.1} mm",
        all.iter().sum::<f64>() / all.len() as f64
    );
}

#[test]
fn neck_starts_at_the_front_girdle_edge_or_at_the_pair() {
    let t = Template::builtin("humanoid").unwrap();
    let input = humanoid();
    // Default: one girdle radius (0.13) above the arm pair at y = 1.4.
    let edge = fit(&input, &t, &FitOptions::default()).unwrap();
    assert!(
        (pos(&edge, "neck").y - 1.53).abs() < 0.02,
        "{}",
        pos(&edge, "neck")
    );
    // 0: dissertation 8.1, the trunk ends at the point nearest the pair's midpoint.
    let options = FitOptions {
        neck_at_girdle_edge: 0.0,
        ..Default::default()
    };
    let pair = fit(&input, &t, &options).unwrap();
    assert!(
        (pos(&pair, "neck").y - 1.4).abs() < 0.02,
        "{}",
        pos(&pair, "neck")
    );
    assert!(pos(&pair, "head").y < pos(&edge, "head").y);
}

/// Oracle measurement on the Khronos fox (ignored; prints errors in % of body length): paths
/// through the reference joints, radii from the mesh's distance map.
/// `SKELFIT_REFDATA=/work/shared/refdata cargo test --release --test it oracle -- --ignored --nocapture`
#[test]
#[ignore]
fn oracle_paths_on_the_fox() {
    use skelfit::distance::edt;
    use skelfit::voxel::{voxelize, VoxelOptions};
    let Some(dir) = crate::common::model("quadruped/khronos_fox") else {
        return;
    };
    let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).unwrap();
    let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
    let dist = edt(&solid);
    let radius = |p: DVec3| {
        dist.grid.voxel_at(p).map_or(0.0, |c| {
            dist.distance(dist.grid.index(c)) * dist.grid.voxel_size
        })
    };
    let rig = skelfit::eval::load_skeleton(&dir.join("rig_gltf.json")).unwrap();
    let key = |k: &str| rig.skeleton.joint(rig.canonical[k]).position;
    let (zmin, zmax) = mesh
        .positions
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.z), b.max(p.z))
        });
    let nose = mesh
        .positions
        .iter()
        .copied()
        .max_by(|a, b| a.z.total_cmp(&b.z))
        .unwrap();
    let tail_tip = mesh
        .positions
        .iter()
        .copied()
        .min_by(|a, b| a.z.total_cmp(&b.z))
        .unwrap();
    let axial = dense(
        &[
            nose,
            key("head"),
            key("neck"),
            key("chest"),
            key("spine"),
            key("pelvis"),
            key("tail_base"),
            key("tail_mid"),
            key("tail_end"),
            tail_tip,
        ],
        0.005,
    );
    let radii = axial.iter().map(|p| radius(*p)).collect();
    let mut limbs = Vec::new();
    for (side, s) in [(Side::Left, "L"), (Side::Right, "R")] {
        for (kind, a, b, c, d) in [
            (LimbKind::ForeLeg, "shoulder", "elbow", "wrist", None),
            (LimbKind::HindLeg, "hip", "knee", "ankle", Some("toe")),
        ] {
            let attach = (key(&format!("{a}_L")) + key(&format!("{a}_R"))) * 0.5;
            let mut corners = vec![
                attach,
                key(&format!("{a}_{s}")),
                key(&format!("{b}_{s}")),
                key(&format!("{c}_{s}")),
            ];
            if let Some(d) = d {
                corners.push(key(&format!("{d}_{s}")));
            }
            let last = *corners.last().unwrap();
            corners.push(DVec3::new(last.x, 0.0, last.z + 0.03));
            let path = dense(&corners, 0.005);
            let r = path.iter().map(|p| radius(*p)).collect();
            limbs.push(LimbInput {
                kind,
                side,
                pair: 0,
                attach,
                path,
                radii: r,
                digits: Vec::new(),
                root: None,
            });
        }
    }
    let input = FitInput {
        up: DVec3::Y,
        forward: DVec3::Z,
        axial: AxialPath {
            points: axial,
            radii,
            sections: None,
            tail: false,
        },
        limbs,
        jaw: None,
        ears: Vec::new(),
    };
    let f = run(&input, "quadruped");
    let length = zmax - zmin;
    let mut errors = Vec::new();
    let mut line = String::new();
    for (k, id) in &rig.canonical {
        if let Some(mine) = f.canonical.get(k) {
            let e = f
                .skeleton
                .joint(*mine)
                .position
                .distance(rig.skeleton.joint(*id).position);
            errors.push(e / length * 100.0);
            line += &format!(" {k}={:.1}%", e / length * 100.0);
        }
    }
    println!("fox:{line}");
    println!(
        "fox mean {:.1}% of body length {length:.3}, warnings {:?}",
        errors.iter().sum::<f64>() / errors.len() as f64,
        f.warnings
    );
}

#[test]
fn inner_limb_joints_snap_to_a_nearby_bend_of_the_path() {
    // A humanoid leg whose knee corner lies 10 % of the leg's length below where Table 8.1
    // puts the knee: the default fit moves the knee onto the corner, `snap_to_bend: None`
    // keeps the table's place.
    let t = Template::builtin("humanoid").unwrap();
    let mut input = humanoid();
    let leg = &input.limbs[1].path;
    let total = length(leg);
    let table = named(&run(&input, "humanoid"), "knee_L");
    let s_table = arc(leg, table);
    let corner_s = s_table + 0.1 * total;
    // Rebuild the left leg as two straight pieces meeting at `corner_s`, bent by 40 degrees.
    let start = leg[0];
    let dir = (leg[leg.len() - 1] - start).normalize();
    let corner = start + dir * corner_s;
    let bent = (dir + DVec3::Z * 0.8).normalize();
    let end = corner + bent * (total - corner_s);
    let new_leg = dense(&[start, corner, end], 0.005);
    let limb = &mut input.limbs[1];
    limb.radii = vec![0.05; new_leg.len()];
    limb.path = new_leg.clone();
    let snapped = fit(&input, &t, &FitOptions::default()).unwrap();
    let plain = run(&input, "humanoid");
    let d_snapped = named(&snapped, "knee_L").distance(corner);
    let d_plain = named(&plain, "knee_L").distance(corner);
    assert!(d_snapped < 0.02, "snapped knee {d_snapped} from the corner");
    assert!(d_plain > 0.05, "table knee {d_plain} from the corner");
}

/// The quadruped's trunk spine is dorsal at the hips and centred at the shoulders (the
/// template's `dorsal_taper`); without the taper it is dorsal all along, and the templates of
/// upright and winged figures keep the even offset.
#[test]
fn quadruped_spine_sinks_from_the_hips_to_the_shoulders() {
    let input = quadruped();
    let tapered = Template::builtin("quadruped").unwrap();
    assert!(tapered.axial.dorsal_taper);
    let mut even = tapered.clone();
    even.axial.dorsal_taper = false;
    let a = fit(&input, &tapered, &FitOptions::default()).unwrap();
    let b = fit(&input, &even, &FitOptions::default()).unwrap();
    let full = tapered.axial.dorsal_offset * 0.2;
    // The trunk joint nearest the shoulders (z 0.45): near the path (y 0.85) when tapered,
    // a full offset above it when not.
    let front = |f: &Fit| {
        f.skeleton
            .joints
            .iter()
            .filter(|j| j.name.starts_with("spine_"))
            .max_by(|p, q| p.position.z.total_cmp(&q.position.z))
            .unwrap()
            .position
    };
    let (pa, pb) = (front(&a), front(&b));
    assert!((pb.y - (0.85 + full)).abs() < 0.02, "{pb}");
    let share = ((0.45 - pa.z) / 0.8).clamp(0.0, 1.0);
    assert!(share < 0.5, "{pa}");
    assert!(pa.y < pb.y - 0.5 * full, "tapered {pa} even {pb}");
    // At the hips the offset is the same either way.
    let (ra, rb) = (pos(&a, "pelvis"), pos(&b, "pelvis"));
    assert!((ra - rb).length() < 0.01, "{ra} {rb}");
    for name in ["humanoid", "winged"] {
        assert!(
            !Template::builtin(name).unwrap().axial.dorsal_taper,
            "{name}"
        );
    }
}

/// An animal-like hip pivots on the trunk's centre line (the acetabulum lies ventral to the
/// sacrum), so it stays put when the template moves the spine dorsally; the spine does move.
#[test]
fn quadruped_hips_do_not_rise_with_the_dorsal_offset() {
    let input = quadruped();
    let dorsal = Template::builtin("quadruped").unwrap();
    assert!(dorsal.axial.dorsal_offset > 0.0);
    let mut centred = dorsal.clone();
    centred.axial.dorsal_offset = 0.0;
    let a = fit(&input, &dorsal, &FitOptions::default()).unwrap();
    let b = fit(&input, &centred, &FitOptions::default()).unwrap();
    let (pa, pb) = (pos(&a, "spine"), pos(&b, "spine"));
    assert!(pa.y > pb.y + 0.01, "spine {pa} vs {pb}");
    for hip in ["hip_L", "hip_R"] {
        let (ha, hb) = (pos(&a, hip), pos(&b, hip));
        assert!((ha - hb).length() < 1e-6, "{hip} {ha} vs {hb}");
    }
}

//! Unit tests of the eval stage against analytic skeletons and brute force.

use super::*;
use crate::skeleton::{Canonical, Joint, JointId, Side, Skeleton};
use glam::DVec3;
use std::path::Path;

fn joint(name: &str, parent: Option<usize>, p: [f64; 3]) -> Joint {
    Joint {
        name: name.into(),
        parent: parent.map(JointId),
        position: DVec3::from_array(p),
        deform: true,
        ..Default::default()
    }
}

/// A stick humanoid with skelfit anatomical names, 1.8 units tall.
fn stick_figure() -> Skeleton {
    Skeleton {
        joints: vec![
            joint(Canonical::Pelvis.as_str(), None, [0.0, 1.0, 0.0]),
            joint(Canonical::Chest.as_str(), Some(0), [0.0, 1.3, 0.0]),
            joint(Canonical::Neck.as_str(), Some(1), [0.0, 1.5, 0.0]),
            joint(Canonical::Head.as_str(), Some(2), [0.0, 1.8, 0.0]),
            joint(
                Canonical::Shoulder(Side::Left).as_str(),
                Some(1),
                [0.2, 1.45, 0.0],
            ),
            joint(
                Canonical::Elbow(Side::Left).as_str(),
                Some(4),
                [0.45, 1.2, 0.0],
            ),
            joint(
                Canonical::Shoulder(Side::Right).as_str(),
                Some(1),
                [-0.2, 1.45, 0.0],
            ),
            joint(
                Canonical::Elbow(Side::Right).as_str(),
                Some(6),
                [-0.45, 1.2, 0.0],
            ),
            joint(
                Canonical::Hip(Side::Left).as_str(),
                Some(0),
                [0.1, 0.95, 0.0],
            ),
            joint(
                Canonical::Knee(Side::Left).as_str(),
                Some(8),
                [0.1, 0.5, 0.0],
            ),
            joint(
                Canonical::Ankle(Side::Left).as_str(),
                Some(9),
                [0.1, 0.0, 0.0],
            ),
            joint(
                Canonical::Hip(Side::Right).as_str(),
                Some(0),
                [-0.1, 0.95, 0.0],
            ),
            joint(
                Canonical::Knee(Side::Right).as_str(),
                Some(11),
                [-0.1, 0.5, 0.0],
            ),
            joint(
                Canonical::Ankle(Side::Right).as_str(),
                Some(12),
                [-0.1, 0.0, 0.0],
            ),
        ],
    }
}

fn rig(skeleton: Skeleton) -> ReferenceRig {
    ReferenceRig::from_skeleton("stick", skeleton)
}

fn translated(skeleton: &Skeleton, by: DVec3) -> Skeleton {
    let mut s = skeleton.clone();
    for j in &mut s.joints {
        j.position += by;
    }
    s
}

#[test]
fn identical_skeletons_give_zero_error() {
    let s = stick_figure();
    let e = evaluate(&rig(s.clone()), &rig(s), None, &EvalOptions::default()).unwrap();
    assert_eq!(e.joints.len(), 14);
    assert_eq!(e.method, MatchMethod::Canonical);
    assert_eq!(e.summary, ErrorSummary::from_values(&[0.0; 14]));
    assert_eq!(e.summary.max, 0.0);
    assert_eq!((e.chamfer.j2j, e.chamfer.j2b), (0.0, 0.0));
    assert!(e.chamfer.b2b < 1e-12, "{}", e.chamfer.b2b); // rounding of bone samples only
    assert!(e.warnings.is_empty(), "{:?}", e.warnings);
    assert!(e.unmatched.is_empty());
}

#[test]
fn known_offset_gives_exactly_that_error() {
    let s = stick_figure();
    let offset = DVec3::new(0.03, 0.0, 0.04); // |offset| = 0.05 exactly in decimal terms
    let e = evaluate(
        &rig(translated(&s, offset)),
        &rig(s),
        None,
        &EvalOptions::default(),
    )
    .unwrap();
    for j in &e.joints {
        assert!((j.error - 0.05).abs() < 1e-12, "{}: {}", j.key, j.error);
        assert!((j.offset - offset).length() < 1e-12);
    }
    for v in [
        e.summary.mean,
        e.summary.median,
        e.summary.max,
        e.summary.rms,
    ] {
        assert!((v - 0.05).abs() < 1e-12, "{v}");
    }
    // Upright figure: size = height of the joints' bounding box = 1.8.
    assert_eq!(e.figure.measure, FigureMeasure::Height);
    assert!((e.figure.size - 1.8).abs() < 1e-12);
    assert!((e.summary_percent.mean - 100.0 * 0.05 / 1.8).abs() < 1e-9);
    // Every joint's nearest neighbour is its own copy, so J2J equals the offset too.
    assert!((e.chamfer.j2j - 0.05).abs() < 1e-12);
}

#[test]
fn single_joint_offset_changes_only_that_joint() {
    let s = stick_figure();
    let mut p = s.clone();
    p.joints[5].position.y -= 0.1;
    let e = evaluate(&rig(p), &rig(s), None, &EvalOptions::default()).unwrap();
    assert_eq!(e.worst_joint, Canonical::Elbow(Side::Left).as_str());
    assert!((e.summary.max - 0.1).abs() < 1e-12);
    assert!((e.summary.mean - 0.1 / 14.0).abs() < 1e-12);
    assert!((e.summary.rms - (0.01f64 / 14.0).sqrt()).abs() < 1e-12);
    assert_eq!(e.summary.median, 0.0);
}

#[test]
fn summary_statistics() {
    let s = ErrorSummary::from_values(&[3.0, 1.0, 4.0, 2.0]);
    assert_eq!(s.count, 4);
    assert_eq!(s.mean, 2.5);
    assert_eq!(s.median, 2.5);
    assert_eq!(s.max, 4.0);
    assert!((s.rms - (30.0f64 / 4.0).sqrt()).abs() < 1e-12);
    assert_eq!(ErrorSummary::from_values(&[]), ErrorSummary::default());
}

/// Deterministic pseudo-random numbers in [0, 1) (64-bit LCG, Knuth's constants).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn skeleton(&mut self, n: usize) -> Skeleton {
        let joints = (0..n)
            .map(|i| {
                let parent = (i > 0).then(|| (self.next() * i as f64) as usize);
                joint(
                    &format!("j{i}"),
                    parent,
                    [self.next(), self.next() * 2.0, self.next()],
                )
            })
            .collect();
        Skeleton { joints }
    }
}

fn brute_point_chamfer(a: &[DVec3], b: &[DVec3]) -> f64 {
    let one_way = |from: &[DVec3], to: &[DVec3]| {
        let mut total = 0.0;
        for p in from {
            let mut best = f64::INFINITY;
            for q in to {
                best = best.min((*p - *q).length());
            }
            total += best;
        }
        total / from.len() as f64
    };
    0.5 * (one_way(a, b) + one_way(b, a))
}

fn dense_bone_points(s: &Skeleton, step: f64) -> Vec<DVec3> {
    let mut points = Vec::new();
    for j in &s.joints {
        if let Some(p) = j.parent {
            let a = s.joints[p.0].position;
            let n = ((a - j.position).length() / step).ceil().max(1.0) as usize;
            for i in 0..=n {
                points.push(a + (j.position - a) * (i as f64 / n as f64));
            }
        }
    }
    points
}

#[test]
fn chamfer_matches_brute_force() {
    let mut rng = Lcg(7);
    for _ in 0..3 {
        let a = rng.skeleton(12);
        let b = rng.skeleton(9);
        let options = ChamferOptions {
            bone_sample_spacing: 0.01,
        };
        let c = chamfer(&a, &b, &options);
        let ja: Vec<DVec3> = a.joints.iter().map(|j| j.position).collect();
        let jb: Vec<DVec3> = b.joints.iter().map(|j| j.position).collect();
        // J2J is exact.
        assert!((c.j2j - brute_point_chamfer(&ja, &jb)).abs() < 1e-12);
        // J2B and B2B against densely sampled bones (error bounded by half the step).
        let step = 2e-3;
        let da = dense_bone_points(&a, step);
        let db = dense_bone_points(&b, step);
        let nearest_mean = |from: &[DVec3], to: &[DVec3]| {
            from.iter()
                .map(|p| {
                    to.iter()
                        .map(|q| (*p - *q).length())
                        .fold(f64::INFINITY, f64::min)
                })
                .sum::<f64>()
                / from.len() as f64
        };
        let j2b = 0.5 * (nearest_mean(&ja, &db) + nearest_mean(&jb, &da));
        assert!((c.j2b - j2b).abs() < step, "j2b {} vs {j2b}", c.j2b);
        let b2b = brute_point_chamfer(&da, &db);
        // B2B samples the source bones at 0.01 and measures to exact segments: agrees with
        // the dense point version to within the coarser spacing.
        assert!((c.b2b - b2b).abs() < 0.01, "b2b {} vs {b2b}", c.b2b);
        // Symmetric.
        let d = chamfer(&b, &a, &options);
        assert!((c.j2j - d.j2j).abs() < 1e-12 && (c.j2b - d.j2b).abs() < 1e-12);
        assert!((c.b2b - d.b2b).abs() < 1e-12);
    }
}

#[test]
fn point_segment_distance_cases() {
    let (a, b) = (DVec3::ZERO, DVec3::X);
    assert_eq!(point_segment_distance(DVec3::new(0.5, 2.0, 0.0), a, b), 2.0);
    assert_eq!(
        point_segment_distance(DVec3::new(-3.0, 4.0, 0.0), a, b),
        5.0
    );
    assert_eq!(point_segment_distance(DVec3::new(4.0, 0.0, 0.0), a, b), 3.0);
    assert_eq!(point_segment_distance(DVec3::Y, a, a), 1.0);
}

#[test]
fn no_shared_joints_lists_both_name_sets() {
    let a = Skeleton {
        joints: vec![
            joint("Body", None, [0.0; 3]),
            joint("Tail1", Some(0), [0.0, 0.0, -1.0]),
        ],
    };
    let b = Skeleton {
        joints: vec![
            joint("Root", None, [0.0; 3]),
            joint("Wing", Some(0), [1.0, 0.0, 0.0]),
        ],
    };
    let err = evaluate(&rig(a), &rig(b), None, &EvalOptions::default()).unwrap_err();
    let message = err.to_string();
    assert!(matches!(err, EvalError::NoSharedJoints { .. }));
    for name in ["Body", "Tail1", "Root", "Wing"] {
        assert!(message.contains(name), "{message}");
    }
}

#[test]
fn falls_back_to_identical_names() {
    let a = Skeleton {
        joints: vec![
            joint("Body", None, [0.0; 3]),
            joint("Tail1", Some(0), [0.0, 0.0, -1.0]),
        ],
    };
    let e = evaluate(&rig(a.clone()), &rig(a), None, &EvalOptions::default()).unwrap();
    assert_eq!(e.method, MatchMethod::Name);
    assert_eq!(e.joints.len(), 2);
    assert_eq!(e.figure.measure, FigureMeasure::LongestSide);
}

#[test]
fn unit_mismatch_warns() {
    let s = stick_figure();
    let mut cm = s.clone();
    for j in &mut cm.joints {
        j.position *= 100.0;
    }
    let e = evaluate(&rig(cm), &rig(s.clone()), None, &EvalOptions::default()).unwrap();
    assert_eq!(e.warnings.len(), 1, "{:?}", e.warnings);
    assert!(
        e.warnings[0].message.contains("100.0x"),
        "{}",
        e.warnings[0]
    );
    assert_eq!(e.warnings[0].code, "unit_mismatch");
    // A mesh in other units than the reference is flagged too.
    let mesh = crate::mesh::Mesh::cuboid(DVec3::ZERO, DVec3::splat(180.0));
    let e = evaluate(
        &rig(s.clone()),
        &rig(s),
        Some(&mesh),
        &EvalOptions::default(),
    )
    .unwrap();
    assert_eq!(e.figure.source, SizeSource::Mesh);
    assert!((e.figure.size - 180.0).abs() < 1e-12);
    assert_eq!(e.warnings.len(), 1, "{:?}", e.warnings);
}

#[test]
fn deforming_filter_reparents() {
    let mut s = stick_figure();
    s.joints.insert(0, joint("Root", None, [0.0; 3]));
    s.joints[0].deform = false;
    for j in s.joints.iter_mut().skip(1) {
        j.parent = Some(j.parent.map_or(JointId(0), |p| JointId(p.0 + 1)));
    }
    let mut r = rig(s);
    r.canonical.insert("root_control".into(), JointId(0));
    r.canonical
        .insert(Canonical::Head.as_str().into(), JointId(4));
    let d = r.deforming();
    assert_eq!(d.skeleton, stick_figure());
    assert_eq!(d.canonical.len(), 1);
    assert_eq!(
        d.canonical_joint(Canonical::Head.as_str()).unwrap().name,
        Canonical::Head.as_str()
    );
}

const BVH: &str = "HIERARCHY
ROOT Hips
{
  OFFSET 0.0 90.0 0.0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT LeftUpLeg
  {
    OFFSET 10.0 -5.0 0.0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT LeftLeg
    {
      OFFSET 0.0 -40.0 0.0
      CHANNELS 3 Zrotation Xrotation Yrotation
      End Site
      {
        OFFSET 0.0 -40.0 5.0
      }
    }
  }
  JOINT Spine
  {
    OFFSET 0.0 10.0 0.0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT Head
    {
      OFFSET 0.0 60.0 0.0
      CHANNELS 3 Zrotation Xrotation Yrotation
      End Site
      {
        OFFSET 0.0 20.0 0.0
      }
    }
  }
}
MOTION
Frames: 1
Frame Time: 0.033333
0 90 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0
";

#[test]
fn bvh_rest_pose() {
    let r = parse_bvh(BVH, Path::new("walk.bvh")).unwrap();
    let names: Vec<&str> = r.skeleton.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "Hips",
            "LeftUpLeg",
            "LeftLeg",
            "LeftLeg_end",
            "Spine",
            "Head",
            "Head_end"
        ]
    );
    let at = |n: &str| r.skeleton.joint(r.skeleton.find(n).unwrap()).position;
    assert_eq!(at("Hips"), DVec3::new(0.0, 90.0, 0.0));
    assert_eq!(at("LeftLeg"), DVec3::new(10.0, 45.0, 0.0));
    assert_eq!(at("LeftLeg_end"), DVec3::new(10.0, 5.0, 5.0));
    assert_eq!(at("Head_end"), DVec3::new(0.0, 180.0, 0.0));
    let end = r.skeleton.joint(r.skeleton.find("Head_end").unwrap());
    assert!(!end.deform);
    assert_eq!(end.parent, r.skeleton.find("Head"));
    assert_eq!(r.skeleton.joints[4].parent, Some(JointId(0)));
    assert_eq!(r.model, "walk");
    assert_eq!(r.format, RigFormat::Bvh);
    // End sites drop out when filtering to deforming joints.
    assert_eq!(r.deforming().skeleton.joints.len(), 5);
}

#[test]
fn bvh_errors_name_the_line() {
    let broken = BVH.replace("OFFSET 0.0 -40.0 0.0", "OFFSET 0.0 oops 0.0");
    let message = parse_bvh(&broken, Path::new("x.bvh"))
        .unwrap_err()
        .to_string();
    assert!(message.contains("line 12"), "{message}");
    let truncated = &BVH[..BVH.find("MOTION").unwrap() - 3];
    assert!(parse_bvh(truncated, Path::new("x.bvh")).is_err());
    assert!(parse_bvh("HIERARCHY\nMOTION\n", Path::new("x.bvh")).is_err());
    assert!(parse_bvh("", Path::new("x.bvh")).is_err());
}

#[test]
fn skelfit_json_with_names_and_indices() {
    let (pelvis, spine) = (Canonical::Pelvis.as_str(), Canonical::Spine.as_str());
    let text = serde_json::json!({"joints": [
        {"name": pelvis, "parent": null, "position": [0, 1, 0]},
        {"name": "spine_01", "parent": pelvis, "position": [0, 1.2, 0]},
        {"name": "tip", "parent": 1, "position": [0, 1.4, 0], "deform": false}],
        "canonical": {pelvis: pelvis, spine: "spine_01"}})
    .to_string();
    let r = parse_json_rig(&text, Path::new("out/fit.json")).unwrap();
    assert_eq!(r.format, RigFormat::Skelfit);
    assert_eq!(r.model, "fit");
    assert_eq!(r.skeleton.joints[2].parent, Some(JointId(1)));
    assert!(!r.skeleton.joints[2].deform);
    assert_eq!(
        r.canonical_joint(Canonical::Spine.as_str()).unwrap().name,
        "spine_01"
    );
}

#[test]
fn invalid_json_skeletons_are_errors() {
    let head_to_nothing = serde_json::json!({
        "joints": [{"name": "a", "position": [0, 0, 0]}],
        "canonical": {Canonical::Head.as_str(): "zz"}
    })
    .to_string();
    let cases = [
        (
            r#"{"joints": [{"name": "a", "parent": "b", "position": [0,0,0]}, {"name": "b", "position": [0,0,0]}]}"#,
            "before",
        ),
        (
            r#"{"joints": [{"name": "a", "position": [0,0,0]}, {"name": "a", "position": [0,0,0]}]}"#,
            "twice",
        ),
        (
            r#"{"joints": [{"name": "a", "parent": 0, "position": [0,0,0]}]}"#,
            "parents must come before",
        ),
        (head_to_nothing.as_str(), "does not exist"),
        (r#"{"format": "other-v2", "joints": []}"#, "other-v2"),
        (r#"{"joints": "#, "not a valid json"),
    ];
    for (text, expected) in cases {
        let message = parse_json_rig(text, Path::new("bad.json"))
            .unwrap_err()
            .to_string();
        assert!(
            message.contains(expected),
            "{message} should mention {expected}"
        );
    }
}

#[test]
fn missing_file_and_unknown_extension() {
    let err = load_skeleton(Path::new("/nonexistent/rig.json")).unwrap_err();
    assert!(matches!(err, EvalError::Io { .. }));
    assert!(err.to_string().contains("/nonexistent/rig.json"));
    let err = load_skeleton(Path::new("rig.fbx")).unwrap_err();
    assert!(matches!(err, EvalError::UnknownFormat { .. }), "{err}");
}

#[test]
fn bundled_presets_are_valid() {
    let presets = parse_presets().unwrap();
    assert_eq!(presets.len(), 5);
    for p in &presets {
        assert!(
            p.joints.contains_key(Canonical::Pelvis.as_str()),
            "{}",
            p.preset
        );
        assert!(p.joints.keys().all(|k| is_canonical_key(k)));
    }
    assert_eq!(
        preset("mixamo").unwrap().joints[Canonical::Shoulder(Side::Left).as_str()][0],
        "mixamorig:LeftArm"
    );
    assert_eq!(
        preset("unity_humanoid").unwrap().joints[Canonical::Shoulder(Side::Left).as_str()],
        ["LeftUpperArm"]
    );
    assert_eq!(
        preset("makehuman_game_engine").unwrap().joints[Canonical::Shoulder(Side::Left).as_str()],
        ["upperarm_l"]
    );
}

fn named(names: &[&str]) -> Skeleton {
    Skeleton {
        joints: names
            .iter()
            .enumerate()
            .map(|(i, n)| joint(n, i.checked_sub(1), [0.0, i as f64, 0.0]))
            .collect(),
    }
}

#[test]
fn presets_are_detected() {
    let mixamo = named(&[
        "mixamorig:Hips",
        "mixamorig:Spine",
        "mixamorig:Spine1",
        "mixamorig:LeftArm",
    ]);
    let (p, map) = detect_preset(&mixamo).unwrap();
    assert_eq!(p.preset, "mixamo");
    assert_eq!(map[Canonical::Shoulder(Side::Left).as_str()], JointId(3));
    // Without the namespace (e.g. a Mixamo BVH) it is still Mixamo (Spine2 = chest) ...
    let bare = named(&["Hips", "Spine", "Spine1", "Spine2", "LeftArm"]);
    assert_eq!(detect_preset(&bare).unwrap().0.preset, "mixamo");
    // ... but a CMU skeleton (LowerBack, Spine, Spine1: Spine1 = chest) is CMU.
    let cmu = named(&["Hips", "LowerBack", "Spine", "Spine1", "Neck", "LeftArm"]);
    let (p, map) = detect_preset(&cmu).unwrap();
    assert_eq!(p.preset, "cmu");
    assert_eq!(map[Canonical::Chest.as_str()], JointId(3));
    // Other namespaces match loosely.
    let other = named(&["mixamorig1:Hips", "mixamorig1:Spine1", "mixamorig1:Spine2"]);
    assert_eq!(detect_preset(&other).unwrap().0.preset, "mixamo");
    let unity = named(&["Hips", "Spine", "Chest", "LeftUpperArm", "LeftLowerArm"]);
    let (p, map) = detect_preset(&unity).unwrap();
    assert_eq!(p.preset, "unity_humanoid");
    assert_eq!(map[Canonical::Elbow(Side::Left).as_str()], JointId(4));
    let game = named(&[
        Canonical::Pelvis.as_str(),
        "spine_01",
        "spine_02",
        "spine_03",
        "upperarm_l",
        "lowerarm_l",
    ]);
    assert_eq!(
        detect_preset(&game).unwrap().0.preset,
        "makehuman_game_engine"
    );
    assert!(detect_preset(&named(&["Body", "Tail"])).is_none());
    // Two rigs in different conventions pair through canonical keys.
    let c = correspond(&rig(mixamo), &rig(unity)).unwrap();
    assert_eq!(c.method, MatchMethod::Canonical);
    let keys: Vec<&str> = c.pairs.iter().map(|p| p.key.as_str()).collect();
    assert_eq!(
        keys,
        [
            Canonical::Pelvis.as_str(),
            Canonical::Spine.as_str(),
            Canonical::Shoulder(Side::Left).as_str()
        ]
    );
    assert_eq!(
        c.reference_naming,
        CanonicalSource::Preset("unity_humanoid".into())
    );
}

#[test]
fn csv_and_json_round_trip() {
    let s = stick_figure();
    let e = evaluate(
        &rig(translated(&s, DVec3::new(0.0, 0.01, 0.0))),
        &rig(s),
        None,
        &EvalOptions::default(),
    )
    .unwrap();
    let rows = joint_rows(&e);
    let mut bytes = Vec::new();
    write_csv(&rows, &mut bytes).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    assert!(text.starts_with("model,key,predicted_joint,reference_joint,error,error_percent"));
    let back: Vec<JointRow> = csv::Reader::from_reader(text.as_bytes())
        .deserialize()
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(back, rows);
    let models = vec![model_row(&e)];
    let mut bytes = Vec::new();
    write_csv(&models, &mut bytes).unwrap();
    let back: Vec<ModelRow> = csv::Reader::from_reader(bytes.as_slice())
        .deserialize()
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(back, models);
    let json = to_json(&e).unwrap();
    let back: Evaluation = serde_json::from_str(&json).unwrap();
    // serde_json parses floats to within an ulp or two (no `float_roundtrip` feature).
    assert_eq!(back.joints.len(), e.joints.len());
    for (b, j) in back.joints.iter().zip(&e.joints) {
        assert_eq!((&b.key, &b.reference_joint), (&j.key, &j.reference_joint));
        assert!((b.error - j.error).abs() < 1e-15 && (b.offset - j.offset).length() < 1e-15);
    }
    assert!((back.summary.rms - e.summary.rms).abs() < 1e-15);
    assert_eq!(back.figure, e.figure);
    let dataset = aggregate(&[e.clone(), e]);
    let back: DatasetSummary = serde_json::from_str(&to_json(&dataset).unwrap()).unwrap();
    assert_eq!(back.keys.len(), dataset.keys.len());
    assert!((back.pooled_percent.mean - dataset.pooled_percent.mean).abs() < 1e-12);
    assert_eq!(dataset.pooled_percent.count, 28);
    assert_eq!(dataset.keys[0].key, Canonical::Pelvis.as_str());
    assert_eq!(dataset.keys[0].count, 2);
}

#[test]
fn tables_render() {
    let s = stick_figure();
    let e = evaluate(&rig(s.clone()), &rig(s), None, &EvalOptions::default()).unwrap();
    let md = joint_table(&joint_rows(&e)).markdown();
    assert!(md.starts_with("| joint | predicted |"));
    assert_eq!(md.lines().count(), 2 + 14);
    let plain = model_table(&[model_row(&e)]).plain();
    assert_eq!(plain.lines().count(), 2);
    assert!(key_table(&aggregate(&[e]).keys)
        .markdown()
        .contains("| elbow_L |"));
}

/// Two skeletons without a shared name or canonical key (the general skeleton's situation).
fn unrelated_pair() -> (Skeleton, Skeleton) {
    let a = Skeleton {
        joints: vec![
            joint("joint_000", None, [0.0; 3]),
            joint("joint_001", Some(0), [0.0, 1.0, 0.0]),
        ],
    };
    let b = Skeleton {
        joints: vec![
            joint("Root", None, [0.1, 0.0, 0.0]),
            joint("Wing", Some(0), [1.0, 0.0, 0.0]),
        ],
    };
    (a, b)
}

#[test]
fn chamfer_only_when_nothing_pairs_and_pairing_is_optional() {
    let (a, b) = unrelated_pair();
    let required = evaluate(
        &rig(a.clone()),
        &rig(b.clone()),
        None,
        &EvalOptions::default(),
    );
    assert!(matches!(required, Err(EvalError::NoSharedJoints { .. })));
    let options = EvalOptions {
        pairing: JointPairing::IfShared,
        ..Default::default()
    };
    let e = evaluate(&rig(a.clone()), &rig(b.clone()), None, &options).unwrap();
    assert_eq!(e.method, MatchMethod::ChamferOnly);
    assert!(!e.has_joint_errors());
    assert!(e.joints.is_empty() && e.worst_joint.is_empty());
    assert!(
        e.warnings[0]
            .message
            .contains("per-joint errors are unavailable"),
        "{:?}",
        e.warnings
    );
    let spacing = options.bone_sample_fraction * e.figure.size;
    let direct = chamfer(
        &a,
        &b,
        &ChamferOptions {
            bone_sample_spacing: spacing,
        },
    );
    assert_eq!(e.chamfer, direct);
    assert!(e.chamfer.j2j > 0.0);
    assert!((e.chamfer_percent.j2j - 100.0 * direct.j2j / e.figure.size).abs() < 1e-12);
    // Tables leave the per-joint columns empty.
    let row = model_row(&e);
    assert_eq!(row.pairing, MatchMethod::ChamferOnly);
    assert_eq!((row.mean_percent, row.max), (None, None));
    assert!(model_table(&[row]).markdown().contains("| – |"));
    // With IfShared, skeletons that do pair are evaluated per joint as usual.
    let s = stick_figure();
    let paired = evaluate(&rig(s.clone()), &rig(s), None, &options).unwrap();
    assert_eq!(paired.method, MatchMethod::Canonical);
    assert!(paired.warnings.is_empty());
}

#[test]
fn skip_pairing_reports_chamfer_only_even_for_identical_skeletons() {
    let s = stick_figure();
    let options = EvalOptions {
        pairing: JointPairing::Skip,
        ..Default::default()
    };
    let e = evaluate(&rig(s.clone()), &rig(s), None, &options).unwrap();
    assert_eq!(e.method, MatchMethod::ChamferOnly);
    assert!(e.warnings.is_empty(), "{:?}", e.warnings);
    // Identical skeletons: zero up to rounding of the bone samples.
    assert!(e.chamfer.j2j == 0.0 && e.chamfer.j2b == 0.0 && e.chamfer.b2b < 1e-12);
}

#[test]
fn aggregate_ignores_chamfer_only_models_in_per_joint_statistics() {
    let s = stick_figure();
    let offset = evaluate(
        &rig(translated(&s, DVec3::new(0.0, 0.018, 0.0))),
        &rig(s.clone()),
        None,
        &EvalOptions::default(),
    )
    .unwrap();
    let (a, b) = unrelated_pair();
    let options = EvalOptions {
        pairing: JointPairing::IfShared,
        ..Default::default()
    };
    let chamfer_only = evaluate(&rig(a), &rig(b), None, &options).unwrap();
    let dataset = aggregate(&[offset.clone(), chamfer_only.clone()]);
    assert_eq!(dataset.models, 2);
    assert_eq!(dataset.model_means_percent.count, 1);
    assert!((dataset.model_means_percent.mean - offset.summary_percent.mean).abs() < 1e-12);
    assert_eq!(dataset.pooled_percent.count, offset.joints.len());
    let mean_j2j = 0.5 * (offset.chamfer_percent.j2j + chamfer_only.chamfer_percent.j2j);
    assert!((dataset.chamfer_percent.j2j - mean_j2j).abs() < 1e-12);
}

#[test]
fn bench_models_are_found_with_rig_fallback() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let models = find_bench_models(&data, "game_engine").unwrap();
    let names: Vec<&str> = models.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["mh_neutral_default", "quaternius_horse"]);
    assert_eq!(models[0].category, "humanoid");
    assert!(models[0].note.is_none());
    let horse = &models[1];
    assert!(horse.reference.as_ref().unwrap().ends_with("rig_gltf.json"));
    assert!(horse
        .note
        .as_ref()
        .unwrap()
        .contains("only rig file rig_gltf.json"));
    // A model folder given directly is one model.
    let one = find_bench_models(&data.join("quadruped/quaternius_horse"), "gltf").unwrap();
    assert_eq!(one.len(), 1);
    assert!(one[0].note.is_none());
}

#[test]
fn bench_failures_are_recorded_not_returned() {
    let dir = tempfile::tempdir().unwrap();
    assert!(matches!(
        find_bench_models(dir.path(), "game_engine"),
        Err(EvalError::NoModels { .. })
    ));
    let ambiguous = dir.path().join("two_rigs");
    std::fs::create_dir_all(&ambiguous).unwrap();
    std::fs::write(ambiguous.join("mesh.obj"), "v 0 0 0\n").unwrap();
    std::fs::write(ambiguous.join("rig_a.json"), "{}").unwrap();
    std::fs::write(ambiguous.join("rig_b.json"), "{}").unwrap();
    let models = find_bench_models(dir.path(), "game_engine").unwrap();
    assert_eq!(models.len(), 1);
    assert!(models[0].reference.is_none());
    let note = models[0].note.clone().unwrap();
    assert!(note.contains("rig_a.json, rig_b.json"), "{note}");
    let result = bench_model(&models[0], &BenchOptions::default());
    assert!(result.failure.is_some());
    assert!(result.evaluation.is_none());
    let csv = bench_csv(std::slice::from_ref(&result)).unwrap();
    assert!(csv.lines().nth(1).unwrap().contains(",failed,"), "{csv}");
    let table = bench_table(std::slice::from_ref(&result));
    assert!(table.rows[0].last().unwrap().starts_with("failed: "));
    assert_eq!(table.rows[0].len(), table.headers.len());
    // The anatomy table says the model failed and leaves its values out.
    let anatomy = anatomy_table(std::slice::from_ref(&result));
    let row = &anatomy.rows[0];
    assert_eq!(row.len(), anatomy.headers.len());
    assert_eq!(row[7], "–", "core %");
    assert!(row.last().unwrap().starts_with("failed: "), "{row:?}");
    assert_eq!(core_summary(&[result], &|_| true), None);
}

#[test]
fn anatomy_table_lists_missing_core_joints_and_parts() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("m");
    std::fs::create_dir_all(&model).unwrap();
    std::fs::write(model.join("mesh.obj"), "v 0 0 0\n").unwrap();
    std::fs::write(model.join("provenance.json"), r#"{"converter": "x"}"#).unwrap();
    let models = find_bench_models(dir.path(), "game_engine").unwrap();
    assert!(models[0].real);
    let mut result = bench_model(&models[0], &BenchOptions::default());
    assert!(result.real);
    result.failure = None;
    result.anatomy = Some(RigAnatomy {
        figure: "human-like".into(),
        template: "humanoid".into(),
        parts: "trunk, head, arm L".into(),
        missing_parts: vec!["arm R".into()],
    });
    result.core = Some(CoreError {
        mapped: vec![
            Canonical::Pelvis.as_str().into(),
            Canonical::Shoulder(Side::Right).as_str().into(),
        ],
        paired: 1,
        mean: 0.02,
        mean_percent: 1.25,
        max_percent: 1.25,
        worst: Canonical::Pelvis.as_str().into(),
        missing: vec![Canonical::Shoulder(Side::Right).as_str().into()],
    });
    let record = |message: String| crate::warning::WarningRecord {
        stage: "fit".into(),
        code: "missing_limb".into(),
        severity: crate::warning::Severity::PartMissing,
        message,
    };
    result.warnings = vec![
        record("w".repeat(WARNING_CHARS + 5)),
        record("second".into()),
        record("third".into()),
    ];
    let mut other = result.clone();
    other.real = false;
    other.core.as_mut().unwrap().mean_percent = 3.25;
    other.core.as_mut().unwrap().missing.clear();
    let results = [result, other];
    let table = anatomy_table(&results);
    let cell = |r: usize, h: &str| {
        let c = table.headers.iter().position(|x| x == h).unwrap();
        table.rows[r][c].clone()
    };
    assert_eq!(cell(0, "real"), "yes");
    assert_eq!(cell(0, "core %"), "1.25");
    assert_eq!(cell(0, "core paired"), "1/2");
    assert_eq!(
        cell(0, "missing core joints"),
        Canonical::Shoulder(Side::Right).as_str()
    );
    assert_eq!(cell(1, "missing core joints"), "none");
    assert_eq!(cell(0, "missing parts"), "arm R");
    assert_eq!(cell(0, "warnings"), "3");
    let top = cell(0, "top warnings");
    assert!(top.ends_with("… · second"), "{top}");
    assert_eq!(
        bench_table(&results).rows[0][14],
        Canonical::Shoulder(Side::Right).as_str()
    );
    let all = core_summary(&results, &|_| true).unwrap();
    assert_eq!((all.models, all.with_missing), (2, 1));
    assert!((all.percent.median - 2.25).abs() < 1e-12);
    let real = core_summary(&results, &|r| r.real).unwrap();
    assert_eq!(real.models, 1);
    let lines = core_summary_lines(&results);
    assert_eq!(lines.len(), 2);
    assert!(
        lines[1].contains("over 1 real characters: median 1.25 %"),
        "{}",
        lines[1]
    );
}

#[test]
fn tessellation_and_rotation_studies_of_a_capsule() {
    let mesh = crate::mesh::Mesh::capsule(DVec3::ZERO, 0.2, 0.6, 8, 16);
    let options = StudyOptions::default();
    let study = tessellation_study(&mesh, "capsule", None, &[0.5, 2.0], &options).unwrap();
    let labels: Vec<&str> = study.variants.iter().map(|v| v.label.as_str()).collect();
    assert_eq!(labels, ["x1", "x0.5", "x2"]);
    let base = study.base().unwrap();
    assert_eq!(base.triangles, mesh.triangles.len());
    let c = base.chamfer_to_base_percent.unwrap();
    assert!(c.j2j == 0.0 && c.j2b == 0.0 && c.b2b < 1e-12, "{c:?}");
    assert_eq!(base.pairing, Some(DisplacementPairing::Index));
    for v in &study.variants {
        assert!(v.failure.is_none(), "{:?}", v.failure);
        // Re-meshing a capsule moves its axis joints by a few percent at most.
        let j2j = v.chamfer_to_base_percent.unwrap().j2j;
        assert!(j2j < 5.0, "{} {j2j}", v.label);
    }
    assert!(study.variants[2].triangles > mesh.triangles.len());
    // A rotation about the capsule's own axis, rotated back, lands near the base rig.
    let study = rotation_study(&mesh, "capsule", None, 4, DVec3::Y, &options).unwrap();
    assert_eq!(study.variants.len(), 4);
    assert_eq!(study.variants[1].level, 90.0);
    for v in &study.variants {
        let j2j = v.chamfer_to_base_percent.unwrap().j2j;
        assert!(j2j < 5.0, "{} {j2j}", v.label);
    }
    let table = study_table(&study);
    assert_eq!(table.rows.len(), 4);
    assert_eq!(table.rows[1][0], "90.0°");
    assert!(study_markdown(&study, "t", "").contains("| 90.0° |"));
    assert_eq!(study_csv(&study).unwrap().lines().count(), 5);
}

#[test]
fn study_parameters_are_validated() {
    let mesh = crate::mesh::Mesh::capsule(DVec3::ZERO, 0.2, 0.6, 8, 16);
    let options = StudyOptions::default();
    let err = tessellation_study(&mesh, "c", None, &[0.5, -1.0], &options).unwrap_err();
    assert!(err.to_string().contains("-1"), "{err}");
    let err = rotation_study(&mesh, "c", None, 0, DVec3::Y, &options).unwrap_err();
    assert!(err.to_string().contains("n >= 1"), "{err}");
    let err = rotation_study(&mesh, "c", None, 4, DVec3::ZERO, &options).unwrap_err();
    assert!(err.to_string().contains("axis"), "{err}");
}

#[test]
fn a_coincidental_shared_name_does_not_make_a_per_joint_evaluation() {
    // The general skeleton's `root` against a reference that also has a `root`.
    let predicted = Skeleton {
        joints: vec![
            joint("root", None, [0.0; 3]),
            joint("joint_001", Some(0), [0.0, 1.0, 0.0]),
        ],
    };
    let reference = Skeleton {
        joints: vec![
            joint("root", None, [0.0, 0.5, 0.0]),
            joint("Spine", Some(0), [0.0, 1.0, 0.0]),
            joint("Tail", Some(0), [0.0, 0.5, -1.0]),
        ],
    };
    let options = EvalOptions {
        pairing: JointPairing::IfShared,
        ..Default::default()
    };
    let e = evaluate(
        &rig(predicted.clone()),
        &rig(reference.clone()),
        None,
        &options,
    )
    .unwrap();
    assert_eq!(e.method, MatchMethod::ChamferOnly);
    assert!(
        e.warnings[0]
            .message
            .contains("only 1 of the reference's 3 joint names"),
        "{:?}",
        e.warnings
    );
    // Asked for explicitly (Required), the name pairing stands.
    let e = evaluate(
        &rig(predicted),
        &rig(reference),
        None,
        &EvalOptions::default(),
    )
    .unwrap();
    assert_eq!(e.method, MatchMethod::Name);
    assert_eq!(e.joints.len(), 1);
}

/// `arms_below_horizontal` (the pose study's re-posing): each arm turns about its shoulder to
/// the angle below the horizontal, out to its own side; the rest stays.
#[test]
fn arms_go_down_out_to_their_sides_and_the_rest_stays() {
    let skeleton = Skeleton {
        joints: vec![
            joint("chest", None, [0.0, 1.4, 0.0]),
            joint("shoulder_L", Some(0), [0.2, 1.4, 0.0]),
            joint("elbow_L", Some(1), [0.5, 1.4, 0.0]),
            joint("wrist_L", Some(2), [0.8, 1.4, 0.0]),
            joint("shoulder_R", Some(0), [-0.2, 1.4, 0.0]),
            joint("elbow_R", Some(4), [-0.5, 1.4, 0.0]),
        ],
    };
    let canonical: std::collections::BTreeMap<String, JointId> = skeleton
        .joints
        .iter()
        .enumerate()
        .map(|(k, j)| (j.name.clone(), JointId(k)))
        .collect();
    let m = arms_below_horizontal(&skeleton, &canonical, 45.0, DVec3::Y, DVec3::Z);
    assert_eq!(m[0], glam::DAffine3::IDENTITY);
    let wrist = m[3].transform_point3(skeleton.joints[3].position);
    let expected = DVec3::new(0.2, 1.4, 0.0) + 0.6 * DVec3::new(1.0, -1.0, 0.0).normalize();
    assert!(wrist.distance(expected) < 1e-9, "{wrist}");
    let elbow_r = m[5].transform_point3(skeleton.joints[5].position);
    let expected_r = DVec3::new(-0.2, 1.4, 0.0) + 0.3 * DVec3::new(-1.0, -1.0, 0.0).normalize();
    assert!(elbow_r.distance(expected_r) < 1e-9, "{elbow_r}");
    // The shoulder is the pivot: it stays.
    assert!(
        m[1].transform_point3(skeleton.joints[1].position)
            .distance(skeleton.joints[1].position)
            < 1e-12
    );
}

use super::*;
use crate::skeleton::canonical::{is_canonical_key, Tail, CANONICAL_KEYS};
use crate::skeleton::{Canonical, Joint, JointId, LocalAxis, Skeleton};
use glam::DVec3;
use std::collections::BTreeMap;

#[test]
fn every_bundled_template_loads() {
    for (name, _) in BUILTIN_TEMPLATES {
        let t = Template::builtin(name).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(&t.name, name);
        assert!(t.placed("root").is_some());
        // Parents come first.
        for (k, j) in t.joints.iter().enumerate() {
            if let Some(p) = &j.parent {
                assert!(
                    t.joints[..k].iter().any(|q| &q.name == p),
                    "{name}: {}",
                    j.name
                );
            }
        }
        for l in &t.limbs {
            assert_eq!(l.chain.len(), t.ratios[&l.ratios].len() + 1);
        }
    }
    // Only the humanoid declares the slicing refinement (`skelfit rig` refines its fits).
    for (name, _) in BUILTIN_TEMPLATES {
        let declared = Template::builtin(name).unwrap().refinement;
        let expected = (*name == "humanoid").then_some(RefineKind::HumanSlicing);
        assert_eq!(declared, expected, "{name}");
    }
    let text =
        BUILTIN_TEMPLATES[0]
            .1
            .replacen("refine = \"human_slicing\"", "refine = \"melting\"", 1);
    let err = Template::parse(&text, "melting.toml").unwrap_err();
    assert!(
        err.to_string().contains("unknown refinement \"melting\""),
        "{err}"
    );
    assert!(matches!(
        Template::builtin("centaur"),
        Err(TemplateError::UnknownTemplate { .. })
    ));
}

#[test]
fn table_8_1_and_digit_ratios() {
    let t = Template::builtin("humanoid").unwrap();
    assert_eq!(
        t.ratios["animal_forelimb"],
        [149.0, 154.0, 22.0, 78.0, 29.0, 19.0, 16.0]
    );
    assert_eq!(
        t.ratios["animal_hind_limb"],
        [175.0, 174.0, 35.0, 89.0, 29.0, 19.0, 17.0]
    );
    assert_eq!(
        t.ratios["human_arm"],
        [190.0, 150.0, 20.0, 36.0, 25.0, 15.0, 10.0]
    );
    assert_eq!(
        t.ratios["human_leg"],
        [180.0, 160.0, 30.0, 30.0, 12.0, 5.0, 5.0]
    );
    assert_eq!(t.ratios["digit"], [36.0, 25.0, 15.0, 10.0]);
    assert_eq!(t.ratios["first_digit"], [36.0, 25.0, 15.0]);
    let f = t.fractions("human_arm").unwrap();
    assert!((f.iter().sum::<f64>() - 1.0).abs() < 1e-12);
}

#[test]
fn dofs_follow_the_anatomy() {
    let t = Template::builtin("quadruped").unwrap();
    let axes =
        |n: &str| -> Vec<LocalAxis> { t.joint(n).unwrap().dofs.iter().map(|d| d.axis).collect() };
    assert_eq!(axes("elbow"), [LocalAxis::X]);
    assert_eq!(axes("knee"), [LocalAxis::X]);
    assert_eq!(axes("shoulder").len(), 3);
    assert_eq!(axes("ankle").len(), 3);
    let fore = &t.limbs[0];
    assert_eq!(fore.first_digit_base_dofs.len(), 2);
    assert_eq!(fore.digit_base_dofs.len(), 1);
    assert!(t.joint("toe_end").unwrap().dofs.is_empty());
    for j in &t.joints {
        for d in &j.dofs {
            assert!(d.min <= d.max && d.max <= std::f64::consts::PI);
        }
    }
}

#[test]
fn canonical_keys_cover_the_reference_set() {
    for name in ["humanoid", "quadruped"] {
        let t = Template::builtin(name).unwrap();
        let mut keys: Vec<String> = vec![
            Canonical::Spine.as_str().into(),
            Canonical::Chest.as_str().into(),
        ];
        for j in &t.joints {
            if let Some(c) = &j.canonical {
                if j.side {
                    keys.push(format!("{c}_L"));
                    keys.push(format!("{c}_R"));
                } else {
                    keys.push(c.clone());
                }
            }
        }
        assert!(keys.iter().all(|k| is_canonical_key(k)));
        for key in CANONICAL_KEYS {
            assert!(keys.iter().any(|k| k == key), "{name} lacks {key}");
        }
    }
    let q = Template::builtin("quadruped").unwrap();
    assert_eq!(
        q.joint("tail").unwrap().canonical.as_deref(),
        Some(Canonical::Tail(Tail::Base).as_str())
    );
}

/// The humanoid template with several deliberate mistakes.
fn broken() -> String {
    let (_, text) = BUILTIN_TEMPLATES[0];
    text.replacen("head = 0.5\nneck = 0.5", "head = 0.5\nneck = 0.6", 1)
        .replacen(
            "name = \"elbow\"\ncanonical = \"elbow\"\nparent = \"shoulder\"",
            "name = \"elbow\"\ncanonical = \"elbows\"\nparent = \"shouldr\"",
            1,
        )
        .replacen(
            "name = \"hand\"\nparent = \"wrist\"",
            "name = \"hand\"\nparent = \"finger_01\"",
            1,
        )
        .replacen(
            "name = \"finger_01\"\nparent = \"hand\"",
            "name = \"finger_01\"\nparent = \"hand\"\n",
            1,
        )
        .replacen("name = \"toe_03\"", "name = \"toe_02\"", 1)
        .replacen(
            "{ axis = \"x\", min = 0, max = 150 }",
            "{ axis = \"x\", min = 150, max = 0 }",
            1,
        )
        .replacen("trunk = [3, 6]", "trunk = [6, 3]", 1)
}

#[test]
fn a_broken_template_reports_every_problem_with_its_location() {
    let text = broken();
    let err = Template::parse(&text, "broken.toml").unwrap_err();
    let TemplateError::Invalid { problems, .. } = &err else {
        panic!("{err}");
    };
    let message = err.to_string();
    let find = |needle: &str| -> &TemplateProblem {
        problems
            .iter()
            .find(|p| p.message.contains(needle) || p.path.contains(needle))
            .unwrap_or_else(|| panic!("no problem mentions {needle}:\n{message}"))
    };
    let line_of = |needle: &str| text.lines().position(|l| l.contains(needle)).unwrap() + 1;
    assert!(find("does not sum to 1").path == "sections");
    let parent = find("unknown parent \"shouldr\"");
    assert!(parent.path.contains("(elbow).parent"));
    assert_eq!(parent.line, Some(line_of("name = \"elbow\"") - 1));
    assert!(find("unknown canonical key \"elbows_L\"")
        .path
        .contains("elbow"));
    assert!(find("cycle").path.contains("hand") || find("cycle").path.contains("finger"));
    assert!(find("duplicate joint name \"toe_02\"").line.is_some());
    let limits = find("min 150 > max 0");
    assert!(limits.path.contains("(elbow).dofs[0]"));
    assert_eq!(
        find("vertebrae.trunk").line,
        Some(line_of("trunk = [6, 3]"))
    );
    assert!(problems.len() >= 7, "{message}");
    // Every problem names the file.
    assert!(problems
        .iter()
        .all(|p| p.to_string().starts_with("broken.toml")));
}

#[test]
fn limb_problems_are_located() {
    let (_, text) = BUILTIN_TEMPLATES[1];
    let text = text
        .replacen("kinds = [\"fore_leg\"]", "kinds = [\"flipper\"]", 1)
        .replacen(
            "ratios = \"animal_hind_limb\"",
            "ratios = \"animal_hindlimb\"",
            1,
        )
        .replacen("girdle = \"pectoral\"", "girdle = \"shoulder\"", 1);
    let err = Template::parse(&text, "q.toml").unwrap_err().to_string();
    assert!(err.contains("unknown limb kind \"flipper\""), "{err}");
    assert!(
        err.contains("unknown ratio list \"animal_hindlimb\""),
        "{err}"
    );
    assert!(err.contains("unknown girdle \"shoulder\""), "{err}");
    assert!(err.contains("limb[0] (fore_leg)"), "{err}");
}

#[test]
fn syntax_errors_carry_a_line() {
    let text = "[template]\nname = \"x\"\nposture = \n";
    match Template::parse(text, "bad.toml") {
        Err(TemplateError::Parse { line, .. }) => assert_eq!(line, Some(3)),
        other => panic!("{other:?}"),
    }
    let unknown = BUILTIN_TEMPLATES[0]
        .1
        .replacen("[axial]\n", "[axial]\nspline = 3\n", 1);
    let err = Template::parse(&unknown, "u.toml").unwrap_err().to_string();
    assert!(err.contains("spline"), "{err}");
}

#[test]
fn template_files_on_disk_load() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates");
    for (name, _) in BUILTIN_TEMPLATES {
        let t = Template::load(&dir.join(format!("{name}.toml"))).unwrap();
        assert_eq!(t.name, *name);
    }
    assert!(matches!(
        Template::load(&dir.join("missing.toml")),
        Err(TemplateError::Io { .. })
    ));
}

/// A small upright skeleton: pelvis at height 2, a three-joint spine up to the neck at 6,
/// head and its end, a left arm with a joint no engine has (`finger_01_L`), a left hip at the
/// ground.
fn little() -> (Skeleton, BTreeMap<String, JointId>) {
    let mut s = Skeleton::default();
    let mut add = |name: &str, parent: Option<usize>, at: DVec3| {
        s.joints.push(Joint::new(name, parent.map(JointId), at));
    };
    add("pelvis", None, DVec3::new(0.0, 2.0, 0.0));
    add("spine_01", Some(0), DVec3::new(0.0, 3.0, 0.0));
    add("spine_02", Some(1), DVec3::new(0.0, 4.0, 0.0));
    add("spine_03", Some(2), DVec3::new(0.0, 5.0, 0.0));
    add("neck_01", Some(3), DVec3::new(0.0, 6.0, 0.0));
    add("head", Some(4), DVec3::new(0.0, 7.0, 0.0));
    add("head_end", Some(5), DVec3::new(0.0, 8.0, 0.0));
    add("clavicle_L", Some(3), DVec3::new(0.5, 5.0, 0.0));
    add("shoulder_L", Some(7), DVec3::new(1.0, 5.0, 0.0));
    add("finger_01_L", Some(8), DVec3::new(2.0, 5.0, 0.0));
    add("hip_L", Some(0), DVec3::new(0.5, 0.0, 0.0));
    s.joints[6].deform = false;
    let canonical = [
        ("pelvis", 0),
        ("spine", 1),
        ("chest", 2),
        ("neck", 4),
        ("head", 5),
        ("clavicle_L", 7),
        ("shoulder_L", 8),
        ("hip_L", 10),
    ]
    .into_iter()
    .map(|(k, j)| (k.to_string(), JointId(j)))
    .collect();
    (s, canonical)
}

fn names_and_parents(s: &Skeleton) -> Vec<(&str, Option<&str>)> {
    s.joints
        .iter()
        .map(|j| (j.name.as_str(), j.parent.map(|p| s.joint(p).name.as_str())))
        .collect()
}

#[test]
fn mixamo_gets_its_own_spine_and_drops_joints_it_lacks() {
    let (mut s, mut c) = little();
    let dropped = apply_preset(&mut s, &mut c, Preset::Mixamo, DVec3::Y, DVec3::Z).unwrap();
    assert!(dropped.is_empty(), "{dropped:?}");
    let m = |n: &str| format!("mixamorig:{n}");
    let expected = [
        ("Hips", None),
        ("Spine", Some("Hips")),
        ("Spine1", Some("Spine")),
        ("Spine2", Some("Spine1")),
        ("Neck", Some("Spine2")),
        ("Head", Some("Neck")),
        ("HeadTop_End", Some("Head")),
        ("LeftShoulder", Some("Spine2")),
        ("LeftArm", Some("LeftShoulder")),
        ("LeftUpLeg", Some("Hips")),
    ];
    let expected: Vec<(String, Option<String>)> =
        expected.iter().map(|(n, p)| (m(n), p.map(m))).collect();
    let got: Vec<(String, Option<String>)> = names_and_parents(&s)
        .into_iter()
        .map(|(n, p)| (n.to_string(), p.map(str::to_string)))
        .collect();
    assert_eq!(got, expected);
    // Spine, Spine1, Spine2 at 20.3 %, 40.4 %, 65.4 % of the 4-long pelvis-to-neck chain.
    for (k, f) in [(1, 0.203), (2, 0.404), (3, 0.654)] {
        let y = s.joints[k].position.y;
        assert!(
            (y - (2.0 + 4.0 * f)).abs() < 1e-9,
            "{} at {y}",
            s.joints[k].name
        );
    }
    // Placed joints keep the fitted joint's position and `deform`.
    assert_eq!(s.joints[4].position, DVec3::new(0.0, 6.0, 0.0));
    assert!(!s.joints[6].deform);
    // The canonical map points at the preset's names.
    assert_eq!(s.joint(c["spine"]).name, "mixamorig:Spine1");
    assert_eq!(s.joint(c["chest"]).name, "mixamorig:Spine2");
    assert_eq!(s.joint(c["neck"]).name, "mixamorig:Neck");
    assert_eq!(c.len(), 8);
    assert!(s.validate().is_ok());
}

#[test]
fn engine_roots_stand_on_the_ground_and_missing_joints_are_bridged() {
    let (mut s, mut c) = little();
    apply_preset(&mut s, &mut c, Preset::MakeHuman, DVec3::Y, DVec3::Z).unwrap();
    assert_eq!(s.joints[0].name, "Root");
    assert_eq!(s.joints[0].position, DVec3::ZERO);
    assert!(!s.joints[0].deform);
    assert_eq!(s.joints[1].name, "pelvis");
    assert_eq!(s.joints[1].parent, Some(JointId(0)));
    let (mut s, mut c) = little();
    apply_preset(&mut s, &mut c, Preset::Unreal, DVec3::Y, DVec3::Z).unwrap();
    let got = names_and_parents(&s);
    for pair in [
        ("root", None),
        ("spine_05", Some("spine_04")),
        ("neck_02", Some("neck_01")),
        ("head", Some("neck_02")),
        ("clavicle_l", Some("spine_05")),
        ("thigh_l", Some("pelvis")),
    ] {
        assert!(got.contains(&pair), "{pair:?} in {got:?}");
    }
    // neck_02 halfway from neck to head.
    let neck_02 = s.find("neck_02").unwrap();
    assert!((s.joint(neck_02).position.y - 6.5).abs() < 1e-9);
    // Without a clavicle, Unity's upper arm hangs from the clavicle's engine parent; no jaw, no Jaw.
    let (mut s, mut c) = little();
    c.remove("clavicle_L");
    s.joints[7].name = "collar".into();
    // A canonical joint the engine has no joint for is left out and returned.
    c.insert("tail_base".into(), JointId(9));
    let dropped = apply_preset(&mut s, &mut c, Preset::Unity, DVec3::Y, DVec3::Z).unwrap();
    assert_eq!(dropped, ["tail_base"]);
    assert!(!c.contains_key("tail_base"));
    let got = names_and_parents(&s);
    assert!(
        got.contains(&("LeftUpperArm", Some("UpperChest"))),
        "{got:?}"
    );
    assert!(s.find("LeftShoulder").is_none() && s.find("Jaw").is_none());
    assert!(s.validate().is_ok());
}

#[test]
fn anatomical_keeps_the_skeleton_and_preset_files_are_checked() {
    let (mut s, mut c) = little();
    let before = (s.clone(), c.clone());
    apply_preset(&mut s, &mut c, Preset::Anatomical, DVec3::Y, DVec3::Z).unwrap();
    assert_eq!((s, c), before);
    assert!(matches!(
        Preset::parse("blender"),
        Err(TemplateError::UnknownPreset { .. })
    ));
    for preset in Preset::ALL {
        let names = preset.names().unwrap();
        assert!(names.joints.keys().all(|k| is_canonical_key(k)));
        assert_eq!(names.skeleton.is_some(), preset != Preset::Anatomical);
        assert_eq!(Preset::parse(preset.file_stem()).unwrap(), preset);
    }
    let bad: EngineSkeleton = serde_json::from_str(
        r#"{"engine": "e", "source": "s", "joints": [
            {"name": "b", "parent": "a", "place": {"at": "pelvis"}},
            {"name": "a", "parent": null, "place": {"at": "pelvis"}}]}"#,
    )
    .unwrap();
    assert!(bad.check().unwrap_err().contains("does not come before"));
    let bad: EngineSkeleton = serde_json::from_str(
        r#"{"engine": "e", "source": "s", "joints": [
            {"name": "a", "parent": null,
             "place": {"along": {"from": "pelvis", "to": "neck", "fraction": 1.5}}}]}"#,
    )
    .unwrap();
    assert!(bad.check().unwrap_err().contains("fraction"));
}

#[test]
fn ear_places_are_sided_and_need_ear_ratios() {
    let (_, text) = BUILTIN_TEMPLATES[1];
    let t = Template::parse(text, "quadruped.toml").unwrap();
    let ear = t.placed("ear").unwrap();
    assert!(ear.side && ear.deform);
    assert!(t.placed("ear_end").is_some_and(|j| j.side && !j.deform));
    assert_eq!(t.fractions("ear").unwrap().len(), 3);

    let broken = text.replacen("ear = [1, 1, 1]", "", 1).replacen(
        "place = \"ear_end\"\nside = true",
        "place = \"ear_end\"",
        1,
    );
    let err = Template::parse(&broken, "broken.toml").unwrap_err();
    let message = err.to_string();
    assert!(message.contains("needs ratios.ear"), "{message}");
    assert!(message.contains("exists per side"), "{message}");
}

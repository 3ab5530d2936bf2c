//! Engine presets (`rig --preset`): the bundled body rigged for each engine gets the engine's
//! own skeleton — every joint named as the engine names it and parented as the engine parents
//! it, the engine's core joints all present (fingers are not placed yet) — and its skin
//! weights still sum to one on every vertex. Mixamo is compared with the names and parents of
//! Mixamo-rigged characters (`../shared/engine_skeletons/mixamo.json`), MakeHuman with the
//! reference rig beside the body (`../shared/refdata/.../rig_game_engine.json`), Unreal and
//! Unity with their documented hierarchies written out below.

use crate::common;
use glam::{DQuat, DVec3};
use skelfit::mesh::{load, Mesh};
use skelfit::pipeline::{rig, Rig, RigOptions};
use skelfit::skeleton::canonical::DIGITS;
use skelfit::skeleton::Skeleton;
use skelfit::template::Preset;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Engine joint name → parent name.
type Hierarchy = BTreeMap<String, Option<String>>;

fn body() -> PathBuf {
    common::data_dir().join("humanoid/mh_neutral_default/mesh.obj")
}

fn rigged(preset: Preset) -> (Mesh, Rig) {
    let mesh = load(&body()).unwrap();
    let mut options = RigOptions::default();
    options.fit.preset = preset;
    let r = rig(&mesh, &options).unwrap();
    (mesh, r)
}

/// The `joints` (`name`, `parent`) of an engine skeleton file, or `None` with a printed reason.
fn engine_file(path: &Path) -> Option<Hierarchy> {
    let Ok(text) = std::fs::read_to_string(path) else {
        eprintln!("SKIPPED: engine skeleton {} missing", path.display());
        return None;
    };
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let joints = value["joints"].as_array().unwrap();
    Some(
        joints
            .iter()
            .map(|j| {
                (
                    j["name"].as_str().unwrap().to_string(),
                    j["parent"].as_str().map(str::to_string),
                )
            })
            .collect(),
    )
}

fn shared() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared")
}

fn is_finger(name: &str) -> bool {
    ["thumb", "index", "middle", "ring", "pinky"]
        .iter()
        .any(|f| name.to_ascii_lowercase().contains(f))
}

/// Every joint of `skeleton` is in `engine` with the engine's parent; every joint of `core`
/// is present.
fn assert_engine_skeleton(preset: &str, skeleton: &Skeleton, engine: &Hierarchy, core: &[&str]) {
    assert!(skeleton.validate().is_ok(), "{preset}");
    for joint in &skeleton.joints {
        let parent = joint.parent.map(|p| skeleton.joint(p).name.clone());
        match engine.get(&joint.name) {
            None => panic!(
                "{preset}: joint {:?} is not in the engine skeleton",
                joint.name
            ),
            Some(expected) => assert_eq!(&parent, expected, "{preset}: parent of {:?}", joint.name),
        }
    }
    let missing: Vec<&&str> = core
        .iter()
        .filter(|name| skeleton.find(name).is_none())
        .collect();
    assert!(
        missing.is_empty(),
        "{preset}: core joints missing {missing:?}"
    );
}

fn assert_weights(preset: &str, mesh: &Mesh, r: &Rig) {
    let weights = &r.skin.engine;
    assert_eq!(weights.weights.len(), mesh.positions.len(), "{preset}");
    for (v, (w, j)) in weights.weights.iter().zip(&weights.joints).enumerate() {
        let sum: f32 = w.iter().sum();
        assert!(
            (sum - 1.0).abs() < 1e-3,
            "{preset}: vertex {v} sums to {sum}"
        );
        for (weight, joint) in w.iter().zip(j) {
            assert!(*weight >= 0.0, "{preset}: vertex {v}");
            if *weight > 0.0 {
                assert!(
                    usize::from(*joint) < r.fit.skeleton.len(),
                    "{preset}: vertex {v} weights joint {joint}"
                );
            }
        }
    }
}

/// The canonical map points at joints of the engine skeleton named by the preset's table.
fn assert_canonical(preset: Preset, r: &Rig) {
    let table = preset.names().unwrap();
    assert_eq!(
        r.fit.canonical.len(),
        skelfit::eval::CANONICAL_KEYS.len() + DIGITS.len()
    );
    for (key, id) in &r.fit.canonical {
        assert_eq!(
            r.fit.skeleton.joint(*id).name,
            table.joints[key][0],
            "{preset:?}: {key}"
        );
    }
}

#[test]
fn mixamo_preset_gives_the_mixamo_skeleton() {
    let Some(engine) = engine_file(&shared().join("engine_skeletons/mixamo.json")) else {
        return;
    };
    let (mesh, r) = rigged(Preset::Mixamo);
    let core: Vec<&str> = engine
        .keys()
        .map(String::as_str)
        .filter(|n| !is_finger(n))
        .collect();
    assert_eq!(core.len(), 25, "Mixamo's body without fingers: {core:?}");
    assert_engine_skeleton("mixamo", &r.fit.skeleton, &engine, &core);
    // The body and every finger, the four-joint digits with their end joints.
    assert_eq!(r.fit.skeleton.len(), engine.len());
    assert_weights("mixamo", &mesh, &r);
    assert_canonical(Preset::Mixamo, &r);
    // Spine, Spine1, Spine2 rise in order between the hips and the neck.
    let height = |n: &str| {
        let id = r.fit.skeleton.find(&format!("mixamorig:{n}")).unwrap();
        r.fit.skeleton.joint(id).position.y
    };
    let chain = ["Hips", "Spine", "Spine1", "Spine2", "Neck"].map(height);
    assert!(chain.windows(2).all(|w| w[0] < w[1]), "{chain:?}");
}

#[test]
fn makehuman_preset_gives_the_game_engine_skeleton() {
    let Some(dir) = common::model("humanoid/mh_neutral_default") else {
        return;
    };
    let Some(engine) = engine_file(&dir.join("rig_game_engine.json")) else {
        return;
    };
    let (mesh, r) = rigged(Preset::MakeHuman);
    let core: Vec<&str> = engine
        .keys()
        .map(String::as_str)
        .filter(|n| !is_finger(n))
        .collect();
    assert!(core.contains(&"Root") && core.contains(&"spine_03"));
    assert_engine_skeleton("makehuman", &r.fit.skeleton, &engine, &core);
    // The body and the three joints of every digit.
    assert_eq!(r.fit.skeleton.len(), core.len() + DIGITS.len());
    assert!(!r.fit.skeleton.joints[0].deform, "Root carries no weight");
    assert_weights("makehuman", &mesh, &r);
    assert_canonical(Preset::MakeHuman, &r);
}

/// `(joint, parent)` pairs for one side: `l`/`r` or `Left`/`Right` put in for `{}`.
fn sided(pairs: &[(&str, &str)], sides: [&str; 2]) -> Vec<(String, Option<String>)> {
    sides
        .iter()
        .flat_map(|s| {
            pairs
                .iter()
                .map(move |(j, p)| (j.replace("{}", s), Some(p.replace("{}", s))))
        })
        .collect()
}

/// `(joint, parent)` of the three joints of every digit on both sides: `name(finger, k, side)`
/// names joint `k` (1..3) of a digit, `hand(side)` the hand.
fn digit_chains(
    name: impl Fn(usize, usize, usize) -> String,
    hand: impl Fn(usize) -> String,
) -> Vec<(String, Option<String>)> {
    let mut h = Vec::new();
    for side in 0..2 {
        for finger in 0..5 {
            for k in 1..=3 {
                let parent = if k == 1 {
                    hand(side)
                } else {
                    name(finger, k - 1, side)
                };
                h.push((name(finger, k, side), Some(parent)));
            }
        }
    }
    h
}

/// UE5 Mannequin body (IK Rig's "UE5 Mannequin" template hierarchy) with its fingers, without
/// twist, metacarpal and IK bones.
fn unreal_core() -> Hierarchy {
    let mut h: Hierarchy = [
        ("root", None),
        ("pelvis", Some("root")),
        ("spine_01", Some("pelvis")),
        ("spine_02", Some("spine_01")),
        ("spine_03", Some("spine_02")),
        ("spine_04", Some("spine_03")),
        ("spine_05", Some("spine_04")),
        ("neck_01", Some("spine_05")),
        ("neck_02", Some("neck_01")),
        ("head", Some("neck_02")),
    ]
    .into_iter()
    .map(|(j, p)| (j.to_string(), p.map(str::to_string)))
    .collect();
    h.extend(sided(
        &[
            ("clavicle_{}", "spine_05"),
            ("upperarm_{}", "clavicle_{}"),
            ("lowerarm_{}", "upperarm_{}"),
            ("hand_{}", "lowerarm_{}"),
            ("thigh_{}", "pelvis"),
            ("calf_{}", "thigh_{}"),
            ("foot_{}", "calf_{}"),
            ("ball_{}", "foot_{}"),
        ],
        ["l", "r"],
    ));
    let sides = ["l", "r"];
    let fingers = ["thumb", "index", "middle", "ring", "pinky"];
    h.extend(digit_chains(
        |f, k, s| format!("{}_{k:02}_{}", fingers[f], sides[s]),
        |s| format!("hand_{}", sides[s]),
    ));
    h
}

/// Unity Humanoid body bones (HumanBodyBones) with Unity's parents and fingers, without eyes
/// (Jaw is allowed: skelfit places it on some heads).
fn unity_bones() -> Hierarchy {
    let mut h: Hierarchy = [
        ("Hips", None),
        ("Spine", Some("Hips")),
        ("Chest", Some("Spine")),
        ("UpperChest", Some("Chest")),
        ("Neck", Some("UpperChest")),
        ("Head", Some("Neck")),
        ("Jaw", Some("Head")),
    ]
    .into_iter()
    .map(|(j, p)| (j.to_string(), p.map(str::to_string)))
    .collect();
    h.extend(sided(
        &[
            ("{}Shoulder", "UpperChest"),
            ("{}UpperArm", "{}Shoulder"),
            ("{}LowerArm", "{}UpperArm"),
            ("{}Hand", "{}LowerArm"),
            ("{}UpperLeg", "Hips"),
            ("{}LowerLeg", "{}UpperLeg"),
            ("{}Foot", "{}LowerLeg"),
            ("{}Toes", "{}Foot"),
        ],
        ["Left", "Right"],
    ));
    let sides = ["Left", "Right"];
    let fingers = ["Thumb", "Index", "Middle", "Ring", "Little"];
    let phalanges = ["Proximal", "Intermediate", "Distal"];
    h.extend(digit_chains(
        |f, k, s| format!("{}{}{}", sides[s], fingers[f], phalanges[k - 1]),
        |s| format!("{}Hand", sides[s]),
    ));
    h
}

#[test]
fn unreal_preset_gives_the_ue5_mannequin_skeleton() {
    let (mesh, r) = rigged(Preset::Unreal);
    let engine = unreal_core();
    let core: Vec<&str> = engine.keys().map(String::as_str).collect();
    assert_engine_skeleton("unreal", &r.fit.skeleton, &engine, &core);
    assert_weights("unreal", &mesh, &r);
    assert_canonical(Preset::Unreal, &r);
    // The root stands on the ground below the pelvis.
    let joint = |n: &str| r.fit.skeleton.joint(r.fit.skeleton.find(n).unwrap());
    let (root, pelvis) = (joint("root"), joint("pelvis"));
    let lowest = r
        .fit
        .skeleton
        .joints
        .iter()
        .map(|j| j.position.y)
        .fold(f64::INFINITY, f64::min);
    assert!((root.position.y - lowest).abs() < 1e-9);
    assert!(root.position.x == pelvis.position.x && root.position.z == pelvis.position.z);
}

#[test]
fn unity_preset_gives_the_humanoid_avatar_skeleton() {
    let (mesh, r) = rigged(Preset::Unity);
    let engine = unity_bones();
    let core: Vec<&str> = engine
        .keys()
        .map(String::as_str)
        .filter(|n| *n != "Jaw")
        .collect();
    assert_engine_skeleton("unity", &r.fit.skeleton, &engine, &core);
    assert_weights("unity", &mesh, &r);
    assert_canonical(Preset::Unity, &r);
}

/// The written .glb carries the engine skeleton: `skelfit rig --preset mixamo` gives nodes
/// named and parented as Mixamo's.
#[test]
fn rig_writes_the_engine_skeleton_into_the_glb() {
    let Some(engine) = engine_file(&shared().join("engine_skeletons/mixamo.json")) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("mixamo.glb");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_skelfit"))
        .arg("rig")
        .arg(body())
        .arg("-o")
        .arg(&out)
        .args(["--preset", "mixamo"])
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let written = skelfit::eval::load_skeleton(&out).unwrap().skeleton;
    let core: Vec<&str> = engine
        .keys()
        .map(String::as_str)
        .filter(|n| !is_finger(n))
        .collect();
    assert_engine_skeleton("mixamo .glb", &written, &engine, &core);
}

/// Blender's rest frame of a bone (head, tail, roll in Blender's Z-up convention) in a Y-up
/// rig, as Blender's glTF exporter writes it: the shortest rotation taking +Y onto the bone,
/// then the roll about it.
fn blender_frame(head: DVec3, tail: DVec3, roll: f64) -> Option<DQuat> {
    let to_blender = DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2);
    let bone = (to_blender * (tail - head)).try_normalize()?;
    let frame = DQuat::from_axis_angle(bone, roll) * DQuat::from_rotation_arc(DVec3::Y, bone);
    Some(to_blender.inverse() * frame)
}

/// The bone-axis convention of the Mixamo and MakeHuman presets (rest frames with local +Y
/// along the bone and the engine's roll): on a MakeHuman body other than the one the
/// presets' frames were taken from, each rig joint's rest frame against the body's own
/// reference rig (`rig_mixamo.json`, `rig_game_engine.json`: Blender bones), median within 8°
/// and three in four within 15°. skelfit's own frames (local +Z along the bone) are 90° or
/// more off on every joint.
#[test]
fn mixamo_and_makehuman_rigs_have_the_engines_bone_axes() {
    let Some(dir) = common::model("humanoid/mh_male_heavy_short") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    for (preset, file) in [
        (Preset::Mixamo, "rig_mixamo.json"),
        (Preset::MakeHuman, "rig_game_engine.json"),
    ] {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let reference: serde_json::Value = serde_json::from_str(&text).unwrap();
        let point = |v: &serde_json::Value| {
            DVec3::new(
                v[0].as_f64().unwrap(),
                v[1].as_f64().unwrap(),
                v[2].as_f64().unwrap(),
            )
        };
        let mut options = RigOptions::default();
        options.fit.preset = preset;
        let r = rig(&mesh, &options).unwrap();
        let mut angles: Vec<(f64, String)> = reference["joints"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|j| {
                let name = j["name"].as_str()?;
                let id = r.fit.skeleton.find(name)?;
                let expected = blender_frame(
                    point(&j["position"]),
                    point(&j["tail"]),
                    j["roll"].as_f64()?,
                )?;
                let angle = r.fit.skeleton.joint(id).frame.angle_between(expected);
                Some((angle.to_degrees(), name.to_string()))
            })
            .collect();
        angles.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert!(
            angles.len() >= 45,
            "{preset:?}: {} joints compared",
            angles.len()
        );
        let median = angles[angles.len() / 2].0;
        let quartile = angles[angles.len() * 3 / 4].0;
        eprintln!(
            "{preset:?}: rest frames vs the reference rig: median {median:.1}°, 75th percentile {quartile:.1}°, worst {:?}",
            angles.last()
        );
        assert!(median <= 8.0 && quartile <= 15.0, "{preset:?}: {angles:?}");
    }
}

//! `skelfit skin` and `skin::skin_skeleton`: skinning a skeleton the user already has, and
//! the errors and warnings for skeletons that do not fit their mesh.

use crate::common::{skelfit, stderr};
use skelfit::eval::load_skeleton;
use skelfit::mesh::{load, load_gltf_scene};
use skelfit::skeleton::{JointId, Skeleton};
use skelfit::skin::check::{check_deformation, sweep, SweepKind};
use skelfit::skin::{skin_skeleton, SkeletonSkinOptions};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;

fn bundled() -> PathBuf {
    crate::common::data_dir().join("humanoid/mh_neutral_default")
}

/// The edges past 2× over the humanoid sweep of a skinned .glb, posed through the canonical
/// map of `reference` (a rig file naming the same joints).
fn stretched_edges(glb: &Path, reference: &Path) -> (usize, usize) {
    let scene = load_gltf_scene(glb).unwrap();
    let skeleton = scene.skeleton.unwrap();
    let weights = scene.weights.unwrap();
    let reference = load_skeleton(reference).unwrap();
    let canonical: BTreeMap<String, JointId> = reference
        .canonical
        .iter()
        .filter_map(|(k, &j)| Some((k.clone(), skeleton.find(&reference.skeleton.joint(j).name)?)))
        .collect();
    let (poses, missing) = sweep(
        &skeleton,
        &canonical,
        SweepKind::Humanoid,
        glam::DVec3::Y,
        glam::DVec3::Z,
    );
    let check = check_deformation(
        &scene.mesh,
        &skeleton,
        &weights,
        SweepKind::Humanoid,
        &poses,
        missing,
    )
    .unwrap();
    (check.total_over_2(), check.poses.len())
}

/// Joint names and parent names, in order.
fn hierarchy(skeleton: &Skeleton) -> Vec<(String, Option<String>)> {
    skeleton
        .joints
        .iter()
        .map(|j| {
            let parent = j.parent.map(|p| skeleton.joint(p).name.clone());
            (j.name.clone(), parent)
        })
        .collect()
}

#[test]
fn skin_keeps_the_skeletons_names_and_weights_only_deforming_joints() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = bundled().join("mesh.obj");
    let rig = bundled().join("rig_game_engine.json");
    let glb = dir.path().join("skinned.glb");
    let json = dir.path().join("skinned.json");
    let out = skelfit(&[
        "skin",
        mesh.to_str().unwrap(),
        "--skeleton",
        rig.to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
        "--skeleton-json",
        json.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let reference = load_skeleton(&rig).unwrap().skeleton;
    let scene = load_gltf_scene(&glb).unwrap();
    let written = scene.skeleton.as_ref().unwrap();
    assert_eq!(hierarchy(written), hierarchy(&reference));
    // Positions as given (f32 in the file).
    for (a, b) in written.joints.iter().zip(&reference.joints) {
        assert!((a.position - b.position).length() < 1e-5, "{}", a.name);
    }
    // The glTF reader marks a joint deforming iff some vertex has weight on it: the control
    // joint `Root` has none.
    for (a, b) in written.joints.iter().zip(&reference.joints) {
        if !b.deform {
            assert!(!a.deform, "control joint {} carries weight", a.name);
        }
    }
    assert_eq!(
        scene.mesh.positions.len(),
        load(&mesh).unwrap().positions.len()
    );
    assert!(scene.weights.unwrap().iter().all(|w| !w.is_empty()));
    let written_json = load_skeleton(&json).unwrap();
    assert_eq!(hierarchy(&written_json.skeleton), hierarchy(&reference));
    assert_eq!(written_json.canonical.len(), 21);
    // skelfit's own rig of this mesh tears 20 edges past 2x over the sweep
    // (reports/deformation); MakeHuman's own game_engine skeleton with the same weights tears
    // 19 (hip abduction).
    let (over_2, poses) = stretched_edges(&glb, &rig);
    assert_eq!(poses, 14);
    assert!(over_2 <= 30, "{over_2} edges past 2x");
}

#[test]
fn skin_skeleton_weights_are_a_partition_of_one_on_deforming_joints() {
    let mesh = load(&bundled().join("mesh.obj")).unwrap();
    let rig = load_skeleton(&bundled().join("rig_game_engine.json")).unwrap();
    let skinned = skin_skeleton(&mesh, &rig.skeleton, &SkeletonSkinOptions::default()).unwrap();
    assert!(skinned.warnings.is_empty(), "{:?}", skinned.warnings);
    let engine = &skinned.skin.engine;
    assert_eq!(engine.weights.len(), mesh.positions.len());
    for (v, (joints, weights)) in engine.joints.iter().zip(&engine.weights).enumerate() {
        let sum: f32 = weights.iter().sum();
        assert!((sum - 1.0).abs() < 1e-5, "vertex {v}: weights sum to {sum}");
        assert!(weights.iter().all(|&w| w >= 0.0), "vertex {v}");
        let used: Vec<_> = joints
            .iter()
            .zip(weights)
            .filter(|(_, &w)| w > 0.0)
            .collect();
        assert!(!used.is_empty() && used.len() <= 4, "vertex {v}");
        for (&j, _) in used {
            assert!(rig.skeleton.joints[usize::from(j)].deform, "vertex {v}");
        }
    }
    for weights in &skinned.skin.weights {
        assert!(weights
            .iter()
            .all(|&(j, w)| w > 0.0 && rig.skeleton.joint(j).deform));
    }
}

#[test]
fn skin_on_an_artists_gltf_skeleton_keeps_its_names_and_deforms_cleanly() {
    let Some(model) = crate::common::model("humanoid/gltf_cesium_man") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("cesium.glb");
    let out = skelfit(&[
        "skin",
        model.join("mesh.obj").to_str().unwrap(),
        "--skeleton",
        model.join("source.glb").to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let source = load_gltf_scene(&model.join("source.glb")).unwrap();
    let written = load_gltf_scene(&glb).unwrap();
    assert_eq!(
        hierarchy(written.skeleton.as_ref().unwrap()),
        hierarchy(source.skeleton.as_ref().unwrap())
    );
    // The joints keep the artist's rest rotations (rest = bind pose in this file), so
    // animations made for the skeleton play: every joint node below the root turns as in
    // the source file.
    let rotations = |path: &Path| -> BTreeMap<String, [f32; 4]> {
        let (document, _, _) = gltf::import(path).unwrap();
        document
            .nodes()
            .filter_map(|n| Some((n.name()?.to_string(), n.transform().decomposed().1)))
            .collect()
    };
    let (source_rotations, written_rotations) =
        (rotations(&model.join("source.glb")), rotations(&glb));
    let skeleton = source.skeleton.as_ref().unwrap();
    for joint in skeleton.joints.iter().filter(|j| j.parent.is_some()) {
        let (a, b) = (
            source_rotations[&joint.name],
            written_rotations[&joint.name],
        );
        let dot: f32 = a.iter().zip(b).map(|(x, y)| x * y).sum();
        assert!(dot.abs() > 0.9999, "{}: {a:?} vs {b:?}", joint.name);
    }
    // The artist's weights tear 8 edges past 2x over this sweep (reports/deformation).
    let (over_2, poses) = stretched_edges(&glb, &model.join("rig_gltf.json"));
    assert_eq!(poses, 14);
    assert!(over_2 <= 8, "{over_2} edges past 2x");
}

/// The bundled rig with `edit` applied to its JSON, written to `dir`.
fn edited_rig(dir: &Path, name: &str, edit: impl FnOnce(&mut serde_json::Value)) -> PathBuf {
    let text = std::fs::read_to_string(bundled().join("rig_game_engine.json")).unwrap();
    let mut rig: serde_json::Value = serde_json::from_str(&text).unwrap();
    edit(&mut rig);
    let path = dir.join(format!("{name}.json"));
    std::fs::write(&path, serde_json::to_string(&rig).unwrap()).unwrap();
    path
}

fn joint<'a>(rig: &'a mut serde_json::Value, name: &str) -> &'a mut serde_json::Value {
    rig["joints"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|j| j["name"] == name)
        .unwrap()
}

/// Runs `skelfit skin` of the bundled mesh on `rig`; returns the output and whether the .glb
/// was written.
fn skin_with(dir: &Path, rig: &Path) -> (Output, bool) {
    let glb = dir.join(format!(
        "{}.glb",
        rig.file_stem().unwrap().to_string_lossy()
    ));
    let bvh = glb.with_extension("bvh");
    let out = skelfit(&[
        "skin",
        bundled().join("mesh.obj").to_str().unwrap(),
        "--skeleton",
        rig.to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
        "--bvh",
        bvh.to_str().unwrap(),
    ]);
    let written = glb.exists();
    assert_eq!(written, bvh.exists(), "half an output set");
    (out, written)
}

#[test]
fn bad_skeletons_are_refused_with_the_joint_named_and_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let duplicate = edited_rig(d, "duplicate", |rig| {
        joint(rig, "calf_r")["name"] = "calf_l".into();
    });
    let centimetres = edited_rig(d, "centimetres", |rig| {
        for j in rig["joints"].as_array_mut().unwrap() {
            for c in j["position"].as_array_mut().unwrap() {
                *c = (c.as_f64().unwrap() * 100.0).into();
            }
        }
    });
    let moved = edited_rig(d, "moved", |rig| {
        for j in rig["joints"].as_array_mut().unwrap() {
            let x = j["position"][0].as_f64().unwrap();
            j["position"][0] = (x + 3.0).into();
        }
    });
    let controls = edited_rig(d, "controls", |rig| {
        for j in rig["joints"].as_array_mut().unwrap() {
            j["deform"] = false.into();
        }
    });
    for (rig, expected) in [
        (&duplicate, vec!["calf_l", "twice"]),
        (
            &centimetres,
            vec!["100 times too large", "--skeleton-scale 0.01"],
        ),
        (&moved, vec!["inside the mesh", "frame"]),
        (&controls, vec!["deform"]),
    ] {
        let (out, written) = skin_with(d, rig);
        let message = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{}: {message}", rig.display());
        assert!(!written, "{}", rig.display());
        assert!(!message.contains("panicked"), "{message}");
        for e in expected {
            assert!(
                message.contains(e),
                "{}: {e:?} not in {message}",
                rig.display()
            );
        }
    }
    // With the scale the message names, the skeleton in centimetres skins.
    let glb = d.join("scaled.glb");
    let out = skelfit(&[
        "skin",
        bundled().join("mesh.obj").to_str().unwrap(),
        "--skeleton",
        centimetres.to_str().unwrap(),
        "--skeleton-scale",
        "0.01",
        "-o",
        glb.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn doubtful_skeletons_skin_with_warnings_naming_the_joints() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let zero = edited_rig(d, "zero", |rig| {
        let p = joint(rig, "spine_01")["position"].clone();
        joint(rig, "spine_02")["position"] = p;
    });
    let outside = edited_rig(d, "outside", |rig| {
        let z = joint(rig, "head")["position"][2].as_f64().unwrap();
        joint(rig, "head")["position"][2] = (z + 0.5).into();
    });
    let crossing = edited_rig(d, "crossing", |rig| {
        joint(rig, "ball_r")["parent"] = "foot_l".into();
    });
    for (rig, expected) in [
        (&zero, vec!["spine_02 sits on its parent spine_01"]),
        (&outside, vec!["outside the mesh: head"]),
        (&crossing, vec!["foot_l -> ball_r", "empty space"]),
    ] {
        let (out, written) = skin_with(d, rig);
        let message = stderr(&out);
        assert!(out.status.success(), "{}: {message}", rig.display());
        assert!(written);
        for e in expected {
            assert!(
                message.contains(e),
                "{}: {e:?} not in {message}",
                rig.display()
            );
        }
    }
    // The bundled rig itself draws no warning.
    let (out, _) = skin_with(d, &bundled().join("rig_game_engine.json"));
    assert!(out.status.success());
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
}

#[test]
fn skin_reads_bvh_skeletons_and_refuses_gltf_skins_with_duplicate_names() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mesh = bundled().join("mesh.obj");
    let (first, bvh) = (d.join("first.glb"), d.join("first.bvh"));
    let out = skelfit(&[
        "skin",
        mesh.to_str().unwrap(),
        "--skeleton",
        bundled().join("rig_game_engine.json").to_str().unwrap(),
        "-o",
        first.to_str().unwrap(),
        "--bvh",
        bvh.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    // A BVH skeleton: every joint of the rig keeps its name and parent.
    let from_bvh = d.join("from_bvh.glb");
    let out = skelfit(&[
        "skin",
        mesh.to_str().unwrap(),
        "--skeleton",
        bvh.to_str().unwrap(),
        "-o",
        from_bvh.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let written = hierarchy(&load_gltf_scene(&from_bvh).unwrap().skeleton.unwrap());
    for joint in hierarchy(&load_skeleton(&bvh).unwrap().skeleton) {
        assert!(written.contains(&joint), "{joint:?}");
    }
    // The same .glb with two joints called calf_l (the name has the same length, so the GLB
    // chunk sizes stay right).
    let mut bytes = std::fs::read(&first).unwrap();
    let needle = br#""name":"calf_r""#;
    let at = bytes
        .windows(needle.len())
        .position(|w| w == needle)
        .expect("the joint node's name");
    bytes[at..at + needle.len()].copy_from_slice(br#""name":"calf_l""#);
    let duplicate = d.join("duplicate.glb");
    std::fs::write(&duplicate, &bytes).unwrap();
    let output = d.join("never.glb");
    let out = skelfit(&[
        "skin",
        mesh.to_str().unwrap(),
        "--skeleton",
        duplicate.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("called calf_l"), "{}", stderr(&out));
    assert!(!output.exists());
}

//! Integration tests of the eval stage.

use crate::common;
use skelfit::eval::{
    evaluate, load_skeleton, EvalError, EvalOptions, FigureMeasure, MatchMethod, RigFormat,
    SizeSource,
};
use std::path::Path;

/// The `scale_applied` recorded in a refdata model's provenance.json (1 when absent).
fn provenance_scale(dir: &Path) -> f64 {
    let text = std::fs::read_to_string(dir.join("provenance.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    json["scale_applied"].as_f64().unwrap_or(1.0)
}

fn gltf_matches_json(model: &str) {
    let Some(dir) = common::model(model) else {
        return;
    };
    let json = load_skeleton(&dir.join("rig_gltf.json")).unwrap();
    let gltf = load_skeleton(&dir.join("source.glb")).unwrap();
    assert_eq!(json.format, RigFormat::Refdata);
    assert_eq!(gltf.format, RigFormat::Gltf);
    assert_eq!(gltf.skeleton.joints.len(), json.skeleton.joints.len());
    let scale = provenance_scale(&dir);
    for joint in &json.skeleton.joints {
        let id = gltf
            .skeleton
            .find(&joint.name)
            .unwrap_or_else(|| panic!("{model}: glTF lacks joint {}", joint.name));
        let other = gltf.skeleton.joint(id);
        let distance = (other.position * scale - joint.position).length();
        assert!(distance < 1e-4, "{model} {}: {distance}", joint.name);
        assert_eq!(other.deform, joint.deform, "{model} {}", joint.name);
        let parent_name = |s: &skelfit::skeleton::Skeleton,
                           p: Option<skelfit::skeleton::JointId>| {
            p.map(|p| s.joint(p).name.clone())
        };
        assert_eq!(
            parent_name(&gltf.skeleton, other.parent),
            parent_name(&json.skeleton, joint.parent),
            "{model} {}",
            joint.name
        );
    }
}

#[test]
fn gltf_reference_joints_agree_with_json_fox() {
    gltf_matches_json("quadruped/khronos_fox");
}

#[test]
fn gltf_reference_joints_agree_with_json_cesium_man() {
    gltf_matches_json("humanoid/gltf_cesium_man");
}

#[test]
fn gltf_reference_joints_agree_with_json_horse() {
    gltf_matches_json("quadruped/quaternius_horse");
}

#[test]
fn refdata_rig_against_itself_with_mesh() {
    let Some(dir) = common::model("quadruped/khronos_fox") else {
        return;
    };
    let rig = load_skeleton(&dir.join("rig_gltf.json")).unwrap();
    assert_eq!(rig.canonical.len(), 23);
    let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).unwrap();
    let e = evaluate(&rig, &rig, Some(&mesh), &EvalOptions::default()).unwrap();
    assert_eq!(e.method, MatchMethod::Canonical);
    // 22 anatomical keys (root_control names a control joint and is not canonical).
    assert_eq!(e.joints.len(), 22);
    assert_eq!(e.summary.max, 0.0);
    // The fox is a quadruped: body length, measured on the mesh.
    assert_eq!(e.figure.measure, FigureMeasure::LongestSide);
    assert_eq!(e.figure.source, SizeSource::Mesh);
    assert!(e.warnings.is_empty(), "{:?}", e.warnings);
}

#[test]
fn different_rigs_of_one_model_pair_by_canonical_keys() {
    let Some(dir) = common::model("humanoid/mh_male_young_average") else {
        return;
    };
    let game = load_skeleton(&dir.join("rig_game_engine.json")).unwrap();
    let mixamo = load_skeleton(&dir.join("rig_mixamo.json")).unwrap();
    let e = evaluate(&mixamo, &game, None, &EvalOptions::default()).unwrap();
    // 21 body joints and the 30 digit joints both rigs carry.
    assert_eq!(
        e.joints.len(),
        21 + skelfit::skeleton::canonical::DIGITS.len()
    );
    assert_eq!(e.figure.measure, FigureMeasure::Height);
    // Same body, two rigs: hips and knees agree to within a few percent of height.
    let knee = e.joints.iter().find(|j| j.key == "knee_L").unwrap();
    assert!(knee.error_percent < 5.0, "{}", knee.error_percent);
    // Dropping the file's canonical maps, the naming presets recover the same pairing.
    let (mut bare_game, mut bare_mixamo) = (game.clone(), mixamo.clone());
    bare_game.canonical.clear();
    bare_mixamo.canonical.clear();
    let again = evaluate(&bare_mixamo, &bare_game, None, &EvalOptions::default()).unwrap();
    assert_eq!(again.joints.len(), e.joints.len());
    for (a, b) in again.joints.iter().zip(&e.joints) {
        assert_eq!((&a.key, &a.reference_joint), (&b.key, &b.reference_joint));
        assert_eq!(a.predicted_joint, b.predicted_joint);
    }
}

#[test]
fn every_refdata_rig_loads() {
    let Some(root) = common::refdata() else {
        return;
    };
    let mut count = 0;
    for group in std::fs::read_dir(&root).unwrap().flatten() {
        let Ok(models) = std::fs::read_dir(group.path()) else {
            continue;
        };
        for model in models.flatten() {
            for file in std::fs::read_dir(model.path())
                .into_iter()
                .flatten()
                .flatten()
            {
                let path = file.path();
                let name = path.file_name().unwrap().to_string_lossy().into_owned();
                if name.starts_with("rig_") && name.ends_with(".json") {
                    let rig =
                        load_skeleton(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                    assert!(rig.deforming_count() > 0, "{}", path.display());
                    count += 1;
                }
            }
        }
    }
    assert!(count > 20, "only {count} rigs found");
}

#[test]
fn missing_file_is_a_clear_error() {
    let err = load_skeleton(Path::new("/definitely/not/here/rig_gltf.json")).unwrap_err();
    assert!(matches!(err, EvalError::Io { .. }));
    let message = err.to_string();
    assert!(
        message.contains("/definitely/not/here/rig_gltf.json"),
        "{message}"
    );
    let err = load_skeleton(Path::new("/definitely/not/here/source.glb")).unwrap_err();
    assert!(err.to_string().contains("source.glb"), "{err}");
}

#[test]
fn bvh_file_loads() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("pose.bvh");
    std::fs::write(
        &path,
        "HIERARCHY\nROOT Hips\n{\n OFFSET 0 1 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n End Site\n {\n  OFFSET 0 0.5 0\n }\n}\nMOTION\nFrames: 0\n",
    )
    .unwrap();
    let rig = load_skeleton(&path).unwrap();
    assert_eq!(rig.skeleton.joints.len(), 2);
    assert_eq!(rig.skeleton.joints[1].name, "Hips_end");
}

#[test]
fn bundled_data_evaluates_and_reports() {
    let dir = common::data_dir().join("humanoid/mh_neutral_default");
    let reference = load_skeleton(&dir.join("rig_game_engine.json")).unwrap();
    let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).unwrap();
    // A prediction 1 cm off along +Z everywhere.
    let mut predicted = reference.clone();
    for joint in &mut predicted.skeleton.joints {
        joint.position.z += 0.01;
    }
    let e = evaluate(&predicted, &reference, Some(&mesh), &EvalOptions::default()).unwrap();
    // 21 body joints and the 30 digit joints both rigs carry.
    assert_eq!(
        e.joints.len(),
        21 + skelfit::skeleton::canonical::DIGITS.len()
    );
    assert!((e.summary.max - 0.01).abs() < 1e-12 && (e.summary.median - 0.01).abs() < 1e-12);
    assert_eq!(e.figure.source, SizeSource::Mesh);
    let (min, max) = mesh.bounding_box().unwrap();
    assert!((e.figure.size - (max.y - min.y)).abs() < 1e-12);
    let html = skelfit::report::html_report(
        &skelfit::report::ReportInput {
            evaluation: &e,
            predicted: &predicted.deforming(),
            reference: &reference.deforming(),
            mesh: Some(&mesh),
        },
        &Default::default(),
    );
    assert_eq!(html.matches("<svg").count(), 4);
}

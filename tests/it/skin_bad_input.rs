//! `skelfit skin MESH --skeleton SKELETON` on a skeleton that is not in the mesh's place: the
//! error names the joints found outside (issue 20's bad-input must-show; the other bad inputs,
//! duplicate names, other units, zero-length bones and bones through empty space, are in
//! `skin_skeleton.rs`).

use std::path::PathBuf;
use std::process::Command;

fn bundled() -> PathBuf {
    crate::common::data_dir().join("humanoid/mh_neutral_default")
}

#[test]
fn a_skeleton_outside_the_mesh_is_refused_naming_the_joints_outside() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(bundled().join("rig_game_engine.json")).unwrap();
    let mut rig: serde_json::Value = serde_json::from_str(&text).unwrap();
    for j in rig["joints"].as_array_mut().unwrap() {
        let y = j["position"][1].as_f64().unwrap();
        j["position"][1] = (y + 5.0).into();
    }
    let skeleton = dir.path().join("above.json");
    std::fs::write(&skeleton, serde_json::to_string(&rig).unwrap()).unwrap();
    let glb = dir.path().join("above.glb");
    let out = Command::new(env!("CARGO_BIN_EXE_skelfit"))
        .args([
            "skin",
            bundled().join("mesh.obj").to_str().unwrap(),
            "--skeleton",
            skeleton.to_str().unwrap(),
            "-o",
            glb.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let message = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{message}");
    assert!(!glb.exists());
    assert!(!message.contains("panicked"), "{message}");
    // `Root` is a control joint: the first deforming joints are named, the rest counted.
    for expected in [
        "outside: pelvis, thigh_l, calf_l, foot_l, ball_l and ",
        " more",
        "inside the mesh",
    ] {
        assert!(message.contains(expected), "{expected:?} not in {message}");
    }
    assert!(!message.contains("Root"), "{message}");
}

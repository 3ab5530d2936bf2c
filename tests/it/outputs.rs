//! Safe outputs (issue 22): `-o` onto an input is refused with exit code 2 and the input left
//! untouched; `.gltf` writes glTF JSON with the data embedded, `.glb` binary; another
//! extension is refused naming the accepted ones.

use crate::common::{skelfit, stderr};
use std::path::Path;

/// A copy of the bundled humanoid in `dir`.
fn humanoid_copy(dir: &Path) -> String {
    let path = dir.join("body.obj");
    std::fs::copy(
        crate::common::data_dir().join("humanoid/mh_neutral_default/mesh.obj"),
        &path,
    )
    .unwrap();
    path.display().to_string()
}

#[test]
fn an_output_onto_the_input_is_refused_with_exit_code_two_and_the_input_kept() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = humanoid_copy(dir.path());
    let before = std::fs::read(&mesh).unwrap();
    let sneaky = dir.path().join(".").join("body.obj").display().to_string();
    for args in [
        vec!["rig", &mesh, "-o", &mesh],
        vec!["rig", &mesh, "-o", &sneaky],
        vec!["skeleton", &mesh, "-o", &mesh],
        vec!["bones", &mesh, "-o", &mesh],
    ] {
        let out = skelfit(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains("also an input"), "{}", stderr(&out));
        assert_eq!(
            std::fs::read(&mesh).unwrap(),
            before,
            "{args:?} touched the input"
        );
    }
    let glb = dir.path().join("out.glb").display().to_string();
    let out = skelfit(&["rig", &mesh, "-o", &glb, "--skeleton-json", &mesh]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert_eq!(std::fs::read(&mesh).unwrap(), before);
    assert!(!Path::new(&glb).exists(), "nothing is written");
}

#[test]
fn an_unknown_output_extension_is_refused_naming_the_accepted_ones() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = humanoid_copy(dir.path());
    for name in ["out.fbx", "out", "out.obj"] {
        let path = dir.path().join(name).display().to_string();
        let out = skelfit(&["rig", &mesh, "-o", &path]);
        assert_eq!(out.status.code(), Some(2), "{name}: {}", stderr(&out));
        let err = stderr(&out);
        assert!(err.contains(".glb") && err.contains(".gltf"), "{err}");
        assert!(!Path::new(&path).exists());
    }
}

#[test]
fn gltf_output_is_json_with_embedded_data_and_glb_is_binary() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = humanoid_copy(dir.path());
    let gltf = dir.path().join("out.gltf");
    let glb = dir.path().join("out.glb");
    for path in [&gltf, &glb] {
        let out = skelfit(&["rig", &mesh, "-o", path.to_str().unwrap()]);
        assert!(out.status.success(), "{}", stderr(&out));
    }
    let text = std::fs::read(&gltf).unwrap();
    let json: serde_json::Value = serde_json::from_slice(&text).expect(".gltf is JSON");
    let uri = json["buffers"][0]["uri"].as_str().unwrap();
    assert!(uri.starts_with("data:application/octet-stream;base64,"));
    assert!(std::fs::read(&glb).unwrap().starts_with(b"glTF"));
    // Both hold the same rig.
    let from_text = skelfit::mesh::load_gltf_scene(&gltf).unwrap();
    let from_binary = skelfit::mesh::load_gltf_scene(&glb).unwrap();
    assert_eq!(from_text, from_binary);
    if let Some(report) = crate::export::validate(&[gltf, glb]) {
        assert_eq!(report.matches("numErrors=0 ").count(), 2, "{report}");
    }
}

//! Frames and units of the written .glb (issue 22): glTF's +Y up, +Z forward, metres, the rig
//! fitted in the mesh's own frame and the whole result turned and scaled on output, unless
//! `--keep-frame`.

use crate::common;
use glam::DVec3;
use skelfit::mesh::load_gltf_scene;
use std::fmt::Write;
use std::path::Path;

/// The bundled humanoid (+Y up, +Z forward, metres) written as OBJ with every position mapped
/// by `f`.
fn humanoid_copy(path: &Path, f: impl Fn(DVec3) -> DVec3) {
    let mesh =
        skelfit::mesh::load(&common::data_dir().join("humanoid/mh_neutral_default/mesh.obj"))
            .unwrap();
    let mut text = String::new();
    for p in &mesh.positions {
        let q = f(*p);
        writeln!(text, "v {} {} {}", q.x, q.y, q.z).unwrap();
    }
    for t in &mesh.triangles {
        writeln!(text, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1).unwrap();
    }
    std::fs::write(path, text).unwrap();
}

/// Runs `skelfit rig` and returns its stdout; panics on failure.
fn rig(args: &[&str]) -> String {
    let out = common::skelfit(&[&["rig"], args].concat());
    assert!(out.status.success(), "{}", common::stderr(&out));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The rest position of joint `name` in the written file.
fn joint(scene: &skelfit::mesh::GltfScene, name: &str) -> DVec3 {
    let skeleton = scene.skeleton.as_ref().unwrap();
    skeleton.joint(skeleton.find(name).unwrap()).position
}

/// Height of the mesh along +Y.
fn height_y(scene: &skelfit::mesh::GltfScene) -> f64 {
    let (min, max) = scene.mesh.bounding_box().unwrap();
    max.y - min.y
}

#[test]
fn a_z_up_millimetre_body_becomes_a_y_up_metre_glb() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("z_up_mm.obj");
    // Blender's convention: +Z up, -Y forward; and millimetres.
    humanoid_copy(&input, |p| DVec3::new(p.x, -p.z, p.y) * 1000.0);
    let glb = dir.path().join("out.glb");
    let stdout = rig(&[
        input.to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
        "--up",
        "+Z",
        "--forward",
        "-Y",
    ]);
    assert!(stdout.contains("units mm guessed"), "{stdout}");
    let scene = load_gltf_scene(&glb).unwrap();
    let head = joint(&scene, "head");
    let ankle = joint(&scene, "ankle_L");
    assert!(
        head.y > ankle.y + 1.0,
        "head {head} above ankle {ankle} along +Y"
    );
    let height = height_y(&scene);
    assert!((1.5..1.9).contains(&height), "{height} m tall");
    // The figure faces +Z: its toes are in front of its ankles.
    assert!(joint(&scene, "toe_L").z > ankle.z, "faces +Z");
    // Its left (+X of the input) stays +X.
    assert!(joint(&scene, "shoulder_L").x > 0.0);
    if let Some(report) = crate::export::validate(&[glb]) {
        assert!(report.contains("numErrors=0 "), "{report}");
    }
}

#[test]
fn millimetres_are_guessed_and_keep_frame_keeps_them() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("mm.obj");
    humanoid_copy(&input, |p| p * 1000.0);
    let auto = dir.path().join("auto.glb");
    let kept = dir.path().join("kept.glb");
    let given = dir.path().join("cm.glb");
    rig(&[
        input.to_str().unwrap(),
        "-o",
        auto.to_str().unwrap(),
        "--units",
        "auto",
    ]);
    rig(&[
        input.to_str().unwrap(),
        "-o",
        kept.to_str().unwrap(),
        "--keep-frame",
    ]);
    rig(&[
        input.to_str().unwrap(),
        "-o",
        given.to_str().unwrap(),
        "--units",
        "cm",
    ]);
    let metres = height_y(&load_gltf_scene(&auto).unwrap());
    let millimetres = height_y(&load_gltf_scene(&kept).unwrap());
    let as_cm = height_y(&load_gltf_scene(&given).unwrap());
    assert!((1.5..1.9).contains(&metres), "{metres}");
    assert!(
        (millimetres / metres - 1000.0).abs() < 1e-3,
        "{millimetres}"
    );
    assert!((as_cm / metres - 10.0).abs() < 1e-6, "{as_cm}");
}

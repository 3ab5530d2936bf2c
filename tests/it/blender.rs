//! The Blender add-on (`integrations/blender/`), headless: `test_addon.py` installs the add-on
//! from the zip `make_zip.py` builds, rigs the bundled MakeHuman body and a multi-part real game
//! character with `bpy.ops.skelfit.rig()`, and checks the armature (>= 20 bones), the vertex
//! groups (every vertex weighted), the materials (kept) and the Armature modifier. Skips with a
//! printed reason when `blender` is not on PATH. `tools/blender_textured.py` checks that a
//! rigged CesiumMan comes into Blender textured and skinned.

use std::path::{Path, PathBuf};
use std::process::Command;

use super::common;

/// `blender` on PATH, or `None` with the reason printed.
fn blender() -> Option<PathBuf> {
    let found = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join("blender"))
            .find(|candidate| candidate.is_file())
    });
    if found.is_none() {
        eprintln!(
            "SKIPPED: blender is not on PATH (apt-get install blender to run the add-on test)"
        );
    }
    found
}

#[test]
fn blender_addon_rigs_meshes_headless() {
    let Some(blender) = blender() else { return };
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut meshes = vec![root.join("data/humanoid/mh_neutral_default/mesh.obj")];
    match common::model("humanoid/quaternius_men_adventurer") {
        Some(dir) => meshes.push(dir.join("source.glb")),
        None => eprintln!("SKIPPED in blender: the multi-part character needs ../shared/refdata"),
    }
    // A scratch user folder: the script installs the add-on's zip there, as a user would.
    let user = tempfile::tempdir().unwrap();
    let output = Command::new(blender)
        .args(["-b", "--factory-startup", "--python"])
        .arg(root.join("integrations/blender/test_addon.py"))
        .arg("--")
        .arg(env!("CARGO_BIN_EXE_skelfit"))
        .args(&meshes)
        .env("BLENDER_USER_SCRIPTS", user.path().join("scripts"))
        .env("BLENDER_USER_CONFIG", user.path().join("config"))
        .env_remove("SKELFIT_BIN")
        .output()
        .expect("run blender");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    let passes: Vec<&str> = stdout.lines().filter(|l| l.starts_with("PASS ")).collect();
    for line in &passes {
        eprintln!("{line}");
    }
    assert!(
        output.status.success() && passes.len() == meshes.len(),
        "the Blender add-on test failed ({}):\n{stdout}\n{stderr}",
        output.status
    );
    assert!(
        stdout.contains("add-on installed from"),
        "the add-on was not installed from its zip:\n{stdout}"
    );
}

/// Rigging CesiumMan's `source.glb` keeps its texture (issue 22): Blender imports the rigged
/// .glb headless with all 3,273 of the source's vertices, a UV layer, the image texture with its
/// pixels in the material, and the mesh skinned to the armature (`tools/blender_textured.py`).
#[test]
fn blender_imports_the_rigged_cesium_man_textured() {
    let Some(blender) = blender() else { return };
    let Some(dir) = common::model("humanoid/gltf_cesium_man") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    let rigged = out.path().join("cesium_man.glb");
    let status = Command::new(env!("CARGO_BIN_EXE_skelfit"))
        .args(["rig", "-q"])
        .arg(dir.join("source.glb"))
        .arg("-o")
        .arg(&rigged)
        .status()
        .unwrap();
    assert!(status.success(), "skelfit rig failed");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let output = Command::new(blender)
        .args(["-b", "--factory-startup", "--python"])
        .arg(root.join("tools/blender_textured.py"))
        .arg("--")
        .arg(&rigged)
        .arg("3273")
        .output()
        .expect("run blender");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success() && stdout.contains("PASS "),
        "Blender did not import the rigged CesiumMan textured ({}):\n{stdout}\n{}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
}

//! End-to-end tests of the `skelfit` binary: outputs, errors and exit codes.

use crate::common::{skelfit, stderr};
use std::path::Path;

fn bundled_humanoid() -> String {
    crate::common::data_dir()
        .join("humanoid/mh_neutral_default/mesh.obj")
        .display()
        .to_string()
}

#[test]
fn info_prints_json_stats_of_the_bundled_humanoid() {
    let out = skelfit(&["info", &bundled_humanoid(), "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let stats: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(stats["triangles"], 26756);
    assert_eq!(stats["closed"], true);
}

#[test]
fn voxelize_reports_volume_and_writes_slices() {
    let dir = tempfile::tempdir().unwrap();
    let slices = dir.path().join("slices");
    let out = skelfit(&[
        "voxelize",
        &bundled_humanoid(),
        "--resolution",
        "96",
        "--json",
        "--slices",
        slices.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let interior = summary["interior_volume"].as_f64().unwrap();
    let mesh = summary["mesh_volume"].as_f64().unwrap();
    assert!((interior - mesh).abs() / mesh < 0.05);
    assert!(summary["max_inscribed_radius"].as_f64().unwrap() > 0.05);
    let pngs = std::fs::read_dir(&slices).unwrap().count();
    assert_eq!(pngs, 7);
    for entry in std::fs::read_dir(&slices).unwrap() {
        let bytes = std::fs::read(entry.unwrap().path()).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
    }
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> String {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path.display().to_string()
}

#[test]
fn bad_inputs_exit_one_with_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let cases: Vec<(String, &str)> = vec![
        (
            dir.path().join("missing.obj").display().to_string(),
            "cannot read",
        ),
        (write(dir.path(), "empty.obj", b""), "no triangles"),
        (
            write(
                dir.path(),
                "garbage.glb",
                &[0xde, 0xad, 0xbe, 0xef, 7, 7, 7],
            ),
            "not a valid",
        ),
        (write(dir.path(), "garbage.stl", &[1, 2, 3]), "not a valid"),
        (
            write(
                dir.path(),
                "nan.obj",
                b"v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n",
            ),
            "non-finite",
        ),
        (
            write(
                dir.path(),
                "range.obj",
                b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
            ),
            "vertex",
        ),
        (
            write(
                dir.path(),
                "flat.obj",
                b"v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n",
            ),
            "zero area",
        ),
        (
            write(dir.path(), "unknown.xyz", b"1 2 3"),
            "unknown mesh format",
        ),
    ];
    for (path, expected) in cases {
        let out = skelfit(&["voxelize", &path]);
        assert_eq!(out.status.code(), Some(1), "{path}: {}", stderr(&out));
        let err = stderr(&out);
        assert!(err.starts_with("skelfit: error: "), "{path}: {err}");
        assert!(
            err.to_lowercase().contains(expected),
            "{path}: expected '{expected}' in {err}"
        );
        assert!(!err.contains("panicked"), "{path}: {err}");
    }
    // A single triangle loads but cannot be voxelized.
    let single = write(
        dir.path(),
        "single.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0.5\nf 1 2 3\n",
    );
    let out = skelfit(&["voxelize", &single]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("no voxel lies inside"),
        "{}",
        stderr(&out)
    );
    // The voxel budget names a size that fits.
    let out = skelfit(&[
        "voxelize",
        &bundled_humanoid(),
        "--resolution",
        "2000",
        "--max-voxels",
        "1000000",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("exceeds the budget"),
        "{}",
        stderr(&out)
    );
    // Usage errors exit 2.
    let out = skelfit(&["voxelize"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn rig_writes_a_skinned_glb_json_with_canonical_map_and_bvh_in_a_preset() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = crate::common::data_dir().join("quadruped/quaternius_horse/mesh.obj");
    let glb = dir.path().join("horse.glb");
    let json = dir.path().join("horse.json");
    let bvh = dir.path().join("horse.bvh");
    let out = skelfit(&[
        "rig",
        mesh.to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
        "--skeleton-json",
        json.to_str().unwrap(),
        "--bvh",
        bvh.to_str().unwrap(),
        "--preset",
        "mixamo",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(&std::fs::read(&glb).unwrap()[0..4], b"glTF");
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(doc["run"]["template"], "quadruped");
    let canonical = doc["canonical"].as_object().unwrap();
    assert_eq!(canonical["pelvis"], "mixamorig:Hips");
    for key in ["shoulder_L", "hip_R"] {
        assert!(canonical.contains_key(key), "{key} missing: {canonical:?}");
    }
    // Mixamo's skeleton has no tail: the tail is left out, and the output says so.
    assert!(!canonical.contains_key("tail_base"), "{canonical:?}");
    assert!(
        stderr(&out).contains("the mixamo skeleton has no joint for")
            && stderr(&out).contains("tail_base"),
        "{}",
        stderr(&out)
    );
    assert!(std::fs::read_to_string(&bvh)
        .unwrap()
        .starts_with("HIERARCHY"));
    // The rig reloads as a reference rig with the same canonical joints.
    let reloaded = skelfit::eval::load_skeleton(&json).unwrap();
    assert_eq!(reloaded.canonical.len(), canonical.len());
}

#[test]
fn rig_refuses_an_unknown_template_and_a_missing_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("out.glb");
    let out = skelfit(&[
        "rig",
        &bundled_humanoid(),
        "-o",
        glb.to_str().unwrap(),
        "--template",
        "centaur",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("not a built-in template"),
        "{}",
        stderr(&out)
    );
    assert!(!glb.exists());
    let out = skelfit(&["rig", "/nonexistent/mesh.obj", "-o", glb.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("skelfit: error:"));
    assert!(!glb.exists());
}

/// A Z-up file: `skelfit rig` with no orientation flags finds +Z up and says so (no hint);
/// read as +Y up (`--up +Y`) it lies on its back and labels as no complete body plan: the rig
/// says so and names `--up`; with `--up +Z --forward -Y` the hint goes away, and the upright
/// file never gets it.
#[test]
fn rig_finds_the_up_axis_of_a_z_up_file_and_hints_when_told_a_wrong_one() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = skelfit::mesh::load(Path::new(&bundled_humanoid())).unwrap();
    let lying = mesh.transformed(|p| glam::DVec3::new(p.x, -p.z, p.y));
    let path = dir.path().join("z_up.obj");
    skelfit::export::write_obj(&path, &lying).unwrap();
    let path = path.display().to_string();
    let out_glb = dir.path().join("out.glb").display().to_string();
    let run = |args: &[&str]| {
        let out = skelfit(args);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        stderr(&out)
    };
    let hint = |text: &str| text.contains("skelfit: hint:") && text.contains("--up");
    let found = run(&["rig", &path, "-o", &out_glb]);
    assert!(
        !hint(&found) && found.contains("up is +Z (found automatically"),
        "{found}"
    );
    assert!(hint(&run(&["rig", &path, "-o", &out_glb, "--up", "+Y"])));
    assert!(!hint(&run(&[
        "rig",
        &path,
        "-o",
        &out_glb,
        "--up",
        "+Z",
        "--forward",
        "-Y"
    ])));
    assert!(!hint(&run(&["rig", &bundled_humanoid(), "-o", &out_glb])));
}

/// `skelfit check` on the bundled body's rig: the standard humanoid sweep, every pose posed,
/// and the skin torn nowhere worse than 0.1 % of the edges over the whole sweep (20 of 40,134
/// measured; the dissertation's anchor weights tore 1,008).
#[test]
fn check_poses_the_bundled_rig_through_the_sweep_without_tearing() {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("rig.glb");
    let report = dir.path().join("check.json");
    let body = crate::common::data_dir().join("humanoid/mh_neutral_default/mesh.obj");
    let o = skelfit(&["rig", body.to_str().unwrap(), "-o", glb.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = skelfit(&[
        "check",
        glb.to_str().unwrap(),
        "--results-json",
        report.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("shoulder raise 80° L"), "{stdout}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let check = &json["check"];
    assert_eq!(check["sweep"], "humanoid");
    let poses = check["poses"].as_array().unwrap();
    assert_eq!(poses.len(), 14, "{check}");
    let edges = check["edges"].as_u64().unwrap();
    let torn: u64 = poses.iter().map(|p| p["over_2"].as_u64().unwrap()).sum();
    assert!(torn * 1000 <= edges, "{torn} of {edges} edges past 2x");
    assert_eq!(json["unweighted_vertices"], 0);
    // A file without a skin is a clear error.
    let o = skelfit(&["check", body.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("error"));
}

/// Never silent: a figure lacking a part the template expects (the bundled body without its
/// right arm) rigs with the missing part named at the end of the output and in the JSON;
/// `--strict` makes it exit code 1 and writes nothing. The whole body passes `--strict`.
#[test]
fn rig_names_missing_parts_and_strict_fails_on_them() {
    let dir = tempfile::tempdir().unwrap();
    let mut mesh = skelfit::mesh::load(Path::new(&bundled_humanoid())).unwrap();
    let positions = mesh.positions.clone();
    mesh.triangles.retain(|t| {
        t.iter().all(|&i| {
            let p = positions[i as usize];
            !(p.x < -0.2 && p.y > 0.9)
        })
    });
    let path = dir.path().join("one_arm.obj");
    skelfit::export::write_obj(&path, &mesh).unwrap();
    let path = path.display().to_string();
    let glb = dir.path().join("out.glb");
    let json = dir.path().join("out.json");
    let (g, j) = (glb.display().to_string(), json.display().to_string());
    let out = skelfit(&["rig", &path, "-o", &g, "--skeleton-json", &j]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let last = stderr(&out).lines().last().unwrap_or_default().to_string();
    assert!(
        last.starts_with("skelfit: missing:") && last.contains("arm R"),
        "{last}"
    );
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(
        written["run"]["missing_parts"],
        serde_json::json!(["arm R"])
    );
    std::fs::remove_file(&glb).unwrap();
    std::fs::remove_file(&json).unwrap();
    let out = skelfit(&["rig", &path, "-o", &g, "--skeleton-json", &j, "--strict"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("--strict") && stderr(&out).contains("arm R"));
    assert!(!glb.exists() && !json.exists());
    let out = skelfit(&["rig", &bundled_humanoid(), "-o", &g, "--strict"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(!stderr(&out).contains("skelfit: missing:"));
}

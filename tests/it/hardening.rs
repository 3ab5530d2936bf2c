//! Regression tests of issue 23 (hardening against untrusted files and invalid options), each
//! named after the defect it came from.

use crate::common::{skelfit, stderr};
use crate::mesh::{cube, gltf_parts, write};
use skelfit::mesh::{load, MeshError};
use skelfit::voxel::{grid_for, VoxelError, VoxelOptions, VoxelSize};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

/// A cube .gltf in `dir` named `name` whose only buffer has `uri`; returns its path.
fn gltf_with_uri(dir: &Path, name: &str, uri: &str) -> std::path::PathBuf {
    let (json, _) = gltf_parts(&cube(), [0.0; 3], Some(uri));
    write(dir, name, json)
}

/// Loads `path`, expecting a parse error whose message names `uri`; returns the message.
fn refused(path: &Path, uri: &str) -> String {
    let start = Instant::now();
    let error = load(path).expect_err("the buffer must be refused");
    assert!(
        start.elapsed() < Duration::from_secs(1),
        "took {:?}",
        start.elapsed()
    );
    let message = error.to_string();
    assert!(
        matches!(error, MeshError::Parse { format: "gltf", .. }),
        "{message}"
    );
    assert!(message.contains(&format!("\"{uri}\"")), "{message}");
    message
}

// ---------------------------------------------------------------- 1: glTF buffer URIs

#[test]
fn gltf_buffer_with_an_absolute_path_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = gltf_with_uri(dir.path(), "passwd.gltf", "/etc/passwd");
    let message = refused(&path, "/etc/passwd");
    assert!(message.contains("absolute"), "{message}");
}

#[test]
fn gltf_buffer_with_a_file_uri_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    for uri in [
        "file:///etc/passwd",
        "file:cube.bin",
        "http://example.com/x.bin",
    ] {
        let path = gltf_with_uri(dir.path(), "scheme.gltf", uri);
        let message = refused(&path, uri);
        assert!(message.contains("scheme"), "{message}");
    }
}

#[test]
fn gltf_buffer_escaping_the_folder_with_dotdot_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (_, bin) = gltf_parts(&cube(), [0.0; 3], None);
    write(dir.path(), "x", &bin);
    let inner = dir.path().join("a/b");
    std::fs::create_dir_all(&inner).unwrap();
    let path = gltf_with_uri(&inner, "up.gltf", "../../x");
    let message = refused(&path, "../../x");
    assert!(message.contains("outside"), "{message}");
    // `..` that stays inside the folder is fine.
    std::fs::create_dir_all(inner.join("c")).unwrap();
    write(&inner, "cube data.bin", &bin);
    let inside = gltf_with_uri(&inner, "inside.gltf", "c/../cube%20data.bin");
    assert_eq!(load(&inside).unwrap().triangles.len(), 12);
}

#[test]
fn gltf_buffer_at_dev_zero_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let path = gltf_with_uri(dir.path(), "zero.gltf", "/dev/zero");
    refused(&path, "/dev/zero");
    // Through the command line too, in well under a second.
    let start = Instant::now();
    let out = skelfit(&["info", path.to_str().unwrap()]);
    assert!(
        start.elapsed() < Duration::from_secs(1),
        "took {:?}",
        start.elapsed()
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("\"/dev/zero\""), "{}", stderr(&out));
}

#[cfg(unix)]
#[test]
fn gltf_buffer_symlinked_outside_the_folder_or_to_a_device_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (_, bin) = gltf_parts(&cube(), [0.0; 3], None);
    let outside = write(dir.path(), "outside.bin", &bin);
    let inner = dir.path().join("model");
    std::fs::create_dir(&inner).unwrap();
    std::os::unix::fs::symlink(&outside, inner.join("link.bin")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", inner.join("zero.bin")).unwrap();
    let path = gltf_with_uri(&inner, "link.gltf", "link.bin");
    assert!(refused(&path, "link.bin").contains("outside"));
    let path = gltf_with_uri(&inner, "zero.gltf", "zero.bin");
    refused(&path, "zero.bin");
    // A symlink that stays inside the folder is followed.
    write(&inner, "real.bin", &bin);
    std::os::unix::fs::symlink("real.bin", inner.join("alias.bin")).unwrap();
    let path = gltf_with_uri(&inner, "alias.gltf", "alias.bin");
    assert_eq!(load(&path).unwrap().triangles.len(), 12);
}

#[cfg(unix)]
#[test]
fn gltf_buffer_that_is_a_fifo_or_a_folder_is_refused_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.bin");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let path = gltf_with_uri(dir.path(), "fifo.gltf", "pipe.bin");
    assert!(refused(&path, "pipe.bin").contains("not a regular file"));
    std::fs::create_dir(dir.path().join("folder.bin")).unwrap();
    let path = gltf_with_uri(dir.path(), "folder.gltf", "folder.bin");
    assert!(refused(&path, "folder.bin").contains("not a regular file"));
}

#[test]
fn gltf_buffer_shorter_than_its_byte_length_or_missing_names_the_uri() {
    let dir = tempfile::tempdir().unwrap();
    let (_, bin) = gltf_parts(&cube(), [0.0; 3], None);
    write(dir.path(), "short.bin", &bin[..bin.len() - 1]);
    let path = gltf_with_uri(dir.path(), "short.gltf", "short.bin");
    assert!(refused(&path, "short.bin").contains("byteLength"));
    let path = gltf_with_uri(dir.path(), "missing.gltf", "missing.bin");
    refused(&path, "missing.bin");
}

#[test]
fn gltf_buffer_in_a_data_uri_loads() {
    let dir = tempfile::tempdir().unwrap();
    let (_, bin) = gltf_parts(&cube(), [0.0; 3], None);
    let uri = format!("data:application/octet-stream;base64,{}", base64(&bin));
    let path = gltf_with_uri(dir.path(), "embedded.gltf", &uri);
    assert_eq!(load(&path).unwrap().triangles.len(), 12);
    let bad = gltf_with_uri(dir.path(), "bad.gltf", "data:;base64,@@@@");
    refused(&bad, "data:;base64,@@@@");
}

/// Standard padded base64 of `bytes`.
fn base64(bytes: &[u8]) -> String {
    const DIGITS: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let mut bits = 0u32;
        for (k, &b) in chunk.iter().enumerate() {
            bits |= u32::from(b) << (16 - 8 * k);
        }
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(DIGITS[(bits >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

// ---------------------------------------------------------------- 2, 3: voxel grid sizing

fn cube_voxels(size: VoxelSize, max_voxels: usize) -> Result<skelfit::voxel::Grid, VoxelError> {
    grid_for(
        &cube(),
        &VoxelOptions {
            size,
            max_voxels,
            ..Default::default()
        },
    )
}

#[test]
fn max_voxels_below_the_smallest_grid_fails_at_once_instead_of_looping() {
    for budget in [0, 1, 100, 124] {
        let start = Instant::now();
        let err = cube_voxels(VoxelSize::Fraction(0.01), budget).unwrap_err();
        assert!(start.elapsed() < Duration::from_secs(1));
        assert_eq!(
            err,
            VoxelError::BudgetTooSmall {
                budget,
                minimum: 125
            }
        );
    }
    assert!(cube_voxels(VoxelSize::Fraction(1.0), 125).is_ok());
    // The command line refuses it before reading the mesh (which does not even exist here).
    let start = Instant::now();
    let out = skelfit(&["voxelize", "no-such-mesh.obj", "--max-voxels", "100"]);
    assert!(start.elapsed() < Duration::from_secs(1));
    assert_eq!(out.status.code(), Some(1));
    let message = stderr(&out);
    assert!(message.contains("--max-voxels"), "{message}");
    assert!(message.contains("at least 125"), "{message}");
    assert!(!message.contains("no-such-mesh"), "{message}");
}

#[test]
fn max_voxels_130_suggests_a_fraction_that_voxel_size_accepts() {
    for budget in [125, 130, 200, 1000, 54_321] {
        let err = cube_voxels(VoxelSize::Fraction(0.01), budget).unwrap_err();
        let VoxelError::TooLarge {
            fitting_size,
            fitting_fraction,
            ..
        } = err
        else {
            panic!("expected TooLarge, got {err}");
        };
        assert!(fitting_fraction > 0.0 && fitting_fraction <= 1.0, "{err}");
        // Both suggestions, as printed, are accepted and fit the budget.
        let message = err.to_string();
        assert!(
            message.contains(&format!("fraction {fitting_fraction})")),
            "{message}"
        );
        let grid = cube_voxels(VoxelSize::Fraction(fitting_fraction), budget).unwrap();
        assert!(grid.len() <= budget);
        let grid = cube_voxels(VoxelSize::Absolute(fitting_size), budget).unwrap();
        assert!(grid.len() <= budget);
    }
}

#[test]
fn tiny_voxel_length_overflows_to_too_large_not_a_wrapped_grid() {
    for length in [1e-19, 1e-20, 1e-300, f64::MIN_POSITIVE] {
        let err = cube_voxels(VoxelSize::Absolute(length), 1_000_000).unwrap_err();
        let VoxelError::TooLarge {
            voxels,
            fitting_size,
            ..
        } = err
        else {
            panic!("{length}: expected TooLarge, got {err}");
        };
        assert_eq!(voxels, usize::MAX, "{err}");
        assert!(err.to_string().contains("overflow"), "{err}");
        assert!(!err.to_string().contains("smaller voxel size"), "{err}");
        assert!(cube_voxels(VoxelSize::Absolute(fitting_size), 1_000_000).is_ok());
    }
}

#[test]
fn huge_max_voxels_grid_beyond_the_memory_is_refused_before_allocating() {
    // 10^4 voxels per side of the cube's longest edge: about 10^12 voxels, terabytes.
    let start = Instant::now();
    let err = cube_voxels(VoxelSize::Fraction(1e-4), usize::MAX).unwrap_err();
    assert!(start.elapsed() < Duration::from_secs(1));
    let VoxelError::OutOfMemory { fitting_size, .. } = err else {
        panic!("expected OutOfMemory, got {err}");
    };
    assert!(err.to_string().contains("MiB"), "{err}");
    assert!(fitting_size > 3e-4, "{err}");
}

// ---------------------------------------------------------------- 4, 5: outputs

fn humanoid() -> String {
    crate::common::data_dir()
        .join("humanoid/mh_neutral_default/mesh.obj")
        .display()
        .to_string()
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn missing_output_folder_is_refused_before_the_voxelization_starts() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("o.json");
    let glb = dir.path().join("no/such/dir/o.glb");
    let start = Instant::now();
    // A fine grid that would take seconds and gigabytes to rig.
    let out = skelfit(&[
        "rig",
        &humanoid(),
        "--voxel-size",
        "0.0015",
        "-o",
        glb.to_str().unwrap(),
        "--skeleton-json",
        json.to_str().unwrap(),
    ]);
    assert!(
        start.elapsed() < Duration::from_secs(1),
        "{:?}",
        start.elapsed()
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("does not exist"), "{}", stderr(&out));
    assert!(listing(dir.path()).is_empty(), "{:?}", listing(dir.path()));
}

#[test]
fn unwritable_json_output_leaves_no_output_at_all() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "file.txt", b"not a folder");
    let out = skelfit(&[
        "rig",
        &humanoid(),
        "-o",
        dir.path().join("o.glb").to_str().unwrap(),
        "--bvh",
        dir.path().join("o.bvh").to_str().unwrap(),
        "--skeleton-json",
        dir.path().join("file.txt/o.json").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("file.txt"), "{}", stderr(&out));
    assert_eq!(listing(dir.path()), ["file.txt"]);
}

#[test]
fn gltf_named_output_holds_gltf_json_not_glb_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("o.gltf");
    let out = skelfit(&["rig", &humanoid(), "-o", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let bytes = std::fs::read(&path).unwrap();
    assert!(!bytes.starts_with(b"glTF"), "binary GLB under a .gltf name");
    let json: serde_json::Value = serde_json::from_slice(&bytes).expect("glTF JSON");
    assert!(json["asset"]["version"].is_string());
}

#[test]
fn output_that_is_an_input_or_named_twice_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("mesh.obj");
    std::fs::copy(humanoid(), &mesh).unwrap();
    let before = std::fs::read(&mesh).unwrap();
    let glb = dir.path().join("o.glb");
    // Onto the input: a usage error (exit 2); one name for two outputs: exit 1.
    for (args, code) in [
        (
            vec![
                "-o",
                glb.to_str().unwrap(),
                "--skeleton-json",
                mesh.to_str().unwrap(),
            ],
            2,
        ),
        (vec!["-o", mesh.to_str().unwrap()], 2),
        (
            vec![
                "-o",
                glb.to_str().unwrap(),
                "--skeleton-json",
                glb.to_str().unwrap(),
            ],
            1,
        ),
    ] {
        let mut all = vec!["rig", mesh.to_str().unwrap()];
        all.extend(args);
        let out = skelfit(&all);
        assert_eq!(out.status.code(), Some(code), "{all:?}");
        assert_eq!(listing(dir.path()), ["mesh.obj"]);
    }
    assert_eq!(std::fs::read(&mesh).unwrap(), before);
}

#[test]
fn failed_output_set_writes_none_of_its_files() {
    let dir = tempfile::tempdir().unwrap();
    let first = write(dir.path(), "first.txt", b"old");
    let second = dir.path().join("missing/second.txt");
    let err = skelfit::output::write_all_atomic(&[(&first, b"new"), (&second, b"new")]);
    assert!(err.is_err());
    assert_eq!(std::fs::read(&first).unwrap(), b"old");
    assert_eq!(listing(dir.path()), ["first.txt"]);
    let third = dir.path().join("third.txt");
    skelfit::output::write_all_atomic(&[(&first, b"new"), (&third, b"3")]).unwrap();
    assert_eq!(std::fs::read(&first).unwrap(), b"new");
    assert_eq!(listing(dir.path()), ["first.txt", "third.txt"]);
}

#[cfg(unix)]
#[test]
fn atomic_write_through_a_symlink_keeps_the_link_and_the_mode() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let target = write(dir.path(), "target.glb", b"old");
    std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o640)).unwrap();
    let link = dir.path().join("link.glb");
    std::os::unix::fs::symlink("target.glb", &link).unwrap();
    skelfit::output::write_atomic(&link, b"new").unwrap();
    assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
    assert_eq!(std::fs::read(&target).unwrap(), b"new");
    let mode = std::fs::metadata(&target).unwrap().permissions().mode();
    assert_eq!(mode & 0o777, 0o640);
    skelfit::output::write_all_atomic(&[(&link, b"newer")]).unwrap();
    assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
    assert_eq!(std::fs::read(&target).unwrap(), b"newer");
    assert_eq!(listing(dir.path()), ["link.glb", "target.glb"]);
}

#[cfg(unix)]
#[test]
fn interrupted_rig_leaves_every_output_or_none_and_no_temporaries() {
    // SIGTERM at several moments of a run: afterwards the folder holds either the whole
    // output set (the run finished) or nothing at all, never a temporary file.
    for delay_ms in [50, 200, 400, 800] {
        let dir = tempfile::tempdir().unwrap();
        let mut child = Command::new(env!("CARGO_BIN_EXE_skelfit"))
            .args([
                "rig",
                &humanoid(),
                "-o",
                dir.path().join("o.glb").to_str().unwrap(),
                "--skeleton-json",
                dir.path().join("o.json").to_str().unwrap(),
                "--bvh",
                dir.path().join("o.bvh").to_str().unwrap(),
            ])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(delay_ms));
        let _ = Command::new("kill")
            .args(["-TERM", &child.id().to_string()])
            .status();
        let status = child.wait().unwrap();
        let names = listing(dir.path());
        match status.code() {
            Some(0) => assert_eq!(names, ["o.bvh", "o.glb", "o.json"], "{delay_ms} ms"),
            // 130: the handler ran; None: the signal came before it was installed (a slow
            // start on a loaded machine). Either way nothing may be left behind.
            Some(130) | None => assert!(names.is_empty(), "{delay_ms} ms: {names:?}"),
            other => panic!("{delay_ms} ms: exit {other:?}, files {names:?}"),
        }
    }
}

// ---------------------------------------------------------------- 6, 9: OBJ and glTF reading

#[test]
fn obj_vertex_with_w_is_divided_by_w() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(
        dir.path(),
        "w.obj",
        "v 0 0 0 2\nv 2 0 0 2\nv 0 4 0 2.0\nv 0 0 1 1\nf 1 2 3\nf 1 2 4\n",
    );
    let mesh = load(&path).unwrap();
    assert_eq!(mesh.positions[1], glam::DVec3::new(1.0, 0.0, 0.0));
    assert_eq!(mesh.positions[2], glam::DVec3::new(0.0, 2.0, 0.0));
    assert_eq!(mesh.positions[3], glam::DVec3::new(0.0, 0.0, 1.0));
    let zero = write(
        dir.path(),
        "w0.obj",
        "v 0 0 0\nv 1 0 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    let message = load(&zero).unwrap_err().to_string();
    assert!(
        message.contains("line 2") && message.contains("w = 0"),
        "{message}"
    );
}

#[test]
fn obj_coordinates_are_parsed_as_f64_far_from_the_origin() {
    let offset = glam::DVec3::new(1e7, -3e7, 2e7);
    let body = skelfit::mesh::Mesh::cuboid(offset, offset + glam::DVec3::new(0.31, 1.7, 0.23));
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::new();
    for p in &body.positions {
        text += &format!("v {} {} {}\n", p.x, p.y, p.z);
    }
    for t in &body.triangles {
        text += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    let mesh = load(&write(dir.path(), "far.obj", text)).unwrap();
    assert_eq!(
        mesh.positions, body.positions,
        "f64 coordinates kept exactly"
    );
    let volume = mesh.transformed(|p| p - offset).signed_volume();
    assert!((volume - 0.31 * 1.7 * 0.23).abs() < 1e-6, "{volume}");
}

#[test]
fn obj_parse_errors_give_the_line_number() {
    let dir = tempfile::tempdir().unwrap();
    for (text, line) in [
        ("v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n", "line 3"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 x\n", "line 5"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "line 4"),
        ("v 0 0\n", "line 1"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2 3\n", "line 4"),
    ] {
        let path = write(dir.path(), "bad.obj", text);
        let error = load(&path).unwrap_err();
        assert!(matches!(error, MeshError::Parse { .. }), "{error}");
        assert!(error.to_string().contains(line), "{text:?}: {error}");
    }
    let path = write(dir.path(), "latin1.obj", b"v 0 0 0\n# caf\xe9\n");
    assert!(load(&path).unwrap_err().to_string().contains("line 2"));
}

#[test]
fn obj_out_of_range_index_is_reported_1_based_as_in_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(
        dir.path(),
        "index.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
    );
    let message = load(&path).unwrap_err().to_string();
    assert!(message.contains("vertex 9 counting from 1"), "{message}");
}

#[test]
fn gltf_extras_that_are_arrays_strings_or_numbers_are_accepted() {
    let dir = tempfile::tempdir().unwrap();
    let (json, bin) = gltf_parts(&cube(), [0.0; 3], None);
    let mut value: serde_json::Value = serde_json::from_str(&json).unwrap();
    value["asset"]["extras"] = serde_json::json!([1, 2, 3]);
    value["nodes"][0]["extras"] = serde_json::json!("a string");
    value["meshes"][0]["extras"] = serde_json::json!(1);
    value["meshes"][0]["primitives"][0]["extras"] = serde_json::json!(null);
    value["accessors"][0]["extras"] = serde_json::json!({"any": ["thing"]});
    value["buffers"][0]["extras"] = serde_json::json!(true);
    let text = serde_json::to_string(&value).unwrap();
    let path = write(dir.path(), "extras.glb", crate::mesh::glb(&text, &bin));
    assert_eq!(load(&path).unwrap().triangles.len(), 12);
}

// ---------------------------------------------------------------- 8: messages

/// A skelfit skeleton JSON of a chain of joints `names` at `positions`, written in `dir`.
fn skeleton_file(dir: &Path, file: &str, names: &[String], positions: &[glam::DVec3]) -> String {
    use skelfit::skeleton::{Joint, JointId, Skeleton};
    let joints = names
        .iter()
        .zip(positions)
        .enumerate()
        .map(|(i, (name, &p))| Joint::new(name.clone(), i.checked_sub(1).map(JointId), p))
        .collect();
    let skeleton = Skeleton { joints };
    let text = skelfit::export::skeleton_json(&skeleton, &Default::default()).unwrap();
    write(dir, file, text).display().to_string()
}

#[test]
fn os_errors_are_printed_once() {
    let out = skelfit(&["info", "/no/such/mesh.obj"]);
    assert_eq!(out.status.code(), Some(1));
    let message = stderr(&out);
    assert_eq!(message.matches("os error 2").count(), 1, "{message}");
}

#[test]
fn ply_parse_errors_have_no_debug_dump() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(
        dir.path(),
        "bad.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_heade\n",
    );
    let message = load(&path).unwrap_err().to_string();
    assert!(!message.contains("ParseError {"), "{message}");
    assert!(!message.contains('\n'), "{message}");
    assert!(
        message.contains("line 5") && message.contains("end_heade"),
        "{message}"
    );
}

#[test]
fn eval_with_a_joint_at_1e300_is_an_error_naming_the_joint() {
    let dir = tempfile::tempdir().unwrap();
    let names: Vec<String> = ["hips", "spine", "head"].map(String::from).to_vec();
    let near = [glam::DVec3::ZERO, glam::DVec3::Y, 2.0 * glam::DVec3::Y];
    let mut far = near;
    far[1].x = 1e300;
    let reference = skeleton_file(dir.path(), "ref.json", &names, &near);
    let predicted = skeleton_file(dir.path(), "pred.json", &names, &far);
    for extra in [None, Some("--chamfer-only")] {
        let mut args = vec![
            "eval",
            predicted.as_str(),
            reference.as_str(),
            "--all-joints",
        ];
        args.extend(extra);
        let out = skelfit(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let message = stderr(&out);
        assert!(message.contains("\"spine\""), "{message}");
        assert!(!String::from_utf8_lossy(&out.stdout).contains("inf"));
    }
}

#[test]
fn eval_share_no_joints_error_lists_a_capped_number_of_names() {
    let dir = tempfile::tempdir().unwrap();
    let count = 500;
    let positions: Vec<glam::DVec3> = (0..count).map(|i| glam::DVec3::Y * i as f64).collect();
    let a: Vec<String> = (0..count)
        .map(|i| format!("a_{i}_{}", "x".repeat(200)))
        .collect();
    let b: Vec<String> = (0..count).map(|i| format!("b_{i}")).collect();
    let predicted = skeleton_file(dir.path(), "a.json", &a, &positions);
    let reference = skeleton_file(dir.path(), "b.json", &b, &positions);
    let out = skelfit(&["eval", &predicted, &reference, "--all-joints"]);
    assert_eq!(out.status.code(), Some(1));
    let message = stderr(&out);
    assert!(message.contains("share no joints"), "{message}");
    assert!(message.contains("and 488 more"), "{message}");
    assert!(message.len() < 2000, "{} bytes", message.len());
}

#[test]
fn eval_encoding_error_does_not_blame_the_path_and_permissions() {
    let dir = tempfile::tempdir().unwrap();
    let bad = write(dir.path(), "latin1.json", b"{\"joints\": \"caf\xe9\"}");
    let out = skelfit(&["eval", bad.to_str().unwrap(), bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let message = stderr(&out);
    assert!(message.contains("UTF-8"), "{message}");
    assert!(!message.contains("permissions"), "{message}");
}

#[test]
fn negative_voxel_size_reaches_validation_instead_of_an_unknown_flag() {
    let out = skelfit(&["voxelize", &humanoid(), "--voxel-size", "-0.01"]);
    assert_eq!(out.status.code(), Some(1));
    let message = stderr(&out);
    assert!(message.contains("invalid voxel size -0.01"), "{message}");
    let out = skelfit(&["voxelize", &humanoid(), "--voxel-length", "-1e3"]);
    assert!(
        stderr(&out).contains("invalid voxel size -1000"),
        "{}",
        stderr(&out)
    );
}

// ---------------------------------------------------------------- 9: geometry

#[test]
fn far_outlier_vertex_is_named_instead_of_blaming_an_open_or_thin_mesh() {
    let mut mesh = skelfit::mesh::load(Path::new(&humanoid())).unwrap();
    let vertex = mesh.triangles[10][0] as usize;
    mesh.positions[vertex] = glam::DVec3::new(0.0, 1e6, 0.0);
    let err = skelfit::voxel::voxelize(&mesh, &VoxelOptions::default()).unwrap_err();
    let VoxelError::Outlier {
        vertex: named,
        position,
        ..
    } = err
    else {
        panic!("expected Outlier, got {err}");
    };
    assert_eq!(named, vertex);
    assert_eq!(position, [0.0, 1e6, 0.0]);
    let message = err.to_string();
    assert!(!message.contains("thinner than a voxel"), "{message}");
}

#[test]
fn loose_piece_rule_leaves_out_a_far_fragment_of_a_many_piece_model() {
    // Fifteen touching boxes (none holds 60 % of the area) and a small box far away.
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut add = |piece: skelfit::mesh::Mesh| {
        let base = positions.len() as u32;
        positions.extend(piece.positions);
        triangles.extend(piece.triangles.iter().map(|t| t.map(|i| i + base)));
    };
    for k in 0..15 {
        let x = 0.1 * k as f64;
        add(skelfit::mesh::Mesh::cuboid(
            glam::DVec3::new(x, 0.0, 0.0),
            glam::DVec3::new(x + 0.1, 1.0, 0.3),
        ));
    }
    add(skelfit::mesh::Mesh::cuboid(
        glam::DVec3::new(100.0, 0.0, 0.0),
        glam::DVec3::new(100.01, 0.01, 0.01),
    ));
    let mesh = skelfit::mesh::Mesh::new(positions, triangles).unwrap();
    let solid = skelfit::voxel::voxelize(&mesh, &VoxelOptions::default()).unwrap();
    assert_eq!(solid.report.left_out_pieces, 1);
    assert!(solid.grid.voxel_size < 0.02, "{}", solid.grid.voxel_size);
}

#[test]
fn skeleton_copes_with_a_sphere_two_spheres_and_a_hollow_shell_like_rig() {
    use skelfit::mesh::Mesh;
    let merge = |parts: &[Mesh]| {
        let (mut positions, mut triangles) = (Vec::new(), Vec::new());
        for part in parts {
            let base = positions.len() as u32;
            positions.extend(&part.positions);
            triangles.extend(part.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        Mesh::new(positions, triangles).unwrap()
    };
    let sphere = Mesh::uv_sphere(glam::DVec3::ZERO, 1.0, 16, 32);
    let other = Mesh::uv_sphere(glam::DVec3::new(3.0, 0.0, 0.0), 1.0, 16, 32);
    let mut inner = Mesh::uv_sphere(glam::DVec3::ZERO, 0.8, 16, 32);
    for t in &mut inner.triangles {
        t.swap(1, 2);
    }
    for (name, mesh) in [
        ("sphere", sphere.clone()),
        ("two spheres", merge(&[sphere.clone(), other])),
        ("hollow shell", merge(&[sphere, inner])),
    ] {
        let rig = skelfit::pipeline::general_rig(&mesh, &Default::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(rig.skin.weights.len(), mesh.positions.len(), "{name}");
        assert!(rig.skin.weights.iter().all(|w| !w.is_empty()), "{name}");
    }
}

#[test]
fn unusable_output_folder_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "file.txt", b"not a folder");
    let inside = file.join("slices");
    // The mesh does not exist: the folder is checked first.
    let out = skelfit(&[
        "voxelize",
        "no-such-mesh.obj",
        "--slices",
        inside.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let message = stderr(&out);
    assert!(message.contains("file.txt"), "{message}");
    assert!(!message.contains("no-such-mesh"), "{message}");
}

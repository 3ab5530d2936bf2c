//! Regression tests of issue 23 (hardening against untrusted files and invalid options), each
//! named after the defect it came from.

use crate::mesh::{cube, gltf_parts, write};
use skelfit::mesh::{load, MeshError};
use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn skelfit(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_skelfit"))
        .args(args)
        .output()
        .expect("the skelfit binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

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

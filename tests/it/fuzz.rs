//! Mutation fuzzing of every file loader: valid OBJ, STL, PLY, glTF/GLB, skeleton JSON, BVH
//! and outline SVG/CSV files are mutated byte by byte (deterministic seeds) and fed to their loaders, which must
//! return (an error or a result) without panicking, in bounded time, with an output bounded by
//! the input's size.
//!
//! `SKELFIT_FUZZ_CASES` sets the number of cases per seed file (default 400, 4,400 cases in
//! all); the test prints the count it ran (`cargo test --release --test it fuzz -- --nocapture`).

use crate::mesh::{cube, glb, gltf_parts, obj_text, ply_ascii, ply_binary, stl_ascii, stl_binary};
use glam::DVec3;
use skelfit::skeleton::{Joint, JointId, Skeleton};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::time::{Duration, Instant};

/// Default number of mutated cases per seed file.
const DEFAULT_CASES: usize = 400;

/// Longest one case may take (generous: CI machines are shared).
const CASE_TIME: Duration = Duration::from_secs(5);

/// A small deterministic generator (xorshift64*), so every run tests the same cases.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Tokens that stress parsers: huge and negative counts, special floats, separators.
const TOKENS: &[&[u8]] = &[
    b"4294967295",
    b"18446744073709551615",
    b"-1",
    b"0",
    b"1e308",
    b"-1e308",
    b"nan",
    b"inf",
    b"1e-320",
    b"999999999999",
    b"\n",
    b" ",
    b"/",
    b"\"",
    b"{",
    b"]",
    b"\\",
    b"\0",
    b"f -1 -2 -3\n",
    b"element face 4000000000\n",
    b"\"count\": 4000000000",
    b"\"byteLength\": 4000000000",
    b"\"uri\": \"/dev/zero\"",
    b"JOINT",
    b"}",
];

/// One random mutation of `bytes`: bit flips, byte replacements, insertions of stress tokens,
/// deletions, duplications and truncations, one to four of them.
fn mutate(rng: &mut Rng, bytes: &[u8]) -> Vec<u8> {
    let mut out = bytes.to_vec();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(out.len() + 1);
        match rng.below(7) {
            0 if !out.is_empty() => {
                let i = at.min(out.len() - 1);
                out[i] ^= 1 << rng.below(8);
            }
            1 if !out.is_empty() => {
                let i = at.min(out.len() - 1);
                out[i] = rng.next() as u8;
            }
            2 => {
                let token = TOKENS[rng.below(TOKENS.len())];
                out.splice(at..at, token.iter().copied());
            }
            3 => {
                let end = (at + 1 + rng.below(16)).min(out.len());
                out.drain(at.min(end)..end);
            }
            4 => {
                let end = (at + 1 + rng.below(64)).min(out.len());
                let chunk: Vec<u8> = out[at.min(end)..end].to_vec();
                out.splice(at..at, chunk);
            }
            5 => out.truncate(at),
            _ => {
                // Overwrite a 4-byte little-endian field with an extreme value (binary headers).
                let value = [0u32, 1, 0x7fff_ffff, u32::MAX, 3, 12][rng.below(6)];
                if at + 4 <= out.len() {
                    out[at..at + 4].copy_from_slice(&value.to_le_bytes());
                }
            }
        }
    }
    out
}

/// The valid seed files: (file name, bytes).
fn seeds() -> Vec<(&'static str, Vec<u8>)> {
    let mesh = cube();
    let faces: Vec<Vec<u32>> = mesh.triangles.iter().map(|t| t.to_vec()).collect();
    let (json, bin) = gltf_parts(&mesh, [0.5, 0.0, 0.0], None);
    let embedded = {
        let digits = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut text = String::new();
        for chunk in bin.chunks(3) {
            let mut bits = 0u32;
            for (k, &b) in chunk.iter().enumerate() {
                bits |= u32::from(b) << (16 - 8 * k);
            }
            for k in 0..4 {
                text.push(if k <= chunk.len() {
                    digits[(bits >> (18 - 6 * k) & 63) as usize] as char
                } else {
                    '='
                });
            }
        }
        gltf_parts(
            &mesh,
            [0.0; 3],
            Some(&format!("data:application/octet-stream;base64,{text}")),
        )
        .0
    };
    let skeleton = Skeleton {
        joints: vec![
            Joint::new("hips", None, DVec3::new(0.0, 1.0, 0.0)),
            Joint::new("spine", Some(JointId(0)), DVec3::new(0.0, 1.3, 0.0)),
            Joint::new("head", Some(JointId(1)), DVec3::new(0.0, 1.7, 0.1)),
            Joint::new("leg_L", Some(JointId(0)), DVec3::new(0.1, 0.5, 0.0)),
        ],
    };
    let skeleton_json = skelfit::export::skeleton_json(&skeleton, &Default::default()).unwrap();
    let bvh = skelfit::export::bvh_text(&skeleton, &Default::default()).unwrap();
    vec![
        ("cube.obj", obj_text(&mesh, false).into_bytes()),
        ("ascii.stl", stl_ascii(&mesh).into_bytes()),
        ("binary.stl", stl_binary(&mesh, b"fuzz")),
        (
            "ascii.ply",
            ply_ascii(&mesh.positions, &faces, "vertex_indices").into_bytes(),
        ),
        ("binary.ply", ply_binary(&mesh.positions, &faces)),
        ("cube.glb", glb(&json, &bin)),
        ("embedded.gltf", embedded.into_bytes()),
        ("skeleton.json", skeleton_json.into_bytes()),
        ("skeleton.bvh", bvh.into_bytes()),
        (
            "starfish.svg",
            std::fs::read(crate::common::data_dir().join("outlines/starfish.svg")).unwrap(),
        ),
        (
            "outline.csv",
            b"x,y\n0,0\n4,0\n4,1\n2.5,1\n2.5,3\n1.5,3\n1.5,1\n0,1\n".to_vec(),
        ),
    ]
}

/// Runs the loader for `path`'s extension; returns the size of what it read (vertices plus
/// triangles, or joints) on success.
fn load(path: &Path) -> Result<usize, String> {
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    match extension {
        "svg" | "csv" => skelfit::outline::read_outline(path, &Default::default())
            .map(|outline| outline.points.len())
            .map_err(|e| e.to_string()),
        "json" | "bvh" => skelfit::eval::load_skeleton(path)
            .map(|rig| rig.skeleton.joints.len())
            .map_err(|e| e.to_string()),
        _ => skelfit::mesh::load_with_source_map(path)
            .map(|(mesh, source)| mesh.positions.len() + mesh.triangles.len() + source.len())
            .map_err(|e| e.to_string()),
    }
}

#[test]
fn fuzz_every_loader_with_mutated_valid_files() {
    let cases: usize = std::env::var("SKELFIT_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_CASES);
    let dir = tempfile::tempdir().unwrap();
    let start = Instant::now();
    let (mut run, mut loaded) = (0usize, 0usize);
    for (k, (name, bytes)) in seeds().iter().enumerate() {
        let path = dir.path().join(name);
        // The seed itself must load.
        std::fs::write(&path, bytes).unwrap();
        load(&path).unwrap_or_else(|e| panic!("seed {name}: {e}"));
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ (k as u64 + 1).wrapping_mul(0x1234_5678_9abc));
        for case in 0..cases {
            let mutated = mutate(&mut rng, bytes);
            std::fs::write(&path, &mutated).unwrap();
            let clock = Instant::now();
            let outcome = catch_unwind(AssertUnwindSafe(|| load(&path)));
            let took = clock.elapsed();
            let keep = || {
                let kept = dir.path().join(format!("failed-{case}-{name}"));
                std::fs::write(&kept, &mutated).unwrap();
                format!("{name} case {case} ({} bytes)", mutated.len())
            };
            let outcome = outcome.unwrap_or_else(|_| panic!("{}: the loader panicked", keep()));
            assert!(took < CASE_TIME, "{}: took {took:?}", keep());
            match outcome {
                Ok(size) => {
                    loaded += 1;
                    // No amplification: what is read is bounded by the bytes it came from.
                    assert!(
                        size <= 16 * mutated.len() + 64,
                        "{}: read {size} elements",
                        keep()
                    );
                }
                Err(message) => {
                    assert!(!message.is_empty(), "{}", keep());
                    assert!(message.len() < 4096, "{}: message {message}", keep());
                }
            }
            run += 1;
        }
    }
    println!(
        "fuzz: {run} cases ({loaded} still loaded) over {} seed files in {:.1} s",
        seeds().len(),
        start.elapsed().as_secs_f64()
    );
    assert_eq!(run, cases * seeds().len());
}

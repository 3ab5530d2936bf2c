//! Shared helpers for the integration tests.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// The reference data directory `../shared/refdata` beside the checkout (or `SKELFIT_REFDATA`),
/// or `None` with a printed reason so that tests needing it skip visibly.
pub fn refdata() -> Option<PathBuf> {
    let dir = std::env::var_os("SKELFIT_REFDATA")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/refdata"));
    if dir.join("README.md").is_file() {
        Some(dir)
    } else {
        eprintln!(
            "SKIPPED: reference data not found at {} (set SKELFIT_REFDATA)",
            dir.display()
        );
        None
    }
}

/// A refdata model directory such as `humanoid/mh_male_young_average`, or `None` (skip).
pub fn model(relative: &str) -> Option<PathBuf> {
    let dir = refdata()?.join(relative);
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("SKIPPED: refdata model {} missing", dir.display());
        None
    }
}

/// The bundled data directory of the repository.
pub fn data_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data")
}

/// `mesh` turned about +Y by `degrees` (a figure facing another way, or a few degrees off the
/// file's axes), with the same triangles.
pub fn turned_about_up(mesh: &skelfit::mesh::Mesh, degrees: f64) -> skelfit::mesh::Mesh {
    let turn = glam::DQuat::from_rotation_y(degrees.to_radians());
    skelfit::mesh::Mesh::new(
        mesh.positions.iter().map(|&p| turn * p).collect(),
        mesh.triangles.clone(),
    )
    .expect("a turned mesh is as valid as the mesh")
}

/// True for the real game characters added to the reference data on 2026-11-24 (their
/// `provenance.json` names the glTF converter that made them).
pub fn is_real_character(dir: &std::path::Path) -> bool {
    std::fs::read_to_string(dir.join("provenance.json"))
        .ok()
        .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok())
        .is_some_and(|p| p.get("converter").is_some())
}

/// True for the real game characters added to the reference data on 2026-11-24 (modular
/// pieces, headwear, props, stylised proportions; their `provenance.json` names the glTF
/// converter that made them), printing that the test leaves the model out. Labelling, fit,
/// bones and bind-pose reading on them are the work of issue 21 ("Real characters"); the tests
/// that hold the pipeline to its guarantees on the earlier models leave them out until then,
/// and `examples/deformation` and the reports measure them.
pub fn awaits_real_character_work(dir: &std::path::Path, test: &str) -> bool {
    let new = is_real_character(dir);
    if new {
        eprintln!(
            "SKIPPED in {test}: {} is a real game character (issue 21)",
            dir.display()
        );
    }
    new
}

/// Runs the built `skelfit` binary with `args`.
pub fn skelfit(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_skelfit"))
        .args(args)
        .output()
        .expect("the skelfit binary runs")
}

/// A command's stderr as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The MakeHuman bodies of the reference data (`humanoid/mh_*`), sorted, or `None` (skip).
pub fn makehuman_bodies() -> Option<Vec<PathBuf>> {
    let root = refdata()?;
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root.join("humanoid"))
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("mh_"))
        })
        .collect();
    dirs.sort();
    assert!(
        !dirs.is_empty(),
        "no MakeHuman bodies in {}",
        root.display()
    );
    Some(dirs)
}

/// Proptest's settings for the integration tests: `cases` cases drawn from a fixed seed, so a
/// run tests the same cases on every machine and CI cannot fail by the luck of the draw.
/// `PROPTEST_CASES` and `PROPTEST_RNG_SEED` still override both, to explore further:
/// `PROPTEST_RNG_SEED=$RANDOM PROPTEST_CASES=2000 cargo test --release --test it outline::`.
pub fn proptest_config(cases: u32) -> proptest::test_runner::Config {
    let from_environment = proptest::test_runner::Config::default();
    let mut config = proptest::test_runner::Config {
        cases,
        failure_persistence: None,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x5eed_f17e),
        ..from_environment.clone()
    };
    if std::env::var_os("PROPTEST_CASES").is_some() {
        config.cases = from_environment.cases;
    }
    if std::env::var_os("PROPTEST_RNG_SEED").is_some() {
        config.rng_seed = from_environment.rng_seed;
    }
    config
}

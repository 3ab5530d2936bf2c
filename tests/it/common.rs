//! Shared helpers for the integration tests.
#![allow(dead_code)]

use std::path::PathBuf;

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

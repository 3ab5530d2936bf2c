//! Integration tests: one binary, one module per stage.

mod common;
mod distance;
mod eval;
mod export;
mod medial;
mod mesh;
mod skin;
mod voxel;

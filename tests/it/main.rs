//! Integration tests: one binary, one module per stage.

mod cli;
mod common;
mod distance;
mod eval;
mod general;
mod medial;
mod mesh;
mod voxel;

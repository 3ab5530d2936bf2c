//! Integration tests: one binary, one module per stage.

mod anatomy;
mod bench;
mod bones;
mod cli;
mod common;
mod distance;
mod eval;
mod export;
mod fit;
mod frames;
mod fuzz;
mod general;
mod hardening;
mod medial;
mod mesh;
mod outline;
mod outputs;
mod presets;
mod refine;
mod rig;
mod robust;
mod roundtrip;
mod skin;
mod skin_bad_input;
mod skin_skeleton;
mod voxel;

//! Evaluation: reference rigs, joint correspondence, per-joint metrics, chamfer distances and
//! result tables.
//!
//! ```text
//! load_skeleton(path) ─▶ ReferenceRig ─┐
//!                                      ├─ correspond (canonical keys / presets / names)
//! load_skeleton(path) ─▶ ReferenceRig ─┘        │
//!                                  evaluate ─▶ Evaluation (per-joint errors, summaries,
//!                                                 chamfer J2J/J2B/B2B, warnings)
//!                                      table ─▶ rows ─▶ CSV / JSON / Markdown; aggregate
//!
//! rig_mesh (RigMethod) ─▶ bench_model (one model of a folder) ─▶ bench tables
//!                     │       core_error (core joints of upright figures, missing ones listed)
//!                     └─▶ tessellation_study / rotation_study ─▶ displacement per variant
//!
//! label_score (a refdata model's per-vertex labels) ─▶ nearest-bone agreement,
//!     reference_skin (source.glb weights) ─▶ weight share (anatomy::weight_share) and ceiling
//! ```
//!
//! Skeletons that share no joint keys (the general control skeleton against an anatomical
//! reference) can still be compared by the topology-free chamfer distances:
//! [`JointPairing::IfShared`] / [`JointPairing::Skip`] give a [`MatchMethod::ChamferOnly`]
//! evaluation instead of [`EvalError::NoSharedJoints`].
//!
//! Errors are given in mesh units and as a percentage of figure size (height for upright
//! figures, longest bounding-box side otherwise), as `DESIGN.md` prescribes.
//!
//! ```
//! use glam::DVec3;
//! use skelfit::eval::{evaluate, EvalOptions, ReferenceRig};
//! use skelfit::skeleton::{Joint, JointId, Skeleton};
//!
//! let joint = |name: &str, parent: Option<usize>, y: f64| Joint {
//!     name: name.into(),
//!     parent: parent.map(JointId),
//!     position: DVec3::new(0.0, y, 0.0),
//!     deform: true,
//!     ..Default::default()
//! };
//! let reference = Skeleton { joints: vec![joint("root", None, 1.0), joint("mid", Some(0), 1.5), joint("tip", Some(1), 1.7)] };
//! let mut predicted = reference.clone();
//! predicted.joints[2].position.z += 0.01;
//! let result = evaluate(
//!     &ReferenceRig::from_skeleton("guess", predicted),
//!     &ReferenceRig::from_skeleton("truth", reference),
//!     None,
//!     &EvalOptions::default(),
//! )
//! .unwrap();
//! assert_eq!(result.worst_joint, "tip");
//! assert!((result.summary.max - 0.01).abs() < 1e-12);
//! ```

mod bench;
mod bench_core;
mod bvh;
mod chamfer;
mod core;
mod correspondence;
mod error;
mod label_table;
mod labels;
mod metrics;
mod pose;
mod reference;
mod regions;
mod rig;
mod rigger;
mod skin_weights;
mod study;
mod table;
#[cfg(test)]
mod tests;
mod warning;

pub use crate::skeleton::canonical::{is_canonical_key, CANONICAL_KEYS};
pub use bench::{
    bench_counts, bench_csv, bench_markdown, bench_model, bench_table, find_bench_models,
    is_real_character, joint_model_table, stage_names, timing_table, BenchCounts, BenchModel,
    BenchOptions, BenchResult, ANATOMY_CAPTION,
};
pub use bench_core::{
    anatomy_table, core_summary, core_summary_lines, CoreSummary, TOP_WARNINGS, WARNING_CHARS,
};
pub use bvh::parse_bvh;
pub use chamfer::{
    bone_segments, chamfer, point_segment_distance, sample_segments, ChamferDistances,
    ChamferOptions,
};
pub use core::{core_error, CoreError, CORE_KEYS};
pub use correspondence::{
    canonical_map, correspond, detect_preset, parse_presets, preset, presets, CanonicalSource,
    Correspondence, JointPair, MatchMethod, NamingPreset,
};
pub use error::EvalError;
pub use label_table::{
    label_table_json, label_table_markdown, label_table_models, label_table_row, LabelTableRow,
    LABEL_TABLE_KINDS,
};
pub use labels::{label_reference_file, label_score, LabelScore};
pub use metrics::{
    evaluate, figure_size, resolve_measure, ErrorSummary, EvalOptions, Evaluation, FigureMeasure,
    FigureSize, JointError, JointPairing, SizeSource,
};
pub use pose::arms_below_horizontal;
pub use reference::{load_gltf_rig, load_skeleton, parse_json_rig, REFDATA_FORMAT};
pub use regions::reference_regions;
pub use rig::{ReferenceRig, RigFormat};
pub use rigger::{rig_mesh, Orientation, RigAnatomy, RigMethod, Rigged, RiggerOptions};
pub use skin_weights::{reference_skin, ReferenceSkin, VERTEX_MATCH_FRACTION};
pub use study::{
    rotation_study, study_csv, study_markdown, study_table, tessellation_study,
    DisplacementPairing, JointDisplacement, Study, StudyKind, StudyOptions, StudyVariant,
};
pub use table::{
    aggregate, joint_rows, joint_table, key_table, model_row, model_table, percent_cell, to_json,
    write_csv, DatasetSummary, JointRow, KeyRow, ModelRow, Table,
};
pub use warning::EvalWarning;

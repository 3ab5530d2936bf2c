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
//! ```
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
//! let reference = Skeleton { joints: vec![joint("pelvis", None, 1.0), joint("neck", Some(0), 1.5), joint("head", Some(1), 1.7)] };
//! let mut predicted = reference.clone();
//! predicted.joints[2].position.z += 0.01;
//! let result = evaluate(
//!     &ReferenceRig::from_skeleton("guess", predicted),
//!     &ReferenceRig::from_skeleton("truth", reference),
//!     None,
//!     &EvalOptions::default(),
//! )
//! .unwrap();
//! assert_eq!(result.worst_joint, "head");
//! assert!((result.summary.max - 0.01).abs() < 1e-12);
//! ```

mod bvh;
mod chamfer;
mod correspondence;
mod error;
mod metrics;
mod reference;
mod rig;
mod table;
#[cfg(test)]
mod tests;

pub use bvh::parse_bvh;
pub use chamfer::{
    bone_segments, chamfer, point_segment_distance, sample_segments, ChamferDistances,
    ChamferOptions,
};
pub use correspondence::{
    canonical_map, correspond, detect_preset, is_canonical_key, parse_presets, preset, presets,
    CanonicalSource, Correspondence, JointPair, MatchMethod, NamingPreset, CANONICAL_KEYS,
};
pub use error::EvalError;
pub use metrics::{
    evaluate, figure_size, resolve_measure, ErrorSummary, EvalOptions, Evaluation, FigureMeasure,
    FigureSize, JointError, SizeSource,
};
pub use reference::{load_gltf_rig, load_skeleton, parse_json_rig, REFDATA_FORMAT};
pub use rig::{ReferenceRig, RigFormat};
pub use table::{
    aggregate, joint_rows, joint_table, key_table, model_row, model_table, to_json, write_csv,
    DatasetSummary, JointRow, KeyRow, ModelRow, Table,
};

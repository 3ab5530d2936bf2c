//! skelfit's own skeleton JSON (`skelfit-skeleton-v1`).

use super::{check_skeleton, io_error, ExportError};
use crate::skeleton::{Dof, Skeleton};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// The `format` value of skelfit skeleton JSON files.
pub const SKELETON_FORMAT: &str = "skelfit-skeleton-v1";

/// Options of [`skeleton_json`] and [`write_skeleton_json`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct JsonOptions {
    /// Model name written as `model`. Default `None` (omitted; readers use the file name).
    pub model: Option<String>,
    /// Units of the positions (e.g. `"m"`), written as `units`. Default `None` (omitted).
    pub units: Option<String>,
    /// Canonical anatomical key (`pelvis`, `elbow_L`, ...) → joint name, written as
    /// `canonical`. Default empty (omitted).
    pub canonical: BTreeMap<String, String>,
    /// Run information written as `run` after the joints (e.g. stage timings, voxel counts,
    /// warnings). Default `None` (omitted). Timings differ between runs: leave this out where
    /// byte-identical files are wanted.
    pub run: Option<serde_json::Value>,
}

#[derive(Serialize)]
struct Document<'a> {
    format: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    model: Option<&'a str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    units: Option<&'a str>,
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    canonical: &'a BTreeMap<String, String>,
    joints: Vec<JointRecord<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    run: Option<&'a serde_json::Value>,
}

#[derive(Serialize)]
struct JointRecord<'a> {
    name: &'a str,
    parent: Option<&'a str>,
    position: [f64; 3],
    frame: [f64; 4],
    dofs: &'a [Dof],
    deform: bool,
}

/// The skeleton as `skelfit-skeleton-v1` JSON text:
///
/// ```json
/// {"format": "skelfit-skeleton-v1", "model": .., "units": .., "canonical": {key: joint name},
///  "joints": [{"name", "parent": name or null, "position": [x, y, z],
///              "frame": [x, y, z, w], "dofs": [{"axis", "min", "max"}], "deform"}]}
/// ```
///
/// Joints are listed in skeleton order (parents before children), positions in the skeleton's
/// units and frame, `frame` is the rest orientation quaternion, DOF limits in radians. Numbers
/// are printed in the shortest form that reads back to the same `f64`, so
/// [`crate::eval::load_skeleton`] returns the same positions bit for bit. Pretty-printed with
/// two-space indentation and a final newline; the same skeleton gives the same text.
///
/// # Errors
/// [`ExportError::EmptySkeleton`], [`ExportError::InvalidSkeleton`],
/// [`ExportError::UnknownCanonicalJoint`].
pub fn skeleton_json(skeleton: &Skeleton, options: &JsonOptions) -> Result<String, ExportError> {
    check_skeleton(skeleton)?;
    for (key, joint) in &options.canonical {
        if skeleton.find(joint).is_none() {
            return Err(ExportError::UnknownCanonicalJoint {
                key: key.clone(),
                joint: joint.clone(),
            });
        }
    }
    let joints = skeleton
        .joints
        .iter()
        .map(|j| JointRecord {
            name: &j.name,
            parent: j.parent.map(|p| skeleton.joint(p).name.as_str()),
            position: j.position.to_array().map(positive_zero),
            frame: j.frame.to_array().map(positive_zero),
            dofs: &j.dofs,
            deform: j.deform,
        })
        .collect();
    let document = Document {
        format: SKELETON_FORMAT,
        model: options.model.as_deref(),
        units: options.units.as_deref(),
        canonical: &options.canonical,
        joints,
        run: options.run.as_ref(),
    };
    let mut text = serde_json::to_string_pretty(&document).map_err(|e| ExportError::TooLarge {
        what: "the skeleton",
        format: "JSON",
        detail: e.to_string(),
    })?;
    text.push('\n');
    Ok(text)
}

/// Writes [`skeleton_json`] to `path` atomically.
///
/// # Errors
/// As [`skeleton_json`], and [`ExportError::Io`] when the file cannot be written.
pub fn write_skeleton_json(
    path: &Path,
    skeleton: &Skeleton,
    options: &JsonOptions,
) -> Result<(), ExportError> {
    let text = skeleton_json(skeleton, options)?;
    crate::output::write_atomic(path, text.as_bytes()).map_err(|cause| io_error(path, cause))
}

/// `-0.0` → `0.0`, so that equal skeletons print equally.
fn positive_zero(v: f64) -> f64 {
    if v == 0.0 {
        0.0
    } else {
        v
    }
}

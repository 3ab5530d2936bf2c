//! Loading skeletons from files: dispatch on extension and JSON `format`.

use super::{bvh, EvalError, ReferenceRig, RigFormat};
use crate::skeleton::{Joint, JointId, Skeleton};
use glam::DVec3;
use serde::Deserialize;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// The `format` value of refdata reference rigs.
pub const REFDATA_FORMAT: &str = "refdata-skeleton-v1";

/// Loads a skeleton from `path`, choosing the reader from the extension: `.json`
/// (`refdata-skeleton-v1` when its `format` field says so, otherwise skelfit's own
/// `{"joints": [{"name", "parent", "position"}], "canonical": {...}}`), `.bvh`, `.glb`/`.gltf`.
///
/// All joints are kept; use [`ReferenceRig::deforming`] to drop control joints. Positions stay
/// in the file's units and frame.
///
/// # Errors
/// [`EvalError::Io`] for a missing or unreadable file, [`EvalError::UnknownFormat`] for another
/// extension or JSON format, [`EvalError::Parse`] / [`EvalError::InvalidSkeleton`] for bad
/// content.
pub fn load_skeleton(path: &Path) -> Result<ReferenceRig, EvalError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    match extension.as_str() {
        "json" => parse_json_rig(&read_text(path)?, path),
        "bvh" => bvh::parse_bvh(&read_text(path)?, path),
        "glb" | "gltf" => load_gltf_rig(path),
        _ => Err(EvalError::UnknownFormat {
            path: path.to_owned(),
            detail: String::new(),
        }),
    }
}

/// Reads the skeleton of the first skin of a glTF/GLB file in its bind pose (joint `j` at
/// `B · inv(IBM_j) · 0`, the frame of [`crate::mesh::load_gltf`]), keeping the skin's `deform`
/// flags. Positions are in glTF units as authored: no provenance scale is applied.
///
/// # Errors
/// [`EvalError::Mesh`] when the file cannot be read, [`EvalError::NoSkin`] without a skin.
pub fn load_gltf_rig(path: &Path) -> Result<ReferenceRig, EvalError> {
    let scene = crate::mesh::load_gltf_scene(path)?;
    let skeleton = scene.skeleton.ok_or_else(|| EvalError::NoSkin {
        path: path.to_owned(),
    })?;
    Ok(ReferenceRig {
        skeleton,
        canonical: BTreeMap::new(),
        model: model_name(path),
        rig: Some("gltf".into()),
        units: None,
        format: RigFormat::Gltf,
    })
}

fn read_text(path: &Path) -> Result<String, EvalError> {
    std::fs::read_to_string(path).map_err(|cause| EvalError::Io {
        path: path.to_owned(),
        cause,
    })
}

/// A parent given by name (refdata, skelfit) or by index into `joints` (skelfit).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum ParentRef {
    Name(String),
    Index(usize),
}

#[derive(Debug, Deserialize)]
struct JsonJoint {
    name: String,
    #[serde(default)]
    parent: Option<ParentRef>,
    position: [f64; 3],
    #[serde(default = "default_deform")]
    deform: bool,
}

fn default_deform() -> bool {
    true
}

#[derive(Debug, Deserialize)]
struct JsonRig {
    #[serde(default)]
    format: Option<String>,
    #[serde(default)]
    model: Option<String>,
    #[serde(default)]
    rig: Option<String>,
    #[serde(default)]
    units: Option<String>,
    #[serde(default)]
    canonical: BTreeMap<String, String>,
    joints: Vec<JsonJoint>,
}

/// Parses a JSON skeleton: `refdata-skeleton-v1` (when `format` says so) or skelfit's own format
/// (no `format` field, or `"skelfit-skeleton-v1"`). `origin` names the source in messages and
/// gives the model name when the JSON has none.
///
/// # Errors
/// [`EvalError::Parse`] for invalid JSON, [`EvalError::UnknownFormat`] for another `format`,
/// [`EvalError::InvalidSkeleton`] for duplicate names, unknown or late parents, non-finite
/// positions or canonical entries naming missing joints.
pub fn parse_json_rig(text: &str, origin: &Path) -> Result<ReferenceRig, EvalError> {
    let raw: JsonRig = serde_json::from_str(text).map_err(|e| EvalError::Parse {
        path: origin.to_owned(),
        format: "json",
        message: e.to_string(),
    })?;
    let format = match raw.format.as_deref() {
        Some(REFDATA_FORMAT) => RigFormat::Refdata,
        None | Some("skelfit-skeleton-v1") => RigFormat::Skelfit,
        Some(other) => {
            return Err(EvalError::UnknownFormat {
                path: origin.to_owned(),
                detail: format!(" (JSON format {other:?})"),
            })
        }
    };
    let mut names: HashMap<&str, JointId> = HashMap::new();
    let mut joints = Vec::with_capacity(raw.joints.len());
    let invalid = |message: String| EvalError::InvalidSkeleton {
        path: origin.to_owned(),
        message,
    };
    for (index, joint) in raw.joints.iter().enumerate() {
        let position = DVec3::from_array(joint.position);
        if !position.is_finite() {
            return Err(invalid(format!(
                "joint {:?} has a non-finite position {:?}",
                joint.name, joint.position
            )));
        }
        let parent = match &joint.parent {
            None => None,
            Some(ParentRef::Name(name)) => Some(*names.get(name.as_str()).ok_or_else(|| {
                invalid(format!(
                    "joint {:?} names parent {name:?}, which is not listed before it; list parents before children",
                    joint.name
                ))
            })?),
            Some(ParentRef::Index(p)) if *p < index => Some(JointId(*p)),
            Some(ParentRef::Index(p)) => {
                return Err(invalid(format!(
                    "joint {:?} (index {index}) has parent index {p}; parents must come before children",
                    joint.name
                )))
            }
        };
        if names.insert(&joint.name, JointId(index)).is_some() {
            return Err(invalid(format!(
                "joint name {:?} occurs twice; names must be unique",
                joint.name
            )));
        }
        joints.push(Joint {
            name: joint.name.clone(),
            parent,
            position,
            deform: joint.deform,
            ..Default::default()
        });
    }
    let mut canonical = BTreeMap::new();
    for (key, name) in &raw.canonical {
        let id = names.get(name.as_str()).ok_or_else(|| {
            invalid(format!(
                "canonical key {key:?} names joint {name:?}, which does not exist"
            ))
        })?;
        canonical.insert(key.clone(), *id);
    }
    Ok(ReferenceRig {
        skeleton: Skeleton { joints },
        canonical,
        model: raw.model.unwrap_or_else(|| model_name(origin)),
        rig: raw.rig,
        units: raw.units,
        format,
    })
}

/// The model name implied by a path: the parent directory for refdata-style `rig_*.json` /
/// `source.glb` files, else the file stem.
pub(crate) fn model_name(path: &Path) -> String {
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("skeleton");
    let generic = stem.starts_with("rig_") || stem == "source" || stem == "mesh";
    match path
        .parent()
        .and_then(|p| p.file_name())
        .and_then(|s| s.to_str())
    {
        Some(dir) if generic => dir.to_owned(),
        _ => stem.to_owned(),
    }
}

use std::path::PathBuf;
use thiserror::Error;

/// Errors from loading reference rigs or comparing skeletons. Messages name the problem and
/// what to do about it.
#[derive(Debug, Error)]
pub enum EvalError {
    /// The file could not be opened or read.
    #[error("cannot read {path}: {cause}; {}", io_hint(cause))]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying I/O error (part of the message, hence not a `source()`).
        cause: std::io::Error,
    },
    /// The file extension (or JSON `format` field) is not one skelfit reads skeletons from.
    #[error("unknown skeleton format for {path}{detail}: expected .json (refdata-skeleton-v1 or skelfit), .bvh, .glb or .gltf")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
        /// Extra context, e.g. ` (format "foo-v9")`; may be empty.
        detail: String,
    },
    /// Reading a glTF/GLB file (or a mesh) failed.
    #[error(transparent)]
    Mesh(#[from] crate::mesh::MeshError),
    /// A glTF/GLB file has no skinned mesh, so there is no skeleton to read.
    #[error("{path} has no skinned mesh, so it holds no skeleton: export the armature with its mesh (skinned)")]
    NoSkin {
        /// The file.
        path: PathBuf,
    },
    /// The file is not valid in its format.
    #[error("{path} is not a valid {format} skeleton: {message}")]
    Parse {
        /// The file (or `<string>` for in-memory input).
        path: PathBuf,
        /// The format that was expected (refdata json, skelfit json, bvh, gltf).
        format: &'static str,
        /// What the parser reported, with a line number where known.
        message: String,
    },
    /// The skeleton is structurally invalid (duplicate names, unknown or late parents, NaN).
    #[error("invalid skeleton in {path}: {message}")]
    InvalidSkeleton {
        /// The file.
        path: PathBuf,
        /// What is wrong, naming the joint.
        message: String,
    },
    /// The skeleton has no joints (or none that deform).
    #[error("the skeleton {what} has no joints to evaluate: check the file or evaluate all joints instead of deforming ones")]
    Empty {
        /// Which skeleton (predicted/reference and its model name).
        what: String,
    },
    /// A joint lies so far out that its distances overflow (e.g. a coordinate of 1e300).
    #[error("the {role} joint {joint:?} at {position:?} is so far out that its distances overflow: check the file's coordinates and units")]
    NonFinite {
        /// `predicted` or `reference`.
        role: String,
        /// The joint's name.
        joint: String,
        /// Its position.
        position: [f64; 3],
    },
    /// The two skeletons share neither canonical anatomical keys nor joint names.
    #[error("the predicted and reference skeletons share no joints: predicted has [{}], reference has [{}]; add a `canonical` map or use a naming preset (mixamo, unity_humanoid, makehuman_game_engine)", capped(predicted), capped(reference))]
    NoSharedJoints {
        /// The predicted skeleton's canonical keys (or joint names when it has none).
        predicted: Vec<String>,
        /// The reference skeleton's canonical keys (or joint names when it has none).
        reference: Vec<String>,
    },
    /// A naming preset file in templates/presets is malformed (a build defect).
    #[error("naming preset {name} is invalid: {message}")]
    Preset {
        /// The preset name.
        name: String,
        /// What is wrong.
        message: String,
    },
    /// A benchmark folder holds no model folders.
    #[error("no model folders (mesh.obj with rig_<rig>.json files) found in {path}: pass a refdata-style folder such as data or ../shared/refdata")]
    NoModels {
        /// The folder searched.
        path: PathBuf,
    },
    /// A study was given invalid parameters.
    #[error("invalid study parameter: {message}")]
    Study {
        /// What is wrong, naming the value.
        message: String,
    },
    /// Writing a table failed.
    #[error("cannot write the {what} table: {message}")]
    Table {
        /// Which table (joints, models, dataset).
        what: &'static str,
        /// The underlying error.
        message: String,
    },
}

/// What to check after an I/O error: the encoding for text that is not UTF-8, else the path.
fn io_hint(cause: &std::io::Error) -> &'static str {
    match cause.kind() {
        std::io::ErrorKind::InvalidData => "the file is not UTF-8 text",
        _ => "check the path and permissions",
    }
}

/// Names listed in a message: at most [`LISTED_NAMES`], then how many more.
fn capped(names: &[String]) -> String {
    let shown: Vec<&str> = names
        .iter()
        .take(LISTED_NAMES)
        .map(|n| cap_chars(n))
        .collect();
    match names.len().checked_sub(LISTED_NAMES) {
        Some(more) if more > 0 => format!("{}, ... and {more} more", shown.join(", ")),
        _ => shown.join(", "),
    }
}

/// At most 40 characters of a name.
fn cap_chars(name: &str) -> &str {
    name.char_indices()
        .nth(40)
        .map_or(name, |(cut, _)| &name[..cut])
}

/// How many joint names an error message lists.
const LISTED_NAMES: usize = 12;

//! Errors of the exporters.

use std::path::PathBuf;

/// Why a rig could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// Writing the file failed.
    #[error("cannot write {path}: {cause}; check the folder exists and is writable")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error (part of the message, hence not a `source()`, which would print it
        /// twice in an error chain).
        cause: std::io::Error,
    },
    /// The skeleton has no joints.
    #[error("the skeleton has no joints: nothing to export")]
    EmptySkeleton,
    /// The skeleton breaks its invariants.
    #[error("the skeleton is invalid: {message}")]
    InvalidSkeleton {
        /// The problems found, joined.
        message: String,
    },
    /// A joint name cannot be written in this format.
    #[error("joint name {name:?} cannot be written as {format}: {reason}; rename the joint")]
    InvalidName {
        /// The name.
        name: String,
        /// The format.
        format: &'static str,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// The skin, mesh and skeleton do not belong together.
    #[error("{what} has {found} entries but {expected} are needed: export the skin with the mesh and skeleton it was made for")]
    SizeMismatch {
        /// Which input.
        what: &'static str,
        /// Entries needed.
        expected: usize,
        /// Entries given.
        found: usize,
    },
    /// A mesh vertex or weight is not finite.
    #[error("{what} {index} is not finite: export meshes and skins built by skelfit, which keep every value finite")]
    NonFinite {
        /// What is not finite (`"vertex"`, `"weight of vertex"`).
        what: &'static str,
        /// Its index.
        index: usize,
    },
    /// The mesh has no triangles.
    #[error("the mesh has no triangles: export a mesh with at least one triangle")]
    EmptyMesh,
    /// A canonical key names a joint the skeleton does not have.
    #[error("canonical key {key:?} names joint {joint:?}, which the skeleton does not have: pass names of existing joints")]
    UnknownCanonicalJoint {
        /// The canonical key.
        key: String,
        /// The joint name given.
        joint: String,
    },
    /// The data does not fit the format's limits.
    #[error("{what} is too large for {format}: {detail}")]
    TooLarge {
        /// What overflowed.
        what: &'static str,
        /// The format.
        format: &'static str,
        /// Details.
        detail: String,
    },
    /// The user's model refers to data it does not hold (a buffer view beyond its buffer).
    #[error(
        "the input model cannot be written back: {message}; re-export it from the modelling tool"
    )]
    InvalidSource {
        /// What is wrong, with the glTF index.
        message: String,
    },
}

/// Rejects empty or invalid skeletons.
pub(super) fn check_skeleton(skeleton: &crate::skeleton::Skeleton) -> Result<(), ExportError> {
    if skeleton.is_empty() {
        return Err(ExportError::EmptySkeleton);
    }
    skeleton
        .validate()
        .map_err(|problems| ExportError::InvalidSkeleton {
            message: problems
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; "),
        })
}

/// Wraps an I/O error with the path written.
pub(super) fn io_error(path: &std::path::Path, cause: std::io::Error) -> ExportError {
    ExportError::Io {
        path: path.to_owned(),
        cause,
    }
}

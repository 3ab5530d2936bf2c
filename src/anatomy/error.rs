//! Errors of the anatomy stage.

use thiserror::Error;

/// What can go wrong while building the level graph or labelling body parts.
#[derive(Debug, Error)]
pub enum AnatomyError {
    /// An option is out of its documented range.
    #[error("anatomy option {name} = {value} is out of range: {expected}")]
    InvalidOption {
        /// Name of the option field.
        name: &'static str,
        /// The offending value.
        value: f64,
        /// The valid range, in words.
        expected: &'static str,
    },
    /// The up or forward direction is zero, not finite, or the two are parallel.
    #[error("invalid orientation: {detail}; give --up and --forward as different axes such as +Y and +Z")]
    InvalidOrientation {
        /// What is wrong.
        detail: String,
    },
    /// The medial surface has no voxel.
    #[error("the medial surface is empty: nothing to label (use a smaller voxel size)")]
    EmptySurface,
    /// The pieces given to [`label_pieces`](super::label_pieces) come from different grids.
    #[error("the solid, distance map and medial surface were computed on different grids")]
    GridMismatch,
    /// A labels override file could not be read or parsed.
    #[error("labels override {path}: {detail}")]
    Override {
        /// The file.
        path: String,
        /// What is wrong with it.
        detail: String,
    },
}

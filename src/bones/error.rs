//! Errors of bone generation.

/// Why bones could not be generated. Missing body parts are not errors: they give warnings in
/// [`super::Bones::warnings`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BoneError {
    /// An option is out of its valid range.
    #[error("bone option {name} = {value} is outside {range}: use a value in range")]
    BadOption {
        /// The field name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The valid range.
        range: &'static str,
    },
    /// The skeleton has no joints.
    #[error("the skeleton has no joints: fit a skeleton before generating bones")]
    EmptySkeleton,
    /// The skeleton breaks its invariants (parent order, non-finite positions or frames).
    #[error("the skeleton is invalid: {message}")]
    InvalidSkeleton {
        /// The problems found, joined.
        message: String,
    },
    /// The distance map has no interior voxel.
    #[error("the distance map has no interior voxel: voxelize a closed figure first")]
    EmptyDistanceMap,
}

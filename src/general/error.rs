//! Errors of the general control skeleton stage.

use thiserror::Error;

/// Errors from [`control_skeleton`](super::control_skeleton): out-of-range options (Table 5.2).
#[derive(Debug, Clone, Error, PartialEq)]
pub enum GeneralError {
    /// The approximation error is negative or NaN.
    #[error("approximation error {value} is out of range: use a value >= 0 in voxel units (default 0.4)")]
    InvalidApproximationError {
        /// The value given.
        value: f64,
    },
    /// The min fraction is not in `[0, 1]`.
    #[error("min fraction {value} is out of range: use a value in [0, 1] (default 0.1)")]
    InvalidMinFraction {
        /// The value given.
        value: f64,
    },
    /// The max fraction is not in `[0, 1]`.
    #[error("max fraction {value} is out of range: use a value in [0, 1] (default 0.3)")]
    InvalidMaxFraction {
        /// The value given.
        value: f64,
    },
    /// The min fraction exceeds the max fraction.
    #[error("min fraction {min} exceeds max fraction {max}: use a min fraction no larger than the max fraction")]
    FractionsOutOfOrder {
        /// The min fraction given.
        min: f64,
        /// The max fraction given.
        max: f64,
    },
    /// The number of segments is zero.
    #[error("number of segments {value} is invalid: use at least 1, or leave it unset")]
    InvalidSegments {
        /// The value given.
        value: usize,
    },
    /// The up direction is zero or not finite.
    #[error("up direction {value:?} is invalid: use a finite, non-zero vector such as [0, 1, 0]")]
    InvalidUp {
        /// The value given.
        value: [f64; 3],
    },
}

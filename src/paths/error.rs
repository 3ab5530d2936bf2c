//! Errors of the path-tree stage.

use thiserror::Error;

/// Errors from [`path_tree`](super::path_tree).
#[derive(Debug, Clone, Error, PartialEq)]
pub enum PathError {
    /// The closeness of fit is not in `[0, 1]`.
    #[error("closeness of fit {value} is out of range: use a value in [0, 1] (default 0.1; dissertation ch.5.2.4 recommends 0.05 to 0.1)")]
    InvalidCloseness {
        /// The value given.
        value: f64,
    },
    /// No heart sample was requested.
    #[error("heart samples {value} is invalid: use at least 1 (default 64)")]
    InvalidHeartSamples {
        /// The value given.
        value: usize,
    },
    /// The extreme-point group radius is negative or not finite.
    #[error("extreme point group radius {value} is invalid: use a finite number of voxels >= 0 (default 5)")]
    InvalidGroupRadius {
        /// The value given.
        value: f64,
    },
    /// The medial surface has no voxel.
    #[error("the medial surface is empty: voxelize the figure with a smaller voxel size")]
    EmptySurface,
}

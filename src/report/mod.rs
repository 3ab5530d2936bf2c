//! Reports: pictures of the voxel stages, evaluation tables and HTML pages.

mod slices;

pub use slices::{distance_slice, png_bytes, RgbImage};

use thiserror::Error;

/// Errors from writing reports.
#[derive(Debug, Error)]
pub enum ReportError {
    /// An I/O error.
    #[error("i/o error: {0}")]
    Io(#[from] std::io::Error),
}

//! report (being implemented).

use thiserror::Error;

/// Errors from writing reports.
#[derive(Debug, Error)]
pub enum ReportError {
    /// An I/O error.
    #[error("i/o error: {0}")]
    Io(#[from] std::io::Error),
}

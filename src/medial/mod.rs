//! medial (being implemented).

use thiserror::Error;

/// Errors from building the discrete medial surface.
#[derive(Debug, Error)]
pub enum MedialError {
    /// An I/O error.
    #[error("i/o error: {0}")]
    Io(#[from] std::io::Error),
}

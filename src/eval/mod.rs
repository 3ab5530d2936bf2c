//! eval (being implemented).

use thiserror::Error;

/// Errors from loading or comparing skeletons.
#[derive(Debug, Error)]
pub enum EvalError {
    /// An I/O error.
    #[error("i/o error: {0}")]
    Io(#[from] std::io::Error),
}

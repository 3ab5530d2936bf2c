use std::path::PathBuf;
use thiserror::Error;

/// Errors from writing reports. Messages name the file and what to do.
#[derive(Debug, Error)]
pub enum ReportError {
    /// The report file could not be written.
    #[error("cannot write {path}: {cause}; check that the directory exists and is writable")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying I/O error (part of the message, hence not a `source()`).
        cause: std::io::Error,
    },
}

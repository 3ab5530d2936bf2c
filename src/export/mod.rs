//! Export (in progress).
mod error;
pub use error::ExportError;

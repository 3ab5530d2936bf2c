//! Warnings: what a stage could not do, and how much it matters. Each stage with typed
//! warnings has its own enum (e.g. [`crate::refine::RefineWarning`]) that says its
//! [`Severity`].

use serde::{Deserialize, Serialize};

/// How much a warning matters, least first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Severity {
    /// Something worth knowing; the result is as good as without it.
    Info,
    /// A part was placed less well than it could have been (e.g. kept at its rough position).
    Degraded,
    /// A part is missing from the result.
    PartMissing,
}

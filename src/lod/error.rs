//! Why a level-of-detail operation could not be applied.

/// Errors of the level-of-detail operations.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LodError {
    /// A threshold is negative or not finite.
    #[error("level-of-detail threshold {name} = {value} is invalid: give a finite value >= 0 (0 turns the operation off)")]
    InvalidThreshold {
        /// Name of the threshold.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// The scope names a joint the skeleton does not have.
    #[error("the skeleton has no joint called {name}: name a joint of the skeleton (see its JSON) as the part or branch")]
    UnknownJoint {
        /// The name given.
        name: String,
    },
    /// The skeleton breaks its invariants.
    #[error("the skeleton is invalid: {message}")]
    InvalidSkeleton {
        /// The problems found, joined.
        message: String,
    },
}

//! Thresholds and scope of the level-of-detail operations.

use super::LodError;

/// Which joints an operation may change.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub enum LodScope {
    /// Every joint (seed 003's global level).
    #[default]
    Global,
    /// The named joint and its descendants (seed 003's subpart level).
    Part(String),
    /// The branch that starts at the named joint: it and its descendants down to the first
    /// junction or terminal joint (seed 003's branch level).
    Branch(String),
}

/// Options of [`level_of_detail`](super::level_of_detail). Thresholds are in skeleton units
/// (the mesh's or outline's units); 0 turns an operation off. Seed 003 uses ε_s = 5,
/// ε_m = 30, ε_t = 30, ε_c = 10 pixels for sketches a few hundred pixels across; here the
/// default is 0 (no change) because skeleton units vary.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LodOptions {
    /// ε_s: Douglas-Peucker tolerance along branches.
    pub simplify: f64,
    /// ε_m: junction joints linked through at most this much bone length are merged.
    pub merge: f64,
    /// ε_t: junction-to-terminal branches shorter than this are pruned.
    pub prune: f64,
    /// ε_c: bones between internal joints shorter than this are collapsed.
    pub collapse: f64,
    /// Where the operations apply.
    pub scope: LodScope,
}

impl LodOptions {
    /// Whether every operation is off.
    pub fn is_identity(&self) -> bool {
        self.simplify == 0.0 && self.merge == 0.0 && self.prune == 0.0 && self.collapse == 0.0
    }

    /// Checks every threshold is finite and non-negative.
    ///
    /// # Errors
    /// [`LodError::InvalidThreshold`] naming the first bad threshold.
    pub fn validate(&self) -> Result<(), LodError> {
        for (name, value) in [
            ("simplify", self.simplify),
            ("merge", self.merge),
            ("prune", self.prune),
            ("collapse", self.collapse),
        ] {
            check_threshold(name, value)?;
        }
        Ok(())
    }
}

/// Rejects negative and non-finite thresholds.
pub(crate) fn check_threshold(name: &'static str, value: f64) -> Result<(), LodError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(LodError::InvalidThreshold { name, value })
    }
}

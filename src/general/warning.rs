//! What the general control skeleton could not build as asked.

use crate::warning::Severity;
use std::fmt;

/// Something about a general control skeleton the user should know.
#[derive(Debug, Clone, PartialEq)]
pub enum GeneralWarning {
    /// The segment limit is below the number of chains: every chain keeps one segment.
    SegmentLimitBelowChains {
        /// The limit asked for ([`super::GeneralOptions::segments`]).
        limit: usize,
        /// Chains of the path tree.
        chains: usize,
    },
    /// The skeleton has a single joint: the path tree has no chain.
    SingleJoint,
}

impl GeneralWarning {
    /// How much it matters.
    pub fn severity(&self) -> Severity {
        match self {
            Self::SegmentLimitBelowChains { .. } => Severity::Info,
            Self::SingleJoint => Severity::PartMissing,
        }
    }

    /// A stable snake_case id of the variant.
    pub fn code(&self) -> &'static str {
        match self {
            Self::SegmentLimitBelowChains { .. } => "segment_limit_below_chains",
            Self::SingleJoint => "single_joint",
        }
    }
}

impl fmt::Display for GeneralWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::SegmentLimitBelowChains { limit, chains } => write!(
                f,
                "number of segments {limit} is below the {chains} chains of the path tree: every chain keeps one segment"
            ),
            Self::SingleJoint => write!(
                f,
                "the skeleton has a single joint: the path tree has no chain"
            ),
        }
    }
}

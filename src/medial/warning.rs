//! What makes a discrete medial surface less useful than it should be.

use crate::warning::Severity;
use std::fmt;
use std::ops::RangeInclusive;

/// Something about a medial surface the user should know (a degenerate DMS, a disconnected
/// figure...).
#[derive(Debug, Clone, PartialEq)]
pub enum MedialWarning {
    /// The exposure threshold is outside the useful range of ch.4.4.
    UnusualThreshold {
        /// The threshold used.
        threshold: f64,
        /// The useful range.
        useful: RangeInclusive<f64>,
    },
    /// The medial surface is a single voxel: the figure is nowhere more than about two voxels
    /// thick.
    SingleVoxel {
        /// Interior voxels of the figure.
        interior_voxels: usize,
    },
    /// DMS voxels kept below the exposure threshold only to start a group.
    ForcedFounders {
        /// How many.
        count: usize,
    },
    /// The figure has several separate 26-connected parts.
    SeveralComponents {
        /// How many.
        components: usize,
    },
}

impl MedialWarning {
    /// How much it matters.
    pub fn severity(&self) -> Severity {
        match self {
            Self::UnusualThreshold { .. } | Self::ForcedFounders { .. } => Severity::Info,
            Self::SingleVoxel { .. } | Self::SeveralComponents { .. } => Severity::Degraded,
        }
    }

    /// A stable snake_case id of the variant.
    pub fn code(&self) -> &'static str {
        match self {
            Self::UnusualThreshold { .. } => "unusual_threshold",
            Self::SingleVoxel { .. } => "single_voxel",
            Self::ForcedFounders { .. } => "forced_founders",
            Self::SeveralComponents { .. } => "several_components",
        }
    }
}

impl fmt::Display for MedialWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnusualThreshold { threshold, useful } => write!(
                f,
                "exposure threshold {threshold} is outside the useful range {useful:?} of ch.4.4: expect a DMS that is too detailed (low) or too sparse (high)"
            ),
            Self::SingleVoxel { interior_voxels } => write!(
                f,
                "the medial surface is a single voxel (the figure has {interior_voxels} interior voxels and is nowhere more than about two voxels thick): use a smaller voxel size"
            ),
            Self::ForcedFounders { count } => write!(
                f,
                "{count} DMS voxels were kept below the exposure threshold only to start a group: lower the exposure threshold or use a smaller voxel size"
            ),
            Self::SeveralComponents { components } => write!(
                f,
                "the figure has {components} separate 26-connected parts, so the medial surface has {components} components: keep only the largest part when voxelizing"
            ),
        }
    }
}

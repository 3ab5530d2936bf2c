//! What [`fit_input`](super::fit_input) could not build from the labels.

use super::Side;
use crate::anatomy::Label;
use crate::template::LimbKind;
use crate::warning::Severity;
use std::fmt;

/// A path between the labelled parts that could not be built, or a limb too short to be one.
#[derive(Debug, Clone, PartialEq)]
pub enum FitInputWarning {
    /// No medial path joins the two limbs of a labelled pair: the pair is left out.
    UnjoinedPair {
        /// The pair's label.
        label: Label,
    },
    /// No head was labelled: the head-to-tail path starts at the figure's top (upright) or
    /// front trunk voxel.
    NoHead,
    /// An unpaired limb has no medial path to the head-to-tail path: it is left out.
    UnreachedLimb {
        /// Its side (`None`: unpaired without a side).
        side: Option<Side>,
        /// Its label.
        label: Label,
    },
    /// A limb shorter than [`FitInputOptions::min_limb_slenderness`](super::FitInputOptions)
    /// times its median radius: a stub rather than a limb.
    Stub {
        /// Its side.
        side: Side,
        /// Its kind.
        kind: LimbKind,
        /// Its length over its median radius.
        slenderness: f64,
    },
}

impl FitInputWarning {
    /// How much it matters: every variant degrades the fit (a part left out is named again
    /// by the fit's own warnings).
    pub fn severity(&self) -> Severity {
        Severity::Degraded
    }

    /// The stable snake_case id: `path` for every variant, the code these warnings had as
    /// sentences, so JSON written before compares with JSON written now.
    pub fn code(&self) -> &'static str {
        "path"
    }
}

impl fmt::Display for FitInputWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnjoinedPair { label } => write!(
                f,
                "no medial path joins the left and right {}: left out",
                label.name()
            ),
            Self::NoHead => f.write_str(
                "no head was labelled: the head-to-tail path starts at the figure's top (upright) or front voxel",
            ),
            Self::UnreachedLimb { side, label } => write!(
                f,
                "the {} {} does not reach the head-to-tail path: left out",
                side.map_or("unpaired", Side::as_str),
                label.name()
            ),
            Self::Stub {
                side,
                kind,
                slenderness,
            } => write!(
                f,
                "the {} {} is only {:.1} times as long as it is thick: a stub rather than a limb; check the labels (skelfit label) or choose another template",
                side.as_str(),
                kind.as_str().replace('_', " "),
                slenderness
            ),
        }
    }
}

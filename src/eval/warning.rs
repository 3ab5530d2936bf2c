//! What makes an evaluation less complete or less trustworthy than it should be.

use crate::warning::Severity;
use std::fmt;

/// Something the caller of an evaluation should tell the user.
#[derive(Debug, Clone, PartialEq)]
pub enum EvalWarning {
    /// Two sizes differ beyond [`super::EvalOptions::unit_mismatch_ratio`]: a unit mismatch?
    UnitMismatch {
        /// What was compared (`the predicted and reference figure sizes`).
        what: &'static str,
        /// The first size.
        first: f64,
        /// The second size.
        second: f64,
    },
    /// No canonical keys shared and too few joint names coincide: only chamfer distances.
    FewSharedNames {
        /// The joint names that coincide.
        names: Vec<String>,
        /// Joints of the reference.
        reference_joints: usize,
    },
    /// The skeletons share no joints: only chamfer distances.
    NoSharedJoints {
        /// Predicted joints without canonical names.
        predicted: usize,
        /// Reference joints without canonical names.
        reference: usize,
    },
    /// The figure size is zero: percentages are 0.
    ZeroFigureSize,
}

impl EvalWarning {
    /// How much it matters: per-joint errors missing are a missing part of the evaluation.
    pub fn severity(&self) -> Severity {
        match self {
            Self::UnitMismatch { .. } | Self::ZeroFigureSize => Severity::Degraded,
            Self::FewSharedNames { .. } | Self::NoSharedJoints { .. } => Severity::PartMissing,
        }
    }

    /// A stable snake_case id of the variant.
    pub fn code(&self) -> &'static str {
        match self {
            Self::UnitMismatch { .. } => "unit_mismatch",
            Self::FewSharedNames { .. } => "few_shared_names",
            Self::NoSharedJoints { .. } => "no_shared_joints",
            Self::ZeroFigureSize => "zero_figure_size",
        }
    }
}

impl fmt::Display for EvalWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnitMismatch {
                what,
                first,
                second,
            } => write!(
                f,
                "{what} differ by {:.1}x ({first:.4} vs {second:.4}): check that both use the same units (e.g. m vs cm)",
                first.max(*second) / first.min(*second)
            ),
            Self::FewSharedNames {
                names,
                reference_joints,
            } => write!(
                f,
                "per-joint errors are unavailable: no canonical keys are shared and only {} of the reference's {} joint names coincide ({}); only the chamfer distances are reported",
                names.len(),
                reference_joints,
                names.join(", ")
            ),
            Self::NoSharedJoints {
                predicted,
                reference,
            } => write!(
                f,
                "per-joint errors are unavailable: the skeletons share no joints (predicted has {predicted} joints without canonical names, reference has {reference}); only the chamfer distances are reported"
            ),
            Self::ZeroFigureSize => write!(
                f,
                "the figure size is zero, so percentages are reported as 0: pass the mesh"
            ),
        }
    }
}

//! What the drivers decided for the user: the template chosen, and stages that fell back.

use crate::warning::Severity;
use std::fmt;

/// How the label shown when [`label_by_bones`](super::label_by_bones) kept the medial
/// per-vertex labels begins.
pub const MEDIAL_FALLBACK: &str = "per-vertex labels follow the medial surface, not bones";

/// A decision or fallback of [`rig`](super::rig), [`general_rig`](super::general_rig) or
/// [`label_by_bones`](super::label_by_bones).
#[derive(Debug, Clone, PartialEq)]
pub enum RigWarning {
    /// No built-in template fits ([`no_template_fits`](super::no_template_fits)): the general
    /// control skeleton was fitted instead.
    NoTemplateFits {
        /// Why none fits.
        reason: String,
    },
    /// The figure class is unknown: the template was chosen by the limbs found.
    UnknownFigureClass {
        /// The template fitted.
        template: &'static str,
        /// The trunk's angle from up, degrees.
        trunk_angle: f64,
    },
    /// The refinement failed: the fitted joints are kept.
    RefineFailed {
        /// The refinement's error.
        error: String,
    },
    /// The rig failed after the labelling: the per-vertex labels follow the medial surface.
    MedialLabels {
        /// The rig's error.
        error: String,
    },
    /// No segment of the skeleton reaches inside the figure: the mesh is skinned to the
    /// nearest bones instead.
    SkinnedToBones,
}

impl RigWarning {
    /// How much it matters.
    pub fn severity(&self) -> Severity {
        match self {
            Self::NoTemplateFits { .. } | Self::MedialLabels { .. } => Severity::PartMissing,
            Self::UnknownFigureClass { .. } | Self::RefineFailed { .. } => Severity::Degraded,
            Self::SkinnedToBones => Severity::Info,
        }
    }

    /// A stable snake_case id of the variant.
    pub fn code(&self) -> &'static str {
        match self {
            Self::NoTemplateFits { .. } => "no_template_fits",
            Self::UnknownFigureClass { .. } => "unknown_figure_class",
            Self::RefineFailed { .. } => "refine_failed",
            Self::MedialLabels { .. } => "medial_labels",
            Self::SkinnedToBones => "skinned_to_bones",
        }
    }
}

impl fmt::Display for RigWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoTemplateFits { reason } => write!(
                f,
                "no template fits: {reason}; fitted the general control skeleton (joints named root, joint_NNN, end_NNN; no canonical joints); choose a template with --template to force one"
            ),
            Self::UnknownFigureClass {
                template,
                trunk_angle,
            } => write!(
                f,
                "the figure class is unknown (trunk {trunk_angle:.0} degrees from up): fitted the {template} template; choose one with --template if it is wrong"
            ),
            Self::RefineFailed { error } => {
                write!(f, "refine: {error}; the fitted joints are kept")
            }
            Self::MedialLabels { error } => {
                write!(f, "{MEDIAL_FALLBACK}: the rig failed ({error})")
            }
            Self::SkinnedToBones => write!(
                f,
                "no segment of the skeleton reaches inside the figure (a figure without limbs): \
                 the mesh is skinned to the nearest bones instead"
            ),
        }
    }
}

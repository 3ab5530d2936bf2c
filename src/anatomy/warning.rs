//! What the labelling could not identify, and how the figure's orientation was found.

use super::Side;
use crate::warning::Severity;
use glam::DVec3;
use std::fmt;

/// Something about the labelling the user should know.
#[derive(Debug, Clone, PartialEq)]
pub enum AnatomyWarning {
    /// Up was found automatically (see [`super::find_up`]), or could not be and +Y was kept.
    UpFound {
        /// The direction chosen.
        up: DVec3,
        /// Confidence in [0, 1]; 0 when no direction gave a complete figure.
        confidence: f64,
        /// The sentence saying how ([`super::UpChoice::note`]).
        note: String,
    },
    /// Forward was found from the figure (`Forward::Auto`) and is not the file's convention.
    ForwardGuessed {
        /// The direction found.
        forward: DVec3,
        /// Confidence in [0, 1] ([`super::ForwardChoice::confidence`]).
        confidence: f64,
        /// From what.
        reason: String,
    },
    /// The medial surface has several parts: only the largest is labelled.
    LargestPartOnly {
        /// DMS voxels of the labelled part.
        labelled: usize,
        /// DMS voxels in all.
        voxels: usize,
    },
    /// No major junction: no clear trunk, so no limbs, head or tail.
    NoMajorJunction,
    /// No head could be identified.
    NoHead,
    /// A single arm without its partner.
    SingleArm {
        /// Its section.
        section: usize,
        /// Its side.
        side: Side,
    },
    /// An odd number of legs: some could not be paired.
    OddLegs {
        /// Legs found.
        legs: usize,
        /// Legs left unpaired.
        unpaired: usize,
    },
    /// More than two leg pairs: the figure is not vertebrate-like (the anterior half of the
    /// pairs are fore legs).
    TooManyLegPairs {
        /// Leg pairs found.
        pairs: usize,
    },
    /// No protrusion reaches the bottom of the figure.
    NoLegs,
    /// A long protrusion matched no rule and was merged into the trunk.
    UnidentifiedProtrusion {
        /// Its section.
        section: usize,
        /// Its DMS voxels.
        voxels: usize,
        /// Its distal point, mesh units.
        reach: DVec3,
    },
    /// The arms hang against the body: found on transverse slices of the mesh and cut apart
    /// from the body in the voxels before the figure was labelled again
    /// ([`super::hanging_arms`]).
    ArmsSeparated {
        /// Transverse levels (one voxel apart) each arm was found on (left, right).
        levels: [usize; 2],
        /// Interior voxels cut.
        voxels: usize,
    },
}

impl AnatomyWarning {
    /// How much it matters.
    pub fn severity(&self) -> Severity {
        match self {
            Self::UpFound { confidence, .. } if *confidence <= 0.0 => Severity::Degraded,
            Self::UpFound { .. } | Self::ForwardGuessed { .. } | Self::ArmsSeparated { .. } => {
                Severity::Info
            }
            Self::LargestPartOnly { .. }
            | Self::OddLegs { .. }
            | Self::TooManyLegPairs { .. }
            | Self::UnidentifiedProtrusion { .. } => Severity::Degraded,
            Self::NoMajorJunction | Self::NoHead | Self::SingleArm { .. } | Self::NoLegs => {
                Severity::PartMissing
            }
        }
    }

    /// A stable snake_case id of the variant.
    pub fn code(&self) -> &'static str {
        match self {
            Self::UpFound { .. } => "up_found",
            Self::ForwardGuessed { .. } => "forward_guessed",
            Self::LargestPartOnly { .. } => "largest_part_only",
            Self::NoMajorJunction => "no_major_junction",
            Self::NoHead => "no_head",
            Self::SingleArm { .. } => "single_arm",
            Self::OddLegs { .. } => "odd_legs",
            Self::TooManyLegPairs { .. } => "too_many_leg_pairs",
            Self::NoLegs => "no_legs",
            Self::UnidentifiedProtrusion { .. } => "unidentified_protrusion",
            Self::ArmsSeparated { .. } => "arms_separated",
        }
    }
}

impl fmt::Display for AnatomyWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UpFound { note, .. } => f.write_str(note),
            Self::ForwardGuessed {
                forward,
                confidence,
                reason,
            } => write!(
                f,
                "the figure faces ({:.3}, {:.3}, {:.3}), not the file's forward axis: {reason} (confidence {confidence:.2}); give --forward if it faces another way",
                forward.x, forward.y, forward.z
            ),
            Self::LargestPartOnly { labelled, voxels } => write!(
                f,
                "the medial surface has several parts: only the largest ({labelled} of {voxels} voxels) is labelled, the rest takes the labels of the nearest labelled voxels"
            ),
            Self::NoMajorJunction => write!(
                f,
                "no major junction: the figure has no clear trunk, so no limbs, head or tail could be identified"
            ),
            Self::NoHead => write!(f, "no head could be identified"),
            Self::SingleArm { section, side } => write!(
                f,
                "found a single arm (section {section}, on the {} side): its partner is missing",
                if *side == Side::Left { "left" } else { "right" }
            ),
            Self::OddLegs { legs, unpaired } => write!(
                f,
                "found an odd number of legs ({legs}): {unpaired} could not be paired"
            ),
            Self::TooManyLegPairs { pairs } => write!(
                f,
                "found {pairs} leg pairs: a vertebrate-like figure has at most two limb pairs, so the figure is not vertebrate-like; its anterior half of the pairs (rounded down) are labelled fore legs, the others hind legs"
            ),
            Self::NoLegs => write!(
                f,
                "no legs: no protrusion reaches the bottom of the figure"
            ),
            Self::UnidentifiedProtrusion {
                section,
                voxels,
                reach,
            } => write!(
                f,
                "an unidentified protrusion (section {section}, {voxels} DMS voxels, reaching ({:.3}, {:.3}, {:.3})) was merged into the trunk; label it in a labels override file if it is a body part",
                reach.x, reach.y, reach.z
            ),
            Self::ArmsSeparated { levels, voxels } => write!(
                f,
                "the arms hang against the body: found on {} and {} transverse slices of the mesh beside the trunk, and cut apart from it in the voxels ({voxels} voxels) before labelling",
                levels[0], levels[1]
            ),
        }
    }
}

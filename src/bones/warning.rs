//! What bone generation could not make, or made smaller than measured.

use crate::warning::Severity;
use std::fmt;

/// A bone left out or shrunk, and why (missing body parts are warnings, not errors).
#[derive(Debug, Clone, PartialEq)]
pub enum BoneWarning {
    /// No head segment (head and head end joints): no cranium or mandible.
    NoHeadSegment,
    /// The head segment has zero length: no cranium.
    ZeroLengthHead,
    /// The jaw segment has zero length: no mandible.
    ZeroLengthJaw,
    /// No head joint on a chain from the root: the vertebral column follows the longest chain.
    NoHeadOnChain,
    /// No vertebral segments between the root and the head.
    NoVertebralSegments,
    /// A vertebral segment of zero length.
    ZeroLengthVertebra {
        /// The vertebra's name.
        name: String,
    },
    /// No pectoral girdle (arms, wings or fore legs): no rib cage.
    NoPectoralGirdle,
    /// A pectoral limb whose girdle joint sits on its shoulder: no scapula.
    NoScapula {
        /// The limb's side (`left`, `right`...).
        side: &'static str,
    },
    /// One pelvic limb only: the pelvis mirrors its socket.
    OnePelvicLimb,
    /// No pelvic limbs: no pelvis.
    NoPelvicLimbs,
    /// The hip joints coincide: no pelvis.
    HipsCoincide,
    /// A limb segment of zero length.
    ZeroLengthLimbSegment {
        /// The limb (`left pectoral limb at shoulder_L`).
        limb: String,
        /// The segment's proximal joint.
        joint: String,
    },
    /// A limb too short for its distal bones.
    ShortLimb {
        /// The limb (`left pectoral limb at shoulder_L`).
        limb: String,
        /// Its segments.
        segments: usize,
        /// What it has no bones for.
        missing: &'static str,
    },
    /// A bone left out: it overlaps a neighbour outside the joints at every size tried.
    Overlapping {
        /// The bone.
        bone: String,
    },
    /// A bone left out: too few of its vertices lie inside the figure at best.
    Outside {
        /// The bone.
        bone: String,
        /// Fraction of its vertices inside, 0-1.
        inside: f64,
    },
    /// A bone kept with part of it outside the figure, shrunk.
    PartlyOutside {
        /// The bone.
        bone: String,
        /// Fraction of its vertices inside, 0-1.
        inside: f64,
        /// Its size as a fraction of the measured one.
        scale: f64,
    },
}

impl BoneWarning {
    /// How much it matters: a bone left out is a missing part.
    pub fn severity(&self) -> Severity {
        match self {
            Self::NoHeadOnChain | Self::OnePelvicLimb | Self::PartlyOutside { .. } => {
                Severity::Degraded
            }
            _ => Severity::PartMissing,
        }
    }

    /// A stable snake_case id of the variant.
    pub fn code(&self) -> &'static str {
        match self {
            Self::NoHeadSegment => "no_head_segment",
            Self::ZeroLengthHead => "zero_length_head",
            Self::ZeroLengthJaw => "zero_length_jaw",
            Self::NoHeadOnChain => "no_head_on_chain",
            Self::NoVertebralSegments => "no_vertebral_segments",
            Self::ZeroLengthVertebra { .. } => "zero_length_vertebra",
            Self::NoPectoralGirdle => "no_pectoral_girdle",
            Self::NoScapula { .. } => "no_scapula",
            Self::OnePelvicLimb => "one_pelvic_limb",
            Self::NoPelvicLimbs => "no_pelvic_limbs",
            Self::HipsCoincide => "hips_coincide",
            Self::ZeroLengthLimbSegment { .. } => "zero_length_limb_segment",
            Self::ShortLimb { .. } => "short_limb",
            Self::Overlapping { .. } => "overlapping",
            Self::Outside { .. } => "outside",
            Self::PartlyOutside { .. } => "partly_outside",
        }
    }
}

impl fmt::Display for BoneWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoHeadSegment => write!(
                f,
                "no head segment (head and head end joints): no cranium or mandible"
            ),
            Self::ZeroLengthHead => write!(f, "the head segment has zero length: no cranium"),
            Self::ZeroLengthJaw => write!(f, "the jaw segment has zero length: no mandible"),
            Self::NoHeadOnChain => write!(
                f,
                "no head joint on a chain from the root: no cranium; the vertebral column follows the root's longest chain"
            ),
            Self::NoVertebralSegments => write!(
                f,
                "no vertebral segments between the root and the head: no vertebrae"
            ),
            Self::ZeroLengthVertebra { name } => {
                write!(f, "{name}: zero-length segment, no vertebra")
            }
            Self::NoPectoralGirdle => write!(
                f,
                "no pectoral girdle (arms, wings or fore legs): no rib cage"
            ),
            Self::NoScapula { side } => write!(
                f,
                "{side} pectoral limb: girdle joint on the shoulder, no scapula"
            ),
            Self::OnePelvicLimb => write!(f, "one pelvic limb only: the pelvis mirrors its socket"),
            Self::NoPelvicLimbs => write!(f, "no pelvic limbs: no pelvis"),
            Self::HipsCoincide => write!(f, "the hip joints coincide: no pelvis"),
            Self::ZeroLengthLimbSegment { limb, joint } => {
                write!(f, "{limb}: zero-length segment at {joint}, no bone")
            }
            Self::ShortLimb {
                limb,
                segments,
                missing,
            } => write!(
                f,
                "{limb} has {segments} segment(s): no {missing} (digit-less or short limb)"
            ),
            Self::Overlapping { bone } => write!(
                f,
                "{bone}: left out, it overlaps a neighbouring bone outside the joints at every size tried"
            ),
            Self::Outside { bone, inside } => write!(
                f,
                "{bone}: left out, only {:.1} % of its vertices lie inside the figure at best (its segment runs outside the figure)",
                100.0 * inside
            ),
            Self::PartlyOutside {
                bone,
                inside,
                scale,
            } => write!(
                f,
                "{bone}: only {:.1} % of its vertices lie inside the figure, at {:.0} % of its measured size",
                100.0 * inside,
                100.0 * scale
            ),
        }
    }
}

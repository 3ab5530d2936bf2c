//! Warnings of the digit stage.

use crate::skeleton::Side;
use crate::warning::Severity;
use std::fmt;

/// What the digit stage could not do as asked; the hand keeps a best effort.
#[derive(Debug, Clone, PartialEq)]
pub enum DigitWarning {
    /// The hand's surface could not be taken (no wrist or elbow, or no triangles beyond the
    /// wrist): the template's finger chain stays.
    NoHand {
        /// The hand.
        side: Side,
    },
    /// The foot's surface could not be read below the ankle (no knee, no surface, or none
    /// reaching ahead of the ankle): the fit's toe chain stays.
    NoFoot {
        /// The foot.
        side: Side,
    },
    /// No fingers separate on the surface (a mitten or a fist): one mitten chain, plus a thumb
    /// when the thumb separates.
    FingersFused {
        /// The hand.
        side: Side,
        /// Whether a thumb separated.
        thumb: bool,
    },
    /// An animal's foot shows more than five separate digits: the five longest are kept.
    FootDigitCount {
        /// The foot's side.
        side: Side,
        /// A fore foot (else a hind foot).
        fore: bool,
        /// Digits found.
        found: usize,
    },
    /// Fewer or more than five digits separate: the digits found are named thumb first, the
    /// rest are left out.
    DigitCount {
        /// The hand.
        side: Side,
        /// Digits found.
        found: usize,
    },
}

impl DigitWarning {
    /// Stable snake_case id.
    pub fn code(&self) -> &'static str {
        match self {
            Self::NoHand { .. } => "no_hand",
            Self::NoFoot { .. } => "no_foot",
            Self::FingersFused { .. } => "fingers_fused",
            Self::DigitCount { .. } => "digit_count",
            Self::FootDigitCount { .. } => "foot_digit_count",
        }
    }

    /// How much it matters.
    pub fn severity(&self) -> Severity {
        Severity::Degraded
    }
}

impl fmt::Display for DigitWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoHand { side } => write!(
                f,
                "the {} hand's surface could not be found beyond the wrist: it keeps one finger chain",
                side.as_str()
            ),
            Self::NoFoot { side } => write!(
                f,
                "the {} foot's surface could not be read below the ankle: its toe joints stay where the fit put them",
                side.as_str()
            ),
            Self::FingersFused { side, thumb } => write!(
                f,
                "the fingers of the {} hand are fused (a mitten or fist): one mitten chain{}",
                side.as_str(),
                if *thumb { " and a thumb" } else { ", no thumb separates" }
            ),
            Self::FootDigitCount { side, fore, found } => write!(
                f,
                "the {} {} foot shows {found} separate digits, more than five: the five longest are kept",
                side.as_str(),
                if *fore { "fore" } else { "hind" }
            ),
            Self::DigitCount { side, found } => write!(
                f,
                "the {} hand shows {found} separate digits, not 5: the digits found are named thumb first",
                side.as_str()
            ),
        }
    }
}

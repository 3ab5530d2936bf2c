//! Fit errors and warnings.

use super::Side;
use std::fmt;

/// Errors of the fit stage: malformed input geometry or options.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// The head-to-tail path has too few points.
    #[error("the head-to-tail path has {points} point(s): give at least 2")]
    ShortAxialPath {
        /// Points given.
        points: usize,
    },
    /// A radius list does not match its path.
    #[error("{what} has {points} points but {radii} radii: give one radius per point")]
    RadiiMismatch {
        /// Which path.
        what: String,
        /// Points.
        points: usize,
        /// Radii.
        radii: usize,
    },
    /// A coordinate or radius is NaN or infinite, or a radius is negative.
    #[error("{what} has a non-finite coordinate or a negative/non-finite radius")]
    NonFinite {
        /// Which input.
        what: String,
    },
    /// Up and forward are zero or parallel.
    #[error("up {up:?} and forward {forward:?} must be non-zero and not parallel")]
    BadOrientation {
        /// Up given.
        up: [f64; 3],
        /// Forward given.
        forward: [f64; 3],
    },
    /// Section boundaries are out of order or out of range.
    #[error("axial sections head_end {head_end} <= neck_end {neck_end} <= trunk_end {trunk_end} must hold and stay below {points} points")]
    BadSections {
        /// Given head end.
        head_end: usize,
        /// Given neck end.
        neck_end: usize,
        /// Given trunk end.
        trunk_end: usize,
        /// Points on the path.
        points: usize,
    },
    /// Options of the fit's input are out of range (every one).
    #[error("fit input options: {0}")]
    InvalidInputOptions(#[from] crate::options::OptionProblems),
    /// An option is out of range.
    #[error("fit option {name} = {value} is out of range {range}")]
    InvalidOption {
        /// Field name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// Allowed range.
        range: String,
    },
    /// A voxel index is outside the distance map's grid.
    #[error(
        "voxel index {index} is outside the grid of {voxels} voxels: use indices of the same grid"
    )]
    VoxelOutOfRange {
        /// The index.
        index: usize,
        /// Voxels in the grid.
        voxels: usize,
    },
    /// Renaming to the naming preset failed.
    #[error("{0}")]
    Preset(String),
}

/// Something the fit could not build as the template asks; the skeleton is still valid.
#[derive(Debug, Clone, PartialEq)]
pub enum FitWarning {
    /// A template limb pair, or one side of it, has no input limb: its joints are left out.
    MissingLimb {
        /// Template limb group (`arm`, `leg`, `fore_leg`...).
        group: String,
        /// The side missing; `None` when the whole pair is.
        side: Option<Side>,
    },
    /// An input limb pair had no place in the template and was ignored.
    UnusedLimb {
        /// Its kind.
        kind: String,
        /// Its pair number.
        pair: usize,
    },
    /// An input limb pair was fitted to a template group of another kind.
    KindMismatch {
        /// Input kind.
        kind: String,
        /// Template group used.
        group: String,
    },
    /// A limb path never leaves its girdle sphere; its root was put at the path start.
    InsideGirdle {
        /// Template limb group.
        group: String,
        /// Side.
        side: Side,
    },
    /// No limb pairs at all: sections and root were placed by fixed fractions.
    NoLimbs,
    /// No pectoral (front) pair: the neck/trunk boundary was put by a fixed fraction.
    NoFrontPair,
    /// The input has a jaw branch but the template has no jaw joints.
    JawNotInTemplate,
    /// The template's vertebra rules asked for a tail (`min > 0`) but the path has none.
    MissingTail,
    /// More digits than the template names; extra digits are named `<limb>_digit_<k>`.
    ExtraDigits {
        /// Template limb group.
        group: String,
        /// Digits found.
        found: usize,
    },
    /// A canonical key of the template got no joint (its part is missing).
    MissingCanonical {
        /// The key.
        key: String,
    },
    /// The preset's engine skeleton has no joint for these fitted canonical joints (a
    /// quadruped's tail in a humanoid engine's skeleton): they are left out.
    NotInPreset {
        /// The preset's file stem.
        preset: String,
        /// The canonical keys left out.
        keys: Vec<String>,
    },
}

impl fmt::Display for FitWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::MissingLimb { group, side: None } => {
                write!(
                    f,
                    "missing limb pair: no {group} found, its joints are left out"
                )
            }
            Self::MissingLimb {
                group,
                side: Some(side),
            } => write!(
                f,
                "missing limb: no {} {group} found, its joints are left out",
                side.as_str()
            ),
            Self::UnusedLimb { kind, pair } => write!(
                f,
                "limb pair {pair} ({kind}) has no place in the template and was ignored"
            ),
            Self::KindMismatch { kind, group } => {
                write!(f, "{kind} limbs were fitted as the template's {group}")
            }
            Self::InsideGirdle { group, side } => write!(
                f,
                "the {} {group} never leaves its girdle sphere: its root is at the path start",
                side.as_str()
            ),
            Self::NoLimbs => write!(
                f,
                "no limbs found: trunk and root placed by fixed fractions"
            ),
            Self::NoFrontPair => write!(
                f,
                "no front limb pair found: the neck/trunk boundary is placed by a fixed fraction"
            ),
            Self::JawNotInTemplate => {
                write!(f, "a jaw was found but the template has no jaw joint")
            }
            Self::MissingTail => write!(f, "missing tail: the template expects one"),
            Self::ExtraDigits { group, found } => write!(
                f,
                "{found} digits on a {group}: more than the template names"
            ),
            Self::MissingCanonical { key } => {
                write!(
                    f,
                    "canonical joint {key} is missing (its body part was not found)"
                )
            }
            Self::NotInPreset { preset, keys } => write!(
                f,
                "the {preset} skeleton has no joint for {}: left out (--preset anatomical keeps them)",
                keys.join(", ")
            ),
        }
    }
}

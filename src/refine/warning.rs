//! What the refinement could not do: one warning per joint (or group of joints) that kept its
//! rough position.

use crate::skeleton::{Canonical, Side};
use crate::warning::Severity;
use std::fmt;

/// A joint, or a group of joints, the refinement could not place; each names the canonical
/// keys it concerns ([`RefineWarning::keys`]).
#[derive(Debug, Clone, PartialEq)]
pub enum RefineWarning {
    /// The rough skeleton has no upright legs: the given up direction was used.
    NoUprightLegs,
    /// No head was found slicing down from the top.
    NoHead,
    /// No occipital circle on the nose-level head slice.
    NoOccipitalCircle,
    /// Shoulder, elbow or wrist of this side is not in the rough skeleton.
    ArmJointsMissing(Side),
    /// This side's arm could not be sliced.
    ArmNotSliced(Side),
    /// No thickness minimum on this side's forearm.
    NoWrist(Side),
    /// No armpit on this side.
    NoArmpit(Side),
    /// No elbow on this side's centroid curve.
    NoElbow(Side),
    /// The limb's slices stop short of this rough joint or run beside it (a sphere stopped
    /// at a seam or a bridge between separate pieces, a strap's loop): it was not searched
    /// there and keeps its rough place (unless a joint piece places it).
    TraceShort(Canonical),
    /// No torso silhouette in the median plane.
    NoTorsoSilhouette,
    /// No transverse slice at hip height.
    NoHipSlice,
    /// The median silhouette runs down past the knees (a skirt, robe or long coat hides the
    /// crotch): the hips' height comes from the arm length when `placed`, else it stays rough.
    CrotchHidden {
        /// Whether the arms gave the hips' height.
        placed: bool,
    },
    /// Hip, knee or ankle of this side is not in the rough skeleton.
    LegJointsMissing(Side),
    /// This side's leg could not be sliced.
    LegNotSliced(Side),
    /// This side's leg's centroid curve ends above the ankle: the ankle goes at the ankle's
    /// height above the sole under the rough one when `placed`, else it stays rough.
    NoAnkle {
        /// The leg's side.
        side: Side,
        /// Whether the sole gave the ankle's height.
        placed: bool,
    },
    /// No knee on this side's centroid curve: the knee goes at the leg ratio between hip and
    /// ankle when `placed`, else it stays rough.
    NoKnee {
        /// The leg's side.
        side: Side,
        /// Whether the leg ratio placed it.
        placed: bool,
    },
    /// The spine curve's control points are out of order (or its lumbar point lies below the
    /// pelvis): the spine joints were carried along.
    SpineOutOfOrder,
    /// No spine without the head joint and the torso silhouette.
    NoSpine,
    /// `--spine full` was asked for, but the rig keeps the template's spine joints: why.
    CoarseSpineKept(super::NoFullSpine),
    /// `--spine full`: no spine curve meeting the refined pelvis, neck and head, so the
    /// vertebrae were spread along the skeleton's trunk and neck ([`super::along_chain`]).
    SpineAlongChain,
    /// `--spine full`: these vertebral joints were outside the body (a gap between layered
    /// shells) and were moved inside along the forward axis ([`super::pull_inside`]).
    VertebraeMovedInside(Vec<String>),
    /// The joint was not found and kept its rough position.
    Kept(Canonical),
    /// The refined position was too far from the rough one ([`super::RefineOptions::max_shift`]).
    TooFar {
        /// The joint.
        key: Canonical,
        /// Distance from the rough position, mesh units.
        distance: f64,
    },
}

impl RefineWarning {
    /// The canonical keys the warning names.
    pub fn keys(&self) -> Vec<Canonical> {
        use Canonical as C;
        match *self {
            Self::NoHead | Self::NoOccipitalCircle => vec![C::Head],
            Self::ArmJointsMissing(s) | Self::ArmNotSliced(s) => {
                vec![C::Shoulder(s), C::Elbow(s), C::Wrist(s)]
            }
            Self::NoWrist(s) => vec![C::Wrist(s)],
            Self::NoArmpit(s) => vec![C::Shoulder(s)],
            Self::NoElbow(s) => vec![C::Elbow(s)],
            Self::TraceShort(key) => vec![key],
            Self::NoTorsoSilhouette => vec![C::Neck],
            Self::NoHipSlice => vec![C::Hip(Side::Left), C::Hip(Side::Right), C::Pelvis],
            Self::CrotchHidden { placed: true } => Vec::new(),
            Self::CrotchHidden { placed: false } => {
                vec![C::Hip(Side::Left), C::Hip(Side::Right), C::Pelvis]
            }
            Self::LegJointsMissing(s) | Self::LegNotSliced(s) => vec![C::Knee(s), C::Ankle(s)],
            Self::NoAnkle { placed: true, .. } | Self::NoKnee { placed: true, .. } => Vec::new(),
            Self::NoAnkle { side, .. } => vec![C::Ankle(side)],
            Self::NoKnee { side, .. } => vec![C::Knee(side)],
            Self::Kept(key) | Self::TooFar { key, .. } => vec![key],
            Self::NoUprightLegs
            | Self::SpineOutOfOrder
            | Self::NoSpine
            | Self::CoarseSpineKept(_)
            | Self::SpineAlongChain
            | Self::VertebraeMovedInside(_) => Vec::new(),
        }
    }

    /// How much it matters: every warning but the body frame's leaves joints at their rough
    /// positions.
    pub fn severity(&self) -> Severity {
        match self {
            Self::NoUprightLegs => Severity::Info,
            _ => Severity::Degraded,
        }
    }
}

impl fmt::Display for RefineWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use Canonical as C;
        match self {
            Self::NoUprightLegs => write!(
                f,
                "body frame: no upright legs in the rough skeleton, using the given up direction"
            ),
            Self::NoHead => write!(f, "head: no head found slicing down from the top"),
            Self::NoOccipitalCircle => {
                write!(f, "head: no occipital circle on the nose-level slice")
            }
            Self::ArmJointsMissing(s) => write!(
                f,
                "{}, {}, {}: arm joints missing from the rough skeleton",
                C::Shoulder(*s),
                C::Elbow(*s),
                C::Wrist(*s)
            ),
            Self::ArmNotSliced(s) => write!(
                f,
                "{}, {}, {}: the arm could not be sliced",
                C::Shoulder(*s),
                C::Elbow(*s),
                C::Wrist(*s)
            ),
            Self::NoWrist(s) => write!(f, "{}: no thickness minimum on the forearm", C::Wrist(*s)),
            Self::NoArmpit(s) => write!(
                f,
                "{}: no armpit (arm touching the torso?)",
                C::Shoulder(*s)
            ),
            Self::NoElbow(s) => write!(f, "{}: no elbow on the arm's centroid curve", C::Elbow(*s)),
            Self::TraceShort(key) => write!(
                f,
                "{key}: the limb's slices do not reach it; it keeps its rough place"
            ),
            Self::NoTorsoSilhouette => write!(
                f,
                "neck: no torso silhouette in the median plane (torso not upright?)"
            ),
            Self::CrotchHidden { placed: true } => write!(
                f,
                "hips: clothing hides the crotch (the median silhouette runs below the knees, or \
                 ends on a hem); hips placed by proportion, {} times the arm's length below the shoulders",
                super::driver::TRUNK_PER_ARM
            ),
            Self::CrotchHidden { placed: false } => write!(
                f,
                "hips: clothing hides the crotch (the median silhouette runs below the knees, or \
                 ends on a hem) and the arms give no length; hips kept where the legs' labels begin"
            ),
            Self::NoHipSlice => write!(
                f,
                "{}, {}, {}: no transverse slice at hip height",
                C::Hip(Side::Left),
                C::Hip(Side::Right),
                C::Pelvis
            ),
            Self::LegJointsMissing(s) => write!(
                f,
                "{}, {}: leg joints missing from the rough skeleton",
                C::Knee(*s),
                C::Ankle(*s)
            ),
            Self::LegNotSliced(s) => write!(
                f,
                "{}, {}: the leg could not be sliced",
                C::Knee(*s),
                C::Ankle(*s)
            ),
            Self::NoAnkle { side, placed } => write!(
                f,
                "{}: the leg's centroid curve ends above the ankle; {}",
                C::Ankle(*side),
                if *placed {
                    "placed at the ankle's height above the sole"
                } else {
                    "kept where the template fit put it"
                }
            ),
            Self::NoKnee { side, placed } => write!(
                f,
                "{}: no knee on the leg's centroid curve; {}",
                C::Knee(*side),
                if *placed {
                    "placed by the leg's proportions between hip and ankle"
                } else {
                    "kept where the template fit put it"
                }
            ),
            Self::SpineOutOfOrder => write!(
                f,
                "spine: the spine curve's control points are out of order; spine joints carried along"
            ),
            Self::NoSpine => write!(
                f,
                "spine: no spine without the head joint and the torso silhouette"
            ),
            Self::CoarseSpineKept(why) => write!(
                f,
                "spine: kept the template's spine joints instead of the full spine: {why}"
            ),
            Self::SpineAlongChain => write!(
                f,
                "spine: no spine curve through the refined pelvis, neck and head; vertebrae spread along the fitted trunk and neck"
            ),
            Self::VertebraeMovedInside(names) => write!(
                f,
                "spine: {} outside the body, moved inside along the forward axis",
                names.join(", ")
            ),
            Self::Kept(key) => write!(f, "{key}: kept at the unrefined position"),
            Self::TooFar { key, distance } => write!(
                f,
                "{key}: refined position {distance:.3} m from the rough one, kept at the unrefined position"
            ),
        }
    }
}

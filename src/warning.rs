//! Warnings: what a stage could not do, and how much it matters. Each stage has its own warning
//! enum whose variants carry the offending values (e.g. [`crate::refine::RefineWarning`],
//! [`crate::fit::FitWarning`], [`crate::anatomy::AnatomyWarning`]); the crate [`Warning`]
//! wraps them the way [`crate::Error`] wraps the stage errors. Each warning has a
//! [`Severity`], a stable snake_case [`code`](Warning::code) and a message (its `Display`).
//! In JSON a warning is a [`WarningRecord`]: `{"stage", "code", "severity", "message"}`.

use crate::anatomy::AnatomyWarning;
use crate::bones::BoneWarning;
use crate::digits::DigitWarning;
use crate::eval::EvalWarning;
use crate::fit::{FitInputWarning, FitWarning};
use crate::general::GeneralWarning;
use crate::medial::MedialWarning;
use crate::paths::PathWarning;
use crate::pipeline::RigWarning;
use crate::refine::RefineWarning;
use crate::skin::SkinWarning;
use crate::voxel::VoxelWarning;
use serde::{Deserialize, Serialize};
use std::fmt;

/// How much a warning matters, least first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Severity {
    /// Something worth knowing; the result is as good as without it.
    Info,
    /// A part was placed less well than it could have been (e.g. kept at its rough position).
    Degraded,
    /// A part is missing from the result.
    PartMissing,
}

impl Severity {
    /// Its snake_case name, as in JSON (`info`, `degraded`, `part_missing`).
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Info => "info",
            Self::Degraded => "degraded",
            Self::PartMissing => "part_missing",
        }
    }
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Any warning of skelfit's library: each variant wraps the warning enum of one stage, in
/// pipeline order (the order [`ranked`] groups them in).
#[derive(Debug, Clone, PartialEq)]
pub enum Warning {
    /// Voxelization (and the input mesh it read).
    Voxel(VoxelWarning),
    /// The discrete medial surface.
    Medial(MedialWarning),
    /// The path tree.
    Paths(PathWarning),
    /// The general control skeleton.
    General(GeneralWarning),
    /// The level graph, orientation and body-part labels.
    Anatomy(AnatomyWarning),
    /// The paths between the labelled parts that the fit takes ([`crate::fit::fit_input`]).
    FitInput(FitInputWarning),
    /// The template fit.
    Fit(FitWarning),
    /// The slicing refinement of humanoid joints.
    Refine(RefineWarning),
    /// The digits of the hands ([`crate::digits::fit_hands`]).
    Digits(DigitWarning),
    /// Skinning.
    Skin(SkinWarning),
    /// Bone meshes.
    Bones(BoneWarning),
    /// Evaluation against a reference rig.
    Eval(EvalWarning),
    /// The anatomical rig driver: template choice and stage fallbacks.
    Rig(RigWarning),
}

impl Warning {
    /// The stage that gave it (`voxel`, `medial`, `paths`, `general`, `anatomy`, `fit`,
    /// `refine`, `skin`, `bones`, `eval`, `rig`).
    pub fn stage(&self) -> &'static str {
        match self {
            Self::Voxel(_) => "voxel",
            Self::Medial(_) => "medial",
            Self::Paths(_) => "paths",
            Self::General(_) => "general",
            Self::Anatomy(_) => "anatomy",
            Self::FitInput(_) => "fit_input",
            Self::Fit(_) => "fit",
            Self::Refine(_) => "refine",
            Self::Digits(_) => "digits",
            Self::Skin(_) => "skin",
            Self::Bones(_) => "bones",
            Self::Eval(_) => "eval",
            Self::Rig(_) => "rig",
        }
    }

    /// Position of its stage in pipeline order, for grouping.
    fn stage_rank(&self) -> usize {
        match self {
            Self::Voxel(_) => 0,
            Self::Medial(_) => 1,
            Self::Paths(_) => 2,
            Self::General(_) => 3,
            Self::Anatomy(_) => 4,
            Self::Rig(_) => 5,
            Self::FitInput(_) => 6,
            Self::Fit(_) => 6,
            Self::Refine(_) => 7,
            Self::Digits(_) => 7,
            Self::Skin(_) => 8,
            Self::Bones(_) => 9,
            Self::Eval(_) => 10,
        }
    }

    /// How much it matters.
    pub fn severity(&self) -> Severity {
        match self {
            Self::Voxel(w) => w.severity(),
            Self::Medial(w) => w.severity(),
            Self::Paths(w) => w.severity(),
            Self::General(w) => w.severity(),
            Self::Anatomy(w) => w.severity(),
            Self::FitInput(w) => w.severity(),
            Self::Fit(w) => fit_severity(w),
            Self::Refine(w) => w.severity(),
            Self::Digits(w) => w.severity(),
            Self::Skin(w) => skin_severity(w),
            Self::Bones(w) => w.severity(),
            Self::Eval(w) => w.severity(),
            Self::Rig(w) => w.severity(),
        }
    }

    /// A stable snake_case id of the variant, unique within its [`stage`](Self::stage).
    pub fn code(&self) -> &'static str {
        match self {
            Self::Voxel(w) => w.code(),
            Self::Medial(w) => w.code(),
            Self::Paths(w) => w.code(),
            Self::General(w) => w.code(),
            Self::Anatomy(w) => w.code(),
            Self::FitInput(w) => w.code(),
            Self::Fit(w) => fit_code(w),
            Self::Refine(w) => refine_code(w),
            Self::Digits(w) => w.code(),
            Self::Skin(w) => skin_code(w),
            Self::Bones(w) => w.code(),
            Self::Eval(w) => w.code(),
            Self::Rig(w) => w.code(),
        }
    }

    /// Its JSON form: stage, code, severity and message.
    pub fn record(&self) -> WarningRecord {
        WarningRecord {
            stage: self.stage().to_string(),
            code: self.code().to_string(),
            severity: self.severity(),
            message: self.to_string(),
        }
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Voxel(w) => w.fmt(f),
            Self::Medial(w) => w.fmt(f),
            Self::Paths(w) => w.fmt(f),
            Self::General(w) => w.fmt(f),
            Self::Anatomy(w) => w.fmt(f),
            Self::FitInput(w) => w.fmt(f),
            Self::Fit(w) => w.fmt(f),
            // The refinement's sentences name joints, not the stage: say which stage it was.
            Self::Refine(w) => write!(f, "refine: {w}"),
            Self::Digits(w) => write!(f, "digits: {w}"),
            Self::Skin(w) => w.fmt(f),
            Self::Bones(w) => w.fmt(f),
            Self::Eval(w) => w.fmt(f),
            Self::Rig(w) => w.fmt(f),
        }
    }
}

impl Serialize for Warning {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.record().serialize(serializer)
    }
}

/// Wraps a stage warning enum into [`Warning`] with `From`.
macro_rules! wrap {
    ($($stage:ident($inner:ty)),* $(,)?) => {
        $(impl From<$inner> for Warning {
            fn from(w: $inner) -> Self {
                Self::$stage(w)
            }
        })*
    };
}

wrap!(
    Voxel(VoxelWarning),
    Medial(MedialWarning),
    Paths(PathWarning),
    General(GeneralWarning),
    Anatomy(AnatomyWarning),
    FitInput(FitInputWarning),
    Fit(FitWarning),
    Refine(RefineWarning),
    Digits(DigitWarning),
    Skin(SkinWarning),
    Bones(BoneWarning),
    Eval(EvalWarning),
    Rig(RigWarning),
);

/// A warning as written to and read from JSON files (bench and study results, evaluations):
/// the values of the typed [`Warning`] live on in its message.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct WarningRecord {
    /// The stage that gave it ([`Warning::stage`]).
    pub stage: String,
    /// Stable snake_case id of the warning ([`Warning::code`]).
    pub code: String,
    /// How much it matters.
    pub severity: Severity,
    /// The sentence for the user.
    pub message: String,
}

impl From<&Warning> for WarningRecord {
    fn from(w: &Warning) -> Self {
        w.record()
    }
}

impl fmt::Display for WarningRecord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// Serializes stage warnings as [`WarningRecord`]s (`#[serde(serialize_with = ...)]` on a stage
/// output's `warnings` field).
///
/// # Errors
/// The serializer's.
pub(crate) fn serialize_records<S, W>(warnings: &[W], serializer: S) -> Result<S::Ok, S::Error>
where
    S: serde::Serializer,
    W: Clone + Into<Warning>,
{
    serializer.collect_seq(warnings.iter().map(|w| w.clone().into().record()))
}

/// `warnings` ranked for the reader: most severe first, then grouped by stage in pipeline
/// order, and in their original order within a group.
pub fn ranked(warnings: &[Warning]) -> Vec<&Warning> {
    let mut out: Vec<&Warning> = warnings.iter().collect();
    out.sort_by_key(|w| (std::cmp::Reverse(w.severity()), w.stage_rank()));
    out
}

/// How much a fit warning matters: a limb, tail or canonical joint left out is a missing part.
fn fit_severity(w: &FitWarning) -> Severity {
    match w {
        FitWarning::MissingLimb { .. }
        | FitWarning::MissingTail
        | FitWarning::MissingCanonical { .. } => Severity::PartMissing,
        FitWarning::UnusedLimb { .. } | FitWarning::JawNotInTemplate => Severity::PartMissing,
        FitWarning::KindMismatch { .. }
        | FitWarning::InsideGirdle { .. }
        | FitWarning::NoLimbs
        | FitWarning::NoFrontPair
        | FitWarning::NotInPreset { .. } => Severity::Degraded,
        FitWarning::ExtraDigits { .. } => Severity::Info,
    }
}

/// Stable id of a fit warning.
fn fit_code(w: &FitWarning) -> &'static str {
    match w {
        FitWarning::MissingLimb { side: None, .. } => "missing_limb_pair",
        FitWarning::MissingLimb { .. } => "missing_limb",
        FitWarning::UnusedLimb { .. } => "unused_limb",
        FitWarning::KindMismatch { .. } => "kind_mismatch",
        FitWarning::InsideGirdle { .. } => "inside_girdle",
        FitWarning::NoLimbs => "no_limbs",
        FitWarning::NoFrontPair => "no_front_pair",
        FitWarning::JawNotInTemplate => "jaw_not_in_template",
        FitWarning::MissingTail => "missing_tail",
        FitWarning::ExtraDigits { .. } => "extra_digits",
        FitWarning::MissingCanonical { .. } => "missing_canonical",
        FitWarning::NotInPreset { .. } => "not_in_preset",
    }
}

/// Stable id of a refinement warning.
fn refine_code(w: &RefineWarning) -> &'static str {
    match w {
        RefineWarning::NoUprightLegs => "no_upright_legs",
        RefineWarning::NoHead => "no_head",
        RefineWarning::NoOccipitalCircle => "no_occipital_circle",
        RefineWarning::ArmJointsMissing(_) => "arm_joints_missing",
        RefineWarning::ArmNotSliced(_) => "arm_not_sliced",
        RefineWarning::NoWrist(_) => "no_wrist",
        RefineWarning::NoArmpit(_) => "no_armpit",
        RefineWarning::NoElbow(_) => "no_elbow",
        RefineWarning::TraceShort(_) => "trace_short",
        RefineWarning::NoTorsoSilhouette => "no_torso_silhouette",
        RefineWarning::NoHipSlice => "no_hip_slice",
        RefineWarning::CrotchHidden { .. } => "crotch_hidden",
        RefineWarning::LegJointsMissing(_) => "leg_joints_missing",
        RefineWarning::LegNotSliced(_) => "leg_not_sliced",
        RefineWarning::NoAnkle { .. } => "no_ankle",
        RefineWarning::NoKnee { .. } => "no_knee",
        RefineWarning::SpineOutOfOrder => "spine_out_of_order",
        RefineWarning::NoSpine => "no_spine",
        RefineWarning::CoarseSpineKept(_) => "coarse_spine_kept",
        RefineWarning::SpineAlongChain => "spine_along_chain",
        RefineWarning::VertebraeMovedInside(_) => "vertebrae_moved_inside",
        RefineWarning::Kept(_) => "kept",
        RefineWarning::TooFar { .. } => "too_far",
    }
}

/// How much a skinning warning matters: every vertex is still bound, some less well.
fn skin_severity(w: &SkinWarning) -> Severity {
    match w {
        SkinWarning::TruncatedInfluences { .. } => Severity::Info,
        _ => Severity::Degraded,
    }
}

/// Stable id of a skinning warning.
fn skin_code(w: &SkinWarning) -> &'static str {
    match w {
        SkinWarning::SegmentOutside { .. } => "segment_outside",
        SkinWarning::UnreachedVertices { .. } => "unreached_vertices",
        SkinWarning::TruncatedInfluences { .. } => "truncated_influences",
        SkinWarning::JointsOutside { .. } => "joints_outside",
        SkinWarning::ZeroLengthBone { .. } => "zero_length_bone",
        SkinWarning::BoneOutside { .. } => "bone_outside",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranked_puts_missing_parts_first_and_groups_by_stage() {
        let warnings: Vec<Warning> = vec![
            RefineWarning::NoUprightLegs.into(),
            FitWarning::NoFrontPair.into(),
            FitWarning::MissingTail.into(),
            MedialWarning::SeveralComponents { components: 2 }.into(),
        ];
        let codes: Vec<&str> = ranked(&warnings).iter().map(|w| w.code()).collect();
        assert_eq!(
            codes,
            [
                "missing_tail",
                "several_components",
                "no_front_pair",
                "no_upright_legs"
            ]
        );
    }

    #[test]
    fn json_carries_code_severity_and_the_message() {
        let w = Warning::from(RefineWarning::NoSpine);
        let json = serde_json::to_value(&w).unwrap();
        assert_eq!(json["stage"], "refine");
        assert_eq!(json["code"], "no_spine");
        assert_eq!(json["severity"], "degraded");
        assert_eq!(
            json["message"],
            "refine: spine: no spine without the head joint and the torso silhouette"
        );
        let back: WarningRecord = serde_json::from_value(json).unwrap();
        assert_eq!(back, w.record());
    }
}

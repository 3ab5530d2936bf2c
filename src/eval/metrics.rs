//! Per-joint errors between a predicted and a reference skeleton, their summaries and the
//! figure size that makes them comparable across models.

use super::{
    canonical_map, chamfer, correspond, CanonicalSource, ChamferDistances, ChamferOptions,
    Correspondence, EvalError, EvalWarning, MatchMethod, ReferenceRig,
};
use crate::mesh::Mesh;
use crate::skeleton::Canonical;
use crate::warning::{Warning, WarningRecord};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// How figure size is measured. Errors are reported in mesh units and as a percentage of it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FigureMeasure {
    /// [`Height`](Self::Height) for upright figures (the reference's canonical head is higher
    /// above its pelvis than it is away from it horizontally), else
    /// [`LongestSide`](Self::LongestSide).
    #[default]
    Auto,
    /// Extent along +Y (humanoids).
    Height,
    /// Longest side of the bounding box (body length of quadrupeds and others).
    LongestSide,
}

/// What the figure size was measured on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SizeSource {
    /// The bounding box of the mesh.
    Mesh,
    /// The bounding box of the reference joints (no mesh given).
    ReferenceJoints,
}

/// The size errors are normalised by.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FigureSize {
    /// Size, mesh units.
    pub size: f64,
    /// The measure used ([`FigureMeasure::Height`] or [`FigureMeasure::LongestSide`]).
    pub measure: FigureMeasure,
    /// What was measured.
    pub source: SizeSource,
}

/// Whether [`evaluate`] pairs joints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JointPairing {
    /// Pair joints; skeletons that share none are an error ([`EvalError::NoSharedJoints`]).
    /// The default for comparing two files, where nothing shared is usually a naming problem.
    #[default]
    Required,
    /// Pair joints when the skeletons share any; otherwise report only the chamfer distances
    /// ([`MatchMethod::ChamferOnly`], with a warning saying per-joint errors are unavailable).
    /// For batch runs whose predicted joints are not anatomically named (the general control
    /// skeleton).
    IfShared,
    /// Never pair: only the chamfer distances.
    Skip,
}

/// Options of [`evaluate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EvalOptions {
    /// Compare only joints with `deform == true` (drops control joints such as IK targets and
    /// floor roots, as `../shared/refdata/README.md` prescribes). Default true.
    pub deforming_only: bool,
    /// How figure size is measured. Default [`FigureMeasure::Auto`].
    pub measure: FigureMeasure,
    /// Warn when predicted and reference (or mesh) sizes differ by more than this factor, a
    /// sign of mismatched units (m vs cm is 100). Default 10 (issue: "more than 10x").
    pub unit_mismatch_ratio: f64,
    /// Spacing of bone samples for the bone-to-bone chamfer distance, as a fraction of figure
    /// size. Default 0.002 (≈3.5 mm on a 1.75 m figure; halving it changes B2B by < 0.1 %).
    pub bone_sample_fraction: f64,
    /// Whether joints are paired. Default [`JointPairing::Required`].
    pub pairing: JointPairing,
    /// With [`JointPairing::IfShared`], a pairing by identical joint names (no canonical keys
    /// shared) is kept only when it covers at least this fraction of the reference's joints;
    /// fewer shared names are taken as coincidental and give a chamfer-only evaluation.
    /// Default 0.5 (measured on refdata: the general skeleton's `root` matched 1 of the
    /// T-rex's 29 joints, a meaningless 30 % "error").
    pub min_name_fraction: f64,
}

impl Default for EvalOptions {
    fn default() -> Self {
        Self {
            pairing: JointPairing::Required,
            min_name_fraction: 0.5,
            deforming_only: true,
            measure: FigureMeasure::Auto,
            unit_mismatch_ratio: 10.0,
            bone_sample_fraction: 0.002,
        }
    }
}

/// The error of one paired joint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointError {
    /// Canonical key (or shared joint name).
    pub key: String,
    /// Name of the predicted joint.
    pub predicted_joint: String,
    /// Name of the reference joint.
    pub reference_joint: String,
    /// Predicted position, mesh units.
    pub predicted: DVec3,
    /// Reference position, mesh units.
    pub reference: DVec3,
    /// `predicted − reference`, mesh units.
    pub offset: DVec3,
    /// `|offset|`, mesh units.
    pub error: f64,
    /// `error` as a percentage of figure size.
    pub error_percent: f64,
}

/// Mean, median, max and RMS of a set of errors.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ErrorSummary {
    /// Number of values.
    pub count: usize,
    /// Arithmetic mean.
    pub mean: f64,
    /// Median (mean of the two middle values for an even count).
    pub median: f64,
    /// Largest value.
    pub max: f64,
    /// Root mean square.
    pub rms: f64,
}

impl ErrorSummary {
    /// Summarises `values` (all zero for an empty slice; NaNs sort last).
    pub fn from_values(values: &[f64]) -> Self {
        if values.is_empty() {
            return Self::default();
        }
        let mut sorted = values.to_vec();
        sorted.sort_by(|a, b| a.total_cmp(b));
        let n = sorted.len();
        let median = if n % 2 == 1 {
            sorted[n / 2]
        } else {
            0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
        };
        Self {
            count: n,
            mean: sorted.iter().sum::<f64>() / n as f64,
            median,
            max: sorted[n - 1],
            rms: (sorted.iter().map(|v| v * v).sum::<f64>() / n as f64).sqrt(),
        }
    }
}

/// The result of comparing one predicted skeleton with one reference.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// Reference model name.
    pub model: String,
    /// Reference rig name, if known.
    pub rig: Option<String>,
    /// Predicted model name.
    pub predicted_model: String,
    /// Units declared by the reference, if any.
    pub units: Option<String>,
    /// Figure size used for the percentages.
    pub figure: FigureSize,
    /// How joints were paired.
    pub method: MatchMethod,
    /// Where the predicted canonical keys came from.
    pub predicted_naming: CanonicalSource,
    /// Where the reference canonical keys came from.
    pub reference_naming: CanonicalSource,
    /// Per-joint errors, in canonical order (empty for [`MatchMethod::ChamferOnly`]).
    pub joints: Vec<JointError>,
    /// Summary of `joints[].error`, mesh units.
    pub summary: ErrorSummary,
    /// Summary of `joints[].error_percent`.
    pub summary_percent: ErrorSummary,
    /// Key of the joint with the largest error.
    pub worst_joint: String,
    /// Reference canonical keys the prediction lacks.
    pub unmatched: Vec<String>,
    /// Chamfer distances over all (deforming) joints, mesh units.
    pub chamfer: ChamferDistances,
    /// Chamfer distances as a percentage of figure size.
    pub chamfer_percent: ChamferDistances,
    /// Things the caller should tell the user (e.g. suspected unit mismatch), from
    /// [`EvalWarning`]s. Never printed by the library. Records rather than typed warnings: an
    /// evaluation is a file format (`skelfit eval --json`, bench results that `skelfit report`
    /// reads back), and a record is what a file can give back.
    pub warnings: Vec<WarningRecord>,
}

fn extent(bbox: Option<(DVec3, DVec3)>, measure: FigureMeasure) -> f64 {
    let Some((lo, hi)) = bbox else { return 0.0 };
    let size = hi - lo;
    match measure {
        FigureMeasure::Height => size.y,
        _ => size.max_element(),
    }
}

/// Resolves [`FigureMeasure::Auto`] for `reference` (see there).
pub fn resolve_measure(reference: &ReferenceRig, measure: FigureMeasure) -> FigureMeasure {
    if measure != FigureMeasure::Auto {
        return measure;
    }
    let (map, _) = canonical_map(reference);
    let at = |key: Canonical| {
        map.get(key.as_str())
            .map(|&id| reference.skeleton.joint(id).position)
    };
    match (at(Canonical::Head), at(Canonical::Pelvis)) {
        (Some(head), Some(pelvis)) => {
            let d = head - pelvis;
            if d.y > d.x.hypot(d.z) {
                FigureMeasure::Height
            } else {
                FigureMeasure::LongestSide
            }
        }
        _ => FigureMeasure::LongestSide,
    }
}

/// Figure size of `reference`: the bounding box of `mesh` when given, else of the reference
/// joints, measured as `measure` (resolved with [`resolve_measure`]).
pub fn figure_size(
    reference: &ReferenceRig,
    mesh: Option<&Mesh>,
    measure: FigureMeasure,
) -> FigureSize {
    let measure = resolve_measure(reference, measure);
    match mesh.and_then(Mesh::bounding_box) {
        Some(bbox) => FigureSize {
            size: extent(Some(bbox), measure),
            measure,
            source: SizeSource::Mesh,
        },
        None => FigureSize {
            size: extent(reference.bounding_box(), measure),
            measure,
            source: SizeSource::ReferenceJoints,
        },
    }
}

fn size_warning(what: &'static str, a: f64, b: f64, ratio: f64) -> Option<EvalWarning> {
    let (lo, hi) = (a.min(b), a.max(b));
    (lo > 0.0 && hi / lo > ratio).then_some(EvalWarning::UnitMismatch {
        what,
        first: a,
        second: b,
    })
}

/// A correspondence without pairs.
fn chamfer_only(predicted: &ReferenceRig, reference: &ReferenceRig) -> Correspondence {
    Correspondence {
        pairs: Vec::new(),
        method: MatchMethod::ChamferOnly,
        predicted_naming: canonical_map(predicted).1,
        reference_naming: canonical_map(reference).1,
    }
}

/// Compares `predicted` with `reference`: pairs joints ([`correspond`]), measures each pair's
/// distance in mesh units and as a percentage of figure size ([`figure_size`], on `mesh` when
/// given), summarises them and adds the RigNet chamfer distances. Both skeletons must be in the
/// same frame and units; a size mismatch beyond `options.unit_mismatch_ratio` adds a warning.
///
/// # Errors
/// [`EvalError::Empty`] when a skeleton has no (deforming) joints,
/// [`EvalError::NoSharedJoints`] when nothing pairs and `options.pairing` is
/// [`JointPairing::Required`]; otherwise such skeletons give an evaluation with no per-joint
/// errors ([`MatchMethod::ChamferOnly`]) and the chamfer distances.
pub fn evaluate(
    predicted: &ReferenceRig,
    reference: &ReferenceRig,
    mesh: Option<&Mesh>,
    options: &EvalOptions,
) -> Result<Evaluation, EvalError> {
    let (predicted, reference) = if options.deforming_only {
        (predicted.deforming(), reference.deforming())
    } else {
        (predicted.clone(), reference.clone())
    };
    for (rig, role) in [(&predicted, "predicted"), (&reference, "reference")] {
        if rig.skeleton.joints.is_empty() {
            return Err(EvalError::Empty {
                what: format!("{role} {:?}", rig.model),
            });
        }
    }
    let mut warnings = Vec::new();
    let correspondence = pairing(&predicted, &reference, options, &mut warnings)?;
    let figure = figure_size(&reference, mesh, options.measure);
    size_warnings(&predicted, &reference, &figure, options, &mut warnings);
    let percent = |e: f64| {
        if figure.size > 0.0 {
            100.0 * e / figure.size
        } else {
            0.0
        }
    };
    let joints: Vec<JointError> = correspondence
        .pairs
        .iter()
        .map(|pair| {
            let p = predicted.skeleton.joint(pair.predicted);
            let r = reference.skeleton.joint(pair.reference);
            let offset = p.position - r.position;
            JointError {
                key: pair.key.clone(),
                predicted_joint: p.name.clone(),
                reference_joint: r.name.clone(),
                predicted: p.position,
                reference: r.position,
                offset,
                error: offset.length(),
                error_percent: percent(offset.length()),
            }
        })
        .collect();
    if let Some(j) = joints.iter().find(|j| !j.error.is_finite()) {
        let far = if j.predicted.abs().max_element() >= j.reference.abs().max_element() {
            ("predicted", &j.predicted_joint, j.predicted)
        } else {
            ("reference", &j.reference_joint, j.reference)
        };
        return Err(non_finite(far));
    }
    let errors: Vec<f64> = joints.iter().map(|j| j.error).collect();
    let errors_percent: Vec<f64> = joints.iter().map(|j| j.error_percent).collect();
    let worst_joint = joints
        .iter()
        .max_by(|a, b| a.error.total_cmp(&b.error))
        .map(|j| j.key.clone())
        .unwrap_or_default();
    let unmatched = if correspondence.method == MatchMethod::Canonical {
        let (ref_map, _) = canonical_map(&reference);
        ref_map
            .keys()
            .filter(|k| !joints.iter().any(|j| &j.key == *k))
            .cloned()
            .collect()
    } else {
        Vec::new()
    };
    let chamfer = checked_chamfer(&predicted, &reference, figure.size, options)?;
    Ok(Evaluation {
        model: reference.model.clone(),
        rig: reference.rig.clone(),
        predicted_model: predicted.model.clone(),
        units: reference.units.clone(),
        figure,
        method: correspondence.method,
        predicted_naming: correspondence.predicted_naming,
        reference_naming: correspondence.reference_naming,
        summary: ErrorSummary::from_values(&errors),
        summary_percent: ErrorSummary::from_values(&errors_percent),
        worst_joint,
        unmatched,
        chamfer,
        chamfer_percent: chamfer.normalised(figure.size / 100.0),
        joints,
        warnings: warnings
            .into_iter()
            .map(|w| Warning::Eval(w).record())
            .collect(),
    })
}

/// Pairs the joints as `options.pairing` asks: by [`correspond`], or none (chamfer only) when
/// nothing is shared or too few names coincide, with a warning saying so.
///
/// # Errors
/// [`EvalError::NoSharedJoints`] when nothing pairs and pairing is required.
fn pairing(
    predicted: &ReferenceRig,
    reference: &ReferenceRig,
    options: &EvalOptions,
    warnings: &mut Vec<EvalWarning>,
) -> Result<Correspondence, EvalError> {
    Ok(match options.pairing {
        JointPairing::Required => correspond(predicted, reference)?,
        JointPairing::IfShared => match correspond(predicted, reference) {
            Ok(c)
                if c.method == MatchMethod::Name
                    && (c.pairs.len() as f64)
                        < options.min_name_fraction * reference.skeleton.len() as f64 =>
            {
                warnings.push(EvalWarning::FewSharedNames {
                    names: c.pairs.iter().map(|p| p.key.clone()).collect(),
                    reference_joints: reference.skeleton.len(),
                });
                chamfer_only(predicted, reference)
            }
            Ok(c) => c,
            Err(EvalError::NoSharedJoints {
                predicted: p,
                reference: r,
            }) => {
                warnings.push(EvalWarning::NoSharedJoints {
                    predicted: p.len(),
                    reference: r.len(),
                });
                chamfer_only(predicted, reference)
            }
            Err(e) => return Err(e),
        },
        JointPairing::Skip => chamfer_only(predicted, reference),
    })
}

/// Warnings about sizes: predicted and reference (and mesh and reference) differing beyond
/// `options.unit_mismatch_ratio`, and a zero figure size.
fn size_warnings(
    predicted: &ReferenceRig,
    reference: &ReferenceRig,
    figure: &FigureSize,
    options: &EvalOptions,
    warnings: &mut Vec<EvalWarning>,
) {
    let predicted_size = extent(predicted.bounding_box(), figure.measure);
    let reference_size = extent(reference.bounding_box(), figure.measure);
    warnings.extend(size_warning(
        "the predicted and reference figure sizes",
        predicted_size,
        reference_size,
        options.unit_mismatch_ratio,
    ));
    if figure.source == SizeSource::Mesh {
        warnings.extend(size_warning(
            "the mesh and reference skeleton sizes",
            figure.size,
            reference_size,
            options.unit_mismatch_ratio,
        ));
    }
    if figure.size <= 0.0 {
        warnings.push(EvalWarning::ZeroFigureSize);
    }
}

/// The RigNet chamfer distances, bones sampled every `bone_sample_fraction` of the figure
/// `size`.
///
/// # Errors
/// [`EvalError::NonFinite`] naming the joint furthest out when a distance overflows.
fn checked_chamfer(
    predicted: &ReferenceRig,
    reference: &ReferenceRig,
    size: f64,
    options: &EvalOptions,
) -> Result<ChamferDistances, EvalError> {
    let spacing = if size > 0.0 {
        options.bone_sample_fraction * size
    } else {
        ChamferOptions::default().bone_sample_spacing
    };
    let chamfer = chamfer(
        &predicted.skeleton,
        &reference.skeleton,
        &ChamferOptions {
            bone_sample_spacing: spacing,
        },
    );
    if ![chamfer.j2j, chamfer.j2b, chamfer.b2b]
        .iter()
        .all(|d| d.is_finite())
    {
        let far = [(predicted, "predicted"), (reference, "reference")]
            .into_iter()
            .flat_map(|(rig, role)| {
                rig.skeleton
                    .joints
                    .iter()
                    .map(move |j| (role, &j.name, j.position))
            })
            .max_by(|a, b| a.2.abs().max_element().total_cmp(&b.2.abs().max_element()));
        if let Some(far) = far {
            return Err(non_finite(far));
        }
    }
    Ok(chamfer)
}

/// [`EvalError::NonFinite`] for the joint `(role, name, position)` furthest out.
fn non_finite((role, joint, position): (&str, &String, glam::DVec3)) -> EvalError {
    EvalError::NonFinite {
        role: role.to_owned(),
        joint: joint.clone(),
        position: position.to_array(),
    }
}

impl Evaluation {
    /// Whether per-joint errors were computed (false for [`MatchMethod::ChamferOnly`]).
    pub fn has_joint_errors(&self) -> bool {
        self.method != MatchMethod::ChamferOnly
    }
}

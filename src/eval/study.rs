//! Robustness studies: rig variants of one mesh (other tessellations, rigid rotations) and
//! measure how far each variant's joints move from the base rig's, and their error to a
//! reference.

use super::{
    chamfer, correspond, evaluate, figure_size, rig_mesh, ChamferDistances, ChamferOptions,
    ErrorSummary, EvalError, EvalOptions, Evaluation, FigureMeasure, FigureSize, JointPairing,
    MatchMethod, ReferenceRig, RiggerOptions, Table,
};
use crate::mesh::Mesh;
use crate::skeleton::Skeleton;
use crate::warning::{Warning, WarningRecord};
use glam::{DQuat, DVec3};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Which study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StudyKind {
    /// Decimated and subdivided variants ([`Mesh::retessellated`]); level = triangle ratio.
    Tessellation,
    /// Rigid rotations; level = angle in degrees.
    Rotation,
}

/// Options of the studies.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyOptions {
    /// The rigging method and its parameters.
    pub rigger: RiggerOptions,
    /// Evaluation against the reference. Default: [`EvalOptions::default`] with
    /// [`JointPairing::IfShared`].
    pub eval: EvalOptions,
}

impl Default for StudyOptions {
    fn default() -> Self {
        Self {
            rigger: RiggerOptions::default(),
            eval: EvalOptions {
                pairing: JointPairing::IfShared,
                ..EvalOptions::default()
            },
        }
    }
}

/// How a variant's joints were paired with the base rig's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DisplacementPairing {
    /// By canonical anatomical keys both rigs have.
    Canonical,
    /// Joint by joint: both skeletons have the same joint count and parent structure.
    Index,
    /// Topology differs and no keys are shared: only the chamfer distances to the base.
    Chamfer,
}

/// The displacement of one paired joint from its base position.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointDisplacement {
    /// Canonical key or joint name.
    pub key: String,
    /// Distance, mesh units.
    pub distance: f64,
    /// Distance, % of figure size.
    pub percent: f64,
}

/// One variant of a study.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct StudyVariant {
    /// Row label (`x0.25`, `45°`, ...).
    pub label: String,
    /// Triangle ratio (tessellation) or angle in degrees (rotation).
    pub level: f64,
    /// Whether this is the base variant (the mesh as given).
    pub base: bool,
    /// Triangles of the variant mesh.
    pub triangles: usize,
    /// Joints of the variant's skeleton (0 when rigging failed).
    pub joints: usize,
    /// How joints were paired with the base (`None` for the base or a failed variant).
    pub pairing: Option<DisplacementPairing>,
    /// Per-joint displacement from the base, in the base frame (empty for chamfer pairing).
    pub displacement: Vec<JointDisplacement>,
    /// Summary of `displacement[].percent`.
    pub displacement_percent: Option<ErrorSummary>,
    /// Chamfer distances to the base skeleton (all joints), % of figure size.
    pub chamfer_to_base_percent: Option<ChamferDistances>,
    /// Evaluation against the reference (in the base frame), when one was given.
    pub to_reference: Option<Evaluation>,
    /// Rig time per stage, milliseconds.
    pub timings: Vec<(String, f64)>,
    /// Warnings of the rig and the evaluation, as records: a study is a file format that
    /// `skelfit report` reads back.
    pub warnings: Vec<WarningRecord>,
    /// Why the variant failed, if it did.
    pub failure: Option<String>,
    /// The variant's skeleton mapped back into the base frame (not serialised).
    #[serde(skip)]
    pub skeleton: Option<Skeleton>,
}

impl StudyVariant {
    /// The headline displacement, % of figure size: the mean per-joint displacement where
    /// joints pair, else CD-J2J to the base.
    pub fn displacement_headline(&self) -> Option<f64> {
        self.displacement_percent
            .map(|s| s.mean)
            .or(self.chamfer_to_base_percent.map(|c| c.j2j))
    }
}

/// A study's result.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Study {
    /// Which study.
    pub kind: StudyKind,
    /// Model name.
    pub model: String,
    /// Reference model and rig, when a reference was given.
    pub reference: Option<String>,
    /// The figure size all percentages refer to (base mesh).
    pub figure: FigureSize,
    /// The variants; the base comes first.
    pub variants: Vec<StudyVariant>,
}

impl Study {
    /// The base variant.
    pub fn base(&self) -> Option<&StudyVariant> {
        self.variants.iter().find(|v| v.base)
    }
}

/// A variant to rig: its mesh and the rotation mapping the base frame into its frame.
struct VariantInput {
    label: String,
    level: f64,
    mesh: Mesh,
    rotation: DQuat,
    centre: DVec3,
}

fn millis(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

/// A variant and its rig (or why it did not rig).
type RiggedVariant = (VariantInput, Result<super::Rigged, String>);

/// Rigs every variant (in parallel; results in input order), its joints moved back into the
/// base frame and its total time appended to its timings.
fn rig_variants(inputs: Vec<VariantInput>, options: &StudyOptions) -> Vec<RiggedVariant> {
    inputs
        .into_par_iter()
        .map(|input| {
            let mut rigger = options.rigger.clone();
            rigger.orientation = rigger.orientation.rotated(input.rotation);
            let clock = Instant::now();
            let result = rig_mesh(&input.mesh, &rigger).map(|mut r| {
                // Back into the base frame.
                let back = input.rotation.inverse();
                for joint in &mut r.skeleton.joints {
                    joint.position = input.centre + back * (joint.position - input.centre);
                }
                r.timings.push(("total".into(), millis(clock)));
                r
            });
            (input, result.map_err(|e| e.to_string()))
        })
        .collect()
}

/// A variant of `input` with nothing measured yet (`base`: the study's base variant).
fn blank_variant(input: VariantInput, base: bool) -> StudyVariant {
    StudyVariant {
        label: input.label,
        level: input.level,
        base,
        triangles: input.mesh.triangles.len(),
        joints: 0,
        pairing: None,
        displacement: Vec::new(),
        displacement_percent: None,
        chamfer_to_base_percent: None,
        to_reference: None,
        timings: Vec::new(),
        warnings: Vec::new(),
        failure: None,
        skeleton: None,
    }
}

/// Runs every variant (in parallel; results in input order), the first being the base.
fn run_study(
    kind: StudyKind,
    model: &str,
    base_mesh: &Mesh,
    reference: Option<&ReferenceRig>,
    inputs: Vec<VariantInput>,
    options: &StudyOptions,
) -> Result<Study, crate::Error> {
    let mut rigged = rig_variants(inputs, options);
    let (base_skeleton, base_canonical) = match &rigged[0].1 {
        Ok(r) => (r.skeleton.clone(), r.canonical.clone()),
        Err(message) => {
            return Err(EvalError::Study {
                message: format!("the base mesh did not rig: {message}"),
            }
            .into())
        }
    };
    // The rigs' own canonical maps (a method that names no anatomy leaves them empty, and the
    // joint names are read by the naming presets).
    let mut base_rig = ReferenceRig::from_skeleton(model, base_skeleton.clone());
    base_rig.canonical = base_canonical;
    let figure = match reference {
        Some(r) => figure_size(r, Some(base_mesh), options.eval.measure),
        None => figure_size(&base_rig, Some(base_mesh), FigureMeasure::LongestSide),
    };
    let percent = |d: f64| {
        if figure.size > 0.0 {
            100.0 * d / figure.size
        } else {
            0.0
        }
    };
    let chamfer_options = ChamferOptions {
        bone_sample_spacing: if figure.size > 0.0 {
            options.eval.bone_sample_fraction * figure.size
        } else {
            ChamferOptions::default().bone_sample_spacing
        },
    };
    let mut variants = Vec::with_capacity(rigged.len());
    for (index, (input, result)) in rigged.drain(..).enumerate() {
        let mut variant = blank_variant(input, index == 0);
        let rig = match result {
            Ok(rig) => rig,
            Err(message) => {
                variant.failure = Some(message);
                variants.push(variant);
                continue;
            }
        };
        variant.joints = rig.skeleton.len();
        variant.timings = rig.timings;
        variant.warnings = rig.warnings.iter().map(Warning::record).collect();
        let mut predicted = ReferenceRig::from_skeleton(model, rig.skeleton.clone());
        predicted.canonical = rig.canonical;
        let (pairing, displacement) = displacement(&predicted, &base_rig);
        variant.displacement = displacement
            .into_iter()
            .map(|(key, distance)| JointDisplacement {
                key,
                distance,
                percent: percent(distance),
            })
            .collect();
        if pairing != DisplacementPairing::Chamfer {
            let values: Vec<f64> = variant.displacement.iter().map(|d| d.percent).collect();
            variant.displacement_percent = Some(ErrorSummary::from_values(&values));
        }
        variant.pairing = Some(pairing);
        variant.chamfer_to_base_percent = Some(
            chamfer(&rig.skeleton, &base_skeleton, &chamfer_options)
                .normalised(figure.size / 100.0),
        );
        if let Some(reference) = reference {
            match evaluate(&predicted, reference, Some(base_mesh), &options.eval) {
                Ok(e) => {
                    variant.warnings.extend(e.warnings.iter().cloned());
                    variant.to_reference = Some(e);
                }
                Err(e) => variant.failure = Some(e.to_string()),
            }
        }
        variant.skeleton = Some(rig.skeleton);
        variants.push(variant);
    }
    Ok(Study {
        kind,
        model: model.to_owned(),
        reference: reference.map(|r| match &r.rig {
            Some(rig) => format!("{} (rig {rig})", r.model),
            None => r.model.clone(),
        }),
        figure,
        variants,
    })
}

/// Pairs `variant` with `base`: canonical keys when both have them, joint by joint when the
/// parent structure is identical, else nothing (chamfer only). Returns `(key, distance)` pairs.
fn displacement(
    variant: &ReferenceRig,
    base: &ReferenceRig,
) -> (DisplacementPairing, Vec<(String, f64)>) {
    if let Ok(c) = correspond(variant, base) {
        if c.method == MatchMethod::Canonical {
            let pairs = c
                .pairs
                .iter()
                .map(|p| {
                    let a = variant.skeleton.joint(p.predicted).position;
                    let b = base.skeleton.joint(p.reference).position;
                    (p.key.clone(), a.distance(b))
                })
                .collect();
            return (DisplacementPairing::Canonical, pairs);
        }
    }
    let same_structure = variant.skeleton.len() == base.skeleton.len()
        && variant
            .skeleton
            .joints
            .iter()
            .zip(&base.skeleton.joints)
            .all(|(a, b)| a.parent == b.parent);
    if same_structure {
        let pairs = variant
            .skeleton
            .joints
            .iter()
            .zip(&base.skeleton.joints)
            .map(|(a, b)| (b.name.clone(), a.position.distance(b.position)))
            .collect();
        (DisplacementPairing::Index, pairs)
    } else {
        (DisplacementPairing::Chamfer, Vec::new())
    }
}

/// Tessellation study: rigs `mesh` and its [`Mesh::retessellated`] variants at `levels`
/// (triangle ratios; 1 = the mesh as given, always included as the base) and measures each
/// variant's joint displacement from the base rig and, with a `reference`, its error to it.
///
/// # Errors
/// [`EvalError::Study`] for a level that is not a positive finite number or when the base mesh
/// does not rig.
pub fn tessellation_study(
    mesh: &Mesh,
    model: &str,
    reference: Option<&ReferenceRig>,
    levels: &[f64],
    options: &StudyOptions,
) -> Result<Study, crate::Error> {
    if let Some(bad) = levels.iter().find(|l| !(l.is_finite() && **l > 0.0)) {
        return Err(EvalError::Study {
            message: format!(
                "tessellation level {bad} must be a positive triangle ratio (e.g. 0.25 or 2)"
            ),
        }
        .into());
    }
    let mut sorted: Vec<f64> = levels.iter().copied().filter(|l| *l != 1.0).collect();
    sorted.sort_by(f64::total_cmp);
    sorted.dedup();
    let centre = DVec3::ZERO;
    let inputs = std::iter::once(1.0)
        .chain(sorted)
        .map(|level| VariantInput {
            label: format!("x{level}"),
            level,
            mesh: if level == 1.0 {
                mesh.clone()
            } else {
                mesh.retessellated(level)
            },
            rotation: DQuat::IDENTITY,
            centre,
        })
        .collect();
    run_study(
        StudyKind::Tessellation,
        model,
        mesh,
        reference,
        inputs,
        options,
    )
}

/// Rotation study: rigs `mesh` rotated rigidly about its bounding-box centre by `k·360°/n`
/// (`k = 0..n`) about `axis`, with the rigger's up/forward rotated to match, maps each rig's
/// joints back by the inverse rotation, and measures their displacement from the unrotated
/// rig (`k = 0`, the base) and, with a `reference`, the error to it.
///
/// # Errors
/// [`EvalError::Study`] for `n == 0` or a zero or non-finite axis, or when the base mesh does
/// not rig.
pub fn rotation_study(
    mesh: &Mesh,
    model: &str,
    reference: Option<&ReferenceRig>,
    n: usize,
    axis: DVec3,
    options: &StudyOptions,
) -> Result<Study, crate::Error> {
    let Some(axis) = axis.try_normalize().filter(|_| n > 0) else {
        return Err(EvalError::Study {
            message: format!(
                "rotation study needs n >= 1 (got {n}) and a non-zero axis (got {axis})"
            ),
        }
        .into());
    };
    let centre = mesh
        .bounding_box()
        .map_or(DVec3::ZERO, |(lo, hi)| 0.5 * (lo + hi));
    let inputs = (0..n)
        .map(|k| {
            let degrees = 360.0 * k as f64 / n as f64;
            let rotation = DQuat::from_axis_angle(axis, degrees.to_radians());
            let positions = mesh
                .positions
                .iter()
                .map(|&p| centre + rotation * (p - centre))
                .collect();
            VariantInput {
                label: format!("{degrees:.1}°"),
                level: degrees,
                mesh: Mesh {
                    positions,
                    triangles: mesh.triangles.clone(),
                },
                rotation,
                centre,
            }
        })
        .collect();
    run_study(StudyKind::Rotation, model, mesh, reference, inputs, options)
}

fn cell(value: Option<f64>) -> String {
    super::percent_cell(value)
}

/// The study as a table: one row per variant.
pub fn study_table(study: &Study) -> Table {
    let level = match study.kind {
        StudyKind::Tessellation => "triangle ratio",
        StudyKind::Rotation => "angle",
    };
    let headers = [
        "variant",
        level,
        "triangles",
        "joints",
        "pairing",
        "disp. mean %",
        "disp. max %",
        "J2J to base %",
        "B2B to base %",
        "ref mean %",
        "ref J2J %",
        "ref B2B %",
        "rig ms",
        "status",
    ];
    let numeric = [
        false, true, true, true, false, true, true, true, true, true, true, true, true, false,
    ];
    let rows = study
        .variants
        .iter()
        .map(|v| {
            let r = v.to_reference.as_ref();
            vec![
                v.label.clone(),
                format!("{}", v.level),
                v.triangles.to_string(),
                v.joints.to_string(),
                match v.pairing {
                    Some(DisplacementPairing::Canonical) => "canonical",
                    Some(DisplacementPairing::Index) => "index",
                    Some(DisplacementPairing::Chamfer) => "chamfer",
                    None => "–",
                }
                .to_owned(),
                cell(v.displacement_percent.map(|s| s.mean)),
                cell(v.displacement_percent.map(|s| s.max)),
                cell(v.chamfer_to_base_percent.map(|c| c.j2j)),
                cell(v.chamfer_to_base_percent.map(|c| c.b2b)),
                cell(
                    r.filter(|e| e.has_joint_errors())
                        .map(|e| e.summary_percent.mean),
                ),
                cell(r.map(|e| e.chamfer_percent.j2j)),
                cell(r.map(|e| e.chamfer_percent.b2b)),
                v.timings
                    .iter()
                    .find(|(s, _)| s == "total")
                    .map_or("–".into(), |(_, ms)| format!("{ms:.0}")),
                match (&v.failure, v.base) {
                    (Some(f), _) => format!("failed: {f}"),
                    (None, true) => "base".into(),
                    (None, false) => "ok".into(),
                },
            ]
        })
        .collect();
    Table {
        headers: headers.map(String::from).to_vec(),
        rows,
        numeric: numeric.to_vec(),
    }
}

/// The study table as CSV (the cells of [`study_table`], `–` written as empty).
///
/// # Errors
/// [`EvalError::Table`] when writing fails.
pub fn study_csv(study: &Study) -> Result<String, EvalError> {
    let table = study_table(study);
    let table_error = |e: &dyn std::fmt::Display| EvalError::Table {
        what: "study csv",
        message: e.to_string(),
    };
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record(&table.headers)
        .map_err(|e| table_error(&e))?;
    for row in &table.rows {
        let cells: Vec<&str> = row
            .iter()
            .map(|c| if c == "–" { "" } else { c.as_str() })
            .collect();
        csv.write_record(&cells).map_err(|e| table_error(&e))?;
    }
    let bytes = csv.into_inner().map_err(|e| table_error(&e))?;
    String::from_utf8(bytes).map_err(|e| table_error(&e))
}

/// The study as a Markdown page: `title`, the caller's `preamble`, what the columns mean and
/// the table.
pub fn study_markdown(study: &Study, title: &str, preamble: &str) -> String {
    let mut md = format!("# {title}\n\n");
    if !preamble.is_empty() {
        md.push_str(preamble.trim_end());
        md.push_str("\n\n");
    }
    md.push_str(&format!(
        "Model `{}`{}; figure size {:.4} ({:?} of the {:?}). Displacement is measured from the base rig (the mesh as given) {}: per joint where joints pair (canonical keys, or index when the skeleton's structure is unchanged), else as chamfer distances (J2J/B2B) to the base. All values are % of figure size.\n\n",
        study.model,
        study
            .reference
            .as_ref()
            .map(|r| format!(", reference {r}"))
            .unwrap_or_default(),
        study.figure.size,
        study.figure.measure,
        study.figure.source,
        match study.kind {
            StudyKind::Tessellation => "after re-tessellation (decimation below 1, subdivision above)",
            StudyKind::Rotation => "after rotating the mesh and rotating the joints back",
        }
    ).replace("LongestSide", "longest side").replace("ReferenceJoints", "reference joints"));
    md.push_str(&study_table(study).markdown());
    let notes: Vec<String> = study
        .variants
        .iter()
        .flat_map(|v| {
            v.warnings
                .iter()
                .map(move |w| format!("* {}: {w}", v.label))
        })
        .collect();
    if !notes.is_empty() {
        md.push_str("\n## Notes\n\n");
        md.push_str(&notes.join("\n"));
        md.push('\n');
    }
    md
}

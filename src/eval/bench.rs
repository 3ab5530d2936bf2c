//! Benchmarks over a refdata-style folder: find the models, rig each with a
//! [`RigMethod`](super::RigMethod), evaluate it against its reference rig, and tabulate accuracy
//! and per-stage timings. One model at a time here; callers run [`bench_model`] in parallel.

use super::{
    aggregate, core_error, evaluate, load_skeleton, percent_cell, rig_mesh, CoreError, EvalError,
    EvalOptions, Evaluation, JointPairing, MatchMethod, ReferenceRig, RigAnatomy, RigMethod,
    RiggerOptions, Table,
};
use crate::warning::{Warning, WarningRecord};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// One model of a benchmark folder.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct BenchModel {
    /// Model name (its folder name).
    pub name: String,
    /// Category folder (`humanoid`, `quadruped`, ...); empty for models directly in the root.
    pub category: String,
    /// The model folder.
    pub dir: PathBuf,
    /// Its `mesh.obj`.
    pub mesh: PathBuf,
    /// The reference rig file chosen, if any.
    pub reference: Option<PathBuf>,
    /// Why the reference is not the requested rig (fallback) or is missing.
    pub note: Option<String>,
    /// A real game character ([`is_real_character`]).
    #[serde(default)]
    pub real: bool,
}

/// Whether the refdata model folder `dir` holds a real game character: its `provenance.json`
/// names the `converter` that made it from the artist's skinned file (refdata README, "Real
/// game characters"; the earlier glTF models and the generated bodies have none).
pub fn is_real_character(dir: &Path) -> bool {
    std::fs::read(dir.join("provenance.json"))
        .ok()
        .and_then(|b| serde_json::from_slice::<serde_json::Value>(&b).ok())
        .is_some_and(|p| p.get("converter").is_some())
}

/// The `rig_*.json` files of `dir`, sorted by name.
fn rig_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("rig_") && n.ends_with(".json"))
        })
        .collect();
    files.sort();
    files
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn bench_model_in(dir: &Path, category: &str, rig: &str) -> BenchModel {
    let wanted = dir.join(format!("rig_{rig}.json"));
    let files = rig_files(dir);
    let (reference, note) = if wanted.is_file() {
        (Some(wanted), None)
    } else if files.len() == 1 {
        let only = files[0].clone();
        let note = format!(
            "no rig_{rig}.json: evaluated against its only rig file {}",
            file_name(&only)
        );
        (Some(only), Some(note))
    } else if files.is_empty() {
        (None, Some("no rig_*.json reference file".to_owned()))
    } else {
        let names: Vec<String> = files.iter().map(|f| file_name(f)).collect();
        let note = format!(
            "no rig_{rig}.json among {}: pass --rig with one of them",
            names.join(", ")
        );
        (None, Some(note))
    };
    BenchModel {
        name: file_name(dir),
        category: category.to_owned(),
        dir: dir.to_owned(),
        mesh: dir.join("mesh.obj"),
        reference,
        note,
        real: is_real_character(dir),
    }
}

fn sorted_dirs(dir: &Path) -> Result<Vec<PathBuf>, EvalError> {
    let entries = std::fs::read_dir(dir).map_err(|cause| EvalError::Io {
        path: dir.to_owned(),
        cause,
    })?;
    let mut dirs: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect();
    dirs.sort();
    Ok(dirs)
}

/// The models of a benchmark folder, sorted by category and name: `root` itself when it holds a
/// `mesh.obj`, else every sub-folder with a `mesh.obj`, and one level further for category
/// folders (the refdata layout `<category>/<model>/mesh.obj`). Each model's reference is
/// `rig_<rig>.json`, else its only `rig_*.json` (with a note saying so), else none (with a note).
///
/// # Errors
/// [`EvalError::Io`] when `root` cannot be read, [`EvalError::NoModels`] when nothing is found.
pub fn find_bench_models(root: &Path, rig: &str) -> Result<Vec<BenchModel>, EvalError> {
    if root.join("mesh.obj").is_file() {
        return Ok(vec![bench_model_in(root, "", rig)]);
    }
    let mut models = Vec::new();
    for dir in sorted_dirs(root)? {
        if dir.join("mesh.obj").is_file() {
            models.push(bench_model_in(&dir, "", rig));
            continue;
        }
        let category = file_name(&dir);
        for sub in sorted_dirs(&dir).unwrap_or_default() {
            if sub.join("mesh.obj").is_file() {
                models.push(bench_model_in(&sub, &category, rig));
            }
        }
    }
    if models.is_empty() {
        return Err(EvalError::NoModels {
            path: root.to_owned(),
        });
    }
    Ok(models)
}

/// Options of [`bench_model`].
#[derive(Debug, Clone, PartialEq)]
pub struct BenchOptions {
    /// The rigging method and its parameters.
    pub rigger: RiggerOptions,
    /// Evaluation options. Default: [`EvalOptions::default`] with
    /// [`JointPairing::IfShared`], so that methods whose joints are not anatomically named
    /// still get the chamfer distances.
    pub eval: EvalOptions,
}

impl Default for BenchOptions {
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

/// The outcome of benchmarking one model. A failure is recorded, not returned, so that one bad
/// model does not stop a run.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct BenchResult {
    /// Model name.
    pub model: String,
    /// Category folder (may be empty).
    pub category: String,
    /// Reference rig file name (e.g. `rig_game_engine.json`), empty when none.
    pub reference: String,
    /// The rigging method.
    pub method: RigMethod,
    /// Triangles of the mesh (0 when it did not load).
    pub triangles: usize,
    /// Joints of the predicted skeleton (all, before the deforming filter).
    pub predicted_joints: usize,
    /// The evaluation, when rigging and evaluation succeeded.
    pub evaluation: Option<Evaluation>,
    /// Wall-clock milliseconds per stage: `load` (mesh and reference), the method's stages,
    /// `evaluate`.
    pub timings: Vec<(String, f64)>,
    /// Notes for the reader: reference fallbacks, stage and evaluation warnings.
    pub notes: Vec<String>,
    /// Why the model failed, if it did.
    pub failure: Option<String>,
    /// The predicted skeleton (for pictures; not serialised).
    #[serde(skip)]
    pub predicted: Option<ReferenceRig>,
    /// The reference rig (for pictures; not serialised).
    #[serde(skip)]
    pub reference_rig: Option<ReferenceRig>,
    /// A real game character ([`BenchModel::real`]).
    #[serde(default)]
    pub real: bool,
    /// The core joint error ([`core_error`]), for upright figures paired by canonical keys.
    #[serde(default)]
    pub core: Option<CoreError>,
    /// What the anatomical rig found (figure, template, parts, missing parts).
    #[serde(default)]
    pub anatomy: Option<RigAnatomy>,
    /// The rigging method's warnings (their messages also among `notes`), as records: bench
    /// results are a file format that `skelfit report` reads back.
    #[serde(default)]
    pub warnings: Vec<WarningRecord>,
}

impl BenchResult {
    /// Sum of the stage timings, milliseconds.
    pub fn total_ms(&self) -> f64 {
        self.timings.iter().map(|(_, ms)| ms).sum()
    }

    /// Milliseconds of `stage`, if it ran.
    pub fn stage_ms(&self, stage: &str) -> Option<f64> {
        self.timings
            .iter()
            .find(|(s, _)| s == stage)
            .map(|(_, ms)| *ms)
    }
}

fn millis(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

/// Loads `model`'s mesh and reference, rigs the mesh with `options.rigger`, and evaluates the
/// prediction against the reference (figure size from the mesh). Never fails: problems are in
/// [`BenchResult::failure`].
pub fn bench_model(model: &BenchModel, options: &BenchOptions) -> BenchResult {
    let mut result = BenchResult {
        model: model.name.clone(),
        category: model.category.clone(),
        reference: model
            .reference
            .as_deref()
            .map(file_name)
            .unwrap_or_default(),
        method: options.rigger.method,
        triangles: 0,
        predicted_joints: 0,
        evaluation: None,
        timings: Vec::new(),
        notes: model.note.iter().cloned().collect(),
        failure: None,
        predicted: None,
        reference_rig: None,
        real: model.real,
        core: None,
        anatomy: None,
        warnings: Vec::new(),
    };
    if let Err(message) = run_model(model, options, &mut result) {
        result.failure = Some(message);
    }
    result
}

fn run_model(
    model: &BenchModel,
    options: &BenchOptions,
    result: &mut BenchResult,
) -> Result<(), String> {
    let clock = Instant::now();
    let mesh = crate::mesh::load(&model.mesh).map_err(|e| e.to_string())?;
    result.triangles = mesh.triangles.len();
    let reference_path = model
        .reference
        .as_deref()
        .ok_or_else(|| "no reference rig to evaluate against".to_owned())?;
    let reference = load_skeleton(reference_path).map_err(|e| e.to_string())?;
    result.timings.push(("load".into(), millis(clock)));
    let rigged = rig_mesh(&mesh, &options.rigger)
        .map_err(|e| format!("{} rig failed: {e}", options.rigger.method.name()))?;
    result.timings.extend(rigged.timings);
    result
        .notes
        .extend(rigged.warnings.iter().map(ToString::to_string));
    result.warnings = rigged.warnings.iter().map(Warning::record).collect();
    result.anatomy = rigged.anatomy;
    result.predicted_joints = rigged.skeleton.len();
    let mut predicted = ReferenceRig::from_skeleton(model.name.clone(), rigged.skeleton);
    predicted.canonical = rigged.canonical;
    let clock = Instant::now();
    let evaluation =
        evaluate(&predicted, &reference, Some(&mesh), &options.eval).map_err(|e| e.to_string())?;
    result.timings.push(("evaluate".into(), millis(clock)));
    result
        .notes
        .extend(evaluation.warnings.iter().map(|w| w.message.clone()));
    result.core = core_error(&evaluation);
    result.evaluation = Some(evaluation);
    result.predicted = Some(predicted);
    result.reference_rig = Some(reference);
    Ok(())
}

/// Stage names over all results, in first-seen order.
pub fn stage_names(results: &[BenchResult]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for (stage, _) in results.iter().flat_map(|r| &r.timings) {
        if !names.contains(stage) {
            names.push(stage.clone());
        }
    }
    names
}

/// `ok`, `chamfer only` or `failed`.
fn status(result: &BenchResult) -> &'static str {
    match (&result.failure, &result.evaluation) {
        (Some(_), _) | (None, None) => "failed",
        (None, Some(e)) if e.method == MatchMethod::ChamferOnly => "chamfer only",
        (None, Some(_)) => "ok",
    }
}

fn pairing_name(e: &Evaluation) -> &'static str {
    match e.method {
        MatchMethod::Canonical => "canonical",
        MatchMethod::Name => "name",
        MatchMethod::ChamferOnly => "chamfer_only",
    }
}

/// The CSV columns before the per-stage timings.
const CSV_HEADERS: [&str; 37] = [
    "category",
    "model",
    "reference",
    "method",
    "status",
    "pairing",
    "triangles",
    "predicted_joints",
    "paired_joints",
    "figure_size",
    "mean",
    "median",
    "max",
    "rms",
    "mean_percent",
    "median_percent",
    "max_percent",
    "rms_percent",
    "worst_joint",
    "cd_j2j",
    "cd_j2b",
    "cd_b2b",
    "cd_j2j_percent",
    "cd_j2b_percent",
    "cd_b2b_percent",
    "core_mean",
    "core_mean_percent",
    "core_max_percent",
    "core_paired",
    "core_mapped",
    "core_missing",
    "real",
    "figure",
    "template",
    "parts",
    "missing_parts",
    "warnings",
];

/// One model's CSV row ([`bench_csv`]), with a timing cell per stage of `stages`.
fn csv_row(r: &BenchResult, stages: &[String]) -> Vec<String> {
    let e = r.evaluation.as_ref();
    let num = |v: Option<f64>| v.map(|v| v.to_string()).unwrap_or_default();
    let joint_stat = |f: fn(&Evaluation) -> f64| num(e.filter(|e| e.has_joint_errors()).map(f));
    let mut row: Vec<String> = vec![
        r.category.clone(),
        r.model.clone(),
        r.reference.clone(),
        r.method.name().to_owned(),
        status(r).to_owned(),
        e.map(pairing_name).unwrap_or_default().to_owned(),
        r.triangles.to_string(),
        r.predicted_joints.to_string(),
        e.map(|e| e.joints.len().to_string()).unwrap_or_default(),
        num(e.map(|e| e.figure.size)),
        joint_stat(|e| e.summary.mean),
        joint_stat(|e| e.summary.median),
        joint_stat(|e| e.summary.max),
        joint_stat(|e| e.summary.rms),
        joint_stat(|e| e.summary_percent.mean),
        joint_stat(|e| e.summary_percent.median),
        joint_stat(|e| e.summary_percent.max),
        joint_stat(|e| e.summary_percent.rms),
        e.map(|e| e.worst_joint.clone()).unwrap_or_default(),
        num(e.map(|e| e.chamfer.j2j)),
        num(e.map(|e| e.chamfer.j2b)),
        num(e.map(|e| e.chamfer.b2b)),
        num(e.map(|e| e.chamfer_percent.j2j)),
        num(e.map(|e| e.chamfer_percent.j2b)),
        num(e.map(|e| e.chamfer_percent.b2b)),
    ];
    let c = r.core.as_ref();
    let a = r.anatomy.as_ref();
    row.extend([
        num(c.map(|c| c.mean)),
        num(c.map(|c| c.mean_percent)),
        num(c.map(|c| c.max_percent)),
        c.map(|c| c.paired.to_string()).unwrap_or_default(),
        c.map(|c| c.mapped.len().to_string()).unwrap_or_default(),
        c.map(|c| c.missing.join(" ")).unwrap_or_default(),
        r.real.to_string(),
        a.map(|a| a.figure.clone()).unwrap_or_default(),
        a.map(|a| a.template.clone()).unwrap_or_default(),
        a.map(|a| a.parts.clone()).unwrap_or_default(),
        a.map(|a| a.missing_parts.join(", ")).unwrap_or_default(),
        r.warnings.len().to_string(),
    ]);
    row.extend(stages.iter().map(|s| num(r.stage_ms(s))));
    row.push(r.total_ms().to_string());
    row.push(r.failure.clone().unwrap_or_default());
    row.push(r.notes.join("; "));
    row
}

/// The results as CSV: one row per model with accuracy in mesh units and % of figure size,
/// chamfer distances, one `<stage>_ms` column per stage ([`stage_names`]) and `total_ms`.
/// Missing values are empty cells.
///
/// # Errors
/// [`EvalError::Table`] when writing fails.
pub fn bench_csv(results: &[BenchResult]) -> Result<String, EvalError> {
    let stages = stage_names(results);
    let mut headers: Vec<String> = CSV_HEADERS.map(String::from).to_vec();
    headers.extend(stages.iter().map(|s| format!("{s}_ms")));
    headers.extend(["total_ms", "failure", "notes"].map(String::from));
    let table_error = |e: csv::Error| EvalError::Table {
        what: "bench csv",
        message: e.to_string(),
    };
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record(&headers).map_err(table_error)?;
    for r in results {
        let row = csv_row(r, &stages);
        csv.write_record(&row).map_err(table_error)?;
    }
    let bytes = csv.into_inner().map_err(|e| EvalError::Table {
        what: "bench csv",
        message: e.to_string(),
    })?;
    String::from_utf8(bytes).map_err(|e| EvalError::Table {
        what: "bench csv",
        message: e.to_string(),
    })
}

/// The accuracy table: one row per model, errors in % of figure size (`–` where unavailable).
pub fn bench_table(results: &[BenchResult]) -> Table {
    let headers = [
        "model",
        "category",
        "reference",
        "pairing",
        "joints",
        "paired",
        "mean %",
        "median %",
        "max %",
        "worst",
        "J2J %",
        "J2B %",
        "B2B %",
        "core %",
        "core missing",
        "status",
    ];
    let numeric = [
        false, false, false, false, true, true, true, true, true, false, true, true, true, true,
        false, false,
    ];
    let rows = results
        .iter()
        .map(|r| {
            let e = r.evaluation.as_ref();
            let stat =
                |f: fn(&Evaluation) -> f64| percent_cell(e.filter(|e| e.has_joint_errors()).map(f));
            let chamfer = |f: fn(&Evaluation) -> f64| percent_cell(e.map(f));
            vec![
                r.model.clone(),
                r.category.clone(),
                r.reference.clone(),
                e.map(pairing_name).unwrap_or("–").to_owned(),
                r.predicted_joints.to_string(),
                e.map_or(0, |e| e.joints.len()).to_string(),
                stat(|e| e.summary_percent.mean),
                stat(|e| e.summary_percent.median),
                stat(|e| e.summary_percent.max),
                e.map(|e| e.worst_joint.clone())
                    .filter(|w| !w.is_empty())
                    .unwrap_or_else(|| "–".into()),
                chamfer(|e| e.chamfer_percent.j2j),
                chamfer(|e| e.chamfer_percent.j2b),
                chamfer(|e| e.chamfer_percent.b2b),
                percent_cell(r.core.as_ref().map(|c| c.mean_percent)),
                r.core.as_ref().map_or_else(
                    || "–".to_owned(),
                    |c| {
                        if c.missing.is_empty() {
                            "none".to_owned()
                        } else {
                            c.missing.join(", ")
                        }
                    },
                ),
                match &r.failure {
                    Some(f) => format!("failed: {f}"),
                    None => status(r).to_owned(),
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

/// The timing table: one row per model, milliseconds per stage and in total.
pub fn timing_table(results: &[BenchResult]) -> Table {
    let stages = stage_names(results);
    let mut headers = vec!["model".to_owned(), "triangles".to_owned()];
    headers.extend(stages.iter().cloned());
    headers.push("total".into());
    let mut numeric = vec![false];
    numeric.resize(headers.len(), true);
    let rows = results
        .iter()
        .map(|r| {
            let mut row = vec![r.model.clone(), r.triangles.to_string()];
            row.extend(
                stages
                    .iter()
                    .map(|s| r.stage_ms(s).map_or("–".into(), |ms| format!("{ms:.1}"))),
            );
            row.push(format!("{:.1}", r.total_ms()));
            row
        })
        .collect();
    Table {
        headers,
        rows,
        numeric,
    }
}

/// Counts of a run: models, evaluated per joint, chamfer only, failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct BenchCounts {
    /// Models in the run.
    pub models: usize,
    /// Models with per-joint errors.
    pub per_joint: usize,
    /// Models evaluated by chamfer distances only.
    pub chamfer_only: usize,
    /// Models that failed.
    pub failed: usize,
}

/// How many models succeeded in which way.
pub fn bench_counts(results: &[BenchResult]) -> BenchCounts {
    let mut counts = BenchCounts {
        models: results.len(),
        ..Default::default()
    };
    for r in results {
        match status(r) {
            "ok" => counts.per_joint += 1,
            "chamfer only" => counts.chamfer_only += 1,
            _ => counts.failed += 1,
        }
    }
    counts
}

/// Per-joint errors in mesh units: one row per joint key (in first-seen order), one column per
/// model with per-joint errors, then the models' mean and max rows. Empty when no model has
/// per-joint errors.
pub fn joint_model_table(results: &[BenchResult]) -> Table {
    let evaluated: Vec<(&str, &Evaluation)> = results
        .iter()
        .filter_map(|r| {
            r.evaluation
                .as_ref()
                .filter(|e| e.has_joint_errors())
                .map(|e| (r.model.as_str(), e))
        })
        .collect();
    let mut keys: Vec<&str> = Vec::new();
    for (_, e) in &evaluated {
        for j in &e.joints {
            if !keys.contains(&j.key.as_str()) {
                keys.push(&j.key);
            }
        }
    }
    let mut headers = vec!["joint".to_string()];
    headers.extend(evaluated.iter().map(|(m, _)| m.to_string()));
    let numeric = std::iter::once(false)
        .chain(evaluated.iter().map(|_| true))
        .collect();
    let cell = |v: Option<f64>| v.map_or_else(|| "–".to_string(), |v| format!("{v:.4}"));
    let mut rows: Vec<Vec<String>> = keys
        .iter()
        .map(|k| {
            std::iter::once(k.to_string())
                .chain(
                    evaluated
                        .iter()
                        .map(|(_, e)| cell(e.joints.iter().find(|j| j.key == *k).map(|j| j.error))),
                )
                .collect()
        })
        .collect();
    if !rows.is_empty() {
        for (name, pick) in [("mean", 0usize), ("max", 1)] {
            rows.push(
                std::iter::once(format!("**{name}**"))
                    .chain(evaluated.iter().map(|(_, e)| {
                        cell(Some(if pick == 0 {
                            e.summary.mean
                        } else {
                            e.summary.max
                        }))
                    }))
                    .collect(),
            );
        }
    }
    Table {
        headers,
        rows,
        numeric,
    }
}

/// What the columns of [`super::anatomy_table`] mean (Markdown).
pub const ANATOMY_CAPTION: &str = "*figure*: the labelling's figure class; *template*: the template fitted; *parts found*: the labelled body parts; *core mean* (mesh units) and *core %* (% of height): mean error over the core joints (pelvis, neck, head, shoulders, elbows, wrists, hips, knees, ankles) that the reference maps and the prediction has (upright figures paired by canonical keys; `–` otherwise); *core paired*: of those the reference maps; *missing core joints*: mapped by the reference but absent from the prediction, so not in the mean; *missing parts*: limbs or tail the template expects but the fit could not build; *warnings*: the rig's warnings, the first ones quoted (all are under Notes).";

/// The run as a Markdown page: `title`, the caller's `preamble` (e.g. the command that made
/// it), a summary (with the core joint error over upright models and real characters), the
/// accuracy table, the anatomical rig per model ([`super::anatomy_table`], when the method
/// found body parts), the per-joint table pooled over models (when any model
/// has per-joint errors), the per-joint and model table in mesh units, the timing table and the notes.
pub fn bench_markdown(results: &[BenchResult], title: &str, preamble: &str) -> String {
    let evaluations: Vec<Evaluation> = results
        .iter()
        .filter_map(|r| r.evaluation.clone())
        .collect();
    let dataset = aggregate(&evaluations);
    let counts = bench_counts(results);
    let mut md = format!("# {title}\n\n");
    if !preamble.is_empty() {
        md.push_str(preamble.trim_end());
        md.push_str("\n\n");
    }
    md.push_str("## Summary\n\n");
    md.push_str(&format!(
        "* models: {} ({} with per-joint errors, {} chamfer only, {} failed)\n",
        counts.models, counts.per_joint, counts.chamfer_only, counts.failed
    ));
    if dataset.pooled_percent.count > 0 {
        let p = &dataset.pooled_percent;
        md.push_str(&format!(
            "* per-joint error over {} joints: mean {:.2} %, median {:.2} %, max {:.2} %, RMS {:.2} % of figure size\n",
            p.count, p.mean, p.median, p.max, p.rms
        ));
    } else {
        md.push_str(
            "* per-joint errors: unavailable (no model shares joint keys with its reference)\n",
        );
    }
    if !evaluations.is_empty() {
        let c = &dataset.chamfer_percent;
        md.push_str(&format!(
            "* mean over {} evaluated models: CD-J2J {:.2} %, CD-J2B {:.2} %, CD-B2B {:.2} % of figure size\n",
            evaluations.len(),
            c.j2j,
            c.j2b,
            c.b2b
        ));
    }
    for line in super::core_summary_lines(results) {
        md.push_str(&format!("* {line}\n"));
    }
    let total: f64 = results.iter().map(BenchResult::total_ms).sum();
    md.push_str(&format!(
        "* time summed over models: {:.2} s (stage timings below are wall-clock per model, models run in parallel)\n\n",
        total / 1e3
    ));
    md.push_str("Errors are percentages of figure size (height for upright figures, longest bounding-box side otherwise, measured on the mesh). J2J/J2B/B2B are the symmetric joint-to-joint, joint-to-bone and bone-to-bone chamfer distances (RigNet), topology-free.\n\n");
    md.push_str("## Accuracy\n\n");
    md.push_str(&bench_table(results).markdown());
    if results
        .iter()
        .any(|r| r.anatomy.is_some() || r.core.is_some())
    {
        md.push_str("\n## Anatomical rig per model\n\n");
        md.push_str(ANATOMY_CAPTION);
        md.push_str("\n\n");
        md.push_str(&super::anatomy_table(results).markdown());
    }
    if !dataset.keys.is_empty() {
        md.push_str("\n## Per joint, pooled over models\n\n");
        md.push_str(&super::key_table(&dataset.keys).markdown());
    }
    let per_model = joint_model_table(results);
    if !per_model.rows.is_empty() {
        md.push_str("\n## Per joint and model (mesh units)\n\n");
        md.push_str(&per_model.markdown());
    }
    md.push_str("\n## Timings (ms)\n\n");
    md.push_str(&timing_table(results).markdown());
    let notes: Vec<String> = results
        .iter()
        .flat_map(|r| r.notes.iter().map(move |n| format!("* {}: {n}", r.model)))
        .collect();
    if !notes.is_empty() {
        md.push_str("\n## Notes\n\n");
        md.push_str(&notes.join("\n"));
        md.push('\n');
    }
    md
}

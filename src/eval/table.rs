//! Tables of evaluation results: flat rows for CSV/JSON (per joint, per model, per canonical key
//! over a dataset) and a small text table rendered as Markdown or aligned plain text.

use super::{ErrorSummary, EvalError, Evaluation};
use crate::skeleton::canonical::key_rank;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::io::Write;

/// One row per paired joint (CSV/JSON). Lengths in mesh units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointRow {
    /// Reference model name.
    pub model: String,
    /// Canonical key (or shared joint name).
    pub key: String,
    /// Predicted joint name.
    pub predicted_joint: String,
    /// Reference joint name.
    pub reference_joint: String,
    /// Distance between them, mesh units.
    pub error: f64,
    /// Distance as a percentage of figure size.
    pub error_percent: f64,
    /// Offset predicted − reference along x.
    pub dx: f64,
    /// Offset along y.
    pub dy: f64,
    /// Offset along z.
    pub dz: f64,
}

/// One row per evaluated model (CSV/JSON).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelRow {
    /// Reference model name.
    pub model: String,
    /// Reference rig name (empty when unknown).
    pub rig: String,
    /// Number of paired joints.
    pub joints: usize,
    /// Figure size, mesh units.
    pub figure_size: f64,
    /// How joints were paired (`chamfer_only`: no per-joint errors, the error columns are
    /// empty).
    pub pairing: super::MatchMethod,
    /// Mean error, mesh units (`None` without per-joint errors).
    pub mean: Option<f64>,
    /// Median error, mesh units.
    pub median: Option<f64>,
    /// Largest error, mesh units.
    pub max: Option<f64>,
    /// RMS error, mesh units.
    pub rms: Option<f64>,
    /// Mean error, % of figure size.
    pub mean_percent: Option<f64>,
    /// Median error, % of figure size.
    pub median_percent: Option<f64>,
    /// Largest error, % of figure size.
    pub max_percent: Option<f64>,
    /// RMS error, % of figure size.
    pub rms_percent: Option<f64>,
    /// Key of the joint with the largest error (empty without per-joint errors).
    pub worst_joint: String,
    /// CD-J2J, % of figure size.
    pub cd_j2j_percent: f64,
    /// CD-J2B, % of figure size.
    pub cd_j2b_percent: f64,
    /// CD-B2B, % of figure size.
    pub cd_b2b_percent: f64,
}

/// Errors of one canonical key pooled over a dataset (CSV/JSON), % of figure size.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct KeyRow {
    /// Canonical key.
    pub key: String,
    /// Number of models with this key paired.
    pub count: usize,
    /// Mean error, %.
    pub mean_percent: f64,
    /// Median error, %.
    pub median_percent: f64,
    /// Largest error, %.
    pub max_percent: f64,
    /// RMS error, %.
    pub rms_percent: f64,
}

/// Aggregate over a dataset of evaluations. Percentages make models of any scale comparable.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DatasetSummary {
    /// Number of models.
    pub models: usize,
    /// All joint errors of all models pooled, % of figure size.
    pub pooled_percent: ErrorSummary,
    /// Summary of the per-model mean errors, % of figure size (models with per-joint errors).
    pub model_means_percent: ErrorSummary,
    /// Mean over models of CD-J2J, CD-J2B, CD-B2B, % of figure size.
    pub chamfer_percent: super::ChamferDistances,
    /// Per canonical key, in canonical order.
    pub keys: Vec<KeyRow>,
    /// Per model.
    pub per_model: Vec<ModelRow>,
}

/// The per-joint rows of `evaluation`.
pub fn joint_rows(evaluation: &Evaluation) -> Vec<JointRow> {
    evaluation
        .joints
        .iter()
        .map(|j| JointRow {
            model: evaluation.model.clone(),
            key: j.key.clone(),
            predicted_joint: j.predicted_joint.clone(),
            reference_joint: j.reference_joint.clone(),
            error: j.error,
            error_percent: j.error_percent,
            dx: j.offset.x,
            dy: j.offset.y,
            dz: j.offset.z,
        })
        .collect()
}

/// The summary row of `evaluation`.
pub fn model_row(evaluation: &Evaluation) -> ModelRow {
    let s = &evaluation.summary;
    let p = &evaluation.summary_percent;
    let some = |v: f64| evaluation.has_joint_errors().then_some(v);
    ModelRow {
        model: evaluation.model.clone(),
        rig: evaluation.rig.clone().unwrap_or_default(),
        joints: s.count,
        figure_size: evaluation.figure.size,
        pairing: evaluation.method,
        mean: some(s.mean),
        median: some(s.median),
        max: some(s.max),
        rms: some(s.rms),
        mean_percent: some(p.mean),
        median_percent: some(p.median),
        max_percent: some(p.max),
        rms_percent: some(p.rms),
        worst_joint: evaluation.worst_joint.clone(),
        cd_j2j_percent: evaluation.chamfer_percent.j2j,
        cd_j2b_percent: evaluation.chamfer_percent.j2b,
        cd_b2b_percent: evaluation.chamfer_percent.b2b,
    }
}

/// Aggregates `evaluations` (one per model) into a [`DatasetSummary`].
pub fn aggregate(evaluations: &[Evaluation]) -> DatasetSummary {
    let pooled: Vec<f64> = evaluations
        .iter()
        .flat_map(|e| e.joints.iter().map(|j| j.error_percent))
        .collect();
    let means: Vec<f64> = evaluations
        .iter()
        .filter(|e| e.has_joint_errors())
        .map(|e| e.summary_percent.mean)
        .collect();
    let mut by_key: BTreeMap<(usize, String), Vec<f64>> = BTreeMap::new();
    for evaluation in evaluations {
        for joint in &evaluation.joints {
            let rank = key_rank(&joint.key);
            by_key
                .entry((rank, joint.key.clone()))
                .or_default()
                .push(joint.error_percent);
        }
    }
    let keys = by_key
        .into_iter()
        .map(|((_, key), values)| {
            let s = ErrorSummary::from_values(&values);
            KeyRow {
                key,
                count: s.count,
                mean_percent: s.mean,
                median_percent: s.median,
                max_percent: s.max,
                rms_percent: s.rms,
            }
        })
        .collect();
    let n = evaluations.len().max(1) as f64;
    let chamfer_sum = evaluations
        .iter()
        .fold(super::ChamferDistances::default(), |acc, e| {
            super::ChamferDistances {
                j2j: acc.j2j + e.chamfer_percent.j2j,
                j2b: acc.j2b + e.chamfer_percent.j2b,
                b2b: acc.b2b + e.chamfer_percent.b2b,
            }
        });
    DatasetSummary {
        models: evaluations.len(),
        pooled_percent: ErrorSummary::from_values(&pooled),
        model_means_percent: ErrorSummary::from_values(&means),
        chamfer_percent: chamfer_sum.normalised(n),
        keys,
        per_model: evaluations.iter().map(model_row).collect(),
    }
}

/// Writes `rows` as CSV with a header line (field names) to `writer`.
///
/// # Errors
/// [`EvalError::Table`] when writing fails.
pub fn write_csv<T: Serialize, W: Write>(rows: &[T], writer: W) -> Result<(), EvalError> {
    let table_error = |e: &dyn std::fmt::Display| EvalError::Table {
        what: "csv",
        message: e.to_string(),
    };
    let mut csv = csv::Writer::from_writer(writer);
    for row in rows {
        csv.serialize(row).map_err(|e| table_error(&e))?;
    }
    csv.flush().map_err(|e| table_error(&e))
}

/// `value` as pretty-printed JSON.
///
/// # Errors
/// [`EvalError::Table`] when serialisation fails (non-string map keys; not expected for the
/// types of this module).
pub fn to_json<T: Serialize>(value: &T) -> Result<String, EvalError> {
    serde_json::to_string_pretty(value).map_err(|e| EvalError::Table {
        what: "json",
        message: e.to_string(),
    })
}

/// A rendered-to-strings table: headers and rows of cells.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    /// Column headers.
    pub headers: Vec<String>,
    /// Rows; each has `headers.len()` cells.
    pub rows: Vec<Vec<String>>,
    /// Whether each column is numeric (right-aligned).
    pub numeric: Vec<bool>,
}

impl Table {
    /// GitHub-flavoured Markdown (numeric columns right-aligned, `|` in cells escaped).
    pub fn markdown(&self) -> String {
        let escape = |s: &str| s.replace('|', "\\|");
        let mut out = String::new();
        out.push_str(&format!(
            "| {} |\n",
            self.headers
                .iter()
                .map(|h| escape(h))
                .collect::<Vec<_>>()
                .join(" | ")
        ));
        let rules: Vec<&str> = (0..self.headers.len())
            .map(|i| {
                if self.numeric.get(i).copied().unwrap_or(false) {
                    "---:"
                } else {
                    "---"
                }
            })
            .collect();
        out.push_str(&format!("| {} |\n", rules.join(" | ")));
        for row in &self.rows {
            out.push_str(&format!(
                "| {} |\n",
                row.iter()
                    .map(|c| escape(c))
                    .collect::<Vec<_>>()
                    .join(" | ")
            ));
        }
        out
    }

    /// Plain text with padded columns, for terminals.
    pub fn plain(&self) -> String {
        let widths: Vec<usize> = (0..self.headers.len())
            .map(|i| {
                self.rows
                    .iter()
                    .filter_map(|r| r.get(i))
                    .chain(std::iter::once(&self.headers[i]))
                    .map(|c| c.chars().count())
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let line = |cells: &[String]| {
            let padded: Vec<String> = cells
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    let w = widths.get(i).copied().unwrap_or(0);
                    if self.numeric.get(i).copied().unwrap_or(false) {
                        format!("{c:>w$}")
                    } else {
                        format!("{c:<w$}")
                    }
                })
                .collect();
            padded.join("  ").trim_end().to_owned() + "\n"
        };
        let mut out = line(&self.headers);
        for row in &self.rows {
            out.push_str(&line(row));
        }
        out
    }
}

/// The per-joint table: key, joint names, error in mesh units and %, offset.
pub fn joint_table(rows: &[JointRow]) -> Table {
    Table {
        headers: [
            "joint",
            "predicted",
            "reference",
            "error",
            "error %",
            "dx",
            "dy",
            "dz",
        ]
        .map(String::from)
        .to_vec(),
        numeric: vec![false, false, false, true, true, true, true, true],
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    r.key.clone(),
                    r.predicted_joint.clone(),
                    r.reference_joint.clone(),
                    format!("{:.4}", r.error),
                    format!("{:.2}", r.error_percent),
                    format!("{:+.4}", r.dx),
                    format!("{:+.4}", r.dy),
                    format!("{:+.4}", r.dz),
                ]
            })
            .collect(),
    }
}

/// `value` with two decimals, or `–` when absent (no per-joint errors).
pub fn percent_cell(value: Option<f64>) -> String {
    value.map_or_else(|| "–".to_owned(), |v| format!("{v:.2}"))
}

/// The per-model table (errors in % of figure size, plus chamfer distances; `–` where
/// per-joint errors are unavailable).
pub fn model_table(rows: &[ModelRow]) -> Table {
    Table {
        headers: [
            "model", "rig", "joints", "mean %", "median %", "max %", "rms %", "worst", "J2J %",
            "J2B %", "B2B %",
        ]
        .map(String::from)
        .to_vec(),
        numeric: vec![
            false, false, true, true, true, true, true, false, true, true, true,
        ],
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    r.model.clone(),
                    r.rig.clone(),
                    r.joints.to_string(),
                    percent_cell(r.mean_percent),
                    percent_cell(r.median_percent),
                    percent_cell(r.max_percent),
                    percent_cell(r.rms_percent),
                    r.worst_joint.clone(),
                    format!("{:.2}", r.cd_j2j_percent),
                    format!("{:.2}", r.cd_j2b_percent),
                    format!("{:.2}", r.cd_b2b_percent),
                ]
            })
            .collect(),
    }
}

/// The per-key dataset table (% of figure size).
pub fn key_table(rows: &[KeyRow]) -> Table {
    Table {
        headers: ["joint", "models", "mean %", "median %", "max %", "rms %"]
            .map(String::from)
            .to_vec(),
        numeric: vec![false, true, true, true, true, true],
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    r.key.clone(),
                    r.count.to_string(),
                    format!("{:.2}", r.mean_percent),
                    format!("{:.2}", r.median_percent),
                    format!("{:.2}", r.max_percent),
                    format!("{:.2}", r.rms_percent),
                ]
            })
            .collect(),
    }
}

//! Bench tables of the anatomical rig per model: figure class, template, parts found, the core
//! joint error ([`super::core_error`]) with the core joints the prediction lacks, the missing
//! parts and the warnings; and the core error summarised over humanoids and real characters.

use super::{BenchResult, ErrorSummary, Table};
use serde::{Deserialize, Serialize};

/// How many warnings [`anatomy_table`] quotes per model.
pub const TOP_WARNINGS: usize = 2;

/// Characters of a quoted warning before it is cut with `…`.
pub const WARNING_CHARS: usize = 110;

/// The core joint error summarised over a set of models (those with a core error).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct CoreSummary {
    /// Models with a core error.
    pub models: usize,
    /// Their core mean errors, % of height: mean, median, max over the models.
    pub percent: ErrorSummary,
    /// Models lacking at least one core joint their reference maps.
    pub with_missing: usize,
}

/// [`CoreSummary`] over the `results` that `keep` selects and that have a core error; `None`
/// when none has.
pub fn core_summary(
    results: &[BenchResult],
    keep: &dyn Fn(&BenchResult) -> bool,
) -> Option<CoreSummary> {
    let cores: Vec<_> = results
        .iter()
        .filter(|r| keep(r))
        .filter_map(|r| r.core.as_ref())
        .collect();
    if cores.is_empty() {
        return None;
    }
    let percents: Vec<f64> = cores.iter().map(|c| c.mean_percent).collect();
    Some(CoreSummary {
        models: cores.len(),
        percent: ErrorSummary::from_values(&percents),
        with_missing: cores.iter().filter(|c| !c.missing.is_empty()).count(),
    })
}

/// Summary lines (Markdown list items without the bullet) for the core error over the upright
/// models and over the real characters among them, when any has a core error.
pub fn core_summary_lines(results: &[BenchResult]) -> Vec<String> {
    let line = |what: &str, s: CoreSummary| {
        format!(
            "core joints (pelvis, neck, head, shoulders, elbows, wrists, hips, knees, ankles) over {} {what}: median {:.2} %, mean {:.2} %, max {:.2} % of height; {} lacking a core joint the reference maps",
            s.models,
            s.percent.median,
            s.percent.mean,
            s.percent.max,
            s.with_missing
        )
    };
    let mut lines = Vec::new();
    if let Some(s) = core_summary(results, &|_| true) {
        lines.push(line("upright models", s));
    }
    if let Some(s) = core_summary(results, &|r| r.real) {
        lines.push(line("real characters", s));
    }
    lines
}

/// `text` cut to [`WARNING_CHARS`] characters with `…`.
fn cut(text: &str) -> String {
    if text.chars().count() <= WARNING_CHARS {
        text.to_owned()
    } else {
        let mut s: String = text.chars().take(WARNING_CHARS - 1).collect();
        s.push('…');
        s
    }
}

/// One row per model: model, category, whether it is a real character, figure class,
/// template, parts found, core mean error (mesh units and % of height), core joints paired of
/// those the reference maps, the core joints missing from the prediction, the parts the
/// template expects but the fit lacks, the number of warnings and the first
/// [`TOP_WARNINGS`]. `–` where a value does not apply (a method without body parts, a figure
/// that is not upright, a failed model).
pub fn anatomy_table(results: &[BenchResult]) -> Table {
    let headers = [
        "model",
        "category",
        "real",
        "figure",
        "template",
        "parts found",
        "core mean",
        "core %",
        "core paired",
        "missing core joints",
        "missing parts",
        "warnings",
        "top warnings",
    ];
    let numeric = [
        false, false, false, false, false, false, true, true, true, false, false, true, false,
    ];
    let dash = || "–".to_owned();
    let rows = results
        .iter()
        .map(|r| {
            let a = r.anatomy.as_ref();
            let c = r.core.as_ref();
            let list = |v: &[String]| {
                if v.is_empty() {
                    "none".to_owned()
                } else {
                    v.join(", ")
                }
            };
            let mut top: Vec<String> = r
                .warnings
                .iter()
                .take(TOP_WARNINGS)
                .map(|w| cut(&w.message))
                .collect();
            if let Some(f) = &r.failure {
                top.insert(0, format!("failed: {}", cut(f)));
            }
            vec![
                r.model.clone(),
                r.category.clone(),
                if r.real { "yes" } else { "" }.to_owned(),
                a.map_or_else(dash, |a| a.figure.clone()),
                a.map_or_else(dash, |a| a.template.clone()),
                a.map_or_else(dash, |a| a.parts.clone()),
                c.map_or_else(dash, |c| format!("{:.4}", c.mean)),
                c.map_or_else(dash, |c| format!("{:.2}", c.mean_percent)),
                c.map_or_else(dash, |c| format!("{}/{}", c.paired, c.mapped.len())),
                c.map_or_else(dash, |c| list(&c.missing)),
                a.map_or_else(dash, |a| list(&a.missing_parts)),
                r.warnings.len().to_string(),
                top.join(" · "),
            ]
        })
        .collect();
    Table {
        headers: headers.map(String::from).to_vec(),
        rows,
        numeric: numeric.to_vec(),
    }
}

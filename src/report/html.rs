//! Self-contained HTML evaluation report: summary, three SVG projections, a bar chart and the
//! per-joint table. No scripts, fonts or other network resources; viewable offline.

use super::{error_bar_chart, escape, projection_svg, ChartOptions, ReportError, SvgOptions, View};
use crate::eval::{Evaluation, ReferenceRig};
use crate::mesh::Mesh;
use std::fmt::Write;
use std::path::Path;

/// What a report shows.
#[derive(Debug, Clone, Copy)]
pub struct ReportInput<'a> {
    /// The comparison.
    pub evaluation: &'a Evaluation,
    /// The predicted skeleton as drawn (usually [`ReferenceRig::deforming`]).
    pub predicted: &'a ReferenceRig,
    /// The reference skeleton as drawn (usually [`ReferenceRig::deforming`]).
    pub reference: &'a ReferenceRig,
    /// The mesh drawn behind the skeletons, if any.
    pub mesh: Option<&'a Mesh>,
}

/// Options of [`html_report`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReportOptions {
    /// Page title; default `skelfit evaluation: <predicted> vs <reference>`.
    pub title: Option<String>,
    /// Projection drawing options.
    pub svg: SvgOptions,
    /// Bar chart options.
    pub chart: ChartOptions,
    /// Further summary rows `(name, value)` after the evaluation's (e.g. the rig's template,
    /// parts and core joint error).
    pub extra_rows: Vec<(String, String)>,
    /// Notes listed at the end of the page (e.g. the rig's warnings).
    pub notes: Vec<String>,
}

pub(crate) const STYLE: &str = "body{font-family:sans-serif;margin:1.5em;color:#222}\
h1{font-size:1.3em}h2{font-size:1.1em;margin-top:1.5em}\
.views{display:flex;flex-wrap:wrap;gap:1em;align-items:flex-start}\
figure{margin:0}figcaption{text-align:center;font-size:.9em;color:#555}\
table{border-collapse:collapse;font-size:.9em}td,th{border:1px solid #ccc;padding:2px 6px}\
td.n{text-align:right;font-variant-numeric:tabular-nums}th{background:#f3f3f3}\
.warn{background:#fff3cd;border:1px solid #e0c060;padding:.5em}\
.swatch{display:inline-block;width:1em;height:.6em;margin:0 .3em 0 1em}";

/// The report page as a string (UTF-8 HTML5, everything inline).
pub fn html_report(input: &ReportInput, options: &ReportOptions) -> String {
    let e = input.evaluation;
    let title = options
        .title
        .clone()
        .unwrap_or_else(|| format!("skelfit evaluation: {} vs {}", e.predicted_model, e.model));
    let mut html = String::new();
    let _ = write!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><style>{STYLE}</style></head><body><h1>{t}</h1>",
        t = escape(&title)
    );
    let _ = write!(
        html,
        "<p class=\"verdict\"><strong>Verdict:</strong> {}</p>",
        escape(&super::eval_verdict(e))
    );
    for warning in &e.warnings {
        let _ = write!(
            html,
            "<p class=\"warn\">warning: {}</p>",
            escape(&warning.message)
        );
    }
    html.push_str(&summary_table(e, &options.extra_rows));
    let s = &options.svg;
    let _ = write!(
        html,
        "<h2>Projections</h2><p><span class=\"swatch\" style=\"background:{}\"></span>reference<span class=\"swatch\" style=\"background:{}\"></span>predicted<span class=\"swatch\" style=\"background:{}\"></span>error (reference → predicted)</p><div class=\"views\">",
        s.reference_colour, s.predicted_colour, s.error_colour
    );
    for view in View::ALL {
        let _ = write!(
            html,
            "<figure>{}<figcaption>{}</figcaption></figure>",
            projection_svg(view, input.mesh, input.predicted, input.reference, e, s),
            view.name()
        );
    }
    html.push_str("</div>");
    if e.has_joint_errors() {
        html.push_str("<h2>Error per joint</h2>");
        html.push_str(&error_bar_chart(e, &options.chart));
        html.push_str(&joint_table(e));
    }
    html.push_str(&notes_list(&options.notes));
    html.push_str("</body></html>\n");
    html
}

/// A page for a model that could not be evaluated: `title`, the reason, the extra summary rows
/// and the notes of `options` (no projections: there is no evaluation to draw).
pub fn failure_report(title: &str, failure: &str, options: &ReportOptions) -> String {
    let mut html = String::new();
    let _ = write!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><style>{STYLE}</style></head><body><h1>{t}</h1><p class=\"warn\">failed: {}</p>",
        escape(failure),
        t = escape(title)
    );
    if !options.extra_rows.is_empty() {
        html.push_str("<h2>Summary</h2>");
        html.push_str(&rows_table(&options.extra_rows));
    }
    html.push_str(&notes_list(&options.notes));
    html.push_str("</body></html>\n");
    html
}

fn notes_list(notes: &[String]) -> String {
    if notes.is_empty() {
        return String::new();
    }
    let items: String = notes
        .iter()
        .map(|n| format!("<li>{}</li>", escape(n)))
        .collect();
    format!("<h2>Notes</h2><ul>{items}</ul>")
}

fn rows_table(rows: &[(String, String)]) -> String {
    let mut html = String::from("<table>");
    for (k, v) in rows {
        let _ = write!(
            html,
            "<tr><th>{}</th><td>{}</td></tr>",
            escape(k),
            escape(v)
        );
    }
    html.push_str("</table>");
    html
}

/// Writes [`html_report`] to `path`.
///
/// # Errors
/// [`ReportError::Io`] when the file cannot be written.
pub fn write_html_report(
    path: &Path,
    input: &ReportInput,
    options: &ReportOptions,
) -> Result<(), ReportError> {
    std::fs::write(path, html_report(input, options)).map_err(|cause| ReportError::Io {
        path: path.to_owned(),
        cause,
    })
}

fn summary_table(e: &Evaluation, extra: &[(String, String)]) -> String {
    let mut rows: Vec<(String, String)> = vec![
        (
            "reference".into(),
            match &e.rig {
                Some(rig) => format!("{} (rig {rig})", e.model),
                None => e.model.clone(),
            },
        ),
        ("predicted".into(), e.predicted_model.clone()),
        (
            "joints paired".into(),
            format!(
                "{} (by {:?}; naming {:?} / {:?})",
                e.joints.len(),
                e.method,
                e.predicted_naming,
                e.reference_naming
            )
            .to_lowercase(),
        ),
        (
            "figure size".into(),
            format!(
                "{:.4} {} ({:?} of the {:?})",
                e.figure.size,
                e.units.as_deref().unwrap_or("units"),
                e.figure.measure,
                e.figure.source
            )
            .replace('_', " "),
        ),
    ];
    let per_joint = if e.has_joint_errors() {
        vec![
            ("mean error", e.summary.mean, e.summary_percent.mean),
            ("median error", e.summary.median, e.summary_percent.median),
            ("max error", e.summary.max, e.summary_percent.max),
            ("RMS error", e.summary.rms, e.summary_percent.rms),
        ]
    } else {
        rows.push((
            "per-joint errors".into(),
            "unavailable: the skeletons share no joint keys; chamfer distances only".into(),
        ));
        Vec::new()
    };
    for (name, u, p) in per_joint.into_iter().chain([
        ("CD-J2J", e.chamfer.j2j, e.chamfer_percent.j2j),
        ("CD-J2B", e.chamfer.j2b, e.chamfer_percent.j2b),
        ("CD-B2B", e.chamfer.b2b, e.chamfer_percent.b2b),
    ]) {
        rows.push((name.into(), format!("{u:.4} ({p:.2} %)")));
    }
    if e.has_joint_errors() {
        rows.push(("worst joint".into(), e.worst_joint.clone()));
    }
    if !e.unmatched.is_empty() {
        rows.push((
            "reference keys not predicted".into(),
            e.unmatched.join(", "),
        ));
    }
    rows.extend(extra.iter().cloned());
    format!("<h2>Summary</h2>{}", rows_table(&rows))
}

fn joint_table(e: &Evaluation) -> String {
    let mut html = String::from(
        "<h2>Per joint</h2><table><tr><th>joint</th><th>predicted</th><th>reference</th><th>error</th><th>% of size</th><th>dx</th><th>dy</th><th>dz</th></tr>",
    );
    for j in &e.joints {
        let _ = write!(
            html,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"n\">{:.4}</td><td class=\"n\">{:.2}</td><td class=\"n\">{:+.4}</td><td class=\"n\">{:+.4}</td><td class=\"n\">{:+.4}</td></tr>",
            escape(&j.key),
            escape(&j.predicted_joint),
            escape(&j.reference_joint),
            j.error,
            j.error_percent,
            j.offset.x,
            j.offset.y,
            j.offset.z
        );
    }
    html.push_str("</table>");
    html
}

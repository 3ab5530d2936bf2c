//! Self-contained HTML pages for benchmark runs and robustness studies: summaries, tables,
//! bar and line charts, and (for studies) projections of the base rig against the reference.

use super::{
    bar_chart, escape, html::STYLE, line_chart, projection_svg, ChartOptions, LineChartOptions,
    ReportInput, Series, SvgOptions, View,
};
use crate::eval::{
    aggregate, anatomy_table, bench_counts, bench_table, core_summary_lines, key_table,
    study_table, timing_table, BenchResult, Evaluation, Study, StudyKind, Table, ANATOMY_CAPTION,
};
use std::fmt::Write;

/// `table` as an HTML `<table>` (numeric columns right-aligned). Cells of column `link_column`
/// become links to `link(row)` where it returns one.
pub fn table_html(
    table: &Table,
    link_column: Option<usize>,
    link: &dyn Fn(usize) -> Option<String>,
) -> String {
    let mut html = String::from("<table><tr>");
    for h in &table.headers {
        let _ = write!(html, "<th>{}</th>", escape(h));
    }
    html.push_str("</tr>");
    for (r, row) in table.rows.iter().enumerate() {
        html.push_str("<tr>");
        for (c, cell) in row.iter().enumerate() {
            let class = if table.numeric.get(c).copied().unwrap_or(false) {
                " class=\"n\""
            } else {
                ""
            };
            let text = escape(cell);
            match (link_column == Some(c)).then(|| link(r)).flatten() {
                Some(href) => {
                    let _ = write!(
                        html,
                        "<td{class}><a href=\"{}\">{text}</a></td>",
                        escape(&href)
                    );
                }
                None => {
                    let _ = write!(html, "<td{class}>{text}</td>");
                }
            }
        }
        html.push_str("</tr>");
    }
    html.push_str("</table>");
    html
}

/// `text` escaped, with Markdown code spans (`...`) as `<code>` and emphasis (`*...*`) as
/// `<em>`.
fn markdown_inline(text: &str) -> String {
    let parts: Vec<String> = text.split('`').map(escape).collect();
    let mut out = String::new();
    for (i, part) in parts.iter().enumerate() {
        match (i % 2, i + 1 < parts.len()) {
            (1, true) => {
                let _ = write!(out, "<code>{part}</code>");
            }
            _ => {
                let pieces: Vec<&str> = part.split('*').collect();
                for (k, piece) in pieces.iter().enumerate() {
                    match (k % 2, k + 1 < pieces.len()) {
                        (1, true) => {
                            let _ = write!(out, "<em>{piece}</em>");
                        }
                        (1, false) => {
                            out.push('*');
                            out.push_str(piece);
                        }
                        _ => out.push_str(piece),
                    }
                }
            }
        }
    }
    out
}

fn page_start(title: &str, preamble: &str) -> String {
    let mut html = format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><style>{STYLE}</style></head><body><h1>{t}</h1>",
        t = escape(title)
    );
    if !preamble.is_empty() {
        let _ = write!(html, "<p>{}</p>", markdown_inline(preamble));
    }
    html
}

/// The headline number of an evaluation: mean per-joint error (% of figure size) when joints
/// paired, else CD-J2J (%).
fn headline(e: &Evaluation) -> f64 {
    if e.has_joint_errors() {
        e.summary_percent.mean
    } else {
        e.chamfer_percent.j2j
    }
}

/// A benchmark run as one page: summary, a bar chart per model (mean per-joint error, or CD-J2J
/// where per-joint errors are unavailable), the accuracy table, the per-joint table pooled over
/// models, the timing table and the notes. `model_page(i)` gives a link for model `i` (e.g.
/// `models/<name>.html`) or `None`.
pub fn bench_html(
    results: &[BenchResult],
    title: &str,
    preamble: &str,
    model_page: &dyn Fn(usize) -> Option<String>,
) -> String {
    let mut html = page_start(title, preamble);
    let _ = write!(
        html,
        "<p class=\"verdict\"><strong>Verdict:</strong> {}</p>",
        escape(&bench_verdict(results))
    );
    let counts = bench_counts(results);
    let evaluations: Vec<Evaluation> = results
        .iter()
        .filter_map(|r| r.evaluation.clone())
        .collect();
    let dataset = aggregate(&evaluations);
    let _ = write!(
        html,
        "<h2>Summary</h2><ul><li>models: {} ({} with per-joint errors, {} chamfer only, {} failed)</li>",
        counts.models, counts.per_joint, counts.chamfer_only, counts.failed
    );
    if dataset.pooled_percent.count > 0 {
        let p = &dataset.pooled_percent;
        let _ = write!(
            html,
            "<li>per-joint error over {} joints: mean {:.2} %, median {:.2} %, max {:.2} %, RMS {:.2} % of figure size</li>",
            p.count, p.mean, p.median, p.max, p.rms
        );
    } else {
        html.push_str("<li>per-joint errors: unavailable (no model shares joint keys with its reference)</li>");
    }
    if !evaluations.is_empty() {
        let c = &dataset.chamfer_percent;
        let _ = write!(
            html,
            "<li>mean over {} evaluated models: CD-J2J {:.2} %, CD-J2B {:.2} %, CD-B2B {:.2} % of figure size</li>",
            evaluations.len(),
            c.j2j,
            c.j2b,
            c.b2b
        );
    }
    for line in core_summary_lines(results) {
        let _ = write!(html, "<li>{}</li>", escape(&line));
    }
    html.push_str("</ul>");
    let bars: Vec<(String, f64)> = results
        .iter()
        .filter_map(|r| Some((r.model.clone(), headline(r.evaluation.as_ref()?))))
        .collect();
    if !bars.is_empty() {
        let caption = if evaluations.iter().all(Evaluation::has_joint_errors) {
            "mean per-joint error, % of figure size"
        } else {
            "mean per-joint error (or CD-J2J where joints do not pair), % of figure size"
        };
        let options = ChartOptions {
            label_width: 230.0,
            ..Default::default()
        };
        html.push_str("<h2>Accuracy per model</h2>");
        html.push_str(&bar_chart(&bars, caption, &options));
    }
    html.push_str("<h2>Accuracy</h2>");
    html.push_str(&table_html(&bench_table(results), Some(0), model_page));
    if results
        .iter()
        .any(|r| r.anatomy.is_some() || r.core.is_some())
    {
        html.push_str("<h2>Anatomical rig per model</h2>");
        let _ = write!(html, "<p>{}</p>", markdown_inline(ANATOMY_CAPTION));
        html.push_str(&table_html(&anatomy_table(results), Some(0), model_page));
    }
    if !dataset.keys.is_empty() {
        html.push_str("<h2>Per joint, pooled over models</h2>");
        html.push_str(&table_html(&key_table(&dataset.keys), None, &|_| None));
    }
    html.push_str("<h2>Timings (ms)</h2>");
    html.push_str(&table_html(&timing_table(results), None, &|_| None));
    let notes: Vec<String> = results
        .iter()
        .flat_map(|r| {
            r.notes
                .iter()
                .map(move |n| format!("<li>{}: {}</li>", escape(&r.model), escape(n)))
        })
        .collect();
    if !notes.is_empty() {
        let _ = write!(html, "<h2>Notes</h2><ul>{}</ul>", notes.concat());
    }
    html.push_str("</body></html>\n");
    html
}

/// The series of a study's displacement plot: CD-J2J to the base rig, the mean joint
/// displacement from it (when variants other than the base pair with it), and the error to
/// the reference (when there is one), per level of the variants that did not fail.
fn study_series(study: &Study) -> Vec<Series> {
    let ok = || study.variants.iter().filter(|v| v.failure.is_none());
    let mut series = vec![Series {
        name: "CD-J2J to the base rig".into(),
        colour: "#d62728".into(),
        points: ok()
            .filter_map(|v| Some((v.level, v.chamfer_to_base_percent?.j2j)))
            .collect(),
    }];
    let paired: Vec<(f64, f64)> = ok()
        .filter_map(|v| Some((v.level, v.displacement_percent?.mean)))
        .collect();
    // A per-joint series only when variants other than the base pair with it.
    if paired.len() > 1 {
        series.push(Series {
            name: "mean joint displacement from the base rig".into(),
            colour: "#ff7f0e".into(),
            points: paired,
        });
    }
    let reference: Vec<(f64, f64)> = ok()
        .filter_map(|v| Some((v.level, headline(v.to_reference.as_ref()?))))
        .collect();
    if !reference.is_empty() {
        series.push(Series {
            name: "error to the reference (mean per joint, or CD-J2J)".into(),
            colour: "#1f77b4".into(),
            points: reference,
        });
    }
    series
}

/// A study as one page: the displacement-per-level plot, the table, and, when `base` is given,
/// the three projections of the base rig against the reference.
pub fn study_html(
    study: &Study,
    title: &str,
    preamble: &str,
    base: Option<&ReportInput>,
) -> String {
    let mut html = page_start(title, preamble);
    let _ = write!(
        html,
        "<p class=\"verdict\"><strong>Verdict:</strong> {}</p>",
        escape(&study_verdict(study))
    );
    let _ = write!(
        html,
        "<p>Model <b>{}</b>{}; figure size {:.4}. All values are % of figure size.</p>",
        escape(&study.model),
        study
            .reference
            .as_ref()
            .map(|r| format!(", reference {}", escape(r)))
            .unwrap_or_default(),
        study.figure.size
    );
    let series = study_series(study);
    let options = LineChartOptions {
        log_x: study.kind == StudyKind::Tessellation,
        x_label: match study.kind {
            StudyKind::Tessellation => "triangle ratio (log scale)".into(),
            StudyKind::Rotation => "rotation, degrees".into(),
        },
        y_label: "% of figure size".into(),
        ..Default::default()
    };
    html.push_str("<h2>Displacement per level</h2>");
    html.push_str(&line_chart(&series, &options));
    html.push_str("<h2>Variants</h2>");
    html.push_str(&table_html(&study_table(study), None, &|_| None));
    if let Some(input) = base {
        let s = SvgOptions::default();
        let _ = write!(
            html,
            "<h2>Base rig against the reference</h2><p><span class=\"swatch\" style=\"background:{}\"></span>reference<span class=\"swatch\" style=\"background:{}\"></span>predicted<span class=\"swatch\" style=\"background:{}\"></span>error</p><div class=\"views\">",
            s.reference_colour, s.predicted_colour, s.error_colour
        );
        for view in View::ALL {
            let _ = write!(
                html,
                "<figure>{}<figcaption>{}</figcaption></figure>",
                projection_svg(
                    view,
                    input.mesh,
                    input.predicted,
                    input.reference,
                    input.evaluation,
                    &s
                ),
                view.name()
            );
        }
        html.push_str("</div>");
    }
    let notes: Vec<String> = study
        .variants
        .iter()
        .flat_map(|v| {
            v.warnings
                .iter()
                .map(|w| &w.message)
                .chain(&v.failure)
                .map(move |w| format!("<li>{}: {}</li>", escape(&v.label), escape(w)))
        })
        .collect();
    if !notes.is_empty() {
        let _ = write!(html, "<h2>Notes</h2><ul>{}</ul>", notes.concat());
    }
    html.push_str("</body></html>\n");
    html
}

/// The one-line verdict an evaluation page opens with: the mean per-joint error in % of the
/// figure's size (height for upright figures), good within 1 %, the worst joint, and the
/// reference joints the prediction lacks; CD-J2J (good within 2 %) where joints were not
/// paired.
pub fn eval_verdict(e: &Evaluation) -> String {
    let of = match e.figure.measure {
        crate::eval::FigureMeasure::Height => "height",
        _ => "figure size",
    };
    let mut line = if e.has_joint_errors() {
        let mean = e.summary_percent.mean;
        let worst = e
            .joints
            .iter()
            .max_by(|a, b| a.error_percent.total_cmp(&b.error_percent));
        format!(
            "{}: mean joint error {mean:.2} % of {of} over {} paired joints{}",
            if mean <= 1.0 { "good" } else { "not good" },
            e.joints.len(),
            worst.map_or(String::new(), |w| format!(
                "; worst: {} {:.1} %",
                w.key, w.error_percent
            ))
        )
    } else {
        let cd = e.chamfer_percent.j2j;
        format!(
            "{}: CD-J2J {cd:.2} % of {of} (no joints paired by name)",
            if cd <= 2.0 { "good" } else { "not good" }
        )
    };
    if !e.unmatched.is_empty() {
        let _ = write!(
            line,
            "; {} reference joints missing ({})",
            e.unmatched.len(),
            e.unmatched.join(", ")
        );
    }
    line
}

/// The one-line verdict a study page opens with: how far the variants' rigs move from the base
/// rig (mean per-joint displacement, % of figure size; stable within 1 %), the variant that
/// moves most, and the variants that failed.
pub fn study_verdict(study: &Study) -> String {
    let moved: Vec<(&str, f64)> = study
        .variants
        .iter()
        .filter(|v| !v.base && v.failure.is_none())
        .filter_map(|v| {
            let d = v
                .displacement_percent
                .as_ref()
                .map(|d| d.mean)
                .or_else(|| v.chamfer_to_base_percent.as_ref().map(|c| c.j2j))?;
            Some((v.label.as_str(), d))
        })
        .collect();
    let failed = study
        .variants
        .iter()
        .filter(|v| v.failure.is_some())
        .count();
    let mut line = match moved.iter().copied().max_by(|a, b| a.1.total_cmp(&b.1)) {
        None => "no variant was compared with the base rig".to_string(),
        Some((worst, w)) => {
            let stable = moved.iter().filter(|(_, d)| *d <= 1.0).count();
            format!(
                "joints within 1 % of figure size of the base rig on {stable} of {} variants; \
                 largest move: {worst} {w:.2} %",
                moved.len()
            )
        }
    };
    if failed > 0 {
        let _ = write!(line, "; {failed} variants failed to rig");
    }
    line
}

/// The one-line verdict a bench page opens with: what is good, what is not, against which
/// reference. Core joints (upright figures, % of height) when any model has them, else the
/// mean per-joint error, else CD-J2J (% of figure size); "good" is within 1 % (2 % for
/// CD-J2J); the worst model is named, and failed models are counted.
pub fn bench_verdict(results: &[BenchResult]) -> String {
    let mut references: Vec<&str> = results.iter().map(|r| r.reference.as_str()).collect();
    references.sort_unstable();
    references.dedup();
    let against = format!(
        "against each model's reference rig ({})",
        references.join(", ")
    );
    let core: Vec<(&str, f64)> = results
        .iter()
        .filter_map(|r| {
            Some((
                r.model.as_str(),
                r.core.as_ref().filter(|c| c.paired > 0)?.mean_percent,
            ))
        })
        .collect();
    let joints: Vec<(&str, f64)> = results
        .iter()
        .filter_map(|r| {
            let e = r.evaluation.as_ref().filter(|e| e.has_joint_errors())?;
            Some((r.model.as_str(), e.summary_percent.mean))
        })
        .collect();
    let chamfer: Vec<(&str, f64)> = results
        .iter()
        .filter_map(|r| Some((r.model.as_str(), r.evaluation.as_ref()?.chamfer_percent.j2j)))
        .collect();
    let (what, of, values, bound) = if !core.is_empty() {
        (
            "core joints (mean) within 1 % of height",
            "upright figures",
            core,
            1.0,
        )
    } else if !joints.is_empty() {
        (
            "mean joint error within 1 % of figure size",
            "models",
            joints,
            1.0,
        )
    } else {
        ("CD-J2J within 2 % of figure size", "models", chamfer, 2.0)
    };
    let mut line = if values.is_empty() {
        "no model was evaluated".to_string()
    } else {
        let good = values.iter().filter(|(_, v)| *v <= bound).count();
        let (worst, w) = values
            .iter()
            .copied()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .expect("not empty");
        format!(
            "{what} on {good} of {} {of} {against}; worst: {worst} {w:.1} %",
            values.len()
        )
    };
    let failed: Vec<&str> = results
        .iter()
        .filter(|r| r.failure.is_some())
        .map(|r| r.model.as_str())
        .collect();
    if !failed.is_empty() {
        line.push_str(&format!("; {} failed: {}", failed.len(), failed.join(", ")));
    }
    line
}

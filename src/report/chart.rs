//! SVG bar chart of the error per joint.

use super::escape;
use crate::eval::Evaluation;
use std::fmt::Write;

/// Layout of [`error_bar_chart`], pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct ChartOptions {
    /// Total width. Default 640.
    pub width: f64,
    /// Height of one bar row. Default 16.
    pub row_height: f64,
    /// Width reserved for joint labels on the left. Default 110.
    pub label_width: f64,
    /// Width reserved for value labels on the right. Default 70.
    pub value_width: f64,
    /// Bar colour. Default dark orange.
    pub colour: String,
}

impl Default for ChartOptions {
    fn default() -> Self {
        Self {
            width: 640.0,
            row_height: 16.0,
            label_width: 110.0,
            value_width: 70.0,
            colour: "#ff7f0e".into(),
        }
    }
}

/// A horizontal bar per paired joint (in `evaluation` order) with length proportional to its
/// error as a percentage of figure size, a dashed line at the mean, and the value at the end
/// of each bar. A standalone `<svg>` element.
pub fn error_bar_chart(evaluation: &Evaluation, options: &ChartOptions) -> String {
    let rows = evaluation.joints.len();
    let top = 18.0;
    let height = top + rows as f64 * options.row_height + 6.0;
    let plot = (options.width - options.label_width - options.value_width).max(10.0);
    let max = evaluation
        .joints
        .iter()
        .map(|j| j.error_percent)
        .fold(0.0, f64::max);
    let scale = if max > 0.0 { plot / max } else { 0.0 };
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" class="chart" width="{w:.0}" height="{height:.0}" viewBox="0 0 {w:.1} {height:.1}" role="img" aria-label="error per joint" font-family="sans-serif" font-size="11">"#,
        w = options.width
    );
    let _ = write!(
        svg,
        r#"<text x="{:.1}" y="12">error, % of figure size</text>"#,
        options.label_width
    );
    for (i, joint) in evaluation.joints.iter().enumerate() {
        let y = top + i as f64 * options.row_height;
        let bar = joint.error_percent * scale;
        let mid = y + options.row_height * 0.5 + 4.0;
        let _ = write!(
            svg,
            r#"<text x="{:.1}" y="{mid:.1}" text-anchor="end">{}</text><rect x="{:.1}" y="{:.1}" width="{bar:.1}" height="{:.1}" fill="{}"><title>{}: {:.4} ({:.2} %)</title></rect><text x="{:.1}" y="{mid:.1}">{:.2}</text>"#,
            options.label_width - 4.0,
            escape(&joint.key),
            options.label_width,
            y + 2.0,
            options.row_height - 4.0,
            options.colour,
            escape(&joint.key),
            joint.error,
            joint.error_percent,
            options.label_width + bar + 4.0,
            joint.error_percent
        );
    }
    if rows > 0 {
        let x = options.label_width + evaluation.summary_percent.mean * scale;
        let _ = write!(
            svg,
            r##"<line x1="{x:.1}" y1="{top:.1}" x2="{x:.1}" y2="{:.1}" stroke="#333" stroke-dasharray="4 3"><title>mean {:.2} %</title></line>"##,
            height - 6.0,
            evaluation.summary_percent.mean
        );
    }
    svg.push_str("</svg>");
    svg
}

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

/// A horizontal bar per `(label, value)` row with the value printed at the end of each bar;
/// `caption` is printed above. A standalone `<svg>` element (same layout options as
/// [`error_bar_chart`]).
pub fn bar_chart(rows: &[(String, f64)], caption: &str, options: &ChartOptions) -> String {
    let top = 18.0;
    let height = top + rows.len() as f64 * options.row_height + 6.0;
    let plot = (options.width - options.label_width - options.value_width).max(10.0);
    let max = rows
        .iter()
        .map(|(_, v)| *v)
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    let scale = if max > 0.0 { plot / max } else { 0.0 };
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" class="chart" width="{w:.0}" height="{height:.0}" viewBox="0 0 {w:.1} {height:.1}" role="img" aria-label="{c}" font-family="sans-serif" font-size="11"><text x="{:.1}" y="12">{c}</text>"#,
        options.label_width,
        w = options.width,
        c = escape(caption)
    );
    for (i, (label, value)) in rows.iter().enumerate() {
        let y = top + i as f64 * options.row_height;
        let bar = if value.is_finite() {
            value.max(0.0) * scale
        } else {
            0.0
        };
        let mid = y + options.row_height * 0.5 + 4.0;
        let _ = write!(
            svg,
            r#"<text x="{:.1}" y="{mid:.1}" text-anchor="end">{l}</text><rect x="{:.1}" y="{:.1}" width="{bar:.1}" height="{:.1}" fill="{}"><title>{l}: {value:.3}</title></rect><text x="{:.1}" y="{mid:.1}">{value:.2}</text>"#,
            options.label_width - 4.0,
            options.label_width,
            y + 2.0,
            options.row_height - 4.0,
            options.colour,
            options.label_width + bar + 4.0,
            l = escape(label),
        );
    }
    svg.push_str("</svg>");
    svg
}

/// One line of a [`line_chart`].
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// Stroke colour (CSS).
    pub colour: String,
    /// `(x, y)` points, drawn in the given order; non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
}

/// Layout of [`line_chart`], pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct LineChartOptions {
    /// Total width. Default 560.
    pub width: f64,
    /// Total height. Default 300.
    pub height: f64,
    /// Logarithmic x axis (for triangle ratios such as 0.1 … 2). Default false.
    pub log_x: bool,
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
}

impl Default for LineChartOptions {
    fn default() -> Self {
        Self {
            width: 560.0,
            height: 300.0,
            log_x: false,
            x_label: String::new(),
            y_label: String::new(),
        }
    }
}

/// An SVG line plot of `series` (points joined in order of x) with ticks at the x values of
/// the points, a y axis from 0 to the largest value with 5 ticks, and a legend below. A
/// standalone `<svg>` element.
pub fn line_chart(series: &[Series], options: &LineChartOptions) -> String {
    let (left, right, top) = (56.0, 16.0, 14.0);
    let (w, h) = (options.width, options.height + 16.0 * series.len() as f64);
    let fx = |x: f64| if options.log_x { x.ln() } else { x };
    let points = || {
        series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .filter(|(x, y)| x.is_finite() && y.is_finite() && (!options.log_x || *x > 0.0))
    };
    let (x0, x1) = points().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (x, _)| {
        (lo.min(fx(x)), hi.max(fx(x)))
    });
    let y1 = points().fold(0.0, |m: f64, (_, y)| m.max(y));
    let y1 = if y1 > 0.0 { y1 * 1.05 } else { 1.0 };
    let (x0, x1) = if x0.is_finite() && x1 > x0 {
        (x0, x1)
    } else if x0.is_finite() {
        (x0 - 1.0, x0 + 1.0)
    } else {
        (0.0, 1.0)
    };
    let plot_w = (w - left - right).max(10.0);
    let plot_h = (options.height - top - 44.0).max(10.0);
    let sx = |x: f64| left + (fx(x) - x0) / (x1 - x0) * plot_w;
    let sy = |y: f64| top + plot_h - y / y1 * plot_h;
    let mut svg = String::new();
    let _ = write!(
        svg,
        r##"<svg xmlns="http://www.w3.org/2000/svg" class="chart" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.1} {h:.1}" role="img" aria-label="{yl}" font-family="sans-serif" font-size="11"><rect x="{left:.1}" y="{top:.1}" width="{plot_w:.1}" height="{plot_h:.1}" fill="none" stroke="#999"/>"##,
        yl = escape(&options.y_label)
    );
    for i in 0..=5 {
        let y = y1 * i as f64 / 5.0;
        let _ = write!(
            svg,
            r##"<line x1="{l:.1}" y1="{p:.1}" x2="{r:.1}" y2="{p:.1}" stroke="#eee"/><text x="{t:.1}" y="{q:.1}" text-anchor="end">{y:.2}</text>"##,
            l = left,
            r = left + plot_w,
            p = sy(y),
            t = left - 4.0,
            q = sy(y) + 4.0
        );
    }
    let mut ticks: Vec<f64> = points().map(|(x, _)| x).collect();
    ticks.sort_by(f64::total_cmp);
    ticks.dedup();
    for x in ticks {
        let _ = write!(
            svg,
            r##"<line x1="{p:.1}" y1="{b:.1}" x2="{p:.1}" y2="{c:.1}" stroke="#999"/><text x="{p:.1}" y="{t:.1}" text-anchor="middle">{x}</text>"##,
            p = sx(x),
            b = top + plot_h,
            c = top + plot_h + 4.0,
            t = top + plot_h + 16.0
        );
    }
    let _ = write!(
        svg,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text><text x="12" y="{:.1}" transform="rotate(-90 12 {:.1})" text-anchor="middle">{}</text>"#,
        left + plot_w / 2.0,
        top + plot_h + 32.0,
        escape(&options.x_label),
        top + plot_h / 2.0,
        top + plot_h / 2.0,
        escape(&options.y_label)
    );
    for (i, s) in series.iter().enumerate() {
        let legend_y = top + plot_h + 52.0 + 16.0 * i as f64;
        series_svg(&mut svg, s, options.log_x, (&sx, &sy), left, legend_y);
    }
    svg.push_str("</svg>");
    svg
}

/// Draws one series of [`line_chart`] into `svg`: its polyline, a dot per point and its legend
/// entry at height `legend_y`. `scale` maps data x and y to picture coordinates.
fn series_svg(
    svg: &mut String,
    s: &Series,
    log_x: bool,
    scale: (&dyn Fn(f64) -> f64, &dyn Fn(f64) -> f64),
    left: f64,
    legend_y: f64,
) {
    let (sx, sy) = scale;
    let mut drawn: Vec<(f64, f64)> = s
        .points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && (!log_x || *x > 0.0))
        .collect();
    drawn.sort_by(|a, b| a.0.total_cmp(&b.0));
    let path: Vec<String> = drawn
        .iter()
        .map(|&(x, y)| format!("{:.1},{:.1}", sx(x), sy(y)))
        .collect();
    let _ = write!(
        svg,
        r#"<polyline points="{}" fill="none" stroke="{c}" stroke-width="2"/>"#,
        path.join(" "),
        c = s.colour
    );
    for p in &path {
        let (x, y) = p.split_once(',').unwrap_or(("0", "0"));
        let _ = write!(
            svg,
            r#"<circle cx="{x}" cy="{y}" r="3" fill="{}"/>"#,
            s.colour
        );
    }
    let ly = legend_y;
    let _ = write!(
        svg,
        r#"<line x1="{l:.1}" y1="{a:.1}" x2="{m:.1}" y2="{a:.1}" stroke="{c}" stroke-width="2"/><text x="{t:.1}" y="{b:.1}">{}</text>"#,
        escape(&s.name),
        l = left,
        m = left + 20.0,
        a = ly - 4.0,
        t = left + 26.0,
        b = ly,
        c = s.colour
    );
}

//! Reports: pictures of the voxel stages (distance slices as PNG), orthographic SVG projections
//! of a mesh with predicted and reference joints, an SVG bar chart of the error per joint, and a
//! self-contained HTML page combining them with the per-joint table; pages for benchmark runs
//! and robustness studies (tables, bar and line charts). Tables for
//! CSV/JSON/Markdown live in [`crate::eval`] (`joint_rows`, `write_csv`, ...).
//!
//! The SVG and HTML output is plain string building: no network resources, no extra crates.

mod chart;
mod error;
mod html;
mod index;
mod pages;
mod slices;
mod svg;
#[cfg(test)]
mod tests;

pub use chart::{bar_chart, error_bar_chart, line_chart, ChartOptions, LineChartOptions, Series};
pub use error::ReportError;
pub use html::{failure_report, html_report, write_html_report, ReportInput, ReportOptions};
pub use index::{index_entries, index_html, IndexEntry};
pub use pages::{bench_html, bench_verdict, eval_verdict, study_html, study_verdict, table_html};
pub use slices::{distance_slice, png_bytes, RgbImage};
pub use svg::{projection_svg, SvgOptions, View};

/// `text` with the five XML/HTML special characters escaped.
pub(crate) fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

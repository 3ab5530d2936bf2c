//! `skelfit report RESULTS.json [-o OUT.html]`: rebuild the self-contained HTML page of a
//! `bench` run (`bench.json`) or a study (`tessellation.json`, `rotation.json`) from its JSON.
//! The JSON holds no skeletons, so study pages are written without the projections.
//! `skelfit report --index DIR [-o DIR/index.html]`: an index page linking every report
//! below DIR (HTML, Markdown, SVG) with the verdict line each accuracy page opens with.

use super::common::Outputs;
use anyhow::Context;
use clap::Args;
use skelfit::eval::{BenchResult, Study};
use skelfit::report::{bench_html, study_html};
use std::path::PathBuf;

/// Arguments of `skelfit report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// `bench.json` written by `skelfit bench`, or `<study>.json` written by `skelfit study`.
    #[arg(required_unless_present = "index", conflicts_with = "index")]
    pub results: Option<PathBuf>,
    /// Write an index page linking every report below DIR (default DIR/index.html) instead.
    #[arg(long, value_name = "DIR")]
    pub index: Option<PathBuf>,
    /// HTML file to write (default: the results file with the extension .html).
    #[arg(short, long, value_name = "OUT.html")]
    pub output: Option<PathBuf>,
    /// Page title.
    #[arg(long)]
    pub title: Option<String>,
}

/// Runs the command.
pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
    if let Some(dir) = &args.index {
        let (output, entries) = write_index(dir, args.output.as_deref(), args.title.as_deref())?;
        if super::common::json_mode() {
            super::common::print_json(&serde_json::json!({
                "index": output.display().to_string(),
                "reports": entries,
            }))?;
        }
        super::common::say!("wrote {} ({} reports)", output.display(), entries.len());
        return Ok(());
    }
    let results = args
        .results
        .as_ref()
        .expect("clap requires RESULTS without --index");
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| results.with_extension("html"));
    let mut outputs = Outputs::check([output.as_path()], [results.as_path()])?;
    let text = std::fs::read_to_string(results)
        .with_context(|| format!("reading {}", results.display()))?;
    let value: serde_json::Value = serde_json::from_str(&text)
        .with_context(|| format!("{} is not JSON", results.display()))?;
    let preamble = format!(
        "Rebuilt from {} by skelfit report (skelfit {}).",
        results.display(),
        env!("CARGO_PKG_VERSION")
    );
    let is_bench = value.is_array();
    let html = if is_bench {
        let results: Vec<BenchResult> = serde_json::from_value(value).with_context(|| {
            format!(
                "{} is not a bench.json written by skelfit bench",
                results.display()
            )
        })?;
        let title = args
            .title
            .clone()
            .unwrap_or_else(|| "skelfit bench".to_owned());
        bench_html(&results, &title, &preamble, &|_| None)
    } else {
        let study: Study = serde_json::from_value(value).with_context(|| {
            format!(
                "{} is neither a bench.json nor a study JSON written by skelfit",
                results.display()
            )
        })?;
        let title = args.title.clone().unwrap_or_else(|| {
            format!(
                "skelfit {} study: {}",
                serde_json::to_value(study.kind)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_owned))
                    .unwrap_or_default(),
                study.model
            )
        });
        study_html(&study, &title, &preamble, None)
    };
    let kind = if is_bench { "bench" } else { "study" };
    outputs.add(&output, html);
    outputs.write()?;
    if super::common::json_mode() {
        super::common::print_json(&serde_json::json!({
            "results": results.display().to_string(),
            "kind": kind,
            "written": [output.display().to_string()],
        }))?;
    }
    super::common::say!("wrote {}", output.display());
    Ok(())
}

/// Writes the index page of the reports below `dir` ([`skelfit::report::index_html`]) to
/// `output` (default `dir/index.html`); returns its path and what it links.
pub fn write_index(
    dir: &std::path::Path,
    output: Option<&std::path::Path>,
    title: Option<&str>,
) -> anyhow::Result<(PathBuf, Vec<skelfit::report::IndexEntry>)> {
    let output = output.map_or_else(|| dir.join("index.html"), std::path::Path::to_path_buf);
    let mut outputs = Outputs::check([output.as_path()], [])?;
    let entries = skelfit::report::index_entries(dir)
        .with_context(|| format!("reading the reports below {}", dir.display()))?;
    let title = title.map_or_else(
        || format!("skelfit reports: {}", dir.display()),
        str::to_owned,
    );
    outputs.add(&output, skelfit::report::index_html(&title, &entries));
    outputs.write()?;
    Ok((output, entries))
}

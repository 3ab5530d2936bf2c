//! `skelfit report RESULTS.json [-o OUT.html]`: rebuild the self-contained HTML page of a
//! `bench` run (`bench.json`) or a study (`tessellation.json`, `rotation.json`) from its JSON.
//! The JSON holds no skeletons, so study pages are written without the projections.

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
    pub results: PathBuf,
    /// HTML file to write (default: the results file with the extension .html).
    #[arg(short, long, value_name = "OUT.html")]
    pub output: Option<PathBuf>,
    /// Page title.
    #[arg(long)]
    pub title: Option<String>,
}

/// Runs the command.
pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| args.results.with_extension("html"));
    let mut outputs = Outputs::check([output.as_path()], [args.results.as_path()])?;
    let text = std::fs::read_to_string(&args.results)
        .with_context(|| format!("reading {}", args.results.display()))?;
    let value: serde_json::Value = serde_json::from_str(&text)
        .with_context(|| format!("{} is not JSON", args.results.display()))?;
    let preamble = format!(
        "Rebuilt from {} by skelfit report (skelfit {}).",
        args.results.display(),
        env!("CARGO_PKG_VERSION")
    );
    let is_bench = value.is_array();
    let html = if is_bench {
        let results: Vec<BenchResult> = serde_json::from_value(value).with_context(|| {
            format!(
                "{} is not a bench.json written by skelfit bench",
                args.results.display()
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
                args.results.display()
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
            "results": args.results.display().to_string(),
            "kind": kind,
            "written": [output.display().to_string()],
        }))?;
    }
    super::common::say!("wrote {}", output.display());
    Ok(())
}

//! `skelfit bench DIR [--rig game_engine] [--method general] [--select all|real] [--out reports/NAME] [--html]`:
//! rig every model of a refdata-style folder in parallel, evaluate each against its reference
//! rig, and write accuracy and timing tables (CSV, Markdown, JSON; HTML on request).

use super::common::{write_file, VoxelArgs};
use anyhow::Context;
use clap::{Args, ValueEnum};
use rayon::prelude::*;
use skelfit::eval::{
    bench_counts, bench_csv, bench_markdown, bench_model, bench_table, find_bench_models, to_json,
    BenchOptions, BenchResult, RigMethod,
};
use skelfit::export::{write_skeleton_json, JsonOptions};
use skelfit::report::{bench_html, failure_report, html_report, ReportInput, ReportOptions};
use std::path::{Path, PathBuf};

/// The rigging method (`--method`). Add a value here when a method is added to
/// [`RigMethod`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// The general control skeleton (dissertation ch.5); not anatomically named, so evaluated
    /// by chamfer distances only.
    General,
    /// The anatomical control skeleton from a template (dissertation ch.7-8, `skelfit rig`
    /// with its defaults); canonical joints are evaluated per joint.
    Anatomical,
}

impl From<MethodArg> for RigMethod {
    fn from(arg: MethodArg) -> Self {
        match arg {
            MethodArg::General => RigMethod::General,
            MethodArg::Anatomical => RigMethod::Anatomical,
        }
    }
}

/// Which models of the folder `skelfit bench` runs (`--select`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub enum SelectArg {
    /// Every model found.
    #[default]
    All,
    /// Only real game characters: models whose provenance.json names the `converter` that
    /// made them from the artist's skinned file (refdata README, "Real game characters").
    Real,
}

/// Arguments of `skelfit bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Folder of models: `<model>/mesh.obj` + `rig_<rig>.json`, or the refdata layout with
    /// category folders (`<category>/<model>/...`).
    pub dir: PathBuf,
    /// Reference rig to evaluate against (`rig_<RIG>.json`); models without it use their only
    /// rig file and say so.
    #[arg(long, default_value = "game_engine")]
    pub rig: String,
    /// Rigging method.
    #[arg(long, value_enum, default_value_t = MethodArg::General)]
    pub method: MethodArg,
    /// Which models to run.
    #[arg(long, value_enum, default_value_t = SelectArg::All)]
    pub select: SelectArg,
    /// Output folder for bench.csv, bench.md, bench.json (and index.html); created if missing.
    #[arg(long, default_value = "reports/bench")]
    pub out: PathBuf,
    /// Also write a self-contained HTML page (index.html).
    #[arg(long)]
    pub html: bool,
    /// With --html, also write one evaluation page per model (models/<model>.html: projections
    /// of the mesh with predicted and reference joints).
    #[arg(long, requires = "html")]
    pub model_pages: bool,
    /// Meshes drawn in model pages are decimated to about this many triangles (file size).
    #[arg(long, value_name = "N", default_value_t = 3000)]
    pub page_triangles: usize,
    /// Also write each predicted skeleton as skelfit JSON (skeletons/<model>.json), e.g. to
    /// re-check one model with `skelfit eval`.
    #[arg(long)]
    pub skeletons: bool,
    /// Page title.
    #[arg(long)]
    pub title: Option<String>,
    #[command(flatten)]
    pub voxel: VoxelArgs,
}

/// The command line as typed, for report preambles (program path replaced by `skelfit`).
pub fn command_line() -> String {
    let args: Vec<String> = std::env::args().skip(1).collect();
    format!("skelfit {}", args.join(" "))
}

/// Runs the command.
pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    let mut options = BenchOptions::default();
    options.rigger.method = args.method.into();
    options.rigger.general.voxel = args.voxel.options()?;
    let mut models = find_bench_models(&args.dir, &args.rig)?;
    if args.select == SelectArg::Real {
        models.retain(|m| m.real);
        anyhow::ensure!(
            !models.is_empty(),
            "no real game characters (provenance.json with a `converter`) in {}",
            args.dir.display()
        );
    }
    super::common::output_folder(&args.out)?;
    let bar = if super::common::quiet() {
        indicatif::ProgressBar::hidden()
    } else {
        indicatif::ProgressBar::new(models.len() as u64)
    };
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{bar:40} {pos}/{len} models  {elapsed_precise}  {msg}",
    ) {
        bar.set_style(style);
    }
    let results: Vec<BenchResult> = models
        .par_iter()
        .map(|model| {
            let result = bench_model(model, &options);
            bar.set_message(model.name.clone());
            bar.inc(1);
            result
        })
        .collect();
    bar.finish_and_clear();
    let title = args.title.clone().unwrap_or_else(|| {
        format!(
            "skelfit bench: {} rig vs rig_{} on {}",
            args.method
                .to_possible_value()
                .map_or("?".into(), |v| v.get_name().to_owned()),
            args.rig,
            args.dir.display()
        )
    });
    let preamble = format!(
        "Generated by `{}` (skelfit {}).",
        command_line(),
        env!("CARGO_PKG_VERSION")
    );
    write_file(&args.out.join("bench.csv"), bench_csv(&results)?.as_bytes())?;
    write_file(
        &args.out.join("bench.md"),
        bench_markdown(&results, &title, &preamble).as_bytes(),
    )?;
    write_file(
        &args.out.join("bench.json"),
        (to_json(&results)? + "\n").as_bytes(),
    )?;
    if args.skeletons {
        write_skeletons(&args.out.join("skeletons"), &results)?;
    }
    if args.html {
        let pages = if args.model_pages {
            write_model_pages(
                &args.out.join("models"),
                &models,
                &results,
                args.page_triangles,
            )?
        } else {
            vec![None; results.len()]
        };
        let html = bench_html(&results, &title, &preamble, &|i| {
            pages.get(i).cloned().flatten()
        });
        write_file(&args.out.join("index.html"), html.as_bytes())?;
    }
    if super::common::json_mode() {
        println!("{}", to_json(&results)?.trim_end());
    }
    super::common::say!("{}", bench_table(&results).plain().trim_end());
    let counts = bench_counts(&results);
    super::common::say!(
        "\n{} models: {} with per-joint errors, {} chamfer only, {} failed; tables in {}",
        counts.models,
        counts.per_joint,
        counts.chamfer_only,
        counts.failed,
        args.out.display()
    );
    Ok(())
}

fn write_skeletons(dir: &Path, results: &[BenchResult]) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    for result in results {
        if let Some(predicted) = &result.predicted {
            let options = JsonOptions {
                model: Some(result.model.clone()),
                ..Default::default()
            };
            write_skeleton_json(
                &dir.join(format!("{}.json", result.model)),
                &predicted.skeleton,
                &options,
            )?;
        }
    }
    Ok(())
}

/// Writes `models/<model>.html` for every model (the projections of predicted and reference
/// joints when it was evaluated, else the reason it failed); returns the relative links.
fn write_model_pages(
    dir: &Path,
    models: &[skelfit::eval::BenchModel],
    results: &[BenchResult],
    triangles: usize,
) -> anyhow::Result<Vec<Option<String>>> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let mut links = Vec::with_capacity(results.len());
    for (model, result) in models.iter().zip(results) {
        let name = format!("{}.html", result.model);
        let options = ReportOptions {
            extra_rows: page_rows(result),
            notes: result.notes.clone(),
            ..Default::default()
        };
        let (Some(evaluation), Some(predicted), Some(reference)) =
            (&result.evaluation, &result.predicted, &result.reference_rig)
        else {
            let title = format!("skelfit bench: {} ({})", result.model, result.method.name());
            let failure = result.failure.as_deref().unwrap_or("not evaluated");
            write_file(
                &dir.join(&name),
                failure_report(&title, failure, &options).as_bytes(),
            )?;
            links.push(Some(format!("models/{name}")));
            continue;
        };
        let mesh = super::common::load_mesh(&model.mesh)?;
        let mesh = if mesh.triangles.len() > triangles && triangles > 0 {
            mesh.decimated(triangles as f64 / mesh.triangles.len() as f64)
        } else {
            mesh
        };
        // The evaluation compared deforming joints (BenchOptions default): draw those.
        let (predicted, reference) = (predicted.deforming(), reference.deforming());
        let input = ReportInput {
            evaluation,
            predicted: &predicted,
            reference: &reference,
            mesh: Some(&mesh),
        };
        write_file(&dir.join(&name), html_report(&input, &options).as_bytes())?;
        links.push(Some(format!("models/{name}")));
    }
    Ok(links)
}

/// Summary rows of a model page beyond the evaluation's: category, real character, and what
/// the anatomical rig found (figure, template, parts, missing parts, core joint error).
fn page_rows(result: &BenchResult) -> Vec<(String, String)> {
    let mut rows = vec![
        ("category".to_owned(), result.category.clone()),
        (
            "real game character".to_owned(),
            if result.real { "yes" } else { "no" }.to_owned(),
        ),
    ];
    let list = |v: &[String]| {
        if v.is_empty() {
            "none".to_owned()
        } else {
            v.join(", ")
        }
    };
    if let Some(a) = &result.anatomy {
        rows.extend([
            ("figure class".to_owned(), a.figure.clone()),
            ("template".to_owned(), a.template.clone()),
            ("parts found".to_owned(), a.parts.clone()),
            ("missing parts".to_owned(), list(&a.missing_parts)),
        ]);
    }
    if let Some(c) = &result.core {
        rows.extend([
            (
                "core joint error".to_owned(),
                format!(
                    "mean {:.4} ({:.2} % of height), max {:.2} % ({}); {} of {} core joints paired",
                    c.mean,
                    c.mean_percent,
                    c.max_percent,
                    if c.worst.is_empty() { "–" } else { &c.worst },
                    c.paired,
                    c.mapped.len()
                ),
            ),
            ("missing core joints".to_owned(), list(&c.missing)),
        ]);
    }
    rows.push(("rig warnings".to_owned(), result.warnings.len().to_string()));
    rows
}

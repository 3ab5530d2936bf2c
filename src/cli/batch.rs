//! `skelfit batch DIR|LIST --out OUT [--shard K/N | --shards N] [--jobs J]` and
//! `skelfit batch --merge OUT`: rig many meshes, resumably, in shards.
//!
//! - Models ([`models`]): every mesh file below DIR (.obj, .glb, .gltf, .stl, .ply; in a folder
//!   holding `source.glb` only that file), or every path of a list file; sorted by relative
//!   path. Each gets `OUT/models/<name>/` with `rig.glb` (as `skelfit rig`), `rig.json` (the
//!   skeleton with its canonical map and run information), `check.json` (the deformation check
//!   of `skelfit check rig.glb --canonical rig.json`) and `result.json` (its log line).
//! - Resumable: a model whose `result.json` (for the same source) says `ok` and whose outputs
//!   exist, or says `failed`, is skipped; every file is written atomically, `result.json`
//!   last. `--retry-failed` tries the failed ones again.
//! - Shards ([`shard`]): shard K of N (0-based) takes positions K, K + N, ... of the sorted
//!   list; from `--shard`, or `JOB_COMPLETION_INDEX` / `SLURM_ARRAY_TASK_ID` with `--shards`.
//! - Log ([`log`]): `OUT/batch-KofN.jsonl`, a line per model and one per finished run;
//!   `--merge` ([`merge`]) joins the logs into `report.json` and `report.md`.
//! - A model that fails (an error or a panic) is a `failed` line; the run goes on. Exit code 0
//!   when no model of the shard failed (in this run or, skipped now, in an earlier one), 3 when
//!   some did (the run still handled every model), 1 when the batch itself could not run.

mod log;
mod merge;
mod models;
mod shard;

use super::check::{check_json, check_rig, SweepArg};
use super::common::{load_model, millis, output_frame, SomeFailed, VoxelArgs};
use super::rig::{rig_glb, rig_json, run_info, template_choice, PresetArg};
use anyhow::{bail, Context};
use clap::Args;
use glam::DVec3;
use log::{CheckSummary, Line, Log, ModelLine, RunLine, Status};
use models::Model;
use shard::Shard;
use skelfit::pipeline::{rig, RigOptions};
use std::io::IsTerminal;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

/// Arguments of `skelfit batch`.
#[derive(Debug, Args)]
pub struct BatchArgs {
    /// A folder of meshes (searched recursively; in a folder holding `source.glb`, as
    /// refdata's model folders do beside `mesh.obj`, only `source.glb` is taken, so that its
    /// materials and textures round-trip), or a list file with one mesh path a line (relative
    /// to the list's folder; `#` comments).
    #[arg(required_unless_present = "merge")]
    pub input: Option<PathBuf>,
    /// Output folder (created): `models/<name>/` per model and the logs `batch-KofN.jsonl`.
    #[arg(long, value_name = "OUT", required_unless_present = "merge")]
    pub out: Option<PathBuf>,
    /// Take shard K of N (0-based K: 0 to N-1): the models at positions K, K+N, K+2N, ... of
    /// the sorted list. Default: from JOB_COMPLETION_INDEX (Kubernetes) or SLURM_ARRAY_TASK_ID
    /// (Slurm, counted from SLURM_ARRAY_TASK_MIN), else the whole list.
    #[arg(long, value_name = "K/N", conflicts_with = "shards")]
    pub shard: Option<String>,
    /// Number of shards N, the index K taken from JOB_COMPLETION_INDEX or SLURM_ARRAY_TASK_ID
    /// (default for Slurm: SLURM_ARRAY_TASK_COUNT).
    #[arg(long, value_name = "N")]
    pub shards: Option<usize>,
    /// Models rigged at once (each rig is already parallel inside).
    #[arg(long, value_name = "J", default_value_t = 1)]
    pub jobs: usize,
    /// Join the logs of OUT's shards into OUT/report.json and OUT/report.md (no rigging).
    #[arg(long, value_name = "OUT", conflicts_with_all = ["input", "out", "shard", "shards"])]
    pub merge: Option<PathBuf>,
    /// Template for every model: auto (from each labelled figure), humanoid, quadruped,
    /// winged, or a template .toml file.
    #[arg(long, value_name = "NAME|FILE", default_value = "auto")]
    pub template: String,
    /// Naming preset of the output joints.
    #[arg(long, value_enum, default_value_t = PresetArg::Anatomical)]
    pub preset: PresetArg,
    /// Units of the meshes for the metre .glb files: mm, cm, m, in, or auto (per model, from
    /// its height, as `skelfit rig --units auto`).
    #[arg(long, value_name = "UNITS", default_value = "auto", value_parser = ["mm", "cm", "m", "in", "auto"])]
    pub units: String,
    /// Rig again the models that failed in an earlier run (by default a rerun skips them as
    /// it skips complete ones: their failure is recorded in their result.json).
    #[arg(long)]
    pub retry_failed: bool,
    #[command(flatten)]
    pub voxel: VoxelArgs,
}

/// What every model is rigged with.
struct Settings {
    options: RigOptions,
    units: String,
    shard: Shard,
    /// Core-seconds per wall-clock second of one model: threads / jobs.
    cores_per_model: f64,
    /// Rig the models that failed in an earlier run again.
    retry_failed: bool,
}

/// Runs the command.
pub fn run(args: &BatchArgs) -> anyhow::Result<()> {
    if let Some(out) = &args.merge {
        return run_merge(out);
    }
    let (Some(input), Some(out)) = (&args.input, &args.out) else {
        bail!("give a folder or list file and --out OUT (or --merge OUT)");
    };
    if args.jobs == 0 {
        bail!("--jobs must be at least 1");
    }
    let (shard, from) = Shard::resolve(args.shard.as_deref(), args.shards, &|name| {
        std::env::var(name).ok()
    })?;
    let mut options = RigOptions::default();
    options.voxel = args.voxel.options()?;
    options.template = template_choice(&args.template)?;
    options.fit.preset = args.preset.into();
    options.validate()?;
    super::common::output_folder(out)?;
    let all = models::find_models(input, Some(out))?;
    let mine: Vec<&Model> = all
        .iter()
        .enumerate()
        .filter(|&(i, _)| shard.takes(i))
        .map(|(_, m)| m)
        .collect();
    let threads = rayon::current_num_threads();
    let settings = Settings {
        options,
        units: args.units.clone(),
        shard,
        cores_per_model: threads as f64 / args.jobs as f64,
        retry_failed: args.retry_failed,
    };
    let log_path = out.join(shard.log_name());
    let log = Log::open(&log_path)?;
    eprintln!(
        "skelfit: batch: shard {} ({from}): {} of {} models, {} at once on {threads} threads; log {}",
        shard.label(),
        mine.len(),
        all.len(),
        args.jobs.min(mine.len().max(1)),
        log_path.display()
    );
    let start = Instant::now();
    let cpu_start = log::cpu_seconds();
    let lines = run_models(&mine, out, &settings, &log, args.jobs);
    let count = |s: Status| lines.iter().filter(|l| l.status == s).count();
    let run_line = RunLine {
        shard: shard.label(),
        total_models: all.len(),
        assigned: mine.len(),
        ok: count(Status::Ok),
        failed: count(Status::Failed),
        skipped: count(Status::Skipped),
        wall_seconds: start.elapsed().as_secs_f64(),
        cpu_seconds: log::cpu_seconds()
            .zip(cpu_start)
            .map(|(end, start)| end - start),
        threads,
        jobs: args.jobs,
        finished: log::now(),
    };
    log.append(&Line::Run(run_line.clone()))?;
    print_summary(&lines, &run_line);
    let failed = lines
        .iter()
        .filter(|l| l.outcome().status == Status::Failed)
        .count();
    if failed > 0 {
        return Err(SomeFailed(format!(
            "{failed} of {} models failed (their lines in {} say why; --retry-failed tries them again); the others are done",
            mine.len(),
            log_path.display()
        ))
        .into());
    }
    Ok(())
}

/// `--merge OUT`: writes report.json and report.md.
fn run_merge(out: &Path) -> anyhow::Result<()> {
    let merged = merge::merge(out)?;
    let json = out.join("report.json");
    let md = out.join("report.md");
    skelfit::output::write_all_atomic(&[
        (
            &json,
            serde_json::to_string_pretty(&merged.report)?.as_bytes(),
        ),
        (&md, merged.markdown.as_bytes()),
    ])?;
    print!("{}", merged.markdown);
    println!("\nwrote {} and {}", json.display(), md.display());
    if merged.failed > 0 {
        return Err(SomeFailed(format!(
            "{} of {} models failed (see {})",
            merged.failed,
            merged.models,
            md.display()
        ))
        .into());
    }
    Ok(())
}

/// Handles `models` on `jobs` threads (each rig uses the global thread pool inside), appending
/// each model's line to the log as it ends; returns the lines in the models' order.
fn run_models(
    models: &[&Model],
    out: &Path,
    settings: &Settings,
    log: &Log,
    jobs: usize,
) -> Vec<ModelLine> {
    let bar = indicatif::ProgressBar::new(models.len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:30} {pos}/{len} models [{elapsed_precise} < {eta}] {msg}",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let plain = !std::io::stderr().is_terminal();
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let lines: Mutex<Vec<Option<ModelLine>>> = Mutex::new(vec![None; models.len()]);
    std::thread::scope(|scope| {
        for _ in 0..jobs.min(models.len()) {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(model) = models.get(i) else { break };
                bar.set_message(model.name.clone());
                let line = handle(model, out, settings);
                if let Err(e) = log.append(&Line::Model(line.clone())) {
                    bar.suspend(|| eprintln!("skelfit: warning: cannot append to the log: {e:#}"));
                }
                let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                if plain {
                    eprintln!(
                        "skelfit: batch [{n}/{}] {} {} ({:.1} s)",
                        models.len(),
                        line.status.as_str(),
                        model.name,
                        line.seconds
                    );
                }
                bar.inc(1);
                lines.lock().unwrap_or_else(|p| p.into_inner())[i] = Some(line);
            });
        }
    });
    bar.finish_and_clear();
    lines
        .into_inner()
        .unwrap_or_else(|p| p.into_inner())
        .into_iter()
        .flatten()
        .collect()
}

/// One model: skipped when complete, else rigged (errors and panics caught) and its
/// `result.json` written.
fn handle(model: &Model, out: &Path, settings: &Settings) -> ModelLine {
    let dir = out.join("models").join(&model.name);
    let start = Instant::now();
    let mut line = ModelLine {
        model: model.name.clone(),
        source: model.relative.clone(),
        status: Status::Ok,
        shard: settings.shard.label(),
        seconds: 0.0,
        core_seconds: 0.0,
        finished: 0.0,
        template: None,
        joints: None,
        warnings: Vec::new(),
        notices: Vec::new(),
        check: None,
        check_error: None,
        error: None,
        previous: None,
    };
    if let Some(previous) = completed(&dir, model, settings.retry_failed) {
        line.status = Status::Skipped;
        line.previous = Some(Box::new(previous));
    } else {
        let result = catch_unwind(AssertUnwindSafe(|| {
            rig_model(model, &dir, settings, &mut line)
        }));
        let error = match result {
            Ok(Ok(())) => None,
            Ok(Err(e)) => Some(format!("{e:#}")),
            Err(panic) => Some(format!("panic: {}", panic_message(panic.as_ref()))),
        };
        if let Some(error) = error {
            line.status = Status::Failed;
            line.error = Some(error);
        }
    }
    line.seconds = start.elapsed().as_secs_f64();
    line.core_seconds = line.seconds * settings.cores_per_model;
    line.finished = log::now();
    if line.status != Status::Skipped && dir.is_dir() {
        // Written last: the mark of a complete model (a failed one is tried again).
        let written = serde_json::to_string_pretty(&line)
            .map_err(anyhow::Error::from)
            .and_then(|text| super::common::write_file(&dir.join("result.json"), text.as_bytes()));
        if let Err(e) = written {
            line.status = Status::Failed;
            line.error = Some(format!("{e:#}"));
        }
    }
    line
}

/// The earlier line of a model that needs no work: `result.json` is for the same source and
/// says `ok` with rig.glb, rig.json and check.json there, or `failed` (unless `retry_failed`).
fn completed(dir: &Path, model: &Model, retry_failed: bool) -> Option<ModelLine> {
    let text = std::fs::read_to_string(dir.join("result.json")).ok()?;
    let line: ModelLine = serde_json::from_str(&text).ok()?;
    if line.source != model.relative {
        return None;
    }
    let done = match line.status {
        Status::Ok => ["rig.glb", "rig.json", "check.json"]
            .iter()
            .all(|f| dir.join(f).is_file()),
        Status::Failed => !retry_failed,
        Status::Skipped => false,
    };
    done.then_some(line)
}

/// Rigs one model into `dir` (rig.glb and rig.json as one set, then check.json), filling in
/// `line`.
fn rig_model(
    model: &Model,
    dir: &Path,
    settings: &Settings,
    line: &mut ModelLine,
) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let clock = Instant::now();
    let (mesh, source) = load_model(&model.path)?;
    let load_ms = millis(clock);
    let rigged =
        rig(&mesh, &settings.options).context("fitting the anatomical control skeleton")?;
    let frame = output_frame(
        false,
        &settings.units,
        &mesh,
        rigged.labelling.frame.up,
        rigged.labelling.frame.forward,
    )?;
    let glb = rig_glb(&mesh, source.as_ref(), &rigged, &frame)?;
    let mut info = run_info(Path::new(&model.relative), &rigged, load_ms);
    info["output_frame"] = frame.json();
    let json = rig_json(&model.path, &rigged, Some(info))?;
    let (glb_path, json_path) = (dir.join("rig.glb"), dir.join("rig.json"));
    skelfit::output::write_all_atomic(&[(&glb_path, &glb), (&json_path, json.as_bytes())])?;
    line.template = Some(rigged.fit.template.clone());
    line.joints = Some(rigged.fit.skeleton.len());
    line.warnings = rigged.warnings.iter().map(|w| w.record()).collect();
    line.notices.extend(frame.warning);
    if let Some(source) = &source {
        line.notices
            .extend(source.warnings.iter().map(|w| w.to_string()));
    }
    // The check of the written file, as `skelfit check rig.glb --canonical rig.json` (the
    // .glb is in glTF's frame: +Y up, +Z forward).
    let check = check_rig(
        &glb_path,
        Some(&json_path),
        SweepArg::Auto,
        DVec3::Y,
        DVec3::Z,
    );
    let check_value = match check {
        Ok(checked) => {
            let c = &checked.check;
            line.check = Some(CheckSummary {
                sweep: serde_json::to_value(c.sweep)?
                    .as_str()
                    .unwrap_or_default()
                    .to_string(),
                poses: c.poses.len(),
                over_1_5: c.total_over_1_5(),
                over_2: c.total_over_2(),
                worst: c.worst(),
                unweighted: checked.unweighted,
            });
            check_json(Path::new("rig.glb"), &checked)
        }
        Err(e) => {
            let message = format!("{e:#}");
            line.check_error = Some(message.clone());
            serde_json::json!({
                "format": "skelfit-check-v1",
                "rig": "rig.glb",
                "check": null,
                "error": message,
            })
        }
    };
    super::common::write_file(
        &dir.join("check.json"),
        serde_json::to_string_pretty(&check_value)?.as_bytes(),
    )?;
    Ok(())
}

/// The message of a caught panic.
fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(no message)".into())
}

/// The table of this run's models and its totals, on stdout.
fn print_summary(lines: &[ModelLine], run: &RunLine) {
    let refs: Vec<&ModelLine> = lines.iter().collect();
    print!("{}", log::table(&refs));
    let rigged: Vec<&ModelLine> = lines
        .iter()
        .filter(|l| l.status != Status::Skipped)
        .collect();
    let core_seconds: f64 = rigged.iter().map(|l| l.core_seconds).sum();
    println!(
        "\nshard {}: {} models: {} ok, {} failed, {} skipped (complete before) in {:.1} s on {} threads, --jobs {}",
        run.shard, run.assigned, run.ok, run.failed, run.skipped, run.wall_seconds, run.threads, run.jobs
    );
    if core_seconds > 0.0 {
        println!(
            "throughput: {:.3} models per core-second ({} models, {:.1} core-seconds = wall-clock seconds x threads / jobs)",
            rigged.len() as f64 / core_seconds,
            rigged.len(),
            core_seconds
        );
    }
    if let Some(cpu) = run.cpu_seconds.filter(|&c| c > 0.0 && !rigged.is_empty()) {
        println!(
            "cpu: {:.1} CPU-seconds, {:.3} models per CPU-second",
            cpu,
            rigged.len() as f64 / cpu
        );
    }
}

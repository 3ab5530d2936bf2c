//! `skelfit batch --merge OUT`: the shards' logs joined into one report (`report.json`,
//! `report.md`). Per model the report takes its latest `ok` or `failed` line from any log (a
//! `skipped` line stands for the line that made the outputs); totals count models, statuses
//! and warnings; throughput is models per core-second of rigging (each model's wall-clock
//! seconds times the cores it had) and models per CPU-second (the runs' measured CPU time).

use super::log::{table, Line, ModelLine, RunLine, Status};
use serde_json::json;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What the merge found.
#[derive(Debug)]
pub struct Merged {
    /// The report (as written to report.json).
    pub report: serde_json::Value,
    /// The Markdown report.
    pub markdown: String,
    /// Models whose outcome is `failed`.
    pub failed: usize,
    /// Models in the report.
    pub models: usize,
}

/// The log files of `out`: `batch-KofN.jsonl`, sorted by name.
pub fn log_files(out: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(out)
        .map_err(|e| anyhow::anyhow!("cannot read {}: {e}", out.display()))?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| {
            p.file_name().and_then(|n| n.to_str()).is_some_and(|n| {
                n.starts_with("batch-") && n.ends_with(".jsonl") && n.contains("of")
            })
        })
        .collect();
    files.sort();
    Ok(files)
}

/// Reads every log of `out` and builds the report.
///
/// # Errors
/// `out` holds no log, or a log cannot be read.
pub fn merge(out: &Path) -> anyhow::Result<Merged> {
    let files = log_files(out)?;
    if files.is_empty() {
        anyhow::bail!(
            "{} holds no batch log (batch-KofN.jsonl): run `skelfit batch ... --out {}` first",
            out.display(),
            out.display()
        );
    }
    let mut models: Vec<ModelLine> = Vec::new();
    let mut runs: Vec<RunLine> = Vec::new();
    let mut unreadable = 0;
    for file in &files {
        let text = std::fs::read_to_string(file)
            .map_err(|e| anyhow::anyhow!("cannot read {}: {e}", file.display()))?;
        for text in text.lines().filter(|l| !l.trim().is_empty()) {
            match serde_json::from_str::<Line>(text) {
                Ok(Line::Model(line)) => models.push(line),
                Ok(Line::Run(line)) => runs.push(line),
                // A line cut by a killed process.
                Err(_) => unreadable += 1,
            }
        }
    }
    // Stable: equal times keep file and line order.
    models.sort_by(|a, b| a.finished.total_cmp(&b.finished));
    runs.sort_by(|a, b| a.finished.total_cmp(&b.finished));
    let mut latest: BTreeMap<String, ModelLine> = BTreeMap::new();
    for line in models {
        let replace = match latest.get(&line.model) {
            None => true,
            Some(_) if line.status != Status::Skipped => true,
            Some(kept) => kept.status == Status::Skipped,
        };
        if replace {
            latest.insert(line.model.clone(), line);
        }
    }
    let outcomes: Vec<&ModelLine> = latest.values().map(|l| l.outcome()).collect();
    let report = report_json(&outcomes, &runs, unreadable, &files);
    let failed = outcomes
        .iter()
        .filter(|l| l.status == Status::Failed)
        .count();
    let markdown = report_markdown(&report, &outcomes);
    Ok(Merged {
        report,
        markdown,
        failed,
        models: outcomes.len(),
    })
}

/// One model of the report.
fn model_json(line: &ModelLine) -> serde_json::Value {
    json!({
        "model": line.model,
        "source": line.source,
        "status": line.status,
        "seconds": line.seconds,
        "core_seconds": line.core_seconds,
        "template": line.template,
        "joints": line.joints,
        "warnings": line.warnings,
        "notices": line.notices,
        "check": line.check,
        "check_error": line.check_error,
        "error": line.error,
    })
}

/// report.json: `models` (per model), `totals` (counts, warnings; timings under `timing`),
/// `runs` (every run's end line), and what is missing.
fn report_json(
    outcomes: &[&ModelLine],
    runs: &[RunLine],
    unreadable: usize,
    files: &[PathBuf],
) -> serde_json::Value {
    let count = |s: Status| outcomes.iter().filter(|l| l.status == s).count();
    let mut by_severity: BTreeMap<String, usize> = BTreeMap::new();
    let mut by_code: BTreeMap<String, usize> = BTreeMap::new();
    for line in outcomes {
        for w in &line.warnings {
            *by_severity.entry(w.severity.as_str().into()).or_default() += 1;
            *by_code
                .entry(format!("{}/{}", w.stage, w.code))
                .or_default() += 1;
        }
    }
    let rigged: Vec<&&ModelLine> = outcomes
        .iter()
        .filter(|l| l.status != Status::Skipped)
        .collect();
    let rig_seconds: f64 = rigged.iter().map(|l| l.seconds).sum();
    let core_seconds: f64 = rigged.iter().map(|l| l.core_seconds).sum();
    let throughput = (core_seconds > 0.0).then(|| rigged.len() as f64 / core_seconds);
    let expected = runs.iter().map(|r| r.total_models).max();
    // CPU time from the runs that rigged something and measured it.
    let measured: Vec<&RunLine> = runs
        .iter()
        .filter(|r| r.ok + r.failed > 0 && r.cpu_seconds.is_some())
        .collect();
    let cpu_seconds: f64 = measured.iter().filter_map(|r| r.cpu_seconds).sum();
    let cpu_models: usize = measured.iter().map(|r| r.ok + r.failed).sum();
    let per_cpu_second = (cpu_seconds > 0.0).then(|| cpu_models as f64 / cpu_seconds);
    // The latest run of every shard.
    let mut shards: BTreeMap<String, &RunLine> = BTreeMap::new();
    for run in runs {
        shards.insert(run.shard.clone(), run);
    }
    let counts: Vec<usize> = shards
        .keys()
        .filter_map(|s| s.split_once('/')?.1.parse().ok())
        .collect();
    let missing_shards: Vec<String> = match counts.first() {
        Some(&n) if counts.iter().all(|&c| c == n) => (0..n)
            .map(|k| format!("{k}/{n}"))
            .filter(|s| !shards.contains_key(s))
            .collect(),
        _ => Vec::new(),
    };
    json!({
        "format": "skelfit-batch-report-v1",
        "logs": files.iter().map(|f| f.file_name().map(|n| n.to_string_lossy().into_owned())).collect::<Vec<_>>(),
        "models": outcomes.iter().map(|l| model_json(l)).collect::<Vec<_>>(),
        "totals": {
            "models": outcomes.len(),
            "expected": expected,
            "missing": expected.map(|e| e.saturating_sub(outcomes.len())),
            "ok": count(Status::Ok),
            "failed": count(Status::Failed),
            "unknown": count(Status::Skipped),
            "models_with_warnings": outcomes.iter().filter(|l| !l.warnings.is_empty()).count(),
            "warnings_by_severity": by_severity,
            "warnings_by_code": by_code,
            "checks_not_run": outcomes.iter().filter(|l| l.check_error.is_some()).count(),
            "timing": {
                "rig_seconds": rig_seconds,
                "core_seconds": core_seconds,
                "models_per_core_second": throughput,
                "cpu_seconds": cpu_seconds,
                "models_per_cpu_second": per_cpu_second,
            },
        },
        "missing_shards": missing_shards,
        "unreadable_lines": unreadable,
        "runs": shards.values().collect::<Vec<_>>(),
    })
}

/// report.md: totals, throughput, warnings by code, the per-model table.
fn report_markdown(report: &serde_json::Value, outcomes: &[&ModelLine]) -> String {
    let t = &report["totals"];
    let mut md = String::from("# skelfit batch report\n\n");
    md.push_str(&format!(
        "{} models: {} ok, {} failed{}{}.\n\n",
        t["models"],
        t["ok"],
        t["failed"],
        match t["missing"].as_u64() {
            Some(m) if m > 0 => format!(", {m} missing (not in any log)"),
            _ => String::new(),
        },
        match t["unknown"].as_u64() {
            Some(u) if u > 0 => format!(", {u} complete from runs whose lines are gone"),
            _ => String::new(),
        }
    ));
    if let Some(missing) = report["missing_shards"]
        .as_array()
        .filter(|m| !m.is_empty())
    {
        md.push_str(&format!(
            "Shards without a finished run: {}.\n\n",
            missing
                .iter()
                .filter_map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let timing = &t["timing"];
    md.push_str(&format!(
        "Rigging took {:.1} s wall-clock summed over the models, {:.1} core-seconds: **{} models per core-second**.\n\n",
        timing["rig_seconds"].as_f64().unwrap_or(0.0),
        timing["core_seconds"].as_f64().unwrap_or(0.0),
        timing["models_per_core_second"]
            .as_f64()
            .map_or("-".into(), |v| format!("{v:.3}"))
    ));
    if let Some(per_cpu) = timing["models_per_cpu_second"].as_f64() {
        md.push_str(&format!(
            "The runs used {:.1} CPU-seconds: {per_cpu:.3} models per CPU-second (core-seconds count \
             the cores a run had, CPU-seconds what it used).\n\n",
            timing["cpu_seconds"].as_f64().unwrap_or(0.0)
        ));
    }
    if let Some(codes) = t["warnings_by_code"].as_object().filter(|c| !c.is_empty()) {
        md.push_str("| warning (stage/code) | count |\n|---|---:|\n");
        for (code, n) in codes {
            md.push_str(&format!("| {code} | {n} |\n"));
        }
        md.push('\n');
    }
    md.push_str(&table(outcomes));
    md
}

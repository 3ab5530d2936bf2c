//! The batch log: one JSON object a line (`OUT/batch-KofN.jsonl`, appended by every run of
//! shard K of N). A `model` line per model handled (`ok`, `failed` or `skipped`), and a `run`
//! line when a run ends. `OUT/models/<name>/result.json` holds the model's last `ok` or
//! `failed` line; it is written last, so a model is complete when it says `ok` and its outputs
//! exist.

use serde::{Deserialize, Serialize};
use skelfit::warning::{Severity, WarningRecord};
use std::io::Write;
use std::path::Path;
use std::sync::Mutex;

/// What happened to a model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Rigged and checked; its outputs are written.
    Ok,
    /// An error or a panic stopped it; `error` says which. Skipped by the next run unless
    /// `--retry-failed`.
    Failed,
    /// Complete (or failed) in an earlier run; nothing was done (`previous` holds that run's
    /// line).
    Skipped,
}

impl Status {
    /// Its name in the log.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Ok => "ok",
            Self::Failed => "failed",
            Self::Skipped => "skipped",
        }
    }
}

/// The deformation check in a line: the sweep and its totals (`check.json` has every pose).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckSummary {
    /// `humanoid` or `animal`.
    pub sweep: String,
    /// Poses measured.
    pub poses: usize,
    /// Edges past 1.5× summed over the poses.
    pub over_1_5: usize,
    /// Edges past 2× summed over the poses.
    pub over_2: usize,
    /// Largest stretch ratio of any pose.
    pub worst: f64,
    /// Vertices without weight.
    pub unweighted: usize,
}

/// A model's line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelLine {
    /// Output name (the folder below `OUT/models/`).
    pub model: String,
    /// The mesh file, relative to the batch's folder or list.
    pub source: String,
    /// What happened.
    pub status: Status,
    /// The shard that wrote the line, `K/N`.
    pub shard: String,
    /// Wall-clock seconds spent on the model.
    pub seconds: f64,
    /// `seconds` times the cores the model had (the process's threads / `--jobs`).
    pub core_seconds: f64,
    /// When the line was written (seconds since 1970).
    pub finished: f64,
    /// The template fitted (`humanoid`, `quadruped`, `winged`, `general`).
    #[serde(default)]
    pub template: Option<String>,
    /// Joints of the rig.
    #[serde(default)]
    pub joints: Option<usize>,
    /// The rig's typed warnings (stage, code, severity, message).
    #[serde(default)]
    pub warnings: Vec<WarningRecord>,
    /// Notices about the written file (units guessed, input animations left out, ...).
    #[serde(default)]
    pub notices: Vec<String>,
    /// The deformation check, when it could run.
    #[serde(default)]
    pub check: Option<CheckSummary>,
    /// Why the deformation check could not run (the rig is still written).
    #[serde(default)]
    pub check_error: Option<String>,
    /// Why the model failed.
    #[serde(default)]
    pub error: Option<String>,
    /// For a skipped model: the line of the run that made its outputs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub previous: Option<Box<ModelLine>>,
}

impl ModelLine {
    /// The line that says what the model's outputs are: itself, or for a skipped model the
    /// line of the run that made them.
    pub fn outcome(&self) -> &ModelLine {
        match (&self.status, &self.previous) {
            (Status::Skipped, Some(previous)) => previous.outcome(),
            _ => self,
        }
    }

    /// The most severe warning's severity.
    pub fn worst_severity(&self) -> Option<Severity> {
        self.warnings.iter().map(|w| w.severity).max()
    }
}

/// The line that ends a run of a shard.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunLine {
    /// `K/N`.
    pub shard: String,
    /// Models in the whole sorted list (every shard's).
    pub total_models: usize,
    /// Models of this shard.
    pub assigned: usize,
    /// Rigged and checked in this run.
    pub ok: usize,
    /// Failed in this run.
    pub failed: usize,
    /// Complete from an earlier run.
    pub skipped: usize,
    /// Wall-clock seconds of the run.
    pub wall_seconds: f64,
    /// CPU seconds (user + system) the process used, where the system tells (Linux); unlike
    /// core-seconds, not inflated by other work on shared cores.
    #[serde(default)]
    pub cpu_seconds: Option<f64>,
    /// Threads the process had (rayon's pool).
    pub threads: usize,
    /// Models rigged at once (`--jobs`).
    pub jobs: usize,
    /// When the run ended (seconds since 1970).
    pub finished: f64,
}

/// One line of the log.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Line {
    /// A model handled.
    Model(ModelLine),
    /// A run ended.
    Run(RunLine),
}

/// An open log, appended to line by line from any thread.
pub struct Log {
    file: Mutex<std::fs::File>,
}

impl Log {
    /// Opens (creates) `path` for appending.
    pub fn open(path: &Path) -> anyhow::Result<Self> {
        let file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .map_err(|e| anyhow::anyhow!("cannot open the log {}: {e}", path.display()))?;
        Ok(Self {
            file: Mutex::new(file),
        })
    }

    /// Appends `line` (one write, flushed to disk).
    pub fn append(&self, line: &Line) -> anyhow::Result<()> {
        let mut text = serde_json::to_string(line)?;
        text.push('\n');
        let mut file = self.file.lock().unwrap_or_else(|p| p.into_inner());
        file.write_all(text.as_bytes())?;
        file.sync_data()?;
        Ok(())
    }
}

/// Seconds since 1970.
pub fn now() -> f64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs_f64())
        .unwrap_or(0.0)
}

/// A table of model lines (Markdown, also readable as plain text): status, seconds, template,
/// warnings (count and worst severity), edges past 2× in the check, error.
pub fn table(lines: &[&ModelLine]) -> String {
    let mut out = String::from(
        "| model | status | seconds | template | warnings | check >2x | error |\n|---|---|---:|---|---|---:|---|\n",
    );
    for line in lines {
        let shown = line.outcome();
        let warnings = match shown.worst_severity() {
            Some(worst) => format!("{} (worst {worst})", shown.warnings.len()),
            None => "0".into(),
        };
        let check = match (&shown.check, &shown.check_error) {
            (Some(c), _) => c.over_2.to_string(),
            (None, Some(_)) => "not run".into(),
            (None, None) => "-".into(),
        };
        let error = shown
            .error
            .as_deref()
            .map(|e| e.replace('|', "\\|").replace('\n', " "))
            .unwrap_or_default();
        out.push_str(&format!(
            "| {} | {} | {:.2} | {} | {} | {} | {} |\n",
            line.model,
            match line.status {
                Status::Skipped => format!("skipped ({})", shown.status.as_str()),
                status => status.as_str().to_string(),
            },
            line.seconds,
            shown.template.as_deref().unwrap_or("-"),
            warnings,
            check,
            error
        ));
    }
    out
}

/// CPU seconds (user + system) this process has used: `/proc/self/stat`'s `utime` + `stime`,
/// in the kernel's fixed user-space clock ticks (100 a second); `None` off Linux.
pub fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The command name (field 2) is in parentheses and may hold spaces: count after it.
    let fields: Vec<&str> = stat
        .get(stat.rfind(')')? + 1..)?
        .split_whitespace()
        .collect();
    // Fields 14 (utime) and 15 (stime), numbered from 1; `fields[0]` is field 3.
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

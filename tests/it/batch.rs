//! `skelfit batch`: shards run as separate processes write every model once, their merged
//! report equals an unsharded run's (timings aside), a rerun does no work, and a broken model
//! is a failed row of a run that goes on (exit code 3, "some models failed").

use crate::common;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary, with no shard index inherited from a Slurm or Kubernetes environment.
fn skelfit() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_skelfit"));
    for var in [
        "SLURM_ARRAY_TASK_ID",
        "SLURM_ARRAY_TASK_MIN",
        "SLURM_ARRAY_TASK_STEP",
        "SLURM_ARRAY_TASK_COUNT",
        "JOB_COMPLETION_INDEX",
    ] {
        command.env_remove(var);
    }
    command
}

/// A folder of four models: a MakeHuman body and a horse (refdata-style and plain names), a
/// model folder whose `source.glb` (taken before its `mesh.obj`) is garbage, and a garbage OBJ.
fn models(root: &Path) -> PathBuf {
    let input = root.join("in");
    let data = common::data_dir();
    for (from, to) in [
        ("humanoid/mh_neutral_default/mesh.obj", "humans/mh/mesh.obj"),
        ("quadruped/quaternius_horse/mesh.obj", "animals/horse.obj"),
        ("quadruped/quaternius_horse/mesh.obj", "broken/mesh.obj"),
    ] {
        let to = input.join(to);
        std::fs::create_dir_all(to.parent().unwrap()).unwrap();
        std::fs::copy(data.join(from), to).unwrap();
    }
    std::fs::write(input.join("broken/source.glb"), b"glTF not really").unwrap();
    std::fs::write(input.join("junk.obj"), "v 0 0 0\nv 1 nonsense 0\nf 1 2 3\n").unwrap();
    input
}

fn code(output: &Output) -> i32 {
    output.status.code().unwrap_or(-1)
}

fn run(args: &[&str], envs: &[(&str, &str)]) -> Output {
    let output = skelfit()
        .args(args)
        .envs(envs.iter().copied())
        .output()
        .unwrap();
    assert!(
        matches!(code(&output), 0 | 3),
        "skelfit {args:?}: exit {}\n{}",
        code(&output),
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// The `model` lines of a log.
fn model_lines(log: &Path) -> Vec<serde_json::Value> {
    std::fs::read_to_string(log)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .filter(|l| l["kind"] == "model")
        .collect()
}

/// report.json without its timings (per-model seconds, totals' timing, the runs).
fn untimed(report: &Path) -> serde_json::Value {
    let mut report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(report).unwrap()).unwrap();
    for model in report["models"].as_array_mut().unwrap() {
        let model = model.as_object_mut().unwrap();
        model.remove("seconds");
        model.remove("core_seconds");
    }
    let report = report.as_object_mut().unwrap();
    report["totals"].as_object_mut().unwrap().remove("timing");
    report.remove("runs");
    report.remove("logs");
    serde_json::Value::Object(report.clone())
}

#[test]
fn batch_shards_merge_resume_and_failures() {
    let temp = tempfile::tempdir().unwrap();
    let input = models(temp.path());
    let input = input.to_str().unwrap();
    let full = temp.path().join("full");
    let sharded = temp.path().join("sharded");

    // One unsharded run: the broken models are rows, the run goes on, exit code 3.
    let output = run(&["batch", input, "--out", full.to_str().unwrap()], &[]);
    assert_eq!(code(&output), 3, "some models failed");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("| humans/mh | ok |"), "{stdout}");
    let lines = model_lines(&full.join("batch-0of1.jsonl"));
    let status: BTreeMap<String, (String, String)> = lines
        .iter()
        .map(|l| {
            (
                l["model"].as_str().unwrap().to_string(),
                (
                    l["status"].as_str().unwrap().to_string(),
                    l["source"].as_str().unwrap().to_string(),
                ),
            )
        })
        .collect();
    let expected: BTreeMap<String, (String, String)> = [
        ("animals/horse", "ok", "animals/horse.obj"),
        ("broken", "failed", "broken/source.glb"),
        ("humans/mh", "ok", "humans/mh/mesh.obj"),
        ("junk", "failed", "junk.obj"),
    ]
    .into_iter()
    .map(|(m, s, f)| (m.to_string(), (s.to_string(), f.to_string())))
    .collect();
    assert_eq!(status, expected);
    for line in &lines {
        if line["status"] == "failed" {
            assert!(line["error"].as_str().is_some_and(|e| !e.is_empty()));
        } else {
            assert!(line["check"]["poses"].as_u64().unwrap() > 0, "{line}");
            assert!(line["warnings"].is_array());
        }
    }
    for file in ["rig.glb", "rig.json", "check.json", "result.json"] {
        assert!(full.join("models/humans/mh").join(file).is_file(), "{file}");
    }

    // Three shards as separate processes, at once.
    let children: Vec<_> = (0..3)
        .map(|k| {
            skelfit()
                .args(["batch", input, "--out", sharded.to_str().unwrap()])
                .arg(format!("--shard={k}/3"))
                .output()
        })
        .collect();
    for child in children {
        let child = child.unwrap();
        assert!(
            matches!(code(&child), 0 | 3),
            "{}",
            String::from_utf8_lossy(&child.stderr)
        );
    }
    let mut written: Vec<String> = (0..3)
        .flat_map(|k| model_lines(&sharded.join(format!("batch-{k}of3.jsonl"))))
        .map(|l| l["model"].as_str().unwrap().to_string())
        .collect();
    written.sort();
    let all: Vec<String> = expected.keys().cloned().collect();
    assert_eq!(written, all, "every model exactly once");

    // The merged reports agree, timings aside.
    run(&["batch", "--merge", full.to_str().unwrap()], &[]);
    let merged = run(&["batch", "--merge", sharded.to_str().unwrap()], &[]);
    assert_eq!(code(&merged), 3, "the report has failed models");
    let report = untimed(&sharded.join("report.json"));
    assert_eq!(report, untimed(&full.join("report.json")));
    assert_eq!(report["totals"]["ok"], 2);
    assert_eq!(report["totals"]["failed"], 2);
    assert_eq!(report["totals"]["missing"], 0);
    assert!(sharded.join("report.md").is_file());

    // A second run of shard 0 (horse, junk), its index from a Kubernetes Indexed Job, does
    // no work: every model is skipped and no output changes.
    let glb = sharded.join("models/animals/horse/rig.glb");
    let before = std::fs::metadata(&glb).unwrap().modified().unwrap();
    run(
        &[
            "batch",
            input,
            "--out",
            sharded.to_str().unwrap(),
            "--shards",
            "3",
        ],
        &[("JOB_COMPLETION_INDEX", "0")],
    );
    assert_eq!(std::fs::metadata(&glb).unwrap().modified().unwrap(), before);
    let again = model_lines(&sharded.join("batch-0of3.jsonl"));
    assert_eq!(again.len(), 4, "two lines per model of shard 0");
    assert!(
        again[2..].iter().all(|l| l["status"] == "skipped"),
        "{again:?}"
    );
    run(&["batch", "--merge", sharded.to_str().unwrap()], &[]);
    assert_eq!(untimed(&sharded.join("report.json")), report);
}

//! End-to-end tests of `skelfit bench`, `skelfit study` and the bad-input paths of
//! `skelfit eval`. Rigging uses a coarse voxel size (0.02) to keep CI time modest.

use crate::common::skelfit;
use std::path::{Path, PathBuf};
use std::process::Command;

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn horse() -> PathBuf {
    crate::common::data_dir().join("quadruped/quaternius_horse")
}

/// A bench folder `<tmp>/quadruped/quaternius_horse` with the bundled horse's files.
fn horse_folder(root: &Path) -> PathBuf {
    let dir = root.join("quadruped/quaternius_horse");
    std::fs::create_dir_all(&dir).unwrap();
    for file in ["mesh.obj", "rig_gltf.json"] {
        std::fs::copy(horse().join(file), dir.join(file)).unwrap();
    }
    dir
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn eval_and_bench_agree_on_the_same_files() {
    let tmp = tempfile::tempdir().unwrap();
    let data = tmp.path().join("data");
    let model = horse_folder(&data);
    let out = tmp.path().join("out");
    let o = skelfit(&[
        "bench",
        data.to_str().unwrap(),
        "--rig",
        "gltf",
        "--out",
        out.to_str().unwrap(),
        "--skeletons",
        "--voxel-size",
        "0.02",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let bench = json(&out.join("bench.json"));
    let row = &bench[0];
    assert_eq!(row["model"], "quaternius_horse");
    assert!(row["failure"].is_null(), "{row}");
    let from_bench = &row["evaluation"];
    assert_eq!(from_bench["method"], "chamfer_only");
    // The same prediction, written by bench, evaluated by eval.
    let eval_json = tmp.path().join("eval.json");
    let o = skelfit(&[
        "eval",
        out.join("skeletons/quaternius_horse.json")
            .to_str()
            .unwrap(),
        model.join("rig_gltf.json").to_str().unwrap(),
        "--mesh",
        model.join("mesh.obj").to_str().unwrap(),
        "--chamfer-only",
        "--results-json",
        eval_json.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let from_eval = json(&eval_json);
    assert_eq!(from_eval["figure"], from_bench["figure"]);
    for metric in ["chamfer", "chamfer_percent"] {
        for key in ["j2j", "j2b", "b2b"] {
            let a = from_eval[metric][key].as_f64().unwrap();
            let b = from_bench[metric][key].as_f64().unwrap();
            assert!(
                a > 0.0 && (a - b).abs() <= 1e-9 * a,
                "{metric}.{key}: {a} vs {b}"
            );
        }
    }
    // The CSV and Markdown tables carry the same numbers and the stage timings.
    let csv = std::fs::read_to_string(out.join("bench.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    for stage in [
        "load_ms",
        "voxelize_ms",
        "distance_ms",
        "medial_ms",
        "paths_ms",
        "general_ms",
        "evaluate_ms",
        "total_ms",
    ] {
        assert!(header.contains(&stage), "{header:?}");
    }
    let md = std::fs::read_to_string(out.join("bench.md")).unwrap();
    let j2j = format!(
        "{:.2}",
        from_eval["chamfer_percent"]["j2j"].as_f64().unwrap()
    );
    assert!(md.contains(&format!("| {j2j} |")), "{md}");
    assert!(md.contains("per-joint errors"), "{md}");
}

#[test]
fn bench_reports_per_model_failures_and_rig_fallbacks() {
    let tmp = tempfile::tempdir().unwrap();
    let data = tmp.path().join("data");
    horse_folder(&data);
    let broken = data.join("quadruped/broken");
    std::fs::create_dir_all(&broken).unwrap();
    std::fs::write(broken.join("mesh.obj"), "v 0 0 0\nv 1 0 0\n").unwrap();
    std::fs::copy(
        horse().join("rig_gltf.json"),
        broken.join("rig_game_engine.json"),
    )
    .unwrap();
    let out = tmp.path().join("out");
    let o = skelfit(&[
        "bench",
        data.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--html",
        "--model-pages",
        "--voxel-size",
        "0.02",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let stdout = text(&o.stdout);
    assert!(stdout.contains("1 chamfer only, 1 failed"), "{stdout}");
    let csv = std::fs::read_to_string(out.join("bench.csv")).unwrap();
    let broken_row = csv.lines().find(|l| l.contains(",broken,")).unwrap();
    assert!(
        broken_row.contains(",failed,") && broken_row.contains("no triangles"),
        "{broken_row}"
    );
    let o = skelfit(&["report", out.join("bench.json").to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let rebuilt = std::fs::read_to_string(out.join("bench.html")).unwrap();
    assert!(rebuilt.contains("1 chamfer only, 1 failed"), "{rebuilt}");
    let md = std::fs::read_to_string(out.join("bench.md")).unwrap();
    assert!(
        md.contains("no rig_game_engine.json: evaluated against its only rig file rig_gltf.json"),
        "{md}"
    );
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(html.contains("href=\"models/quaternius_horse.html\""));
    // Self-contained: nothing to fetch.
    assert!(!html.contains("<script") && !html.contains("<link") && !html.contains("src="));
    let page = std::fs::read_to_string(out.join("models/quaternius_horse.html")).unwrap();
    assert_eq!(
        page.matches("<svg").count(),
        3,
        "three projections, no per-joint chart"
    );
    assert!(page.contains("per-joint errors"));
}

#[test]
fn eval_without_shared_joints_lists_both_name_sets() {
    let tmp = tempfile::tempdir().unwrap();
    let predicted = tmp.path().join("general.json");
    std::fs::write(
        &predicted,
        r#"{"joints": [{"name": "joint_000", "parent": null, "position": [0, 1, 0]},
                       {"name": "joint_001", "parent": 0, "position": [0, 2, 0]}]}"#,
    )
    .unwrap();
    let reference = horse().join("rig_gltf.json");
    let o = skelfit(&[
        "eval",
        predicted.to_str().unwrap(),
        reference.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = text(&o.stderr);
    assert!(err.contains("share no joints"), "{err}");
    assert!(
        err.contains("joint_000") && err.contains("joint_001"),
        "{err}"
    );
    let rig = json(&reference);
    let first_deforming = rig["joints"]
        .as_array()
        .unwrap()
        .iter()
        .find(|j| j["deform"] == true)
        .unwrap()["name"]
        .as_str()
        .unwrap()
        .to_owned();
    assert!(
        err.contains(&first_deforming),
        "{first_deforming} not in {err}"
    );
    // --chamfer-only compares them anyway.
    let o = skelfit(&[
        "eval",
        predicted.to_str().unwrap(),
        reference.to_str().unwrap(),
        "--chamfer-only",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(text(&o.stdout).contains("CD-J2J"));
}

#[test]
fn eval_warns_about_mismatched_units_and_names_missing_files() {
    let tmp = tempfile::tempdir().unwrap();
    let reference = horse().join("rig_gltf.json");
    let mut rig = json(&reference);
    for joint in rig["joints"].as_array_mut().unwrap() {
        for c in joint["position"].as_array_mut().unwrap() {
            *c = serde_json::json!(c.as_f64().unwrap() * 100.0);
        }
    }
    let scaled = tmp.path().join("rig_cm.json");
    std::fs::write(&scaled, rig.to_string()).unwrap();
    let o = skelfit(&[
        "eval",
        scaled.to_str().unwrap(),
        reference.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let err = text(&o.stderr);
    assert!(
        err.contains("skelfit: warning:") && err.contains("100.0x"),
        "{err}"
    );
    let missing = tmp.path().join("nowhere/rig_gltf.json");
    let o = skelfit(&[
        "eval",
        missing.to_str().unwrap(),
        reference.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = text(&o.stderr);
    assert!(
        err.contains("nowhere/rig_gltf.json") && err.contains("predicted"),
        "{err}"
    );
    let o = skelfit(&["bench", tmp.path().join("nowhere").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(text(&o.stderr).contains("nowhere"), "{}", text(&o.stderr));
}

#[test]
fn studies_write_tables_and_a_page_with_the_plot() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("study");
    let mesh = horse().join("mesh.obj");
    let reference = horse().join("rig_gltf.json");
    let o = skelfit(&[
        "study",
        "tessellation",
        mesh.to_str().unwrap(),
        "--reference",
        reference.to_str().unwrap(),
        "--levels",
        "0.5,2",
        "--out",
        out.to_str().unwrap(),
        "--html",
        "--voxel-size",
        "0.02",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let csv = std::fs::read_to_string(out.join("tessellation.csv")).unwrap();
    assert_eq!(csv.lines().count(), 4, "{csv}");
    let html = std::fs::read_to_string(out.join("tessellation.html")).unwrap();
    assert!(html.contains("Displacement per level") && html.contains("<polyline"));
    assert!(html.contains("triangle ratio (log scale)"));
    let o = skelfit(&[
        "study",
        "rotation",
        mesh.to_str().unwrap(),
        "--n",
        "2",
        "--out",
        out.to_str().unwrap(),
        "--voxel-size",
        "0.02",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    // `skelfit report` rebuilds the page from the JSON.
    let rebuilt = tmp.path().join("rebuilt.html");
    let o = skelfit(&[
        "report",
        out.join("tessellation.json").to_str().unwrap(),
        "-o",
        rebuilt.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let page = std::fs::read_to_string(&rebuilt).unwrap();
    assert!(
        page.contains("<polyline") && page.contains("x0.5"),
        "{page}"
    );
    let study = json(&out.join("rotation.json"));
    assert_eq!(study["kind"], "rotation");
    assert_eq!(study["variants"][1]["level"], 180.0);
    let base = &study["variants"][0]["chamfer_to_base_percent"];
    assert_eq!(base["j2j"], 0.0);
}

#[test]
fn bench_on_refdata_category_other() {
    let Some(root) = crate::common::refdata() else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let o = skelfit(&[
        "bench",
        root.join("other").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--voxel-size",
        "0.02",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let bench = json(&out.join("bench.json"));
    let rows = bench.as_array().unwrap();
    let models: Vec<std::path::PathBuf> = std::fs::read_dir(root.join("other"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("mesh.obj").is_file())
        .collect();
    assert_eq!(rows.len(), models.len());
    for row in rows {
        let model = row["model"].as_str().unwrap_or_default();
        let established = models.iter().find(|m| m.ends_with(model)).is_some_and(|m| {
            !crate::common::awaits_real_character_work(m, "bench_on_refdata_category_other")
        });
        if !established {
            continue;
        }
        assert!(row["failure"].is_null(), "{row}");
        assert_eq!(row["reference"], "rig_gltf.json");
        let j2j = row["evaluation"]["chamfer_percent"]["j2j"]
            .as_f64()
            .unwrap();
        // Rigged skeletons lie inside their figures: within a fifth of its size of the reference.
        assert!(j2j > 0.0 && j2j < 20.0, "{row}");
    }
}

/// `bench.json` without the timings (which differ between runs).
fn without_timings(mut value: serde_json::Value) -> serde_json::Value {
    for row in value.as_array_mut().unwrap() {
        row.as_object_mut().unwrap().remove("timings");
    }
    value
}

#[test]
fn bench_results_do_not_depend_on_the_thread_count() {
    let tmp = tempfile::tempdir().unwrap();
    let data = tmp.path().join("data");
    horse_folder(&data);
    let mut runs = Vec::new();
    for threads in ["1", "2"] {
        let out = tmp.path().join(format!("out{threads}"));
        let o = Command::new(env!("CARGO_BIN_EXE_skelfit"))
            .args([
                "bench",
                data.to_str().unwrap(),
                "--rig",
                "gltf",
                "--out",
                out.to_str().unwrap(),
                "--voxel-size",
                "0.02",
            ])
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", text(&o.stderr));
        runs.push(without_timings(json(&out.join("bench.json"))));
    }
    assert_eq!(runs[0], runs[1]);
}

/// `--select real` runs only the real game characters (provenance.json with a `converter`),
/// and with `--model-pages` every one of them gets a page: the projections when it was
/// evaluated, the reason when it failed. The anatomical rig's table gives the core joint error.
#[test]
fn bench_select_real_pages_every_real_character() {
    let tmp = tempfile::tempdir().unwrap();
    let data = tmp.path().join("data");
    horse_folder(&data); // no provenance: not real
    let body = crate::common::data_dir().join("humanoid/mh_neutral_default");
    let real = data.join("humanoid/body");
    std::fs::create_dir_all(&real).unwrap();
    for file in ["mesh.obj", "rig_game_engine.json"] {
        std::fs::copy(body.join(file), real.join(file)).unwrap();
    }
    let provenance = r#"{"converter": "test"}"#;
    std::fs::write(real.join("provenance.json"), provenance).unwrap();
    let broken = data.join("humanoid/broken");
    std::fs::create_dir_all(&broken).unwrap();
    std::fs::write(
        broken.join("mesh.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    std::fs::copy(
        body.join("rig_game_engine.json"),
        broken.join("rig_game_engine.json"),
    )
    .unwrap();
    std::fs::write(broken.join("provenance.json"), provenance).unwrap();
    let out = tmp.path().join("out");
    let o = skelfit(&[
        "bench",
        data.to_str().unwrap(),
        "--method",
        "anatomical",
        "--select",
        "real",
        "--out",
        out.to_str().unwrap(),
        "--html",
        "--model-pages",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let bench = json(&out.join("bench.json"));
    let rows = bench.as_array().unwrap();
    let names: Vec<&str> = rows.iter().map(|r| r["model"].as_str().unwrap()).collect();
    assert_eq!(names, ["body", "broken"]);
    let body = &rows[0];
    assert_eq!(body["real"], true);
    assert_eq!(body["anatomy"]["template"], "humanoid");
    assert_eq!(body["core"]["mapped"].as_array().unwrap().len(), 15);
    assert_eq!(body["core"]["missing"].as_array().unwrap().len(), 0);
    let core = body["core"]["mean_percent"].as_f64().unwrap();
    assert!(core > 0.0 && core < 2.0, "core {core} % of height");
    assert!(rows[1]["failure"].is_string());
    for name in ["body", "broken"] {
        let page = out.join(format!("models/{name}.html"));
        assert!(page.is_file(), "{}", page.display());
    }
    let failed = std::fs::read_to_string(out.join("models/broken.html")).unwrap();
    assert!(failed.contains("failed: "), "{failed}");
    let index = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(index.contains("href=\"models/broken.html\""));
    let md = std::fs::read_to_string(out.join("bench.md")).unwrap();
    assert!(md.contains("## Anatomical rig per model"), "{md}");
    assert!(md.contains("over 1 real characters: median"), "{md}");
}

//! The CLI's one convention (issue 22 item 5) and readable reports (item 6): `--json` prints
//! the command's result as JSON on stdout for every command, warnings are grouped by kind
//! (`-v` lists each, `-q` prints errors only), `--help` lists the main commands first, the
//! bones preview stays small, and report folders get an index page with verdict lines.

use crate::common::skelfit;
use std::path::Path;

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn data(relative: &str) -> String {
    crate::common::data_dir()
        .join(relative)
        .display()
        .to_string()
}

const BODY: &str = "humanoid/mh_neutral_default/mesh.obj";
const HORSE: &str = "quadruped/quaternius_horse/mesh.obj";

/// Runs `args` and parses its whole stdout as one JSON value.
fn json_of(args: &[&str]) -> serde_json::Value {
    let out = skelfit(args);
    assert!(out.status.success(), "{args:?}: {}", text(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "{args:?}: stdout is not one JSON value ({e}): {}",
            text(&out.stdout)
        )
    })
}

fn p(path: &Path) -> &str {
    path.to_str().unwrap()
}

#[test]
fn json_prints_the_result_on_stdout_for_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let info = json_of(&["info", &data(BODY), "--json"]);
    assert_eq!(info["triangles"], 26756);
    let vox = json_of(&["voxelize", &data(BODY), "--resolution", "32", "--json"]);
    assert!(vox["interior_voxels"].as_u64().unwrap() > 0);

    // rig: the skeleton JSON that --skeleton-json writes, on stdout.
    let (glb, file) = (d.join("rig.glb"), d.join("rig.json"));
    let rig = json_of(&[
        "rig",
        &data(BODY),
        "-o",
        p(&glb),
        "--skeleton-json",
        p(&file),
        "--json",
    ]);
    let written: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&file).unwrap()).unwrap();
    assert_eq!(rig, written);
    assert_eq!(rig["run"]["template"], "humanoid");
    assert!(rig["canonical"]["pelvis"].is_string());

    let label = json_of(&["label", &data(BODY), "-o", p(&d.join("l.json")), "--json"]);
    assert_eq!(label["figure"], "human-like");

    let reference = data("humanoid/mh_neutral_default/rig_game_engine.json");
    let eval = json_of(&["eval", p(&file), &reference, "--json"]);
    assert!(eval["joints"].as_array().is_some_and(|j| !j.is_empty()));

    let check = json_of(&["check", p(&glb), "--json"]);
    assert_eq!(check["format"], "skelfit-check-v1");

    let bench = json_of(&[
        "bench",
        p(&crate::common::data_dir()),
        "--out",
        p(&d.join("bench")),
        "--json",
    ]);
    assert_eq!(bench.as_array().map(Vec::len), Some(2));

    // The deprecated spelling still works for one release.
    let old = json_of(&["info", &data(HORSE), "--print-json"]);
    assert_eq!(old["closed"], true);
}

/// `skeleton`, `skin`, `simplify`, `study` and `demo` print their result as one JSON value on
/// stdout with `--json` and nothing else there (`skin` and `simplify` printed it on stderr).
#[test]
fn json_is_the_whole_stdout_of_skeleton_skin_simplify_study_and_demo() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (glb, file) = (d.join("general.glb"), d.join("general.json"));
    let general = json_of(&["skeleton", &data(HORSE), "-o", p(&glb), "--json"]);
    assert!(general["joints"].as_array().is_some_and(|j| !j.is_empty()));
    std::fs::write(&file, serde_json::to_vec(&general).unwrap()).unwrap();

    let skinned = d.join("skinned.glb");
    let skin = json_of(&[
        "skin",
        &data(HORSE),
        "--skeleton",
        p(&file),
        "-o",
        p(&skinned),
        "--json",
    ]);
    let names = |v: &serde_json::Value| -> Vec<serde_json::Value> {
        v["joints"]
            .as_array()
            .unwrap()
            .iter()
            .map(|j| j["name"].clone())
            .collect()
    };
    assert_eq!(names(&skin), names(&general));

    let simplified = d.join("simplified.json");
    let simplify = json_of(&[
        "simplify",
        p(&file),
        "-o",
        p(&simplified),
        "--lod-prune",
        "0.1",
        "--json",
    ]);
    assert!(simplify["joints"].as_array().is_some_and(|j| !j.is_empty()));

    let study = json_of(&[
        "study",
        "rotation",
        &data(HORSE),
        "--n",
        "2",
        "--out",
        p(&d.join("study")),
        "--json",
    ]);
    assert!(study.is_object() || study.is_array(), "{study}");

    let demo = json_of(&[
        "demo",
        "--data",
        p(&crate::common::data_dir()),
        "--out",
        p(&d.join("demo")),
        "--json",
    ]);
    assert!(demo.is_object() || demo.is_array(), "{demo}");
}

#[test]
fn json_and_summary_go_to_different_streams_and_q_keeps_only_the_json() {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("h.glb");
    let out = skelfit(&["rig", &data(HORSE), "-o", p(&glb), "--json"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        text(&out.stderr).contains("wrote"),
        "the summary goes to stderr"
    );
    serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap();

    let quiet = skelfit(&["rig", &data(HORSE), "-o", p(&glb), "-q"]);
    assert!(quiet.status.success());
    assert_eq!(text(&quiet.stdout), "");
    assert_eq!(text(&quiet.stderr), "", "-q prints errors only");

    let both = skelfit(&["rig", &data(HORSE), "-o", p(&glb), "-q", "--json"]);
    assert!(both.status.success());
    serde_json::from_slice::<serde_json::Value>(&both.stdout).unwrap();
    assert_eq!(text(&both.stderr), "");

    // Errors still print under -q.
    let missing = skelfit(&["rig", "no/such/mesh.obj", "-o", p(&glb), "-q"]);
    assert_eq!(missing.status.code(), Some(1));
    assert!(text(&missing.stderr).contains("skelfit: error:"));
}

/// The warning lines of a run's stderr.
fn warning_lines(stderr: &str) -> Vec<&str> {
    stderr
        .lines()
        .filter(|l| l.starts_with("skelfit: warning:"))
        .collect()
}

#[test]
fn warnings_of_one_kind_are_one_line_unless_verbose() {
    // The bundled body's bones: the toe tips' bones left out for lying outside the figure.
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("b.glb");
    let grouped = skelfit(&["bones", &data(BODY), "-o", p(&glb)]);
    assert!(grouped.status.success(), "{}", text(&grouped.stderr));
    let verbose = skelfit(&["bones", &data(BODY), "-o", p(&glb), "-v"]);
    assert!(verbose.status.success());
    let (grouped, verbose) = (text(&grouped.stderr), text(&verbose.stderr));
    let each = warning_lines(&verbose);
    let outside: Vec<&&str> = each
        .iter()
        .filter(|l| l.ends_with("[bones, part_missing]") && l.contains("left out, only"))
        .collect();
    assert!(outside.len() >= 2, "{verbose}");
    let lines = warning_lines(&grouped);
    assert!(lines.len() < each.len(), "{grouped}");
    let group: Vec<&&str> = lines
        .iter()
        .filter(|l| l.contains("left out, only"))
        .collect();
    assert_eq!(group.len(), 1, "one line for the kind: {grouped}");
    assert!(
        group[0].contains(&format!(" ({}): ", outside.len())),
        "{}",
        group[0]
    );
    // Each bone named in the line, or counted in its "and N more".
    let listed = group[0]
        .split_once("): ")
        .and_then(|(_, rest)| rest.split([';', '[']).next())
        .map(str::trim)
        .unwrap();
    let named: Vec<&str> = listed.split(" and ").next().unwrap().split(", ").collect();
    let more = listed.split_once(" and ").map_or(0, |(_, m)| {
        m.trim_end_matches(" more").parse::<usize>().unwrap()
    });
    assert_eq!(named.len() + more, outside.len(), "{}", group[0]);
    for bone in &named {
        assert!(
            outside.iter().any(|l| l.contains(&format!(" {bone}: "))),
            "{bone} in the group but not warned: {verbose}"
        );
    }
    // Ranked: parts missing before degraded ones.
    let first_degraded = lines.iter().position(|l| l.contains(", degraded"));
    let last_missing = lines.iter().rposition(|l| l.contains(", part_missing"));
    if let (Some(d), Some(m)) = (first_degraded, last_missing) {
        assert!(m < d, "{grouped}");
    }
}

#[test]
fn help_lists_rig_skin_and_check_first() {
    let out = skelfit(&["--help"]);
    assert!(out.status.success());
    let help = text(&out.stdout);
    let commands: Vec<&str> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert_eq!(commands[..3], ["rig", "skin", "check"], "{help}");
    let rest = &commands[3..commands.len() - 1];
    let mut sorted = rest.to_vec();
    sorted.sort_unstable();
    assert_eq!(rest, sorted, "the rest alphabetically: {help}");
    assert!(help.contains("--json") && help.contains("--quiet") && help.contains("--verbose"));
}

#[test]
fn bones_svg_stays_under_half_a_megabyte() {
    let dir = tempfile::tempdir().unwrap();
    for (model, name) in [(BODY, "body"), (HORSE, "horse")] {
        let svg = dir.path().join(format!("{name}.svg"));
        let glb = dir.path().join(format!("{name}.glb"));
        let out = skelfit(&["bones", &data(model), "-o", p(&glb), "--svg", p(&svg), "-q"]);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let bytes = std::fs::read(&svg).unwrap();
        assert!(bytes.len() < 500_000, "{name}: {} bytes", bytes.len());
        let svg = text(&bytes);
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        // Three views, each bone a titled group in each view where it shows.
        let groups = svg.matches("<g><title>").count();
        assert!(groups > 3 * 20, "{name}: {groups} groups");
    }
}

#[test]
fn report_index_links_every_page_with_its_verdict() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bench");
    let o = skelfit(&[
        "bench",
        p(&crate::common::data_dir()),
        "--out",
        p(&out),
        "--html",
        "--method",
        "anatomical",
        "-q",
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    let verdict = page
        .split("<p class=\"verdict\"><strong>Verdict:</strong> ")
        .nth(1)
        .and_then(|rest| rest.split("</p>").next())
        .expect("the bench page opens with a verdict");
    assert!(
        verdict.contains("reference rig (rig_game_engine.json"),
        "{verdict}"
    );
    assert!(verdict.contains("worst: "), "{verdict}");
    let listed = json_of(&["report", "--index", p(dir.path()), "--json"]);
    let index = std::fs::read_to_string(dir.path().join("index.html")).unwrap();
    assert!(index.contains("href=\"bench/index.html\""), "{index}");
    assert!(index.contains("href=\"bench/bench.md\""), "{index}");
    let reports = listed["reports"].as_array().unwrap();
    let bench_page = reports
        .iter()
        .find(|r| r["path"] == "bench/index.html")
        .unwrap();
    assert!(bench_page["verdict"].as_str().unwrap().contains("worst: "));
}

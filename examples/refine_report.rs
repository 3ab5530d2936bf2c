//! Accuracy of the slicing refinement (seed 004) against the reference rigs, on the whole
//! `skelfit rig` pipeline (refinement off and on) and from displaced reference joints, and its
//! robustness to tessellation: writes `reports/refine/accuracy.{md,csv}`,
//! `reports/refine/pipeline.csv` and `reports/refine/robustness.{md,csv,svg}`.
//!
//! Starting skeletons: the fitted skeleton of `skelfit rig` (default options, refinement off
//! and on), and each reference rig's canonical joints displaced by deterministic offsets of 3-6
//! cm (the joints in between carried along; robustness uses this start). Errors are measured
//! on the 15 joints of [`skelfit::refine::REFINED_KEYS`] before and after refinement.
//!
//! Run: `cargo run --release --example refine_report [-- REFDATA_DIR [OUT_DIR]]`
//! (defaults `../shared/refdata` and `reports/refine`).

use glam::DVec3;
use skelfit::eval::load_skeleton;
use skelfit::mesh::load;
use skelfit::pipeline::{rig, RigOptions};
use skelfit::refine::{carry, refine, RefineOptions, REFINED_KEYS};
use skelfit::report::{line_chart, LineChartOptions, Series};
use skelfit::skeleton::JointId;
use skelfit::warning::Warning;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn main() {
    if let Err(message) = run() {
        eprintln!("refine_report: error: {message}");
        std::process::exit(1);
    }
}

/// The deterministic displacement of the `k`-th refined key: 3, 4, 5 or 6 cm in a direction
/// that changes from key to key.
fn offset(k: usize) -> DVec3 {
    let k = k as f64;
    let dir = DVec3::new(
        (1.7 * k + 0.3).sin(),
        (2.3 * k + 1.1).cos(),
        (0.9 * k + 2.0).sin(),
    )
    .normalize();
    dir * (0.03 + 0.01 * (k % 4.0))
}

/// A markdown section `title` opening a table with a `first` column and one column per refined
/// joint (header and separator rows).
fn joint_table_header(title: &str, first: &str) -> String {
    format!(
        "\n## {title}\n\n| {first} | {} |\n|---|{}\n",
        REFINED_KEYS.join(" | "),
        "---|".repeat(REFINED_KEYS.len())
    )
}

struct Outcome {
    before: Vec<f64>,
    after: Vec<f64>,
    refined: BTreeMap<String, DVec3>,
    warnings: Vec<String>,
}

fn evaluate(mesh_path: &Path, rig_path: &Path) -> Result<Outcome, String> {
    let mesh = load(mesh_path).map_err(|e| format!("{}: {e}", mesh_path.display()))?;
    let rig = load_skeleton(rig_path).map_err(|e| format!("{}: {e}", rig_path.display()))?;
    let canonical: BTreeMap<String, JointId> = rig.canonical.clone();
    let targets: BTreeMap<JointId, DVec3> = REFINED_KEYS
        .iter()
        .enumerate()
        .filter_map(|(k, key)| {
            let id = *canonical.get(*key)?;
            Some((id, rig.skeleton.joint(id).position + offset(k)))
        })
        .collect();
    let rough = carry(&rig.skeleton, &targets);
    let refined = refine(
        &mesh,
        &rough,
        &canonical,
        DVec3::Y,
        DVec3::Z,
        &RefineOptions::default(),
    )
    .map_err(|e| e.to_string())?;
    if std::env::var_os("REFINE_DEBUG").is_some() {
        if let Some(t) = &refined.torso {
            eprintln!(
                "   torso neck {:.3} back {:.3} lumbar {:.3} sacro {:.3} throat {:.3} crotch {:.3}",
                t.neck, t.back, t.lumbar, t.sacroiliac, t.throat, t.crotch
            );
        }
    }
    let mut out = Outcome {
        before: Vec::new(),
        after: Vec::new(),
        refined: BTreeMap::new(),
        warnings: refined.warnings.iter().map(ToString::to_string).collect(),
    };
    for key in REFINED_KEYS {
        let Some(&id) = canonical.get(key) else {
            continue;
        };
        let truth = rig.skeleton.joint(id).position;
        let after = refined.skeleton.joint(id).position;
        out.before
            .push(rough.joint(id).position.distance(truth) * 1000.0);
        out.after.push(after.distance(truth) * 1000.0);
        out.refined.insert(key.to_string(), after);
        if std::env::var_os("REFINE_DEBUG").is_some() {
            eprintln!(
                "   {key:12} truth {truth:.3} refined {after:.3} diff {:.3}",
                after - truth
            );
        }
    }
    Ok(out)
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(0.0, f64::max)
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = PathBuf::from(args.first().map_or("../shared/refdata", String::as_str));
    let out_dir = PathBuf::from(args.get(1).map_or("reports/refine", String::as_str));
    std::fs::create_dir_all(&out_dir).map_err(|e| e.to_string())?;
    let models = [
        ("mh_child_10y", "rig_game_engine.json"),
        ("mh_female_thin_short", "rig_game_engine.json"),
        ("mh_female_young_average", "rig_game_engine.json"),
        ("mh_male_heavy_short", "rig_game_engine.json"),
        ("mh_male_young_average", "rig_game_engine.json"),
        ("mh_neutral_default", "rig_game_engine.json"),
        ("gltf_cesium_man", "rig_gltf.json"),
    ];
    let command = "cargo run --release --example refine_report";
    let mut md = format!("# Refinement accuracy (seed 004)\n\nRegenerate: `{command}`\n\nErrors in mm over {} joints ({}) against the reference rigs' canonical joints.\n", REFINED_KEYS.len(), REFINED_KEYS.join(", "));
    md += &pipeline(&root, &models, &out_dir)?;
    md += "\n## Displaced reference start\n\nStart: reference canonical joints displaced by deterministic 3-6 cm offsets (the joints in between carried along), so the refinement is measured apart from the fit.\n\n| model | before mean | before max | after mean | after max | worst joint |\n|---|---|---|---|---|---|\n";
    let mut csv = String::from("model,joint,before_mm,after_mm\n");
    let mut joints_md =
        joint_table_header("Per joint, displaced reference start (after, mm)", "model");
    let mut warnings_md = String::new();
    for (model, rig) in models {
        let dir = root.join("humanoid").join(model);
        let o = evaluate(&dir.join("mesh.obj"), &dir.join(rig))?;
        let worst = REFINED_KEYS
            .iter()
            .zip(&o.after)
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map_or("", |(k, _)| *k);
        let _ = writeln!(
            md,
            "| {model} | {:.1} | {:.1} | {:.1} | {:.1} | {worst} |",
            mean(&o.before),
            max(&o.before),
            mean(&o.after),
            max(&o.after)
        );
        let _ = write!(joints_md, "| {model} |");
        for ((key, b), a) in REFINED_KEYS.iter().zip(&o.before).zip(&o.after) {
            let _ = writeln!(csv, "{model},{key},{b:.2},{a:.2}");
            let _ = write!(joints_md, " {a:.0} |");
        }
        joints_md += "\n";
        for w in &o.warnings {
            let _ = writeln!(warnings_md, "- {model}: {w}");
        }
        eprintln!(
            "{model}: before {:.1}/{:.1} after {:.1}/{:.1} mm",
            mean(&o.before),
            max(&o.before),
            mean(&o.after),
            max(&o.after)
        );
        for ((key, b), a) in REFINED_KEYS.iter().zip(&o.before).zip(&o.after) {
            eprintln!("   {key:12} {b:6.1} {a:6.1}");
        }
        for w in &o.warnings {
            eprintln!("   warning: {w}");
        }
    }
    md += &joints_md;
    if !warnings_md.is_empty() {
        md += "\n## Warnings\n\n";
        md += &warnings_md;
    }
    std::fs::write(out_dir.join("accuracy.md"), md).map_err(|e| e.to_string())?;
    std::fs::write(out_dir.join("accuracy.csv"), csv).map_err(|e| e.to_string())?;
    robustness(&root, &out_dir, command)
}

/// The whole `skelfit rig` pipeline with refinement off and on (`RigOptions::refine.in_rig`),
/// per model: a markdown section, and `pipeline.csv` in `out_dir`.
fn pipeline(root: &Path, models: &[(&str, &str)], out_dir: &Path) -> Result<String, String> {
    let mut md = String::from("\n## Full pipeline (`skelfit rig`)\n\nThe rig's own start: labels, template fit, then refinement (default options). *fitted*: `--refine off`; *refined*: the default.\n\n| model | triangles | fitted mean | fitted max | refined mean | refined max | worst joint |\n|---|---|---|---|---|---|---|\n");
    let mut joints_md = joint_table_header("Per joint, full pipeline (refined, mm)", "model");
    let mut csv = String::from("model,joint,fitted_mm,refined_mm\n");
    let mut warnings_md = String::new();
    let (mut all_fitted, mut all_refined) = (Vec::new(), Vec::new());
    for (model, rig_file) in models {
        let dir = root.join("humanoid").join(model);
        let mesh = load(&dir.join("mesh.obj")).map_err(|e| format!("{model}: {e}"))?;
        let reference = load_skeleton(&dir.join(rig_file)).map_err(|e| format!("{model}: {e}"))?;
        let errors = |refine: bool| -> Result<(Vec<f64>, Vec<String>), String> {
            let mut options = RigOptions::default();
            options.refine.in_rig = refine;
            let r = rig(&mesh, &options).map_err(|e| format!("{model}: {e}"))?;
            let e = REFINED_KEYS
                .iter()
                .map(|k| {
                    let ours = r
                        .fit
                        .canonical
                        .get(*k)
                        .map(|&id| r.fit.skeleton.joint(id).position);
                    let truth = reference.canonical_joint(k).map(|j| j.position);
                    match (ours, truth) {
                        (Some(a), Some(b)) => Ok(a.distance(b) * 1000.0),
                        _ => Err(format!("{model}: joint {k} missing")),
                    }
                })
                .collect::<Result<Vec<f64>, String>>()?;
            let warnings = r
                .warnings
                .iter()
                .filter(|w| matches!(w, Warning::Refine(_)))
                .map(ToString::to_string)
                .collect();
            Ok((e, warnings))
        };
        let (fitted, _) = errors(false)?;
        let (refined, warnings) = errors(true)?;
        let worst = REFINED_KEYS
            .iter()
            .zip(&refined)
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map_or("", |(k, _)| *k);
        let _ = writeln!(
            md,
            "| {model} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {worst} |",
            mesh.triangles.len(),
            mean(&fitted),
            max(&fitted),
            mean(&refined),
            max(&refined)
        );
        let _ = write!(joints_md, "| {model} |");
        for ((key, f), r) in REFINED_KEYS.iter().zip(&fitted).zip(&refined) {
            let _ = writeln!(csv, "{model},{key},{f:.2},{r:.2}");
            let _ = write!(joints_md, " {r:.0} |");
        }
        joints_md += "\n";
        for w in &warnings {
            let _ = writeln!(warnings_md, "- {model}: {w}");
        }
        eprintln!(
            "{model} (skelfit rig): fitted {:.1}/{:.1} refined {:.1}/{:.1} mm",
            mean(&fitted),
            max(&fitted),
            mean(&refined),
            max(&refined)
        );
        if model.starts_with("mh_") {
            all_fitted.extend(fitted);
            all_refined.extend(refined);
        }
    }
    let _ = writeln!(
        md,
        "\nMakeHuman bodies together: fitted {:.1} mm mean, refined {:.1} mm mean.",
        mean(&all_fitted),
        mean(&all_refined)
    );
    md += &joints_md;
    if !warnings_md.is_empty() {
        md += "\nJoints the refinement left at the fitted position:\n\n";
        md += &warnings_md;
    }
    std::fs::write(out_dir.join("pipeline.csv"), csv).map_err(|e| e.to_string())?;
    Ok(md)
}

/// Mean and max displacement of the refined joints on each tessellation variant of
/// `mh_male_young_average` from the result on the 27k-triangle original (same start).
fn robustness(root: &Path, out_dir: &Path, command: &str) -> Result<(), String> {
    let model = "mh_male_young_average";
    let base_dir = root.join("humanoid").join(model);
    let rig = base_dir.join("rig_game_engine.json");
    let base = evaluate(&base_dir.join("mesh.obj"), &rig)?;
    let mut variants: Vec<PathBuf> = std::fs::read_dir(root.join("robustness"))
        .map_err(|e| e.to_string())?
        .filter_map(|e| Some(e.ok()?.path()))
        .filter(|p| p.join("mesh.obj").is_file())
        .collect();
    variants.sort();
    let mut md = format!("# Refinement robustness to tessellation (seed 004, table 1)\n\nRegenerate: `{command}`\n\nDisplacement (mm) of the {} refined joints of {model} from the result on the 27k-triangle original, same starting skeleton.\n\n| variant | triangles | mean | max | worst joint |\n|---|---|---|---|---|\n", REFINED_KEYS.len());
    let mut csv = String::from("variant,triangles,mean_mm,max_mm\n");
    let mut means: Vec<(f64, f64)> = Vec::new();
    let mut maxima: Vec<(f64, f64)> = Vec::new();
    let mut per_joint = joint_table_header("Per joint (mm)", "variant");
    for dir in variants {
        let name = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let mesh = load(&dir.join("mesh.obj")).map_err(|e| e.to_string())?;
        let o = evaluate(&dir.join("mesh.obj"), &rig)?;
        let d: Vec<(String, f64)> = o
            .refined
            .iter()
            .filter_map(|(k, p)| Some((k.clone(), base.refined.get(k)?.distance(*p) * 1000.0)))
            .collect();
        let values: Vec<f64> = d.iter().map(|x| x.1).collect();
        let worst = d
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map_or("", |x| x.0.as_str());
        let _ = writeln!(
            md,
            "| {name} | {} | {:.1} | {:.1} | {worst} |",
            mesh.triangles.len(),
            mean(&values),
            max(&values)
        );
        let _ = writeln!(
            csv,
            "{name},{},{:.2},{:.2}",
            mesh.triangles.len(),
            mean(&values),
            max(&values)
        );
        means.push((mesh.triangles.len() as f64, mean(&values)));
        maxima.push((mesh.triangles.len() as f64, max(&values)));
        let _ = writeln!(
            per_joint,
            "| {name} | {} |",
            REFINED_KEYS
                .iter()
                .map(|k| d
                    .iter()
                    .find(|x| x.0 == *k)
                    .map_or("–".to_string(), |x| format!("{:.1}", x.1)))
                .collect::<Vec<_>>()
                .join(" | ")
        );
        for w in &o.warnings {
            eprintln!("   warning: {w}");
        }
        eprintln!(
            "{name}: {} triangles, displacement mean {:.1} max {:.1} mm ({worst})",
            mesh.triangles.len(),
            mean(&values),
            max(&values)
        );
    }
    means.sort_by(|a, b| a.0.total_cmp(&b.0));
    maxima.sort_by(|a, b| a.0.total_cmp(&b.0));
    let svg = line_chart(
        &[
            Series {
                name: "mean displacement".into(),
                colour: "#1f77b4".into(),
                points: means,
            },
            Series {
                name: "max displacement".into(),
                colour: "#d62728".into(),
                points: maxima,
            },
        ],
        &LineChartOptions {
            log_x: true,
            x_label: "triangles".into(),
            y_label: "mm from the 27k result".into(),
            ..Default::default()
        },
    );
    md += &per_joint;
    md += "\n![displacement against triangle count](robustness.svg)\n";
    std::fs::write(out_dir.join("robustness.svg"), svg).map_err(|e| e.to_string())?;
    std::fs::write(out_dir.join("robustness.md"), md).map_err(|e| e.to_string())?;
    std::fs::write(out_dir.join("robustness.csv"), csv).map_err(|e| e.to_string())?;
    Ok(())
}

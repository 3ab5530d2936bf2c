//! `skelfit demo [--data DIR] [--out DIR]`: the main job on the bundled data.
//!
//! For every `mesh.obj` below the data folder (the refdata layout: `<kind>/<model>/mesh.obj`),
//! prints the mesh statistics, voxelizes it, computes its distance map, fits the general control
//! skeleton and the anatomical skeleton (template chosen from the labelled figure) and skins the
//! mesh to each, and writes `<out>/<model>/{info.json, voxelize.json, slices/*.png, general.glb,
//! general.json, general.bvh, rig.glb, rig.json, rig.bvh, bones.glb, bones.svg}` (bones.glb:
//! the rig with bone meshes as child nodes of their joints, dissertation 9.1); with a reference rig beside the mesh
//! (`rig_game_engine.json`, else the only `rig_*.json`) it also prints the anatomical rig's
//! per-joint error; then a summary table.

use super::common::{say, write_file, VoxelArgs};
use super::voxelize::{print_text, summarize};
use anyhow::Context;
use clap::Args;
use skelfit::eval::{
    evaluate, find_bench_models, load_skeleton, EvalOptions, JointPairing, ReferenceRig,
};
use skelfit::export::{
    write_bvh, write_glb, write_skeleton_json, BvhOptions, GltfOptions, JsonOptions,
};
use skelfit::pipeline::{general_rig, rig, GeneralRigOptions, RigOptions};
use skelfit::warning::Warning;
use std::path::{Path, PathBuf};

/// Arguments of `skelfit demo`.
#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Folder with models in the refdata layout (`<kind>/<model>/mesh.obj`).
    #[arg(long, default_value = "data")]
    pub data: PathBuf,
    /// Folder for the results (created if missing).
    #[arg(long, default_value = "reports/demo")]
    pub out: PathBuf,
    #[command(flatten)]
    pub voxel: VoxelArgs,
}

/// Finds `mesh.obj` files up to two folders deep, sorted by path.
pub fn find_models(data: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut found = Vec::new();
    let mut stack = vec![(data.to_path_buf(), 0)];
    while let Some((dir, depth)) = stack.pop() {
        let entries =
            std::fs::read_dir(&dir).with_context(|| format!("reading folder {}", dir.display()))?;
        for entry in entries {
            let path = entry?.path();
            if path.is_dir() && depth < 2 {
                stack.push((path, depth + 1));
            } else if path.file_name().is_some_and(|n| n == "mesh.obj") {
                found.push(path);
            }
        }
    }
    found.sort();
    if found.is_empty() {
        anyhow::bail!(
            "no <kind>/<model>/mesh.obj found below {}: run from the repository root or pass --data",
            data.display()
        );
    }
    Ok(found)
}

/// Runs the demo.
pub fn run(args: &DemoArgs) -> anyhow::Result<()> {
    let options = args.voxel.options()?;
    super::common::output_folder(&args.out)?;
    let models = find_models(&args.data)?;
    let mut rows = Vec::new();
    for mesh_path in &models {
        let name = mesh_path
            .parent()
            .and_then(|p| p.file_name())
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "model".into());
        let out = args.out.join(&name);
        std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
        say!("== {name}");
        let stats = super::common::load_mesh(mesh_path)?.stats();
        write_file(
            &out.join("info.json"),
            serde_json::to_string_pretty(&stats)?.as_bytes(),
        )?;
        let summary = summarize(mesh_path, &options, Some(&out.join("slices")))?;
        write_file(
            &out.join("voxelize.json"),
            serde_json::to_string_pretty(&summary)?.as_bytes(),
        )?;
        print_text(&summary);
        let (general, general_warnings) = rig_general(mesh_path, &out)?;
        let (anatomical, anatomical_warnings) = rig_anatomical(mesh_path, &out)?;
        // One grouped, ranked list per model: what needs attention first.
        let mut warnings = general_warnings;
        warnings.extend(anatomical_warnings);
        super::common::print_warnings(&warnings);
        rows.push((name, stats, summary, general, anatomical, warnings));
    }
    if super::common::json_mode() {
        let models: Vec<serde_json::Value> = rows
            .iter()
            .map(|(name, stats, s, (joints, rig_ms), a, warnings)| {
                serde_json::json!({
                    "model": name,
                    "info": stats,
                    "voxelize": s,
                    "general": {"joints": joints, "rig_ms": rig_ms},
                    "anatomical": {
                        "template": a.template,
                        "joints": a.joints,
                        "rig_ms": a.rig_ms,
                        "mean_error": a.error.map(|e| e.0),
                        "mean_error_percent": a.error.map(|e| e.1),
                    },
                    "warnings": warnings,
                })
            })
            .collect();
        super::common::print_json(&serde_json::json!({
            "out": args.out.display().to_string(),
            "models": models,
        }))?;
    }
    say!();
    say!(
        "{:<24} {:>9} {:>6} {:>16} {:>10} {:>9} {:>9} | {:>7} {:>9} | {:>10} {:>7} {:>9} {:>16}",
        "",
        "",
        "",
        "",
        "",
        "",
        "",
        "general",
        "skeleton",
        "anatomical",
        "rig",
        "",
        ""
    );
    say!(
        "{:<24} {:>9} {:>6} {:>16} {:>10} {:>9} {:>9} | {:>7} {:>9} | {:>10} {:>7} {:>9} {:>16}",
        "model",
        "triangles",
        "closed",
        "grid",
        "interior",
        "vol err",
        "voxel ms",
        "joints",
        "rig ms",
        "template",
        "joints",
        "rig ms",
        "mean joint error"
    );
    for (name, stats, s, (joints, rig_ms), anatomical, _) in &rows {
        let vol = s
            .mesh_volume
            .map(|v| format!("{:+.2}%", 100.0 * (s.interior_volume - v) / v))
            .unwrap_or_else(|| "n/a".into());
        let error = anatomical
            .error
            .map(|(mean, percent)| format!("{mean:.4} u ({percent:.1}%)"))
            .unwrap_or_else(|| "n/a".into());
        say!(
            "{:<24} {:>9} {:>6} {:>16} {:>10} {:>9} {:>9.1} | {:>7} {:>9.1} | {:>10} {:>7} {:>9.1} {:>16}",
            name,
            stats.triangles,
            if stats.closed { "yes" } else { "no" },
            format!("{}x{}x{}", s.dims[0], s.dims[1], s.dims[2]),
            s.interior_voxels,
            vol,
            s.timings_ms.load + s.timings_ms.voxelize + s.timings_ms.distance,
            joints,
            rig_ms,
            anatomical.template,
            anatomical.joints,
            anatomical.rig_ms,
            error
        );
    }
    say!("mean joint error: of the anatomical rig against the reference rig beside the mesh, in mesh units (u; the bundled models are in metres) and % of the figure's size");
    let (index, _) = super::report::write_index(&args.out, None, Some("skelfit demo"))?;
    say!(
        "results written to {} (index: {})",
        args.out.display(),
        index.display()
    );
    Ok(())
}

/// Rigs one model with the general method (default parameters) and writes
/// `general.glb`, `general.json` and `general.bvh` into `out`. Returns the joint count and the
/// total rig time in milliseconds.
fn rig_general(mesh_path: &Path, out: &Path) -> anyhow::Result<((usize, f64), Vec<Warning>)> {
    let mesh = super::common::load_mesh(mesh_path)?;
    let start = std::time::Instant::now();
    let rig = general_rig(&mesh, &GeneralRigOptions::default())
        .with_context(|| format!("rigging {}", mesh_path.display()))?;
    let rig_ms = start.elapsed().as_secs_f64() * 1e3;
    let glb = out.join("general.glb");
    write_glb(
        &glb,
        &mesh,
        &rig.general.skeleton,
        &rig.skin,
        &GltfOptions::default(),
    )?;
    let json_options = JsonOptions {
        run: Some(super::skeleton::run_info(mesh_path, &rig, 0.0)),
        ..Default::default()
    };
    write_skeleton_json(
        &out.join("general.json"),
        &rig.general.skeleton,
        &json_options,
    )?;
    write_bvh(
        &out.join("general.bvh"),
        &rig.general.skeleton,
        &BvhOptions::default(),
    )?;
    say!(
        "general rig          {} joints, {} segments, {} end effectors in {:.1} ms -> {}",
        rig.general.skeleton.len(),
        rig.general.segments.len(),
        rig.general.end_effectors().len(),
        rig_ms,
        glb.display()
    );
    Ok(((rig.general.skeleton.len(), rig_ms), rig.warnings))
}

/// What the demo reports of an anatomical rig.
struct AnatomicalRow {
    template: String,
    joints: usize,
    rig_ms: f64,
    /// Mean canonical-joint error against the reference rig beside the mesh (mesh units, % of
    /// figure size), when there is one.
    error: Option<(f64, f64)>,
}

/// Rigs one model with the anatomical skeleton (template chosen from the labels) and writes
/// `rig.glb`, `rig.json` (with the canonical map) and `rig.bvh` into `out`; evaluates it
/// against the model's reference rig when one is beside the mesh.
fn rig_anatomical(mesh_path: &Path, out: &Path) -> anyhow::Result<(AnatomicalRow, Vec<Warning>)> {
    let mesh = super::common::load_mesh(mesh_path)?;
    let start = std::time::Instant::now();
    let rigged = rig(&mesh, &RigOptions::default())
        .with_context(|| format!("rigging {} with a template", mesh_path.display()))?;
    let rig_ms = start.elapsed().as_secs_f64() * 1e3;
    let glb = out.join("rig.glb");
    write_glb(
        &glb,
        &mesh,
        &rigged.fit.skeleton,
        &rigged.skin,
        &GltfOptions::default(),
    )?;
    let info = super::rig::run_info(mesh_path, &rigged, 0.0);
    super::rig::write_rig_json(&out.join("rig.json"), mesh_path, &rigged, Some(info))?;
    write_bvh(
        &out.join("rig.bvh"),
        &rigged.fit.skeleton,
        &BvhOptions::default(),
    )?;
    let made = super::bones::rig_bones(&rigged, &mesh)?;
    skelfit::bones::write_bones_glb(
        &out.join("bones.glb"),
        &rigged.fit.skeleton,
        &made,
        Some((&mesh, &rigged.skin)),
        &GltfOptions::default(),
    )?;
    write_file(
        &out.join("bones.svg"),
        skelfit::bones::bones_svg(&made, Some(&mesh), 360.0).as_bytes(),
    )?;
    say!(
        "bone meshes          {} bones -> {}",
        made.bones.len(),
        out.join("bones.glb").display()
    );
    say!(
        "anatomical rig       {} template, {} joints ({} canonical) in {:.1} ms -> {}",
        rigged.fit.template,
        rigged.fit.skeleton.len(),
        rigged.fit.canonical.len(),
        rig_ms,
        glb.display()
    );
    let mut warnings = rigged.warnings.clone();
    warnings.extend(made.warnings.iter().cloned().map(Warning::Bones));
    let error = match reference_beside(mesh_path) {
        Some(reference) => {
            let reference = load_skeleton(&reference)?;
            let mut predicted = ReferenceRig::from_skeleton("rig", rigged.fit.skeleton.clone());
            predicted.canonical = rigged.fit.canonical.clone();
            let options = EvalOptions {
                pairing: JointPairing::IfShared,
                ..Default::default()
            };
            let e = evaluate(&predicted, &reference, Some(&mesh), &options)?;
            if e.has_joint_errors() {
                say!(
                    "                     mean joint error {:.4} ({:.2} % of figure size) over {} joints",
                    e.summary.mean,
                    e.summary_percent.mean,
                    e.joints.len()
                );
                Some((e.summary.mean, e.summary_percent.mean))
            } else {
                say!(
                    "                     no shared joint names: chamfer CD-J2J {:.2} % of figure size",
                    e.chamfer_percent.j2j
                );
                None
            }
        }
        None => None,
    };
    let row = AnatomicalRow {
        template: rigged.fit.template.clone(),
        joints: rigged.fit.skeleton.len(),
        rig_ms,
        error,
    };
    Ok((row, warnings))
}

/// The reference rig beside a mesh: `rig_game_engine.json`, else the only `rig_*.json` (the
/// rule of `skelfit bench`, [`find_bench_models`]).
fn reference_beside(mesh_path: &Path) -> Option<PathBuf> {
    let models = find_bench_models(mesh_path.parent()?, "game_engine").ok()?;
    models.into_iter().next()?.reference
}

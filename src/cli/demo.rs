//! `skelfit demo [--data DIR] [--out DIR]`: the main job on the bundled data.
//!
//! For every `mesh.obj` below the data folder (the refdata layout: `<kind>/<model>/mesh.obj`),
//! prints the mesh statistics, voxelizes it, computes its distance map, fits the general control
//! skeleton and skins the mesh to it, and writes `<out>/<model>/{info.json, voxelize.json,
//! slices/*.png, general.glb, general.json, general.bvh}`; then a summary table.

use super::common::{write_file, VoxelArgs};
use super::voxelize::{print_text, summarize};
use anyhow::Context;
use clap::Args;
use skelfit::export::{
    write_bvh, write_glb, write_skeleton_json, BvhOptions, GltfOptions, JsonOptions,
};
use skelfit::pipeline::{general_rig, GeneralRigOptions};
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
        println!("== {name}");
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
        let rig = rig_general(mesh_path, &out)?;
        rows.push((name, stats, summary, rig));
    }
    println!();
    println!(
        "{:<24} {:>9} {:>6} {:>16} {:>10} {:>9} {:>9} {:>7} {:>9}",
        "model",
        "triangles",
        "closed",
        "grid",
        "interior",
        "vol err",
        "voxel ms",
        "joints",
        "rig ms"
    );
    for (name, stats, s, (joints, rig_ms)) in &rows {
        let vol = s
            .mesh_volume
            .map(|v| format!("{:+.2}%", 100.0 * (s.interior_volume - v) / v))
            .unwrap_or_else(|| "n/a".into());
        println!(
            "{:<24} {:>9} {:>6} {:>16} {:>10} {:>9} {:>9.1} {:>7} {:>9.1}",
            name,
            stats.triangles,
            if stats.closed { "yes" } else { "no" },
            format!("{}x{}x{}", s.dims[0], s.dims[1], s.dims[2]),
            s.interior_voxels,
            vol,
            s.timings_ms.load + s.timings_ms.voxelize + s.timings_ms.distance,
            joints,
            rig_ms
        );
    }
    println!("results written to {}", args.out.display());
    Ok(())
}

/// Rigs one model with the general method (default parameters) and writes
/// `general.glb`, `general.json` and `general.bvh` into `out`. Returns the joint count and the
/// total rig time in milliseconds.
fn rig_general(mesh_path: &Path, out: &Path) -> anyhow::Result<(usize, f64)> {
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
    println!(
        "general rig          {} joints, {} segments, {} end effectors in {:.1} ms -> {}",
        rig.general.skeleton.len(),
        rig.general.segments.len(),
        rig.general.end_effectors().len(),
        rig_ms,
        glb.display()
    );
    for w in &rig.warnings {
        eprintln!("skelfit: warning: {w}");
    }
    Ok((rig.general.skeleton.len(), rig_ms))
}

//! `skelfit demo [--data DIR] [--out DIR]`: the main job on the bundled data.
//!
//! For every `mesh.obj` below the data folder (the refdata layout: `<kind>/<model>/mesh.obj`),
//! prints the mesh statistics, voxelizes it, computes its distance map and writes
//! `<out>/<model>/voxelize.json` and slice pictures; then a summary table.

use super::common::{write_file, VoxelArgs};
use super::voxelize::{print_text, summarize};
use anyhow::Context;
use clap::Args;
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
        rows.push((name, stats, summary));
    }
    println!();
    println!(
        "{:<24} {:>9} {:>6} {:>16} {:>10} {:>9} {:>9}",
        "model", "triangles", "closed", "grid", "interior", "vol err", "total ms"
    );
    for (name, stats, s) in &rows {
        let vol = s
            .mesh_volume
            .map(|v| format!("{:+.2}%", 100.0 * (s.interior_volume - v) / v))
            .unwrap_or_else(|| "n/a".into());
        println!(
            "{:<24} {:>9} {:>6} {:>16} {:>10} {:>9} {:>9.1}",
            name,
            stats.triangles,
            if stats.closed { "yes" } else { "no" },
            format!("{}x{}x{}", s.dims[0], s.dims[1], s.dims[2]),
            s.interior_voxels,
            vol,
            s.timings_ms.load + s.timings_ms.voxelize + s.timings_ms.distance
        );
    }
    println!("results written to {}", args.out.display());
    Ok(())
}

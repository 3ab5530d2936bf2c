//! Time from mesh to skinned general control skeleton against interior voxel count: skelfit's
//! analogue of the dissertation's Table 5.1 and Figure 5.11 (its O2 machine needed 89 s for
//! 353k interior voxels).
//!
//! Rigs the bundled meshes (`data/*/*/mesh.obj`) at a series of voxel sizes (fractions of the
//! longest bounding-box side), each `--repeat` times (default 3, the median is reported), and
//! writes `reports/scaling/scaling.md` and `reports/scaling/scaling.csv`.
//!
//! Run: `cargo run --release --example scaling [-- --repeat N --out DIR --fractions a,b,c]`.
//! Times depend on the machine and its load: compare rows of one run, not runs of two days.

use skelfit::mesh::{load, Mesh};
use skelfit::pipeline::{general_rig, GeneralRigOptions, GeneralSkeletonOptions};
use skelfit::voxel::{VoxelOptions, VoxelSize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Default voxel sizes as fractions of the longest side: from a coarse preview to about
/// 1-2 M interior voxels on the bundled humanoid.
const FRACTIONS: [f64; 6] = [0.02, 0.01, 0.007, 0.005, 0.004, 0.0033];

struct Row {
    model: String,
    fraction: f64,
    grid: [usize; 3],
    interior: usize,
    joints: usize,
    stages: Vec<(String, f64)>,
    total_ms: f64,
}

fn main() {
    if let Err(message) = run() {
        eprintln!("scaling: error: {message}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let mut repeat = 3usize;
    let mut out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("reports/scaling");
    let mut fractions = FRACTIONS.to_vec();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = || args.next().ok_or(format!("{arg} needs a value"));
        match arg.as_str() {
            "--repeat" => {
                repeat = value()?.parse().map_err(|e| format!("--repeat: {e}"))?;
                if repeat == 0 {
                    return Err("--repeat must be at least 1".into());
                }
            }
            "--out" => out = PathBuf::from(value()?),
            "--fractions" => {
                fractions = value()?
                    .split(',')
                    .map(|f| {
                        f.trim()
                            .parse::<f64>()
                            .map_err(|e| format!("--fractions: {e}"))
                    })
                    .collect::<Result<_, _>>()?;
            }
            other => {
                return Err(format!(
                    "unknown argument {other:?} (use --repeat, --out, --fractions)"
                ))
            }
        }
    }
    let models = bundled_models()?;
    let mut rows = Vec::new();
    for (name, mesh) in &models {
        for &fraction in &fractions {
            let row = measure(name, mesh, fraction, repeat)?;
            eprintln!(
                "{:<32} {:>7.4} {:>9} interior voxels {:>9.1} ms",
                row.model, row.fraction, row.interior, row.total_ms
            );
            rows.push(row);
        }
    }
    std::fs::create_dir_all(&out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let threads = rayon::current_num_threads();
    write(&out.join("scaling.csv"), &csv(&rows))?;
    write(&out.join("scaling.md"), &markdown(&rows, repeat, threads))?;
    eprintln!("wrote {}", out.display());
    Ok(())
}

fn write(path: &Path, text: &str) -> Result<(), String> {
    skelfit::output::write_atomic(path, text.as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

fn bundled_models() -> Result<Vec<(String, Mesh)>, String> {
    let data = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data");
    let mut models = Vec::new();
    let mut categories: Vec<_> = std::fs::read_dir(&data)
        .map_err(|e| format!("cannot read {}: {e}", data.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    categories.sort();
    for category in categories {
        let mut dirs: Vec<_> = std::fs::read_dir(&category)
            .map_err(|e| format!("cannot read {}: {e}", category.display()))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.join("mesh.obj").is_file())
            .collect();
        dirs.sort();
        for dir in dirs {
            let mesh =
                load(&dir.join("mesh.obj")).map_err(|e| format!("{}: {e}", dir.display()))?;
            let name = format!(
                "{}/{}",
                category.file_name().unwrap_or_default().to_string_lossy(),
                dir.file_name().unwrap_or_default().to_string_lossy()
            );
            models.push((name, mesh));
        }
    }
    if models.is_empty() {
        return Err(format!("no data/*/*/mesh.obj under {}", data.display()));
    }
    Ok(models)
}

fn measure(name: &str, mesh: &Mesh, fraction: f64, repeat: usize) -> Result<Row, String> {
    let options = GeneralRigOptions {
        skeleton: GeneralSkeletonOptions {
            voxel: VoxelOptions {
                size: VoxelSize::Fraction(fraction),
                max_voxels: 256_000_000,
                ..Default::default()
            },
            ..Default::default()
        },
        ..Default::default()
    };
    let mut runs = Vec::new();
    for _ in 0..repeat {
        let clock = Instant::now();
        let rig = general_rig(mesh, &options).map_err(|e| format!("{name} at {fraction}: {e}"))?;
        runs.push((clock.elapsed().as_secs_f64() * 1e3, rig));
    }
    runs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (total_ms, rig) = runs.swap_remove(repeat / 2);
    Ok(Row {
        model: name.to_string(),
        fraction,
        grid: rig.grid.dims,
        interior: rig.voxels.interior_voxels,
        joints: rig.general.skeleton.len(),
        stages: rig.general.timings.clone(),
        total_ms,
    })
}

fn stage_names(rows: &[Row]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for row in rows {
        for (name, _) in &row.stages {
            if !names.contains(name) {
                names.push(name.clone());
            }
        }
    }
    names
}

fn stage(row: &Row, name: &str) -> f64 {
    row.stages
        .iter()
        .find(|(n, _)| n == name)
        .map_or(f64::NAN, |(_, t)| *t)
}

fn csv(rows: &[Row]) -> String {
    let names = stage_names(rows);
    let mut text = String::from("model,voxel_fraction,grid_x,grid_y,grid_z,interior_voxels,joints");
    for name in &names {
        let _ = write!(text, ",{name}_ms");
    }
    text.push_str(",total_ms,us_per_1k_interior_voxels\n");
    for row in rows {
        let _ = write!(
            text,
            "{},{},{},{},{},{},{}",
            row.model,
            row.fraction,
            row.grid[0],
            row.grid[1],
            row.grid[2],
            row.interior,
            row.joints
        );
        for name in &names {
            let _ = write!(text, ",{:.2}", stage(row, name));
        }
        let _ = writeln!(
            text,
            ",{:.2},{:.1}",
            row.total_ms,
            1e3 * row.total_ms / (row.interior as f64 / 1e3)
        );
    }
    text
}

fn markdown(rows: &[Row], repeat: usize, threads: usize) -> String {
    let names = stage_names(rows);
    let mut text = String::from(
        "# Mesh to skinned general skeleton: time against interior voxels\n\n\
         skelfit's analogue of the dissertation's Table 5.1 / Figure 5.11 (its O2 needed 89 s for \
         353k interior voxels). Target: 1 M interior voxels in at most 1 s end to end.\n\n",
    );
    let _ = writeln!(
        text,
        "Median of {repeat} runs per row, {threads} worker threads, release build. \
         Regenerate: `cargo run --release --example scaling`. Times in ms; `total` is \
         mesh → voxels → distance → medial surface → path tree → skeleton → skin weights.\n"
    );
    text.push_str("| model | voxel size (fraction) | grid | interior voxels | joints |");
    for name in &names {
        let _ = write!(text, " {name} |");
    }
    text.push_str(" total | µs per 1k interior voxels |\n|---|---:|---|---:|---:|");
    for _ in &names {
        text.push_str("---:|");
    }
    text.push_str("---:|---:|\n");
    for row in rows {
        let _ = write!(
            text,
            "| {} | {} | {}×{}×{} | {} | {} |",
            row.model,
            row.fraction,
            row.grid[0],
            row.grid[1],
            row.grid[2],
            row.interior,
            row.joints
        );
        for name in &names {
            let _ = write!(text, " {:.1} |", stage(row, name));
        }
        let _ = writeln!(
            text,
            " {:.1} | {:.1} |",
            row.total_ms,
            1e3 * row.total_ms / (row.interior as f64 / 1e3)
        );
    }
    // The 1 M voxel target, by linear interpolation between the rows that bracket it.
    text.push('\n');
    for model in rows
        .iter()
        .map(|r| r.model.as_str())
        .collect::<std::collections::BTreeSet<_>>()
    {
        let mut points: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.model == model)
            .map(|r| (r.interior as f64, r.total_ms))
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        let bracket = points.windows(2).find(|w| w[0].0 <= 1e6 && w[1].0 >= 1e6);
        match bracket {
            Some(w) => {
                let t = (1e6 - w[0].0) / (w[1].0 - w[0].0);
                let ms = w[0].1 + t * (w[1].1 - w[0].1);
                let _ = writeln!(
                    text,
                    "* {model}: 1 M interior voxels ≈ {ms:.0} ms (interpolated) — target ≤ 1000 ms: {}",
                    if ms <= 1000.0 { "met" } else { "NOT met" }
                );
            }
            None => {
                let _ = writeln!(
                    text,
                    "* {model}: the rows do not bracket 1 M interior voxels (add finer --fractions)"
                );
            }
        }
    }
    text
}

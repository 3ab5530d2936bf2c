//! `skelfit voxelize MESH [--voxel-size F] [--json] [--slices DIR]`.

use super::common::{load_mesh, millis, say, write_file, VoxelArgs};
use anyhow::Context;
use clap::Args;
use serde::Serialize;
use skelfit::distance::{edt, DistanceMap};
use skelfit::report::{distance_slice, png_bytes};
use skelfit::voxel::{voxelize_figure, Solid, VoxelOptions, VoxelReport, VoxelWarning};
use skelfit::warning::Warning;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `skelfit voxelize`.
#[derive(Debug, Args)]
pub struct VoxelizeArgs {
    /// Mesh file (.obj, .gltf, .glb, .stl, .ply).
    pub mesh: PathBuf,
    #[command(flatten)]
    pub voxel: VoxelArgs,
    /// Write PNG pictures of distance-map slices into this folder (created if missing).
    #[arg(long, value_name = "DIR")]
    pub slices: Option<PathBuf>,
}

/// What `skelfit voxelize` reports.
#[derive(Debug, Serialize)]
pub struct VoxelSummary {
    pub mesh: String,
    pub dims: [usize; 3],
    pub voxel_size: f64,
    pub origin: [f64; 3],
    pub interior_voxels: usize,
    pub interior_volume: f64,
    pub mesh_volume: Option<f64>,
    /// Radius of the largest inscribed ball, mesh units: (max distance - 0.5) voxels, since the
    /// surface passes between an interior and an exterior voxel centre.
    pub max_inscribed_radius: f64,
    pub voxels: VoxelReport,
    pub timings_ms: Timings,
    pub slices: Vec<String>,
    pub warnings: Vec<Warning>,
}

#[derive(Debug, Serialize)]
pub struct Timings {
    pub load: f64,
    pub voxelize: f64,
    pub distance: f64,
    pub voxelize_voxels_per_second: f64,
    pub distance_voxels_per_second: f64,
}

/// Voxelizes one mesh, computes its distance map and reports.
pub fn run(args: &VoxelizeArgs) -> anyhow::Result<()> {
    let options = args.voxel.options()?;
    if let Some(dir) = &args.slices {
        super::common::output_folder(dir)?;
    }
    let summary = summarize(&args.mesh, &options, args.slices.as_deref())?;
    if super::common::json_mode() {
        super::common::print_json(&summary)?;
    }
    print_text(&summary);
    Ok(())
}

/// Loads, voxelizes and measures one mesh; writes slice pictures into `slices` if given.
pub fn summarize(
    mesh_path: &Path,
    options: &VoxelOptions,
    slices: Option<&Path>,
) -> anyhow::Result<VoxelSummary> {
    let start = Instant::now();
    let mesh = load_mesh(mesh_path)?;
    let load_ms = millis(start);
    let start = Instant::now();
    let solid = voxelize_figure(&mesh, options).context("voxelizing")?;
    let voxelize_ms = millis(start);
    let start = Instant::now();
    let map = edt(&solid);
    let distance_ms = millis(start);
    let grid = solid.grid;
    let stats = mesh.stats();

    let mut warnings: Vec<Warning> = solid
        .report
        .warnings()
        .into_iter()
        .map(Warning::Voxel)
        .collect();
    if stats.boundary_edges > 0 || stats.non_manifold_edges > 0 {
        warnings.push(
            VoxelWarning::OpenMesh {
                boundary_edges: stats.boundary_edges,
                non_manifold_edges: stats.non_manifold_edges,
                ambiguous_voxels: solid.report.ambiguous_voxels,
            }
            .into(),
        );
    }
    let slices = match slices {
        Some(dir) => write_slices(dir, &solid, &map)?,
        None => Vec::new(),
    };
    let voxels = grid.len() as f64;
    let summary = VoxelSummary {
        mesh: mesh_path.display().to_string(),
        dims: grid.dims,
        voxel_size: grid.voxel_size,
        origin: grid.origin.to_array(),
        interior_voxels: solid.interior_count(),
        interior_volume: solid.interior_volume(),
        mesh_volume: stats.signed_volume,
        max_inscribed_radius: (map.max_distance() - 0.5).max(0.0) * grid.voxel_size,
        voxels: solid.report.clone(),
        timings_ms: Timings {
            load: load_ms,
            voxelize: voxelize_ms,
            distance: distance_ms,
            voxelize_voxels_per_second: voxels / (voxelize_ms / 1e3),
            distance_voxels_per_second: voxels / (distance_ms / 1e3),
        },
        slices,
        warnings,
    };
    Ok(summary)
}

/// Prints a summary as aligned text (warnings to stderr).
pub fn print_text(s: &VoxelSummary) {
    say!("mesh                 {}", s.mesh);
    say!(
        "grid                 {} x {} x {} voxels of {:.6} (origin {:?})",
        s.dims[0],
        s.dims[1],
        s.dims[2],
        s.voxel_size,
        s.origin
    );
    say!("interior voxels      {}", s.interior_voxels);
    match s.mesh_volume {
        Some(v) => say!(
            "interior volume      {:.6} (mesh {:.6}, {:+.2} %)",
            s.interior_volume,
            v,
            100.0 * (s.interior_volume - v) / v
        ),
        None => say!("interior volume      {:.6}", s.interior_volume),
    }
    say!("max inscribed radius {:.6}", s.max_inscribed_radius);
    say!(
        "timings              load {:.1} ms, voxelize {:.1} ms ({:.1} M voxels/s), distance {:.1} ms ({:.1} M voxels/s)",
        s.timings_ms.load,
        s.timings_ms.voxelize,
        s.timings_ms.voxelize_voxels_per_second / 1e6,
        s.timings_ms.distance,
        s.timings_ms.distance_voxels_per_second / 1e6
    );
    for path in &s.slices {
        say!("wrote                {path}");
    }
    super::common::print_warnings(&s.warnings);
}

/// Writes five slices across the up axis (y) through the interior and one x and one z slice
/// through the deepest voxel.
fn write_slices(dir: &Path, solid: &Solid, map: &DistanceMap) -> anyhow::Result<Vec<String>> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let grid = solid.grid;
    let interior = solid.interior_indices();
    let (lo, hi) = interior
        .iter()
        .map(|&i| grid.coords(i)[1])
        .fold((usize::MAX, 0), |(lo, hi), y| (lo.min(y), hi.max(y)));
    let deepest = grid.coords(map.deepest());
    let scale = (768 / grid.dims.iter().copied().max().unwrap_or(1).max(1)).clamp(1, 16) as u32;
    let mut picks: Vec<(usize, usize)> = (1..=5).map(|k| (1, lo + (hi - lo) * k / 6)).collect();
    picks.push((0, deepest[0]));
    picks.push((2, deepest[2]));
    let mut written = Vec::new();
    for (axis, index) in picks {
        let image = distance_slice(map, Some(solid), axis, index, scale);
        let name = format!("slice_{}_{:04}.png", ["x", "y", "z"][axis], index);
        let path = dir.join(name);
        write_file(&path, &png_bytes(&image)?)?;
        written.push(path.display().to_string());
    }
    Ok(written)
}

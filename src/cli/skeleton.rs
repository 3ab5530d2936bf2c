//! `skelfit skeleton MESH -o OUT.glb [--skeleton-json OUT.json] [--bvh OUT.bvh] [parameters]`:
//! the general control skeleton of any figure (dissertation ch.5), skinned and exported;
//! `--json` prints the skeleton JSON on stdout.

use super::common::{load_mesh, require_mesh_output, say, Outputs, VoxelArgs};
use super::simplify::LodArgs;
use anyhow::Context;
use clap::Args;
use serde_json::json;
use skelfit::export::{bvh_text, glb_bytes, skeleton_json, BvhOptions, GltfOptions, JsonOptions};
use skelfit::pipeline::{general_rig, GeneralRig, GeneralRigOptions};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Arguments of `skelfit skeleton`.
#[derive(Debug, Args)]
pub struct SkeletonArgs {
    /// Mesh file (.obj, .gltf, .glb, .stl, .ply).
    pub mesh: PathBuf,
    /// Skinned binary glTF to write (mesh, armature, weights).
    #[arg(short, long, value_name = "OUT.glb")]
    pub output: PathBuf,
    /// Also write the skeleton as skelfit JSON (with stage timings under "run"; `--json`
    /// prints the same on stdout).
    #[arg(long, value_name = "OUT.json")]
    pub skeleton_json: Option<PathBuf>,
    /// Also write the skeleton as BVH.
    #[arg(long, value_name = "OUT.bvh")]
    pub bvh: Option<PathBuf>,
    #[command(flatten)]
    pub voxel: VoxelArgs,
    /// Exposure threshold of the medial surface, [0, 2] (Table 5.2: default 0.5).
    #[arg(long, value_name = "F")]
    pub exposure: Option<f64>,
    /// Closeness of fit: minimum branch length as a fraction of the heart radius, [0, 1]
    /// (Table 5.2: default 0.1).
    #[arg(long, value_name = "F")]
    pub closeness: Option<f64>,
    /// Approximation error of skeletal edges, voxels (Table 5.2: default 0.4).
    #[arg(long, value_name = "F")]
    pub approx_error: Option<f64>,
    /// Chains shorter than this fraction of the heart radius are not split (default 0.1).
    #[arg(long, value_name = "F")]
    pub min_fraction: Option<f64>,
    /// Chains longer than this fraction of the heart radius are always split (default 0.3).
    #[arg(long, value_name = "F")]
    pub max_fraction: Option<f64>,
    /// Maximum number of segments (default: automatic).
    #[arg(long, value_name = "N")]
    pub segments: Option<usize>,
    /// Put the root joint at the lowest end point instead of a deep segment (ch.5.3).
    #[arg(long)]
    pub root_at_lowest: bool,
    #[command(flatten)]
    pub lod: LodArgs,
}

impl SkeletonArgs {
    /// Validated pipeline options (ranges are checked by the library before any work).
    pub fn options(&self) -> anyhow::Result<GeneralRigOptions> {
        let mut options = GeneralRigOptions::default();
        options.skeleton.voxel = self.voxel.options()?;
        if let Some(v) = self.exposure {
            options.skeleton.medial.exposure_threshold = v;
        }
        if let Some(v) = self.closeness {
            options.skeleton.paths.closeness = v;
        }
        let general = &mut options.skeleton.general;
        if let Some(v) = self.approx_error {
            general.approximation_error = v;
        }
        if let Some(v) = self.min_fraction {
            general.min_fraction = v;
        }
        if let Some(v) = self.max_fraction {
            general.max_fraction = v;
        }
        general.segments = self.segments;
        general.root_at_lowest = self.root_at_lowest;
        Ok(options)
    }
}

/// A spinner on stderr while `work` runs (drawn only when stderr is a terminal).
pub fn with_spinner<T>(message: String, work: impl FnOnce() -> T) -> T {
    let spinner = if super::common::quiet() {
        indicatif::ProgressBar::hidden()
    } else {
        indicatif::ProgressBar::new_spinner()
    };
    spinner.set_message(message);
    spinner.enable_steady_tick(Duration::from_millis(120));
    let out = work();
    spinner.finish_and_clear();
    out
}

/// Runs the command.
pub fn run(args: &SkeletonArgs) -> anyhow::Result<()> {
    let options = args.options()?;
    let mut outputs = Outputs::check(
        [
            Some(args.output.as_path()),
            args.skeleton_json.as_deref(),
            args.bvh.as_deref(),
        ]
        .into_iter()
        .flatten(),
        [args.mesh.as_path()],
    )?;
    require_mesh_output(&args.output, "-o")?;
    let start = Instant::now();
    let mesh = load_mesh(&args.mesh)?;
    let load_ms = start.elapsed().as_secs_f64() * 1e3;
    let mut rig = with_spinner(format!("rigging {}", args.mesh.display()), || {
        general_rig(&mesh, &options)
    })
    .context("fitting the general control skeleton")?;
    apply_lod(&mesh, &mut rig, &args.lod, &options)?;
    let clock = Instant::now();
    outputs.add_mesh(
        &args.output,
        glb_bytes(
            &mesh,
            &rig.general.skeleton,
            &rig.skin,
            &GltfOptions::default(),
        )?,
    )?;
    let run = run_info(&args.mesh, &rig, load_ms);
    let json_options = JsonOptions {
        model: model_name(&args.mesh),
        run: Some(run),
        ..Default::default()
    };
    let json_text = skeleton_json(&rig.general.skeleton, &json_options)?;
    if let Some(path) = &args.skeleton_json {
        outputs.add(path, json_text.clone());
    }
    if let Some(path) = &args.bvh {
        outputs.add(
            path,
            bvh_text(&rig.general.skeleton, &BvhOptions::default())?,
        );
    }
    outputs.write()?;
    let export_ms = clock.elapsed().as_secs_f64() * 1e3;
    if super::common::json_mode() {
        println!("{}", json_text.trim_end());
    }
    print_summary(args, &rig, load_ms, export_ms);
    super::common::print_warnings(&rig.warnings);
    Ok(())
}

/// Applies the level-of-detail options (seed 003) to the fitted skeleton and skins the mesh
/// again to the coarser bones (the chain voxels of merged segments no longer exist).
fn apply_lod(
    mesh: &skelfit::mesh::Mesh,
    rig: &mut GeneralRig,
    lod: &LodArgs,
    options: &GeneralRigOptions,
) -> anyhow::Result<()> {
    let lod = lod.options();
    if lod.is_identity() {
        return Ok(());
    }
    let clock = Instant::now();
    let skeleton = skelfit::lod::level_of_detail(&rig.general.skeleton, &lod)
        .context("applying level of detail")?;
    let solid = skelfit::voxel::voxelize_figure(mesh, &options.skeleton.voxel)?;
    let distance = skelfit::distance::edt(&solid);
    rig.skin = skelfit::skin::skin_from_bones(mesh, &skeleton, &solid, &distance, &options.skin)
        .context("skinning the mesh to the simplified skeleton")?;
    rig.general.skeleton = skeleton;
    // The chain segments belong to the joints before simplification.
    rig.general.segments.clear();
    rig.general
        .timings
        .push(("lod".to_string(), clock.elapsed().as_secs_f64() * 1e3));
    Ok(())
}

/// The model name of a mesh path: its stem, or its folder for refdata's `<model>/mesh.obj`.
pub fn model_name(path: &Path) -> Option<String> {
    let stem = path.file_stem()?.to_string_lossy().into_owned();
    if stem == "mesh" {
        // refdata layout: <kind>/<model>/mesh.obj
        path.parent()?
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
    } else {
        Some(stem)
    }
}

/// Run information: sizes, stage timings and warnings.
pub fn run_info(mesh: &Path, rig: &GeneralRig, load_ms: f64) -> serde_json::Value {
    let mut timings = serde_json::Map::new();
    timings.insert("load".into(), json!(load_ms));
    for (stage, ms) in &rig.general.timings {
        timings.insert(stage.clone(), json!(ms));
    }
    json!({
        "mesh": mesh.display().to_string(),
        "grid": rig.grid.dims,
        "voxel_size": rig.grid.voxel_size,
        "interior_voxels": rig.voxels.interior_voxels,
        "joints": rig.general.skeleton.len(),
        "segments": rig.general.segments.len(),
        "end_effectors": rig.general.end_effectors().len(),
        "heart_radius": rig.general.path_tree.heart_radius,
        "timings_ms": timings,
        "warnings": rig.warnings,
    })
}

fn print_summary(args: &SkeletonArgs, rig: &GeneralRig, load_ms: f64, export_ms: f64) {
    let g = &rig.general;
    say!("mesh            {}", args.mesh.display());
    say!(
        "grid            {} x {} x {} ({} interior voxels of {:.6})",
        rig.grid.dims[0],
        rig.grid.dims[1],
        rig.grid.dims[2],
        rig.voxels.interior_voxels,
        rig.grid.voxel_size
    );
    say!(
        "skeleton        {} joints, {} segments, {} end effectors",
        g.skeleton.len(),
        g.segments.len(),
        g.end_effectors().len()
    );
    let stages: Vec<String> = std::iter::once(format!("load {load_ms:.1}"))
        .chain(g.timings.iter().map(|(s, ms)| format!("{s} {ms:.1}")))
        .chain(std::iter::once(format!("export {export_ms:.1}")))
        .collect();
    say!("timings (ms)    {}", stages.join(", "));
    say!("wrote           {}", args.output.display());
    for path in [&args.skeleton_json, &args.bvh].into_iter().flatten() {
        say!("wrote           {}", path.display());
    }
}

//! `skelfit outline OUTLINE.(csv|svg)... -o OUT.glb [--thickness F] [--svg OUT.svg]
//! [--json OUT.json] [level-of-detail options]`: animatable skeletons from closed 2D outlines
//! (seed 003), inflated into a skinned 3D model.

use super::common::{millis, require_mesh_output, say, Outputs};
use super::simplify::LodArgs;
use anyhow::Context;
use clap::Args;
use glam::{DAffine3, DQuat, DVec3};
use serde_json::json;
use skelfit::distance::edt;
use skelfit::export::{glb_bytes, skeleton_json, GltfOptions, JsonOptions};
use skelfit::lod::level_of_detail;
use skelfit::mesh::Mesh;
use skelfit::outline::{
    assemble, outline_part, outline_svg, read_outline, OutlineOptions, PartPlacement,
};
use skelfit::skeleton::Skeleton;
use skelfit::skin::{skin_from_bones, Skin, SkinOptions};
use skelfit::voxel::{voxelize, VoxelOptions, VoxelSize};
use skelfit::warning::Warning;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `skelfit outline`.
#[derive(Debug, Args)]
pub struct OutlineArgs {
    /// Closed outlines (.csv of x,y rows or .svg with one path), in modelling order; all are
    /// drawn in the same XY plane and parts that overlap are connected.
    #[arg(required = true)]
    pub outlines: Vec<PathBuf>,
    /// Skinned binary glTF to write (inflated mesh, armature, weights).
    #[arg(short, long, value_name = "OUT.glb")]
    pub output: PathBuf,
    /// Thickness of the inflated mesh (height parameter; 1 = round cross-sections).
    #[arg(long, value_name = "F", default_value_t = 1.0)]
    pub thickness: f64,
    /// Douglas-Peucker tolerance of the polygon, fraction of the outline's diagonal.
    #[arg(long, value_name = "F")]
    pub tolerance: Option<f64>,
    /// Initial BoundedDP threshold along branches, fraction of the diagonal.
    #[arg(long, value_name = "F")]
    pub joint_error: Option<f64>,
    /// Also write a picture of outline, straight skeleton and bones (one per outline:
    /// OUT.svg, OUT_2.svg, ...).
    #[arg(long, value_name = "OUT.svg")]
    pub svg: Option<PathBuf>,
    /// Also write the skeleton as skelfit JSON (`--json` prints a summary on stdout).
    #[arg(long, value_name = "OUT.json")]
    pub skeleton_json: Option<PathBuf>,
    /// Voxels along the longest side for skinning.
    #[arg(long, value_name = "N", default_value_t = 96)]
    pub resolution: u32,
    /// Place outline N (1-based, modelling order) in 3D: rotate it by YAW degrees about +Y,
    /// then move it by (X, Y, Z). Repeat for several outlines; unplaced outlines stay in the
    /// XY plane as drawn.
    #[arg(long, value_name = "N:X,Y,Z[,YAW]")]
    pub place: Vec<String>,
    #[command(flatten)]
    pub lod: LodArgs,
}

fn svg_path(base: &Path, k: usize) -> PathBuf {
    if k == 0 {
        return base.to_path_buf();
    }
    let stem = base
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let ext = base
        .extension()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "svg".into());
    base.with_file_name(format!("{stem}_{}.{ext}", k + 1))
}

/// Parses `--place N:X,Y,Z[,YAW]` values into one placement per outline.
fn placements(values: &[String], count: usize) -> anyhow::Result<Vec<PartPlacement>> {
    let mut out = vec![PartPlacement::default(); count];
    for value in values {
        let bad = || {
            anyhow::anyhow!(
                "--place {value:?} is not N:X,Y,Z[,YAW] with N an outline number from 1 to {count}"
            )
        };
        let (index, rest) = value.split_once(':').ok_or_else(bad)?;
        let index: usize = index.trim().parse().map_err(|_| bad())?;
        let numbers: Vec<f64> = rest
            .split(',')
            .map(|s| s.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| bad())?;
        if index == 0 || index > count || !(3..=4).contains(&numbers.len()) {
            return Err(bad());
        }
        if numbers.iter().any(|x| !x.is_finite()) {
            return Err(bad());
        }
        let yaw = numbers.get(3).copied().unwrap_or(0.0).to_radians();
        out[index - 1] = PartPlacement {
            transform: DAffine3::from_rotation_translation(
                DQuat::from_rotation_y(yaw),
                DVec3::new(numbers[0], numbers[1], numbers[2]),
            ),
        };
    }
    Ok(out)
}

/// Skins the inflated `mesh` to `skeleton` by voxel distance, with voxels of 1/`resolution`
/// of the longest side (at most 1/8).
fn skin_inflated(mesh: &Mesh, skeleton: &Skeleton, resolution: u32) -> anyhow::Result<Skin> {
    let voxel = VoxelOptions {
        size: VoxelSize::Fraction(1.0 / f64::from(resolution.max(8))),
        ..Default::default()
    };
    let solid = voxelize(mesh, &voxel).context("voxelizing the inflated mesh")?;
    let distance = edt(&solid);
    skin_from_bones(mesh, skeleton, &solid, &distance, &SkinOptions::default())
        .context("skinning the inflated mesh")
}

/// Runs the command.
pub fn run(args: &OutlineArgs) -> anyhow::Result<()> {
    let mut options = OutlineOptions::default();
    options.inflate.thickness = args.thickness;
    if let Some(t) = args.tolerance {
        options.polygon_tolerance = t;
    }
    if let Some(e) = args.joint_error {
        options.bounded_dp.epsilon = e;
    }
    let lod = args.lod.options();
    options.validate().context("checking the options")?;
    lod.validate()
        .context("checking the level-of-detail options")?;
    let svgs: Vec<PathBuf> = match &args.svg {
        Some(svg) => (0..args.outlines.len()).map(|k| svg_path(svg, k)).collect(),
        None => Vec::new(),
    };
    let mut outputs = Outputs::check(
        std::iter::once(args.output.as_path())
            .chain(args.skeleton_json.as_deref())
            .chain(svgs.iter().map(PathBuf::as_path)),
        args.outlines.iter().map(PathBuf::as_path),
    )?;
    require_mesh_output(&args.output, "-o")?;
    let start = Instant::now();
    let mut parts = Vec::new();
    let mut skeleton_ms = 0.0;
    for (k, path) in args.outlines.iter().enumerate() {
        let outline = read_outline(path, &options)
            .with_context(|| format!("reading outline {}", path.display()))?;
        let clock = Instant::now();
        let part = outline_part(&outline, &options)
            .with_context(|| format!("building the skeleton of {}", path.display()))?;
        skeleton_ms += millis(clock);
        if let Some(file) = svgs.get(k) {
            outputs.add(file, outline_svg(&part.skeleton));
        }
        parts.push(part);
    }
    let placements = placements(&args.place, parts.len())?;
    let assembly = assemble(&parts, &placements).context("connecting the parts")?;
    let skeleton = if lod.is_identity() {
        assembly.skeleton.clone()
    } else {
        level_of_detail(&assembly.skeleton, &lod).context("applying level of detail")?
    };
    let clock = Instant::now();
    let skin = skin_inflated(&assembly.mesh, &skeleton, args.resolution)?;
    let skin_ms = millis(clock);
    outputs.add_mesh(
        &args.output,
        glb_bytes(&assembly.mesh, &skeleton, &skin, &GltfOptions::default())?,
    )?;
    if let Some(path) = &args.skeleton_json {
        let model = args.outlines[0]
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned());
        outputs.add(
            path,
            skeleton_json(
                &skeleton,
                &JsonOptions {
                    model,
                    ..Default::default()
                },
            )?,
        );
    }
    outputs.write()?;
    let skin_warnings: Vec<Warning> = skin.warnings.iter().cloned().map(Warning::Skin).collect();
    let summary = json!({
        "outlines": args.outlines.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
        "polygon_corners": parts.iter().map(|p| p.skeleton.polygon.len()).collect::<Vec<_>>(),
        "joints": skeleton.len(),
        "vertices": assembly.mesh.positions.len(),
        "triangles": assembly.mesh.triangles.len(),
        "parent_part": assembly.parent_part,
        "timings_ms": {"skeleton_and_inflate": skeleton_ms, "skin": skin_ms, "total": millis(start)},
        "warnings": skin_warnings,
    });
    if super::common::json_mode() {
        super::common::print_json(&summary)?;
    }
    say!("outlines        {}", args.outlines.len());
    say!("joints          {}", skeleton.len());
    say!(
        "mesh            {} vertices, {} triangles",
        assembly.mesh.positions.len(),
        assembly.mesh.triangles.len()
    );
    say!("timings (ms)    skeleton+inflate {skeleton_ms:.1}, skin {skin_ms:.1}");
    for path in std::iter::once(&args.output).chain(args.skeleton_json.iter()) {
        say!("wrote           {}", path.display());
    }
    super::common::print_warnings(&skin_warnings);
    Ok(())
}

//! `skelfit study tessellation MESH --reference REF [--levels ...]` and
//! `skelfit study rotation MESH --reference REF [--n 8]`: robustness of the rig to re-meshing and
//! to rigid rotations, as tables (CSV, Markdown, JSON) and an HTML page with a plot.

use super::bench::{command_line, MethodArg};
use super::common::{load_mesh, write_file, VoxelArgs};
use anyhow::Context;
use clap::{Args, Subcommand};
use skelfit::eval::{
    evaluate, load_skeleton, rotation_study, study_csv, study_markdown, study_table,
    tessellation_study, to_json, ReferenceRig, Study, StudyOptions,
};
use skelfit::report::{study_html, ReportInput};
use std::path::PathBuf;

/// Arguments of `skelfit study`.
#[derive(Debug, Args)]
pub struct StudyArgs {
    #[command(subcommand)]
    pub kind: StudyKindArgs,
}

/// Which study.
#[derive(Debug, Subcommand)]
pub enum StudyKindArgs {
    /// Rig decimated and subdivided variants of a mesh and report joint displacement from the
    /// base rig and error to the reference per level.
    Tessellation(TessellationArgs),
    /// Rig rigidly rotated copies of a mesh, rotate the joints back and report their
    /// displacement from the unrotated rig (rotational invariance).
    Rotation(RotationArgs),
}

/// Arguments shared by the studies.
#[derive(Debug, Args)]
pub struct StudyCommon {
    /// Mesh file (.obj, .gltf, .glb, .stl, .ply).
    pub mesh: PathBuf,
    /// Reference skeleton of the mesh (.json, .bvh, .glb): adds the error to it per variant.
    #[arg(long, value_name = "REF")]
    pub reference: Option<PathBuf>,
    /// Rigging method.
    #[arg(long, value_enum, default_value_t = MethodArg::General)]
    pub method: MethodArg,
    /// Output folder (created if missing) for <study>.csv, .md, .json and .html.
    #[arg(long, default_value = "reports/study")]
    pub out: PathBuf,
    /// Also write a self-contained HTML page with the displacement plot.
    #[arg(long)]
    pub html: bool,
    /// Meshes drawn in the HTML page are decimated to about this many triangles.
    #[arg(long, value_name = "N", default_value_t = 3000)]
    pub page_triangles: usize,
    #[command(flatten)]
    pub voxel: VoxelArgs,
}

/// Arguments of `skelfit study tessellation`.
#[derive(Debug, Args)]
pub struct TessellationArgs {
    #[command(flatten)]
    pub common: StudyCommon,
    /// Triangle ratios of the variants (1 = the mesh as given, always included as the base).
    #[arg(long, value_delimiter = ',', default_values_t = [0.1, 0.25, 0.5, 1.0, 2.0])]
    pub levels: Vec<f64>,
}

/// Arguments of `skelfit study rotation`.
#[derive(Debug, Args)]
pub struct RotationArgs {
    #[command(flatten)]
    pub common: StudyCommon,
    /// Number of rotations: k·360°/n for k = 0..n (k = 0 is the base).
    #[arg(long, default_value_t = 8)]
    pub n: usize,
    /// Rotation axis x,y,z (default the up axis +Y).
    #[arg(long, value_delimiter = ',', num_args = 1, allow_hyphen_values = true, default_values_t = [0.0, 1.0, 0.0])]
    pub axis: Vec<f64>,
}

/// Runs the command.
pub fn run(args: &StudyArgs) -> anyhow::Result<()> {
    match &args.kind {
        StudyKindArgs::Tessellation(a) => {
            run_study(&a.common, "tessellation", |mesh, name, r, o| {
                Ok(tessellation_study(mesh, name, r, &a.levels, o)?)
            })
        }
        StudyKindArgs::Rotation(a) => {
            let [x, y, z] = a.axis[..] else {
                anyhow::bail!("--axis takes three numbers x,y,z (got {:?})", a.axis);
            };
            run_study(&a.common, "rotation", |mesh, name, r, o| {
                Ok(rotation_study(
                    mesh,
                    name,
                    r,
                    a.n,
                    glam::DVec3::new(x, y, z),
                    o,
                )?)
            })
        }
    }
}

fn run_study(
    common: &StudyCommon,
    kind: &str,
    study: impl Fn(
        &skelfit::mesh::Mesh,
        &str,
        Option<&ReferenceRig>,
        &StudyOptions,
    ) -> anyhow::Result<Study>,
) -> anyhow::Result<()> {
    let mut options = StudyOptions::default();
    options.rigger.method = common.method.into();
    options.rigger.general.voxel = common.voxel.options()?;
    super::common::output_folder(&common.out)?;
    let mesh = load_mesh(&common.mesh)?;
    let reference = match &common.reference {
        Some(path) => Some(
            load_skeleton(path)
                .with_context(|| format!("loading the reference skeleton {}", path.display()))?,
        ),
        None => None,
    };
    let name = model_name(&common.mesh);
    let result = super::skeleton::with_spinner(format!("{kind} study of {name}"), || {
        study(&mesh, &name, reference.as_ref(), &options)
    })
    .with_context(|| format!("{kind} study of {}", common.mesh.display()))?;
    std::fs::create_dir_all(&common.out)
        .with_context(|| format!("creating {}", common.out.display()))?;
    let title = format!("skelfit {kind} study: {name}");
    let preamble = format!(
        "Generated by `{}` (skelfit {}).",
        command_line(),
        env!("CARGO_PKG_VERSION")
    );
    let out = |ext: &str| common.out.join(format!("{kind}.{ext}"));
    write_file(&out("csv"), study_csv(&result)?.as_bytes())?;
    write_file(
        &out("md"),
        study_markdown(&result, &title, &preamble).as_bytes(),
    )?;
    write_file(&out("json"), (to_json(&result)? + "\n").as_bytes())?;
    if common.html {
        let page_mesh = if mesh.triangles.len() > common.page_triangles && common.page_triangles > 0
        {
            mesh.decimated(common.page_triangles as f64 / mesh.triangles.len() as f64)
        } else {
            mesh.clone()
        };
        let base = result.base().and_then(|b| {
            let reference = reference.as_ref()?.deforming();
            let predicted =
                ReferenceRig::from_skeleton(name.clone(), b.skeleton.clone()?).deforming();
            let evaluation = b
                .to_reference
                .clone()
                .or_else(|| evaluate(&predicted, &reference, Some(&mesh), &options.eval).ok())?;
            Some((evaluation, predicted, reference))
        });
        let input = base
            .as_ref()
            .map(|(evaluation, predicted, reference)| ReportInput {
                evaluation,
                predicted,
                reference,
                mesh: Some(&page_mesh),
            });
        write_file(
            &out("html"),
            study_html(&result, &title, &preamble, input.as_ref()).as_bytes(),
        )?;
    }
    if super::common::json_mode() {
        super::common::print_json(&result)?;
    }
    super::common::say!("{}", study_table(&result).plain().trim_end());
    super::common::say!("tables in {}", common.out.display());
    for v in &result.variants {
        if let Some(f) = &v.failure {
            super::common::warn(
                &format!("variant {} failed: {f}", v.label),
                "study",
                "part_missing",
            );
        }
    }
    Ok(())
}

fn model_name(path: &std::path::Path) -> String {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "model".into());
    if stem == "mesh" {
        if let Some(dir) = path.parent().and_then(|p| p.file_name()) {
            return dir.to_string_lossy().into_owned();
        }
    }
    stem
}

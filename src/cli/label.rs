//! `skelfit label MESH -o labels.json [--up +Y] [--forward +Z|auto] [--labels OVERRIDE.json]
//! [--ply OUT.ply] [--svg OUT.svg] [--vertex-labels skin|bones|medial]`: body-part labels
//! (dissertation ch.7); and
//! `skelfit label --table REFDATA -o DIR`: the labelling accuracy table over reference models.

use super::common::{load_mesh, write_file, Outputs, VoxelArgs};
use anyhow::{bail, Context};
use clap::{Args, ValueEnum};
use skelfit::anatomy::{
    label_with_overrides, labels_json, labels_ply, labels_svg, LabelPipelineOptions, Overrides,
};
use skelfit::eval::{label_table_json, label_table_markdown, label_table_models, label_table_row};
use skelfit::pipeline::{label_by_bones, label_by_skin, RigOptions, RigWarning};
use skelfit::warning::Warning;
use std::path::{Path, PathBuf};

/// Where the per-mesh-vertex labels come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub enum VertexLabels {
    /// From the rig fitted to the labels (`skelfit rig`): each vertex takes the part whose
    /// bones carry most of its skin weight (else its nearest bone's), so a vertex's part is
    /// that of the bones that move it; the medial labels when no rig can be fitted (with a
    /// warning) or the figure got the general skeleton.
    #[default]
    Skin,
    /// From the same rig, each vertex the part of its nearest bone.
    Bones,
    /// From the labelled medial surface through the interior voxels (dissertation ch.7).
    Medial,
}

/// Arguments of `skelfit label`.
#[derive(Debug, Args)]
pub struct LabelArgs {
    /// Mesh file (.obj, .gltf, .glb, .stl, .ply); not with --table.
    #[arg(required_unless_present = "table")]
    pub mesh: Option<PathBuf>,
    /// labels.json to write (with --table: the folder for the table).
    #[arg(short, long, value_name = "OUT")]
    pub output: PathBuf,
    /// Up direction: an axis (+Y, -Z, ...), a vector x,y,z, or `auto` (found from the figure:
    /// +Y when it stands on its legs under +Y, else the axis under which it does; the choice
    /// and its confidence are reported).
    #[arg(
        long,
        value_name = "DIR",
        default_value = "auto",
        allow_hyphen_values = true
    )]
    pub up: String,
    /// Forward direction: an axis, a vector x,y,z, or `auto` (the file's convention, +Z turned
    /// with the up found, unless the figure's paired limbs, feet or head and tail show it faces
    /// another way; the choice and its confidence are reported).
    #[arg(
        long,
        value_name = "DIR",
        default_value = "auto",
        allow_hyphen_values = true
    )]
    pub forward: String,
    /// A labels override file (JSON) correcting sections (see ARCHITECTURE.md).
    #[arg(long, value_name = "OVERRIDE.json")]
    pub labels: Option<PathBuf>,
    /// Also write the mesh as PLY with a colour per vertex by body part.
    #[arg(long, value_name = "OUT.ply")]
    pub ply: Option<PathBuf>,
    /// Also write an SVG picture (front, side, top) with the level graph by label.
    #[arg(long, value_name = "OUT.svg")]
    pub svg: Option<PathBuf>,
    /// Number of heart-value bins of the level graph (default 20, ch.7.3.1).
    #[arg(long, value_name = "N")]
    pub bins: Option<usize>,
    /// Major junctions merge regions each holding at least this fraction of the DMS voxels
    /// (default 0.02, ch.7.3.2).
    #[arg(long, value_name = "F")]
    pub junction_fraction: Option<f64>,
    /// Interior voxels go to the DMS voxel minimising path length minus this multiple of its
    /// inscribed radius, in [0, 1] (default 0).
    #[arg(long, value_name = "F")]
    pub radius_weight: Option<f64>,
    /// Keep the neck (trunk between the arms' or fore legs' junction and the head's) in the
    /// trunk in the per-vertex labels; by default it goes to the head.
    #[arg(long)]
    pub neck_in_trunk: bool,
    /// Arms' and fore legs' DMS voxels within this multiple of a trunk voxel's inscribed
    /// radius count as trunk in the per-vertex labels, in [0, 1] (default 0.4; 0 = off).
    #[arg(long, value_name = "F")]
    pub pectoral_root_scale: Option<f64>,
    /// Per-vertex labels from the skin weights of the anatomical skeleton fitted to the labels
    /// (`skin`, default: runs `skelfit rig`), from its nearest bone (`bones`) or from the labelled medial surface
    /// (`medial`, dissertation ch.7).
    #[arg(long, value_enum, default_value_t = VertexLabels::Skin)]
    pub vertex_labels: VertexLabels,
    /// Regenerate the accuracy table over the reference models below this folder
    /// (`<kind>/<model>/mesh.obj` + `rig_*.json`); writes labels.md and labels.json to -o.
    #[arg(long, value_name = "REFDATA", conflicts_with_all = ["mesh", "labels", "ply", "svg"])]
    pub table: Option<PathBuf>,
    #[command(flatten)]
    pub voxel: VoxelArgs,
}

impl LabelArgs {
    /// Validated options.
    pub fn options(&self) -> anyhow::Result<LabelPipelineOptions> {
        let mut stages = LabelPipelineOptions {
            voxel: self.voxel.options()?,
            ..Default::default()
        };
        let options = &mut stages.label;
        options.up = super::common::parse_up(&self.up)?;
        options.forward = super::common::parse_forward(&self.forward)?;
        if let Some(j) = self.junction_fraction {
            options.level.junction_fraction = j;
        }
        if let Some(w) = self.radius_weight {
            options.level.radius_weight = w;
        }
        options.rules.neck_in_head = !self.neck_in_trunk;
        if let Some(s) = self.pectoral_root_scale {
            options.rules.pectoral_root_scale = s;
        }
        if let Some(b) = self.bins {
            options.level.bins = b;
        }
        options.validate()?;
        Ok(stages)
    }
}

/// Runs the command.
pub fn run(args: &LabelArgs) -> anyhow::Result<()> {
    let options = args.options()?;
    if let Some(dir) = &args.table {
        return table(dir, &args.output, &options);
    }
    let Some(mesh_path) = &args.mesh else {
        bail!("give a MESH or --table REFDATA");
    };
    let mut outputs = Outputs::check(
        [
            Some(args.output.as_path()),
            args.ply.as_deref(),
            args.svg.as_deref(),
        ]
        .into_iter()
        .flatten(),
        [Some(mesh_path.as_path()), args.labels.as_deref()]
            .into_iter()
            .flatten(),
    )?;
    let (mesh, source) = skelfit::mesh::load_with_source_map(mesh_path)
        .with_context(|| format!("loading mesh {}", mesh_path.display()))?;
    let overrides = match &args.labels {
        Some(p) => Some(Overrides::load(p)?),
        None => None,
    };
    let rig_options = || RigOptions {
        overrides: overrides.clone(),
        ..RigOptions::from(options)
    };
    let labels = match args.vertex_labels {
        VertexLabels::Medial => label_with_overrides(&mesh, &options, overrides.as_ref()),
        VertexLabels::Skin => label_by_skin(&mesh, &rig_options()),
        VertexLabels::Bones => label_by_bones(&mesh, &rig_options()),
    }
    .with_context(|| format!("labelling {}", mesh_path.display()))?;
    let json = serde_json::to_string_pretty(&labels_json(&labels, Some(&source)))?;
    if super::common::json_mode() {
        println!("{json}");
    }
    outputs.add(&args.output, json);
    if let Some(p) = &args.ply {
        outputs.add(p, labels_ply(&mesh, &labels));
    }
    if let Some(p) = &args.svg {
        outputs.add(p, labels_svg(&mesh, &labels, 320.0));
    }
    outputs.write()?;
    super::common::say!("figure          {}", labels.figure.name());
    super::common::say!("parts           {}", labels.parts_summary());
    let fell_back = labels
        .warnings
        .iter()
        .any(|w| matches!(w, Warning::Rig(RigWarning::MedialLabels { .. })));
    super::common::say!(
        "vertex labels   {}",
        match args.vertex_labels {
            VertexLabels::Skin if !fell_back =>
                "the bones carrying most of each vertex's skin weight",
            VertexLabels::Bones if !fell_back => "nearest bone of the fitted skeleton",
            VertexLabels::Skin | VertexLabels::Bones => {
                "medial surface (no rig could be fitted, see the warning)"
            }
            VertexLabels::Medial => "medial surface",
        }
    );
    super::common::say!("wrote           {}", args.output.display());
    for p in [&args.ply, &args.svg].into_iter().flatten() {
        super::common::say!("wrote           {}", p.display());
    }
    super::common::print_warnings(&labels.warnings);
    if let Some(hint) = super::common::orientation_hint(&labels, labels.frame.up) {
        super::common::note(&format!("skelfit: hint: {hint}"));
    }
    Ok(())
}

/// Labels every `<kind>/<model>/mesh.obj` below `refdata`
/// (kinds humanoid, quadruped, other, robustness) and writes the table of figure class, parts
/// found and the scores of [`skelfit::eval::label_score`] ([`skelfit::eval::label_table_row`]).
fn table(refdata: &Path, out: &Path, options: &LabelPipelineOptions) -> anyhow::Result<()> {
    super::common::output_folder(out)?;
    let mut rows = Vec::new();
    for (name, model) in label_table_models(refdata) {
        super::common::note(&format!("labelling {name}"));
        let mesh = load_mesh(&model.join("mesh.obj"))?;
        let row = label_table_row(&name, &model, &mesh, options)
            .with_context(|| format!("labelling {name}"))?;
        for note in &row.notes {
            super::common::note(&format!("  {note}"));
        }
        rows.push(row);
    }
    let md = label_table_markdown(&rows);
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    write_file(&out.join("labels.md"), md.as_bytes())?;
    let json = label_table_json(&rows)?;
    write_file(&out.join("labels.json"), json.as_bytes())?;
    if super::common::json_mode() {
        println!("{}", json.trim_end());
    }
    super::common::say!("{}", md.trim_end());
    Ok(())
}

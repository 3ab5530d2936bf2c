//! `skelfit eval PRED REF [--mesh MESH] [--csv OUT] [--json OUT] [--html OUT] [--chamfer-only]`:
//! compare a predicted skeleton with a reference rig joint by joint.

use super::common::{load_mesh, Outputs};
use anyhow::Context;
use clap::{Args, ValueEnum};
use skelfit::eval::{
    evaluate, joint_rows, joint_table, load_skeleton, to_json, write_csv, EvalOptions, Evaluation,
    FigureMeasure, JointPairing, ReferenceRig,
};
use skelfit::report::{html_report, ReportInput, ReportOptions};
use std::path::{Path, PathBuf};

/// How errors are normalised (`--measure`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MeasureArg {
    /// Height for upright figures, longest bounding-box side otherwise.
    Auto,
    /// Extent along +Y.
    Height,
    /// Longest bounding-box side (body length).
    LongestSide,
}

impl From<MeasureArg> for FigureMeasure {
    fn from(arg: MeasureArg) -> Self {
        match arg {
            MeasureArg::Auto => FigureMeasure::Auto,
            MeasureArg::Height => FigureMeasure::Height,
            MeasureArg::LongestSide => FigureMeasure::LongestSide,
        }
    }
}

/// Arguments of `skelfit eval`.
#[derive(Debug, Args)]
pub struct EvalArgs {
    /// Predicted skeleton (.json skelfit or refdata-skeleton-v1, .bvh, .glb, .gltf).
    pub predicted: PathBuf,
    /// Reference skeleton (.json refdata-skeleton-v1 or skelfit, .bvh, .glb, .gltf).
    pub reference: PathBuf,
    /// Mesh of the figure: sets the figure size (its bounding box) and is drawn in --html.
    #[arg(long, value_name = "MESH")]
    pub mesh: Option<PathBuf>,
    /// Write the per-joint table as CSV to this file.
    #[arg(long, value_name = "OUT")]
    pub csv: Option<PathBuf>,
    /// Write the whole evaluation (joints, summaries, chamfer distances, warnings) as JSON to
    /// this file (`--json` prints it on stdout).
    #[arg(long, value_name = "OUT")]
    pub results_json: Option<PathBuf>,
    /// Write a self-contained HTML report (projections, chart, table) to this file.
    #[arg(long, value_name = "OUT")]
    pub html: Option<PathBuf>,
    /// Compare all joints, not only deforming ones (keeps IK targets and control roots).
    #[arg(long)]
    pub all_joints: bool,
    /// How the figure size that percentages refer to is measured.
    #[arg(long, value_enum, default_value_t = MeasureArg::Auto)]
    pub measure: MeasureArg,
    /// Print the table as Markdown instead of aligned text.
    #[arg(long)]
    pub markdown: bool,
    /// Do not pair joints: report only the topology-free chamfer distances (for skeletons
    /// that share no joint names or canonical keys, e.g. the general control skeleton).
    #[arg(long)]
    pub chamfer_only: bool,
}

/// Loads both skeletons (and the mesh), evaluates, prints the per-joint table and summary to
/// stdout and warnings to stderr, and writes the requested files.
pub fn run(args: &EvalArgs) -> anyhow::Result<()> {
    let mut outputs = Outputs::check(
        [
            args.csv.as_deref(),
            args.results_json.as_deref(),
            args.html.as_deref(),
        ]
        .into_iter()
        .flatten(),
        [
            Some(args.predicted.as_path()),
            Some(args.reference.as_path()),
            args.mesh.as_deref(),
        ]
        .into_iter()
        .flatten(),
    )?;
    let predicted = load_rig(&args.predicted, "predicted")?;
    let reference = load_rig(&args.reference, "reference")?;
    let mesh = match &args.mesh {
        Some(path) => Some(load_mesh(path)?),
        None => None,
    };
    let options = EvalOptions {
        deforming_only: !args.all_joints,
        measure: args.measure.into(),
        pairing: if args.chamfer_only {
            JointPairing::Skip
        } else {
            JointPairing::Required
        },
        ..Default::default()
    };
    let evaluation =
        evaluate(&predicted, &reference, mesh.as_ref(), &options).with_context(|| {
            format!(
                "comparing {} with {}",
                args.predicted.display(),
                args.reference.display()
            )
        })?;
    super::common::print_warning_records(&evaluation.warnings);
    super::common::say!("{}", summary_text(&evaluation, args.markdown).trim_end());
    if super::common::json_mode() {
        println!("{}", to_json(&evaluation)?.trim_end());
    }
    if let Some(path) = &args.csv {
        let mut bytes = Vec::new();
        write_csv(&joint_rows(&evaluation), &mut bytes)?;
        outputs.add(path, bytes);
    }
    if let Some(path) = &args.results_json {
        outputs.add(path, to_json(&evaluation)? + "\n");
    }
    if let Some(path) = &args.html {
        let (predicted, reference) = if options.deforming_only {
            (predicted.deforming(), reference.deforming())
        } else {
            (predicted, reference)
        };
        let input = ReportInput {
            evaluation: &evaluation,
            predicted: &predicted,
            reference: &reference,
            mesh: mesh.as_ref(),
        };
        outputs.add(path, html_report(&input, &ReportOptions::default()));
    }
    outputs.write()
}

fn load_rig(path: &Path, role: &str) -> anyhow::Result<ReferenceRig> {
    load_skeleton(path).with_context(|| format!("loading the {role} skeleton {}", path.display()))
}

/// The per-joint table followed by the summary lines.
fn summary_text(e: &Evaluation, markdown: bool) -> String {
    if !e.has_joint_errors() {
        return format!(
            "per-joint errors not computed (--chamfer-only); figure size {:.4} ({:?})\nCD-J2J {:.4} ({:.2} %)  CD-J2B {:.4} ({:.2} %)  CD-B2B {:.4} ({:.2} %)\n",
            e.figure.size,
            e.figure.measure,
            e.chamfer.j2j,
            e.chamfer_percent.j2j,
            e.chamfer.j2b,
            e.chamfer_percent.j2b,
            e.chamfer.b2b,
            e.chamfer_percent.b2b,
        );
    }
    let table = joint_table(&joint_rows(e));
    let mut out = if markdown {
        table.markdown()
    } else {
        table.plain()
    };
    let s = &e.summary;
    let p = &e.summary_percent;
    out.push_str(&format!(
        "\n{} joints, figure size {:.4} ({:?})\nmean {:.4} ({:.2} %)  median {:.4} ({:.2} %)  max {:.4} ({:.2} %, {})  rms {:.4} ({:.2} %)\nCD-J2J {:.2} %  CD-J2B {:.2} %  CD-B2B {:.2} %\n",
        s.count,
        e.figure.size,
        e.figure.measure,
        s.mean,
        p.mean,
        s.median,
        p.median,
        s.max,
        p.max,
        e.worst_joint,
        s.rms,
        p.rms,
        e.chamfer_percent.j2j,
        e.chamfer_percent.j2b,
        e.chamfer_percent.b2b,
    ));
    if !e.unmatched.is_empty() {
        out.push_str(&format!(
            "reference joints not predicted: {}\n",
            e.unmatched.join(", ")
        ));
    }
    out
}

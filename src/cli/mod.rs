//! Command-line front end. Each subcommand has a module with its clap `Args` and a `run`.
//!
//! Exit codes: 0 success, 1 an error while working (printed as `skelfit: error: ...` with its
//! chain of causes), 2 invalid command-line usage (printed by clap; also an output that is an
//! input, or an output extension skelfit cannot write), 130 interrupted (SIGINT,
//! SIGTERM or SIGHUP; temporary output files are removed and no output is written), 3 a
//! `skelfit batch` that ran to its end with some models failed (each is a row of its log).

mod batch;
mod bench;
mod bones;
mod check;
mod common;
mod demo;
mod eval;
mod info;
mod label;
mod outline;
mod report;
mod rig;
mod simplify;
mod skeleton;
mod skin;
mod study;
mod voxelize;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::process::ExitCode;

/// Fits anatomical control skeletons into polygon meshes and validates them against reference
/// rigs.
#[derive(Debug, Parser)]
#[command(name = "skelfit", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    #[command(flatten)]
    global: common::GlobalArgs,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Rig every mesh of a folder (recursively) or of a list file into one output folder per
    /// model (rig.glb, rig.json, check.json), resumably, optionally as shard K of N of a Slurm
    /// array or Kubernetes Indexed Job; `--merge OUT` joins the shards' logs into one report.
    Batch(batch::BatchArgs),
    /// Rig every model of a refdata-style folder (in parallel), evaluate each against its
    /// reference rig, and write accuracy and timing tables (CSV, Markdown, JSON, HTML).
    Bench(bench::BenchArgs),
    /// Rig a figure and build its bone meshes (dissertation 9.1): a .glb with every bone as a
    /// child node of its joint (plus OBJ and an SVG preview on request).
    Bones(bones::BonesArgs),
    /// Pose a skinned .glb through the standard sweep (shoulders, elbows, wrists, hips, knees,
    /// chest, neck; or an animal's legs, neck, spine and tail) and count the mesh edges
    /// stretched past 1.5x and 2x: where the skin weights tear.
    Check(check::CheckArgs),
    /// Run the main job on the bundled data: statistics, voxelization and distance maps of every
    /// model below data/, results in reports/demo/.
    Demo(demo::DemoArgs),
    /// Compare a predicted skeleton with a reference rig joint by joint (per-joint error, chamfer
    /// distances; CSV, JSON and a self-contained HTML report).
    Eval(eval::EvalArgs),
    /// Print statistics of a mesh: vertices, triangles, components, boundary and non-manifold
    /// edges, bounding box, volume.
    Info(info::InfoArgs),
    /// Label body parts (trunk, head, tail, arms, legs, wings, digits; dissertation ch.7) and
    /// write labels.json (plus a coloured PLY and an SVG picture on request), or regenerate the
    /// accuracy table with --table.
    Label(label::LabelArgs),
    /// Build an animatable skeleton from closed 2D outlines (CSV or SVG; seed 003), inflate
    /// them into a 3D mesh, skin it and write a .glb (plus an SVG picture and JSON on request).
    Outline(outline::OutlineArgs),
    /// Fit the anatomical control skeleton of a humanoid, quadruped or winged figure from a
    /// template (dissertation ch.7-8), skin the mesh to it and write a skinned .glb (plus JSON
    /// with the canonical joint map, BVH).
    Rig(rig::RigArgs),
    /// Rebuild the self-contained HTML page of a bench run or a study from its JSON results.
    Report(report::ReportArgs),
    /// Fit the general control skeleton of any figure (dissertation ch.5), skin the mesh to it
    /// and write a skinned .glb (plus JSON/BVH on request).
    Skeleton(skeleton::SkeletonArgs),
    /// Skin a mesh to a skeleton you already have (refdata or skelfit JSON, BVH, a glTF/GLB's
    /// skin) with the rig's weights and write a skinned .glb with the skeleton's own joint
    /// names and hierarchy (control joints, deform: false, get no weight).
    Skin(skin::SkinArgs),
    /// Level-of-detail controls on any skeleton JSON (seed 003): simplify branches, merge
    /// junctions, prune short branches, collapse short bones.
    Simplify(simplify::SimplifyArgs),
    /// Robustness studies: re-tessellated or rotated variants of a mesh, rigged and compared
    /// with the base rig and the reference.
    Study(study::StudyArgs),
    /// Voxelize a mesh and compute its exact distance map; print grid, interior and timings.
    Voxelize(voxelize::VoxelizeArgs),
}

/// Parses the command line. Every option that takes a value accepts a negative number
/// (`--voxel-size -0.01` reaches validation, which names the option, instead of being read as
/// an unknown flag `-0`). `--help` lists the main commands first ([`common::help_order`]).
fn parse() -> Cli {
    let command = Cli::command().mut_subcommands(|sub| {
        let order = common::help_order(sub.get_name());
        sub.display_order(order).mut_args(|arg| {
            if arg.get_action().takes_values() && !arg.is_positional() {
                arg.allow_negative_numbers(true)
            } else {
                arg
            }
        })
    });
    Cli::from_arg_matches(&command.get_matches()).unwrap_or_else(|e| e.exit())
}

/// Runs the tool and maps the outcome to an exit code.
pub fn main() -> ExitCode {
    let cli = parse();
    common::set_global(cli.global);
    // On SIGINT, SIGTERM or SIGHUP: remove the temporary output files, write nothing more.
    let _ = ctrlc::set_handler(|| {
        skelfit::output::remove_temporaries();
        eprintln!("skelfit: interrupted; no output written");
        std::process::exit(130);
    });
    let result = match &cli.command {
        Command::Batch(args) => batch::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Bones(args) => bones::run(args),
        Command::Check(args) => check::run(args),
        Command::Demo(args) => demo::run(args),
        Command::Eval(args) => eval::run(args),
        Command::Info(args) => info::run(args),
        Command::Label(args) => label::run(args),
        Command::Outline(args) => outline::run(args),
        Command::Report(args) => report::run(args),
        Command::Rig(args) => rig::run(args),
        Command::Skeleton(args) => skeleton::run(args),
        Command::Simplify(args) => simplify::run(args),
        Command::Skin(args) => skin::run(args),
        Command::Study(args) => study::run(args),
        Command::Voxelize(args) => voxelize::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) if error.is::<common::SomeFailed>() => {
            eprintln!("skelfit: {error}");
            ExitCode::from(3)
        }
        Err(error) => {
            eprintln!("skelfit: error: {error:#}");
            if error.chain().any(|e| e.is::<common::UsageError>()) {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}

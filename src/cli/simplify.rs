//! `skelfit simplify SKELETON.json -o OUT.json [--simplify F] [--merge F] [--prune F]
//! [--collapse F] [--part JOINT | --branch JOINT]`: the level-of-detail operations of seed 003
//! on any skelfit skeleton. [`LodArgs`] also serves `skelfit skeleton` and `skelfit outline`.

use super::common::Outputs;
use anyhow::Context;
use clap::Args;
use skelfit::eval::load_skeleton;
use skelfit::export::{skeleton_json, JsonOptions};
use skelfit::lod::{level_of_detail, LodOptions, LodScope};
use std::path::PathBuf;

/// Level-of-detail thresholds (skeleton units; 0 = off) and their scope.
#[derive(Debug, Args, Clone, Default)]
pub struct LodArgs {
    /// ε_s: Douglas-Peucker tolerance along branches; drops sleeve joints.
    #[arg(
        long = "lod-simplify",
        visible_alias = "simplify",
        value_name = "F",
        default_value_t = 0.0
    )]
    pub simplify: f64,
    /// ε_m: merge junction joints linked by at most this much bone.
    #[arg(
        long = "lod-merge",
        visible_alias = "merge",
        value_name = "F",
        default_value_t = 0.0
    )]
    pub merge: f64,
    /// ε_t: prune junction-to-terminal branches shorter than this.
    #[arg(
        long = "lod-prune",
        visible_alias = "prune",
        value_name = "F",
        default_value_t = 0.0
    )]
    pub prune: f64,
    /// ε_c: collapse bones between internal joints shorter than this.
    #[arg(
        long = "lod-collapse",
        visible_alias = "collapse",
        value_name = "F",
        default_value_t = 0.0
    )]
    pub collapse: f64,
    /// Apply only to this joint and its descendants (a part).
    #[arg(
        long = "lod-part",
        visible_alias = "part",
        value_name = "JOINT",
        conflicts_with = "branch"
    )]
    pub part: Option<String>,
    /// Apply only to the branch starting at this joint.
    #[arg(long = "lod-branch", visible_alias = "branch", value_name = "JOINT")]
    pub branch: Option<String>,
}

impl LodArgs {
    /// The library options (validated by the library before any work).
    pub fn options(&self) -> LodOptions {
        let scope = match (&self.part, &self.branch) {
            (Some(p), _) => LodScope::Part(p.clone()),
            (None, Some(b)) => LodScope::Branch(b.clone()),
            (None, None) => LodScope::Global,
        };
        LodOptions {
            simplify: self.simplify,
            merge: self.merge,
            prune: self.prune,
            collapse: self.collapse,
            scope,
        }
    }
}

/// Arguments of `skelfit simplify`.
#[derive(Debug, Args)]
pub struct SimplifyArgs {
    /// Skeleton to simplify (skelfit JSON, a refdata rig JSON or BVH).
    pub skeleton: PathBuf,
    /// Simplified skeleton to write (skelfit JSON).
    #[arg(short, long, value_name = "OUT.json")]
    pub output: PathBuf,
    #[command(flatten)]
    pub lod: LodArgs,
}

/// Runs the command.
pub fn run(args: &SimplifyArgs) -> anyhow::Result<()> {
    let mut outputs = Outputs::check([args.output.as_path()], [args.skeleton.as_path()])?;
    let rig = load_skeleton(&args.skeleton)
        .with_context(|| format!("loading skeleton {}", args.skeleton.display()))?;
    let simplified =
        level_of_detail(&rig.skeleton, &args.lod.options()).context("simplifying the skeleton")?;
    let canonical = rig
        .canonical
        .iter()
        .filter_map(|(key, id)| {
            let name = &rig.skeleton.joint(*id).name;
            simplified.find(name).map(|_| (key.clone(), name.clone()))
        })
        .collect();
    let options = JsonOptions {
        model: Some(rig.model.clone()),
        units: rig.units.clone(),
        canonical,
        run: None,
    };
    let json = skeleton_json(&simplified, &options)?;
    if super::common::json_mode() {
        println!("{}", json.trim_end());
    }
    outputs.add(&args.output, json);
    outputs.write()?;
    super::common::say!(
        "joints          {} -> {}",
        rig.skeleton.len(),
        simplified.len()
    );
    super::common::say!("wrote           {}", args.output.display());
    Ok(())
}

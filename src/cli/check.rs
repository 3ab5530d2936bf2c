//! `skelfit check RIG.glb [--canonical RIG.json] [--sweep auto|humanoid|animal] [--up ..]
//! [--forward ..] [--results-json OUT.json]`: pose a skinned glTF through the standard sweep and
//! count the mesh edges stretched past 1.5× and 2× (`--json`: the same JSON on stdout).

use super::common::{say, write_file};
use anyhow::{bail, Context};
use clap::{Args, ValueEnum};
use glam::DVec3;
use skelfit::anatomy::parse_direction;
use skelfit::eval::{canonical_map, load_skeleton, ReferenceRig};
use skelfit::mesh::load_gltf_scene;
use skelfit::skeleton::canonical::Tail;
use skelfit::skeleton::{Canonical, JointId};
use skelfit::skin::check::{check_deformation, sweep, DeformationCheck, SweepKind};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Which sweep (`--sweep`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SweepArg {
    /// Humanoid when the neck stands above the pelvis, animal otherwise.
    Auto,
    /// Shoulders, elbows, wrists, hips, knees, chest and neck.
    Humanoid,
    /// Leg swings, elbows and knees, neck, spine and tail.
    Animal,
}

/// Arguments of `skelfit check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// Skinned glTF/GLB (skelfit's rig.glb, or any file with a skin and JOINTS_0/WEIGHTS_0).
    pub rig: PathBuf,
    /// A skeleton file whose `canonical` map names the joints to pose (skelfit rig JSON or
    /// refdata-skeleton-v1; its names are looked up in the glTF's skin). Without it the
    /// joints are recognised by the naming presets (skelfit, Mixamo, Unity, MakeHuman).
    #[arg(long, value_name = "RIG.json")]
    pub canonical: Option<PathBuf>,
    /// Which pose sweep to run.
    #[arg(long, value_enum, default_value_t = SweepArg::Auto)]
    pub sweep: SweepArg,
    /// Up direction of the figure in the file: an axis (+Y, -Z, ...) or a vector x,y,z.
    #[arg(
        long,
        value_name = "DIR",
        default_value = "+Y",
        allow_hyphen_values = true
    )]
    pub up: String,
    /// Forward (facing) direction of the figure in the file.
    #[arg(
        long,
        value_name = "DIR",
        default_value = "+Z",
        allow_hyphen_values = true
    )]
    pub forward: String,
    /// Write the per-pose counts as JSON to this file (`--json` prints them on stdout).
    #[arg(long, value_name = "OUT.json")]
    pub results_json: Option<PathBuf>,
}

/// Runs `skelfit check`.
pub fn run(args: &CheckArgs) -> anyhow::Result<()> {
    let up = parse_direction(&args.up).map_err(anyhow::Error::msg)?;
    let forward = parse_direction(&args.forward).map_err(anyhow::Error::msg)?;
    let checked = check_rig(
        &args.rig,
        args.canonical.as_deref(),
        args.sweep,
        up,
        forward,
    )?;
    print_check(&checked.check, checked.check.sweep);
    if checked.unweighted > 0 {
        super::common::warn(
            &format!(
                "{} vertices carry no weight and stay at rest in every pose",
                checked.unweighted
            ),
            "skin",
            "degraded",
        );
    }
    let json = check_json(&args.rig, &checked);
    if let Some(path) = &args.results_json {
        write_file(path, serde_json::to_string_pretty(&json)?.as_bytes())?;
        say!("wrote {}", path.display());
    }
    if super::common::json_mode() {
        super::common::print_json(&json)?;
    }
    Ok(())
}

/// What [`check_rig`] found.
#[derive(Debug, Clone)]
pub struct CheckedRig {
    /// The per-pose counts.
    pub check: DeformationCheck,
    /// Vertices that carry no weight (they stay at rest in every pose).
    pub unweighted: usize,
}

/// The deformation check of a skinned glTF/GLB (`skelfit check RIG --canonical CANONICAL`):
/// reads the file, finds the joints to pose (from `canonical`'s map, else by the naming
/// presets), runs the sweep and measures the stretched edges.
///
/// # Errors
/// The file cannot be read or has no skin, no joint to pose is found, the directions are
/// parallel.
pub fn check_rig(
    rig: &Path,
    canonical: Option<&Path>,
    sweep_arg: SweepArg,
    up: DVec3,
    forward: DVec3,
) -> anyhow::Result<CheckedRig> {
    if up.cross(forward).length() < 1e-6 {
        bail!(
            "--up and --forward are parallel: give two different axes (e.g. --up +Y --forward +Z)"
        );
    }
    let scene = load_gltf_scene(rig).with_context(|| format!("cannot read {}", rig.display()))?;
    let (Some(skeleton), Some(weights)) = (scene.skeleton, scene.weights) else {
        bail!(
            "{} has no skin: check needs a skinned mesh (JOINTS_0/WEIGHTS_0); rig it first with `skelfit rig`",
            rig.display()
        );
    };
    let unweighted = weights.iter().filter(|w| w.is_empty()).count();
    let canonical = canonical_joints(rig, canonical, &skeleton)?;
    let kind = match sweep_arg {
        SweepArg::Humanoid => SweepKind::Humanoid,
        SweepArg::Animal => SweepKind::Animal,
        SweepArg::Auto => guess_sweep(&skeleton, &canonical, up, forward),
    };
    let (poses, missing) = sweep(&skeleton, &canonical, kind, up, forward);
    if poses.is_empty() {
        bail!(
            "none of the {kind:?} sweep's joints are in the canonical map ({}): give --canonical or --sweep",
            canonical.keys().cloned().collect::<Vec<_>>().join(", ")
        );
    }
    let check = check_deformation(&scene.mesh, &skeleton, &weights, kind, &poses, missing)?;
    Ok(CheckedRig { check, unweighted })
}

/// The `skelfit-check-v1` JSON of a check of `rig`.
pub fn check_json(rig: &Path, checked: &CheckedRig) -> serde_json::Value {
    serde_json::json!({
        "format": "skelfit-check-v1",
        "rig": rig.display().to_string(),
        "unweighted_vertices": checked.unweighted,
        "check": checked.check,
    })
}

/// The joints to pose: `canonical`'s map looked up by name in the skin, else the naming
/// presets recognised in the skin's joint names.
fn canonical_joints(
    rig: &Path,
    canonical: Option<&Path>,
    skeleton: &skelfit::skeleton::Skeleton,
) -> anyhow::Result<BTreeMap<String, JointId>> {
    match canonical {
        Some(path) => {
            let reference = load_skeleton(path)
                .with_context(|| format!("cannot read the canonical map in {}", path.display()))?;
            let map: BTreeMap<String, JointId> = reference
                .canonical
                .iter()
                .filter_map(|(key, &id)| {
                    skeleton
                        .find(&reference.skeleton.joint(id).name)
                        .map(|j| (key.clone(), j))
                })
                .collect();
            if map.is_empty() {
                bail!(
                    "no joint of {}'s canonical map is named in {}'s skin: give the skeleton file written with this rig",
                    path.display(),
                    rig.display()
                );
            }
            Ok(map)
        }
        None => {
            let (map, _) = canonical_map(&ReferenceRig::from_skeleton("rig", skeleton.clone()));
            if map.is_empty() {
                bail!(
                    "the joints of {} follow no known naming (skelfit, Mixamo, Unity, MakeHuman): give --canonical RIG.json",
                    rig.display()
                );
            }
            Ok(map)
        }
    }
}

/// Prints the table of poses and their stretched edges.
fn print_check(check: &DeformationCheck, kind: SweepKind) {
    say!(
        "{} edges, {:?} sweep ({} poses)",
        check.edges,
        kind,
        check.poses.len()
    );
    say!("{:<24} {:>8} {:>8} {:>7}", "pose", ">1.5x", ">2x", "worst");
    for p in &check.poses {
        say!(
            "{:<24} {:>8} {:>8} {:>7.2}",
            p.pose,
            p.over_1_5,
            p.over_2,
            p.worst
        );
    }
    say!(
        "{:<24} {:>8} {:>8} {:>7.2}",
        "all poses",
        check.total_over_1_5(),
        check.total_over_2(),
        check.worst()
    );
    if !check.missing.is_empty() {
        say!("not posed (no joint): {}", check.missing.join(", "));
    }
}

/// Humanoid when the neck stands above the pelvis more than it lies ahead of it.
fn guess_sweep(
    skeleton: &skelfit::skeleton::Skeleton,
    canonical: &BTreeMap<String, JointId>,
    up: DVec3,
    forward: DVec3,
) -> SweepKind {
    let at = |k: Canonical| {
        canonical
            .get(k.as_str())
            .map(|&j| skeleton.joint(j).position)
    };
    match (
        at(Canonical::Pelvis),
        at(Canonical::Neck).or_else(|| at(Canonical::Head)),
    ) {
        (Some(pelvis), Some(neck)) => {
            let d = neck - pelvis;
            if d.dot(up.normalize()) > d.dot(forward.normalize()).abs() {
                SweepKind::Humanoid
            } else {
                SweepKind::Animal
            }
        }
        _ if canonical.contains_key(Canonical::Tail(Tail::Base).as_str()) => SweepKind::Animal,
        _ => SweepKind::Humanoid,
    }
}

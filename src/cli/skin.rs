//! `skelfit skin MESH --skeleton SKELETON -o OUT.glb [--skeleton-json OUT.json] [--bvh OUT.bvh]
//! [--skeleton-scale F]`: skin a mesh to a skeleton the user already has (refdata or skelfit
//! JSON, BVH, a glTF/GLB's skin) with `skelfit rig`'s weights, keeping the skeleton's own
//! joint names and hierarchy.

use super::common::{load_mesh, millis, require_mesh_output, say, Outputs, VoxelArgs};
use super::skeleton::with_spinner;
use anyhow::{bail, Context};
use clap::Args;
use serde_json::json;
use skelfit::eval::{load_skeleton, ReferenceRig, RigFormat};
use skelfit::export::{bvh_text, glb_bytes, skeleton_json, BvhOptions, GltfOptions, JsonOptions};
use skelfit::mesh::load_gltf_scene;
use skelfit::skin::{skin_skeleton, SkeletonSkinOptions, SkinError, SkinnedSkeleton};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `skelfit skin`.
#[derive(Debug, Args)]
pub struct SkinArgs {
    /// Mesh file (.obj, .gltf, .glb, .stl, .ply).
    pub mesh: PathBuf,
    /// The skeleton to skin: refdata-skeleton-v1 or skelfit JSON, BVH, or a glTF/GLB with a
    /// skin. It is used as given: same units and frame as the mesh.
    #[arg(long, value_name = "SKELETON")]
    pub skeleton: PathBuf,
    /// Skinned binary glTF to write (mesh, the skeleton's joints as nodes, weights).
    #[arg(short, long, value_name = "OUT.glb")]
    pub output: PathBuf,
    /// Also write the skeleton as skelfit JSON (with its `canonical` map when the file had
    /// one, run information under "run"; `--json` prints the same on stdout).
    #[arg(long, value_name = "OUT.json")]
    pub skeleton_json: Option<PathBuf>,
    /// Also write the skeleton as BVH.
    #[arg(long, value_name = "OUT.bvh")]
    pub bvh: Option<PathBuf>,
    /// Multiply the skeleton's joint positions by this factor first (a skeleton in
    /// centimetres on a mesh in metres: 0.01). The outputs hold the scaled skeleton.
    #[arg(long, value_name = "F", default_value_t = 1.0)]
    pub skeleton_scale: f64,
    #[command(flatten)]
    pub voxel: VoxelArgs,
}

impl SkinArgs {
    /// Validated options (stage ranges are checked by the library before any work).
    pub fn options(&self) -> anyhow::Result<SkeletonSkinOptions> {
        if !(self.skeleton_scale.is_finite() && self.skeleton_scale > 0.0) {
            bail!(
                "--skeleton-scale {}: give a finite factor above zero",
                self.skeleton_scale
            );
        }
        Ok(SkeletonSkinOptions {
            voxel: self.voxel.options()?,
            ..Default::default()
        })
    }

    /// Checks every output before any work.
    fn outputs(&self) -> anyhow::Result<Outputs> {
        let checked = Outputs::check(
            [
                Some(self.output.as_path()),
                self.skeleton_json.as_deref(),
                self.bvh.as_deref(),
            ]
            .into_iter()
            .flatten(),
            [self.mesh.as_path(), self.skeleton.as_path()],
        )?;
        require_mesh_output(&self.output, "-o")?;
        Ok(checked)
    }
}

/// Runs the command.
pub fn run(args: &SkinArgs) -> anyhow::Result<()> {
    let options = args.options()?;
    let mut outputs = args.outputs()?;
    let start = Instant::now();
    let mesh = load_mesh(&args.mesh)?;
    let mut rig = given_skeleton(&args.skeleton)
        .with_context(|| format!("loading skeleton {}", args.skeleton.display()))?;
    if args.skeleton_scale != 1.0 {
        for joint in &mut rig.skeleton.joints {
            joint.position *= args.skeleton_scale;
        }
    }
    let load_ms = millis(start);
    let clock = Instant::now();
    let skinned = with_spinner(format!("skinning {}", args.mesh.display()), || {
        skin_skeleton(&mesh, &rig.skeleton, &options)
    })
    .map_err(|error| {
        let hint = match &error {
            skelfit::Error::Skin(SkinError::UnitMismatch { factor, .. }) => format!(
                " (if the units differ, rerun with --skeleton-scale {})",
                trimmed(args.skeleton_scale / factor)
            ),
            _ => String::new(),
        };
        anyhow::Error::new(error).context(format!(
            "skinning {} to the skeleton of {}{hint}",
            args.mesh.display(),
            args.skeleton.display()
        ))
    })?;
    let skin_ms = millis(clock);
    let clock = Instant::now();
    outputs.add_mesh(
        &args.output,
        glb_bytes(&mesh, &rig.skeleton, &skinned.skin, &GltfOptions::default())?,
    )?;
    let info = run_info(args, &rig, &skinned, load_ms, skin_ms);
    let mut json_text = None;
    if args.skeleton_json.is_some() || super::common::json_mode() {
        let canonical = rig
            .canonical
            .iter()
            .map(|(key, &id)| (key.clone(), rig.skeleton.joint(id).name.clone()))
            .collect();
        let options = JsonOptions {
            model: Some(rig.model.clone()),
            units: rig.units.clone().filter(|_| args.skeleton_scale == 1.0),
            canonical,
            run: Some(info),
        };
        let text = skeleton_json(&rig.skeleton, &options)?;
        if let Some(path) = &args.skeleton_json {
            outputs.add(path, text.clone());
        }
        json_text = Some(text);
    }
    if let Some(path) = &args.bvh {
        outputs.add(path, bvh_text(&rig.skeleton, &BvhOptions::default())?);
    }
    outputs.write()?;
    let export_ms = millis(clock);
    if let (true, Some(text)) = (super::common::json_mode(), &json_text) {
        println!("{}", text.trim_end());
    }
    print_summary(args, &rig, &skinned, [load_ms, skin_ms, export_ms]);
    super::common::print_warnings(&skinned.warnings);
    Ok(())
}

/// The skeleton of `path` as [`load_skeleton`] reads it; a glTF/GLB whose skin has joints
/// sharing a name is refused (the loader renames them, and the written file would then not
/// match the animations made for the skeleton).
fn given_skeleton(path: &Path) -> anyhow::Result<ReferenceRig> {
    let gltf = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("glb") || e.eq_ignore_ascii_case("gltf"));
    if !gltf {
        return Ok(load_skeleton(path)?);
    }
    let scene = load_gltf_scene(path)?;
    let Some(skeleton) = scene.skeleton else {
        bail!(
            "the file has no skin: give a glTF/GLB with a skinned mesh, or a JSON or BVH skeleton"
        );
    };
    if !scene.duplicate_joint_names.is_empty() {
        bail!(
            "several joints of the skin are called {}: joint names must be unique; rename them in the file",
            scene.duplicate_joint_names.join(", ")
        );
    }
    let model = path
        .file_stem()
        .map_or_else(|| "skeleton".into(), |s| s.to_string_lossy().into_owned());
    let mut rig = ReferenceRig::from_skeleton(model, skeleton);
    rig.rig = Some("gltf".into());
    rig.format = RigFormat::Gltf;
    Ok(rig)
}

/// A number with at most six decimals, trailing zeros cut.
fn trimmed(value: f64) -> String {
    let text = format!("{value:.6}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Deforming joints that no vertex depends on.
fn unweighted_joints(rig: &ReferenceRig, skinned: &SkinnedSkeleton) -> Vec<String> {
    let mut used = vec![false; rig.skeleton.len()];
    for &(j, _) in skinned.skin.weights.iter().flatten() {
        used[j.0] = true;
    }
    rig.skeleton
        .joints
        .iter()
        .zip(used)
        .filter(|(j, used)| j.deform && !used)
        .map(|(j, _)| j.name.clone())
        .collect()
}

/// Run information: the skeleton, the grid, the placement, timings and warnings.
fn run_info(
    args: &SkinArgs,
    rig: &ReferenceRig,
    skinned: &SkinnedSkeleton,
    load_ms: f64,
    skin_ms: f64,
) -> serde_json::Value {
    let grid = &skinned.solid.grid;
    let placement = &skinned.placement;
    let names = |ids: &[skelfit::skeleton::JointId]| -> Vec<String> {
        ids.iter()
            .map(|&j| rig.skeleton.joint(j).name.clone())
            .collect()
    };
    json!({
        "mesh": args.mesh.display().to_string(),
        "skeleton": args.skeleton.display().to_string(),
        "skeleton_scale": args.skeleton_scale,
        "joints": rig.skeleton.len(),
        "deforming_joints": rig.skeleton.joints.iter().filter(|j| j.deform).count(),
        "unweighted_deforming_joints": unweighted_joints(rig, skinned),
        "size_ratio": placement.size_ratio,
        "joints_outside": names(&placement.outside),
        "zero_length_bones": names(&placement.zero_length),
        "bones_outside": placement.empty_bones.iter().map(|&(p, c, share)| json!({
            "parent": rig.skeleton.joint(p).name,
            "joint": rig.skeleton.joint(c).name,
            "share_outside": share,
        })).collect::<Vec<_>>(),
        "grid": grid.dims,
        "voxel_size": grid.voxel_size,
        "interior_voxels": skinned.solid.report.interior_voxels,
        "timings_ms": {"load": load_ms, "skin": skin_ms},
        "warnings": skinned.warnings,
    })
}

fn print_summary(
    args: &SkinArgs,
    rig: &ReferenceRig,
    skinned: &SkinnedSkeleton,
    [load_ms, skin_ms, export_ms]: [f64; 3],
) {
    let grid = &skinned.solid.grid;
    let deforming = rig.skeleton.joints.iter().filter(|j| j.deform).count();
    say!("mesh            {}", args.mesh.display());
    say!(
        "skeleton        {} ({} joints, {} deforming; {:.2} of the figure's size)",
        args.skeleton.display(),
        rig.skeleton.len(),
        deforming,
        skinned.placement.size_ratio
    );
    say!(
        "grid            {} x {} x {} ({} interior voxels of {:.6})",
        grid.dims[0],
        grid.dims[1],
        grid.dims[2],
        skinned.solid.report.interior_voxels,
        grid.voxel_size
    );
    let unweighted = unweighted_joints(rig, skinned);
    if !unweighted.is_empty() {
        say!("no vertex on    {}", unweighted.join(", "));
    }
    say!("timings (ms)    load {load_ms:.1}, skin {skin_ms:.1}, export {export_ms:.1}");
    for path in
        std::iter::once(&args.output).chain([&args.skeleton_json, &args.bvh].into_iter().flatten())
    {
        say!("wrote           {}", path.display());
    }
}

#[cfg(test)]
mod tests {
    use super::trimmed;

    #[test]
    fn factors_print_without_trailing_zeros() {
        assert_eq!(trimmed(0.01), "0.01");
        assert_eq!(trimmed(100.0), "100");
        assert_eq!(trimmed(1.0 / 39.37), "0.0254");
    }
}

//! `skelfit bones MESH -o BONES.glb [--obj BONES.obj] [--svg BONES.svg] [--with-skin]` plus the
//! options of `skelfit rig`: rig the figure, generate its bone meshes (dissertation 9.1) and
//! write them as child nodes of the armature's joints.

use super::common::{millis, note, say};
use super::rig::RigArgs;
use super::skeleton::with_spinner;
use anyhow::Context;
use clap::Args;
use skelfit::bones::{bones_glb_bytes, bones_svg, bones_with_surface, BoneOptions, Bones};
use skelfit::export::{obj_text, GltfOptions};
use skelfit::mesh::Mesh;
use skelfit::pipeline::{rig, Rig};
use skelfit::warning::Warning;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `skelfit bones`: those of `skelfit rig` (`-o` names the bones .glb: the
/// armature with every bone mesh as a child node of its joint) and the extra outputs.
#[derive(Debug, Args)]
pub struct BonesArgs {
    #[command(flatten)]
    pub rig: RigArgs,
    /// Also write every bone, merged at the rest pose, as OBJ.
    #[arg(long, value_name = "BONES.obj")]
    pub obj: Option<PathBuf>,
    /// Also write an SVG preview (front, side and top views over the skin's silhouette).
    #[arg(long, value_name = "BONES.svg")]
    pub svg: Option<PathBuf>,
    /// Put the skinned mesh into the .glb too.
    #[arg(long = "with-skin")]
    pub with_skin: bool,
}

/// Bones of a rig of `mesh` with the default options (digits sized on the mesh's surface).
pub fn rig_bones(rigged: &Rig, mesh: &Mesh) -> anyhow::Result<Bones> {
    bones_with_surface(&rigged.fit, &rigged.distance, mesh, &BoneOptions::default())
        .context("generating bone meshes")
}

/// Runs the command.
pub fn run(args: &BonesArgs) -> anyhow::Result<()> {
    let options = args.rig.options()?;
    let mut outputs = args
        .rig
        .outputs(&[args.obj.as_deref(), args.svg.as_deref()])?;
    let start = Instant::now();
    let mesh = super::common::load_mesh(&args.rig.mesh)?;
    let load_ms = millis(start);
    let rigged = with_spinner(format!("rigging {}", args.rig.mesh.display()), || {
        rig(&mesh, &options)
    })
    .context("fitting the anatomical control skeleton")?;
    let clock = Instant::now();
    let made = rig_bones(&rigged, &mesh)?;
    let bones_ms = millis(clock);
    let skinned = args.with_skin.then_some((&mesh, &rigged.skin));
    outputs.add_mesh(
        &args.rig.output,
        bones_glb_bytes(
            &rigged.fit.skeleton,
            &made,
            skinned,
            &GltfOptions::default(),
        )?,
    )?;
    if let Some(path) = &args.obj {
        outputs.add(path, obj_text(&made.world_mesh()));
    }
    if let Some(path) = &args.svg {
        outputs.add(path, bones_svg(&made, Some(&mesh), 360.0));
    }
    if let Some(path) = &args.rig.skeleton_json {
        outputs.add(path, super::rig::rig_json(&args.rig.mesh, &rigged, None)?);
    }
    outputs.write()?;
    let mut warnings = rigged.warnings.clone();
    warnings.extend(made.warnings.iter().cloned().map(Warning::Bones));
    if super::common::json_mode() {
        let written: Vec<String> = [Some(&args.rig.output), args.obj.as_ref(), args.svg.as_ref()]
            .into_iter()
            .chain([args.rig.skeleton_json.as_ref()])
            .flatten()
            .map(|p| p.display().to_string())
            .collect();
        super::common::print_json(&serde_json::json!({
            "mesh": args.rig.mesh.display().to_string(),
            "template": rigged.fit.template,
            "joints": rigged.fit.skeleton.len(),
            "bones": made.bones.iter().map(|b| serde_json::json!({
                "name": b.name,
                "kind": b.kind.as_str(),
                "joint": rigged.fit.skeleton.joints[b.joint.0].name,
            })).collect::<Vec<_>>(),
            "timings_ms": {"load": load_ms, "bones": bones_ms},
            "written": written,
            "warnings": warnings,
        }))?;
    }
    let mut kinds: BTreeMap<&str, usize> = BTreeMap::new();
    for b in &made.bones {
        *kinds.entry(b.kind.as_str()).or_default() += 1;
    }
    let list: Vec<String> = kinds.iter().map(|(k, n)| format!("{k} {n}")).collect();
    say!("mesh            {}", args.rig.mesh.display());
    say!(
        "skeleton        {} joints, template {}",
        rigged.fit.skeleton.len(),
        rigged.fit.template
    );
    say!("bones           {}: {}", made.bones.len(), list.join(", "));
    say!("timings (ms)    load {load_ms:.1}, bones {bones_ms:.1}");
    for path in [Some(&args.rig.output), args.obj.as_ref(), args.svg.as_ref()]
        .into_iter()
        .flatten()
    {
        say!("wrote           {}", path.display());
    }
    super::common::print_warnings(&warnings);
    if let Some(hint) = super::common::orientation_hint(&rigged.labelling, rigged.input.up) {
        note(&format!("skelfit: hint: {hint}"));
    }
    Ok(())
}

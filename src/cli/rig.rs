//! `skelfit rig MESH -o OUT.glb [--skeleton-json OUT.json] [--bvh OUT.bvh] [--template ...]
//! [--preset ...] [--up ..] [--forward ..] [--labels OVERRIDE.json]`: the anatomical control
//! skeleton from a template (dissertation ch.7-8), skinned and exported; `--json` prints the
//! skeleton JSON on stdout.

use super::common::{
    load_model, millis, note, output_frame, require_mesh_output, say, Outputs, UsageError,
    VoxelArgs,
};
use super::skeleton::with_spinner;
use anyhow::Context;
use clap::{Args, ValueEnum};
use serde_json::json;
use skelfit::anatomy::Overrides;
use skelfit::export::{
    bvh_text, glb_bytes, model_glb_bytes, skeleton_json, BvhOptions, GltfOptions, JsonOptions,
};
use skelfit::pipeline::{rig, Rig, RigOptions, TemplateChoice, GENERAL};
use skelfit::refine::SpineDetail;
use skelfit::template::{Preset, Template};
use skelfit::warning::Warning;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Engine skeleton of the output (`--preset`): joint set, names and parents.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PresetArg {
    /// skelfit's anatomical skeleton (pelvis, spine_01..05, shoulder_L, ...).
    Anatomical,
    /// Adobe Mixamo (mixamorig:Hips, Spine, Spine1, Spine2, Neck, Head, LeftArm, ...).
    Mixamo,
    /// Unity Humanoid avatar (Hips, Spine, Chest, UpperChest, Neck, LeftUpperArm, ...).
    Unity,
    /// MakeHuman / MPFB2 game_engine (Root, pelvis, spine_01..03, neck_01, upperarm_l, ...).
    Makehuman,
    /// Unreal Engine 5 Mannequin (root, pelvis, spine_01..05, neck_01..02, upperarm_l, ...).
    Unreal,
}

impl From<PresetArg> for Preset {
    fn from(p: PresetArg) -> Self {
        match p {
            PresetArg::Anatomical => Preset::Anatomical,
            PresetArg::Mixamo => Preset::Mixamo,
            PresetArg::Unity => Preset::Unity,
            PresetArg::Makehuman => Preset::MakeHuman,
            PresetArg::Unreal => Preset::Unreal,
        }
    }
}

/// Arguments of `skelfit rig`.
#[derive(Debug, Args)]
pub struct RigArgs {
    /// Mesh file (.obj, .gltf, .glb, .stl, .ply).
    pub mesh: PathBuf,
    /// Skinned binary glTF to write (mesh, armature, weights).
    #[arg(short, long, value_name = "OUT.glb")]
    pub output: PathBuf,
    /// Also write the skeleton as skelfit JSON (joints, `canonical` map, timings under "run";
    /// `--json` prints the same on stdout).
    #[arg(long, value_name = "OUT.json")]
    pub skeleton_json: Option<PathBuf>,
    /// Also write the skeleton as BVH.
    #[arg(long, value_name = "OUT.bvh")]
    pub bvh: Option<PathBuf>,
    /// Template: auto (from the labelled figure), humanoid, quadruped, winged, or a path to a
    /// template .toml file.
    #[arg(long, value_name = "NAME|FILE", default_value = "auto")]
    pub template: String,
    /// Engine skeleton of the output: the engine's joints, names and parents for every joint
    /// skelfit places (spine joints spread along the fitted spine; joints the engine lacks
    /// left out, their skin going to the engine joints around them).
    #[arg(long, value_enum, default_value_t = PresetArg::Anatomical)]
    pub preset: PresetArg,
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
    /// Write OUT.glb in the mesh's own frame and units instead of glTF's (+Y up, +Z forward,
    /// metres).
    #[arg(long, conflicts_with = "units")]
    pub keep_frame: bool,
    /// Units of the mesh, for the metre .glb: mm, cm, m, in, or auto (from the figure's height
    /// along up: 0.3-3 is m, 30-300 cm, 300-3000 mm; the choice is printed).
    #[arg(long, value_name = "UNITS", default_value = "auto", value_parser = ["mm", "cm", "m", "in", "auto"])]
    pub units: String,
    /// A labels override file (JSON) correcting body-part sections (see `skelfit label`).
    #[arg(long, value_name = "OVERRIDE.json")]
    pub labels: Option<PathBuf>,
    /// Slicing-based refinement of humanoid joints (seed 004) after the fit.
    #[arg(long, value_name = "on|off", default_value = "on", value_parser = ["on", "off"])]
    pub refine: String,
    /// Make the paired joints of a bilaterally symmetric figure mirror each other across its
    /// median plane (figures that are not symmetric, e.g. posed with one arm raised, keep theirs).
    #[arg(long, value_name = "on|off", default_value = "on", value_parser = ["on", "off"])]
    pub symmetry: String,
    /// Spine of a humanoid rig: `coarse`, the template's trunk and neck joints placed on the
    /// spine curve; `full`, the 24 inter-vertebral joints C1..C7, T1..T12, L1..L5 and the
    /// sacrum from the pelvis to the head (clavicles on T1), with per-region anatomical limits.
    /// `full` needs `--preset anatomical` and `--refine on`; a figure that is not a humanoid,
    /// or whose spine the refinement does not find, keeps the coarse spine with a warning.
    #[arg(long, value_name = "coarse|full", default_value = "coarse", value_parser = ["coarse", "full"])]
    pub spine: String,
    /// Fingers of a humanoid's hands: `auto`, the digits found on each hand's surface beyond
    /// the wrist (thumb..pinky, three joints and a tip each; a mitten hand gets one chain and a
    /// thumb, with a warning), skinned finger by finger; an animal's fore feet get the digits
    /// their hooves or paws show (no thumb); `off`, the template's single finger chain per hand.
    #[arg(long, value_name = "auto|off", default_value = "auto", value_parser = ["auto", "off"])]
    pub fingers: String,
    /// Toes of an upright figure's feet: `auto`, the toe joint at the ball of the foot (its
    /// widest cross-section) and the toe end at the foot's tip, read from the foot's surface;
    /// an animal's hind feet get the digits their hooves or paws show; `off`, where the
    /// template's leg ratios put them.
    #[arg(long, value_name = "auto|off", default_value = "auto", value_parser = ["auto", "off"])]
    pub toes: String,
    /// Fail (exit code 1, nothing written) when the rig lacks a body part the template expects
    /// (a head, an arm, a leg, a wing), or when no template fits the figure (`--template auto`
    /// then fits the general control skeleton), instead of writing it with a warning.
    #[arg(long)]
    pub strict: bool,
    /// Add bone meshes (dissertation 9.1) to OUT.glb as child nodes of their joints.
    #[arg(long)]
    pub bones: bool,
    #[command(flatten)]
    pub voxel: VoxelArgs,
}

impl RigArgs {
    /// Validated options (stage ranges are checked by the library before any work).
    pub fn options(&self) -> anyhow::Result<RigOptions> {
        let mut options = RigOptions::default();
        options.voxel = self.voxel.options()?;
        options.label.up = super::common::parse_up(&self.up)?;
        options.label.forward = super::common::parse_forward(&self.forward)?;
        options.template = template_choice(&self.template)?;
        options.fit.preset = self.preset.into();
        options.refine.in_rig = self.refine == "on";
        options.refine.symmetry = self.symmetry == "on";
        options.digits.enabled = self.fingers == "auto";
        options.digits.feet = self.toes == "auto";
        if self.spine == "full" {
            options.refine.spine = SpineDetail::Full;
            // Conflicts (an engine preset, the refinement off) are usage errors.
            options
                .full_spine_conflicts()
                .map_err(|e| UsageError(e.to_string()))?;
        }
        if let Some(path) = &self.labels {
            options.overrides = Some(Overrides::load(path)?);
        }
        Ok(options)
    }
}

/// `--template`: `auto`, a built-in template's name, or a template file (loaded).
pub fn template_choice(text: &str) -> anyhow::Result<TemplateChoice> {
    Ok(match text {
        "auto" => TemplateChoice::Auto,
        name @ ("humanoid" | "quadruped" | "winged") => TemplateChoice::Builtin(name.into()),
        path => {
            let path = Path::new(path);
            if !path.is_file() {
                anyhow::bail!(
                    "--template {}: not a built-in template (auto, humanoid, quadruped, winged) nor a template file",
                    path.display()
                );
            }
            TemplateChoice::Custom(Box::new(Template::load(path)?))
        }
    })
}

impl RigArgs {
    /// The files the command reads (the mesh, a template file, a labels override).
    pub fn inputs(&self) -> Vec<&Path> {
        let mut inputs = vec![self.mesh.as_path(), Path::new(&self.template)];
        inputs.extend(self.labels.as_deref());
        inputs
    }

    /// Checks `-o` (a .glb) and the other outputs, together with `extra` ones, before any work.
    pub fn outputs<'a>(&'a self, extra: &[Option<&'a Path>]) -> anyhow::Result<Outputs> {
        let outputs = [
            Some(self.output.as_path()),
            self.skeleton_json.as_deref(),
            self.bvh.as_deref(),
        ]
        .into_iter()
        .chain(extra.iter().copied())
        .flatten();
        let checked = Outputs::check(outputs, self.inputs())?;
        require_mesh_output(&self.output, "-o")?;
        Ok(checked)
    }
}

/// Runs the command.
pub fn run(args: &RigArgs) -> anyhow::Result<()> {
    let options = args.options()?;
    let mut outputs = args.outputs(&[])?;
    let start = Instant::now();
    let (mesh, model) = load_model(&args.mesh)?;
    let load_ms = millis(start);
    let rigged = with_spinner(format!("rigging {}", args.mesh.display()), || {
        rig(&mesh, &options)
    })
    .context("fitting the anatomical control skeleton")?;
    if args.strict && !rigged.missing.is_empty() {
        super::common::print_warnings(&rigged.warnings);
        anyhow::bail!(
            "--strict: the rig lacks {} that the {} template expects; nothing was written (see the warnings above for why, or label the parts with --labels)",
            rigged.missing.join(", "),
            rigged.fit.template
        );
    }
    let general = rigged.fit.template == GENERAL;
    if args.strict && general {
        super::common::print_warnings(&rigged.warnings);
        anyhow::bail!(
            "--strict: no template fits the figure (see the warnings above for why); nothing was written (choose one with --template, or run without --strict for the general control skeleton)"
        );
    }
    let clock = Instant::now();
    let frame = output_frame(
        args.keep_frame,
        &args.units,
        &mesh,
        rigged.labelling.frame.up,
        rigged.labelling.frame.forward,
    )?;
    let skeleton = frame.frame.skeleton(&rigged.fit.skeleton);
    let mut bone_warnings = Vec::new();
    let glb = if args.bones {
        let mut made = super::bones::rig_bones(&rigged, &mesh)?;
        for bone in &mut made.bones {
            bone.mesh = frame.frame.mesh(&bone.mesh);
        }
        let bytes = skelfit::bones::bones_glb_bytes(
            &skeleton,
            &made,
            Some((&frame.frame.mesh(&mesh), &rigged.skin)),
            &GltfOptions::default(),
        )?;
        bone_warnings = made.warnings;
        bytes
    } else {
        rig_glb(&mesh, model.as_ref(), &rigged, &frame)?
    };
    outputs.add_mesh(&args.output, glb)?;
    let mut info = run_info(&args.mesh, &rigged, load_ms);
    info["output_frame"] = frame.json();
    let json_text = rig_json(&args.mesh, &rigged, Some(info))?;
    if let Some(path) = &args.skeleton_json {
        outputs.add(path, json_text.clone());
    }
    if let Some(path) = &args.bvh {
        outputs.add(
            path,
            bvh_text(&rigged.fit.skeleton, &BvhOptions::default())?,
        );
    }
    outputs.write()?;
    let export_ms = millis(clock);
    if super::common::json_mode() {
        println!("{}", json_text.trim_end());
    }
    print_summary(args, &rigged, load_ms, export_ms);
    say!("frame           {}", frame.note);
    if let Some(warning) = &frame.warning {
        super::common::warn(warning, "export", "notice");
    }
    let mut warnings = rigged.warnings.clone();
    warnings.extend(bone_warnings.into_iter().map(Warning::Bones));
    super::common::print_warnings(&warnings);
    if let Some(model) = &model {
        super::common::print_model_warnings(model, args.bones);
    }
    if let Some(hint) = super::common::orientation_hint(&rigged.labelling, rigged.input.up) {
        note(&format!("skelfit: hint: {hint}"));
    }
    if general {
        note(
            "skelfit: general: no template fits the figure, so it has the general control skeleton (no canonical joints; --template forces one, --strict makes this an error)",
        );
    }
    if !rigged.missing.is_empty() {
        note(&format!(
            "skelfit: missing: the rig lacks {} that the {} template expects (no joints for {}; --strict makes this an error)",
            rigged.missing.join(", "),
            rigged.fit.template,
            if rigged.missing.len() == 1 { "it" } else { "them" }
        ));
    }
    Ok(())
}

/// The skinned .glb of a rig without bone meshes, in `frame`: the input model (its
/// primitives, UVs, materials, textures) when the file held one, else the welded mesh.
pub fn rig_glb(
    mesh: &skelfit::mesh::Mesh,
    model: Option<&skelfit::mesh::SourceModel>,
    rigged: &Rig,
    frame: &super::common::ChosenFrame,
) -> anyhow::Result<Vec<u8>> {
    Ok(match model {
        Some(model) => model_glb_bytes(
            model,
            &rigged.fit.skeleton,
            &rigged.skin,
            &frame.frame,
            &GltfOptions::default(),
        )?,
        None => glb_bytes(
            &frame.frame.mesh(mesh),
            &frame.frame.skeleton(&rigged.fit.skeleton),
            &rigged.skin,
            &GltfOptions::default(),
        )?,
    })
}

/// The fitted skeleton as skelfit JSON with its `canonical` map and `run` information.
pub fn rig_json(
    mesh: &Path,
    rigged: &Rig,
    run: Option<serde_json::Value>,
) -> anyhow::Result<String> {
    let options = JsonOptions {
        model: super::skeleton::model_name(mesh),
        canonical: rigged.fit.canonical_names(),
        run,
        ..Default::default()
    };
    Ok(skeleton_json(&rigged.fit.skeleton, &options)?)
}

/// Writes [`rig_json`] to `path`.
pub fn write_rig_json(
    path: &Path,
    mesh: &Path,
    rigged: &Rig,
    run: Option<serde_json::Value>,
) -> anyhow::Result<()> {
    super::common::write_file(path, rig_json(mesh, rigged, run)?.as_bytes())
}

/// Run information: template, figure, sizes, stage timings and warnings.
pub fn run_info(mesh: &Path, rigged: &Rig, load_ms: f64) -> serde_json::Value {
    let mut timings = serde_json::Map::new();
    timings.insert("load".into(), json!(load_ms));
    for (stage, ms) in &rigged.timings {
        timings.insert(stage.clone(), json!(ms));
    }
    let grid = &rigged.solid.grid;
    let frame = rigged.labelling.frame;
    json!({
        "mesh": mesh.display().to_string(),
        "template": rigged.fit.template,
        "figure": rigged.labelling.figure.name(),
        "missing_parts": rigged.missing,
        "up_found": rigged.labelling.up_found,
        "forward_found": rigged.labelling.forward_found,
        "up": frame.up.to_array(),
        "forward": frame.forward.to_array(),
        "grid": grid.dims,
        "voxel_size": grid.voxel_size,
        "interior_voxels": rigged.solid.report.interior_voxels,
        "joints": rigged.fit.skeleton.len(),
        "canonical_joints": rigged.fit.canonical.len(),
        "ears": rigged.input.ears.iter().map(|e| e.side.as_str()).collect::<Vec<_>>(),
        "timings_ms": timings,
        "warnings": rigged.warnings,
    })
}

fn print_summary(args: &RigArgs, rigged: &Rig, load_ms: f64, export_ms: f64) {
    let grid = &rigged.solid.grid;
    say!("mesh            {}", args.mesh.display());
    say!(
        "figure          {} (trunk {:.0} degrees from up), template {}",
        rigged.labelling.figure.name(),
        rigged.labelling.trunk_angle,
        rigged.fit.template
    );
    say!(
        "grid            {} x {} x {} ({} interior voxels of {:.6}){}",
        grid.dims[0],
        grid.dims[1],
        grid.dims[2],
        rigged.solid.report.interior_voxels,
        grid.voxel_size,
        match rigged.solid.report.refined_from {
            Some((fraction, held)) => format!(
                "; refined: {held} interior voxels at {fraction} of the longest side were too \
                 few for a thin figure"
            ),
            None => String::new(),
        }
    );
    say!(
        "skeleton        {} joints, {} canonical",
        rigged.fit.skeleton.len(),
        rigged.fit.canonical.len()
    );
    let stages: Vec<String> = std::iter::once(format!("load {load_ms:.1}"))
        .chain(rigged.timings.iter().map(|(s, ms)| format!("{s} {ms:.1}")))
        .chain(std::iter::once(format!("export {export_ms:.1}")))
        .collect();
    say!("timings (ms)    {}", stages.join(", "));
    say!("wrote           {}", args.output.display());
    for path in [&args.skeleton_json, &args.bvh].into_iter().flatten() {
        say!("wrote           {}", path.display());
    }
}

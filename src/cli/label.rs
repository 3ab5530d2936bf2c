//! `skelfit label MESH -o labels.json [--up +Y] [--forward +Z|auto] [--labels OVERRIDE.json]
//! [--ply OUT.ply] [--svg OUT.svg] [--vertex-labels bones|medial]`: body-part labels
//! (dissertation ch.7); and
//! `skelfit label --table REFDATA -o DIR`: the labelling accuracy table over reference models.

use super::common::{load_mesh, write_file, Outputs, VoxelArgs};
use anyhow::{bail, Context};
use clap::{Args, ValueEnum};
use skelfit::anatomy::{
    label_with_overrides, labels_json, labels_ply, labels_svg, Label, LabelOptions, Overrides,
};
use skelfit::eval::label_score;
use skelfit::pipeline::{label_by_bones, rig, RigOptions, MEDIAL_FALLBACK};
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Where the per-mesh-vertex labels come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum)]
pub enum VertexLabels {
    /// From the nearest bone of the anatomical skeleton fitted to the labels (`skelfit rig`),
    /// so a vertex's part is that of the bone that moves it; the medial labels when no rig
    /// can be fitted (with a warning).
    #[default]
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
    /// Forward direction: an axis, a vector x,y,z, or `auto` (guessed from head/tail or feet).
    #[arg(
        long,
        value_name = "DIR",
        default_value = "+Z",
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
    /// Per-vertex labels from the nearest bone of the anatomical skeleton fitted to the labels
    /// (`bones`, default: runs `skelfit rig`'s fit) or from the labelled medial surface
    /// (`medial`, dissertation ch.7).
    #[arg(long, value_enum, default_value_t = VertexLabels::Bones)]
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
    pub fn options(&self) -> anyhow::Result<LabelOptions> {
        let mut options = LabelOptions {
            voxel: self.voxel.options()?,
            up: super::common::parse_up(&self.up)?,
            forward: super::common::parse_forward(&self.forward)?,
            ..Default::default()
        };
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
        Ok(options)
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
    let labels = match args.vertex_labels {
        VertexLabels::Medial => label_with_overrides(&mesh, &options, overrides.as_ref()),
        VertexLabels::Bones => label_by_bones(
            &mesh,
            &RigOptions {
                label: options,
                overrides,
                ..Default::default()
            },
        ),
    }
    .with_context(|| format!("labelling {}", mesh_path.display()))?;
    let json = serde_json::to_string_pretty(&labels_json(&labels, Some(&source)))?;
    outputs.add(&args.output, json);
    if let Some(p) = &args.ply {
        outputs.add(p, labels_ply(&mesh, &labels));
    }
    if let Some(p) = &args.svg {
        outputs.add(p, labels_svg(&mesh, &labels, 320.0));
    }
    outputs.write()?;
    println!("figure          {}", labels.figure.name());
    println!("parts           {}", labels.parts_summary());
    let fell_back = labels
        .warnings
        .iter()
        .any(|w| w.starts_with(MEDIAL_FALLBACK));
    println!(
        "vertex labels   {}",
        match args.vertex_labels {
            VertexLabels::Bones if !fell_back => "nearest bone of the fitted skeleton",
            VertexLabels::Bones => "medial surface (no rig could be fitted, see the warning)",
            VertexLabels::Medial => "medial surface",
        }
    );
    println!("wrote           {}", args.output.display());
    for p in [&args.ply, &args.svg].into_iter().flatten() {
        println!("wrote           {}", p.display());
    }
    for w in &labels.warnings {
        eprintln!("skelfit: warning: {w}");
    }
    if let Some(hint) = super::common::orientation_hint(&labels, labels.frame.up) {
        eprintln!("skelfit: hint: {hint}");
    }
    Ok(())
}

/// Labels every `<kind>/<model>/mesh.obj` below `refdata`
/// (kinds humanoid, quadruped, other, robustness) and writes the table of figure class, parts
/// found and the scores of [`skelfit::eval::label_score`].
fn table(refdata: &Path, out: &Path, options: &LabelOptions) -> anyhow::Result<()> {
    super::common::output_folder(out)?;
    let mut rows = Vec::new();
    // (model, weight share, ceiling) of models with artist weights; (bones, medial) agreements.
    let mut shares: Vec<(String, f64, f64)> = Vec::new();
    let mut agreements: Vec<(f64, f64)> = Vec::new();
    let mut md = String::from(
        "# Body-part labelling accuracy\n\nGenerated by `skelfit label --table ../shared/refdata -o reports/labels` \
         (default options: voxel size 0.01 of the longest side, 20 bins, +Y up, +Z forward; kinds humanoid, quadruped, other, robustness). \
         The scores are computed by `skelfit::eval::label_score` (`src/eval/labels.rs`).\n\n\
         **weight share %** (the headline, issue 21 item 6) scores each vertex's label against the reference's own skin weights, \
         where the model's `source.glb` holds the rig's skin (the artists' JOINTS_0/WEIGHTS_0): the share of the vertex's weight \
         that lies on bones of its predicted part, averaged over the vertices (`anatomy::weight_share`). Bones get their part by the \
         region rule in `src/anatomy/reference.rs` (trunk, head+neck, tail, fore limb L/R, hind limb L/R, wing; arms and front \
         legs are fore limbs); girdle bones with a side (canonical `clavicle_*`, or names with shoulder, clavicle, scapula, \
         hips or pelvis such as `Shoulder.L`, `FrontShoulder.R`, `BackShoulder.L`) count for the trunk and for the limb hanging \
         from them (`anatomy::girdle_limbs`). A vertex moved by a single part scores 100 % when labelled with it; a vertex \
         the artist shared between two parts can score only the larger share: *ceiling %* is the score of labels that give \
         every vertex its best part (`anatomy::best_regions`), the most any labelling can reach on that model. Empty for models without artist weights \
         (the MakeHuman bodies). Target: at least 95 % on every model with artist weights.\n\n\
         *agreement %*: share of mesh vertices whose label maps to the body region of the nearest reference bone \
         (same region rule). Reference rig: `rig_game_engine.json`, else `rig_gltf.json`.\n\n\
         Both are for the default per-vertex labels (`--vertex-labels bones`): each vertex takes the part of the nearest bone \
         of the anatomical skeleton fitted to the labels (`skelfit rig` with default options; our bones' regions by the same rule as the \
         reference's), so a vertex's part is that of the bone that moves it. *per region* is for these labels too. \
         *medial %* is for `--vertex-labels medial`, the labelled medial surface carried through the interior voxels \
         (dissertation ch.7). Medial per-vertex labels give the neck (the trunk's level-graph pieces between the pectoral limbs' junction and the head's, \
         with the protrusions merged into the trunk there) to the head (`RuleOptions::neck_in_head`; `--neck-in-trunk` keeps it in the trunk), and the DMS voxels of arms and fore legs \
         within 0.4 inscribed radii of a trunk DMS voxel (limb roots inside the chest) to the trunk (`RuleOptions::pectoral_root_scale`; \
         `--pectoral-root-scale 0` turns it off). labels.json also has the medial labels' weight share.\n\n\
         *reference rule vs weights %* measures the reference itself: \
         the share of vertices whose nearest-reference-bone region (the rule above) is also the region whose bones carry \
         most of the vertex's skin weight as the artist painted it (`anatomy::weight_regions`). It is how far the \
         nearest-bone rule is from the rig's own answer to \"which bone moves this vertex\". *weights %* is our default \
         labels' agreement with those heaviest-weight regions (no girdle allowance, whole vertices).\n\n\
         | model | figure | parts found | heads | arms | legs | tails | weight share % | ceiling % | agreement % | medial % | reference rule vs weights % | weights % | per region (agreeing/vertices) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for kind in ["humanoid", "quadruped", "other", "robustness"] {
        let dir = refdata.join(kind);
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut models: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
        models.sort();
        for model in models {
            let mesh_path = model.join("mesh.obj");
            if !mesh_path.is_file() {
                continue;
            }
            let name = format!(
                "{kind}/{}",
                model.file_name().unwrap_or_default().to_string_lossy()
            );
            eprintln!("labelling {name}");
            let mesh = load_mesh(&mesh_path)?;
            // One rig gives both: its labelling is `label_with_overrides`'s (the medial
            // per-vertex labels), and its fitted skeleton the default, bone-following ones.
            let rig_options = RigOptions {
                label: *options,
                ..Default::default()
            };
            let (medial, by_bones) = match rig(&mesh, &rig_options) {
                Ok(r) => (r.labelling.clone(), Some(r.into_bone_labels(&mesh))),
                Err(e) => {
                    eprintln!("  {name}: no rig ({e}); medial labels only");
                    let labels = label_with_overrides(&mesh, options, None)
                        .with_context(|| format!("labelling {name}"))?;
                    (labels, None)
                }
            };
            let labels = by_bones.as_ref().unwrap_or(&medial);
            let score = label_score(&model, &mesh, labels, Some(&medial))
                .with_context(|| format!("scoring {name}"))?;
            for note in score.iter().flat_map(|s| &s.notes) {
                eprintln!("  {name}: {note}");
            }
            let percent = |v: Option<f64>| v.map(|p| format!("{p:.1}")).unwrap_or_default();
            let share = score
                .as_ref()
                .and_then(|s| s.weight_share.as_ref())
                .map(|w| w.percent);
            if let (Some(p), Some(c)) = (share, score.as_ref().and_then(|s| s.weight_share_ceiling))
            {
                shares.push((name.clone(), p, c));
            }
            if let Some((a, Some(m))) = score
                .as_ref()
                .filter(|_| by_bones.is_some())
                .map(|s| (s.agreement.percent, s.agreement_medial))
            {
                agreements.push((a, m));
            }
            let regions = score
                .as_ref()
                .map(|s| {
                    s.agreement
                        .per_region
                        .iter()
                        .map(|(r, n, k)| format!("{r} {k}/{n}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                })
                .unwrap_or_default();
            let fell_back = if by_bones.is_none() {
                " (medial: no rig)"
            } else {
                ""
            };
            let _ = writeln!(
                md,
                "| {name} | {} | {} | {} | {} | {} | {} | {} | {} | {}{fell_back} | {} | {} | {} | {} |",
                labels.figure.name(),
                labels.parts_summary(),
                labels.count(Label::Head),
                labels.count(Label::Arm),
                labels.count(Label::Leg),
                labels.count(Label::Tail),
                share.map(|p| format!("**{p:.1}**")).unwrap_or_default(),
                percent(score.as_ref().and_then(|s| s.weight_share_ceiling)),
                percent(score.as_ref().map(|s| s.agreement.percent)),
                percent(score.as_ref().and_then(|s| s.agreement_medial)),
                percent(score.as_ref().and_then(|s| s.rule_vs_weights)),
                percent(score.as_ref().and_then(|s| s.agreement_with_weights)),
                regions
            );
            rows.push(serde_json::json!({
                "model": name,
                "figure": labels.figure.name(),
                "parts": labels.parts_summary(),
                "vertex_labels": if by_bones.is_some() { "bones" } else { "medial" },
                "weight_share_percent": share,
                "weight_share_per_region": score.as_ref().and_then(|s| s.weight_share.as_ref()).map(|w| &w.per_region),
                "weight_share_vertices": score.as_ref().and_then(|s| s.weight_share.as_ref()).map(|w| w.compared),
                "weight_share_medial_percent": score.as_ref().and_then(|s| s.weight_share_medial),
                "weight_share_ceiling_percent": score.as_ref().and_then(|s| s.weight_share_ceiling),
                "agreement_percent": score.as_ref().map(|s| s.agreement.percent),
                "agreement_medial_percent": score.as_ref().and_then(|s| s.agreement_medial),
                "reference_rule_vs_weights_percent": score.as_ref().and_then(|s| s.rule_vs_weights),
                "agreement_with_weights_percent": score.as_ref().and_then(|s| s.agreement_with_weights),
                "per_region": regions,
                "confusion": score.as_ref().map(|s| &s.agreement.confusion),
                "warnings": labels.warnings,
            }));
        }
    }
    let list = |v: Vec<String>| {
        if v.is_empty() {
            "none".to_owned()
        } else {
            v.join(", ")
        }
    };
    let below: Vec<String> = shares
        .iter()
        .filter(|s| s.1 < 95.0)
        .map(|(m, p, _)| format!("{m} {p:.1}"))
        .collect();
    let capped: Vec<String> = shares
        .iter()
        .filter(|s| s.2 < 95.0)
        .map(|(m, _, c)| format!("{m} {c:.1}"))
        .collect();
    let _ = write!(
        md,
        "\n## Summary\n\n\
         * weight share: {} of {} models with artist weights reach 95 %; below: {}.\n\
         * ceiling below 95 % (no labelling reaches 95 % on these weights): {}.\n\
         * the bone-following labels agree with the nearest reference bone better than the medial ones on {} of {} models.\n",
        shares.len() - below.len(),
        shares.len(),
        list(below),
        list(capped),
        agreements.iter().filter(|(a, m)| a > m).count(),
        agreements.len(),
    );
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    md.push_str(
        "\n## Notes\n\n\
         Where the ceiling is below 100 %, the artist blended two parts across a joint, and a vertex there can be \
         labelled with one of them only. On the humanoids most of the loss is the hip crease, where a central `Hips`/pelvis \
         bone (the trunk's root, not a sided girdle, so it counts for the trunk only) shares the groin with the thigh, \
         and the armpit, where the upper arm shares with the chest rather than with the clavicle; on the quadrupeds the \
         base of the neck and the haunches. `cargo run --release --example weight_share_loss -- ../shared/refdata/<kind>/<model>` \
         lists, for one model, the girdle bones and which bones cost the ceiling how much.\n\n\
         Below the ceiling, a lost limb or a limb taken for another part costs its whole skin: the real characters whose \
         fit drops an arm (gdquest_mannequiny, the cyberpunk character) or splits stubby limbs into several parts (the \
         platformer character; see `reports/real/`) score far below their ceiling, as do the figures no template suits \
         (spider, wasp, dolphin, apatosaurus).\n\n\
         The nearest-bone agreement depends on the reference rig's conventions at the limb roots and the base of the \
         neck, where the reference rigs disagree with each other and with anatomy: the Quaternius rigs have no upper-arm \
         bone (their front legs start at the elbow, `FrontUpperLeg.*` is the forearm, and a short trunk `FrontShoulder` \
         bone leads to it from the chest floor), so the skin over the upper arm is trunk, but their hind legs start at \
         the top of the haunch (`BackLeg` from the hip beside the spine); the fox's legs hang straight from the spine \
         (its belly is nearer the hind-leg bones than the dorsal spine); the triceratops' `FrontLeg.*`/`BackLeg.*` \
         bones run horizontally from the body's midline, so by the region rule (a bone named `leg` is a limb) its chest \
         and belly count as legs. The medial labels' limb roots follow wherever the medial surface's limb pieces leave \
         the trunk's, so they vary more with tessellation (the `robustness/` variants) than the bone-following ones; \
         `cargo run --release --example label_conventions` compares conventions for the skin over the upper arm. \
         The weight share does not depend on these conventions: it reads the artists' weights, and the girdle bones \
         (the `FrontShoulder`/`BackShoulder` bones, clavicles) count for both the trunk and their limb.\n",
    );
    write_file(&out.join("labels.md"), md.as_bytes())?;
    write_file(
        &out.join("labels.json"),
        serde_json::to_string_pretty(&rows)?.as_bytes(),
    )?;
    print!("{md}");
    Ok(())
}

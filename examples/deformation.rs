//! The deformation check over the reference data: for every humanoid and quadruped, the
//! stretched edges of the standard pose sweep with skelfit's rig and weights, with the
//! artist's own skeleton and weights from `source.glb` where the model has them, and with
//! skelfit's weights on the artist's skeleton (`skelfit skin`, `skin::skin_skeleton`), which
//! is also compared with the artist's weights over 20 seeded random poses (mean vertex
//! distance, RigNet's deformation error).
//!
//! Writes `reports/deformation/deformation.md` (per model and per pose) and
//! `reports/deformation/deformation.json`.
//!
//! Blender's automatic (bone heat) weights on the same artist skeletons are measured the
//! same way where `tools/blender_autoweights.py` has written them (`OUT_DIR/blender/<kind>/
//! <model>.json`); the report says "not measured" where they are absent. Blender is not needed
//! to run this example.
//!
//! Run: `cargo run --release --example deformation [-- REFDATA_DIR [OUT_DIR]]`
//! (defaults `../shared/refdata`, `reports/deformation`).

#[path = "common/refdata.rs"]
mod refdata;

use refdata::{
    artist_rig, blender_file, blender_weights, check, distance_with_unweighted, exported, models,
    weight_difference, ArtistRig,
};
use skelfit::mesh::load;
use skelfit::pipeline::{rig, RigOptions};
use skelfit::skin::check::{DeformationCheck, PoseStretch, SweepKind};
use skelfit::skin::compare::{pose_distance, PoseDistance, RandomPoseOptions};
use skelfit::skin::{skin_skeleton, SkeletonSkinOptions, SkinMethod};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn main() {
    if let Err(message) = run() {
        eprintln!("deformation: error: {message}");
        std::process::exit(1);
    }
}

struct Row {
    model: String,
    ours: Result<DeformationCheck, String>,
    anchor: Result<DeformationCheck, String>,
    artist: Option<Result<DeformationCheck, String>>,
    /// skelfit's weights on the artist's skeleton: the sweep, the random-pose distance to the
    /// artist's weights (mesh units) and the figure size it is divided by.
    on_artist: Option<Result<OnArtist, String>>,
    /// Blender's bone heat weights on the artist's skeleton, where exported.
    blender: Option<Result<Blender, String>>,
}

/// Blender's automatic weights on the artist's skeleton, through the sweep and against the
/// artist's weights.
struct Blender {
    check: DeformationCheck,
    distance: PoseDistance,
    /// Vertices of the artist's mesh Blender left without weight (or that matched no vertex
    /// of Blender's export).
    unweighted: usize,
    /// How far Blender's weights lie from the artist's ([`weight_difference`]).
    difference: f64,
}

struct OnArtist {
    check: DeformationCheck,
    distance: PoseDistance,
    /// The same distance for the anchor weights on the artist's skeleton.
    anchor: PoseDistance,
    size: f64,
    check_vertices: usize,
    warnings: usize,
    /// How far skelfit's weights lie from the artist's ([`weight_difference`]).
    difference: f64,
}

fn ours(dir: &Path, kind: SweepKind, method: SkinMethod) -> Result<DeformationCheck, String> {
    let mesh = load(&dir.join("mesh.obj")).map_err(|e| e.to_string())?;
    let mut options = RigOptions::default();
    options.skin.method = method;
    let rig = rig(&mesh, &options).map_err(|e| e.to_string())?;
    let weights = exported(&rig.skin.engine);
    check(&mesh, &rig.fit.skeleton, &rig.fit.canonical, &weights, kind)
}

fn artist(rig: &ArtistRig, kind: SweepKind) -> Result<DeformationCheck, String> {
    check(&rig.mesh, &rig.skeleton, &rig.canonical, &rig.weights, kind)
}

/// skelfit's weights on the artist's skeleton (what `skelfit skin source.glb --skeleton
/// source.glb` writes), through the sweep and against the artist's weights.
fn on_artist(rig: &ArtistRig, kind: SweepKind) -> Result<OnArtist, String> {
    let skinned = skin_skeleton(&rig.mesh, &rig.skeleton, &SkeletonSkinOptions::default())
        .map_err(|e| e.to_string())?;
    let weights = exported(&skinned.skin.engine);
    let check = check(&rig.mesh, &rig.skeleton, &rig.canonical, &weights, kind)?;
    let distance = pose_distance(
        &rig.mesh,
        &rig.skeleton,
        &weights,
        &rig.weights,
        &RandomPoseOptions::default(),
    )
    .map_err(|e| e.to_string())?;
    // The dissertation's anchor weights on the same skeleton, for scale.
    let mut options = SkeletonSkinOptions::default();
    options.skin.method = SkinMethod::Anchor;
    let anchor = skin_skeleton(&rig.mesh, &rig.skeleton, &options).map_err(|e| e.to_string())?;
    let anchor = pose_distance(
        &rig.mesh,
        &rig.skeleton,
        &exported(&anchor.skin.engine),
        &rig.weights,
        &RandomPoseOptions::default(),
    )
    .map_err(|e| e.to_string())?;
    let size = rig.size();
    if size <= 0.0 {
        return Err("empty mesh".into());
    }
    Ok(OnArtist {
        check,
        distance,
        anchor,
        size,
        check_vertices: rig.mesh.positions.len(),
        warnings: skinned.warnings.len(),
        difference: weight_difference(rig, &weights),
    })
}

/// Blender's bone heat weights on the artist's skeleton through the sweep and against the
/// artist's weights; `None` where `tools/blender_autoweights.py` wrote no file.
fn blender(file: &Path, rig: &ArtistRig, kind: SweepKind) -> Option<Result<Blender, String>> {
    if !file.is_file() {
        return None;
    }
    Some((|| {
        let (weights, unweighted) = blender_weights(file, rig)?;
        let check = check(&rig.mesh, &rig.skeleton, &rig.canonical, &weights, kind)?;
        let distance = distance_with_unweighted(rig, &weights);
        Ok(Blender {
            check,
            distance,
            unweighted,
            difference: weight_difference(rig, &weights),
        })
    })())
}

/// The stretch of the pose called `pose` in `check`, if it was posed.
fn pose_in<'a>(check: Option<&'a DeformationCheck>, pose: &str) -> Option<&'a PoseStretch> {
    check.and_then(|c| c.poses.iter().find(|q| q.pose == pose))
}

/// The table of skelfit's weights on the artists' skeletons against the artists' weights.
fn on_artist_section(md: &mut String, rows: &[Row]) {
    let options = RandomPoseOptions::default();
    let _ = writeln!(
        md,
        "\n## skelfit weights on the artist's skeleton\n\n\
         Every model with `source.glb`: its mesh and skeleton as the artist shipped them, skinned \
         by `skelfit skin` (the weights `skelfit rig` computes, on the artist's joints; control \
         joints get none). \"sweep\" counts the edges past 2x (1.5x) over the standard sweep as \
         above (— where the model's canonical map names no joints to pose). \"random poses\" is \
         the deformation error RigNet reports: the mean (and largest) distance between the mesh \
         skinned with skelfit's weights and with the artist's, over {} seeded random poses \
         (every deforming joint turned about a random axis by up to ±{}°, seed {}), in % of the \
         longest side of the bounding box, over the vertices the artist skinned (the stag's \
         antlers are a rigid part attached to a joint node, not skinned). \"anchor\" is the \
         same distance for the dissertation's anchor weights on the artist's skeleton \
         (`SkinMethod::Anchor`), for scale. \"Blender bone heat\" is Blender's automatic \
         weights (Object > Parent > With Automatic Weights, Baran & Popović 2007) on the same \
         skeleton, the same mesh and the same deforming joints, at most four per vertex as its \
         glTF exporter writes, measured the same way; where bone heat left vertices unweighted \
         on the first try, after Merge by Distance; vertices it still leaves unweighted stay at \
         rest, as in Blender, and count in the distance. \"weights apart\" is how far \
         skelfit's and Blender's weights lie from the artist's: per vertex, half the sum of the \
         absolute weight differences over the joints (0: the same, 1: no joint in common), \
         averaged; where Blender's are within a few hundredths, the artist's weights are bone \
         heat's own, touched up. Regenerate them with Blender 3.4 \
         (not part of `cargo test`): `blender -b --python tools/blender_autoweights.py -- \
         reports/deformation/blender ../shared/refdata/humanoid/* ../shared/refdata/quadruped/*`, \
         then this example; \"not measured\" where no export is present.\n\n\
         | model | artist sweep >2x (>1.5x) | skelfit on artist sweep >2x (>1.5x) | Blender bone heat sweep >2x (>1.5x) | random poses: skelfit mean % | skelfit max % | Blender bone heat mean % | Blender max % | weights apart from the artist's: skelfit / Blender | anchor: mean % | vertices measured | Blender unweighted | skin warnings |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        options.poses, options.max_degrees, options.seed
    );
    let sweep = |c: &DeformationCheck| {
        if c.poses.is_empty() {
            "—".to_string()
        } else {
            format!("{} ({})", c.total_over_2(), c.total_over_1_5())
        }
    };
    let (mut means, mut anchor_means) = (Vec::new(), Vec::new());
    // skelfit's and Blender's means over the models where both were measured.
    let mut pairs: Vec<(f64, f64)> = Vec::new();
    for row in rows {
        let Some(on) = &row.on_artist else {
            continue;
        };
        let artist = match &row.artist {
            Some(Ok(a)) => sweep(a),
            _ => "—".into(),
        };
        match on {
            Ok(o) => {
                let mean = 100.0 * o.distance.mean / o.size;
                let anchor = 100.0 * o.anchor.mean / o.size;
                means.push(mean);
                anchor_means.push(anchor);
                let (b_sweep, b_mean, b_max, b_apart, b_unweighted) = match &row.blender {
                    None => (
                        "not measured".to_string(),
                        "not measured".to_string(),
                        "—".to_string(),
                        "—".to_string(),
                        "—".to_string(),
                    ),
                    Some(Err(e)) => (
                        format!("failed: {e}"),
                        "—".into(),
                        "—".into(),
                        "—".into(),
                        "—".into(),
                    ),
                    Some(Ok(b)) => {
                        let b_mean = 100.0 * b.distance.mean / o.size;
                        pairs.push((mean, b_mean));
                        (
                            sweep(&b.check),
                            format!("{b_mean:.2}"),
                            format!("{:.1}", 100.0 * b.distance.max / o.size),
                            format!("{:.2}", b.difference),
                            b.unweighted.to_string(),
                        )
                    }
                };
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {} | {:.2} | {:.1} | {} | {} | {:.2} / {} | {:.2} | {} / {} | {} | {} |",
                    row.model,
                    artist,
                    sweep(&o.check),
                    b_sweep,
                    mean,
                    100.0 * o.distance.max / o.size,
                    b_mean,
                    b_max,
                    o.difference,
                    b_apart,
                    anchor,
                    o.distance.vertices,
                    o.check_vertices,
                    b_unweighted,
                    o.warnings
                );
            }
            Err(e) => {
                let _ = writeln!(
                    md,
                    "| {} | {} | failed: {e} | — | — | — | — | — | — | — | — | — | — |",
                    row.model, artist
                );
            }
        }
    }
    if !means.is_empty() {
        let _ = writeln!(
            md,
            "\nMean over {} models: {:.2} % of the longest side (anchor weights: {:.2} %).",
            means.len(),
            means.iter().sum::<f64>() / means.len() as f64,
            anchor_means.iter().sum::<f64>() / anchor_means.len() as f64
        );
    }
    if !pairs.is_empty() {
        let n = pairs.len() as f64;
        let _ = writeln!(
            md,
            "\nOn the {} models with Blender's weights: skelfit {:.2} %, Blender bone heat {:.2} %; \
             skelfit closer to the artist on {} of them.",
            pairs.len(),
            pairs.iter().map(|p| p.0).sum::<f64>() / n,
            pairs.iter().map(|p| p.1).sum::<f64>() / n,
            pairs.iter().filter(|p| p.0 < p.1).count()
        );
    }
    // The models whose artist's weights are bone heat's own (Blender's lie within 0.1).
    let bone_heat: Vec<String> = rows
        .iter()
        .filter_map(|row| match (&row.on_artist, &row.blender) {
            (Some(Ok(o)), Some(Ok(b))) if b.difference < 0.1 => Some(format!(
                "{} ({:.2} apart; {:.2} % against skelfit's {:.2} %)",
                row.model.rsplit('/').next().unwrap_or(&row.model),
                b.difference,
                100.0 * b.distance.mean / o.size,
                100.0 * o.distance.mean / o.size
            )),
            _ => None,
        })
        .collect();
    if !bone_heat.is_empty() {
        let _ = writeln!(
            md,
            "\nWhere Blender's weights lie within 0.1 of the artist's, the artist kept bone heat's \
             own weights, touched up, and Blender's distance measures its own output: {}.",
            bone_heat.join(", ")
        );
    }
    let _ = writeln!(
        md,
        "\nThe largest distances (20-30 % of the figure at the worst vertex) are on the \
         Quaternius animals whose hoof or paw bones are IK joints outside the leg chains \
         (`IKFrontLeg.L`, `IKBackLeg.R`...: deforming root joints at the feet). The lower leg's \
         segment ends where the IK joint's inscribed ball begins, so the hoof follows the IK \
         joint as the artist's does, but the ankle blends the two, and random \
         forward-kinematics poses leave the IK joints where they are while the leg turns; \
         under the IK solver they are meant for, they follow the leg. The animals without such \
         joints (apatosaurus, rat, triceratops) stay below 15 %."
    );
}

fn run() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let root = PathBuf::from(args.next().unwrap_or_else(|| "../shared/refdata".into()));
    let out = PathBuf::from(args.next().unwrap_or_else(|| "reports/deformation".into()));
    if !root.is_dir() {
        return Err(format!(
            "{} is not a directory: pass the reference data folder",
            root.display()
        ));
    }
    let mut rows = Vec::new();
    for model in models(&root) {
        let (dir, kind) = (&model.dir, model.kind);
        eprintln!("deformation: {}", model.id());
        let rig = artist_rig(dir);
        rows.push(Row {
            model: model.id(),
            ours: ours(dir, kind, SkinMethod::Geodesic),
            anchor: ours(dir, kind, SkinMethod::Anchor),
            artist: rig.as_ref().map(|r| {
                r.as_ref()
                    .map_err(Clone::clone)
                    .and_then(|r| artist(r, kind))
            }),
            on_artist: rig.as_ref().map(|r| {
                r.as_ref()
                    .map_err(Clone::clone)
                    .and_then(|r| on_artist(r, kind))
            }),
            blender: rig.as_ref().and_then(|r| match r {
                Ok(r) => blender(&blender_file(&out, &model), r, kind),
                Err(e) => Some(Err(e.clone())),
            }),
        });
    }
    std::fs::create_dir_all(&out).map_err(|e| e.to_string())?;
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Deformation check\n\nEdges stretched past 2x (and 1.5x) their rest length, summed \
         over the standard pose sweep (humanoid: 14 poses; animal: 11; each joint turned about \
         its own position, linear blend skinning with at most four influences per vertex as \
         exported). \"skelfit\" is `skelfit rig` with its default (geodesic) weights, \"anchor\" \
         the same rig with the dissertation's anchor weights (`SkinMethod::Anchor`, the default \
         before), \"artist\" the model's own skeleton and weights from `source.glb`, posed \
         through the same sweep where its canonical map names the joints (— where it has none), \
         \"on artist\" skelfit's weights on the artist's skeleton (`skelfit skin source.glb \
         --skeleton source.glb`: the same skinning as `skelfit rig`, on the artist's joints; \
         same mesh, same poses as \"artist\").\n\n\
         Regenerate: `cargo run --release --example deformation`\n\n\
         | model | edges | skelfit >2x | skelfit >1.5x | skelfit worst | anchor >2x | artist >2x | artist >1.5x | artist worst | skelfit weights on the artist's skeleton >2x | Blender bone heat on the artist's skeleton >2x | poses (skelfit / artist) |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
    );
    let cell = |c: &Option<&DeformationCheck>| match c {
        Some(c) if !c.poses.is_empty() => format!(
            "{} | {} | {:.2}",
            c.total_over_2(),
            c.total_over_1_5(),
            c.worst()
        ),
        _ => "— | — | —".into(),
    };
    for row in &rows {
        let ours = row.ours.as_ref().ok();
        let artist = row.artist.as_ref().and_then(|a| a.as_ref().ok());
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} / {} |",
            row.model,
            ours.or(artist).map_or(0, |c| c.edges),
            cell(&ours),
            row.anchor
                .as_ref()
                .map_or("—".into(), |a| a.total_over_2().to_string()),
            cell(&artist),
            match &row.on_artist {
                Some(Ok(o)) if !o.check.poses.is_empty() => o.check.total_over_2().to_string(),
                Some(Err(_)) => "failed".into(),
                _ => "—".into(),
            },
            match &row.blender {
                Some(Ok(b)) if !b.check.poses.is_empty() => b.check.total_over_2().to_string(),
                Some(Ok(_)) => "—".into(),
                Some(Err(_)) => "failed".into(),
                None if row.on_artist.is_some() => "not measured".into(),
                None => "—".into(),
            },
            ours.map_or(0, |c| c.poses.len()),
            artist.map_or(0, |c| c.poses.len()),
        );
    }
    on_artist_section(&mut md, &rows);
    let _ = writeln!(md, "\n## Per pose (edges past 2x: skelfit / artist)\n");
    for row in &rows {
        let _ = writeln!(md, "### {}\n", row.model);
        match &row.ours {
            Err(e) => {
                let _ = writeln!(md, "skelfit failed: {e}\n");
            }
            Ok(ours) => {
                let artist = row.artist.as_ref().and_then(|a| a.as_ref().ok());
                let _ = writeln!(
                    md,
                    "| pose | skelfit >2x | skelfit >1.5x | artist >2x | artist >1.5x | on artist >2x | on artist >1.5x |\n|---|---:|---:|---:|---:|---:|---:|"
                );
                let on = match &row.on_artist {
                    Some(Ok(o)) => Some(&o.check),
                    _ => None,
                };
                for p in &ours.poses {
                    let (a, o) = (pose_in(artist, &p.pose), pose_in(on, &p.pose));
                    let _ = writeln!(
                        md,
                        "| {} | {} | {} | {} | {} | {} | {} |",
                        p.pose,
                        p.over_2,
                        p.over_1_5,
                        a.map_or("—".into(), |a| a.over_2.to_string()),
                        a.map_or("—".into(), |a| a.over_1_5.to_string()),
                        o.map_or("—".into(), |o| o.over_2.to_string()),
                        o.map_or("—".into(), |o| o.over_1_5.to_string()),
                    );
                }
                if !ours.missing.is_empty() {
                    let _ = writeln!(md, "\nnot posed (no joint): {}", ours.missing.join(", "));
                }
                if let Some(Err(e)) = &row.artist {
                    let _ = writeln!(md, "\nartist weights not checked: {e}");
                }
                let _ = writeln!(md);
            }
        }
    }
    std::fs::write(out.join("deformation.md"), &md).map_err(|e| e.to_string())?;
    let json: Vec<serde_json::Value> = rows
        .iter()
        .map(|r| {
            serde_json::json!({
                "model": r.model,
                "skelfit": r.ours.as_ref().map_err(Clone::clone),
                "artist": r.artist.as_ref().map(|a| a.as_ref().map_err(Clone::clone)),
                "skelfit_on_artist_skeleton": r.on_artist.as_ref().map(|o| match o {
                    Ok(o) => serde_json::json!({
                        "check": o.check,
                        "random_pose_distance": o.distance,
                        "anchor_random_pose_distance": o.anchor,
                        "figure_size": o.size,
                        "weight_difference": o.difference,
                        "mean_percent": 100.0 * o.distance.mean / o.size,
                        "max_percent": 100.0 * o.distance.max / o.size,
                        "warnings": o.warnings,
                    }),
                    Err(e) => serde_json::json!({"error": e}),
                }),
                "blender_bone_heat_on_artist_skeleton": r.blender.as_ref().map(|b| match b {
                    Ok(b) => serde_json::json!({
                        "check": b.check,
                        "random_pose_distance": b.distance,
                        "unweighted_vertices": b.unweighted,
                        "weight_difference": b.difference,
                    }),
                    Err(e) => serde_json::json!({"error": e}),
                }),
            })
        })
        .collect();
    std::fs::write(
        out.join("deformation.json"),
        serde_json::to_string_pretty(&json).map_err(|e| e.to_string())?,
    )
    .map_err(|e| e.to_string())?;
    print!("{md}");
    Ok(())
}

//! The deformation check over the reference data: for every humanoid and quadruped, the
//! stretched edges of the standard pose sweep with skelfit's rig and weights, and with the
//! artist's own skeleton and weights from `source.glb` where the model has them.
//!
//! Writes `reports/deformation/deformation.md` (per model and per pose) and
//! `reports/deformation/deformation.json`.
//!
//! Run: `cargo run --release --example deformation [-- REFDATA_DIR [OUT_DIR]]`
//! (defaults `../shared/refdata`, `reports/deformation`).

use skelfit::eval::load_skeleton;
use skelfit::mesh::{load, load_gltf_scene, Mesh};
use skelfit::pipeline::{rig, RigOptions};
use skelfit::skeleton::{JointId, Skeleton};
use skelfit::skin::check::{check_deformation, sweep, DeformationCheck, SweepKind};
use skelfit::skin::SkinMethod;
use std::collections::BTreeMap;
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
}

fn check(
    mesh: &Mesh,
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    weights: &[Vec<(JointId, f64)>],
    kind: SweepKind,
) -> Result<DeformationCheck, String> {
    let (poses, missing) = sweep(skeleton, canonical, kind, glam::DVec3::Y, glam::DVec3::Z);
    check_deformation(mesh, skeleton, weights, kind, &poses, missing).map_err(|e| e.to_string())
}

fn ours(dir: &Path, kind: SweepKind, method: SkinMethod) -> Result<DeformationCheck, String> {
    let mesh = load(&dir.join("mesh.obj")).map_err(|e| e.to_string())?;
    let mut options = RigOptions::default();
    options.skin.method = method;
    let rig = rig(&mesh, &options).map_err(|e| e.to_string())?;
    let engine = &rig.skin.engine;
    let weights: Vec<Vec<(JointId, f64)>> = engine
        .joints
        .iter()
        .zip(&engine.weights)
        .map(|(j, w)| {
            j.iter()
                .zip(w)
                .filter(|(_, &w)| w > 0.0)
                .map(|(&j, &w)| (JointId(usize::from(j)), f64::from(w)))
                .collect()
        })
        .collect();
    check(&mesh, &rig.fit.skeleton, &rig.fit.canonical, &weights, kind)
}

fn artist(dir: &Path, kind: SweepKind) -> Option<Result<DeformationCheck, String>> {
    let source = dir.join("source.glb");
    if !source.is_file() {
        return None;
    }
    Some((|| {
        let scene = load_gltf_scene(&source).map_err(|e| e.to_string())?;
        let skeleton = scene.skeleton.ok_or("no skin")?;
        let weights = scene.weights.ok_or("no weights")?;
        let reference = std::fs::read_dir(dir)
            .map_err(|e| e.to_string())?
            .filter_map(Result::ok)
            .map(|e| e.path())
            .find(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("rig_") && n.ends_with(".json"))
            })
            .ok_or("no rig_*.json")?;
        let reference = load_skeleton(&reference).map_err(|e| e.to_string())?;
        let canonical: BTreeMap<String, JointId> = reference
            .canonical
            .iter()
            .filter_map(|(key, &id)| {
                let name = &reference.skeleton.joint(id).name;
                Some((key.clone(), skeleton.find(name)?))
            })
            .collect();
        check(&scene.mesh, &skeleton, &canonical, &weights, kind)
    })())
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
    for (folder, kind) in [
        ("humanoid", SweepKind::Humanoid),
        ("quadruped", SweepKind::Animal),
    ] {
        let Ok(entries) = std::fs::read_dir(root.join(folder)) else {
            continue;
        };
        let mut dirs: Vec<PathBuf> = entries.filter_map(Result::ok).map(|e| e.path()).collect();
        dirs.sort();
        for dir in dirs {
            let model = format!(
                "{folder}/{}",
                dir.file_name().unwrap_or_default().to_string_lossy()
            );
            eprintln!("deformation: {model}");
            rows.push(Row {
                model,
                ours: ours(&dir, kind, SkinMethod::Geodesic),
                anchor: ours(&dir, kind, SkinMethod::Anchor),
                artist: artist(&dir, kind),
            });
        }
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
         through the same sweep where its canonical map names the joints (— where it has none).\n\n\
         Regenerate: `cargo run --release --example deformation`\n\n\
         | model | edges | skelfit >2x | skelfit >1.5x | skelfit worst | anchor >2x | artist >2x | artist >1.5x | artist worst | poses (skelfit / artist) |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---|"
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
            "| {} | {} | {} | {} | {} | {} / {} |",
            row.model,
            ours.or(artist).map_or(0, |c| c.edges),
            cell(&ours),
            row.anchor
                .as_ref()
                .map_or("—".into(), |a| a.total_over_2().to_string()),
            cell(&artist),
            ours.map_or(0, |c| c.poses.len()),
            artist.map_or(0, |c| c.poses.len()),
        );
    }
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
                    "| pose | skelfit >2x | skelfit >1.5x | artist >2x | artist >1.5x |\n|---|---:|---:|---:|---:|"
                );
                for p in &ours.poses {
                    let a = artist
                        .filter(|a| !a.poses.is_empty())
                        .and_then(|a| a.poses.iter().find(|q| q.pose == p.pose));
                    let _ = writeln!(
                        md,
                        "| {} | {} | {} | {} | {} |",
                        p.pose,
                        p.over_2,
                        p.over_1_5,
                        a.map_or("—".into(), |a| a.over_2.to_string()),
                        a.map_or("—".into(), |a| a.over_1_5.to_string()),
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

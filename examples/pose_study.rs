//! Pose robustness of the anatomical rig on real characters: every humanoid with the artist's
//! skinned `source.glb` is re-posed by the artist's own skin weights (linear blend skinning of
//! the artist's skeleton) with both arms set at several angles below the horizontal (raised
//! -20°, T-pose 0°, A-poses 15° to 45°, arms low 60° and 75°, at the sides 85°), then rigged by
//! `skelfit rig`'s defaults (automatic orientation); the core joints are compared with the
//! artist's joints in the same pose.
//!
//! `cargo run --release --example pose_study [REFDATA] [OUT] [--meshes]` (defaults
//! `../shared/refdata`, `reports/pose`): prints a table and writes `pose.md` and `pose.json`
//! to OUT; with `--meshes` also each posed mesh (`OUT/meshes/<model>_<angle>.obj`) and the
//! artist's core joints in that pose beside it (`.reference.json`), to rig again by hand.

#[path = "common/refdata.rs"]
mod refdata;

use refdata::{artist_rig, ArtistRig};
use skelfit::eval::CORE_KEYS;
use skelfit::pipeline::{rig, RigOptions};
use std::fmt::Write as _;
use std::path::PathBuf;

/// Arm angles below the horizontal, degrees.
const ANGLES: [f64; 8] = [-20.0, 0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0];

/// One posed variant's result.
#[derive(serde::Serialize)]
struct Row {
    model: String,
    angle: f64,
    /// Core keys the artist maps.
    mapped: usize,
    /// Of those, the keys the rig has.
    paired: usize,
    /// Mean core error, % of height (paired keys).
    mean_percent: Option<f64>,
    /// Worst core key and its error, % of height.
    worst: Option<(String, f64)>,
    /// Core keys the artist maps that the rig lacks.
    missing: Vec<String>,
    failure: Option<String>,
}

impl Row {
    /// The mean core error as printed, `–` without one.
    fn mean_cell(&self) -> String {
        self.mean_percent.map_or("–".into(), |m| format!("{m:.2}"))
    }

    /// The worst core key and its error as printed, empty without one.
    fn worst_cell(&self) -> String {
        self.worst
            .as_ref()
            .map_or(String::new(), |(k, e)| format!("{k} {e:.2}"))
    }
}

fn posed_row(name: &str, artist: &ArtistRig, angle: f64, meshes: Option<&std::path::Path>) -> Row {
    let mut row = Row {
        model: name.to_string(),
        angle,
        mapped: 0,
        paired: 0,
        mean_percent: None,
        worst: None,
        missing: Vec::new(),
        failure: None,
    };
    let (mesh, posed) = match artist.with_arms_at(angle) {
        Ok(posed) => posed,
        Err(e) => {
            row.failure = Some(e);
            return row;
        }
    };
    // The posed mesh and the artist's core joints in the pose, to rig again by hand.
    if let Some(dir) = meshes {
        let file = dir.join(format!("{name}_{angle}.obj"));
        let core: std::collections::BTreeMap<&str, [f64; 3]> = CORE_KEYS
            .iter()
            .filter_map(|&key| Some((key, posed.get(key)?.to_array())))
            .collect();
        if let Err(e) = std::fs::create_dir_all(dir)
            .map_err(|e| e.to_string())
            .and_then(|()| skelfit::export::write_obj(&file, &mesh).map_err(|e| e.to_string()))
            .and_then(|()| {
                std::fs::write(
                    file.with_extension("reference.json"),
                    serde_json::to_string_pretty(&core).unwrap_or_default(),
                )
                .map_err(|e| e.to_string())
            })
        {
            eprintln!("could not write {}: {e}", file.display());
        }
    }
    let height = mesh
        .bounding_box()
        .map_or(1.0, |(low, high)| (high - low).y.max(1e-12));
    let fitted = match rig(&mesh, &RigOptions::default()) {
        Ok(r) => r,
        Err(e) => {
            row.failure = Some(e.to_string());
            return row;
        }
    };
    let mut errors = Vec::new();
    for key in CORE_KEYS {
        let Some(&reference) = posed.get(key) else {
            continue;
        };
        row.mapped += 1;
        match fitted.fit.canonical.get(key) {
            Some(&p) => {
                let error =
                    100.0 * fitted.fit.skeleton.joint(p).position.distance(reference) / height;
                errors.push((key.to_string(), error));
            }
            None => row.missing.push(key.to_string()),
        }
    }
    row.paired = errors.len();
    if !errors.is_empty() {
        row.mean_percent = Some(errors.iter().map(|e| e.1).sum::<f64>() / errors.len() as f64);
        row.worst = errors.into_iter().max_by(|a, b| a.1.total_cmp(&b.1));
    }
    row
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let write_meshes = args.iter().any(|a| a == "--meshes");
    let mut paths = args.iter().filter(|a| *a != "--meshes");
    let root = PathBuf::from(paths.next().map_or("../shared/refdata", |s| s.as_str()));
    let out = PathBuf::from(paths.next().map_or("reports/pose", |s| s.as_str()));
    let meshes = write_meshes.then(|| out.join("meshes"));
    let humanoids = root.join("humanoid");
    let Ok(entries) = std::fs::read_dir(&humanoids) else {
        eprintln!("no {}: nothing to study", humanoids.display());
        return;
    };
    let mut dirs: Vec<PathBuf> = entries.filter_map(Result::ok).map(|e| e.path()).collect();
    dirs.sort();
    let mut rows = Vec::new();
    for dir in dirs {
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        let Some(artist) = artist_rig(&dir) else {
            continue;
        };
        let artist = match artist {
            Ok(a) => a,
            Err(e) => {
                eprintln!("{name}: {e}");
                continue;
            }
        };
        for angle in ANGLES {
            let row = posed_row(&name, &artist, angle, meshes.as_deref());
            println!(
                "{:32} {:>4}°  core {:>6}  paired {}/{}  worst {:<24} missing {:?} {}",
                row.model,
                row.angle,
                row.mean_cell(),
                row.paired,
                row.mapped,
                row.worst_cell(),
                row.missing,
                row.failure.as_deref().unwrap_or("")
            );
            rows.push(row);
        }
    }
    let mut md = String::from(
        "# Pose robustness: real characters re-posed by their artists' weights\n\n\
         Generated by `cargo run --release --example pose_study`. Each humanoid with the artist's \
         skinned `source.glb` is posed by linear blend skinning of the artist's skeleton and \
         weights with both upper arms set at the angle below the horizontal, then rigged by \
         `skelfit rig`'s defaults (automatic orientation); *core %* is the mean error of the core \
         joints against the artist's joints in the same pose, % of height.\n\n\
         | model | arms below horizontal | core % | paired / mapped | worst | missing | failure |\n\
         |---|---:|---:|---|---|---|---|\n",
    );
    for r in &rows {
        let _ = writeln!(
            md,
            "| {} | {}° | {} | {}/{} | {} | {} | {} |",
            r.model,
            r.angle,
            r.mean_cell(),
            r.paired,
            r.mapped,
            r.worst_cell(),
            r.missing.join(", "),
            r.failure.as_deref().unwrap_or("")
        );
    }
    if let Err(e) = std::fs::create_dir_all(&out)
        .and_then(|()| std::fs::write(out.join("pose.md"), &md))
        .and_then(|()| {
            std::fs::write(
                out.join("pose.json"),
                serde_json::to_string_pretty(&rows).unwrap_or_default(),
            )
        })
    {
        eprintln!("could not write {}: {e}", out.display());
        std::process::exit(1);
    }
}

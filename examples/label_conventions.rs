//! How the reference rigs disagree about the skin over the upper arm, and what that does to
//! the per-vertex label agreement of the labelling issue.
//!
//! For every quadruped (and humanoid) in the reference data, rigs the mesh with default
//! options and takes the skin vertices whose nearest fitted bone is an upper arm (`shoulder_*`
//! → `elbow_*`). It prints how many of them the reference rig's nearest bone puts in a fore
//! limb and how many in the trunk, and the agreement of the bone-following labels with the
//! reference region (the accuracy table's measure) two ways: the default, where the upper
//! arm's skin is a fore limb, and the variant where it is trunk (the fitted rig's `shoulder_*`
//! joints read by their names, without the canonical map, so their bones count as girdle
//! bones).
//!
//! Run: `cargo run --release --example label_conventions [-- REFDATA_DIR]`
//! (default `../shared/refdata`).

use skelfit::anatomy::{skeleton_regions, Region};
use skelfit::eval::{load_skeleton, reference_regions};
use skelfit::mesh::load;
use skelfit::pipeline::{rig, RigOptions};
use std::path::PathBuf;

fn main() {
    if let Err(message) = run() {
        eprintln!("label_conventions: error: {message}");
        std::process::exit(1);
    }
}

fn agreement(ours: &[Option<Region>], reference: &[Option<Region>]) -> f64 {
    let (mut compared, mut agreeing) = (0usize, 0usize);
    for (a, b) in ours.iter().zip(reference) {
        if let (Some(a), Some(b)) = (a, b) {
            compared += 1;
            agreeing += usize::from(a == b);
        }
    }
    100.0 * agreeing as f64 / compared.max(1) as f64
}

fn run() -> Result<(), String> {
    let root = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "../shared/refdata".into()),
    );
    if !root.is_dir() {
        return Err(format!(
            "{} is not a directory: pass the reference data folder",
            root.display()
        ));
    }
    println!(
        "| model | upper-arm skin vertices | reference: fore limb | reference: trunk | \
         agreement, upper arm = limb % | agreement, upper arm = trunk % |"
    );
    println!("|---|---|---|---|---|---|");
    for kind in ["quadruped", "humanoid"] {
        let Ok(entries) = std::fs::read_dir(root.join(kind)) else {
            continue;
        };
        let mut dirs: Vec<PathBuf> = entries.filter_map(|e| Some(e.ok()?.path())).collect();
        dirs.sort();
        for dir in dirs {
            let Some(rig_path) = ["rig_game_engine.json", "rig_gltf.json"]
                .iter()
                .map(|n| dir.join(n))
                .find(|p| p.is_file())
            else {
                continue;
            };
            let mesh =
                load(&dir.join("mesh.obj")).map_err(|e| format!("{}: {e}", dir.display()))?;
            let reference_rig =
                load_skeleton(&rig_path).map_err(|e| format!("{}: {e}", rig_path.display()))?;
            let reference = reference_regions(&reference_rig, &mesh);
            let fitted = rig(&mesh, &RigOptions::default())
                .map_err(|e| format!("{}: {e}", dir.display()))?;
            let skeleton = &fitted.fit.skeleton;
            let limb = skeleton_regions(skeleton, &fitted.fit.canonical, &mesh);
            let mut girdle_canonical = fitted.fit.canonical.clone();
            girdle_canonical.retain(|key, _| !key.starts_with("shoulder_"));
            let trunk = skeleton_regions(skeleton, &girdle_canonical, &mesh);
            let (mut upper_arm, mut as_fore, mut as_trunk) = (0, 0, 0);
            for ((a, b), r) in limb.iter().zip(&trunk).zip(&reference) {
                if a != b {
                    upper_arm += 1;
                    match r {
                        Some(Region::Fore(_)) => as_fore += 1,
                        Some(Region::Trunk) => as_trunk += 1,
                        _ => {}
                    }
                }
            }
            println!(
                "| {kind}/{} | {upper_arm} | {as_fore} | {as_trunk} | {:.1} | {:.1} |",
                dir.file_name().unwrap_or_default().to_string_lossy(),
                agreement(&limb, &reference),
                agreement(&trunk, &reference),
            );
        }
    }
    Ok(())
}

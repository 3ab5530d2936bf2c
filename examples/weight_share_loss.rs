//! Where a model's skin weights keep any labelling below 100 % weight share (the headline of
//! `skelfit label --table`, issue 21 item 6).
//!
//! For each refdata model folder given, reads the artists' skin weights from its `source.glb`
//! (`eval::reference_skin`), prints its girdle bones with the limb each also counts for
//! (`anatomy::girdle_limbs`), the weight-share ceiling (every vertex labelled with its best
//! region, `anatomy::best_regions`), and the bone sets that cost the ceiling most: for the
//! vertices whose best region does not hold all of their weight, the best region and the bones
//! carrying the rest, with the vertices and points of the ceiling they cost.
//!
//! Run: `cargo run --release --example weight_share_loss -- MODEL_DIR [MODEL_DIR ...]`
//! (e.g. `../shared/refdata/humanoid/quaternius_knight`).

use skelfit::anatomy::{best_regions, weight_share, WeightRegions};
use skelfit::eval::{label_reference_file, load_skeleton, reference_skin};
use skelfit::mesh::load;
use std::collections::BTreeMap;
use std::path::Path;

/// Bone sets listed per model.
const SHOWN: usize = 8;

fn main() {
    let dirs: Vec<String> = std::env::args().skip(1).collect();
    if dirs.is_empty() {
        eprintln!("weight_share_loss: give one or more refdata model folders");
        std::process::exit(2);
    }
    for dir in dirs {
        if let Err(message) = run(Path::new(&dir)) {
            eprintln!("weight_share_loss: {dir}: {message}");
            std::process::exit(1);
        }
    }
}

fn run(dir: &Path) -> Result<(), String> {
    let rig_path = label_reference_file(dir).ok_or("no rig_*.json")?;
    let rig = load_skeleton(&rig_path).map_err(|e| e.to_string())?;
    let mesh = load(&dir.join("mesh.obj")).map_err(|e| e.to_string())?;
    let skin = reference_skin(dir, &rig, &mesh)
        .map_err(|e| e.to_string())?
        .ok_or("no skin weights for this rig in source.glb")?;
    let regions = WeightRegions::new(&skin.skeleton, &skin.canonical);
    println!(
        "{}: {} of {} vertices weighted",
        dir.display(),
        skin.matched,
        mesh.positions.len()
    );
    for (j, joint) in skin.skeleton.joints.iter().enumerate() {
        if let Some(limb) = regions.girdle[j] {
            println!(
                "  girdle {} counts for the trunk and {}",
                joint.name,
                limb.name()
            );
        }
    }
    let best = best_regions(&regions, &skin.weights);
    let ceiling = weight_share(&best, &regions, &skin.weights);
    println!(
        "  ceiling {:.1} % over {} vertices",
        ceiling.percent, ceiling.compared
    );
    let mut loss: BTreeMap<String, (usize, f64)> = BTreeMap::new();
    for (weights, region) in skin.weights.iter().zip(&best) {
        let Some(region) = *region else { continue };
        let Some(share) = regions.share(weights, region) else {
            continue;
        };
        if share >= 1.0 {
            continue;
        }
        let mut rest: Vec<&str> = weights
            .iter()
            .filter(|(j, _)| !regions.counts_for(*j, region))
            .map(|(j, _)| skin.skeleton.joints[j.0].name.as_str())
            .collect();
        rest.sort();
        rest.dedup();
        let entry = loss
            .entry(format!("{} / {}", region.name(), rest.join(" + ")))
            .or_default();
        entry.0 += 1;
        entry.1 += 1.0 - share;
    }
    let mut rows: Vec<(String, (usize, f64))> = loss.into_iter().collect();
    rows.sort_by(|a, b| b.1 .1.total_cmp(&a.1 .1).then(a.0.cmp(&b.0)));
    let n = ceiling.compared.max(1) as f64;
    for (bones, (vertices, lost)) in rows.iter().take(SHOWN) {
        println!(
            "  {bones}: {vertices} vertices, {:.2} points",
            100.0 * lost / n
        );
    }
    Ok(())
}

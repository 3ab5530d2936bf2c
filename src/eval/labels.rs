//! Scores of a model's per-vertex body-part labels against its reference (the labelling
//! accuracy table, `skelfit label --table`): agreement with the nearest reference bone's
//! region, and, where the model carries the artists' skin weights, the share of each vertex's
//! weight on bones of its predicted part (girdle bones counting for trunk and limb).

use super::{load_skeleton, reference_regions, reference_skin, EvalError};
use crate::anatomy::{
    agreement, best_regions, vertex_regions, weight_regions, weight_share, Agreement, Labelling,
    WeightRegions, WeightShare,
};
use crate::mesh::Mesh;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The reference rig a refdata model's labels are scored against: `rig_game_engine.json`,
/// else `rig_gltf.json`, else the first `rig_*.json` by name; `None` without any.
pub fn label_reference_file(model: &Path) -> Option<PathBuf> {
    for name in ["rig_game_engine.json", "rig_gltf.json"] {
        if model.join(name).is_file() {
            return Some(model.join(name));
        }
    }
    let mut rigs: Vec<PathBuf> = std::fs::read_dir(model)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("rig_") && n.ends_with(".json"))
        })
        .collect();
    rigs.sort();
    rigs.into_iter().next()
}

/// How a model's per-vertex labels compare with its reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LabelScore {
    /// The reference rig file ([`label_reference_file`]).
    pub reference: PathBuf,
    /// The labels against the region of the nearest reference bone
    /// ([`super::reference_regions`]).
    pub agreement: Agreement,
    /// The second labelling (the medial per-vertex labels), if given, against the same.
    pub agreement_medial: Option<f64>,
    /// The headline where the model has skin weights: the mean share of each vertex's artist
    /// weight on bones of its predicted part ([`crate::anatomy::weight_share`]).
    pub weight_share: Option<WeightShare>,
    /// The same for the second labelling.
    pub weight_share_medial: Option<f64>,
    /// The best a labelling can score: the weight share of the labels that give every vertex
    /// its best region ([`crate::anatomy::best_regions`]). Below 100 % where the artist shared
    /// vertices between parts.
    pub weight_share_ceiling: Option<f64>,
    /// The reference measured against itself: the share of vertices whose nearest-bone region
    /// is also the region carrying most of their weight ([`crate::anatomy::weight_regions`]).
    pub rule_vs_weights: Option<f64>,
    /// The labels' agreement with the region carrying most of each vertex's weight.
    pub agreement_with_weights: Option<f64>,
    /// Vertices of the mesh with skin weights (0 without a skin).
    pub weighted_vertices: usize,
    /// Why the skin weights were not used, if they exist but could not be read.
    pub notes: Vec<String>,
}

/// Scores `labels` (per-vertex labels of `mesh`, the model folder's `mesh.obj`), and
/// optionally a second labelling `medial`, against the refdata model folder `model`: its
/// reference rig ([`label_reference_file`]) and, when `source.glb` holds the rig's skin
/// ([`reference_skin`]), its skin weights. `Ok(None)` when the folder has no reference rig.
///
/// # Errors
/// [`EvalError`] when the reference rig cannot be read. A skin that cannot be read is a note.
pub fn label_score(
    model: &Path,
    mesh: &Mesh,
    labels: &Labelling,
    medial: Option<&Labelling>,
) -> Result<Option<LabelScore>, EvalError> {
    let Some(reference) = label_reference_file(model) else {
        return Ok(None);
    };
    let rig = load_skeleton(&reference)?;
    let nearest = reference_regions(&rig, mesh);
    let mut score = LabelScore {
        reference,
        agreement: agreement(labels, &nearest),
        agreement_medial: medial.map(|m| agreement(m, &nearest).percent),
        weight_share: None,
        weight_share_medial: None,
        weight_share_ceiling: None,
        rule_vs_weights: None,
        agreement_with_weights: None,
        weighted_vertices: 0,
        notes: Vec::new(),
    };
    let skin = match reference_skin(model, &rig, mesh) {
        Ok(skin) => skin,
        Err(e) => {
            score.notes.push(format!("skin weights not compared: {e}"));
            None
        }
    };
    let Some(skin) = skin.filter(|s| s.matched > 0) else {
        return Ok(Some(score));
    };
    score.weighted_vertices = skin.matched;
    let regions = WeightRegions::new(&skin.skeleton, &skin.canonical);
    score.weight_share = Some(weight_share(
        &vertex_regions(labels),
        &regions,
        &skin.weights,
    ));
    score.weight_share_medial =
        medial.map(|m| weight_share(&vertex_regions(m), &regions, &skin.weights).percent);
    let by_weight = weight_regions(&skin.skeleton, &skin.canonical, &skin.weights);
    let best = best_regions(&regions, &skin.weights);
    score.weight_share_ceiling = Some(weight_share(&best, &regions, &skin.weights).percent);
    let (n, same) = nearest
        .iter()
        .zip(&by_weight)
        .filter_map(|(a, b)| Some(((*a)?, (*b)?)))
        .fold((0usize, 0usize), |(n, k), (a, b)| {
            (n + 1, k + usize::from(a == b))
        });
    if n > 0 {
        score.rule_vs_weights = Some(100.0 * same as f64 / n as f64);
        score.agreement_with_weights = Some(agreement(labels, &by_weight).percent);
    }
    Ok(Some(score))
}

//! Joint correspondence between two skeletons: canonical anatomical keys, naming presets that
//! derive them from engine names, and the pairing used by the metrics.

use super::{EvalError, ReferenceRig};
use crate::skeleton::canonical::{is_canonical_key, is_digit_key, key_rank};
use crate::skeleton::{JointId, Skeleton};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::sync::OnceLock;

/// Fewest canonical keys a preset must resolve before it is taken as a skeleton's naming.
const MIN_PRESET_MATCHES: usize = 3;

/// A naming preset: for each canonical key the joint names that denote it in one naming
/// convention, first existing name wins. Loaded from `templates/presets/*.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NamingPreset {
    /// Preset name (`mixamo`, `unity_humanoid`, `makehuman_game_engine`, `cmu`, `skelfit`).
    pub preset: String,
    /// What naming convention this is.
    pub description: String,
    /// Where the table comes from.
    pub source: String,
    /// Canonical key -> candidate joint names.
    pub joints: BTreeMap<String, Vec<String>>,
}

/// The preset files, in tie-break order (earlier wins when two match equally well).
const PRESET_FILES: &[(&str, &str)] = &[
    (
        "skelfit",
        include_str!("../../templates/presets/skelfit.json"),
    ),
    (
        "mixamo",
        include_str!("../../templates/presets/mixamo.json"),
    ),
    (
        "unity_humanoid",
        include_str!("../../templates/presets/unity_humanoid.json"),
    ),
    (
        "makehuman_game_engine",
        include_str!("../../templates/presets/makehuman_game_engine.json"),
    ),
    ("cmu", include_str!("../../templates/presets/cmu.json")),
];

/// Parses and validates the bundled preset files.
///
/// # Errors
/// [`EvalError::Preset`] when a file is malformed or uses a non-canonical key (a build defect,
/// caught by the unit tests).
pub fn parse_presets() -> Result<Vec<NamingPreset>, EvalError> {
    PRESET_FILES
        .iter()
        .map(|(name, text)| {
            let preset: NamingPreset =
                serde_json::from_str(text).map_err(|e| EvalError::Preset {
                    name: (*name).into(),
                    message: e.to_string(),
                })?;
            let problem = if preset.preset != *name {
                Some(format!("file declares preset {:?}", preset.preset))
            } else {
                preset
                    .joints
                    .iter()
                    .find(|(key, names)| !is_canonical_key(key) || names.is_empty())
                    .map(|(key, _)| format!("key {key:?} is not canonical or has no names"))
            };
            match problem {
                Some(message) => Err(EvalError::Preset {
                    name: (*name).into(),
                    message,
                }),
                None => Ok(preset),
            }
        })
        .collect()
}

/// The bundled naming presets (parsed once; the files are validated by the unit tests).
pub fn presets() -> &'static [NamingPreset] {
    static PRESETS: OnceLock<Vec<NamingPreset>> = OnceLock::new();
    // An invalid bundled file is a build defect, not bad user input; tests keep them valid.
    PRESETS.get_or_init(|| parse_presets().unwrap_or_default())
}

/// The bundled preset called `name`, if any.
pub fn preset(name: &str) -> Option<&'static NamingPreset> {
    presets().iter().find(|p| p.preset == name)
}

/// A joint name reduced for loose matching: namespace (`mixamorig:`) dropped, lowercase.
fn loose(name: &str) -> String {
    name.rsplit(':').next().unwrap_or(name).to_ascii_lowercase()
}

impl NamingPreset {
    /// Resolves the preset against `skeleton`: canonical key -> joint. Exact names are tried
    /// first, then names without namespace prefix, case-insensitively. Returns the map and how
    /// many keys matched exactly.
    pub fn resolve(&self, skeleton: &Skeleton) -> (BTreeMap<String, JointId>, usize) {
        let mut map = BTreeMap::new();
        let mut exact = 0;
        for (key, names) in &self.joints {
            let hit = names
                .iter()
                .find_map(|n| skeleton.find(n).map(|id| (id, true)))
                .or_else(|| {
                    names.iter().find_map(|n| {
                        let wanted = loose(n);
                        skeleton
                            .joints
                            .iter()
                            .position(|j| loose(&j.name) == wanted)
                            .map(|i| (JointId(i), false))
                    })
                });
            if let Some((id, is_exact)) = hit {
                exact += usize::from(is_exact);
                map.insert(key.clone(), id);
            }
        }
        (map, exact)
    }
}

/// The preset whose names match `skeleton` best — most keys matched exactly, then most keys
/// matched at all, then the earlier preset in skelfit, mixamo, unity_humanoid,
/// makehuman_game_engine, cmu order — with its resolved map; `None` when none resolves at least
/// three keys.
pub fn detect_preset(
    skeleton: &Skeleton,
) -> Option<(&'static NamingPreset, BTreeMap<String, JointId>)> {
    let mut best: Option<(&'static NamingPreset, BTreeMap<String, JointId>, usize)> = None;
    for preset in presets() {
        let (map, exact) = preset.resolve(skeleton);
        let better = match &best {
            None => true,
            Some((_, b, b_exact)) => (exact, map.len()) > (*b_exact, b.len()),
        };
        if better {
            best = Some((preset, map, exact));
        }
    }
    best.filter(|(_, map, _)| map.len() >= MIN_PRESET_MATCHES)
        .map(|(preset, map, _)| (preset, map))
}

/// Where a rig's canonical keys came from.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CanonicalSource {
    /// The file's own `canonical` map.
    File,
    /// A naming preset, by name.
    Preset(String),
    /// None found.
    None,
}

/// The canonical map of `rig`: its own when non-empty (non-canonical keys such as
/// `root_control` dropped) with the digit keys it lacks taken from [`detect_preset`] (reference
/// files map the body, not the fingers), else one derived by [`detect_preset`].
pub fn canonical_map(rig: &ReferenceRig) -> (BTreeMap<String, JointId>, CanonicalSource) {
    let mut own: BTreeMap<String, JointId> = rig
        .canonical
        .iter()
        .filter(|(k, _)| is_canonical_key(k))
        .map(|(k, v)| (k.clone(), *v))
        .collect();
    if !own.is_empty() {
        if !own.keys().any(|k| is_digit_key(k)) {
            if let Some((_, map)) = detect_preset(&rig.skeleton) {
                for (key, id) in map.into_iter().filter(|(k, _)| is_digit_key(k)) {
                    own.entry(key).or_insert(id);
                }
            }
        }
        return (own, CanonicalSource::File);
    }
    match detect_preset(&rig.skeleton) {
        Some((preset, map)) => (map, CanonicalSource::Preset(preset.preset.clone())),
        None => (BTreeMap::new(), CanonicalSource::None),
    }
}

/// How joints were paired.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MatchMethod {
    /// By canonical anatomical keys present on both sides.
    Canonical,
    /// By identical joint names (no shared canonical keys).
    Name,
    /// Not paired: only the topology-free chamfer distances were computed (see
    /// [`JointPairing`](super::JointPairing)).
    ChamferOnly,
}

/// One paired joint.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct JointPair {
    /// The canonical key, or the shared joint name for [`MatchMethod::Name`].
    pub key: String,
    /// The joint in the predicted skeleton.
    pub predicted: JointId,
    /// The joint in the reference skeleton.
    pub reference: JointId,
}

/// The pairing of two skeletons' joints.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Correspondence {
    /// Paired joints, in canonical order (or reference order when matched by name).
    pub pairs: Vec<JointPair>,
    /// How they were paired.
    pub method: MatchMethod,
    /// Where the predicted skeleton's canonical keys came from.
    pub predicted_naming: CanonicalSource,
    /// Where the reference skeleton's canonical keys came from.
    pub reference_naming: CanonicalSource,
}

/// Pairs the joints of `predicted` and `reference`: by canonical keys that both have (their own
/// maps or ones derived from a naming preset), otherwise by identical joint names.
///
/// # Errors
/// [`EvalError::NoSharedJoints`] listing both sides' keys (or names) when nothing pairs.
pub fn correspond(
    predicted: &ReferenceRig,
    reference: &ReferenceRig,
) -> Result<Correspondence, EvalError> {
    let (pred_map, predicted_naming) = canonical_map(predicted);
    let (ref_map, reference_naming) = canonical_map(reference);
    let mut pairs: Vec<JointPair> = ref_map
        .iter()
        .filter_map(|(key, &r)| {
            Some(JointPair {
                key: key.clone(),
                predicted: *pred_map.get(key)?,
                reference: r,
            })
        })
        .collect();
    pairs.sort_by(|a, b| (key_rank(&a.key), &a.key).cmp(&(key_rank(&b.key), &b.key)));
    let method = if pairs.is_empty() {
        pairs = reference
            .skeleton
            .joints
            .iter()
            .enumerate()
            .filter_map(|(i, joint)| {
                Some(JointPair {
                    key: joint.name.clone(),
                    predicted: predicted.skeleton.find(&joint.name)?,
                    reference: JointId(i),
                })
            })
            .collect();
        MatchMethod::Name
    } else {
        MatchMethod::Canonical
    };
    if pairs.is_empty() {
        let names = |map: &BTreeMap<String, JointId>, rig: &ReferenceRig| -> Vec<String> {
            if map.is_empty() {
                rig.skeleton.joints.iter().map(|j| j.name.clone()).collect()
            } else {
                map.keys().cloned().collect()
            }
        };
        return Err(EvalError::NoSharedJoints {
            predicted: names(&pred_map, predicted),
            reference: names(&ref_map, reference),
        });
    }
    Ok(Correspondence {
        pairs,
        method,
        predicted_naming,
        reference_naming,
    })
}

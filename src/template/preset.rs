//! Naming presets: renaming a fitted skeleton's joints for an engine. The tables are
//! `templates/presets/*.json` (shared with evaluation): `joints` maps canonical keys to engine
//! names (the first is the one written), `names` maps other anatomical joint names, and
//! `prefix` is put before any joint name neither covers.

use super::TemplateError;
use crate::skeleton::{JointId, Skeleton};
use serde::Deserialize;
use std::collections::{BTreeMap, BTreeSet};

/// A naming preset for output skeletons.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Preset {
    /// skelfit's anatomical names (the template's names; `templates/presets/skelfit.json`).
    Anatomical,
    /// Adobe Mixamo (`mixamorig:` names).
    Mixamo,
    /// Unity Humanoid (HumanBodyBones).
    Unity,
    /// MakeHuman / MPFB2 game_engine (Unreal-style).
    MakeHuman,
}

impl Preset {
    /// Parses `anatomical`, `mixamo`, `unity` or `makehuman` (also the preset file stems).
    ///
    /// # Errors
    /// [`TemplateError::UnknownPreset`] for anything else.
    pub fn parse(name: &str) -> Result<Self, TemplateError> {
        match name {
            "anatomical" | "skelfit" => Ok(Self::Anatomical),
            "mixamo" => Ok(Self::Mixamo),
            "unity" | "unity_humanoid" => Ok(Self::Unity),
            "makehuman" | "makehuman_game_engine" | "game_engine" => Ok(Self::MakeHuman),
            _ => Err(TemplateError::UnknownPreset { name: name.into() }),
        }
    }

    /// The preset file's stem in `templates/presets/`.
    pub fn file_stem(self) -> &'static str {
        match self {
            Self::Anatomical => "skelfit",
            Self::Mixamo => "mixamo",
            Self::Unity => "unity_humanoid",
            Self::MakeHuman => "makehuman_game_engine",
        }
    }

    fn text(self) -> &'static str {
        match self {
            Self::Anatomical => include_str!("../../templates/presets/skelfit.json"),
            Self::Mixamo => include_str!("../../templates/presets/mixamo.json"),
            Self::Unity => include_str!("../../templates/presets/unity_humanoid.json"),
            Self::MakeHuman => include_str!("../../templates/presets/makehuman_game_engine.json"),
        }
    }

    /// The parsed naming tables.
    ///
    /// # Errors
    /// [`TemplateError::PresetFile`] when the bundled file is malformed (a build defect).
    pub fn names(self) -> Result<PresetNames, TemplateError> {
        let bad = |message: String| TemplateError::PresetFile {
            name: self.file_stem().into(),
            message,
        };
        let names: PresetNames =
            serde_json::from_str(self.text()).map_err(|e| bad(e.to_string()))?;
        if let Some((key, _)) = names.joints.iter().find(|(_, v)| v.is_empty()) {
            return Err(bad(format!("canonical key {key:?} lists no names")));
        }
        Ok(names)
    }
}

/// The renaming tables of one preset file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct PresetNames {
    /// Preset name as in the file.
    pub preset: String,
    /// Canonical key → engine names; the first is written.
    pub joints: BTreeMap<String, Vec<String>>,
    /// Anatomical joint name → engine name, for joints without a canonical key.
    #[serde(default)]
    pub names: BTreeMap<String, String>,
    /// Prefix for joints neither table names.
    #[serde(default)]
    pub prefix: String,
}

/// Renames `skeleton`'s joints for `preset`. `canonical` maps canonical keys to joints: a
/// canonical joint takes the preset's first name for its key; other joints take their entry in
/// the preset's `names`, else `prefix` + their anatomical name, with `_2`, `_3`... appended when
/// that name is taken. [`Preset::Anatomical`] keeps the names.
///
/// # Errors
/// [`TemplateError::PresetCollision`] when two canonical keys map to one name (nothing is
/// renamed);
/// [`TemplateError::PresetFile`] for a malformed bundled file.
pub fn apply_preset(
    skeleton: &mut Skeleton,
    canonical: &BTreeMap<String, JointId>,
    preset: Preset,
) -> Result<(), TemplateError> {
    if preset == Preset::Anatomical {
        return Ok(());
    }
    let table = preset.names()?;
    let by_joint: BTreeMap<JointId, &str> =
        canonical.iter().map(|(k, id)| (*id, k.as_str())).collect();
    // Canonical joints first: their names are fixed by the preset.
    let mut new_names: Vec<Option<String>> = vec![None; skeleton.len()];
    let mut used = BTreeSet::new();
    for (k, joint) in skeleton.joints.iter().enumerate() {
        let Some(name) = by_joint
            .get(&JointId(k))
            .and_then(|key| table.joints.get(*key))
            .and_then(|names| names.first().cloned())
        else {
            continue;
        };
        if !used.insert(name.clone()) {
            return Err(TemplateError::PresetCollision {
                preset: table.preset.clone(),
                file: preset.file_stem().into(),
                name,
                joint: joint.name.clone(),
            });
        }
        new_names[k] = Some(name);
    }
    // Then the others; a name already taken gets `_2`, `_3`... (deterministic, joint order).
    for (k, joint) in skeleton.joints.iter().enumerate() {
        if new_names[k].is_some() {
            continue;
        }
        let base = table
            .names
            .get(&joint.name)
            .cloned()
            .unwrap_or_else(|| format!("{}{}", table.prefix, joint.name));
        let mut name = base.clone();
        let mut n = 1;
        while !used.insert(name.clone()) {
            n += 1;
            name = format!("{base}_{n}");
        }
        new_names[k] = Some(name);
    }
    let new_names: Vec<String> = new_names.into_iter().flatten().collect();
    for (joint, name) in skeleton.joints.iter_mut().zip(new_names) {
        joint.name = name;
    }
    Ok(())
}

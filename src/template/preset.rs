//! Naming presets: an engine's skeleton built from a fitted one. The tables are
//! `templates/presets/*.json` (shared with evaluation): `joints` maps canonical keys to engine
//! names (the first is the one written, and the output's canonical map points at it), and
//! `skeleton` lists the engine's joints in hierarchy order, each with its parent and where it is
//! placed on the fitted skeleton: at a canonical joint or template joint (`at`), at an
//! arc-length fraction of the fitted chain between two such joints (`along`: the engine's
//! spine joints spread over skelfit's spine, whatever its joint count), or on the ground below
//! one (`ground_below`: an engine root). Fitted joints the engine has no place for are left
//! out; the skin, computed afterwards on the engine skeleton, weights their region to the
//! engine joints around it.

use super::rest_frames::{apply_rest_frames, RestFrames};
use super::TemplateError;
use crate::skeleton::{ball_dofs, Joint, JointId, Skeleton};
use glam::DVec3;
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
    /// MakeHuman / MPFB2 game_engine (with its `Root`).
    MakeHuman,
    /// Unreal Engine 5 Mannequin (`root`, `pelvis`, `spine_01`..`spine_05`, ...).
    Unreal,
}

impl Preset {
    /// Every preset, in the order `--preset` lists them.
    pub const ALL: [Preset; 5] = [
        Self::Anatomical,
        Self::Mixamo,
        Self::Unity,
        Self::MakeHuman,
        Self::Unreal,
    ];

    /// Parses `anatomical`, `mixamo`, `unity`, `makehuman` or `unreal` (also the preset file
    /// stems).
    ///
    /// # Errors
    /// [`TemplateError::UnknownPreset`] for anything else.
    pub fn parse(name: &str) -> Result<Self, TemplateError> {
        match name {
            "anatomical" | "skelfit" => Ok(Self::Anatomical),
            "mixamo" => Ok(Self::Mixamo),
            "unity" | "unity_humanoid" => Ok(Self::Unity),
            "makehuman" | "makehuman_game_engine" | "game_engine" => Ok(Self::MakeHuman),
            "unreal" | "ue5" => Ok(Self::Unreal),
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
            Self::Unreal => "unreal",
        }
    }

    fn text(self) -> &'static str {
        match self {
            Self::Anatomical => include_str!("../../templates/presets/skelfit.json"),
            Self::Mixamo => include_str!("../../templates/presets/mixamo.json"),
            Self::Unity => include_str!("../../templates/presets/unity_humanoid.json"),
            Self::MakeHuman => include_str!("../../templates/presets/makehuman_game_engine.json"),
            Self::Unreal => include_str!("../../templates/presets/unreal.json"),
        }
    }

    /// The parsed and checked preset file.
    ///
    /// # Errors
    /// [`TemplateError::PresetFile`] when the bundled file is malformed (a build defect): a
    /// canonical key without names, an engine preset without a `skeleton`, or a skeleton whose
    /// names repeat, whose parents do not come before their children, or whose fractions lie
    /// outside `(0, 1)`.
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
        match &names.skeleton {
            Some(skeleton) => skeleton.check().map_err(bad)?,
            None if self != Self::Anatomical => {
                return Err(bad("an engine preset needs a \"skeleton\"".into()))
            }
            None => {}
        }
        if let Some(frames) = &names.rest_frames {
            frames.check().map_err(bad)?;
        }
        Ok(names)
    }
}

/// One preset file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct PresetNames {
    /// Preset name as in the file.
    pub preset: String,
    /// Canonical key → engine names; the first is written.
    pub joints: BTreeMap<String, Vec<String>>,
    /// The engine's skeleton (every preset but the anatomical one).
    #[serde(default)]
    pub skeleton: Option<EngineSkeleton>,
    /// The engine's rest frames (its bone-axis convention), where the preset ships them.
    #[serde(default)]
    pub rest_frames: Option<RestFrames>,
}

/// An engine's joint set and hierarchy, as far as skelfit places its joints.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EngineSkeleton {
    /// Which engine skeleton this is.
    pub engine: String,
    /// Where the names, parents and placements come from.
    pub source: String,
    /// The joints, parents before children.
    pub joints: Vec<EngineJoint>,
}

/// One joint of an engine skeleton.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EngineJoint {
    /// The engine's name.
    pub name: String,
    /// The engine's parent name; `None` for the root.
    pub parent: Option<String>,
    /// Where it goes on the fitted skeleton.
    pub place: EnginePlacement,
}

/// Where an engine joint goes on the fitted skeleton. A fitted joint is named by its canonical
/// key (`pelvis`, `wrist_L`) or, for joints without one, its template name (`head_end`,
/// `toe_end_L`, `jaw`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum EnginePlacement {
    /// At that fitted joint (taking its frame, DOFs and `deform`).
    At(String),
    /// At `fraction` of the arc length of the fitted chain from `from` to its descendant `to`
    /// (taking the frame and DOFs of the fitted joint that starts the segment it falls on).
    Along {
        /// The chain's proximal fitted joint.
        from: String,
        /// The chain's distal fitted joint.
        to: String,
        /// Fraction of the chain's length from `from`, in `(0, 1)`.
        fraction: f64,
    },
    /// On the ground below that fitted joint: moved along −up to the level of the lowest
    /// fitted joint. Not deforming (an engine's root).
    GroundBelow(String),
}

impl EngineSkeleton {
    /// Names unique, parents before children, fractions in `(0, 1)`: what is wrong, if anything.
    pub(crate) fn check(&self) -> Result<(), String> {
        let mut seen = BTreeSet::new();
        for j in &self.joints {
            if let Some(p) = &j.parent {
                if !seen.contains(p.as_str()) {
                    return Err(format!(
                        "joint {:?}: parent {p:?} does not come before it",
                        j.name
                    ));
                }
            }
            if !seen.insert(j.name.as_str()) {
                return Err(format!("joint {:?} is listed twice", j.name));
            }
            if let EnginePlacement::Along { fraction, .. } = j.place {
                if !(fraction > 0.0 && fraction < 1.0) {
                    return Err(format!(
                        "joint {:?}: fraction {fraction} is not in (0, 1)",
                        j.name
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Replaces the fitted `skeleton` (template names; `canonical` its canonical map) by
/// `preset`'s engine skeleton: the engine's joints in its order, named and parented as the
/// engine names and parents them, each placed as its [`EnginePlacement`] says. An engine joint whose
/// place the fit lacks (a missing arm, a jaw the template did not place) is left out and its
/// children hang from its nearest placed engine ancestor. Fitted joints the engine has no
/// joint for are dropped. `canonical` is remapped: each key to the engine joint the preset's
/// `joints` table names for it, else to the engine joint placed at the key's fitted joint;
/// keys with neither are dropped and returned. `up` (the figure's up) sets the ground for
/// [`EnginePlacement::GroundBelow`]. Where the preset ships the engine's rest frames, every
/// joint gets the engine's bone-axis convention ([`apply_rest_frames`], with `up` and
/// `forward`); elsewhere joints keep skelfit's frames. [`Preset::Anatomical`] changes nothing.
///
/// # Errors
/// [`TemplateError::PresetFile`] for a malformed bundled file.
pub fn apply_preset(
    skeleton: &mut Skeleton,
    canonical: &mut BTreeMap<String, JointId>,
    preset: Preset,
    up: DVec3,
    forward: DVec3,
) -> Result<Vec<String>, TemplateError> {
    let table = preset.names()?;
    let Some(engine) = &table.skeleton else {
        return Ok(Vec::new());
    };
    let (built, origin) = build(skeleton, canonical, engine, up);
    let remapped: BTreeMap<String, JointId> = canonical
        .iter()
        .filter_map(|(key, fitted)| {
            let by_name = table
                .joints
                .get(key)
                .and_then(|names| names.first())
                .and_then(|name| built.find(name));
            let by_place = origin.iter().position(|o| *o == Some(*fitted)).map(JointId);
            by_name.or(by_place).map(|id| (key.clone(), id))
        })
        .collect();
    let dropped = canonical
        .keys()
        .filter(|k| !remapped.contains_key(*k))
        .cloned()
        .collect();
    *skeleton = built;
    *canonical = remapped;
    if let Some(frames) = &table.rest_frames {
        apply_rest_frames(skeleton, frames, up, forward);
    }
    Ok(dropped)
}

/// An engine joint's place on the fitted skeleton.
struct Placed {
    position: DVec3,
    deform: bool,
    frame: glam::DQuat,
    dofs: Vec<crate::skeleton::Dof>,
    /// The fitted joint it stands on ([`EnginePlacement::At`]).
    at: Option<JointId>,
}

/// The engine skeleton and, per engine joint, the fitted joint it was placed at.
fn build(
    fitted: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    engine: &EngineSkeleton,
    up: DVec3,
) -> (Skeleton, Vec<Option<JointId>>) {
    let parent_of: BTreeMap<&str, Option<&str>> = engine
        .joints
        .iter()
        .map(|j| (j.name.as_str(), j.parent.as_deref()))
        .collect();
    let mut out = Skeleton::default();
    let mut origin = Vec::new();
    let mut placed: BTreeMap<&str, JointId> = BTreeMap::new();
    for joint in &engine.joints {
        let Some(p) = place(fitted, canonical, &joint.place, up) else {
            continue;
        };
        let mut ancestor = joint.parent.as_deref();
        let parent = loop {
            match ancestor {
                None => break None,
                Some(name) => match placed.get(name) {
                    Some(id) => break Some(*id),
                    None => ancestor = parent_of.get(name).copied().flatten(),
                },
            }
        };
        placed.insert(joint.name.as_str(), JointId(out.len()));
        origin.push(p.at);
        out.joints.push(Joint {
            name: joint.name.clone(),
            parent,
            position: p.position,
            deform: p.deform,
            frame: p.frame,
            dofs: p.dofs,
        });
    }
    (out, origin)
}

/// Where `placement` puts an engine joint, `None` when the fit lacks a joint it needs.
fn place(
    fitted: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    placement: &EnginePlacement,
    up: DVec3,
) -> Option<Placed> {
    let resolve = |name: &str| canonical.get(name).copied().or_else(|| fitted.find(name));
    match placement {
        EnginePlacement::At(name) => {
            let id = resolve(name)?;
            let j = fitted.joint(id);
            Some(Placed {
                position: j.position,
                deform: j.deform,
                frame: j.frame,
                dofs: j.dofs.clone(),
                at: Some(id),
            })
        }
        EnginePlacement::Along { from, to, fraction } => {
            let (from, to) = (resolve(from)?, resolve(to)?);
            let chain = chain(fitted, from, to)?;
            let points: Vec<DVec3> = chain.iter().map(|id| fitted.joint(*id).position).collect();
            let lengths: Vec<f64> = points.windows(2).map(|w| w[0].distance(w[1])).collect();
            let mut left = fraction.clamp(0.0, 1.0) * lengths.iter().sum::<f64>();
            // The segment the point falls on, and how far along it.
            let mut segment = 0;
            while segment + 1 < lengths.len() && left > lengths[segment] {
                left -= lengths[segment];
                segment += 1;
            }
            let t = if lengths[segment] > 0.0 {
                (left / lengths[segment]).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let start = fitted.joint(chain[segment]);
            Some(Placed {
                position: points[segment].lerp(points[segment + 1], t),
                deform: true,
                frame: start.frame,
                dofs: start.dofs.clone(),
                at: None,
            })
        }
        EnginePlacement::GroundBelow(name) => {
            let up = up.try_normalize().unwrap_or(DVec3::Y);
            let above = fitted.joint(resolve(name)?).position;
            let ground = fitted
                .joints
                .iter()
                .map(|j| j.position.dot(up))
                .fold(above.dot(up), f64::min);
            Some(Placed {
                position: above - up * (above.dot(up) - ground),
                deform: false,
                frame: glam::DQuat::IDENTITY,
                dofs: ball_dofs(),
                at: None,
            })
        }
    }
}

/// The fitted joints from `from` down to its descendant `to`, both included; `None` when `to`
/// does not descend from `from` or they are the same joint.
fn chain(fitted: &Skeleton, from: JointId, to: JointId) -> Option<Vec<JointId>> {
    let mut chain = vec![to];
    let mut at = to;
    while at != from {
        at = fitted.joint(at).parent?;
        chain.push(at);
    }
    chain.reverse();
    (chain.len() >= 2).then_some(chain)
}

use crate::skeleton::{Joint, JointId, Skeleton};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The file format a rig was read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RigFormat {
    /// `refdata-skeleton-v1` JSON (see `../shared/refdata/README.md`).
    Refdata,
    /// skelfit's own skeleton JSON.
    Skelfit,
    /// Biovision hierarchy (rest pose from the HIERARCHY offsets).
    Bvh,
    /// Skinned glTF/GLB (bind pose from the inverse bind matrices).
    Gltf,
    /// Built in memory (tests, the pipeline).
    Memory,
}

/// A skeleton to evaluate or to evaluate against: the joints, a map from canonical anatomical
/// keys (`pelvis`, `elbow_L`, ..., see [`CANONICAL_KEYS`](super::CANONICAL_KEYS)) to joints, and
/// metadata.
///
/// Positions are in the file's units and frame (for refdata: +Y up, +Z forward, +X left).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReferenceRig {
    /// The joints, parents before children.
    pub skeleton: Skeleton,
    /// Canonical anatomical key -> joint. Empty when the file gives none and no naming preset
    /// matched.
    pub canonical: BTreeMap<String, JointId>,
    /// Model name (refdata `model`, else the file stem).
    pub model: String,
    /// Rig name (refdata `rig`, e.g. `game_engine`), if known.
    pub rig: Option<String>,
    /// Units as declared by the file (e.g. `m`), if any.
    pub units: Option<String>,
    /// Format the rig was read from.
    pub format: RigFormat,
}

impl ReferenceRig {
    /// Wraps a skeleton built in memory, with no canonical map.
    pub fn from_skeleton(model: impl Into<String>, skeleton: Skeleton) -> Self {
        Self {
            skeleton,
            canonical: BTreeMap::new(),
            model: model.into(),
            rig: None,
            units: None,
            format: RigFormat::Memory,
        }
    }

    /// The joint mapped to canonical `key`, if any.
    pub fn canonical_joint(&self, key: &str) -> Option<&Joint> {
        self.canonical.get(key).map(|&id| self.skeleton.joint(id))
    }

    /// Number of joints that deform the skin.
    pub fn deforming_count(&self) -> usize {
        self.skeleton.joints.iter().filter(|j| j.deform).count()
    }

    /// A copy keeping only the deforming joints. Each kept joint is re-parented to its nearest
    /// deforming ancestor; canonical keys that pointed at a dropped (control) joint are removed.
    pub fn deforming(&self) -> ReferenceRig {
        let mut new_id: Vec<Option<JointId>> = Vec::with_capacity(self.skeleton.joints.len());
        let mut joints = Vec::new();
        for joint in &self.skeleton.joints {
            if joint.deform {
                let mut parent = joint.parent;
                // Parents come before children, so `new_id` of an ancestor is already known.
                while let Some(p) = parent {
                    match new_id.get(p.0).copied().flatten() {
                        Some(id) => {
                            parent = Some(id);
                            break;
                        }
                        None => parent = self.skeleton.joints.get(p.0).and_then(|j| j.parent),
                    }
                }
                new_id.push(Some(JointId(joints.len())));
                joints.push(Joint {
                    parent,
                    ..joint.clone()
                });
            } else {
                new_id.push(None);
            }
        }
        let canonical = self
            .canonical
            .iter()
            .filter_map(|(key, id)| Some((key.clone(), new_id.get(id.0).copied().flatten()?)))
            .collect();
        ReferenceRig {
            skeleton: Skeleton { joints },
            canonical,
            ..self.clone()
        }
    }

    /// Axis-aligned bounding box `(min, max)` of the joint positions, or `None` without joints.
    pub fn bounding_box(&self) -> Option<(glam::DVec3, glam::DVec3)> {
        let mut iter = self.skeleton.joints.iter().map(|j| j.position);
        let first = iter.next()?;
        Some(iter.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// Bones as `(parent position, child position)` segments, one per joint with a parent.
    pub fn bones(&self) -> Vec<(glam::DVec3, glam::DVec3)> {
        super::bone_segments(&self.skeleton)
    }
}

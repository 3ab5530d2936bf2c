//! The body region of each mesh vertex from a reference rig, and the agreement of a labelling
//! with it (the accuracy table of the labelling issue).
//!
//! **Rule.** Every deforming joint of the rig gets a region:
//! 1. a joint named by the rig's `canonical` map takes its key's region: `pelvis`, `spine`,
//!    `chest`, `clavicle_*` → trunk; `neck`, `head` → head; `shoulder_*`, `elbow_*`, `wrist_*`
//!    → fore limb; `hip_*`, `knee_*`, `ankle_*`, `toe_*` → hind limb; `tail_*` → tail; side
//!    from the key's `_L`/`_R`;
//! 2. otherwise its name, split into words (at `_ . -`, digits and lower→upper case changes),
//!    decides, first match wins: `tail` → tail; `head neck ear jaw mouth tongue eye nose horn`
//!    → head; `shoulder clavicle scapula hips pelvis` → trunk (girdle bones; a canonical
//!    `shoulder_*` is the arm's ball joint and stays a fore limb by rule 1); `wing` → wing;
//!    `arm forearm hand finger thumb wrist elbow` → fore limb; `leg foot toe thigh calf shin
//!    knee ankle` → fore limb when a word is `front` or `fore`, else hind limb; `spine chest
//!    torso body back root` → trunk; side from a word `l`/`left` or `r`/`right`;
//! 3. otherwise it inherits its parent's region and side.
//!
//! Bones are the segments parent → child, each carrying the region of its *parent* (the bone
//! named by its head joint, so `chest → clavicle` and `clavicle → upper arm` are trunk and
//! `upper arm → forearm` is a fore limb), plus a point at every leaf joint carrying the leaf's
//! region. A vertex takes the region of the nearest bone. Our labels map to regions as: trunk
//! → trunk; head, neck, jaw → head; tail → tail; arm → fore limb; leg → its `limb_pair` (fore
//! or hind); wing → wing; digit → its limb's region. A quadruped's front legs are therefore
//! compared as fore limbs whether the rig calls them arms (the Khronos fox) or front legs.

use super::{Label, Labelling, LimbPair, Side};
use crate::eval::ReferenceRig;
use crate::mesh::Mesh;
use crate::skeleton::Canonical;
use crate::skeleton::{JointId, Skeleton};
use glam::DVec3;
use serde::Serialize;
use std::collections::BTreeMap;

/// A body region, the unit of comparison between a labelling and a reference rig.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum Region {
    /// Trunk (with the girdles).
    Trunk,
    /// Head and neck.
    Head,
    /// Tail.
    Tail,
    /// Pectoral limb (arm, front leg) with its side.
    Fore(Option<Side>),
    /// Pelvic limb (leg, back leg) with its side.
    Hind(Option<Side>),
    /// Wing with its side.
    Wing(Option<Side>),
}

impl Region {
    fn with_side(self, side: Option<Side>) -> Region {
        match self {
            Region::Fore(_) => Region::Fore(side),
            Region::Hind(_) => Region::Hind(side),
            Region::Wing(_) => Region::Wing(side),
            other => other,
        }
    }

    /// Short name such as `fore_L`, `hind_R`, `trunk`.
    pub fn name(self) -> String {
        let s = |side: Option<Side>| side.map_or("", Side::suffix);
        match self {
            Region::Trunk => "trunk".into(),
            Region::Head => "head".into(),
            Region::Tail => "tail".into(),
            Region::Fore(side) => format!("fore{}", s(side)),
            Region::Hind(side) => format!("hind{}", s(side)),
            Region::Wing(side) => format!("wing{}", s(side)),
        }
    }
}

fn key_region(key: &str) -> Option<Region> {
    let Ok(key) = key.parse::<Canonical>() else {
        return key.starts_with("tail").then_some(Region::Tail);
    };
    let region = match key {
        Canonical::Pelvis | Canonical::Spine | Canonical::Chest | Canonical::Clavicle(_) => {
            Region::Trunk
        }
        Canonical::Neck | Canonical::Head => Region::Head,
        Canonical::Shoulder(_) | Canonical::Elbow(_) | Canonical::Wrist(_) => Region::Fore(None),
        Canonical::Hip(_) | Canonical::Knee(_) | Canonical::Ankle(_) | Canonical::Toe(_) => {
            Region::Hind(None)
        }
        Canonical::Tail(_) => Region::Tail,
    };
    Some(region.with_side(key.side()))
}

/// Words of a joint name: split at non-alphanumerics, digits and lower→upper case changes,
/// lowercased (`b_LeftForeArm_010` → `b left fore arm`; `IKBackLeg.L` → `ik back leg l`).
fn words(name: &str) -> Vec<String> {
    let chars: Vec<char> = name.chars().collect();
    let mut out = Vec::new();
    let mut word = String::new();
    for (i, &c) in chars.iter().enumerate() {
        if !c.is_alphabetic() {
            if !word.is_empty() {
                out.push(std::mem::take(&mut word));
            }
            continue;
        }
        let boundary = c.is_uppercase()
            && i > 0
            && (chars[i - 1].is_lowercase()
                || (chars[i - 1].is_uppercase()
                    && chars.get(i + 1).is_some_and(|n| n.is_lowercase())));
        if boundary && !word.is_empty() {
            out.push(std::mem::take(&mut word));
        }
        word.extend(c.to_lowercase());
    }
    if !word.is_empty() {
        out.push(word);
    }
    out
}

fn name_region(name: &str) -> Option<Region> {
    let w = words(name);
    let has = |list: &[&str]| w.iter().any(|x| list.contains(&x.as_str()));
    let side = if has(&["l", "left"]) {
        Some(Side::Left)
    } else if has(&["r", "right"]) {
        Some(Side::Right)
    } else {
        None
    };
    let region = if has(&["tail"]) {
        Region::Tail
    } else if has(&[
        "head", "neck", "ear", "jaw", "mouth", "tongue", "eye", "nose", "horn",
    ]) {
        Region::Head
    } else if has(&["shoulder", "clavicle", "scapula", "hips", "pelvis"]) {
        Region::Trunk
    } else if has(&["wing"]) {
        Region::Wing(None)
    } else if has(&[
        "arm", "forearm", "hand", "finger", "thumb", "wrist", "elbow",
    ]) {
        Region::Fore(None)
    } else if has(&[
        "leg", "foot", "toe", "thigh", "calf", "shin", "knee", "ankle",
    ]) {
        if has(&["front", "fore"]) {
            Region::Fore(None)
        } else {
            Region::Hind(None)
        }
    } else if has(&["spine", "chest", "torso", "body", "back", "root"]) {
        Region::Trunk
    } else {
        return None;
    };
    Some(region.with_side(side))
}

/// The region of each mesh vertex from the nearest bone of `rig`'s deforming joints (see the
/// module documentation for the rule). `None` for every vertex when no joint has a region.
pub fn reference_regions(rig: &ReferenceRig, mesh: &Mesh) -> Vec<Option<Region>> {
    let rig = rig.deforming();
    skeleton_regions(&rig.skeleton, &rig.canonical, mesh)
}

/// The region of each mesh vertex from the nearest bone of `skeleton`, every joint counted
/// (a fitted skeleton's non-deforming `*_end` tips included, so a tail or a head reaches its
/// tip), by the rule of [`reference_regions`]. This is how the labelling's bone-following
/// per-vertex labels ([`super::label_vertices_by_bones`]) read a fitted skeleton.
pub fn skeleton_regions(
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    mesh: &Mesh,
) -> Vec<Option<Region>> {
    let joints = &skeleton.joints;
    let region = joint_regions(skeleton, canonical);
    let mut has_child = vec![false; joints.len()];
    let mut bones: Vec<(DVec3, DVec3, Region)> = Vec::new();
    for joint in joints {
        if let Some(p) = joint.parent {
            has_child[p.0] = true;
            if let Some(r) = region[p.0] {
                bones.push((joints[p.0].position, joint.position, r));
            }
        }
    }
    for (j, joint) in joints.iter().enumerate() {
        if let (false, Some(r)) = (has_child[j], region[j]) {
            bones.push((joint.position, joint.position, r));
        }
    }
    mesh.positions
        .iter()
        .map(|&x| {
            bones
                .iter()
                .map(|&(a, b, r)| (point_segment(x, a, b), r))
                .min_by(|p, q| p.0.total_cmp(&q.0))
                .map(|(_, r)| r)
        })
        .collect()
}

/// The region of every joint of `skeleton` by rules 1-3 of the module documentation (the
/// region of the bones it heads, and of the skin it moves).
pub fn joint_regions(
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
) -> Vec<Option<Region>> {
    let joints = &skeleton.joints;
    let mut region: Vec<Option<Region>> = vec![None; joints.len()];
    let canonical_of: std::collections::HashMap<usize, &str> =
        canonical.iter().map(|(k, id)| (id.0, k.as_str())).collect();
    for (j, joint) in joints.iter().enumerate() {
        region[j] = canonical_of
            .get(&j)
            .and_then(|k| key_region(k))
            .or_else(|| name_region(&joint.name))
            .or_else(|| {
                joint
                    .parent
                    .and_then(|p| region.get(p.0).copied().flatten())
            });
    }
    region
}

/// The region of each vertex from skin weights instead of the nearest bone: the region whose
/// joints ([`joint_regions`]) carry the largest share of the vertex's weight, i.e. the part
/// whose bones move it most. `weights[v]` lists `(joint, weight)` of vertex `v`; `None` for a
/// vertex without weights on a joint with a region. Ties go to the first region in [`Region`]
/// order.
///
/// This is the reference rig's own statement of which bone moves which vertex; the accuracy
/// table compares it with the nearest-bone rule to show how far that rule is from the artist's
/// intent on each model.
pub fn weight_regions(
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    weights: &[Vec<(JointId, f64)>],
) -> Vec<Option<Region>> {
    let region = joint_regions(skeleton, canonical);
    weights
        .iter()
        .map(|list| {
            let mut per: BTreeMap<Region, f64> = BTreeMap::new();
            for &(j, w) in list {
                if let Some(r) = region.get(j.0).copied().flatten() {
                    *per.entry(r).or_default() += w;
                }
            }
            let mut best: Option<(Region, f64)> = None;
            for (r, w) in per {
                if best.is_none_or(|(_, b)| w > b) {
                    best = Some((r, w));
                }
            }
            best.map(|(r, _)| r)
        })
        .collect()
}

fn point_segment(x: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((x - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    x.distance(a + ab * t)
}

/// Agreement of a labelling with reference regions.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Agreement {
    /// Mesh vertices with a reference region.
    pub compared: usize,
    /// Of those, vertices whose label maps to the same region (side included).
    pub agreeing: usize,
    /// `agreeing / compared`, in percent (0 when nothing was compared).
    pub percent: f64,
    /// Per reference region: (region name, vertices, agreeing).
    pub per_region: Vec<(String, usize, usize)>,
    /// Disagreements: (reference region, our region, vertices), most frequent first.
    pub confusion: Vec<(String, String, usize)>,
}

/// The region a labelled part stands for (see the module documentation).
pub fn part_region(labelling: &Labelling, part: usize) -> Region {
    let p = &labelling.parts[part];
    match p.label {
        Label::Trunk => Region::Trunk,
        Label::Head | Label::Neck | Label::Jaw => Region::Head,
        Label::Tail => Region::Tail,
        Label::Arm => Region::Fore(p.side),
        Label::Leg => match p.limb_pair {
            Some(LimbPair::Fore) => Region::Fore(p.side),
            _ => Region::Hind(p.side),
        },
        Label::Wing => Region::Wing(p.side),
        Label::Digit => match p.parent {
            Some(parent) if parent != part => part_region(labelling, parent),
            _ => Region::Trunk,
        },
    }
}

/// Per-vertex agreement of `labelling` with `reference` (from [`reference_regions`]).
pub fn agreement(labelling: &Labelling, reference: &[Option<Region>]) -> Agreement {
    let regions: Vec<Region> = (0..labelling.parts.len())
        .map(|i| part_region(labelling, i))
        .collect();
    let mut per: std::collections::BTreeMap<Region, (usize, usize)> = Default::default();
    let (mut compared, mut agreeing) = (0, 0);
    let mut confused: std::collections::BTreeMap<(Region, Region), usize> = Default::default();
    for (&part, r) in labelling.mesh_parts.iter().zip(reference) {
        let Some(r) = *r else { continue };
        let ours = regions.get(part as usize).copied().unwrap_or(Region::Trunk);
        let e = per.entry(r).or_default();
        e.0 += 1;
        compared += 1;
        if ours == r {
            e.1 += 1;
            agreeing += 1;
        } else {
            *confused.entry((r, ours)).or_insert(0usize) += 1;
        }
    }
    Agreement {
        compared,
        agreeing,
        percent: if compared > 0 {
            100.0 * agreeing as f64 / compared as f64
        } else {
            0.0
        },
        per_region: per
            .into_iter()
            .map(|(r, (n, a))| (r.name(), n, a))
            .collect(),
        confusion: {
            let mut c: Vec<(String, String, usize)> = confused
                .into_iter()
                .map(|((r, o), n)| (r.name(), o.name(), n))
                .collect();
            c.sort_by(|a, b| b.2.cmp(&a.2).then(a.cmp(b)));
            c
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joint_names_map_to_regions() {
        assert_eq!(words("b_LeftForeArm_010"), ["b", "left", "fore", "arm"]);
        assert_eq!(words("IKBackLeg.L"), ["ik", "back", "leg", "l"]);
        assert_eq!(
            name_region("FrontUpperLeg.L"),
            Some(Region::Fore(Some(Side::Left)))
        );
        assert_eq!(
            name_region("BackLowerLeg.R"),
            Some(Region::Hind(Some(Side::Right)))
        );
        assert_eq!(name_region("Ear2.L"), Some(Region::Head));
        assert_eq!(name_region("FrontShoulder.L"), Some(Region::Trunk));
        assert_eq!(name_region("Tail3"), Some(Region::Tail));
        assert_eq!(name_region("Torso2"), Some(Region::Trunk));
        assert_eq!(name_region("FFB.L"), None);
        assert_eq!(
            key_region("shoulder_L"),
            Some(Region::Fore(Some(Side::Left)))
        );
        assert_eq!(key_region("tail_mid"), Some(Region::Tail));
    }
}

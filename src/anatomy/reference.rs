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
//!    torso body back root thorax abdomen belly` → trunk; side from a word `l`/`left` or
//!    `r`/`right`;
//!    2b. legs named without a front or back word (`TopLeg1.L`, `MidLeg2.R`, `Leg3.L`) are
//!    hind limbs, except on a side with more than two such chains hanging from the trunk (an
//!    insect's, a spider's): there the anterior half of the chains (rounded down), those whose
//!    root is nearest to the head's joints, are fore limbs, as the labelling divides its leg
//!    pairs;
//! 3. otherwise it inherits its parent's region and side.
//!
//! Bones are the segments parent → child, each carrying the region of its *parent* (the bone
//! named by its head joint, so `chest → clavicle` and `clavicle → upper arm` are trunk and
//! `upper arm → forearm` is a fore limb), plus a point at every leaf joint carrying the leaf's
//! region. A vertex takes the region of the nearest bone. Our labels map to regions as: trunk
//! → trunk; head, neck, jaw → head; tail → tail; arm → fore limb; leg → its `limb_pair` (fore
//! or hind); wing → wing; digit → its limb's region. A quadruped's front legs are therefore
//! compared as fore limbs whether the rig calls them arms (the Khronos fox) or front legs.
//!
//! **Girdles.** A joint the rule puts in the trunk as a *girdle bone* (a canonical
//! `clavicle_*`, or a name with `shoulder`, `clavicle`, `scapula`, `hips` or `pelvis`, such as
//! `Shoulder.L`, `FrontShoulder.R`, `BackShoulder.L`) that has a side moves skin that belongs
//! to the trunk and to the limb hanging from it alike. [`girdle_limbs`] names that limb (the
//! region of its nearest descendant on a limb of the same side), and the skin-weight score
//! ([`weight_share`]) counts such a bone's weight for both. A central `Hips`/`pelvis` (no side)
//! is the trunk's root, not a girdle.

use super::{Label, Labelling, LimbPair, Side};
use crate::mesh::Mesh;
use crate::skeleton::canonical::SpineRegion;
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
        Canonical::Shoulder(_)
        | Canonical::Elbow(_)
        | Canonical::Wrist(_)
        | Canonical::Digit(..) => Region::Fore(None),
        Canonical::Hip(_) | Canonical::Knee(_) | Canonical::Ankle(_) | Canonical::Toe(_) => {
            Region::Hind(None)
        }
        Canonical::Tail(_) => Region::Tail,
        Canonical::Vertebra(v) => match v.region() {
            SpineRegion::Cervical => Region::Head,
            _ => Region::Trunk,
        },
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

/// Words that make a joint a girdle bone (rule 2's trunk words other than the column's).
/// (`pelvis` is also the canonical key's word.)
const GIRDLE_WORDS: [&str; 5] = [
    "shoulder",
    "clavicle",
    "scapula",
    "hips",
    Canonical::Pelvis.as_str(),
];

/// Words of the trunk's column and body segments (an insect's or a spider's thorax and
/// abdomen are its trunk, as a vertebrate's chest and belly are).
const TRUNK_WORDS: [&str; 9] = [
    "spine", "chest", "torso", "body", "back", "root", "thorax", "abdomen", "belly",
];

/// Words of a leg (rule 2).
const LEG_WORDS: [&str; 8] = [
    "leg", "foot", "toe", "thigh", "calf", "shin", "knee", "ankle",
];

/// Words that say which girdle a leg hangs from.
const GIRDLE_SIDE_WORDS: [&str; 5] = ["front", "fore", "back", "hind", "rear"];

/// Whether a joint's name makes it a leg (rule 2) without saying front or back: such a leg's
/// girdle comes from its place (rule 2b).
fn unmarked_leg(name: &str) -> bool {
    let w = words(name);
    let has = |list: &[&str]| w.iter().any(|x| list.contains(&x.as_str()));
    matches!(name_region(name), Some(Region::Hind(_)))
        && has(&LEG_WORDS)
        && !has(&GIRDLE_SIDE_WORDS)
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
    } else if has(&GIRDLE_WORDS) {
        Region::Trunk
    } else if has(&["wing"]) {
        Region::Wing(None)
    } else if has(&[
        "arm", "forearm", "hand", "finger", "thumb", "wrist", "elbow",
    ]) {
        Region::Fore(None)
    } else if has(&LEG_WORDS) {
        if has(&["front", "fore"]) {
            Region::Fore(None)
        } else {
            Region::Hind(None)
        }
    } else if has(&TRUNK_WORDS) {
        Region::Trunk
    } else {
        return None;
    };
    Some(region.with_side(side))
}

/// The region of each mesh vertex from the nearest bone of `skeleton`, every joint counted
/// (a fitted skeleton's non-deforming `*_end` tips included, so a tail or a head reaches its
/// tip), by the rule in the module documentation (a reference rig's regions,
/// [`crate::eval::reference_regions`], come from its deforming joints). This is how the labelling's bone-following
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
    let named = regions_by_rules(skeleton, canonical, &[]);
    let fore = fore_leg_chains(skeleton, canonical, &named);
    if fore.is_empty() {
        named
    } else {
        regions_by_rules(skeleton, canonical, &fore)
    }
}

/// Rules 1-3, with the unmarked leg chains rooted at `fore_roots` fore limbs (rule 2b).
fn regions_by_rules(
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    fore_roots: &[usize],
) -> Vec<Option<Region>> {
    let joints = &skeleton.joints;
    let mut region: Vec<Option<Region>> = vec![None; joints.len()];
    let mut fore_chain = vec![false; joints.len()];
    let canonical_of: std::collections::HashMap<usize, &str> =
        canonical.iter().map(|(k, id)| (id.0, k.as_str())).collect();
    for (j, joint) in joints.iter().enumerate() {
        let by_key = canonical_of.get(&j).and_then(|k| key_region(k));
        if by_key.is_none() && unmarked_leg(&joint.name) {
            let parent_fore = joint.parent.is_some_and(|p| fore_chain[p.0]);
            fore_chain[j] = fore_roots.contains(&j) || parent_fore;
        }
        region[j] = by_key
            .or_else(|| name_region(&joint.name))
            .map(|r| match r {
                Region::Hind(side) if fore_chain[j] => Region::Fore(side),
                r => r,
            })
            .or_else(|| {
                joint
                    .parent
                    .and_then(|p| region.get(p.0).copied().flatten())
            });
    }
    region
}

/// Rule 2b: the roots of the unmarked leg chains (named legs without a front or back word,
/// not named by the canonical map) that are fore limbs. A chain hangs from the trunk (its
/// root's parent has the trunk's region); on a side with more than two such chains (a
/// vertebrate has at most two limb pairs: an insect or a spider) the anterior half of them
/// (rounded down, as the labelling divides its leg pairs, `rules::fore_pairs`), nearest to the
/// head's joints, are fore limbs. Fewer chains on a side, or no head, change nothing.
fn fore_leg_chains(
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    region: &[Option<Region>],
) -> Vec<usize> {
    let joints = &skeleton.joints;
    let named: std::collections::HashSet<usize> = canonical.values().map(|id| id.0).collect();
    let unmarked = |j: usize| !named.contains(&j) && unmarked_leg(&joints[j].name);
    let heads: Vec<DVec3> = (0..joints.len())
        .filter(|&j| region[j] == Some(Region::Head))
        .map(|j| joints[j].position)
        .collect();
    if heads.is_empty() {
        return Vec::new();
    }
    let to_head = |j: usize| {
        heads
            .iter()
            .map(|h| h.distance(joints[j].position))
            .fold(f64::INFINITY, f64::min)
    };
    let mut fore = Vec::new();
    for side in [Side::Left, Side::Right] {
        let mut roots: Vec<usize> = (0..joints.len())
            .filter(|&j| {
                unmarked(j)
                    && region[j] == Some(Region::Hind(Some(side)))
                    && joints[j].parent.is_some_and(|p| {
                        !unmarked(p.0) && region.get(p.0).copied().flatten() == Some(Region::Trunk)
                    })
            })
            .collect();
        if roots.len() <= 2 {
            continue;
        }
        roots.sort_by(|&a, &b| to_head(a).total_cmp(&to_head(b)).then(a.cmp(&b)));
        fore.extend(&roots[..super::rules::fore_pairs(roots.len())]);
    }
    fore
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
        .map(|list| heaviest_region(&region, list))
        .collect()
}

/// The region carrying the largest share of `list`'s weight (ties: the first in [`Region`]
/// order); `None` when no weight lies on a joint with a region.
fn heaviest_region(region: &[Option<Region>], list: &[(JointId, f64)]) -> Option<Region> {
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
}

/// For every joint of `skeleton`, the limb region its skin weight also counts for when it is a
/// girdle bone (module documentation, "Girdles"), else `None`: a joint whose region
/// ([`joint_regions`]) is the trunk, classed there as a girdle (canonical `clavicle_*` key, or
/// by a girdle word in its name when the canonical map does not name it), with a side, takes
/// the region of its first descendant (in joint order) that lies on a fore limb, hind limb or
/// wing of that side. A girdle with no such descendant counts for the trunk only.
pub fn girdle_limbs(
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
) -> Vec<Option<Region>> {
    let joints = &skeleton.joints;
    let region = joint_regions(skeleton, canonical);
    let canonical_of: std::collections::HashMap<usize, &str> =
        canonical.iter().map(|(k, id)| (id.0, k.as_str())).collect();
    let side_of = |j: usize| -> Option<Side> {
        match canonical_of.get(&j) {
            Some(key) => key.parse::<Canonical>().ok().and_then(|k| k.side()),
            None => {
                let w = words(&joints[j].name);
                let has = |list: &[&str]| w.iter().any(|x| list.contains(&x.as_str()));
                if has(&["l", "left"]) {
                    Some(Side::Left)
                } else if has(&["r", "right"]) {
                    Some(Side::Right)
                } else {
                    None
                }
            }
        }
    };
    let is_girdle = |j: usize| -> bool {
        if region[j] != Some(Region::Trunk) {
            return false;
        }
        match canonical_of.get(&j) {
            Some(key) => matches!(key.parse::<Canonical>(), Ok(Canonical::Clavicle(_))),
            None => words(&joints[j].name)
                .iter()
                .any(|w| GIRDLE_WORDS.contains(&w.as_str())),
        }
    };
    // Parents come before children, so a joint's ancestors are known when it is reached.
    let descends_from = |mut j: usize, ancestor: usize| -> bool {
        while let Some(p) = joints[j].parent {
            if p.0 == ancestor {
                return true;
            }
            j = p.0;
        }
        false
    };
    (0..joints.len())
        .map(|g| {
            let side = side_of(g)?;
            if !is_girdle(g) {
                return None;
            }
            (g + 1..joints.len())
                .filter(|&d| descends_from(d, g))
                .find_map(|d| match region[d] {
                    Some(r @ (Region::Fore(s) | Region::Hind(s) | Region::Wing(s)))
                        if s == Some(side) =>
                    {
                        Some(r)
                    }
                    _ => None,
                })
        })
        .collect()
}

/// Which parts a joint's skin weight counts for in [`weight_share`]: its own region, and for a
/// girdle bone also its limb ([`girdle_limbs`]).
#[derive(Debug, Clone, PartialEq)]
pub struct WeightRegions {
    /// Region of every joint ([`joint_regions`]); `None`: a joint with no region, whose weight
    /// is left out.
    pub region: Vec<Option<Region>>,
    /// The limb a girdle joint's weight also counts for ([`girdle_limbs`]).
    pub girdle: Vec<Option<Region>>,
}

impl WeightRegions {
    /// The regions of `skeleton`'s joints by the module's rule, girdles included.
    pub fn new(skeleton: &Skeleton, canonical: &BTreeMap<String, JointId>) -> Self {
        Self {
            region: joint_regions(skeleton, canonical),
            girdle: girdle_limbs(skeleton, canonical),
        }
    }

    /// Whether weight on joint `j` counts for a vertex labelled `predicted`.
    pub fn counts_for(&self, j: JointId, predicted: Region) -> bool {
        let own = self.region.get(j.0).copied().flatten();
        let girdle = self.girdle.get(j.0).copied().flatten();
        own == Some(predicted)
            || (girdle.is_some() && (predicted == Region::Trunk || girdle == Some(predicted)))
    }

    /// The share of `weights` (one vertex's `(joint, weight)` list) on joints that count for
    /// `predicted`, over the weight on joints with a region; `None` when no weight lies on a
    /// joint with a region.
    pub fn share(&self, weights: &[(JointId, f64)], predicted: Region) -> Option<f64> {
        let (mut total, mut counted) = (0.0, 0.0);
        for &(j, w) in weights {
            if self.region.get(j.0).copied().flatten().is_none() || w.is_nan() || w <= 0.0 {
                continue;
            }
            total += w;
            if self.counts_for(j, predicted) {
                counted += w;
            }
        }
        (total > 0.0).then(|| counted / total)
    }
}

/// For every vertex, the region a labelling should give it to score best in [`weight_share`]:
/// of the regions its weighted joints stand for (a girdle's limb included), the one with the
/// largest [`WeightRegions::share`] (ties: the first in [`Region`] order); `None` for a vertex
/// without weight on a joint with a region. Labelling every vertex so scores the most any
/// labelling can on these weights.
pub fn best_regions(
    regions: &WeightRegions,
    weights: &[Vec<(JointId, f64)>],
) -> Vec<Option<Region>> {
    weights
        .iter()
        .map(|list| {
            let mut candidates: Vec<Region> = list
                .iter()
                .flat_map(|&(j, _)| {
                    [regions.region.get(j.0), regions.girdle.get(j.0)]
                        .into_iter()
                        .flatten()
                        .flatten()
                        .copied()
                })
                .collect();
            candidates.sort();
            candidates.dedup();
            let mut best: Option<(Region, f64)> = None;
            for r in candidates {
                if let Some(share) = regions.share(list, r) {
                    if best.is_none_or(|(_, b)| share > b) {
                        best = Some((r, share));
                    }
                }
            }
            best.map(|(r, _)| r)
        })
        .collect()
}

/// Per-vertex labels scored against a rig's own skin weights ([`weight_share`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WeightShare {
    /// Vertices scored: with a predicted region and weight on joints with a region.
    pub compared: usize,
    /// Mean over those vertices of the share of the vertex's weight that lies on bones of its
    /// predicted part, in percent (0 when nothing was compared).
    pub percent: f64,
    /// Per region of the vertex's weight ([`weight_regions`], the part whose bones move it
    /// most): (region name, vertices, mean share in percent), in [`Region`] order.
    pub per_region: Vec<(String, usize, f64)>,
}

/// Scores per-vertex labels against skin weights, the artist's answer to "which bones move
/// this vertex": each vertex scores the share of its weight that lies on bones of its
/// predicted region ([`WeightRegions::share`]; a girdle bone's weight counts for the trunk and
/// for its limb), and the result is the mean over the vertices. `predicted[v]` is vertex `v`'s
/// region (`None`: not labelled, not scored); `weights[v]` its `(joint, weight)` list on
/// `regions`' skeleton (empty: not scored). A labelling that gives every vertex the region of
/// its heaviest bone scores the mean heaviest share, 100 % only where every vertex is moved by
/// a single part.
pub fn weight_share(
    predicted: &[Option<Region>],
    regions: &WeightRegions,
    weights: &[Vec<(JointId, f64)>],
) -> WeightShare {
    let mut per: BTreeMap<Region, (usize, f64)> = BTreeMap::new();
    let (mut compared, mut sum) = (0usize, 0.0);
    for (p, w) in predicted.iter().zip(weights) {
        let Some(p) = *p else { continue };
        let Some(share) = regions.share(w, p) else {
            continue;
        };
        compared += 1;
        sum += share;
        if let Some(heaviest) = heaviest_region(&regions.region, w) {
            let e = per.entry(heaviest).or_default();
            e.0 += 1;
            e.1 += share;
        }
    }
    WeightShare {
        compared,
        percent: if compared > 0 {
            100.0 * sum / compared as f64
        } else {
            0.0
        },
        per_region: per
            .into_iter()
            .map(|(r, (n, s))| (r.name(), n, 100.0 * s / n as f64))
            .collect(),
    }
}

/// The region of each mesh vertex by `labelling`'s per-vertex labels ([`part_region`] of
/// `mesh_parts`); `None` for a vertex with no part.
pub fn vertex_regions(labelling: &Labelling) -> Vec<Option<Region>> {
    let regions: Vec<Region> = (0..labelling.parts.len())
        .map(|i| part_region(labelling, i))
        .collect();
    labelling
        .mesh_parts
        .iter()
        .map(|&p| regions.get(p as usize).copied())
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

/// Per-vertex agreement of `labelling` with `reference` (from [`crate::eval::reference_regions`]).
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
    use crate::skeleton::canonical::Tail;

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
            key_region(Canonical::Shoulder(Side::Left).as_str()),
            Some(Region::Fore(Some(Side::Left)))
        );
        assert_eq!(
            key_region(Canonical::Tail(Tail::Mid).as_str()),
            Some(Region::Tail)
        );
    }

    /// pelvis → spine → {clavicle_l → upperarm_l → forearm_l, Shoulder.R → UpperArm.R,
    /// neck}, pelvis → {thigh_l, Hips}: canonical keys for the left side, names only for the
    /// right girdle and the central `Hips`.
    fn girdle_rig() -> (Skeleton, BTreeMap<String, JointId>) {
        let names = [
            (Canonical::Pelvis.as_str(), None),
            (Canonical::Spine.as_str(), Some(0)),
            ("clavicle_l", Some(1)),
            ("upperarm_l", Some(2)),
            ("forearm_l", Some(3)),
            ("Shoulder.R", Some(1)),
            ("UpperArm.R", Some(5)),
            ("thigh_l", Some(0)),
            ("Hips", Some(0)),
            (Canonical::Neck.as_str(), Some(1)),
        ];
        let skeleton = Skeleton {
            joints: names
                .iter()
                .enumerate()
                .map(|(i, &(name, parent))| crate::skeleton::Joint {
                    name: name.into(),
                    parent: parent.map(JointId),
                    position: DVec3::new(0.0, i as f64, 0.0),
                    deform: true,
                    ..Default::default()
                })
                .collect(),
        };
        let canonical = [
            (Canonical::Pelvis, 0),
            (Canonical::Chest, 1),
            (Canonical::Clavicle(Side::Left), 2),
            (Canonical::Shoulder(Side::Left), 3),
            (Canonical::Elbow(Side::Left), 4),
            (Canonical::Hip(Side::Left), 7),
        ]
        .into_iter()
        .map(|(k, j)| (k.as_str().to_string(), JointId(j)))
        .collect();
        (skeleton, canonical)
    }

    #[test]
    fn girdle_bones_name_the_limb_hanging_from_them() {
        let (skeleton, canonical) = girdle_rig();
        let girdle = girdle_limbs(&skeleton, &canonical);
        let fore_l = Some(Region::Fore(Some(Side::Left)));
        let fore_r = Some(Region::Fore(Some(Side::Right)));
        assert_eq!(girdle[2], fore_l, "canonical clavicle_L");
        assert_eq!(girdle[5], fore_r, "Shoulder.R by its name");
        // The pelvis (canonical), the central Hips (no side), limb and column joints are no
        // girdles.
        for j in [0, 1, 3, 4, 6, 7, 8, 9] {
            assert_eq!(girdle[j], None, "{}", skeleton.joints[j].name);
        }
    }

    #[test]
    fn weight_share_counts_girdle_weight_for_trunk_and_limb() {
        let (skeleton, canonical) = girdle_rig();
        let regions = WeightRegions::new(&skeleton, &canonical);
        let w = |list: &[(usize, f64)]| -> Vec<(JointId, f64)> {
            list.iter().map(|&(j, w)| (JointId(j), w)).collect()
        };
        let trunk = Some(Region::Trunk);
        let fore_l = Some(Region::Fore(Some(Side::Left)));
        let hind_l = Some(Region::Hind(Some(Side::Left)));
        let predicted = vec![trunk, fore_l, trunk, hind_l, hind_l, None, trunk, fore_l];
        let weights = vec![
            w(&[(1, 1.0)]),             // spine, trunk: 1
            w(&[(2, 0.5), (3, 0.5)]),   // clavicle + upper arm, arm: 1 (girdle counts)
            w(&[(2, 0.5), (3, 0.5)]),   // the same, trunk: 0.5 (girdle yes, upper arm no)
            w(&[(1, 0.25), (7, 0.75)]), // spine + thigh, leg: 0.75
            w(&[(2, 1.0)]),             // clavicle, leg: 0 (not the girdle's limb)
            w(&[(1, 1.0)]),             // no prediction: not scored
            Vec::new(),                 // no weights: not scored
            w(&[(5, 1.0)]),             // right girdle, left arm: 0 (other side)
        ];
        let score = weight_share(&predicted, &regions, &weights);
        assert_eq!(score.compared, 6);
        let expected = 100.0 * (1.0 + 1.0 + 0.5 + 0.75 + 0.0 + 0.0) / 6.0;
        assert!(
            (score.percent - expected).abs() < 1e-12,
            "{}",
            score.percent
        );
        // Per heaviest region: trunk (spine; clavicle+upper arm tie → trunk first; clavicle;
        // right girdle), fore_L never heaviest, hind_L (spine + thigh).
        let trunk_row = score.per_region.iter().find(|r| r.0 == "trunk").unwrap();
        assert_eq!(trunk_row.1, 5);
        let hind_row = score.per_region.iter().find(|r| r.0 == "hind_L").unwrap();
        assert_eq!((hind_row.1, hind_row.2), (1, 75.0));
        // Labelling every vertex by its heaviest region scores exactly its heaviest share.
        let heaviest: Vec<Option<Region>> = weights
            .iter()
            .map(|l| heaviest_region(&regions.region, l))
            .collect();
        let best = weight_share(&heaviest, &regions, &weights);
        assert_eq!(best.compared, 7);
        assert!(best.percent > score.percent);
        // The best labels: clavicle + upper arm is wholly the arm's (girdle counts), so they
        // beat the heaviest-region labels there; every vertex but spine + thigh scores 1.
        let ideal = best_regions(&regions, &weights);
        assert_eq!(ideal[1], fore_l);
        assert_eq!(ideal[3], hind_l);
        let top = weight_share(&ideal, &regions, &weights);
        assert!(
            (top.percent - 100.0 * (6.0 + 0.75) / 7.0).abs() < 1e-12,
            "{}",
            top.percent
        );
        assert!(top.percent > best.percent);
    }

    /// An insect's abdomen and thorax are its trunk (the wasp's `Abdomen` hangs from its
    /// `Neck` and took the head's region), and of its three unnamed leg pairs the one nearest
    /// the head is the fore pair, the others hind, as the labelling divides three leg pairs.
    #[test]
    fn an_insects_abdomen_is_trunk_and_its_front_leg_pair_is_fore() {
        let mut joints = vec![
            ("Body", None, [0.0, 0.5, 0.0]),
            ("Thorax", Some(0), [0.0, 2.6, 0.3]),
            ("Neck", Some(1), [0.0, 2.8, 0.7]),
            ("Head", Some(2), [0.0, 2.9, 1.0]),
            ("Abdomen", Some(2), [0.0, 2.3, 0.1]),
            ("Abdomen2", Some(4), [0.0, 1.9, -0.3]),
            ("Sting", Some(5), [0.0, 0.6, -0.2]),
        ];
        let legs = [("Top", 0.65), ("Mid", 0.5), ("Bottom", 0.35)];
        let names: Vec<[String; 2]> = legs
            .iter()
            .flat_map(|(leg, _)| {
                ["L", "R"].map(|s| [format!("{leg}Leg1.{s}"), format!("{leg}Leg2.{s}")])
            })
            .collect();
        for (k, (_, z)) in legs.iter().enumerate() {
            for (s, x) in [0.2, -0.2].into_iter().enumerate() {
                let [a, b] = &names[2 * k + s];
                joints.push((a.as_str(), Some(1), [x, 2.4, *z]));
                let root = joints.len() - 1;
                joints.push((b.as_str(), Some(root), [x * 2.0, 2.0, *z]));
            }
        }
        let rig = crate::skeleton::test_skeleton(&joints);
        let region = joint_regions(&rig, &BTreeMap::new());
        let of = |name: &str| region[rig.find(name).unwrap().0];
        for name in ["Thorax", "Abdomen", "Abdomen2", "Sting"] {
            assert_eq!(of(name), Some(Region::Trunk), "{name}");
        }
        assert_eq!(of("Neck"), Some(Region::Head));
        let (l, r) = (Some(Side::Left), Some(Side::Right));
        for (name, expected) in [
            ("TopLeg1.L", Region::Fore(l)),
            ("TopLeg2.R", Region::Fore(r)),
            ("MidLeg1.L", Region::Hind(l)),
            ("MidLeg2.R", Region::Hind(r)),
            ("BottomLeg2.L", Region::Hind(l)),
        ] {
            assert_eq!(of(name), Some(expected), "{name}");
        }
    }

    /// Two unnamed leg chains on a side (a biped's leg and its foot control hanging from the
    /// root) stay hind limbs: only more than two limb pairs are divided by place.
    #[test]
    fn two_unnamed_leg_chains_on_a_side_stay_hind_limbs() {
        let rig = crate::skeleton::test_skeleton(&[
            ("Root", None, [0.0, 0.0, 0.0]),
            ("Hips", Some(0), [0.0, 1.0, 0.0]),
            ("Neck", Some(1), [0.0, 1.5, 0.0]),
            ("Head", Some(2), [0.0, 1.7, 0.0]),
            ("UpperLeg.L", Some(1), [0.1, 0.9, 0.0]),
            ("LowerLeg.L", Some(4), [0.1, 0.5, 0.0]),
            ("Foot.L", Some(0), [0.1, 0.0, 0.0]),
        ]);
        let region = joint_regions(&rig, &BTreeMap::new());
        for (j, r) in region.iter().enumerate().take(7).skip(4) {
            assert_eq!(
                *r,
                Some(Region::Hind(Some(Side::Left))),
                "{}",
                rig.joints[j].name
            );
        }
    }

    #[test]
    fn weight_on_joints_without_a_region_is_left_out() {
        let skeleton = Skeleton {
            joints: vec![crate::skeleton::Joint {
                name: "FFB.L".into(),
                deform: true,
                ..Default::default()
            }],
        };
        let regions = WeightRegions::new(&skeleton, &BTreeMap::new());
        let weights = vec![vec![(JointId(0), 1.0)]];
        let score = weight_share(&[Some(Region::Trunk)], &regions, &weights);
        assert_eq!((score.compared, score.percent), (0, 0.0));
    }
}

//! The full spine (`skelfit rig --spine full`, issue 25): the 24 inter-vertebral joints and the
//! sacrum centre that the refinement finds on the spine curve ([`super::Refinement::spine`],
//! seed 004, 3.2) replace the template's trunk and neck joints between pelvis and head.
//!
//! The chain runs pelvis → `sacrum` → `L5` → ... → `L1` → `T12` → ... → `T1` → `C7` → ... →
//! `C1` → head; each joint rotates its vertebra and everything above it. The clavicles (or the
//! shoulders, when the skeleton has no clavicles) hang from `T1`: the clavicle's medial end
//! sits in the manubrium, which the first ribs carry, and the first rib articulates with T1
//! alone (the costoclavicular ligament ties the clavicle to that rib). Any other joint that
//! hung from a replaced joint hangs from the vertebral joint nearest to it.

use super::{RefineWarning, Refinement};
use crate::fit::assign_trunk_keys;
use crate::mesh::{winding_number, Mesh};
use crate::skeleton::canonical::{Vertebra, VERTEBRA_NAMES};
use crate::skeleton::{Canonical, Joint, JointId, Skeleton};
use crate::template::{FullSpineDofs, Template};
use crate::voxel::Solid;
use glam::{DMat3, DQuat, DVec3};
use std::collections::BTreeMap;
use std::fmt;

/// Which spine a humanoid rig gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpineDetail {
    /// The template's trunk and neck joints, placed on the spine curve (today's rig).
    #[default]
    Coarse,
    /// The 24 inter-vertebral joints and the sacrum ([`full_spine`]).
    Full,
}

/// The vertebral joint the pectoral girdle hangs from (see the module documentation).
pub const GIRDLE_VERTEBRA: &str = "T1";

/// Why a rig kept the coarse spine although the full one was asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoFullSpine {
    /// The figure's template declares no refinement (not a humanoid), or it was switched off.
    NotRefined,
    /// The template has no `[full_spine]` limits.
    NoLimits,
    /// The spine joints given are not `C1`..`L5` and `sacrum` in order.
    NoCurve,
    /// The skeleton has no pelvis and head with the head above the pelvis in the tree.
    NoChain,
}

impl fmt::Display for NoFullSpine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::NotRefined => "the figure's template has no slicing refinement (or it is off)",
            Self::NoLimits => "the template declares no [full_spine] limits",
            Self::NoCurve => "the spine joints are not C1..L5 and the sacrum in order",
            Self::NoChain => "the skeleton has no chain from the pelvis to the head",
        })
    }
}

/// `skeleton` with the joints strictly between the canonical pelvis and head replaced by the
/// full spine, and its canonical map: every vertebral key (`C1`..`L5`, `sacrum`) added, `neck`
/// on `C7` (the refinement's neck is the C7/T1 joint), other keys following their joints.
/// `spine` and `chest` are left for the caller to assign again
/// ([`crate::fit::assign_trunk_keys`]).
///
/// * `spine`: the refinement's joints, top first, named as [`VERTEBRA_NAMES`] (mesh frame).
/// * `dorsal`: the body's backward direction (unit), for the joint frames: z along the spine
///   towards the head, y dorsal, x lateral, as every axial joint's frame.
/// * `dofs`: each region's limits; the sacrum gets none.
///
/// # Errors
/// [`NoFullSpine::NoCurve`] when `spine` does not hold the 25 joints, [`NoFullSpine::NoChain`]
/// when the head does not descend from the pelvis.
pub fn full_spine(
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    spine: &[(String, DVec3)],
    dorsal: DVec3,
    dofs: &FullSpineDofs,
) -> Result<(Skeleton, BTreeMap<String, JointId>), NoFullSpine> {
    let names: Vec<&str> = spine.iter().map(|(n, _)| n.as_str()).collect();
    if names != VERTEBRA_NAMES {
        return Err(NoFullSpine::NoCurve);
    }
    let key = |k: Canonical| canonical.get(k.as_str()).copied();
    let (pelvis, head) = key(Canonical::Pelvis)
        .zip(key(Canonical::Head))
        .ok_or(NoFullSpine::NoChain)?;
    let replaced = between(skeleton, pelvis, head).ok_or(NoFullSpine::NoChain)?;

    // New order: the old joints without the replaced ones, the spine (sacrum first) where
    // the first replaced joint was (or right after the pelvis).
    let at = replaced.iter().map(|j| j.0).min().unwrap_or(pelvis.0 + 1);
    let mut order: Vec<Slot> = Vec::with_capacity(skeleton.len() + spine.len());
    for k in 0..skeleton.len() {
        if k == at {
            order.extend((0..spine.len()).rev().map(Slot::Vertebra));
        }
        if !replaced.contains(&JointId(k)) {
            order.push(Slot::Old(k));
        }
    }
    if at >= skeleton.len() {
        order.extend((0..spine.len()).rev().map(Slot::Vertebra));
    }
    let new_of_old: BTreeMap<usize, JointId> = order
        .iter()
        .enumerate()
        .filter_map(|(n, s)| match s {
            Slot::Old(k) => Some((*k, JointId(n))),
            Slot::Vertebra(_) => None,
        })
        .collect();
    let vertebra_id = |i: usize| {
        JointId(
            order
                .iter()
                .position(|s| *s == Slot::Vertebra(i))
                .unwrap_or(0),
        )
    };
    let girdle = girdle_joints(skeleton, canonical);
    let nearest_vertebra = |p: DVec3| {
        (0..spine.len())
            .min_by(|&a, &b| spine[a].1.distance(p).total_cmp(&spine[b].1.distance(p)))
            .map_or(vertebra_id(0), vertebra_id)
    };

    let mut joints = Vec::with_capacity(order.len());
    for slot in &order {
        match *slot {
            Slot::Vertebra(i) => {
                let v = Vertebra::ALL[i];
                let parent = if v == Vertebra::SACRUM {
                    new_of_old[&pelvis.0]
                } else {
                    vertebra_id(i + 1)
                };
                let up_to = match i {
                    0 => skeleton.joint(head).position,
                    _ => spine[i - 1].1,
                };
                joints.push(Joint {
                    name: v.as_str().to_string(),
                    parent: Some(parent),
                    position: spine[i].1,
                    deform: true,
                    frame: axial_frame(spine[i].1, up_to, dorsal),
                    dofs: dofs.of(v.region()).to_vec(),
                });
            }
            Slot::Old(k) => {
                let old = skeleton.joint(JointId(k));
                let parent = match old.parent {
                    Some(_) if JointId(k) == head => Some(vertebra_id(0)),
                    Some(p) if replaced.contains(&p) => Some(if girdle.contains(&JointId(k)) {
                        vertebra_id(index_of(GIRDLE_VERTEBRA))
                    } else {
                        nearest_vertebra(old.position)
                    }),
                    Some(p) => Some(new_of_old[&p.0]),
                    None => None,
                };
                joints.push(Joint {
                    parent,
                    ..old.clone()
                });
            }
        }
    }
    let mut out_map: BTreeMap<String, JointId> = canonical
        .iter()
        .filter_map(|(k, id)| new_of_old.get(&id.0).map(|n| (k.clone(), *n)))
        .collect();
    for (i, v) in Vertebra::ALL.iter().enumerate() {
        out_map.insert(v.as_str().to_string(), vertebra_id(i));
    }
    out_map.insert(
        Canonical::Neck.as_str().to_string(),
        vertebra_id(index_of("C7")),
    );
    Ok((Skeleton { joints }, out_map))
}

/// `refined` with the full spine ([`full_spine`] with the template's `[full_spine]` limits,
/// then `spine`/`chest` assigned again by its trunk rules), or unchanged with a
/// [`RefineWarning::CoarseSpineKept`] saying why not.
pub(super) fn with_full_spine(mut refined: Refinement, template: &Template) -> Refinement {
    let ends = [Canonical::Pelvis, Canonical::Neck, Canonical::Head];
    let on_curve =
        !refined.spine.is_empty() && ends.iter().all(|k| refined.moved.contains_key(k.as_str()));
    let result = match template.full_spine.as_ref() {
        None => Err(NoFullSpine::NoLimits),
        Some(dofs) => {
            let spine = match on_curve {
                true => Some(refined.spine.clone()),
                false => along_chain(&refined.skeleton, &refined.canonical),
            };
            if !on_curve && spine.is_some() {
                refined.warnings.push(RefineWarning::SpineAlongChain);
            }
            spine.ok_or(NoFullSpine::NoChain).and_then(|spine| {
                full_spine(
                    &refined.skeleton,
                    &refined.canonical,
                    &spine,
                    -refined.frame.forward,
                    dofs,
                )
            })
        }
    };
    match result {
        Ok((skeleton, mut canonical)) => {
            assign_trunk_keys(&skeleton, &mut canonical, &template.axial);
            refined.skeleton = skeleton;
            refined.canonical = canonical;
        }
        Err(why) => refined.warnings.push(RefineWarning::CoarseSpineKept(why)),
    }
    refined
}

/// Length of a lumbar motion segment over a thoracic one: adult columns measure about 27 cm
/// for T1-T12 and 18 cm for L1-L5 with their discs (Gray's Anatomy, 41st ed., ch. 43).
const LUMBAR_PER_THORACIC: f64 = 1.6;

/// The full spine's joints spread along the skeleton's own chain when the refinement found no
/// spine curve (or it does not meet the refined pelvis, neck and head): C1..C6 evenly from
/// the head down to `C7` at the canonical neck; T1..L5 and the sacrum from the neck down to
/// the pelvis, lumbar intervals 1.6 times the thoracic ones (adult proportions), the sacrum
/// half an interval above the pelvis. Top first, named as [`VERTEBRA_NAMES`]; `None` without a
/// pelvis → neck → head chain.
pub fn along_chain(
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
) -> Option<Vec<(String, DVec3)>> {
    let key = |k: Canonical| canonical.get(k.as_str()).copied();
    let (pelvis, neck, head) = (
        key(Canonical::Pelvis)?,
        key(Canonical::Neck)?,
        key(Canonical::Head)?,
    );
    let path = |from: JointId, to: JointId| -> Option<Vec<DVec3>> {
        let mut points: Vec<DVec3> = between(skeleton, from, to)?
            .iter()
            .map(|j| skeleton.joint(*j).position)
            .collect();
        points.insert(0, skeleton.joint(to).position);
        points.push(skeleton.joint(from).position);
        Some(points) // `to` first
    };
    let neck_to_head: Vec<DVec3> = path(neck, head)?.into_iter().rev().collect();
    let neck_to_pelvis = path(pelvis, neck)?;
    let mut out = Vec::with_capacity(VERTEBRA_NAMES.len());
    // C1..C7: fractions 1/7..7/7 of the way from the head to the neck.
    for k in 1..=7 {
        let p = at_fraction(&neck_to_head, 1.0 - f64::from(k) / 7.0);
        out.push(p);
    }
    // T1..T12, L1..L5, sacrum below the neck.
    let (a, b) = (1.0, LUMBAR_PER_THORACIC);
    let total = 12.0 * a + 6.5 * b;
    let mut along = 0.0;
    for k in 0..18 {
        along += if k < 12 { a } else { b };
        out.push(at_fraction(&neck_to_pelvis, along / total));
    }
    Some(
        VERTEBRA_NAMES
            .iter()
            .map(|n| n.to_string())
            .zip(out)
            .collect(),
    )
}

/// The point at `t` (0..1) of a polyline's length.
fn at_fraction(points: &[DVec3], t: f64) -> DVec3 {
    let total: f64 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
    let mut s = t.clamp(0.0, 1.0) * total;
    for w in points.windows(2) {
        let l = w[0].distance(w[1]);
        if s <= l && l > 0.0 {
            return w[0].lerp(w[1], s / l);
        }
        s -= l;
    }
    points.last().copied().unwrap_or(DVec3::ZERO)
}

/// Moves each full-spine joint of `skeleton` (the [`VERTEBRA_NAMES`] keys of `canonical`)
/// that is outside the body (its voxel outside `solid`, or `mesh`'s [`winding_number`] there
/// below one half) along ±`forward`, keeping its height so that the order along the back
/// holds, to the nearest inside point on that line in half-voxel steps, a step deeper when
/// that is inside too; at most a fifth of the grid's longest side. Clothes or armour layered
/// over a body leave gaps between shells (which the joined solid bridges) where the spine
/// curve can pass; the joints belong in the body. Frames of the moved joints and of those
/// below them turn to their new segments. Returns the names of the joints moved.
pub fn pull_inside(
    skeleton: &mut Skeleton,
    canonical: &BTreeMap<String, JointId>,
    mesh: &Mesh,
    solid: &Solid,
    forward: DVec3,
) -> Vec<String> {
    let grid = &solid.grid;
    let inside = |p: DVec3| {
        grid.voxel_at(p)
            .is_some_and(|v| solid.inside[grid.index(v)])
            && winding_number(mesh, p) > 0.5
    };
    let Some(forward) = forward.try_normalize() else {
        return Vec::new();
    };
    let h = grid.voxel_size * 0.5;
    let max_steps = grid.dims.iter().copied().max().unwrap_or(0) * 2 / 5;
    let ids: Vec<JointId> = VERTEBRA_NAMES
        .iter()
        .filter_map(|n| canonical.get(*n).copied())
        .filter(|id| id.0 < skeleton.len())
        .collect();
    let mut moved = Vec::new();
    for &id in &ids {
        let p = skeleton.joint(id).position;
        if inside(p) {
            continue;
        }
        let found = (1..=max_steps).find_map(|k| {
            [1.0, -1.0].into_iter().find_map(|sign| {
                let step = forward * (sign * h);
                let q = p + step * k as f64;
                inside(q).then(|| if inside(q + step) { q + step } else { q })
            })
        });
        if let Some(q) = found {
            skeleton.joints[id.0].position = q;
            moved.push(id);
        }
    }
    // Frames: each vertebral joint's z points at the joint above it (its only chain child).
    for (k, &id) in ids.iter().enumerate() {
        let above = match k {
            0 => skeleton.children(id).first().copied(),
            _ => Some(ids[k - 1]),
        };
        let touched = moved.contains(&id) || above.is_some_and(|a| moved.contains(&a));
        if let (true, Some(above)) = (touched, above) {
            let dorsal = skeleton.joint(id).frame * DVec3::Y;
            let (at, next) = (skeleton.joint(id).position, skeleton.joint(above).position);
            skeleton.joints[id.0].frame = axial_frame(at, next, dorsal);
        }
    }
    moved
        .iter()
        .map(|id| skeleton.joint(*id).name.clone())
        .collect()
}

/// A joint of the new skeleton: an old one by index, or a spine joint by its index from the
/// top.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Slot {
    Old(usize),
    Vertebra(usize),
}

/// Index of `name` in [`VERTEBRA_NAMES`] (a name of that list).
fn index_of(name: &str) -> usize {
    VERTEBRA_NAMES
        .iter()
        .position(|n| *n == name)
        .unwrap_or_default()
}

/// The joints strictly between `pelvis` and its descendant `head`, or `None` when `head` does
/// not descend from `pelvis`.
fn between(skeleton: &Skeleton, pelvis: JointId, head: JointId) -> Option<Vec<JointId>> {
    let mut chain = Vec::new();
    let mut k = skeleton.joint(head).parent;
    while let Some(p) = k {
        if p == pelvis {
            return Some(chain);
        }
        if chain.len() > skeleton.len() {
            return None;
        }
        chain.push(p);
        k = skeleton.joint(p).parent;
    }
    None
}

/// The pectoral girdle's roots: the clavicles, or the shoulders of a skeleton without them.
fn girdle_joints(skeleton: &Skeleton, canonical: &BTreeMap<String, JointId>) -> Vec<JointId> {
    use crate::skeleton::Side;
    let mut out = Vec::new();
    for side in Side::BOTH {
        let clavicle = canonical.get(Canonical::Clavicle(side).as_str());
        let shoulder = canonical.get(Canonical::Shoulder(side).as_str());
        out.extend(clavicle.or(shoulder).filter(|id| id.0 < skeleton.len()));
    }
    out
}

/// An axial joint's frame at `at`: z towards `next`, y the dorsal direction made perpendicular
/// to z, x = y × z (lateral).
fn axial_frame(at: DVec3, next: DVec3, dorsal: DVec3) -> DQuat {
    let z = (next - at).try_normalize().unwrap_or(DVec3::Y);
    let y = [dorsal, DVec3::Y, DVec3::Z]
        .into_iter()
        .filter_map(|d| (d - z * d.dot(z)).try_normalize())
        .next()
        .unwrap_or(DVec3::X);
    let x = y.cross(z);
    DQuat::from_mat3(&DMat3::from_cols(x, y, z)).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::Dof;

    fn joint(name: &str, parent: Option<usize>, y: f64) -> Joint {
        Joint::new(name, parent.map(JointId), DVec3::new(0.0, y, 0.0))
    }

    /// pelvis, spine, neck, head, clavicle_L (on spine), shoulder_L, jaw (on head).
    fn coarse() -> (Skeleton, BTreeMap<String, JointId>) {
        let mut clavicle = joint("clavicle_L", Some(1), 1.4);
        clavicle.position.x = 0.02;
        let mut shoulder = joint("shoulder_L", Some(4), 1.4);
        shoulder.position.x = 0.2;
        let skeleton = Skeleton {
            joints: vec![
                joint("pelvis", None, 1.0),
                joint("spine", Some(0), 1.2),
                joint("neck", Some(1), 1.45),
                joint("head", Some(2), 1.55),
                clavicle,
                shoulder,
                joint("jaw", Some(3), 1.5),
            ],
        };
        let canonical = [
            ("pelvis", 0),
            ("spine", 1),
            ("neck", 2),
            ("head", 3),
            ("clavicle_L", 4),
            ("shoulder_L", 5),
        ]
        .into_iter()
        .map(|(k, i)| (k.to_string(), JointId(i)))
        .collect();
        (skeleton, canonical)
    }

    fn curve() -> Vec<(String, DVec3)> {
        VERTEBRA_NAMES
            .iter()
            .enumerate()
            .map(|(i, n)| (n.to_string(), DVec3::new(0.0, 1.5 - 0.02 * i as f64, -0.05)))
            .collect()
    }

    fn limits() -> FullSpineDofs {
        let one = |d: f64| {
            vec![Dof {
                axis: crate::skeleton::LocalAxis::X,
                min: -d.to_radians(),
                max: d.to_radians(),
            }]
        };
        FullSpineDofs {
            cervical: one(10.0),
            thoracic: one(4.0),
            lumbar: one(11.0),
        }
    }

    #[test]
    fn the_spine_replaces_the_trunk_from_pelvis_to_head() {
        let (skeleton, canonical) = coarse();
        let (out, map) = full_spine(&skeleton, &canonical, &curve(), DVec3::NEG_Z, &limits())
            .expect("a full spine");
        assert!(out.validate().is_ok());
        assert_eq!(out.len(), skeleton.len() - 2 + 25);
        assert!(out.find("spine").is_none() && out.find("neck").is_none());
        // head → C1 → ... → sacrum → pelvis.
        let mut k = out.find("head").unwrap();
        let mut seen = Vec::new();
        while let Some(p) = out.joint(k).parent {
            seen.push(out.joint(p).name.clone());
            k = p;
        }
        let mut expected: Vec<String> = VERTEBRA_NAMES.iter().map(|n| n.to_string()).collect();
        expected.push("pelvis".into());
        assert_eq!(seen, expected);
        let t1 = out.find(GIRDLE_VERTEBRA).unwrap();
        assert_eq!(out.joint(out.find("clavicle_L").unwrap()).parent, Some(t1));
        assert_eq!(map["neck"], out.find("C7").unwrap());
        assert_eq!(map["sacrum"], out.find("sacrum").unwrap());
        assert_eq!(map["shoulder_L"], out.find("shoulder_L").unwrap());
        assert!(out.joint(map["sacrum"]).dofs.is_empty());
        assert_eq!(out.joint(map["L3"]).dofs, limits().lumbar);
        // Frames: z up the spine, y dorsal.
        let f = out.joint(map["T6"]).frame;
        assert!((f * DVec3::Z).distance(DVec3::Y) < 1e-9);
        assert!((f * DVec3::Y).distance(DVec3::NEG_Z) < 1e-9);
    }

    #[test]
    fn along_the_chain_the_joints_descend_from_head_to_pelvis() {
        let (skeleton, canonical) = coarse();
        let spine = along_chain(&skeleton, &canonical).expect("a chain");
        let names: Vec<&str> = spine.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, VERTEBRA_NAMES);
        assert!(
            (spine[6].1.y - 1.45).abs() < 1e-9,
            "C7 at the neck: {spine:?}"
        );
        let mut above = 1.55;
        for (n, p) in &spine {
            assert!(p.y < above && p.y > 1.0, "{n} {p}");
            above = p.y;
        }
    }

    #[test]
    fn a_head_outside_the_pelvis_subtree_is_refused() {
        let (mut skeleton, canonical) = coarse();
        skeleton.joints[3].parent = None;
        let refused = full_spine(&skeleton, &canonical, &curve(), DVec3::NEG_Z, &limits());
        assert_eq!(refused.err(), Some(NoFullSpine::NoChain));
        let (skeleton, canonical) = coarse();
        let short = &curve()[1..];
        let refused = full_spine(&skeleton, &canonical, short, DVec3::NEG_Z, &limits());
        assert_eq!(refused.err(), Some(NoFullSpine::NoCurve));
    }
}

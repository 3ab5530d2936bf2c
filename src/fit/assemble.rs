//! Assembling the fitted skeleton: joint instances from the axial, ear and limb fits, the
//! joints in template order, the digits, the frames, and the canonical map.

use super::axial::AxialFit;
use super::frames::{self, FrameKind};
use super::limbs::LimbFit;
use super::polyline::Polyline;
use super::{assign_trunk_keys, resolve_parent, BodyFrame, FitInput, FitWarning, Side};
use crate::skeleton::{Canonical, Joint, JointId, Skeleton};
use crate::template::Template;
use glam::DVec3;
use std::collections::BTreeMap;

/// A template joint on one side (`None` for axial joints).
type Key = (String, Option<Side>);

/// A joint instance waiting to be added.
struct Instance {
    position: DVec3,
    next: Option<DVec3>,
}

/// The skeleton under construction, with each joint's next point and frame kind.
struct Built {
    skeleton: Skeleton,
    next: Vec<Option<DVec3>>,
    kind: Vec<FrameKind>,
    ids: BTreeMap<Key, Vec<JointId>>,
}

/// Builds the skeleton in template order and the canonical map.
pub(super) fn assemble(
    template: &Template,
    axial: &AxialFit,
    input: &FitInput,
    limbs: &[(usize, LimbFit)],
    frame: &BodyFrame,
    warnings: &mut Vec<FitWarning>,
) -> (Skeleton, BTreeMap<String, JointId>) {
    let mut instances = axial_instances(template, axial, input);
    ear_instances(template, input, &mut instances);
    let mut kinds: BTreeMap<Key, FrameKind> = BTreeMap::new();
    for j in &template.joints {
        if j.place.is_some() && !j.side {
            kinds.insert((j.name.clone(), None), FrameKind::Axial);
        }
    }
    limb_instances(template, limbs, &mut instances, &mut kinds);
    let mut built = build_joints(template, &instances, &kinds);
    let digit_ids = add_digits(template, limbs, &mut built);
    frames::set_frames(&mut built.skeleton, &built.next, &built.kind, frame);
    let canonical = canonical_map(template, limbs, &built, &digit_ids, warnings);
    (built.skeleton, canonical)
}

/// The axial joints' instances: root, trunk, neck, head, head_end; tail, tail_end; jaw.
fn axial_instances(
    template: &Template,
    axial: &AxialFit,
    input: &FitInput,
) -> BTreeMap<Key, Vec<Instance>> {
    let mut instances: BTreeMap<Key, Vec<Instance>> = BTreeMap::new();
    let mut put = |place: &str, list: Vec<Instance>| {
        if let Some(j) = template.placed(place) {
            if !list.is_empty() {
                instances.insert((j.name.clone(), None), list);
            }
        }
    };
    // Axial chain order away from the root: root, trunk, neck, head, head_end; tail, tail_end.
    let mut forward_chain: Vec<DVec3> = vec![axial.root];
    forward_chain.extend(axial.trunk.iter().map(|(p, _)| *p));
    forward_chain.extend(axial.neck.iter().copied());
    forward_chain.push(axial.head);
    forward_chain.push(axial.head_end);
    let next_of = |chain: &[DVec3], k: usize| chain.get(k + 1).copied();
    let nt = axial.trunk.len();
    let nn = axial.neck.len();
    put(
        "root",
        vec![Instance {
            position: axial.root,
            next: next_of(&forward_chain, 0),
        }],
    );
    put(
        "trunk",
        (0..nt)
            .map(|k| Instance {
                position: forward_chain[1 + k],
                next: next_of(&forward_chain, 1 + k),
            })
            .collect(),
    );
    put(
        "neck",
        (0..nn)
            .map(|k| Instance {
                position: forward_chain[1 + nt + k],
                next: next_of(&forward_chain, 1 + nt + k),
            })
            .collect(),
    );
    put(
        "head",
        vec![Instance {
            position: axial.head,
            next: Some(axial.head_end),
        }],
    );
    put(
        "head_end",
        vec![Instance {
            position: axial.head_end,
            next: None,
        }],
    );
    let mut tail_chain = axial.tail.clone();
    tail_chain.extend(axial.tail_end);
    put(
        "tail",
        (0..axial.tail.len())
            .map(|k| Instance {
                position: tail_chain[k],
                next: tail_chain.get(k + 1).copied(),
            })
            .collect(),
    );
    if let Some(end) = axial.tail_end {
        put(
            "tail_end",
            vec![Instance {
                position: end,
                next: None,
            }],
        );
    }
    if let Some(jaw) = input.jaw.as_ref().filter(|j| j.len() >= 2) {
        let (a, b) = (jaw[0], jaw[jaw.len() - 1]);
        put(
            "jaw",
            vec![Instance {
                position: a,
                next: Some(b),
            }],
        );
        put(
            "jaw_end",
            vec![Instance {
                position: b,
                next: None,
            }],
        );
    }
    instances
}

/// The ears' instances: the template's `ear` joints divide each ear path by the `ear` ratios,
/// base first; `ear_end` marks the tip.
fn ear_instances(
    template: &Template,
    input: &FitInput,
    instances: &mut BTreeMap<Key, Vec<Instance>>,
) {
    if let (Some(ear), Some(fractions)) = (template.placed("ear"), template.fractions("ear")) {
        for e in input.ears.iter().filter(|e| e.path.len() >= 2) {
            let path = Polyline::new(e.path.clone());
            let length = path.length();
            let mut at = 0.0;
            let mut chain = Vec::new();
            for f in &fractions {
                chain.push(path.at(at * length));
                at += f;
            }
            let tip = path.at(length);
            let list = (0..chain.len())
                .map(|k| Instance {
                    position: chain[k],
                    next: Some(chain.get(k + 1).copied().unwrap_or(tip)),
                })
                .collect();
            instances.insert((ear.name.clone(), Some(e.side)), list);
            if let Some(end) = template.placed("ear_end") {
                instances.insert(
                    (end.name.clone(), Some(e.side)),
                    vec![Instance {
                        position: tip,
                        next: None,
                    }],
                );
            }
        }
    }
}

/// The limbs' instances (chain joints and girdle joints), all with limb frames.
fn limb_instances(
    template: &Template,
    limbs: &[(usize, LimbFit)],
    instances: &mut BTreeMap<Key, Vec<Instance>>,
    kinds: &mut BTreeMap<Key, FrameKind>,
) {
    for (g, fit) in limbs {
        let group = &template.limbs[*g];
        let side = Some(fit.side);
        let emitted: Vec<(usize, DVec3)> = fit
            .chain
            .iter()
            .enumerate()
            .filter_map(|(k, p)| p.map(|p| (k, p)))
            .collect();
        let digit_base = fit.digits.first().and_then(|d| d.first().copied());
        for (e, &(k, p)) in emitted.iter().enumerate() {
            let next = emitted.get(e + 1).map(|x| x.1).or(digit_base);
            instances.insert(
                (group.chain[k].clone(), side),
                vec![Instance { position: p, next }],
            );
            kinds.insert((group.chain[k].clone(), side), FrameKind::Limb);
        }
        if let (Some(name), Some(p)) = (&group.girdle_joint, fit.girdle) {
            instances.insert(
                (name.clone(), side),
                vec![Instance {
                    position: p,
                    next: emitted.first().map(|x| x.1),
                }],
            );
            kinds.insert((name.clone(), side), FrameKind::Limb);
        }
    }
}

/// The joints in template order, repeated places numbered, each under its resolved parent.
fn build_joints(
    template: &Template,
    instances: &BTreeMap<Key, Vec<Instance>>,
    kinds: &BTreeMap<Key, FrameKind>,
) -> Built {
    let repeated = |name: &str| {
        template
            .joint(name)
            .and_then(|j| j.place.as_deref())
            .is_some_and(|p| matches!(p, "trunk" | "neck" | "tail" | "ear"))
    };
    let girdle_joints: Vec<&str> = template
        .limbs
        .iter()
        .filter_map(|l| l.girdle_joint.as_deref())
        .collect();
    let mut skeleton = Skeleton::default();
    let mut next: Vec<Option<DVec3>> = Vec::new();
    let mut kind: Vec<FrameKind> = Vec::new();
    let mut ids: BTreeMap<Key, Vec<JointId>> = BTreeMap::new();
    for tj in &template.joints {
        let sides: Vec<Option<Side>> = if tj.side {
            vec![Some(Side::Left), Some(Side::Right)]
        } else {
            vec![None]
        };
        for side in sides {
            let key = (tj.name.clone(), side);
            let Some(list) = instances.get(&key) else {
                continue;
            };
            let suffix = side.map_or("", |s| s.suffix());
            let mut built = Vec::new();
            for (k, inst) in list.iter().enumerate() {
                let name = if repeated(&tj.name) {
                    format!("{}_{:02}{suffix}", tj.name, k + 1)
                } else {
                    format!("{}{suffix}", tj.name)
                };
                let parent = if k > 0 {
                    built.last().copied()
                } else {
                    resolve_parent(
                        template,
                        &tj.name,
                        side,
                        inst.position,
                        &ids,
                        &skeleton,
                        girdle_joints.contains(&tj.name.as_str()),
                        &repeated,
                    )
                };
                let mut joint = Joint::new(name, parent, inst.position);
                joint.deform = tj.deform;
                joint.dofs = if tj.deform {
                    tj.dofs.clone()
                } else {
                    Vec::new()
                };
                skeleton.joints.push(joint);
                next.push(inst.next);
                kind.push(kinds.get(&key).copied().unwrap_or(FrameKind::Limb));
                built.push(JointId(skeleton.joints.len() - 1));
            }
            ids.insert(key, built);
        }
    }
    Built {
        skeleton,
        next,
        kind,
        ids,
    }
}

/// The digits, after everything else (their parents exist): per (limb group, side), each
/// digit's joints base first.
fn add_digits(
    template: &Template,
    limbs: &[(usize, LimbFit)],
    built: &mut Built,
) -> BTreeMap<(usize, Side), Vec<Vec<JointId>>> {
    let Built {
        skeleton,
        next,
        kind,
        ids,
    } = built;
    let mut digit_ids: BTreeMap<(usize, Side), Vec<Vec<JointId>>> = BTreeMap::new();
    for (g, fit) in limbs {
        let group = &template.limbs[*g];
        let parent = (0..group.digit_row.min(group.chain.len()))
            .rev()
            .find_map(|k| ids.get(&(group.chain[k].clone(), Some(fit.side))))
            .and_then(|v| v.first().copied());
        let mut per_digit = Vec::new();
        for (d, positions) in fit.digits.iter().enumerate() {
            let base_name = group
                .digits
                .get(d)
                .cloned()
                .unwrap_or_else(|| format!("{}_digit_{}", group.name, d + 1));
            let mut prev = parent;
            let mut list = Vec::new();
            for (k, &p) in positions.iter().enumerate() {
                let last = k + 1 == positions.len();
                let name = if last {
                    format!("{base_name}_end{}", fit.side.suffix())
                } else {
                    format!("{base_name}_{:02}{}", k + 1, fit.side.suffix())
                };
                let mut joint = Joint::new(name, prev, p);
                joint.deform = !last;
                joint.dofs = match (last, k, d) {
                    (true, ..) => Vec::new(),
                    (false, 0, 0) => group.first_digit_base_dofs.clone(),
                    (false, 0, _) => group.digit_base_dofs.clone(),
                    _ => group.phalanx_dofs.clone(),
                };
                skeleton.joints.push(joint);
                next.push(positions.get(k + 1).copied());
                kind.push(FrameKind::Limb);
                let id = JointId(skeleton.joints.len() - 1);
                list.push(id);
                prev = Some(id);
            }
            per_digit.push(list);
        }
        digit_ids.insert((*g, fit.side), per_digit);
    }
    digit_ids
}

/// The canonical key → joint map, with a warning per key the template wants but the fit could
/// not place.
fn canonical_map(
    template: &Template,
    limbs: &[(usize, LimbFit)],
    built: &Built,
    digit_ids: &BTreeMap<(usize, Side), Vec<Vec<JointId>>>,
    warnings: &mut Vec<FitWarning>,
) -> BTreeMap<String, JointId> {
    let (skeleton, ids) = (&built.skeleton, &built.ids);
    let mut canonical = BTreeMap::new();
    let mut wanted = Vec::new();
    for tj in &template.joints {
        let Some(c) = &tj.canonical else { continue };
        let sides: Vec<Option<Side>> = if tj.side {
            vec![Some(Side::Left), Some(Side::Right)]
        } else {
            vec![None]
        };
        // A tail the template allows but does not require (`[vertebrae] tail = [0, n]`: a
        // humanoid's) is no missing joint when the figure has none.
        let optional = template.vertebrae.tail.min == 0
            && matches!(tj.place.as_deref(), Some("tail" | "tail_end"));
        for side in sides {
            let key = format!("{c}{}", side.map_or("", |s| s.suffix()));
            if !optional {
                wanted.push(key.clone());
            }
            let id = ids
                .get(&(tj.name.clone(), side))
                .and_then(|v| v.first().copied())
                .or_else(|| {
                    // A chain joint replaced by digits: the central digit's joint at that row.
                    let side = side?;
                    let (g, group) = template
                        .limbs
                        .iter()
                        .enumerate()
                        .find(|(_, l)| l.chain.contains(&tj.name))?;
                    let row = group.chain.iter().position(|n| n == &tj.name)?;
                    let fit = limbs.iter().find(|(lg, f)| *lg == g && f.side == side)?;
                    let digits = digit_ids.get(&(g, side))?;
                    let digit = digits.get(fit.1.central_digit()?)?;
                    let k = row.checked_sub(group.digit_row)?;
                    digit.get(k.min(digit.len().saturating_sub(2))).copied()
                });
            if let Some(id) = id {
                canonical.insert(key, id);
            }
        }
    }
    if template.placed("trunk").is_some() {
        wanted.push(Canonical::Spine.to_string());
        wanted.push(Canonical::Chest.to_string());
        assign_trunk_keys(skeleton, &mut canonical, &template.axial);
    }
    for key in wanted {
        if !canonical.contains_key(&key) {
            warnings.push(FitWarning::MissingCanonical { key });
        }
    }
    canonical
}

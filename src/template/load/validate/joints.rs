//! The template's joints: names, places, canonical keys and DOFs one by one, then the
//! hierarchy they form.

use super::super::{dofs, Problems, RawJoint};
use crate::skeleton::canonical::{is_canonical_key, Canonical};
use crate::template::model::*;
use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;
use toml::Spanned;

/// The validated joints in file order, with their spans and the axial places taken.
pub(super) struct JointTable {
    pub(super) joints: Vec<TemplateJoint>,
    pub(super) spans: BTreeMap<String, Range<usize>>,
    pub(super) places: BTreeSet<String>,
}

impl JointTable {
    /// Joints by name.
    pub(super) fn by_name(&self) -> BTreeMap<&str, &TemplateJoint> {
        self.joints.iter().map(|j| (j.name.as_str(), j)).collect()
    }
}

pub(super) fn joints(
    raw: &[Spanned<RawJoint>],
    ratios: &BTreeMap<String, Vec<f64>>,
    p: &mut Problems,
) -> JointTable {
    let mut joints = Vec::new();
    let mut spans = BTreeMap::new();
    let mut names: BTreeMap<String, usize> = BTreeMap::new();
    let mut expanded = BTreeSet::new();
    let mut canon = BTreeSet::new();
    let mut places = BTreeSet::new();
    for (k, j) in raw.iter().enumerate() {
        let span = j.span();
        let j = j.get_ref();
        let path = format!("joint[{k}] ({})", j.name);
        if j.name.trim().is_empty() {
            p.push(&path, &span, "name is empty");
        }
        if names.insert(j.name.clone(), k).is_some() {
            p.push(&path, &span, format!("duplicate joint name {:?}", j.name));
            continue;
        }
        let full: Vec<String> = if j.side {
            vec![format!("{}_L", j.name), format!("{}_R", j.name)]
        } else {
            vec![j.name.clone()]
        };
        for n in full {
            if !expanded.insert(n.clone()) {
                p.push(
                    &path,
                    &span,
                    format!("joint name {n:?} clashes with another joint's sided name"),
                );
            }
        }
        if let Some(place) = &j.place {
            check_place(j, place, ratios, &mut places, &path, &span, p);
        }
        if let Some(c) = &j.canonical {
            let keys: Vec<String> = if j.side {
                vec![format!("{c}_L"), format!("{c}_R")]
            } else {
                vec![c.clone()]
            };
            for key in keys {
                if !is_canonical_key(&key) {
                    p.push(
                        format!("{path}.canonical"),
                        &span,
                        format!("unknown canonical key {key:?}"),
                    );
                } else if !canon.insert(key.clone()) {
                    p.push(
                        format!("{path}.canonical"),
                        &span,
                        format!("canonical key {key:?} is used twice"),
                    );
                }
            }
        }
        let deform = j.deform.unwrap_or(true);
        let d = dofs(p, &format!("{path}.dofs"), &j.dofs);
        spans.insert(j.name.clone(), span.clone());
        joints.push(TemplateJoint {
            name: j.name.clone(),
            parent: j.parent.clone().filter(|s| !s.is_empty()),
            place: j.place.clone(),
            side: j.side,
            canonical: j.canonical.clone(),
            deform,
            dofs: d,
            line: Some(p.line(&span)),
        });
    }
    for key in [Canonical::Spine.as_str(), Canonical::Chest.as_str()] {
        if canon.contains(key) {
            p.push(
                "joint",
                &(0..0),
                format!("canonical {key:?} is set by axial.{key}_at, not by a joint"),
            );
        }
    }
    JointTable {
        joints,
        spans,
        places,
    }
}

/// Checks a joint's axial `place`: known, free, sided as the place is, with its ratios.
fn check_place(
    j: &RawJoint,
    place: &String,
    ratios: &BTreeMap<String, Vec<f64>>,
    places: &mut BTreeSet<String>,
    path: &str,
    span: &Range<usize>,
    p: &mut Problems,
) {
    if !AXIAL_PLACES.contains(&place.as_str()) {
        p.push(
            format!("{path}.place"),
            span,
            format!(
                "unknown place {place:?}: use one of {}",
                AXIAL_PLACES.join(", ")
            ),
        );
    } else if !places.insert(place.clone()) {
        p.push(
            format!("{path}.place"),
            span,
            format!("place {place:?} is taken by another joint"),
        );
    }
    let sided = SIDED_PLACES.contains(&place.as_str());
    if j.side && !sided {
        p.push(path, span, "axial joints cannot be sided");
    }
    if sided && !j.side {
        p.push(
            path,
            span,
            format!("place {place:?} exists per side: add side = true"),
        );
    }
    if place == "ear" && !ratios.contains_key("ear") {
        p.push(
            format!("{path}.place"),
            span,
            "place \"ear\" needs ratios.ear (relative segment lengths, base first)",
        );
    }
}

/// Parents: known, side-compatible, one root, no cycles; every required axial place taken.
pub(super) fn hierarchy(table: &JointTable, p: &mut Problems) {
    let JointTable {
        joints,
        spans,
        places,
    } = table;
    let by_name = table.by_name();
    let mut roots = 0;
    for (k, j) in joints.iter().enumerate() {
        let span = &spans[&j.name];
        let path = format!("joint[{k}] ({})", j.name);
        match &j.parent {
            None => {
                roots += 1;
                if j.place.as_deref() != Some("root") {
                    p.push(
                        format!("{path}.parent"),
                        span,
                        "only the root joint (place = \"root\") may have no parent",
                    );
                }
            }
            Some(parent) => match by_name.get(parent.as_str()) {
                None => p.push(
                    format!("{path}.parent"),
                    span,
                    format!("unknown parent {parent:?}"),
                ),
                Some(pj) if pj.side && !j.side => p.push(
                    format!("{path}.parent"),
                    span,
                    format!("unsided joint has sided parent {parent:?}"),
                ),
                _ => {}
            },
        }
    }
    if roots != 1 || !places.contains("root") {
        p.push(
            "joint",
            &(0..0),
            format!(
                "need exactly one root joint with place = \"root\" and no parent, found {roots}"
            ),
        );
    }
    // A joint is in a cycle when its own parent chain leads back to it.
    for (k, j) in joints.iter().enumerate() {
        let mut current = j.parent.as_deref();
        for _ in 0..joints.len() {
            let Some(parent) = current else { break };
            if parent == j.name {
                p.push(
                    format!("joint[{k}] ({}).parent", j.name),
                    &spans[&j.name],
                    "the parent chain forms a cycle back to this joint",
                );
                break;
            }
            current = by_name.get(parent).and_then(|q| q.parent.as_deref());
        }
    }
    for place in ["root", "trunk", "neck", "head", "head_end"] {
        if !places.contains(place) {
            p.push(
                "joint",
                &(0..0),
                format!("no joint has place {place:?}: every template needs one"),
            );
        }
    }
}

/// Joints with no place that no limb uses (`owner`: joint name → limb).
pub(super) fn unused(table: &JointTable, owner: &BTreeMap<String, String>, p: &mut Problems) {
    for (k, j) in table.joints.iter().enumerate() {
        if j.place.is_none() && !owner.contains_key(&j.name) {
            p.push(
                format!("joint[{k}] ({})", j.name),
                &table.spans[&j.name],
                "joint has no place and no limb uses it: give it a place or add it to a limb",
            );
        }
    }
}

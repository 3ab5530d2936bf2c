//! The template's limb groups: kinds, girdle, placement, manus, ratio lists and the joints
//! they chain.

use super::super::{dofs, Problems, RawLimb, RATIO_ROWS};
use super::joints::JointTable;
use crate::template::model::*;
use std::collections::BTreeMap;
use std::ops::Range;
use toml::Spanned;

/// The limb groups, and which limb uses each limb joint (joint name → limb name).
pub(super) fn limbs(
    raw: &[Spanned<RawLimb>],
    ratios: &BTreeMap<String, Vec<f64>>,
    table: &JointTable,
    p: &mut Problems,
) -> (Vec<LimbGroup>, BTreeMap<String, String>) {
    let by_name = table.by_name();
    let mut limbs = Vec::new();
    let mut owner: BTreeMap<String, String> = BTreeMap::new();
    for (k, l) in raw.iter().enumerate() {
        let span = l.span();
        let l = l.get_ref();
        let path = format!("limb[{k}] ({})", l.name);
        let (kinds, girdle, placement, manus) = choices(l, &path, &span, p);
        check_ratios(l, ratios, &path, &span, p);
        claim_joints(l, girdle, &by_name, &mut owner, &path, &span, p);
        let first_digit_base_dofs = dofs(
            p,
            &format!("{path}.first_digit_base_dofs"),
            &l.first_digit_base_dofs,
        );
        let digit_base_dofs = dofs(p, &format!("{path}.digit_base_dofs"), &l.digit_base_dofs);
        let phalanx_dofs = dofs(p, &format!("{path}.phalanx_dofs"), &l.phalanx_dofs);
        limbs.push(LimbGroup {
            name: l.name.clone(),
            kinds,
            optional: l.optional,
            girdle,
            placement,
            ratios: l.ratios.clone(),
            girdle_joint: l.girdle_joint.clone(),
            chain: l.chain.clone(),
            digit_row: l.digit_row,
            digits: l.digits.clone(),
            manus,
            wing: l.wing,
            first_digit_base_dofs,
            digit_base_dofs,
            phalanx_dofs,
            line: Some(p.line(&span)),
        });
    }
    (limbs, owner)
}

/// The limb's kinds, girdle, placement and manus.
fn choices(
    l: &RawLimb,
    path: &str,
    span: &Range<usize>,
    p: &mut Problems,
) -> (Vec<LimbKind>, Girdle, Placement, Manus) {
    let mut kinds = Vec::new();
    for kind in &l.kinds {
        match LimbKind::parse(kind) {
            Some(x) => kinds.push(x),
            None => p.push(
                format!("{path}.kinds"),
                span,
                format!("unknown limb kind {kind:?}: use arm, leg, wing, fore_leg or hind_leg"),
            ),
        }
    }
    if l.kinds.is_empty() {
        p.push(format!("{path}.kinds"), span, "give at least one limb kind");
    }
    let girdle = match l.girdle.as_str() {
        "pectoral" => Girdle::Pectoral,
        "pelvic" => Girdle::Pelvic,
        other => {
            p.push(
                format!("{path}.girdle"),
                span,
                format!("unknown girdle {other:?}: use pectoral or pelvic"),
            );
            Girdle::Pelvic
        }
    };
    let placement = match l.placement.as_str() {
        "human" => Placement::Human,
        "animal" => Placement::Animal,
        other => {
            p.push(
                format!("{path}.placement"),
                span,
                format!("unknown placement {other:?}: use human or animal"),
            );
            Placement::Human
        }
    };
    let manus = match l.manus.as_str() {
        "digit" => Manus::Digit,
        "segment" => Manus::Segment,
        other => {
            p.push(
                format!("{path}.manus"),
                span,
                format!("unknown manus {other:?}: use digit or segment"),
            );
            Manus::Digit
        }
    };
    (kinds, girdle, placement, manus)
}

/// The limb's chain and girdle joint: known, sided, not axial, used by no other limb (claimed
/// in `owner`).
fn claim_joints(
    l: &RawLimb,
    girdle: Girdle,
    by_name: &BTreeMap<&str, &TemplateJoint>,
    owner: &mut BTreeMap<String, String>,
    path: &str,
    span: &Range<usize>,
    p: &mut Problems,
) {
    let mut refs: Vec<(&str, &String)> = l.chain.iter().map(|n| ("chain", n)).collect();
    if let Some(g) = &l.girdle_joint {
        refs.push(("girdle_joint", g));
        if girdle == Girdle::Pelvic {
            p.push(
                format!("{path}.girdle_joint"),
                span,
                "a pelvic girdle is a rigid extension of the root: remove girdle_joint",
            );
        }
    }
    for (field, name) in refs {
        match by_name.get(name.as_str()) {
            None => p.push(
                format!("{path}.{field}"),
                span,
                format!("unknown joint {name:?}"),
            ),
            Some(j) => {
                if !j.side {
                    p.push(
                        format!("{path}.{field}"),
                        span,
                        format!("limb joint {name:?} must be sided (side = true)"),
                    );
                }
                if j.place.is_some() {
                    p.push(
                        format!("{path}.{field}"),
                        span,
                        format!("joint {name:?} is axial (has a place)"),
                    );
                }
                if let Some(other) = owner.insert(name.clone(), l.name.clone()) {
                    p.push(
                        format!("{path}.{field}"),
                        span,
                        format!("joint {name:?} is already used by limb {other:?}"),
                    );
                }
            }
        }
    }
}

/// The limb's ratio list: known, one row per Table 8.1 row, one chain joint per boundary, a
/// digit row inside it with matching digit ratio lists.
fn check_ratios(
    l: &RawLimb,
    ratios: &BTreeMap<String, Vec<f64>>,
    path: &str,
    span: &Range<usize>,
    p: &mut Problems,
) {
    let Some(r) = ratios.get(&l.ratios) else {
        p.push(
            format!("{path}.ratios"),
            span,
            format!("unknown ratio list {:?}", l.ratios),
        );
        return;
    };
    if r.len() != RATIO_ROWS {
        p.push(
            format!("{path}.ratios"),
            span,
            format!(
                "ratio list {:?} has {} rows, Table 8.1 has {RATIO_ROWS}",
                l.ratios,
                r.len()
            ),
        );
    }
    if l.chain.len() != r.len() + 1 {
        p.push(
            format!("{path}.chain"),
            span,
            format!(
                "chain has {} joints, ratio list {:?} needs {} (one per boundary)",
                l.chain.len(),
                l.ratios,
                r.len() + 1
            ),
        );
    }
    if l.digit_row < 2 || l.digit_row >= r.len() {
        p.push(
            format!("{path}.digit_row"),
            span,
            format!("digit_row {} must be in 2..{}", l.digit_row, r.len()),
        );
    } else {
        let n = r.len() - l.digit_row;
        for (list, want) in [("digit", n), ("first_digit", n.saturating_sub(1))] {
            match ratios.get(list) {
                Some(d) if d.len() == want => {}
                Some(d) => p.push(
                    format!("ratios.{list}"),
                    span,
                    format!("has {} entries, limb {:?} needs {want}", d.len(), l.name),
                ),
                None => p.push(
                    format!("ratios.{list}"),
                    span,
                    format!("missing: limb {:?} needs it", l.name),
                ),
            }
        }
    }
}

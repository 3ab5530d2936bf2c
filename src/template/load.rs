//! Parsing and validating template files: every problem is collected with its location.

use super::model::*;
use super::{TemplateError, TemplateProblem};
use crate::skeleton::canonical::is_canonical_key;
use crate::skeleton::{Dof, LocalAxis};
use serde::Deserialize;
use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;
use std::path::Path;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTemplate {
    template: Spanned<RawHeader>,
    sections: Spanned<BTreeMap<String, Spanned<f64>>>,
    axial: Spanned<RawAxial>,
    vertebrae: Spanned<BTreeMap<String, Spanned<[i64; 2]>>>,
    ratios: Spanned<BTreeMap<String, Spanned<Vec<f64>>>>,
    #[serde(default)]
    joint: Vec<Spanned<RawJoint>>,
    #[serde(default)]
    limb: Vec<Spanned<RawLimb>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHeader {
    name: String,
    #[serde(default)]
    description: String,
    posture: Spanned<String>,
    #[serde(default)]
    refine: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxial {
    dorsal_offset: Spanned<f64>,
    vertebra_to_head: Spanned<f64>,
    cervical_s_curve: bool,
    spine_at: Spanned<f64>,
    chest_at: Spanned<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDof {
    axis: String,
    min: f64,
    max: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawJoint {
    name: String,
    #[serde(default)]
    parent: Option<String>,
    #[serde(default)]
    place: Option<String>,
    #[serde(default)]
    side: bool,
    #[serde(default)]
    canonical: Option<String>,
    #[serde(default)]
    deform: Option<bool>,
    #[serde(default)]
    dofs: Vec<Spanned<RawDof>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLimb {
    name: String,
    kinds: Vec<String>,
    #[serde(default)]
    optional: bool,
    girdle: String,
    placement: String,
    ratios: String,
    #[serde(default)]
    girdle_joint: Option<String>,
    chain: Vec<String>,
    digit_row: usize,
    #[serde(default)]
    digits: Vec<String>,
    manus: String,
    #[serde(default)]
    wing: bool,
    #[serde(default)]
    first_digit_base_dofs: Vec<Spanned<RawDof>>,
    #[serde(default)]
    digit_base_dofs: Vec<Spanned<RawDof>>,
    #[serde(default)]
    phalanx_dofs: Vec<Spanned<RawDof>>,
}

/// Collects problems with locations.
struct Problems<'a> {
    file: &'a str,
    text: &'a str,
    list: Vec<TemplateProblem>,
}

impl Problems<'_> {
    fn line(&self, span: &Range<usize>) -> usize {
        line_of(self.text, span.start)
    }

    fn push(&mut self, path: impl Into<String>, span: &Range<usize>, message: impl Into<String>) {
        // An empty span marks a problem of the whole file (no single line).
        let line = (span.end > 0).then(|| self.line(span));
        self.list.push(TemplateProblem {
            file: self.file.to_string(),
            path: path.into(),
            line,
            message: message.into(),
        });
    }
}

fn line_of(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

const RATIO_ROWS: usize = 7;

impl Template {
    /// Parses the bundled template `name` (`humanoid`, `quadruped`, `winged`).
    ///
    /// # Errors
    /// [`TemplateError::UnknownTemplate`] for another name; parse/validation errors would be
    /// build defects (the unit tests load every bundled template).
    pub fn builtin(name: &str) -> Result<Template, TemplateError> {
        let (_, text) = BUILTIN_TEMPLATES
            .iter()
            .find(|(n, _)| *n == name)
            .ok_or_else(|| TemplateError::UnknownTemplate { name: name.into() })?;
        Template::parse(text, &format!("builtin:{name}"))
    }

    /// Reads and validates a template file.
    ///
    /// # Errors
    /// [`TemplateError::Io`] when unreadable, [`TemplateError::Parse`] for TOML/shape errors
    /// and [`TemplateError::Invalid`] listing every rule broken.
    pub fn load(path: &Path) -> Result<Template, TemplateError> {
        let text = std::fs::read_to_string(path).map_err(|source| TemplateError::Io {
            path: path.display().to_string(),
            source,
        })?;
        Template::parse(&text, &path.display().to_string())
    }

    /// Parses and validates template text; `file` names it in messages.
    ///
    /// # Errors
    /// [`TemplateError::Parse`] when the text is not TOML of the template's shape (unknown or
    /// missing keys, wrong types); [`TemplateError::Invalid`] with every problem found: unknown
    /// or cyclic parents, duplicate names, several roots, unknown places, kinds, girdles,
    /// placements, axes or canonical keys, sections not summing to 1, non-positive ratios,
    /// chains not matching their ratio rows, limits with min > max or beyond ±180°.
    pub fn parse(text: &str, file: &str) -> Result<Template, TemplateError> {
        let raw: RawTemplate = toml::from_str(text).map_err(|e| TemplateError::Parse {
            file: file.into(),
            line: e.span().map(|s| line_of(text, s.start)),
            message: e.message().trim().to_string(),
        })?;
        let mut p = Problems {
            file,
            text,
            list: Vec::new(),
        };
        let template = validate(raw, &mut p);
        if p.list.is_empty() {
            Ok(template)
        } else {
            p.list.sort_by_key(|q| q.line);
            Err(TemplateError::Invalid {
                file: file.into(),
                problems: p.list,
            })
        }
    }
}

fn unit_fraction(p: &mut Problems, path: &str, v: &Spanned<f64>, open: bool) -> f64 {
    let x = *v.get_ref();
    let ok = if open {
        x > 0.0 && x < 1.0
    } else {
        (0.0..=1.0).contains(&x)
    };
    if !ok || !x.is_finite() {
        let range = if open { "(0, 1)" } else { "[0, 1]" };
        p.push(path, &v.span(), format!("{x} is outside {range}"));
    }
    x
}

fn dofs(p: &mut Problems, path: &str, raw: &[Spanned<RawDof>]) -> Vec<Dof> {
    let mut out = Vec::new();
    let mut seen = BTreeSet::new();
    for (k, d) in raw.iter().enumerate() {
        let span = d.span();
        let d = d.get_ref();
        let here = format!("{path}[{k}]");
        let axis = match d.axis.to_ascii_lowercase().as_str() {
            "x" => Some(LocalAxis::X),
            "y" => Some(LocalAxis::Y),
            "z" => Some(LocalAxis::Z),
            _ => {
                p.push(
                    format!("{here}.axis"),
                    &span,
                    format!("unknown axis {:?}: use x, y or z", d.axis),
                );
                None
            }
        };
        if axis.is_some() && !seen.insert(d.axis.to_ascii_lowercase()) {
            p.push(&here, &span, format!("axis {} appears twice", d.axis));
        }
        if !(d.min.is_finite() && d.max.is_finite()) || d.min > d.max {
            p.push(
                &here,
                &span,
                format!("limits min {} > max {}: swap them", d.min, d.max),
            );
        }
        if d.min < -180.0 || d.max > 180.0 {
            p.push(
                &here,
                &span,
                format!("limits [{}, {}] exceed [-180, 180] degrees", d.min, d.max),
            );
        }
        if let Some(axis) = axis {
            out.push(Dof {
                axis,
                min: d.min.to_radians(),
                max: d.max.to_radians(),
            });
        }
    }
    out
}

fn validate(raw: RawTemplate, p: &mut Problems) -> Template {
    // Header.
    let header_span = raw.template.span();
    let header = raw.template.into_inner();
    if header.name.trim().is_empty() {
        p.push("template.name", &header_span, "name is empty");
    }
    let posture = match header.posture.get_ref().as_str() {
        "upright" => Posture::Upright,
        "horizontal" => Posture::Horizontal,
        other => {
            p.push(
                "template.posture",
                &header.posture.span(),
                format!("unknown posture {other:?}: use upright or horizontal"),
            );
            Posture::Upright
        }
    };

    let refinement = header.refine.and_then(|r| match r.get_ref().as_str() {
        "human_slicing" => Some(RefineKind::HumanSlicing),
        other => {
            p.push(
                "template.refine",
                &r.span(),
                format!("unknown refinement {other:?}: use human_slicing or leave it out"),
            );
            None
        }
    });

    // Sections.
    let sections_span = raw.sections.span();
    let sections_map = raw.sections.into_inner();
    for (key, v) in &sections_map {
        if key != "head" && key != "neck" {
            p.push(
                format!("sections.{key}"),
                &v.span(),
                "unknown section: use head and neck",
            );
        }
    }
    let section = |name: &str, p: &mut Problems| match sections_map.get(name) {
        Some(v) => unit_fraction(p, &format!("sections.{name}"), v, false),
        None => {
            p.push(
                format!("sections.{name}"),
                &sections_span,
                "missing: give the head and neck fractions",
            );
            0.0
        }
    };
    let sections = Sections {
        head: section("head", p),
        neck: section("neck", p),
    };
    if (sections.head + sections.neck - 1.0).abs() > 1e-6 {
        p.push(
            "sections",
            &sections_span,
            format!(
                "head {} + neck {} = {} does not sum to 1",
                sections.head,
                sections.neck,
                sections.head + sections.neck
            ),
        );
    }

    // Axial rules.
    let axial = raw.axial.into_inner();
    let dorsal_offset = unit_fraction(p, "axial.dorsal_offset", &axial.dorsal_offset, false);
    let vertebra_to_head = *axial.vertebra_to_head.get_ref();
    if !(vertebra_to_head > 0.0 && vertebra_to_head.is_finite()) {
        p.push(
            "axial.vertebra_to_head",
            &axial.vertebra_to_head.span(),
            format!("{vertebra_to_head} must be positive"),
        );
    }
    let spine_at = unit_fraction(p, "axial.spine_at", &axial.spine_at, true);
    let chest_at = unit_fraction(p, "axial.chest_at", &axial.chest_at, true);
    if spine_at >= chest_at {
        p.push(
            "axial.chest_at",
            &axial.chest_at.span(),
            format!("chest_at {chest_at} must be above spine_at {spine_at}"),
        );
    }

    // Vertebra counts.
    let vert_span = raw.vertebrae.span();
    let vert = raw.vertebrae.into_inner();
    for (key, v) in &vert {
        if !["neck", "trunk", "tail"].contains(&key.as_str()) {
            p.push(
                format!("vertebrae.{key}"),
                &v.span(),
                "unknown section: use neck, trunk and tail",
            );
        }
    }
    let count = |name: &str, least: i64, p: &mut Problems| -> CountRange {
        match vert.get(name) {
            Some(v) => {
                let [min, max] = *v.get_ref();
                let path = format!("vertebrae.{name}");
                if min < least {
                    p.push(&path, &v.span(), format!("min {min} is below {least}"));
                }
                if min > max {
                    p.push(
                        &path,
                        &v.span(),
                        format!("min {min} > max {max}: swap them"),
                    );
                }
                CountRange {
                    min: min.max(0) as usize,
                    max: max.max(min).max(0) as usize,
                }
            }
            None => {
                p.push(
                    format!("vertebrae.{name}"),
                    &vert_span,
                    "missing: give [min, max]",
                );
                CountRange { min: 0, max: 0 }
            }
        }
    };
    let vertebrae = VertebraRules {
        neck: count("neck", 1, p),
        trunk: count("trunk", 2, p),
        tail: count("tail", 0, p),
    };

    // Ratios.
    let ratio_map = raw.ratios.into_inner();
    let mut ratios = BTreeMap::new();
    for (key, v) in &ratio_map {
        let list = v.get_ref();
        if list.is_empty() || list.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
            p.push(
                format!("ratios.{key}"),
                &v.span(),
                "ratios must be a non-empty list of positive numbers",
            );
        }
        ratios.insert(key.clone(), list.clone());
    }

    // Joints.
    let mut joints = Vec::new();
    let mut spans = BTreeMap::new();
    let mut names: BTreeMap<String, usize> = BTreeMap::new();
    let mut expanded = BTreeSet::new();
    let mut canon = BTreeSet::new();
    let mut places = BTreeSet::new();
    for (k, j) in raw.joint.iter().enumerate() {
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
            if !AXIAL_PLACES.contains(&place.as_str()) {
                p.push(
                    format!("{path}.place"),
                    &span,
                    format!(
                        "unknown place {place:?}: use one of {}",
                        AXIAL_PLACES.join(", ")
                    ),
                );
            } else if !places.insert(place.clone()) {
                p.push(
                    format!("{path}.place"),
                    &span,
                    format!("place {place:?} is taken by another joint"),
                );
            }
            let sided = SIDED_PLACES.contains(&place.as_str());
            if j.side && !sided {
                p.push(&path, &span, "axial joints cannot be sided");
            }
            if sided && !j.side {
                p.push(
                    &path,
                    &span,
                    format!("place {place:?} exists per side: add side = true"),
                );
            }
            if place == "ear" && !ratios.contains_key("ear") {
                p.push(
                    format!("{path}.place"),
                    &span,
                    "place \"ear\" needs ratios.ear (relative segment lengths, base first)",
                );
            }
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
    for key in ["spine", "chest"] {
        if canon.contains(key) {
            p.push(
                "joint",
                &(0..0),
                format!("canonical {key:?} is set by axial.{key}_at, not by a joint"),
            );
        }
    }
    // Parents: known, side-compatible, one root, no cycles.
    let by_name: BTreeMap<&str, &TemplateJoint> =
        joints.iter().map(|j| (j.name.as_str(), j)).collect();
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

    // Limbs.
    let mut limbs = Vec::new();
    let mut owner: BTreeMap<String, String> = BTreeMap::new();
    for (k, l) in raw.limb.iter().enumerate() {
        let span = l.span();
        let l = l.get_ref();
        let path = format!("limb[{k}] ({})", l.name);
        let mut kinds = Vec::new();
        for kind in &l.kinds {
            match LimbKind::parse(kind) {
                Some(x) => kinds.push(x),
                None => p.push(
                    format!("{path}.kinds"),
                    &span,
                    format!("unknown limb kind {kind:?}: use arm, leg, wing, fore_leg or hind_leg"),
                ),
            }
        }
        if l.kinds.is_empty() {
            p.push(
                format!("{path}.kinds"),
                &span,
                "give at least one limb kind",
            );
        }
        let girdle = match l.girdle.as_str() {
            "pectoral" => Girdle::Pectoral,
            "pelvic" => Girdle::Pelvic,
            other => {
                p.push(
                    format!("{path}.girdle"),
                    &span,
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
                    &span,
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
                    &span,
                    format!("unknown manus {other:?}: use digit or segment"),
                );
                Manus::Digit
            }
        };
        match ratios.get(&l.ratios) {
            None => p.push(
                format!("{path}.ratios"),
                &span,
                format!("unknown ratio list {:?}", l.ratios),
            ),
            Some(r) => {
                if r.len() != RATIO_ROWS {
                    p.push(
                        format!("{path}.ratios"),
                        &span,
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
                        &span,
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
                        &span,
                        format!("digit_row {} must be in 2..{}", l.digit_row, r.len()),
                    );
                } else {
                    let n = r.len() - l.digit_row;
                    for (list, want) in [("digit", n), ("first_digit", n.saturating_sub(1))] {
                        match ratios.get(list) {
                            Some(d) if d.len() == want => {}
                            Some(d) => p.push(
                                format!("ratios.{list}"),
                                &span,
                                format!("has {} entries, limb {:?} needs {want}", d.len(), l.name),
                            ),
                            None => p.push(
                                format!("ratios.{list}"),
                                &span,
                                format!("missing: limb {:?} needs it", l.name),
                            ),
                        }
                    }
                }
            }
        }
        let mut refs: Vec<(&str, &String)> = l.chain.iter().map(|n| ("chain", n)).collect();
        if let Some(g) = &l.girdle_joint {
            refs.push(("girdle_joint", g));
            if girdle == Girdle::Pelvic {
                p.push(
                    format!("{path}.girdle_joint"),
                    &span,
                    "a pelvic girdle is a rigid extension of the root: remove girdle_joint",
                );
            }
        }
        for (field, name) in refs {
            match by_name.get(name.as_str()) {
                None => p.push(
                    format!("{path}.{field}"),
                    &span,
                    format!("unknown joint {name:?}"),
                ),
                Some(j) => {
                    if !j.side {
                        p.push(
                            format!("{path}.{field}"),
                            &span,
                            format!("limb joint {name:?} must be sided (side = true)"),
                        );
                    }
                    if j.place.is_some() {
                        p.push(
                            format!("{path}.{field}"),
                            &span,
                            format!("joint {name:?} is axial (has a place)"),
                        );
                    }
                    if let Some(other) = owner.insert(name.clone(), l.name.clone()) {
                        p.push(
                            format!("{path}.{field}"),
                            &span,
                            format!("joint {name:?} is already used by limb {other:?}"),
                        );
                    }
                }
            }
        }
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
    for (k, j) in joints.iter().enumerate() {
        if j.place.is_none() && !owner.contains_key(&j.name) {
            p.push(
                format!("joint[{k}] ({})", j.name),
                &spans[&j.name],
                "joint has no place and no limb uses it: give it a place or add it to a limb",
            );
        }
    }

    // Parents before children.
    let order = topological(&joints);
    let joints = order.into_iter().map(|k| joints[k].clone()).collect();

    Template {
        name: header.name,
        description: header.description,
        file: p.file.to_string(),
        posture,
        refinement,
        sections,
        axial: AxialRules {
            dorsal_offset,
            vertebra_to_head,
            cervical_s_curve: axial.cervical_s_curve,
            spine_at,
            chest_at,
        },
        vertebrae,
        ratios,
        joints,
        limbs,
    }
}

/// Joint indices ordered parents first (file order otherwise); joints in cycles or under
/// unknown parents come last (validation reports them).
fn topological(joints: &[TemplateJoint]) -> Vec<usize> {
    let mut done = vec![false; joints.len()];
    let mut order = Vec::new();
    loop {
        let before = order.len();
        for (k, j) in joints.iter().enumerate() {
            if done[k] {
                continue;
            }
            let ready = match &j.parent {
                None => true,
                Some(parent) => joints
                    .iter()
                    .position(|q| &q.name == parent)
                    .is_some_and(|pk| done[pk]),
            };
            if ready {
                done[k] = true;
                order.push(k);
            }
        }
        if order.len() == before {
            break;
        }
    }
    order.extend((0..joints.len()).filter(|&k| !done[k]));
    order
}

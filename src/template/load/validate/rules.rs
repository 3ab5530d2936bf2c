//! The template's header, sections, axial rules, vertebra counts and ratio lists.

use super::super::{unit_fraction, Problems, RawAxial, RawHeader};
use crate::template::model::*;
use std::collections::BTreeMap;
use toml::Spanned;

/// The validated header.
pub(super) struct Header {
    pub(super) name: String,
    pub(super) description: String,
    pub(super) posture: Posture,
    pub(super) refinement: Option<RefineKind>,
    pub(super) expects: Vec<ExpectedPart>,
}

pub(super) fn header(raw: Spanned<RawHeader>, p: &mut Problems) -> Header {
    let header_span = raw.span();
    let header = raw.into_inner();
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
    let expects = expected_parts(header.expects, p);
    Header {
        name: header.name,
        description: header.description,
        posture,
        refinement,
        expects,
    }
}

/// The header's `expects` list: known part names, each once.
fn expected_parts(raw: Vec<Spanned<String>>, p: &mut Problems) -> Vec<ExpectedPart> {
    let mut out = Vec::new();
    for (k, name) in raw.iter().enumerate() {
        let path = format!("template.expects[{k}]");
        match ExpectedPart::parse(name.get_ref()) {
            Some(part) if out.contains(&part) => p.push(
                path,
                &name.span(),
                format!("{name:?} is listed twice", name = name.get_ref()),
            ),
            Some(part) => out.push(part),
            None => {
                let known: Vec<&str> = ExpectedPart::ALL.iter().map(|p| p.as_str()).collect();
                p.push(
                    path,
                    &name.span(),
                    format!(
                        "unknown part {:?}: use {}",
                        name.get_ref(),
                        known.join(", ")
                    ),
                )
            }
        }
    }
    out
}

pub(super) fn sections(raw: Spanned<BTreeMap<String, Spanned<f64>>>, p: &mut Problems) -> Sections {
    let sections_span = raw.span();
    let sections_map = raw.into_inner();
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
    sections
}

pub(super) fn axial(axial: RawAxial, p: &mut Problems) -> AxialRules {
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
    AxialRules {
        dorsal_offset,
        vertebra_to_head,
        cervical_s_curve: axial.cervical_s_curve,
        dorsal_taper: axial.dorsal_taper,
        spine_at,
        chest_at,
    }
}

pub(super) fn vertebrae(
    raw: Spanned<BTreeMap<String, Spanned<[i64; 2]>>>,
    p: &mut Problems,
) -> VertebraRules {
    let vert_span = raw.span();
    let vert = raw.into_inner();
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
    VertebraRules {
        neck: count("neck", 1, p),
        trunk: count("trunk", 2, p),
        tail: count("tail", 0, p),
    }
}

pub(super) fn ratios(
    raw: Spanned<BTreeMap<String, Spanned<Vec<f64>>>>,
    p: &mut Problems,
) -> BTreeMap<String, Vec<f64>> {
    let ratio_map = raw.into_inner();
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
    ratios
}

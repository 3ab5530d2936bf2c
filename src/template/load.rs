//! Parsing and validating template files: every problem is collected with its location.

use super::model::*;
use super::{TemplateError, TemplateProblem};
use crate::skeleton::{Dof, LocalAxis};
use serde::Deserialize;
use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;
use std::path::Path;
use toml::Spanned;
use validate::validate;

mod validate;

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
    #[serde(default)]
    full_spine: Option<RawFullSpine>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFullSpine {
    cervical: Vec<Spanned<RawDof>>,
    thoracic: Vec<Spanned<RawDof>>,
    lumbar: Vec<Spanned<RawDof>>,
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
    #[serde(default)]
    expects: Vec<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxial {
    dorsal_offset: Spanned<f64>,
    vertebra_to_head: Spanned<f64>,
    cervical_s_curve: bool,
    #[serde(default)]
    dorsal_taper: bool,
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

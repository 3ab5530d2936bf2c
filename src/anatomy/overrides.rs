//! A labels override file: the user's corrections (ch.7.3.3 lets the user modify any label).

use super::rules::{Assignment, Draft};
use super::{AnatomyError, FigureClass, Label, LimbPair, Side};
use glam::DVec3;
use serde::Deserialize;
use std::path::Path;

/// One correction: a section, chosen by index or by the point nearest to it, and its new label.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionOverride {
    /// Section index as listed under `"sections"` in labels.json.
    #[serde(default)]
    pub section: Option<usize>,
    /// A point (mesh units and frame): the section with a level-graph vertex nearest to it.
    #[serde(default)]
    pub point: Option<[f64; 3]>,
    /// The new label (`"trunk"` merges the section into the trunk).
    pub label: Label,
    /// Side of a paired part.
    #[serde(default)]
    pub side: Option<Side>,
    /// Girdle of a limb.
    #[serde(default)]
    pub limb_pair: Option<LimbPair>,
}

/// A labels override file:
/// `{"figure": "animal-like", "sections": [{"section": 3, "label": "tail"},
/// {"point": [0.1, 1.2, 0.0], "label": "arm", "side": "L", "limb_pair": "fore"}]}`.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Overrides {
    /// Replaces the figure class.
    #[serde(default)]
    pub figure: Option<FigureClass>,
    /// Section corrections, applied in order.
    #[serde(default)]
    pub sections: Vec<SectionOverride>,
}

impl Overrides {
    /// Reads an override file.
    ///
    /// # Errors
    /// [`AnatomyError::Override`] naming the file and the problem.
    pub fn load(path: &Path) -> Result<Self, AnatomyError> {
        let err = |detail: String| AnatomyError::Override {
            path: path.display().to_string(),
            detail,
        };
        let text = std::fs::read_to_string(path).map_err(|e| err(e.to_string()))?;
        serde_json::from_str(&text).map_err(|e| err(e.to_string()))
    }

    /// Applies the corrections to `draft` (centroids of the level-graph vertices are needed to
    /// resolve points). Pair partners are recomputed for corrected limbs.
    ///
    /// # Errors
    /// [`AnatomyError::Override`] for a section index out of range or an entry with neither
    /// or both of `section` and `point`.
    pub fn apply(&self, draft: &mut Draft, centroids: &[DVec3]) -> Result<(), AnatomyError> {
        let err = |detail: String| AnatomyError::Override {
            path: "(override)".to_string(),
            detail,
        };
        if let Some(f) = self.figure {
            draft.figure = f;
        }
        for (k, o) in self.sections.iter().enumerate() {
            let s = match (o.section, o.point) {
                (Some(s), None) if s < draft.sections.len() => s,
                (Some(s), None) => {
                    return Err(err(format!(
                        "entry {k}: section {s} does not exist (there are {})",
                        draft.sections.len()
                    )))
                }
                (None, Some(p)) => {
                    let p = DVec3::from_array(p);
                    let best = (0..draft.sections.len()).min_by(|&a, &b| {
                        let d = |s: usize| {
                            draft.sections[s]
                                .vertices
                                .iter()
                                .map(|&v| centroids[v].distance(p))
                                .fold(f64::INFINITY, f64::min)
                        };
                        d(a).total_cmp(&d(b))
                    });
                    best.ok_or_else(|| err(format!("entry {k}: the figure has no sections")))?
                }
                _ => {
                    return Err(err(format!(
                        "entry {k}: give exactly one of \"section\" and \"point\""
                    )))
                }
            };
            draft.assignments[s] = Assignment {
                label: (o.label != Label::Trunk).then_some(o.label),
                side: o.side,
                limb_pair: o.limb_pair,
                partner: None,
            };
        }
        // Partners: same label and girdle, opposite side.
        for s in 0..draft.assignments.len() {
            let a = draft.assignments[s];
            if a.partner.is_some() || a.side.is_none() || a.label.is_none() {
                continue;
            }
            let partner = (0..draft.assignments.len()).find(|&t| {
                let b = draft.assignments[t];
                t != s
                    && b.label == a.label
                    && b.limb_pair == a.limb_pair
                    && b.side.is_some()
                    && b.side != a.side
            });
            draft.assignments[s].partner = partner;
        }
        Ok(())
    }
}

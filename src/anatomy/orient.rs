//! The up direction found from the figure when the user does not give it.
//!
//! A figure stands on its legs: under the right up direction the labelling rules find the
//! parts of a whole humanoid (two legs, two arms, a head), quadruped (four legs, a head) or
//! winged figure (two legs, two wings, a head), and its legs hang down from the trunk. Under a
//! wrong one (a Z-up file read as Y-up: the figure lies on its back) the "legs" are whatever
//! reaches the floor, lying flat. [`find_up`] scores the labels of the level graph (cheap: no
//! per-vertex projection) under each axis direction: +Y first (the glTF convention), kept
//! at once when the figure is complete and standing, or stands on a pair of legs hanging
//! within 45° of vertical, under it; otherwise every axis is scored and the best
//! complete one wins, unless the opposite direction is complete too (a figure standing either way
//! up, legs sprawling from a flat body, has no up to find) or its legs hang less plumb than the
//! legs labelled under +Y do (an insect standing under +Y on one leg the labels found). A
//! whole humanoid carries its body on legs no thinner than its arms and its head tops its arm
//! roots, so a big-headed figure read upside down (long ears hanging like legs) is not whole.
//! When no axis gives a complete standing figure, +Y stays, with a warning.

use super::{label_graph, Draft, FigureClass, Frame, Label, LabelOptions, LevelTree, Section};
use crate::medial::MedialSurface;
use crate::paths::PathOptions;
use crate::voxel::Solid;
use glam::DVec3;
use serde::Serialize;

/// The candidates, in order of preference on ties.
const CANDIDATES: [(DVec3, &str); 6] = [
    (DVec3::Y, "+Y"),
    (DVec3::Z, "+Z"),
    (DVec3::NEG_Y, "-Y"),
    (DVec3::NEG_Z, "-Z"),
    (DVec3::X, "+X"),
    (DVec3::NEG_X, "-X"),
];

/// Under +Y (the glTF convention) a figure whose legs hang at least this much (45° from
/// vertical) stands, and +Y is kept even when its labels miss a part.
const STANDING: f64 = 0.7;

/// How much less plumb the legs under another up direction may hang than those under +Y for
/// that direction to replace +Y (0.1: about 25 degrees from vertical when +Y's hang straight).
const PLUMB_MARGIN: f64 = 0.1;

/// Legs carry the body: a humanoid whose "arms" are this much thicker than its "legs" is read
/// upside down (ears or a hat hanging from a head taken for legs).
const THICKER_ARMS: f64 = 1.25;

/// A leg hangs down when the unit vector from its end to where it joins the trunk has at
/// least this component along up (60° from vertical).
const HANGING: f64 = 0.5;

/// How one up direction labels the figure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UpScore {
    /// The direction.
    pub up: DVec3,
    /// Its name (`+Y`, `-Z`, ...).
    pub name: &'static str,
    /// Whether the labels make a whole humanoid, quadruped or winged figure whose legs hang
    /// down.
    pub complete: bool,
    /// Whether at least one pair of legs was found and the legs hang down (60° from vertical
    /// or closer).
    pub standing: bool,
    /// Mean over the legs of how much they hang down (1: vertical below the trunk, 0:
    /// horizontal, negative: above it).
    pub hanging: f64,
    /// The score: parts found, completeness and hanging legs.
    pub score: f64,
}

/// The up direction chosen by [`find_up`] and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UpChoice {
    /// The direction.
    pub up: DVec3,
    /// The scores of the directions tried (one when +Y was kept at once).
    pub scores: Vec<UpScore>,
    /// Confidence in [0, 1]: 1 when the choice was complete and the runner-up not, less as the
    /// runner-up's score approaches it; 0 when no direction gave a complete figure.
    pub confidence: f64,
    /// A sentence for the user.
    pub note: String,
}

/// Scores the draft labels of one up direction.
fn score(draft: &Draft, up: DVec3, name: &'static str) -> UpScore {
    let count = |label: Label, paired: bool| {
        draft
            .assignments
            .iter()
            .filter(|a| a.label == Some(label) && (!paired || a.partner.is_some()))
            .count()
    };
    let paired_legs = count(Label::Leg, true);
    let arms = count(Label::Arm, true);
    let wings = count(Label::Wing, true);
    let head = count(Label::Head, false) > 0;
    let legs: Vec<f64> = draft
        .assignments
        .iter()
        .zip(&draft.sections)
        .filter(|(a, _)| a.label == Some(Label::Leg))
        .filter_map(|(_, s)| (s.attachment - s.distal).try_normalize().map(|v| v.dot(up)))
        .collect();
    let hanging = if legs.is_empty() {
        0.0
    } else {
        legs.iter().sum::<f64>() / legs.len() as f64
    };
    let standing = paired_legs >= 2 && hanging >= HANGING;
    // Thickness of a limb: DMS voxels per unit length (the medial sheet widens with the limb).
    let thickness = |label: Label| {
        let (sum, n) = draft
            .assignments
            .iter()
            .zip(&draft.sections)
            .filter(|(a, s)| a.label == Some(label) && s.length > 0.0)
            .fold((0.0, 0usize), |(t, n), (_, s)| {
                (t + s.voxels as f64 / s.length, n + 1)
            });
        (n > 0).then(|| sum / n as f64)
    };
    let legs_carry = match (thickness(Label::Leg), thickness(Label::Arm)) {
        (Some(legs), Some(arms)) => arms <= THICKER_ARMS * legs,
        _ => true,
    };
    let whole = head
        && match draft.figure {
            FigureClass::HumanLike => {
                paired_legs == 2 && arms == 2 && legs_carry && head_on_top(draft, up)
            }
            FigureClass::AnimalLike => paired_legs == 4 || (paired_legs == 2 && wings == 2),
            FigureClass::Unknown => false,
        };
    let complete = whole && standing;
    let score = 2.0 * paired_legs.min(4) as f64
        + arms.min(2) as f64
        + wings.min(2) as f64
        + if head { 2.0 } else { 0.0 }
        + if complete { 5.0 } else { 0.0 }
        + 6.0 * hanging
        - if draft.figure == FigureClass::Unknown {
            3.0
        } else {
            0.0
        };
    UpScore {
        up,
        name,
        complete,
        standing,
        hanging,
        score,
    }
}

/// Whether the head's end lies above the mean root of the arms along `up` (true when either is
/// missing): a humanoid's head tops its shoulders in any arm pose, while a figure read upside
/// down (ears hanging like legs from a big head) finds its "head" in a bump below the arms.
fn head_on_top(draft: &Draft, up: DVec3) -> bool {
    let along = |label: Label, point: fn(&Section) -> DVec3| {
        let (sum, n) = draft
            .assignments
            .iter()
            .zip(&draft.sections)
            .filter(|(a, _)| a.label == Some(label))
            .fold((0.0, 0usize), |(t, n), (_, s)| {
                (t + point(s).dot(up), n + 1)
            });
        (n > 0).then(|| sum / n as f64)
    };
    match (
        along(Label::Head, |s| s.distal),
        along(Label::Arm, |s| s.attachment),
    ) {
        (Some(head), Some(arms)) => head > arms,
        _ => true,
    }
}

/// The draft labels of the level graph under `up` (any forward across it).
fn draft_under(
    tree: &LevelTree,
    solid: &Solid,
    surface: &MedialSurface,
    options: &LabelOptions,
    up: DVec3,
) -> Option<Draft> {
    let across = if up.dot(DVec3::Z).abs() < 0.9 {
        DVec3::Z
    } else {
        DVec3::Y
    };
    let frame = Frame::new(up, across).ok()?;
    let graph = super::graph_in_frame(solid, surface, tree, &frame);
    Some(label_graph(&graph, surface, &frame, &options.rules))
}

/// Finds the up direction of the figure voxelized in `solid` with medial `surface` (see the
/// module docs); `paths` samples the heart.
pub fn find_up(
    solid: &Solid,
    surface: &MedialSurface,
    paths: &PathOptions,
    options: &LabelOptions,
) -> UpChoice {
    let tree = LevelTree::new(surface, Some(solid), paths, &options.level);
    find_up_in(&tree, solid, surface, options)
}

/// [`find_up`] with the level graph's frame-independent part already built (`tree`, over
/// `surface` and `solid` with `options.level`), as the labelling shares it with the frames it
/// labels in.
pub(super) fn find_up_in(
    tree: &LevelTree,
    solid: &Solid,
    surface: &MedialSurface,
    options: &LabelOptions,
) -> UpChoice {
    let mut scores = Vec::new();
    for &(up, name) in &CANDIDATES {
        let Some(draft) = draft_under(tree, solid, surface, options, up) else {
            continue;
        };
        let s = score(&draft, up, name);
        // +Y stands: keep it (a figure standing on paired legs under the glTF convention is
        // upright even when its labels miss a part).
        let keep_first = scores.is_empty() && (s.complete || (s.standing && s.hanging >= STANDING));
        scores.push(s);
        if keep_first {
            return UpChoice {
                up,
                confidence: 1.0,
                note: format!(
                    "up is {name} (found automatically: the figure stands on its legs; give --up to override)"
                ),
                scores,
            };
        }
    }
    let mut order: Vec<usize> = (0..scores.len()).collect();
    order.sort_by(|&a, &b| {
        (scores[b].complete, scores[b].score)
            .partial_cmp(&(scores[a].complete, scores[a].score))
            .unwrap_or(std::cmp::Ordering::Equal)
            .then(a.cmp(&b))
    });
    // A figure that stands either way up (legs sprawling from a flat body, a spider) has no
    // up to find.
    let flips = |best: &UpScore| {
        scores
            .iter()
            .any(|s| s.complete && s.up.dot(best.up) < -0.5)
    };
    // Leaving the glTF convention needs legs that hang at least as plumb under the new up as
    // the labelled legs do under +Y (less PLUMB_MARGIN): an insect whose one labelled leg hangs
    // straight down under +Y is upright, not a humanoid lying on its side whose "legs" are
    // wings slanting 40 degrees from vertical.
    let plumb_under_y = scores
        .first()
        .filter(|s| s.up == DVec3::Y)
        .map_or(f64::NEG_INFINITY, |s| s.hanging);
    match order.first().map(|&b| &scores[b]) {
        Some(best) if best.complete && !flips(best) && best.hanging + PLUMB_MARGIN >= plumb_under_y => {
            let runner = order.get(1).map(|&r| &scores[r]);
            let confidence = match runner {
                Some(r) if r.complete => (1.0 - r.score / best.score).clamp(0.0, 1.0),
                _ => 1.0,
            };
            let note = format!(
                "up is {} (found automatically with confidence {:.2}: the labels make a whole figure standing on its legs{}; give --up to override)",
                best.name,
                confidence,
                runner
                    .map(|r| format!(", next best {} scores {:.1} vs {:.1}", r.name, r.score, best.score))
                    .unwrap_or_default()
            );
            UpChoice {
                up: best.up,
                confidence,
                note,
                scores,
            }
        }
        _ => UpChoice {
            up: DVec3::Y,
            confidence: 0.0,
            note: "the up direction could not be found from the figure (no axis, or both ends of one, makes its labels a whole figure standing on its legs): kept +Y, the glTF convention; give --up (and --forward) if the figure is not Y-up".to_string(),
            scores,
        },
    }
}

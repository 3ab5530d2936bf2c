//! The core joint error of an upright figure (issue 21): the mean error over the joints every
//! humanoid rig has and every animation drives (pelvis, neck, head, shoulders, elbows, wrists,
//! hips, knees, ankles), with the core joints the reference maps but the prediction lacks
//! listed, so a dropped limb shows instead of leaving the mean.

use super::{Evaluation, FigureMeasure, MatchMethod};
use crate::skeleton::Canonical;
use crate::skeleton::Side::{Left, Right};
use serde::{Deserialize, Serialize};

/// The core joints, canonical keys (the joints `refine::REFINED` places on humanoids).
pub const CORE_KEYS: [&str; 15] = [
    Canonical::Pelvis.as_str(),
    Canonical::Neck.as_str(),
    Canonical::Head.as_str(),
    Canonical::Shoulder(Left).as_str(),
    Canonical::Shoulder(Right).as_str(),
    Canonical::Elbow(Left).as_str(),
    Canonical::Elbow(Right).as_str(),
    Canonical::Wrist(Left).as_str(),
    Canonical::Wrist(Right).as_str(),
    Canonical::Hip(Left).as_str(),
    Canonical::Hip(Right).as_str(),
    Canonical::Knee(Left).as_str(),
    Canonical::Knee(Right).as_str(),
    Canonical::Ankle(Left).as_str(),
    Canonical::Ankle(Right).as_str(),
];

/// The core joint error of one evaluation ([`core_error`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CoreError {
    /// Core keys the reference maps (deforming joints), in [`CORE_KEYS`] order.
    pub mapped: Vec<String>,
    /// Of those, the keys paired with a predicted joint.
    pub paired: usize,
    /// Mean error over the paired core joints, mesh units (0 when none paired).
    pub mean: f64,
    /// The same as a percentage of the figure's height.
    pub mean_percent: f64,
    /// Largest error over the paired core joints, % of height.
    pub max_percent: f64,
    /// The paired core key with the largest error (empty when none paired).
    pub worst: String,
    /// Core keys the reference maps but the prediction lacks, in [`CORE_KEYS`] order. Their
    /// error is unknown, so they are not in the mean: report them beside it.
    pub missing: Vec<String>,
}

/// The core joint error of `evaluation`, for upright figures: `None` unless joints were paired
/// by canonical keys, the figure size is its height ([`FigureMeasure::Height`]: the
/// reference's head is above its pelvis) and the reference maps at least one core joint.
///
/// A core joint counts as mapped when the reference's deforming joints name it (the
/// evaluation's paired keys and its `unmatched` keys); mapped but unpaired means the
/// prediction lacks it (`missing`).
pub fn core_error(evaluation: &Evaluation) -> Option<CoreError> {
    if evaluation.method != MatchMethod::Canonical
        || evaluation.figure.measure != FigureMeasure::Height
    {
        return None;
    }
    let mut mapped = Vec::new();
    let mut missing = Vec::new();
    let mut paired = Vec::new();
    for key in CORE_KEYS {
        if let Some(j) = evaluation.joints.iter().find(|j| j.key == key) {
            mapped.push(key.to_owned());
            paired.push(j);
        } else if evaluation.unmatched.iter().any(|k| k == key) {
            mapped.push(key.to_owned());
            missing.push(key.to_owned());
        }
    }
    if mapped.is_empty() {
        return None;
    }
    let n = paired.len().max(1) as f64;
    let worst = paired.iter().max_by(|a, b| a.error.total_cmp(&b.error));
    Some(CoreError {
        paired: paired.len(),
        mean: paired.iter().map(|j| j.error).sum::<f64>() / n,
        mean_percent: paired.iter().map(|j| j.error_percent).sum::<f64>() / n,
        max_percent: worst.map_or(0.0, |j| j.error_percent),
        worst: worst.map(|j| j.key.clone()).unwrap_or_default(),
        mapped,
        missing,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::{evaluate, EvalOptions, ReferenceRig};
    use crate::skeleton::JointId;

    /// An upright stick figure: pelvis at 1, neck 1.5, head 1.7, arms and legs; every joint
    /// named by its canonical key.
    fn figure(keys: &[(&str, Option<usize>, [f64; 3])]) -> ReferenceRig {
        let skeleton = crate::skeleton::test_skeleton(keys);
        let mut rig = ReferenceRig::from_skeleton("figure", skeleton);
        rig.canonical = keys
            .iter()
            .enumerate()
            .map(|(i, &(name, _, _))| (name.to_owned(), JointId(i)))
            .collect();
        rig
    }

    const BODY: [(&str, Option<usize>, [f64; 3]); 8] = [
        (Canonical::Pelvis.as_str(), None, [0.0, 1.0, 0.0]),
        (Canonical::Chest.as_str(), Some(0), [0.0, 1.3, 0.0]),
        (Canonical::Neck.as_str(), Some(1), [0.0, 1.5, 0.0]),
        (Canonical::Head.as_str(), Some(2), [0.0, 1.7, 0.0]),
        (
            Canonical::Shoulder(Left).as_str(),
            Some(1),
            [0.2, 1.45, 0.0],
        ),
        (Canonical::Elbow(Left).as_str(), Some(4), [0.45, 1.45, 0.0]),
        (Canonical::Hip(Left).as_str(), Some(0), [0.1, 0.95, 0.0]),
        (Canonical::Knee(Left).as_str(), Some(6), [0.1, 0.5, 0.0]),
    ];

    #[test]
    fn core_error_averages_paired_core_joints_and_lists_missing_ones() {
        let reference = figure(&BODY);
        // The prediction: head 0.02 off, elbow 0.04 off, chest (not core) 0.5 off, knee absent.
        let mut joints = BODY[..7].to_vec();
        joints[3].2[2] += 0.02;
        joints[5].2[1] -= 0.04;
        joints[1].2[2] += 0.5;
        let predicted = figure(&joints);
        let e = evaluate(&predicted, &reference, None, &EvalOptions::default()).unwrap();
        let core = core_error(&e).expect("upright, canonical");
        assert_eq!(
            core.mapped,
            [
                Canonical::Pelvis.as_str(),
                Canonical::Neck.as_str(),
                Canonical::Head.as_str(),
                Canonical::Shoulder(Left).as_str(),
                Canonical::Elbow(Left).as_str(),
                Canonical::Hip(Left).as_str(),
                Canonical::Knee(Left).as_str()
            ]
        );
        assert_eq!(core.paired, 6);
        assert_eq!(core.missing, [Canonical::Knee(Left).as_str()]);
        assert!((core.mean - 0.06 / 6.0).abs() < 1e-12, "{}", core.mean);
        assert!((core.mean_percent - 100.0 * core.mean / e.figure.size).abs() < 1e-9);
        assert_eq!(core.worst, Canonical::Elbow(Left).as_str());
    }

    #[test]
    fn core_error_needs_an_upright_canonically_paired_figure() {
        // Lying down: the head is beside the pelvis, so the size is the longest side.
        let lying: Vec<_> = BODY
            .iter()
            .map(|&(k, p, [x, y, _])| (k, p, [x, 0.1 * y, y]))
            .collect();
        let rig = figure(&lying);
        let e = evaluate(&rig, &rig, None, &EvalOptions::default()).unwrap();
        assert_eq!(e.figure.measure, FigureMeasure::LongestSide);
        assert_eq!(core_error(&e), None);
        // Measured by height but no core key mapped (only the chest).
        let chest = figure(
            &BODY[1..2]
                .iter()
                .map(|&(k, _, p)| (k, None, p))
                .collect::<Vec<_>>(),
        );
        let height = EvalOptions {
            measure: FigureMeasure::Height,
            ..EvalOptions::default()
        };
        let e = evaluate(&chest, &chest, None, &height).unwrap();
        assert_eq!(e.figure.measure, FigureMeasure::Height);
        assert_eq!(core_error(&e), None);
    }
}

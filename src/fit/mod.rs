//! Anatomical control skeleton from a template (dissertation ch.8, 8.1-8.2) fitted to measured
//! geometry.
//!
//! The fit takes geometry, not labels: a [`FitInput`] holds the centralised head-to-tail path
//! with its distance-map radii, each limb's path from the body's centre line outwards with its
//! attach point (the midpoint of the pair's limb-to-limb path), separated digits, a jaw
//! branch and ears ([`ears`]: a mirrored pair of rising head protrusions found in the voxels).
//! Labelling (ch.7) produces it; tests build it from polylines.
//!
//! ```text
//! FitInput ─▶ limb pairs ordered head→tail, matched to template limb groups
//!          ─▶ sections head / neck / trunk / tail (8.1, from the pairs' midpoints)
//!          ─▶ axial: dorsal trunk offset, S-shaped neck, smoothing, head segment,
//!             vertebrae ≈ 1/3 head, root at the hindmost pair
//!          ─▶ limbs: girdle sphere, human/animal placement, Table 8.1, digits, wings
//!          ─▶ joints in template order, frames (z distal, y dorsal/normal, x lateral/hinge),
//!             DOFs and limits, canonical map, naming preset
//! ```
//!
//! Missing parts never panic: a missing limb leaves its joints out with a [`FitWarning`].

mod assemble;
mod axial;
mod ears;
mod error;
mod frames;
mod from_labels;
mod input;
mod input_warning;
mod limbs;
mod options;
mod polyline;
mod probe;
mod reach;
mod thin_end;

pub use ears::{ears, EarOptions};
pub use error::{FitError, FitWarning};
pub use from_labels::{fit_input, FitInputOptions};
pub use input::{
    voxel_path, AxialPath, AxialSections, DigitInput, DorsalProbe, EarInput, FitInput, LimbInput,
    Side,
};
pub use input_warning::FitInputWarning;
pub use options::{BendSnap, FitOptions};
pub use reach::ReachOptions;

use crate::skeleton::canonical::{CanonicalJoints, Finger};
use crate::skeleton::{Canonical, JointId, Skeleton};
use crate::template::{apply_preset, Girdle, LimbKind, Preset, Template};
use assemble::assemble;
use axial::Bounds;
use glam::DVec3;
use limbs::{GirdleSphere, LimbFit};
pub(crate) use polyline::Polyline;
use std::collections::BTreeMap;

/// The figure's orthonormal body directions.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BodyFrame {
    pub up: DVec3,
    pub forward: DVec3,
    /// The figure's left: `up × forward`.
    pub left: DVec3,
    /// The back: −forward for upright figures, up for horizontal ones.
    pub dorsal: DVec3,
}

/// A fitted anatomical skeleton.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// Joints named by the chosen preset, parents first, frames and DOFs set.
    pub skeleton: Skeleton,
    /// Canonical anatomical key (`pelvis`, `shoulder_L`, `tail_base`...) → joint.
    pub canonical: BTreeMap<String, JointId>,
    /// What could not be built as the template asks.
    pub warnings: Vec<FitWarning>,
    /// Name of the template used.
    pub template: String,
}

impl Fit {
    /// Canonical key → joint name (for the JSON skeleton's `canonical` map).
    pub fn canonical_names(&self) -> BTreeMap<String, String> {
        self.canonical
            .iter()
            .map(|(k, id)| (k.clone(), self.skeleton.joint(*id).name.clone()))
            .collect()
    }

    /// Turns every frame's z onto its bone at the joints' final positions
    /// (`frames::realign_frames`): the rig's last step before naming, after the refinement,
    /// the symmetry and the digits have moved joints that kept the fit's frames. A wrist aims at
    /// its middle digit's base where the digits were found.
    pub fn realign_frames(&mut self) {
        let wrist_middle: Vec<(JointId, JointId)> = [Side::Left, Side::Right]
            .into_iter()
            .filter_map(|side| {
                let wrist = self.canonical.joint_of(Canonical::Wrist(side))?;
                let middle = self
                    .canonical
                    .joint_of(Canonical::Digit(side, Finger::Middle, 1))?;
                Some((wrist, middle))
            })
            .collect();
        frames::realign_frames(&mut self.skeleton, &wrist_middle);
    }

    /// Turns the skeleton into `preset`'s engine skeleton ([`apply_preset`]: the engine's
    /// joints, names and parents, its spine joints spread along the fitted spine, joints the
    /// engine lacks left out) and remaps the canonical map: the fit's last step, which the rig
    /// repeats after the refinement has moved the canonical keys of a fit made with anatomical
    /// names. `up` is the figure's up (an engine root goes on the ground below the pelvis),
    /// `forward` its facing (with `up`, the body axes of the engine's rest frames).
    /// Canonical joints the engine has no joint for are left out with a
    /// [`FitWarning::NotInPreset`] in [`Fit::warnings`].
    ///
    /// # Errors
    /// [`FitError::Preset`] when the preset file cannot be read.
    pub fn name_joints(
        &mut self,
        preset: Preset,
        up: DVec3,
        forward: DVec3,
    ) -> Result<(), FitError> {
        let dropped = apply_preset(&mut self.skeleton, &mut self.canonical, preset, up, forward)
            .map_err(|e| FitError::Preset(e.to_string()))?;
        if !dropped.is_empty() {
            self.warnings.push(FitWarning::NotInPreset {
                preset: preset.file_stem().into(),
                keys: dropped,
            });
        }
        Ok(())
    }
}

/// Fits `template` to `input` without a dorsal ray probe (the S-shaped neck uses the
/// distance-map radii). See [`fit_with_probe`].
///
/// # Errors
/// As [`fit_with_probe`].
pub fn fit(input: &FitInput, template: &Template, options: &FitOptions) -> Result<Fit, FitError> {
    fit_with_probe(input, template, options, None)
}

/// Fits `template` to `input` (dissertation 8.1-8.2). `probe`, when given, measures dorsal ray
/// depths for the S-shaped cervical replacement of animal-like figures.
///
/// Output positions are in the input's units and frame; joint names follow
/// [`FitOptions::preset`]; [`Fit::canonical`] maps canonical keys to joints.
///
/// # Errors
/// [`FitError`] for malformed input: fewer than two axial points, radii not matching their
/// paths, non-finite values, zero or parallel up/forward, bad section indices, options out of
/// range. Missing body parts are warnings, not errors.
pub fn fit_with_probe(
    input: &FitInput,
    template: &Template,
    options: &FitOptions,
    probe: Option<&dyn DorsalProbe>,
) -> Result<Fit, FitError> {
    options.validate()?;
    check(input)?;
    let frame = body_frame(input, template)?;
    let mut warnings = Vec::new();
    let original = Polyline::new(input.axial.points.clone());
    let radii = &input.axial.radii;

    // Limb pairs, ordered head → tail, matched to template groups.
    let pairs = pairs(input, template, options, &original, &mut warnings);

    // Sections (8.1).
    let bounds = section_bounds(input, template, options, &original, &pairs, &mut warnings);
    let root_t = pairs
        .iter()
        .map(|p| p.t)
        .reduce(f64::max)
        .unwrap_or(bounds.trunk);
    let pectoral_t = pairs
        .iter()
        .filter(|p| template.limbs[p.group].girdle == crate::template::Girdle::Pectoral)
        .map(|p| p.t)
        .reduce(f64::min);
    let axial = axial::axial(
        &original,
        radii,
        bounds,
        root_t,
        pectoral_t,
        template,
        options,
        &frame,
        probe,
        input.axial.tail,
        &mut warnings,
    );

    // Limbs (8.2).
    let centre_distance = |p: DVec3| original.at(original.project(p)).distance(p);
    let mut fitted: Vec<(usize, LimbFit)> = Vec::new();
    for pair in &pairs {
        let group = &template.limbs[pair.group];
        let sphere = GirdleSphere {
            centre: original.at(pair.t),
            radius: original.value_at(radii, pair.t),
            spine: axial.spine_at(pair.t),
            anterior: -original.tangent(pair.t),
        };
        for side in [Side::Left, Side::Right] {
            match pair.limbs.iter().find(|l| l.side == side) {
                Some(l) if l.path.len() >= 2 => fitted.push((
                    pair.group,
                    limbs::limb(
                        l,
                        group,
                        template,
                        &sphere,
                        &frame,
                        options,
                        &centre_distance,
                        probe,
                        &mut warnings,
                    ),
                )),
                _ => warnings.push(FitWarning::MissingLimb {
                    group: group.name.clone(),
                    side: Some(side),
                }),
            }
        }
    }
    for (g, group) in template.limbs.iter().enumerate() {
        if !group.optional && !pairs.iter().any(|p| p.group == g) {
            warnings.push(FitWarning::MissingLimb {
                group: group.name.clone(),
                side: None,
            });
        }
    }
    if input.jaw.is_some() && template.placed("jaw").is_none() {
        warnings.push(FitWarning::JawNotInTemplate);
    }

    let (skeleton, canonical) = assemble(template, &axial, input, &fitted, &frame, &mut warnings);
    let mut fit = Fit {
        skeleton,
        canonical,
        warnings,
        template: template.name.clone(),
    };
    fit.name_joints(options.preset, frame.up, frame.forward)?;
    Ok(fit)
}

/// The head, neck and trunk ends along the axial path (8.1): the input's sections when given,
/// else from the limb pairs (the neck ends at the front pair's girdle, the trunk at the hind
/// pair's) and the head at the narrowing or the template's fraction of the neck.
fn section_bounds(
    input: &FitInput,
    template: &Template,
    options: &FitOptions,
    original: &Polyline,
    pairs: &[Pair<'_>],
    warnings: &mut Vec<FitWarning>,
) -> Bounds {
    let radii = &input.axial.radii;
    let length = original.length();
    match input.axial.sections {
        Some(s) => Bounds {
            head: original.cum[s.head_end],
            neck: original.cum[s.neck_end],
            trunk: original.cum[s.trunk_end],
        },
        None => {
            let front = pairs
                .iter()
                .filter(|p| template.limbs[p.group].girdle == Girdle::Pectoral)
                .map(|p| p.t)
                .reduce(f64::min)
                .map(|t| {
                    let r = original.value_at(radii, t);
                    (t - options.neck_at_girdle_edge * r).max(0.0)
                });
            let hind = pairs.iter().map(|p| p.t).reduce(f64::max);
            let (neck, trunk) = match (front, hind) {
                (Some(f), Some(h)) if h > f => (f, h),
                (Some(f), _) => (f, length),
                (None, Some(h)) => {
                    warnings.push(FitWarning::NoFrontPair);
                    (options.fallback_trunk_start * h, h)
                }
                (None, None) => {
                    warnings.push(FitWarning::NoLimbs);
                    (options.fallback_trunk_start * length, length)
                }
            };
            let head = match options.head_at_narrowing {
                Some([lo, hi]) => narrowest(original, radii, lo * neck, hi * neck)
                    .unwrap_or(template.sections.head * neck),
                None => template.sections.head * neck,
            };
            Bounds { head, neck, trunk }
        }
    }
}

/// Arc length in `[lo, hi]` where the path's radius (moving average over a few points) is
/// smallest: the narrowing between the head and the neck. `None` for an empty range.
fn narrowest(path: &Polyline, radii: &[f64], lo: f64, hi: f64) -> Option<f64> {
    const HALF: usize = 2;
    let n = radii.len();
    (0..n)
        .filter(|&i| path.cum[i] >= lo && path.cum[i] <= hi)
        .map(|i| {
            let (a, b) = (i.saturating_sub(HALF), (i + HALF).min(n - 1));
            let mean = radii[a..=b].iter().sum::<f64>() / (b - a + 1) as f64;
            (mean, i)
        })
        .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
        .map(|(_, i)| path.cum[i])
}

fn finite(points: &[DVec3]) -> bool {
    points.iter().all(|p| p.is_finite())
}

fn check(input: &FitInput) -> Result<(), FitError> {
    let a = &input.axial;
    if a.points.len() < 2 {
        return Err(FitError::ShortAxialPath {
            points: a.points.len(),
        });
    }
    let radii_ok = |r: &[f64]| r.iter().all(|x| x.is_finite() && *x >= 0.0);
    if a.radii.len() != a.points.len() {
        return Err(FitError::RadiiMismatch {
            what: "the head-to-tail path".into(),
            points: a.points.len(),
            radii: a.radii.len(),
        });
    }
    if !finite(&a.points) || !radii_ok(&a.radii) {
        return Err(FitError::NonFinite {
            what: "the head-to-tail path".into(),
        });
    }
    if let Some(s) = a.sections {
        if !(s.head_end <= s.neck_end && s.neck_end <= s.trunk_end && s.trunk_end < a.points.len())
        {
            return Err(FitError::BadSections {
                head_end: s.head_end,
                neck_end: s.neck_end,
                trunk_end: s.trunk_end,
                points: a.points.len(),
            });
        }
    }
    for l in &input.limbs {
        let what = format!(
            "the {} {} (pair {})",
            l.side.as_str(),
            l.kind.as_str(),
            l.pair
        );
        if l.radii.len() != l.path.len() {
            return Err(FitError::RadiiMismatch {
                what,
                points: l.path.len(),
                radii: l.radii.len(),
            });
        }
        if !finite(&l.path)
            || !radii_ok(&l.radii)
            || !l.attach.is_finite()
            || l.digits.iter().any(|d| !finite(&d.path))
        {
            return Err(FitError::NonFinite { what });
        }
    }
    if input.ears.iter().any(|e| !finite(&e.path)) {
        return Err(FitError::NonFinite {
            what: "an ear path".into(),
        });
    }
    if input.jaw.as_ref().is_some_and(|j| !finite(j)) {
        return Err(FitError::NonFinite {
            what: "the jaw path".into(),
        });
    }
    Ok(())
}

fn body_frame(input: &FitInput, template: &Template) -> Result<BodyFrame, FitError> {
    let bad = || FitError::BadOrientation {
        up: input.up.to_array(),
        forward: input.forward.to_array(),
    };
    let up = input.up.try_normalize().ok_or_else(bad)?;
    let forward = (input.forward - up * input.forward.dot(up))
        .try_normalize()
        .ok_or_else(bad)?;
    let left = up.cross(forward);
    let dorsal = match template.posture {
        crate::template::Posture::Upright => -forward,
        crate::template::Posture::Horizontal => up,
    };
    Ok(BodyFrame {
        up,
        forward,
        left,
        dorsal,
    })
}

/// A limb pair matched to a template group.
struct Pair<'a> {
    group: usize,
    /// Arc length on the original path nearest the pair's attach midpoint.
    t: f64,
    limbs: Vec<&'a LimbInput>,
}

fn pairs<'a>(
    input: &'a FitInput,
    template: &Template,
    options: &FitOptions,
    original: &Polyline,
    warnings: &mut Vec<FitWarning>,
) -> Vec<Pair<'a>> {
    // Group by (kind, pair); keep the first limb per side.
    let mut groups: BTreeMap<(LimbKind, usize), Vec<&LimbInput>> = BTreeMap::new();
    for l in &input.limbs {
        let entry = groups.entry((l.kind, l.pair)).or_default();
        if !entry.iter().any(|x| x.side == l.side) {
            entry.push(l);
        }
    }
    let mut found: Vec<(LimbKind, usize, f64, Vec<&LimbInput>)> = groups
        .into_iter()
        .map(|((kind, pair), limbs)| {
            // The pair sits where its limbs leave the trunk (their roots, when labelling gave
            // them and the options use them), else at its limb-to-limb midpoint (8.1).
            let at = |l: &&LimbInput| match l.root.filter(|_| options.root_from_labels) {
                Some(r) => r,
                None => l.attach,
            };
            let mid = limbs.iter().map(at).sum::<DVec3>() / limbs.len() as f64;
            (kind, pair, original.project(mid), limbs)
        })
        .collect();
    found.sort_by(|a, b| a.2.total_cmp(&b.2).then(a.0.cmp(&b.0)).then(a.1.cmp(&b.1)));
    // 8.2: with two or more leg pairs the foremost is a fore (pectoral) pair and the others
    // hind (pelvic) pairs; a single leg pair stays pelvic.
    let legs = |k: LimbKind| matches!(k, LimbKind::Leg | LimbKind::ForeLeg | LimbKind::HindLeg);
    let leg_pairs = found.iter().filter(|f| legs(f.0)).count();
    if leg_pairs >= 2 && !found.iter().any(|f| f.0 == LimbKind::ForeLeg) {
        let mut first = true;
        for f in found.iter_mut().filter(|f| legs(f.0)) {
            if f.0 == LimbKind::Leg {
                f.0 = if first {
                    LimbKind::ForeLeg
                } else {
                    LimbKind::HindLeg
                };
            }
            first = false;
        }
    }
    // Exact kinds first (head → tail), then any free group with the kind's natural girdle.
    let mut used = vec![false; template.limbs.len()];
    let mut assigned: Vec<Option<usize>> = vec![None; found.len()];
    for (i, (kind, ..)) in found.iter().enumerate() {
        if let Some(g) =
            (0..template.limbs.len()).find(|&g| !used[g] && template.limbs[g].kinds.contains(kind))
        {
            used[g] = true;
            assigned[i] = Some(g);
        }
    }
    for (i, (kind, ..)) in found.iter().enumerate() {
        if assigned[i].is_some() {
            continue;
        }
        if let Some(g) = (0..template.limbs.len())
            .find(|&g| !used[g] && template.limbs[g].girdle == kind.natural_girdle())
        {
            used[g] = true;
            assigned[i] = Some(g);
            warnings.push(FitWarning::KindMismatch {
                kind: kind.as_str().into(),
                group: template.limbs[g].name.clone(),
            });
        }
    }
    found
        .into_iter()
        .zip(assigned)
        .filter_map(|((kind, pair, t, limbs), g)| match g {
            Some(group) => Some(Pair { group, t, limbs }),
            None => {
                warnings.push(FitWarning::UnusedLimb {
                    kind: kind.as_str().into(),
                    pair,
                });
                None
            }
        })
        .collect()
}

/// Chooses the canonical `spine` and `chest` joints: among the joints strictly between the
/// canonical `pelvis` and `neck` on the skeleton's chain, the one nearest `axial.spine_at`,
/// and another nearest `axial.chest_at`, of the chain's length from the pelvis (spine below
/// chest; ties to the lower joint). Called by the fit, and again after the refinement has
/// moved the trunk joints onto the spine curve, so the keys follow the joints' final places.
/// Removes both keys when the chain has no joint between pelvis and neck, one when it has one
/// (`chest` then goes).
pub fn assign_trunk_keys(
    skeleton: &Skeleton,
    canonical: &mut BTreeMap<String, JointId>,
    axial: &crate::template::AxialRules,
) {
    canonical.remove(Canonical::Spine.as_str());
    canonical.remove(Canonical::Chest.as_str());
    let (Some(&pelvis), Some(&neck)) = (
        canonical.get(Canonical::Pelvis.as_str()),
        canonical.get(Canonical::Neck.as_str()),
    ) else {
        return;
    };
    // The chain pelvis -> ... -> neck, pelvis first.
    let mut chain = vec![neck];
    let mut k = skeleton.joint(neck).parent;
    while let Some(p) = k {
        chain.push(p);
        if p == pelvis || chain.len() > skeleton.joints.len() {
            break;
        }
        k = skeleton.joint(p).parent;
    }
    if chain.last() != Some(&pelvis) {
        return;
    }
    chain.reverse();
    let mut along = vec![0.0];
    for w in chain.windows(2) {
        let step = skeleton
            .joint(w[0])
            .position
            .distance(skeleton.joint(w[1]).position);
        along.push(along.last().copied().unwrap_or(0.0) + step);
    }
    let total = along.last().copied().unwrap_or(0.0);
    let inner = 1..chain.len() - 1;
    let fraction = |k: usize| if total > 0.0 { along[k] / total } else { 0.0 };
    let nearest = |at: f64, skip: Option<usize>| {
        inner.clone().filter(|&k| Some(k) != skip).min_by(|&a, &b| {
            (fraction(a) - at)
                .abs()
                .total_cmp(&(fraction(b) - at).abs())
                .then(a.cmp(&b))
        })
    };
    let spine = nearest(axial.spine_at, None);
    let chest = nearest(axial.chest_at, spine);
    // With two joints left the nearer to each fraction wins; keep spine below chest.
    let (spine, chest) = match (spine, chest) {
        (Some(s), Some(c)) if s > c => (Some(c), Some(s)),
        other => other,
    };
    if let Some(s) = spine {
        canonical.insert(Canonical::Spine.to_string(), chain[s]);
    }
    if let Some(c) = chest {
        canonical.insert(Canonical::Chest.to_string(), chain[c]);
    }
}

#[allow(clippy::too_many_arguments)]
fn resolve_parent(
    template: &Template,
    name: &str,
    side: Option<Side>,
    position: DVec3,
    ids: &BTreeMap<(String, Option<Side>), Vec<JointId>>,
    skeleton: &Skeleton,
    girdle: bool,
    repeated: &dyn Fn(&str) -> bool,
) -> Option<JointId> {
    let mut current = template.joint(name)?.parent.clone();
    while let Some(parent) = current {
        let pj = template.joint(&parent)?;
        let pside = if pj.side { side } else { None };
        if let Some(list) = ids.get(&(parent.clone(), pside)).filter(|l| !l.is_empty()) {
            if girdle && repeated(&parent) {
                return list.iter().copied().min_by(|a, b| {
                    skeleton
                        .joint(*a)
                        .position
                        .distance(position)
                        .total_cmp(&skeleton.joint(*b).position.distance(position))
                        .then(a.cmp(b))
                });
            }
            return list.last().copied();
        }
        current = pj.parent.clone();
    }
    // The root always exists; anything else hangs from it.
    (!skeleton.is_empty()).then_some(JointId(0))
}

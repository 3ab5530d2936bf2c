//! The digit stage's entry: each hand looked at again, its digits named and jointed.

use super::contour::{digit_branches, Branch};
use super::place::{digit_frame, place_digit, DigitJoints};
use super::surface::{hand_surface, HandSurface};
use super::{DigitOptions, DigitWarning};
use crate::bones::windings;
use crate::fit::Fit;
use crate::mesh::Mesh;
use crate::skeleton::canonical::{CanonicalJoints, Finger};
use crate::skeleton::{Canonical, Dof, Joint, JointId, Side, Skeleton};
use crate::template::{LimbGroup, Posture, Template};
use glam::DVec3;

/// Replaces each hand's finger chain in `fit` by the digits its surface shows (module docs):
/// `thumb_01_L`..`pinky_03_R` joints with their canonical keys and a `_end` joint at each tip,
/// hung from the wrist. A mitten keeps one finger chain, moved onto the mitten (plus a thumb
/// when it separates). Does nothing when the fit has no wrists, the template's wrist limb
/// names no digits or the template is not upright (an animal's feet are
/// [`super::paws::fit_paws`]'s); `options.enabled: false` switches it off.
///
/// Returns a warning per hand that is not a five-digit hand. Never fails: a hand it cannot read
/// keeps the fit's chain.
pub fn fit_hands(
    mesh: &Mesh,
    template: &Template,
    fit: &mut Fit,
    options: &DigitOptions,
) -> Vec<DigitWarning> {
    let readings = read_hands(mesh, template, fit, options);
    place_hands(mesh, template, fit, options, readings)
}

/// What one hand's surface shows: the digits (thumb first, or a mitten's), the palm normal and
/// how many digit branches were found; or why the hand keeps the fit's chain.
type HandOutcome = Result<(Vec<(Option<Finger>, DigitJoints)>, DVec3, usize), DigitWarning>;

/// One hand read before any hand is rebuilt: the wrist and elbow positions it was read from
/// and what it showed.
pub(super) struct HandReading {
    side: Side,
    from: (DVec3, Option<DVec3>),
    outcome: HandOutcome,
}

/// The hands of [`fit_hands`] read from the fit as it stands, both at once (on two threads):
/// reading a hand only looks at the mesh and at its arm's wrist and elbow. Empty when the
/// stage does not apply (see [`fit_hands`]).
pub(super) fn read_hands(
    mesh: &Mesh,
    template: &Template,
    fit: &Fit,
    options: &DigitOptions,
) -> Vec<HandReading> {
    if template.posture != Posture::Upright || !options.enabled || hand_group(template).is_none() {
        return Vec::new();
    }
    let read = |side: Side| {
        let wrist = fit.canonical.joint_of(Canonical::Wrist(side))?;
        let from = arm_end(fit, wrist, side);
        Some(HandReading {
            side,
            from,
            outcome: read_hand(mesh, from, side, options),
        })
    };
    let (left, right) = rayon::join(|| read(Side::Left), || read(Side::Right));
    left.into_iter().chain(right).collect()
}

/// Rebuilds each hand of [`fit_hands`] from its reading, left then right; a hand whose wrist or
/// elbow stands elsewhere than where it was read (not the case when the readings come from
/// [`read_hands`] on this fit: rebuilding a hand moves no other joint) is read again here.
/// Returns a warning per hand that is not a five-digit hand.
pub(super) fn place_hands(
    mesh: &Mesh,
    template: &Template,
    fit: &mut Fit,
    options: &DigitOptions,
    readings: Vec<HandReading>,
) -> Vec<DigitWarning> {
    let mut warnings = Vec::new();
    if template.posture != Posture::Upright {
        return warnings; // an animal's feet: `fit_paws`
    }
    let Some(group) = hand_group(template) else {
        return warnings;
    };
    if !options.enabled {
        return warnings;
    }
    let mut readings = readings.into_iter().peekable();
    for side in Side::BOTH {
        let Some(wrist) = fit.canonical.joint_of(Canonical::Wrist(side)) else {
            continue;
        };
        let from = arm_end(fit, wrist, side);
        let outcome = match readings.next_if(|r| r.side == side) {
            Some(r) if r.from == from => r.outcome,
            _ => read_hand(mesh, from, side, options),
        };
        if let Some(w) = place_hand(fit, group, wrist, side, outcome) {
            warnings.push(w);
        }
    }
    warnings
}

/// The template's limb group whose chain holds the wrist and names five digits.
fn hand_group(template: &Template) -> Option<&LimbGroup> {
    let wrist = template
        .joints
        .iter()
        .find(|j| j.canonical.as_deref() == Some(Canonical::Wrist(Side::Left).stem()))?;
    template
        .limbs
        .iter()
        .find(|g| g.chain.contains(&wrist.name) && g.digits.len() >= Finger::ALL.len())
}

/// The positions of the `wrist` of `side` and of its elbow (when the fit has one).
fn arm_end(fit: &Fit, wrist: JointId, side: Side) -> (DVec3, Option<DVec3>) {
    let w = fit.skeleton.joint(wrist).position;
    let elbow = fit
        .canonical
        .joint_of(Canonical::Elbow(side))
        .map(|e| fit.skeleton.joint(e).position);
    (w, elbow)
}

/// One hand read from its wrist `w` and `elbow`: its digits, palm normal and branch count, or
/// the warning when no hand or only fused fingers are found.
fn read_hand(
    mesh: &Mesh,
    (w, elbow): (DVec3, Option<DVec3>),
    side: Side,
    options: &DigitOptions,
) -> HandOutcome {
    let Some((forearm, axis)) = elbow.and_then(|e| {
        let d = w - e;
        let len = d.length();
        (len > 0.0).then(|| (len, d / len))
    }) else {
        return Err(DigitWarning::NoHand { side });
    };
    let Some(surface) = hand_surface(
        mesh,
        w,
        axis,
        options.reach * forearm,
        options.wrist_band * forearm,
    ) else {
        return Err(DigitWarning::NoHand { side });
    };
    let step = options.level_step * forearm;
    let mut branches = separated_digits(mesh, &surface, step, 0.0, options);
    // A shallow web (ring and little finger) parts between two levels or not, with a sub-voxel
    // shift of the wrist: fewer than five digits are read again on levels half a step shifted,
    // and the reading with more digits, at most five, is kept.
    if branches.len() < Finger::ALL.len() {
        let shifted = separated_digits(mesh, &surface, step, 0.5, options);
        if shifted.len() > branches.len() && shifted.len() <= Finger::ALL.len() {
            branches = shifted;
        }
    }
    // Thumb first: the deepest web, at equal webs the thinner digit.
    branches.sort_by(|a, b| {
        (a.split_level, base_perimeter(a))
            .partial_cmp(&(b.split_level, base_perimeter(b)))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    // A digit whose joints, extrapolated behind its web, leave the figure is not a digit of
    // this hand (a held prop's grip or blade within reach of the wrist): it is left out and
    // the hand read again without it.
    let (found, digits) = loop {
        let found = branches.len();
        if found < 2 {
            return Err(DigitWarning::FingersFused { side, thumb: false });
        }
        let digits = hand_digits(&branches, w, axis, options);
        let points: Vec<DVec3> = digits
            .iter()
            .flat_map(|(_, d)| d.joints.joints.into_iter().chain([d.joints.tip]))
            .collect();
        let inside = windings(mesh, &points);
        let outside = (0..digits.len()).find(|&i| (0..4).any(|k| inside[4 * i + k] == 0));
        match outside {
            None => break (found, digits),
            Some(i) => {
                branches.remove(digits[i].1.branch);
            }
        }
    };
    let digits: Vec<(Option<Finger>, DigitJoints)> =
        digits.into_iter().map(|(f, d)| (f, d.joints)).collect();
    let palm = palm_normal(w, &digits, axis);
    Ok((digits, palm, found))
}

/// One hand rebuilt from what was read; the warning when it is not a five-digit hand.
fn place_hand(
    fit: &mut Fit,
    group: &LimbGroup,
    wrist: JointId,
    side: Side,
    outcome: HandOutcome,
) -> Option<DigitWarning> {
    let (digits, palm, found) = match outcome {
        Ok(read) => read,
        Err(warning) => return Some(warning),
    };
    replace_hand(fit, group, wrist, side, &digits, palm, true);
    match found {
        2 => Some(DigitWarning::FingersFused { side, thumb: true }),
        5 => None,
        _ => Some(DigitWarning::DigitCount { side, found }),
    }
}

/// A digit placed from one of the branches it was chosen among.
struct Placed {
    /// Index of its branch in the candidates.
    branch: usize,
    joints: DigitJoints,
}

/// The digits of a hand from its candidate `branches` (thumb first): the thumb, then at most
/// the four longest other branches in order of their bases from the thumb's; two branches are
/// a thumb and a mitten. `Placed::branch` indexes `branches`.
fn hand_digits(
    branches: &[Branch],
    w: DVec3,
    axis: DVec3,
    options: &DigitOptions,
) -> Vec<(Option<Finger>, Placed)> {
    let thumb = &branches[0];
    let thumb_base = thumb.base();
    // Six or more: the four longest fingers; then in order of their bases from the thumb's.
    let mut others: Vec<usize> = (1..branches.len()).collect();
    others.sort_by(|&a, &b| {
        branches[b]
            .free_length()
            .total_cmp(&branches[a].free_length())
    });
    others.truncate(Finger::ALL.len() - 1);
    others.sort_by(|&a, &b| {
        let da = branches[a].base().distance(thumb_base);
        let db = branches[b].base().distance(thumb_base);
        da.total_cmp(&db)
    });
    let mut digits = vec![(
        Some(Finger::Thumb),
        Placed {
            branch: 0,
            joints: place_digit(
                thumb,
                options.free_share[0],
                options.thumb_from_tip,
                Some(w),
                axis,
            ),
        },
    )];
    let mitten = branches.len() == 2;
    for (k, &b) in others.iter().enumerate() {
        let (finger, share) = if mitten {
            (None, options.free_share[2])
        } else {
            (Some(Finger::ALL[k + 1]), options.free_share[k + 1])
        };
        digits.push((
            finger,
            Placed {
                branch: b,
                joints: place_digit(&branches[b], share, options.finger_from_tip, None, axis),
            },
        ));
    }
    digits
}

/// The contour length at a branch's web end.
fn base_perimeter(b: &Branch) -> f64 {
    b.perimeters.last().copied().unwrap_or(0.0)
}

/// Mean diameter of a branch's contours (each contour's length over π).
fn mean_width(b: &Branch) -> f64 {
    b.perimeters.iter().sum::<f64>() / (b.perimeters.len().max(1) as f64 * std::f64::consts::PI)
}

/// The digits of a hand's or foot's `surface`: the contour tree's leaf branches (levels
/// `step` apart, shifted by `phase` of a step: [`digit_branches`]) that stand out at least as long as they are wide (a shorter one is a bump of
/// the palm or of another body part's surface in reach) and whose contour centres all lie
/// inside the figure (a coarse or open surface can give branches whose centres do not).
pub(super) fn separated_digits(
    mesh: &Mesh,
    surface: &HandSurface,
    step: f64,
    phase: f64,
    options: &DigitOptions,
) -> Vec<Branch> {
    let mut branches = digit_branches(surface, step, phase, options.min_levels);
    branches.retain(|b| b.free_length() >= mean_width(b));
    let centres: Vec<DVec3> = branches
        .iter()
        .flat_map(|b| b.path.iter().copied())
        .collect();
    let inside: Vec<bool> = windings(mesh, &centres).iter().map(|&w| w != 0).collect();
    let mut first = 0;
    branches.retain(|b| {
        let all = inside[first..first + b.path.len()].iter().all(|&i| i);
        first += b.path.len();
        all
    });
    branches
}

/// The palm's normal on its inner side: normal to the hand's direction and the line across
/// the digit bases, turned to the side the thumb's tip lies on (a relaxed thumb sits in front
/// of the palm).
fn palm_normal(wrist: DVec3, digits: &[(Option<Finger>, DigitJoints)], axis: DVec3) -> DVec3 {
    let thumb = digits[0].1;
    let fingers: Vec<&DigitJoints> = digits[1..].iter().map(|d| &d.1).collect();
    let centre = fingers.iter().map(|d| d.joints[0]).sum::<DVec3>() / fingers.len() as f64;
    let hand = (centre - wrist).try_normalize().unwrap_or(axis);
    let across = match (fingers.first(), fingers.last()) {
        (Some(a), Some(b)) if fingers.len() > 1 => b.joints[0] - a.joints[0],
        _ => centre - thumb.joints[1],
    };
    let normal = hand
        .cross(across)
        .try_normalize()
        .unwrap_or_else(|| hand.any_orthonormal_vector());
    if (thumb.tip - centre).dot(normal) < 0.0 {
        -normal
    } else {
        normal
    }
}

/// Removes the descendants of `wrist` (the template's hand and finger chain; or a foot's
/// metapodial joint and its digit chain) and hangs the digits from it; with `canonical`,
/// canonical keys for named digits (a hand's or fore foot's: the keys name hand digits).
pub(super) fn replace_hand(
    fit: &mut Fit,
    group: &LimbGroup,
    wrist: JointId,
    side: Side,
    digits: &[(Option<Finger>, DigitJoints)],
    palm: DVec3,
    canonical: bool,
) {
    remove_descendants(fit, wrist);
    for (finger, d) in digits {
        let stem = match finger {
            Some(f) => group
                .digits
                .get(*f as usize)
                .cloned()
                .unwrap_or_else(|| f.as_str().to_string()),
            None => "finger".to_string(),
        };
        let points = [d.joints[0], d.joints[1], d.joints[2], d.tip];
        let mut parent = Some(wrist);
        for (k, &p) in points.iter().enumerate() {
            let end = k == 3;
            let name = if end {
                format!("{stem}_end{}", side.suffix())
            } else {
                format!("{stem}_{:02}{}", k + 1, side.suffix())
            };
            let mut joint = Joint::new(name, parent, p);
            joint.deform = !end;
            let to = if end {
                p + (p - points[2])
            } else {
                points[k + 1]
            };
            let from = if end { points[2] } else { p };
            joint.frame = digit_frame(from, to, palm);
            joint.dofs = digit_dofs(group, *finger, k);
            fit.skeleton.joints.push(joint);
            let id = JointId(fit.skeleton.joints.len() - 1);
            if let (Some(f), false, true) = (finger, end, canonical) {
                fit.canonical.insert(
                    Canonical::Digit(side, *f, k as u8 + 1).as_str().to_string(),
                    id,
                );
            }
            parent = Some(id);
        }
    }
}

/// The template's DOFs of a digit joint (`k`: 0 base .. 3 end).
fn digit_dofs(group: &LimbGroup, finger: Option<Finger>, k: usize) -> Vec<Dof> {
    match (k, finger) {
        (3, _) => Vec::new(),
        (0, Some(Finger::Thumb)) => group.first_digit_base_dofs.clone(),
        (0, _) => group.digit_base_dofs.clone(),
        _ => group.phalanx_dofs.clone(),
    }
}

/// Drops every joint below `root`, keeping ids of the rest consistent (parents and the
/// canonical map renumbered; keys of dropped joints removed).
fn remove_descendants(fit: &mut Fit, root: JointId) {
    let joints = &fit.skeleton.joints;
    let mut dropped = vec![false; joints.len()];
    for (i, j) in joints.iter().enumerate() {
        // Parents come first, so a parent's mark is final.
        dropped[i] = j.parent.is_some_and(|p| p == root || dropped[p.0]);
    }
    let mut new_id = vec![None; joints.len()];
    let mut kept = Vec::new();
    for (i, j) in joints.iter().enumerate() {
        if !dropped[i] {
            new_id[i] = Some(JointId(kept.len()));
            let mut j = j.clone();
            j.parent = j.parent.and_then(|p| new_id[p.0]);
            kept.push(j);
        }
    }
    fit.skeleton = Skeleton { joints: kept };
    fit.canonical = std::mem::take(&mut fit.canonical)
        .into_iter()
        .filter_map(|(k, id)| Some((k, new_id[id.0]?)))
        .collect();
}

//! The feet of a horizontal figure (quadrupeds, a winged figure's legs): hooves and paws get
//! the digits their surface shows (issue 25, item 5).
//!
//! Each fore and hind foot is read as a hand is (the surface beyond the wrist or ankle, its
//! contour tree; [`super::hands::separated_digits`]). An animal's foot has no thumb that
//! parts first and opposes the rest: its digits are ordered across the foot from the median
//! plane outwards and numbered by the mammalian reduction pattern (the first digit goes first,
//! then the fifth, then the second), so two digits are the third and fourth (a cloven hoof),
//! three the second to fourth, four the second to fifth (a dog's paw without its dewclaw),
//! five all of them. They hang from the metapodial joint (`hand`, `foot`: the start of the
//! cannon bone or the sole) in place of the template's single digit chain, which a foot with
//! fewer than two separate digits (a horse's hoof, a low-poly paw) keeps, without a warning:
//! that is the foot it is. A digit holds three phalanges: a branch standing free for less
//! than half the length the template's ratios give them (a dewclaw high behind a hoof, a toe
//! notched into a paw's rim) does not count, and a paw whose toes are all such notches bends
//! as one: it gets a single digit from the root to the middle of the notches' tips.

use super::hands::{replace_hand, separated_digits};
use super::place::{place_digit, DigitJoints};
use super::surface::hand_surface;
use super::{DigitOptions, DigitWarning};
use crate::fit::{Fit, Polyline};
use crate::mesh::Mesh;
use crate::skeleton::canonical::{CanonicalJoints, Finger};
use crate::skeleton::{Canonical, JointId, Side};
use crate::template::{LimbGroup, Template};
use glam::DVec3;

/// The digit numbers (0-based: 0 the first digit) of a foot showing `n` separate digits,
/// by the mammalian reduction pattern; `None` for none or more than five.
pub(super) fn reduced_digits(n: usize) -> Option<&'static [usize]> {
    match n {
        1 => Some(&[2]),
        2 => Some(&[2, 3]),
        3 => Some(&[1, 2, 3]),
        4 => Some(&[1, 2, 3, 4]),
        5 => Some(&[0, 1, 2, 3, 4]),
        _ => None,
    }
}

/// Gives each foot of a horizontal figure the digits its surface shows (module docs). `up` is
/// the figure's up; the forward direction is taken from the pelvis to the head. The fore feet
/// only with `options.enabled` (`--fingers`), the hind feet with `options.feet` (`--toes`).
/// Returns a warning per foot showing more than five digits (the five longest are kept).
pub fn fit_paws(
    mesh: &Mesh,
    template: &Template,
    fit: &mut Fit,
    up: DVec3,
    options: &DigitOptions,
) -> Vec<DigitWarning> {
    let mut warnings = Vec::new();
    let (Some(pelvis), Some(head)) = (
        fit.canonical.joint_of(Canonical::Pelvis),
        fit.canonical.joint_of(Canonical::Head),
    ) else {
        return warnings;
    };
    let (pelvis, head) = (
        fit.skeleton.joint(pelvis).position,
        fit.skeleton.joint(head).position,
    );
    let Some(up) = up.try_normalize() else {
        return warnings;
    };
    let Some(forward) = (head - pelvis).reject_from_normalized(up).try_normalize() else {
        return warnings;
    };
    let body = Body {
        up,
        forward,
        left: up.cross(forward),
        centre: pelvis,
    };
    let feet = [
        (
            Canonical::Elbow as fn(Side) -> Canonical,
            Canonical::Wrist as fn(Side) -> Canonical,
            true,
        ),
        (Canonical::Knee, Canonical::Ankle, false),
    ];
    for (proximal, root, fore) in feet {
        // `--fingers` switches the fore feet, `--toes` the hind feet.
        if !(if fore { options.enabled } else { options.feet }) {
            continue;
        }
        for side in Side::BOTH {
            let (Some(p), Some(r)) = (
                fit.canonical.joint_of(proximal(side)),
                fit.canonical.joint_of(root(side)),
            ) else {
                continue;
            };
            let Some(group) = limb_of(template, fit, r, side) else {
                continue;
            };
            let foot = Foot {
                joints: (p, r),
                side,
                fore,
            };
            if let Some(w) = fit_paw(mesh, template, group, fit, &foot, &body, options) {
                warnings.push(w);
            }
        }
    }
    warnings
}

/// The figure's axes and a point on its median plane.
struct Body {
    up: DVec3,
    forward: DVec3,
    left: DVec3,
    centre: DVec3,
}

/// The template's limb group whose chain holds the fitted joint `root` of `side` (the digit
/// stage runs before the preset's names: joints carry the template's names) and names digits.
fn limb_of<'t>(
    template: &'t Template,
    fit: &Fit,
    root: JointId,
    side: Side,
) -> Option<&'t LimbGroup> {
    let name = &fit.skeleton.joint(root).name;
    let stem = name.strip_suffix(side.suffix())?;
    template
        .limbs
        .iter()
        .find(|g| !g.digits.is_empty() && g.chain.iter().any(|c| c == stem))
}

/// One foot of the figure.
struct Foot {
    /// The joint above the foot's root (elbow, knee) and the root (wrist, ankle).
    joints: (JointId, JointId),
    side: Side,
    /// A fore foot (else a hind one).
    fore: bool,
}

/// The length the template's ratios give a digit's three phalanges on a limb whose shank (the
/// segment ending at the foot's `root`, elbow to wrist or knee to ankle) is `shank` long:
/// `shank` times the phalanges' ratios over the shank's. `None` when the chain or its ratios
/// do not say.
fn phalanges_length(
    template: &Template,
    group: &LimbGroup,
    fit: &Fit,
    root: JointId,
    side: Side,
    shank: f64,
) -> Option<f64> {
    let ratios = template.ratios.get(&group.ratios)?;
    let name = &fit.skeleton.joint(root).name;
    let stem = name.strip_suffix(side.suffix())?;
    let at = group.chain.iter().position(|c| c == stem)?;
    let shank_ratio = *ratios.get(at.checked_sub(1)?)?;
    let phalanges: f64 = ratios.get(group.digit_row + 1..)?.iter().sum();
    (shank_ratio > 0.0 && phalanges > 0.0).then(|| shank * phalanges / shank_ratio)
}

/// One digit chain of a paw from its `root` (wrist, ankle) to the mean of its toes' `tips`,
/// cut by the template's `digit` ratios (metapodial, proximal, middle, distal: 8.2) along the
/// foot's centre line: from the root down the `stem` (the contour centres from the lowest
/// level up to where the toes part, those before the first one beyond the wrist plane through
/// the root normal to `axis` left out) and on to the tips' mean. A plantigrade foot turns at
/// the heel, and its digit follows the sole rather than cutting through the air from the
/// ankle to the toes. `None` without the ratios or when the tips are at the root.
fn paw_digit(
    template: &Template,
    root: DVec3,
    axis: DVec3,
    stem: &[DVec3],
    tips: &[DVec3],
) -> Option<DigitJoints> {
    let ratios = template.ratios.get("digit").filter(|r| r.len() >= 4)?;
    let total: f64 = ratios.iter().sum();
    let tip = tips.iter().sum::<DVec3>() / tips.len() as f64;
    if total <= 0.0 || tip.distance(root) <= 0.0 {
        return None;
    }
    let beyond = stem
        .iter()
        .position(|&p| (p - root).dot(axis) > 0.0)
        .unwrap_or(stem.len());
    let line = Polyline::new(
        std::iter::once(root)
            .chain(stem[beyond..].iter().copied())
            .chain(std::iter::once(tip))
            .collect(),
    );
    let at = |k: usize| line.at(line.length() * ratios[..k].iter().sum::<f64>() / total);
    Some(DigitJoints {
        joints: [at(1), at(2), at(3)],
        tip,
    })
}

/// One foot: leaves the fit's chain when fewer than two digits separate.
fn fit_paw(
    mesh: &Mesh,
    template: &Template,
    group: &LimbGroup,
    fit: &mut Fit,
    foot: &Foot,
    body: &Body,
    options: &DigitOptions,
) -> Option<DigitWarning> {
    let Foot { joints, side, fore } = *foot;
    let (p, r) = (
        fit.skeleton.joint(joints.0).position,
        fit.skeleton.joint(joints.1).position,
    );
    let length = p.distance(r);
    let axis = (r - p).try_normalize()?;
    let surface = hand_surface(
        mesh,
        r,
        axis,
        options.reach * length,
        options.wrist_band * length,
    )?;
    let mut branches = separated_digits(mesh, &surface, options.level_step * length, 0.0, options);
    // A foot's digits reach down to the ground the figure stands on: a branch whose tip is
    // higher than the root is another part within reach (a tail, the rump behind a hind foot).
    branches.retain(|b| b.path[0].dot(body.up) < r.dot(body.up));
    // A digit holds its three phalanges: a branch standing free for less than
    // `min_paw_digit` of the length the template's ratios give them (from the shank's length)
    // is a scallop of the hoof's or paw's rim, not a toe that bends on its own.
    let scallops = branches.clone();
    if let Some(phalanges) = phalanges_length(template, group, fit, joints.1, side, length) {
        branches.retain(|b| b.free_length() >= options.min_paw_digit * phalanges);
    }
    if branches.is_empty() && scallops.len() >= 2 {
        // Toes all scalloped: a paw that bends as one, one digit (the third, as a single
        // digit is numbered) from the root along the sole to the middle of the toes' tips;
        // the fit's chain follows the labelled foot, which need not reach the toes. The
        // centre line up to the lowest split, where the toes start to part.
        let tips: Vec<DVec3> = scallops.iter().map(|b| b.path[0]).collect();
        let first = scallops.iter().min_by_key(|b| b.split_level)?;
        let stem: Vec<DVec3> = first.stem.iter().rev().copied().collect();
        let digit = paw_digit(template, r, axis, &stem, &tips)?;
        let sole = -(body.up + body.forward);
        let middle = [(Some(Finger::Middle), digit)];
        replace_hand(fit, group, joints.1, side, &middle, sole, fore);
        return None;
    }
    let found = branches.len();
    let warning =
        (found > Finger::ALL.len()).then_some(DigitWarning::FootDigitCount { side, fore, found });
    branches.sort_by(|a, b| b.free_length().total_cmp(&a.free_length()));
    branches.truncate(Finger::ALL.len());
    let numbers = reduced_digits(branches.len()).filter(|n| n.len() >= 2)?;
    // Across the foot from the median plane outwards.
    let lateral =
        |b: &super::contour::Branch| (b.base() - body.centre).dot(body.left) * side.sign();
    branches.sort_by(|a, b| lateral(a).total_cmp(&lateral(b)));
    let digits: Vec<(Option<Finger>, DigitJoints)> = branches
        .iter()
        .zip(numbers)
        .map(|(b, &n)| {
            let joints = place_digit(
                b,
                options.free_share[n],
                options.finger_from_tip,
                None,
                axis,
            );
            (Some(Finger::ALL[n]), joints)
        })
        .collect();
    let attach = metapodial(fit, group, joints.1, side, axis, &digits);
    // The sole (or the back of a hoof) faces down and backwards: digits curl that way.
    let sole = -(body.up + body.forward);
    replace_hand(fit, group, attach, side, &digits, sole, fore);
    warning
}

/// The joint the digits hang from: the limb chain's metapodial joint (the template's joint at
/// `digit_row`, `hand` or `foot`) when it lies on the root's distal side and behind every
/// digit's base along `axis`; else the root itself.
fn metapodial(
    fit: &Fit,
    group: &LimbGroup,
    root: JointId,
    side: Side,
    axis: DVec3,
    digits: &[(Option<Finger>, DigitJoints)],
) -> JointId {
    let Some(stem) = group.chain.get(group.digit_row) else {
        return root;
    };
    let name = format!("{stem}{}", side.suffix());
    let root_at = fit.skeleton.joint(root).position;
    let found = fit.skeleton.children(root).into_iter().find(|&c| {
        let j = fit.skeleton.joint(c);
        let along = (j.position - root_at).dot(axis);
        j.name == name
            && along >= 0.0
            && digits
                .iter()
                .all(|(_, d)| (d.joints[0] - root_at).dot(axis) > along)
    });
    found.unwrap_or(root)
}

#[cfg(test)]
mod tests {
    use super::{paw_digit, reduced_digits, Polyline};
    use crate::template::Template;
    use glam::DVec3;

    #[test]
    fn a_paw_digit_runs_from_the_root_to_the_toes_middle_by_the_digit_ratios() {
        let template = Template::builtin("quadruped").unwrap();
        let root = DVec3::new(0.0, 1.0, 0.0);
        let tips = [DVec3::new(-0.1, 0.0, 1.0), DVec3::new(0.1, 0.0, 1.0)];
        let down = DVec3::NEG_Y;
        let d = paw_digit(&template, root, down, &[], &tips).unwrap();
        let tip = DVec3::new(0.0, 0.0, 1.0);
        assert!(d.tip.distance(tip) < 1e-12);
        // digit = [36, 25, 15, 10]: metapodial, proximal, middle, distal.
        for (joint, share) in d.joints.iter().zip([36.0, 61.0, 76.0]) {
            let expected = root.lerp(tip, share / 86.0);
            assert!(joint.distance(expected) < 1e-12, "{joint:?} {expected:?}");
        }
        assert!(paw_digit(&template, root, down, &[], &[root, root]).is_none());
    }

    #[test]
    fn a_plantigrade_paw_digit_follows_the_sole_round_the_heel() {
        // An ankle one unit above the heel, the sole one unit forward along the ground: the
        // centre line goes down then forward (a contour behind the wrist plane is skipped).
        let template = Template::builtin("quadruped").unwrap();
        let root = DVec3::new(0.0, 1.0, 0.0);
        let stem = [
            DVec3::new(0.0, 1.1, 0.0),
            DVec3::new(0.0, 0.5, 0.0),
            DVec3::new(0.0, 0.05, 0.0),
            DVec3::new(0.0, 0.05, 0.5),
        ];
        let tips = [DVec3::new(-0.1, 0.0, 1.0), DVec3::new(0.1, 0.0, 1.0)];
        let d = paw_digit(&template, root, DVec3::NEG_Y, &stem, &tips).unwrap();
        // Line: root -> (0, .5, 0) -> (0, .05, 0) -> (0, .05, .5) -> (0, 0, 1); every joint
        // on it, none on the chord from the ankle to the toes.
        let line = Polyline::new(vec![
            root,
            stem[1],
            stem[2],
            stem[3],
            DVec3::new(0.0, 0.0, 1.0),
        ]);
        for (joint, share) in d.joints.iter().zip([36.0, 61.0, 76.0]) {
            let expected = line.at(line.length() * share / 86.0);
            assert!(joint.distance(expected) < 1e-12, "{joint:?} {expected:?}");
            assert!(
                joint.y <= 0.05 + 1e-12 || joint.z.abs() < 1e-12,
                "{joint:?} off the sole"
            );
        }
        // The base joint is near the heel, not halfway along the chord.
        assert!(
            d.joints[0].distance(DVec3::new(0.0, 0.05, 0.0)) < 0.3,
            "{:?}",
            d.joints[0]
        );
    }

    #[test]
    fn reduction_keeps_the_middle_digits_longest() {
        assert_eq!(reduced_digits(0), None);
        assert_eq!(reduced_digits(1), Some(&[2][..]));
        // A cloven hoof: the third and fourth digits (artiodactyls).
        assert_eq!(reduced_digits(2), Some(&[2, 3][..]));
        // A dog's paw without its dewclaw: the second to fifth.
        assert_eq!(reduced_digits(4), Some(&[1, 2, 3, 4][..]));
        assert_eq!(reduced_digits(5), Some(&[0, 1, 2, 3, 4][..]));
        assert_eq!(reduced_digits(6), None);
    }
}

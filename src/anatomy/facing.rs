//! Which way the figure faces (`Forward::Auto`), from a first labelling.
//!
//! A file has a convention (glTF: the asset's front faces +Z; a Z-up file turned as Blender
//! turns it: -Y), and most figures follow it; some face -Z or ±X. The first labelling runs
//! facing the convention (the *prior*); its labels then say which way the figure faces:
//!
//! * **Axis** — a figure is bilaterally symmetric: its paired limbs (arms, legs, wings) lie
//!   either side of the median plane, so the left-right axis runs between the two limbs of a
//!   pair (their attachments and distal ends, summed over the pairs), and forward is across it.
//!   An animal-like figure's head-tail line gives the axis directly.
//! * **Sign** — a human-like figure faces where its feet point: a foot is longer along forward
//!   than the shin above it is deep, and reaches further in front of the shin than behind it
//!   (toes against heel). A leg that ends in a point or a block (a peg leg, a robot's post, a
//!   foot the labels did not reach) gives no sign. An animal-like figure faces from its tail
//!   (or the trunk's centre) to its head.
//! * **Prior** — what the figure cannot tell keeps the convention: without a sign the forward
//!   nearest the prior's is kept; a direction within [`SNAP_DEG`] of one of the file's axes is
//!   that axis (figures are modelled square to the axes; the labels' asymmetry, a head turned or
//!   a tail swung aside, must not tilt the frame).

use super::{FigureClass, Label, Labelling, Side};
use crate::mesh::Mesh;
use glam::DVec3;
use serde::Serialize;

/// Angle (degrees) within which a found forward is taken to be the nearest file axis.
pub const SNAP_DEG: f64 = 30.0;

/// A foot is a foot when its length along forward is at least this multiple of the shin's depth
/// along forward (a human foot is about twice the shin's depth; a peg leg's end is less than one).
const FOOT_LENGTH: f64 = 1.5;

/// The toes must reach in front of the shin's centre by at least this fraction of the foot's
/// length more than the heel reaches behind it (a human foot: about 0.6).
const TOE_REACH: f64 = 0.25;

/// How forward was found (`Forward::Auto`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ForwardChoice {
    /// The direction (unit, across up).
    pub forward: DVec3,
    /// The file's convention the search started from (glTF: +Z, turned with the up found).
    pub prior: DVec3,
    /// Confidence in [0, 1]: how clearly the figure's own shape gave the direction; 0 when the
    /// convention was kept for want of evidence.
    pub confidence: f64,
    /// A sentence for the user.
    pub note: String,
}

/// Which way the figure of `first` (labelled facing `prior`) faces.
pub fn find_forward(first: &Labelling, mesh: &Mesh, prior: DVec3) -> ForwardChoice {
    let up = first.frame.up;
    let flat = |v: DVec3| v - up * v.dot(up);
    let prior = flat(prior).try_normalize().unwrap_or(first.frame.forward);
    let kept = |note: &str| ForwardChoice {
        forward: prior,
        prior,
        confidence: 0.0,
        note: format!("kept the file's convention: {note}"),
    };
    match first.figure {
        FigureClass::HumanLike => {
            let Some(lateral) = lateral_axis(first, up) else {
                return kept("no paired limbs show the figure's left-right axis");
            };
            let axis = snap(up.cross(lateral).normalize(), up);
            match foot_sign(first, mesh, axis) {
                Some((sign, strength)) => ForwardChoice {
                    forward: axis * sign,
                    prior,
                    confidence: strength,
                    note: "the figure faces where its feet point".to_string(),
                },
                None => {
                    let sign = if axis.dot(prior) < 0.0 { -1.0 } else { 1.0 };
                    let forward = axis * sign;
                    if forward.dot(prior) > 0.9 {
                        return kept("the feet do not show which way the figure faces");
                    }
                    ForwardChoice {
                        forward,
                        prior,
                        confidence: 0.0,
                        note: "across the paired limbs, on the side of the file's convention (the feet do not show which way the figure faces)".to_string(),
                    }
                }
            }
        }
        FigureClass::AnimalLike => {
            let head = first.part(Label::Head, None).map(|p| p.distal);
            let back = first
                .part(Label::Tail, None)
                .map(|p| p.distal)
                .unwrap_or(first.parts[0].attachment);
            match head.and_then(|h| flat(h - back).try_normalize()) {
                Some(f) => ForwardChoice {
                    forward: snap(f, up),
                    prior,
                    confidence: 1.0,
                    note: "from the tail (or the trunk) towards the head".to_string(),
                },
                None => kept("no head to go by"),
            }
        }
        FigureClass::Unknown => kept("the figure is neither upright nor horizontal"),
    }
}

/// The figure's left-right axis across `up` from its paired limbs (the sum of the vectors
/// between the two limbs of every pair, attachments and distal ends), `None` without a pair.
fn lateral_axis(l: &Labelling, up: DVec3) -> Option<DVec3> {
    let flat = |v: DVec3| v - up * v.dot(up);
    let mut sum = DVec3::ZERO;
    for (i, a) in l.parts.iter().enumerate() {
        if a.side != Some(Side::Left) || !matches!(a.label, Label::Arm | Label::Leg | Label::Wing) {
            continue;
        }
        let partner = l.parts.iter().skip(i + 1).chain(&l.parts[..i]).find(|b| {
            b.label == a.label && b.limb_pair == a.limb_pair && b.side == Some(Side::Right)
        });
        let Some(b) = partner else { continue };
        for d in [flat(a.attachment - b.attachment), flat(a.distal - b.distal)] {
            sum += if d.dot(sum) < 0.0 { -d } else { d };
        }
    }
    sum.try_normalize()
}

/// `f` turned onto the nearest axis of the file across `up` when within [`SNAP_DEG`] of it.
fn snap(f: DVec3, up: DVec3) -> DVec3 {
    let cos = SNAP_DEG.to_radians().cos();
    [DVec3::X, DVec3::Y, DVec3::Z]
        .into_iter()
        .flat_map(|a| [a, -a])
        .filter(|a| a.dot(up).abs() < 1e-9)
        .find(|a| a.dot(f) >= cos)
        .unwrap_or(f)
}

/// Which end of `axis` the legs' feet point to, and how clearly (in (0, 1]): `None` when no leg
/// ends in a foot (see [`FOOT_LENGTH`], [`TOE_REACH`]) or the feet disagree.
fn foot_sign(l: &Labelling, mesh: &Mesh, axis: DVec3) -> Option<(f64, f64)> {
    let up = l.frame.up;
    let mut votes = Vec::new();
    for leg in l.find(Label::Leg) {
        let points: Vec<DVec3> = l
            .mesh_parts
            .iter()
            .zip(&mesh.positions)
            .filter(|(&p, _)| p as usize == leg)
            .map(|(_, &x)| x)
            .collect();
        let heights = || points.iter().map(|x| x.dot(up));
        let bottom = heights().fold(f64::INFINITY, f64::min);
        let length = heights().fold(f64::NEG_INFINITY, f64::max) - bottom;
        if points.len() < 8 || length.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            continue;
        }
        let band = |lo: f64, hi: f64| {
            points
                .iter()
                .copied()
                .filter(move |x| (bottom + lo * length..bottom + hi * length).contains(&x.dot(up)))
        };
        // The shin well above the ankle, the foot below it (a foot is about a tenth of the
        // leg's length high).
        let shin: Vec<f64> = band(0.15, 0.3).map(|x| x.dot(axis)).collect();
        let foot: Vec<f64> = band(0.0, 0.07).map(|x| x.dot(axis)).collect();
        if shin.len() < 3 || foot.len() < 3 {
            continue;
        }
        let range = |v: &[f64]| {
            v.iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
                    (lo.min(x), hi.max(x))
                })
        };
        let (s0, s1) = range(&shin);
        let (f0, f1) = range(&foot);
        let centre = 0.5 * (s0 + s1);
        let (depth, foot_length) = (s1 - s0, f1 - f0);
        if foot_length < FOOT_LENGTH * depth || foot_length <= 0.0 {
            continue;
        }
        let reach = ((f1 - centre) - (centre - f0)) / foot_length;
        if reach.abs() >= TOE_REACH {
            votes.push(reach);
        }
    }
    if votes.is_empty() || votes.iter().any(|r| r.signum() != votes[0].signum()) {
        return None;
    }
    let mean = votes.iter().sum::<f64>() / votes.len() as f64;
    Some((mean.signum(), mean.abs().min(1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_direction_near_an_axis_snaps_to_it_and_one_between_axes_does_not() {
        let up = DVec3::Y;
        let near = DVec3::new(0.2, 0.0, -1.0).normalize();
        assert_eq!(snap(near, up), DVec3::NEG_Z);
        let between = DVec3::new(1.0, 0.0, 1.0).normalize();
        assert_eq!(snap(between, up), between);
        // Never onto up itself.
        let z_up = DVec3::Z;
        assert_eq!(
            snap(DVec3::new(0.1, -1.0, 0.0).normalize(), z_up),
            DVec3::NEG_Y
        );
    }
}

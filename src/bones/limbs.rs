//! Limb placement (9.1): humerus/femur, radius + ulna / tibia + fibula (+ patella), carpals /
//! tarsals, metacarpals / metatarsals and phalanges, scaled to segment lengths with widths from
//! distance-map values.

use super::context::Context;
use super::measure::median_radius;
use super::settle::{Draft, Shrink};
use super::shapes::{
    carpals, femur, humerus, metapodial, patella, phalanx, radius_ulna, tarsals, tibia_fibula,
    Block, LongBone,
};
use super::structure::{GirdleKind, Limb};
use super::{BoneKind, BoneWarning};
use crate::mesh::{winding_number, Mesh};
use crate::skeleton::JointId;
use glam::DVec3;

/// Bones of every limb.
pub(crate) fn limbs(ctx: &mut Context) {
    let limbs = ctx.body.limbs.clone();
    for limb in &limbs {
        limb_bones(ctx, limb);
    }
}

fn name(ctx: &Context, kind: BoneKind, joint: JointId) -> String {
    format!("{}_{}", kind.as_str(), ctx.skeleton.joint(joint).name)
}

/// A long bone on segment `from → to`: length from the joints, shaft from the distance map.
fn long(ctx: &Context, from: DVec3, to: DVec3, fraction: f64) -> Option<(LongBone, DVec3)> {
    let z = (to - from).try_normalize()?;
    let o = ctx.options;
    Some((
        LongBone {
            length: from.distance(to),
            radius: (fraction * o.shaft_fraction * median_radius(ctx.map, from, to))
                .min(o.max_shaft_ratio * from.distance(to)),
            epiphysis: o.epiphysis_scale,
            rings: o.rings,
            segments: o.segments,
        },
        z,
    ))
}

/// A metacarpal, metatarsal or phalanx on segment `from → to` (`last`: the digit's last
/// bone). With the figure's surface given and the segment's middle inside it, sized on the
/// surface (digits are thinner than the voxels): the shaft `shaft_fraction` of the smallest
/// distance from the segment's middle (20 % to 80 %) to a surface vertex, the last bone ending
/// that far short of the tip (which lies on the skin). Else [`long`] on the distance map.
/// Returns the bone, its direction and whether it was sized on the surface.
fn digit_long(
    ctx: &Context,
    from: DVec3,
    to: DVec3,
    last: bool,
) -> Option<(LongBone, DVec3, bool)> {
    let inside = |s: &&Mesh| winding_number(s, from.lerp(to, 0.5)) > 0.5;
    let Some(surface) = ctx.surface.filter(inside) else {
        let (bone, z) = long(ctx, from, to, 1.0)?;
        return Some((bone, z, false));
    };
    let z = (to - from).try_normalize()?;
    let depth = (0..5)
        .map(|k| {
            let p = from.lerp(to, 0.2 + 0.15 * k as f64);
            surface
                .positions
                .iter()
                .map(|q| q.distance_squared(p))
                .fold(f64::INFINITY, f64::min)
                .sqrt()
        })
        .fold(f64::INFINITY, f64::min);
    let length = from.distance(to) - if last { depth } else { 0.0 };
    if length <= 0.0 || !depth.is_finite() {
        return None;
    }
    let o = ctx.options;
    let bone = LongBone {
        length,
        radius: (o.shaft_fraction * depth).min(o.max_shaft_ratio * length),
        epiphysis: o.epiphysis_scale,
        rings: o.rings,
        segments: o.segments,
    };
    Some((bone, z, true))
}

fn push_long(
    ctx: &mut Context,
    limb: &Limb,
    kind: BoneKind,
    joint: JointId,
    from: DVec3,
    z: DVec3,
    local: Mesh,
) {
    let draft = long_draft(ctx, limb, kind, joint, from, z, local);
    ctx.keep(draft);
}

/// The draft of a long bone of `limb` from `from` along `z`.
fn long_draft(
    ctx: &Context,
    limb: &Limb,
    kind: BoneKind,
    joint: JointId,
    from: DVec3,
    z: DVec3,
    local: Mesh,
) -> Draft {
    Draft {
        kind,
        name: name(ctx, kind, joint),
        joint,
        local,
        origin: from,
        axes: ctx.limb_axes(z, limb.side),
        shrink: Shrink::CrossSection,
        slide: None,
    }
}

fn limb_bones(ctx: &mut Context, limb: &Limb) {
    let pelvic = limb.girdle == GirdleKind::Pelvic;
    let chain = &limb.chain;
    let label = format!(
        "{} {} limb at {}",
        limb.side.as_str(),
        if pelvic { "pelvic" } else { "pectoral" },
        ctx.skeleton.joint(chain[0]).name
    );
    let segments = chain.len().saturating_sub(1);
    for i in 0..segments {
        let a = if i == 0 {
            limb.origin
        } else {
            ctx.pos(chain[i])
        };
        let (j, b) = (chain[i], ctx.pos(chain[i + 1]));
        let Some((bone, z)) = long(ctx, a, b, 1.0) else {
            ctx.warnings.push(BoneWarning::ZeroLengthLimbSegment {
                limb: label.clone(),
                joint: ctx.skeleton.joint(j).name.clone(),
            });
            continue;
        };
        match (i, pelvic) {
            (0, false) => push_long(ctx, limb, BoneKind::Humerus, j, a, z, humerus(&bone)),
            (0, true) => push_long(ctx, limb, BoneKind::Femur, j, a, z, femur(&bone)),
            (1, false) => push_long(ctx, limb, BoneKind::RadiusUlna, j, a, z, radius_ulna(&bone)),
            (1, true) => {
                push_long(
                    ctx,
                    limb,
                    BoneKind::TibiaFibula,
                    j,
                    a,
                    z,
                    tibia_fibula(&bone),
                );
                knee_cap(ctx, limb, j, a, z, &bone);
            }
            (2, _) => small_bones(ctx, limb, j, a, z, bone.length, pelvic),
            (3, _) => {
                let kind = if pelvic {
                    BoneKind::Metatarsal
                } else {
                    BoneKind::Metacarpal
                };
                if let Some((bone, z, fine)) = digit_long(ctx, a, b, i + 1 == segments) {
                    let draft = long_draft(ctx, limb, kind, j, a, z, metapodial(&bone));
                    ctx.keep_sized(draft, fine);
                }
            }
            _ => {
                let last = i + 1 == segments;
                if let Some((bone, z, fine)) = digit_long(ctx, a, b, last) {
                    let local = phalanx(&bone, last);
                    let draft = long_draft(ctx, limb, BoneKind::Phalanx, j, a, z, local);
                    ctx.keep_sized(draft, fine);
                }
            }
        }
    }
    if limb.digits.is_empty() {
        let missing = match segments {
            0 => Some("any bone"),
            1 => Some("a lower limb, carpals/tarsals or digits"),
            2 => Some("carpals/tarsals or digits"),
            3 | 4 => Some("digits"),
            _ => None,
        };
        if let Some(m) = missing {
            ctx.warnings.push(BoneWarning::ShortLimb {
                limb: label,
                segments,
                missing: m,
            });
        }
        return;
    }
    digit_bones(ctx, limb, pelvic);
}

/// The bones of a limb's separated digits, which hang from the chain's last joint (the
/// wrist/ankle): carpals/tarsals there, then per digit a metacarpal/metatarsal and phalanges.
fn digit_bones(ctx: &mut Context, limb: &Limb, pelvic: bool) {
    let chain = &limb.chain;
    let wrist = *chain.last().unwrap_or(&chain[0]);
    let w = ctx.pos(wrist);
    let firsts: Vec<DVec3> = limb
        .digits
        .iter()
        .filter_map(|d| d.get(1).map(|&j| ctx.pos(j) - w))
        .collect();
    let mean = firsts.iter().copied().sum::<DVec3>() / firsts.len().max(1) as f64;
    let block_length =
        0.3 * firsts.iter().map(|v| v.length()).sum::<f64>() / firsts.len().max(1) as f64;
    if let Some(z) = mean.try_normalize() {
        small_bones(ctx, limb, wrist, w, z, block_length, pelvic);
    }
    for digit in &limb.digits {
        let n = digit.len().saturating_sub(1);
        for k in 0..n {
            let (j, mut a, b) = (digit[k], ctx.pos(digit[k]), ctx.pos(digit[k + 1]));
            if k == 0 {
                // Leave room for the carpals/tarsals.
                if let Some(z) = (b - a).try_normalize() {
                    a += z * block_length.min(0.5 * a.distance(b));
                }
            }
            let Some((bone, z, fine)) = digit_long(ctx, a, b, k + 1 == n) else {
                continue;
            };
            let (kind, local) = match k {
                0 if pelvic => (BoneKind::Metatarsal, metapodial(&bone)),
                0 => (BoneKind::Metacarpal, metapodial(&bone)),
                _ => (BoneKind::Phalanx, phalanx(&bone, k + 1 == n)),
            };
            let draft = long_draft(ctx, limb, kind, j, a, z, local);
            ctx.keep_sized(draft, fine);
        }
    }
}

fn small_bones(
    ctx: &mut Context,
    limb: &Limb,
    joint: JointId,
    from: DVec3,
    z: DVec3,
    length: f64,
    pelvic: bool,
) {
    let r = median_radius(ctx.map, from, from + z * length);
    let block = Block {
        length,
        width: 0.6 * r,
        depth: 0.4 * r,
        rings: ctx.options.rings,
        segments: ctx.options.segments,
    };
    let (kind, local) = if pelvic {
        (BoneKind::Tarsals, tarsals(&block))
    } else {
        (BoneKind::Carpals, carpals(&block))
    };
    let axes = ctx.limb_axes(z, limb.side);
    ctx.keep(Draft {
        kind,
        name: name(ctx, kind, joint),
        joint,
        local,
        origin: from,
        axes,
        shrink: Shrink::About(DVec3::new(0.0, 0.0, 0.5 * length)),
        slide: None,
    });
}

/// Patella in front of the knee, in the shank's frame.
fn knee_cap(ctx: &mut Context, limb: &Limb, knee: JointId, at: DVec3, z: DVec3, shank: &LongBone) {
    let width = 1.2 * shank.radius * shank.epiphysis;
    let axes = ctx.limb_axes(z, limb.side);
    let forward = 1.1 * shank.radius * shank.epiphysis + 0.3 * width;
    ctx.keep(Draft {
        kind: BoneKind::Patella,
        name: name(ctx, BoneKind::Patella, knee),
        joint: knee,
        local: patella(width, ctx.options.rings, ctx.options.segments),
        origin: at + axes[1] * forward - z * 0.4 * width,
        axes,
        shrink: Shrink::About(DVec3::ZERO),
        slide: Some((axes[1], forward)),
    });
}

//! Axial placement (9.1): cranium and mandible scaled to their segments with widths from
//! distance values; one vertebra per vertebral segment, tail vertebrae tapering.

use super::context::Context;
use super::measure::max_radius;
use super::settle::{Draft, Shrink};
use super::shapes::{animal_cranium, human_cranium, mandible, vertebra, Jaw, Skull, Vertebra};
use super::{Articulation, BoneKind, BoneWarning};
use glam::DVec3;

/// Cranium on the head segment, mandible on the jaw segment (or under the cranium, its hinges
/// then added to the articulations).
pub(crate) fn skull(ctx: &mut Context) {
    let (Some(head), Some(end)) = (ctx.body.head, ctx.body.head_end) else {
        ctx.warnings.push(BoneWarning::NoHeadSegment);
        return;
    };
    let (a, b) = (ctx.pos(head), ctx.pos(end));
    let length = a.distance(b);
    let Some(z) = (b - a).try_normalize() else {
        ctx.warnings.push(BoneWarning::ZeroLengthHead);
        return;
    };
    let o = ctx.options;
    let radius = max_radius(ctx.map, a, b, 24);
    let half = o.cranium_fraction * radius;
    let upright = ctx.body.upright;
    let skull = Skull {
        length,
        width: half.min(0.45 * length),
        depth: if upright {
            half.min(0.55 * length)
        } else {
            half.min(0.4 * length)
        },
        rings: o.rings,
        segments: o.segments,
    };
    let axes = ctx.axial_axes(z);
    let (kind, local) = if upright {
        (BoneKind::Cranium, human_cranium(&skull))
    } else {
        (BoneKind::AnimalCranium, animal_cranium(&skull))
    };
    ctx.keep(Draft {
        kind,
        name: "cranium".into(),
        joint: head,
        local,
        origin: a,
        axes,
        shrink: Shrink::About(DVec3::new(0.0, 0.0, 0.5 * length)),
        slide: Some((axes[1], 0.25 * skull.depth)),
    });
    // Mandible: on its own segment, else hinged under the cranium.
    let (joint, hinge, chin, jaw_axes) = match ctx.body.jaw {
        Some((j, e)) => {
            let (h, c) = (ctx.pos(j), ctx.pos(e));
            (j, h, c, None)
        }
        None => {
            let local = |p: DVec3| a + axes[0] * p.x + axes[1] * p.y + axes[2] * p.z;
            let (h, c) = if upright {
                (
                    DVec3::new(0.0, -0.05 * skull.depth, 0.3 * length),
                    DVec3::new(0.0, -0.75 * skull.depth, 0.06 * length),
                )
            } else {
                (
                    DVec3::new(0.0, -0.85 * skull.depth, 0.28 * length),
                    DVec3::new(0.0, -0.8 * skull.depth, 0.92 * length),
                )
            };
            (head, local(h), local(c), Some(axes))
        }
    };
    let Some(jz) = (chin - hinge).try_normalize() else {
        ctx.warnings.push(BoneWarning::ZeroLengthJaw);
        return;
    };
    let jaw_length = hinge.distance(chin);
    let dorsal = jaw_axes.map_or(ctx.dorsal, |ax| ax[1]);
    let jy = super::structure::perpendicular(dorsal, jz).unwrap_or(axes[1]);
    let jaw = Jaw {
        length: jaw_length,
        width: if upright { 0.8 } else { 0.6 } * skull.width,
        height: if upright { 0.3 } else { 0.15 } * jaw_length,
        segments: o.segments,
    };
    if ctx.body.jaw.is_none() {
        for side in [1.0, -1.0] {
            ctx.articulations.push(Articulation {
                centre: hinge + jy.cross(jz) * side * jaw.width + jy * jaw.height,
                radius: 0.35 * jaw.width,
            });
        }
    }
    ctx.keep(Draft {
        kind: BoneKind::Mandible,
        name: "mandible".into(),
        joint,
        local: mandible(&jaw),
        origin: hinge,
        axes: [jy.cross(jz), jy, jz],
        shrink: Shrink::About(DVec3::new(0.0, 0.0, 0.5 * jaw_length)),
        slide: Some((jy, jaw.height)),
    });
}

/// One vertebra per neck and trunk segment (root → … → head), and per tail segment with the
/// width shrinking by [`super::BoneOptions::tail_taper`] each.
pub(crate) fn column(ctx: &mut Context) {
    let mut segments: Vec<(usize, usize)> = Vec::new();
    let spine = ctx.body.spine.clone();
    let mut chain = spine.clone();
    if let Some(h) = ctx.body.head {
        chain.push(h);
    }
    for k in 0..chain.len().saturating_sub(1) {
        segments.push((k, k + 1));
    }
    if segments.is_empty() {
        ctx.warnings.push(BoneWarning::NoVertebralSegments);
    }
    let width = ctx.vertebra_width;
    for (n, (i, j)) in segments.into_iter().enumerate() {
        add_vertebra(
            ctx,
            BoneKind::Vertebra,
            format!("vertebra_{:02}", n + 1),
            chain[i],
            chain[j],
            width,
        );
    }
    let mut tail = vec![ctx.body.root];
    tail.extend(ctx.body.tail.iter().copied());
    let mut w = width;
    for k in 0..tail.len().saturating_sub(1) {
        add_vertebra(
            ctx,
            BoneKind::TailVertebra,
            format!("tail_vertebra_{:02}", k + 1),
            tail[k],
            tail[k + 1],
            w,
        );
        w *= ctx.options.tail_taper;
    }
}

fn add_vertebra(
    ctx: &mut Context,
    kind: BoneKind,
    name: String,
    from: crate::skeleton::JointId,
    to: crate::skeleton::JointId,
    width: f64,
) {
    let (a, b) = (ctx.pos(from), ctx.pos(to));
    let Some(z) = (b - a).try_normalize() else {
        ctx.warnings.push(BoneWarning::ZeroLengthVertebra { name });
        return;
    };
    let local = vertebra(&Vertebra {
        length: a.distance(b),
        width,
        rings: ctx.options.rings,
        segments: ctx.options.segments,
    });
    let axes = ctx.axial_axes(z);
    ctx.keep(Draft {
        kind,
        name,
        joint: from,
        local,
        origin: a,
        axes,
        shrink: Shrink::CrossSection,
        slide: Some((axes[1], width)),
    });
}

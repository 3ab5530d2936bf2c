//! Girdle placement (9.1): a rib cage per group of overlapping pectoral girdle spheres, a
//! scapula per pectoral limb tangent to its rib cage, and the pelvis fixed to the root with
//! its sockets at the hip joints.

use super::context::Context;
use super::measure::median_radius;
use super::settle::{Draft, Shrink};
use super::shapes::{pelvis, rib_cage, scapula, Pelvis, RibCage, Scapula};
use super::structure::{perpendicular, GirdleKind};
use super::{BoneKind, BoneWarning};
use crate::fit::Side;
use crate::skeleton::JointId;
use glam::DVec3;

/// A girdle sphere: the largest distance-map ball ventral of the spine beside a limb's root.
#[derive(Debug, Clone, Copy)]
struct Sphere {
    centre: DVec3,
    radius: f64,
}

/// The vertebral polyline root → head and the nearest point on it to `p`, with the index of
/// the segment holding it.
fn nearest_on_spine(ctx: &Context, p: DVec3) -> Option<(DVec3, usize)> {
    let mut chain: Vec<JointId> = ctx.body.spine.clone();
    if let Some(h) = ctx.body.head {
        chain.push(h);
    }
    let pts: Vec<DVec3> = chain.iter().map(|j| ctx.pos(*j)).collect();
    if pts.len() == 1 {
        return Some((pts[0], 0));
    }
    let mut best: Option<(f64, DVec3, usize)> = None;
    for k in 0..pts.len().saturating_sub(1) {
        let (a, b) = (pts[k], pts[k + 1]);
        let ab = b - a;
        let t = if ab.length_squared() > 0.0 {
            ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = a + ab * t;
        let d = q.distance(p);
        if best.is_none_or(|(bd, ..)| d < bd) {
            best = Some((d, q, k));
        }
    }
    best.map(|(_, q, k)| (q, k))
}

fn girdle_sphere(ctx: &Context, at: DVec3) -> Option<Sphere> {
    let (s, _) = nearest_on_spine(ctx, at)?;
    let h = ctx.map.grid.voxel_size;
    let reach = 2.0 * ctx.map.max_distance() * h;
    let steps = (reach / h).ceil() as usize;
    let mut best = Sphere {
        centre: s,
        radius: ctx.map.radius_at(s),
    };
    for k in 1..=steps {
        let q = s - ctx.dorsal * (k as f64 * h);
        let r = ctx.map.radius_at(q);
        if r > best.radius {
            best = Sphere {
                centre: q,
                radius: r,
            };
        }
    }
    (best.radius > 0.0).then_some(best)
}

/// Groups of overlapping spheres (union-find by index): each group's sphere indices in
/// increasing order, groups ordered by their first index.
fn overlap_groups(spheres: &[Sphere]) -> Vec<Vec<usize>> {
    let mut group: Vec<usize> = (0..spheres.len()).collect();
    fn find(g: &mut [usize], mut i: usize) -> usize {
        while g[i] != i {
            g[i] = g[g[i]];
            i = g[i];
        }
        i
    }
    for a in 0..spheres.len() {
        for b in a + 1..spheres.len() {
            let (sa, sb) = (spheres[a], spheres[b]);
            if sa.centre.distance(sb.centre) < sa.radius + sb.radius {
                let (ra, rb) = (find(&mut group, a), find(&mut group, b));
                group[ra.max(rb)] = ra.min(rb);
            }
        }
    }
    (0..spheres.len())
        .map(|g| {
            (0..spheres.len())
                .filter(|&k| find(&mut group, k) == g)
                .collect::<Vec<usize>>()
        })
        .filter(|members| !members.is_empty())
        .collect()
}

/// Rib cages; returns, per limb of `ctx.body.limbs`, the index in `ctx.bones` of its cage.
pub(crate) fn rib_cages(ctx: &mut Context) -> Vec<Option<usize>> {
    let limbs = ctx.body.limbs.clone();
    let mut cage_of = vec![None; limbs.len()];
    let mut spheres: Vec<(usize, Sphere)> = Vec::new();
    for (i, l) in limbs.iter().enumerate() {
        if l.girdle != GirdleKind::Pectoral {
            continue;
        }
        let root = l.girdle_joint.unwrap_or(l.chain[0]);
        if let Some(s) = girdle_sphere(ctx, ctx.pos(root)) {
            spheres.push((i, s));
        }
    }
    if spheres.is_empty() {
        ctx.warnings.push(BoneWarning::NoPectoralGirdle);
        return cage_of;
    }
    let groups = overlap_groups(&spheres.iter().map(|&(_, s)| s).collect::<Vec<_>>());
    let o = ctx.options;
    let mut cage_count = 0;
    for members in groups {
        let centre =
            members.iter().map(|&k| spheres[k].1.centre).sum::<DVec3>() / members.len() as f64;
        let radius = members
            .iter()
            .map(|&k| spheres[k].1.radius)
            .fold(0.0, f64::max);
        let Some((_, seg)) = nearest_on_spine(ctx, centre) else {
            continue;
        };
        let mut chain: Vec<JointId> = ctx.body.spine.clone();
        if let Some(h) = ctx.body.head {
            chain.push(h);
        }
        let cranial = chain
            .get(seg + 1)
            .and_then(|&b| (ctx.pos(b) - ctx.pos(chain[seg])).try_normalize())
            .unwrap_or(ctx.body.up);
        let axes = ctx.axial_axes(cranial);
        let middle = centre - cranial * (o.ribcage_shift * radius);
        let (spine_point, seg) = nearest_on_spine(ctx, middle).unwrap_or((middle, seg));
        let spine_y = (spine_point - middle).dot(axes[1]);
        let spine_y = if spine_y > 0.1 * radius {
            spine_y
        } else {
            0.5 * radius
        };
        let spread = members
            .iter()
            .map(|&k| (spheres[k].1.centre - centre).dot(cranial).abs())
            .fold(0.0, f64::max);
        let half = o.ribcage_fraction * radius;
        let cage = RibCage {
            half_width: half,
            spine_y,
            sternum_y: half,
            half_height: half + spread,
            vertebra_half_width: 0.5 * ctx.vertebra_width + o.gap * radius,
            rib_radius: o.rib_thickness * radius,
            pairs: o.rib_pairs,
            segments: o.segments,
        };
        let joint = chain[seg.min(chain.len() - 1)];
        cage_count += 1;
        let index = ctx.keep(Draft {
            kind: BoneKind::RibCage,
            name: format!("rib_cage_{cage_count}"),
            joint,
            local: rib_cage(&cage),
            origin: middle,
            axes,
            shrink: Shrink::About(DVec3::ZERO),
            slide: Some((axes[1], 0.3 * radius)),
        });
        for &k in &members {
            cage_of[spheres[k].0] = index;
        }
    }
    cage_of
}

/// A scapula per pectoral limb: from the shoulder towards the girdle joint (or the trunk
/// joint the limb hangs from), half as wide as long, lying on its rib cage.
pub(crate) fn scapulae(ctx: &mut Context, cage_of: &[Option<usize>]) {
    let limbs = ctx.body.limbs.clone();
    let o = ctx.options;
    for (i, l) in limbs.iter().enumerate() {
        if l.girdle != GirdleKind::Pectoral {
            continue;
        }
        let shoulder = ctx.pos(l.chain[0]);
        let anchor = l.girdle_joint.unwrap_or(l.parent);
        let toward = ctx.pos(anchor);
        let Some(u) = (toward - shoulder).try_normalize() else {
            ctx.warnings.push(BoneWarning::NoScapula {
                side: l.side.as_str(),
            });
            continue;
        };
        let length = o.scapula_length * shoulder.distance(toward);
        let width = o.scapula_width * length;
        let middle = shoulder + u * (0.5 * length);
        let cage = cage_of
            .get(i)
            .copied()
            .flatten()
            .map(|k| &ctx.bones[k].mesh);
        // Radial from the cage's long axis (the body's cranial direction), so the blade lies
        // on the cage's side (quadrupeds) or back (upright figures).
        let axis = if ctx.body.upright {
            ctx.body.up
        } else {
            ctx.body.forward
        };
        let normal = cage
            .and_then(|m| {
                let c = m.bounding_box().map(|(a, b)| 0.5 * (a + b))?;
                let d = middle - c;
                perpendicular(d - axis * d.dot(axis), u)
            })
            .or_else(|| perpendicular(ctx.dorsal, u))
            .unwrap_or_else(|| u.any_orthonormal_vector());
        let across = normal.cross(u);
        let thick = 2.6 * 0.035 * length;
        let radius = ctx.map.radius_at(middle);
        let lift = cage.map_or(0.0, |m| {
            m.positions
                .iter()
                .filter(|v| {
                    let d = **v - middle;
                    d.dot(u).abs() < 0.5 * length && d.dot(across).abs() < 0.5 * width
                })
                .map(|v| (*v - middle).dot(normal))
                .fold(f64::NEG_INFINITY, f64::max)
        });
        let lift = if lift.is_finite() {
            (lift + o.gap * radius + thick).max(0.0)
        } else {
            0.0
        };
        let joint = anchor;
        let name = format!(
            "{}_{}",
            BoneKind::Scapula.as_str(),
            ctx.skeleton.joint(l.chain[0]).name
        );
        ctx.keep(Draft {
            kind: BoneKind::Scapula,
            name,
            joint,
            local: scapula(&Scapula {
                length,
                width,
                rings: o.rings,
                segments: o.segments,
            }),
            origin: shoulder + normal * lift,
            axes: [across, normal, u],
            shrink: Shrink::About(DVec3::new(0.0, 0.0, 0.5 * length)),
            slide: Some((u, 0.2 * length)),
        });
    }
}

/// The pelvis at the root, its sockets at the hip joints (one side mirrored when a leg is
/// missing).
pub(crate) fn pelvic_girdle(ctx: &mut Context) {
    let hips: Vec<(Side, JointId, Option<JointId>, DVec3)> = ctx
        .body
        .limbs
        .iter()
        .filter(|l| l.girdle == GirdleKind::Pelvic)
        .map(|l| (l.side, l.chain[0], l.chain.get(1).copied(), l.origin))
        .collect();
    let root = ctx.pos(ctx.body.root);
    let left = ctx.body.left;
    let mirror = |p: DVec3| p - left * (2.0 * (p - root).dot(left));
    let find = |s: Side| hips.iter().find(|h| h.0 == s).copied();
    let (l, r) = match (find(Side::Left), find(Side::Right)) {
        (Some(l), Some(r)) => (l, r),
        (Some(l), None) | (None, Some(l)) => {
            ctx.warnings.push(BoneWarning::OnePelvicLimb);
            (l, l)
        }
        (None, None) => {
            ctx.warnings.push(BoneWarning::NoPelvicLimbs);
            return;
        }
    };
    let (mut pl, mut pr) = (l.3, r.3);
    if l.1 == r.1 {
        let p = pl;
        if (p - root).dot(left) >= 0.0 {
            pr = mirror(p);
        } else {
            pl = mirror(p);
        }
    }
    let Some(x) = (pl - pr).try_normalize() else {
        ctx.warnings.push(BoneWarning::HipsCoincide);
        return;
    };
    let half_width = 0.5 * pl.distance(pr);
    let cranial = ctx
        .body
        .spine
        .get(1)
        .map(|&j| ctx.pos(j) - root)
        .or_else(|| ctx.body.head.map(|h| ctx.pos(h) - root))
        .unwrap_or(ctx.body.up);
    let z = perpendicular(cranial, x)
        .or_else(|| perpendicular(ctx.body.up, x))
        .unwrap_or_else(|| x.any_orthonormal_vector());
    let y = z.cross(x);
    let o = ctx.options;
    let socket =
        l.2.map(|knee| {
            let (a, b) = (l.3, ctx.pos(knee));
            let shaft = (o.shaft_fraction * median_radius(ctx.map, a, b))
                .min(o.max_shaft_ratio * a.distance(b));
            (1.15 * o.epiphysis_scale * shaft).min(0.15 * a.distance(b))
        })
        .unwrap_or(0.3 * half_width)
        .min(0.6 * half_width);
    let mid = 0.5 * (pl + pr);
    ctx.keep(Draft {
        kind: BoneKind::Pelvis,
        name: "pelvic_girdle".into(),
        joint: ctx.body.root,
        local: pelvis(&Pelvis {
            half_width,
            height: o.pelvis_height * half_width,
            socket,
            rings: o.rings,
            segments: o.segments,
        }),
        origin: mid,
        axes: [x, y, z],
        shrink: Shrink::About(DVec3::ZERO),
        slide: Some((z, half_width)),
    });
}

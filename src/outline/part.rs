//! One outline to one rigged part: resample, simplify, straight skeleton, axis graph,
//! BoundedDP joints, skeleton (seed 003, 3.1).

use super::{
    axis_graph, bounded_dp, douglas_peucker_closed, resample, slices, spline_samples,
    straight_skeleton, AxisGraph, Outline, OutlineError, OutlineOptions, StraightSkeleton,
};
use crate::lod::{level_of_detail, LodOptions};
use crate::skeleton::{Joint, JointId, Skeleton};
use glam::{DQuat, DVec2, DVec3};

/// A skeleton extracted from one outline, with every intermediate result.
#[derive(Debug, Clone)]
pub struct OutlineSkeleton {
    /// The validated input outline (counter-clockwise).
    pub outline: Outline,
    /// The uniformly resampled stroke.
    pub resampled: Vec<DVec2>,
    /// The Douglas-Peucker polygon the straight skeleton was computed on.
    pub polygon: Vec<DVec2>,
    /// Its straight skeleton.
    pub straight: StraightSkeleton,
    /// The straight skeleton without peripheral arcs, short arcs collapsed.
    pub axis: AxisGraph,
    /// The final skeleton in the outline plane (z = 0), outline units: `root` at the thickest
    /// axis node, then `joint_NNN` in breadth-first order; frames with local z along the bone
    /// to the first child.
    pub skeleton: Skeleton,
    /// Local half thickness of the part at each joint (outline units), for the cylinder-ball
    /// intersection test.
    pub radii: Vec<f64>,
}

/// The skeleton of `outline` (seed 003, 3.1): uniform resampling, Douglas-Peucker polygon
/// (tolerance lowered until the polygon stays simple), straight skeleton, removal of peripheral
/// arcs and collapse of short arcs, BoundedDP joints along each branch, then the
/// level-of-detail operations of `options.lod` (with junction-to-terminal branches shorter than
/// `options.prune_fraction` and bones between internal joints shorter than
/// `options.collapse_fraction` of the diagonal always removed).
///
/// # Errors
/// [`OutlineError::InvalidOption`], [`OutlineError::SelfIntersecting`] when even the
/// resampled stroke is not simple, [`OutlineError::StraightSkeleton`], and
/// [`OutlineError::Lod`] for a bad level-of-detail setting.
pub fn outline_skeleton(
    outline: &Outline,
    options: &OutlineOptions,
) -> Result<OutlineSkeleton, OutlineError> {
    options.validate()?;
    let (lo, hi) = outline.bounds();
    let diagonal = (hi - lo).length();
    let resampled = resample(
        &outline.points,
        options.resample_fraction * outline.perimeter(),
    );
    let polygon = simple_polygon(&resampled, options.polygon_tolerance * diagonal)?;
    let straight = straight_skeleton(&polygon, options.tolerance)?;
    let axis = axis_graph(&straight, options.collapse_ratio);
    let (positions, radii, edges, axis_joints) = joints(&axis, &resampled, diagonal, options);
    let (skeleton, radii) = tree(&positions, &radii, &edges, axis_joints);
    let lod = LodOptions {
        collapse: options
            .lod
            .collapse
            .max(options.collapse_fraction * diagonal),
        prune: options.lod.prune.max(options.prune_fraction * diagonal),
        ..options.lod.clone()
    };
    let skeleton = if lod.is_identity() {
        skeleton
    } else {
        let s = level_of_detail(&skeleton, &lod)?;
        let radii = s
            .joints
            .iter()
            .map(|j| skeleton.find(&j.name).map(|id| radii[id.0]).unwrap_or(0.0))
            .collect::<Vec<_>>();
        return Ok(OutlineSkeleton {
            outline: outline.clone(),
            resampled,
            polygon,
            straight,
            axis,
            skeleton: with_frames(renumbered(s)),
            radii,
        });
    };
    Ok(OutlineSkeleton {
        outline: outline.clone(),
        resampled,
        polygon,
        straight,
        axis,
        skeleton,
        radii,
    })
}

/// Names the joints `root`, `joint_001`, ... again in order (level of detail leaves gaps).
fn renumbered(mut skeleton: Skeleton) -> Skeleton {
    for (k, joint) in skeleton.joints.iter_mut().enumerate() {
        joint.name = if k == 0 {
            "root".to_string()
        } else {
            format!("joint_{k:03}")
        };
    }
    skeleton
}

/// Douglas-Peucker polygon of `points`, halving the tolerance while the result crosses itself.
fn simple_polygon(points: &[DVec2], tolerance: f64) -> Result<Vec<DVec2>, OutlineError> {
    let lifted: Vec<DVec3> = points.iter().map(|p| p.extend(0.0)).collect();
    let mut tolerance = tolerance;
    for _ in 0..12 {
        let kept = douglas_peucker_closed(&lifted, tolerance);
        let polygon: Vec<DVec2> = kept.iter().map(|&i| points[i]).collect();
        if polygon.len() >= 3
            && super::simple::first_crossing(&polygon).is_none()
            && super::input::signed_area(&polygon) > 0.0
        {
            return Ok(polygon);
        }
        tolerance *= 0.5;
    }
    match super::simple::first_crossing(points) {
        None => Ok(points.to_vec()),
        Some((first, second, at)) => Err(OutlineError::SelfIntersecting {
            first,
            second,
            x: at.x,
            y: at.y,
        }),
    }
}

/// Joint positions, radii and bones: the axis graph's junction and terminal nodes plus the
/// BoundedDP samples kept along each branch; the axis joints come first (their count is the
/// last value).
#[allow(clippy::type_complexity)]
fn joints(
    axis: &AxisGraph,
    outline: &[DVec2],
    diagonal: f64,
    options: &OutlineOptions,
) -> (Vec<DVec2>, Vec<f64>, Vec<[usize; 2]>, usize) {
    let adj = axis.neighbours();
    let mut positions: Vec<DVec2> = Vec::new();
    let mut radii: Vec<f64> = Vec::new();
    let mut id = vec![usize::MAX; axis.nodes.len()];
    for k in 0..axis.nodes.len() {
        if adj[k].len() != 2 {
            id[k] = positions.len();
            positions.push(axis.nodes[k]);
            radii.push(axis.radii[k]);
        }
    }
    let mut edges = Vec::new();
    let b = &options.bounded_dp;
    for branch in axis.branches() {
        let polyline: Vec<DVec2> = branch.iter().map(|&k| axis.nodes[k]).collect();
        let (r0, r1) = (axis.radii[branch[0]], axis.radii[branch[branch.len() - 1]]);
        let all = spline_samples(&polyline, b.sample_spacing * diagonal);
        let arc = arc_lengths(&all);
        let total = arc.last().copied().unwrap_or(0.0);
        // Inner samples outside the end joints' balls, with the ends themselves.
        let mut chosen: Vec<usize> = vec![0];
        chosen.extend(
            (1..all.len().saturating_sub(1))
                .filter(|&i| arc[i] >= b.end_margin * r0 && total - arc[i] >= b.end_margin * r1),
        );
        if all.len() > 1 {
            chosen.push(all.len() - 1);
        }
        let samples: Vec<DVec2> = chosen.iter().map(|&i| all[i]).collect();
        let local: Vec<f64> = chosen
            .iter()
            .map(|&i| {
                let u = if total > 0.0 { arc[i] / total } else { 0.0 };
                r0 + (r1 - r0) * u
            })
            .collect();
        let mut previous = id[branch[0]];
        if samples.len() >= b.min_samples.max(3) {
            let mut s = slices(&samples, outline);
            for (slice, r) in s.iter_mut().zip(&local) {
                slice.left = slice.left.min(b.extent_cap * r);
                slice.right = slice.right.min(b.extent_cap * r);
            }
            let keep = bounded_dp(&s, b.epsilon * diagonal, b);
            for i in 1..samples.len() - 1 {
                if keep[i] {
                    positions.push(samples[i]);
                    radii.push(local[i]);
                    let here = positions.len() - 1;
                    edges.push([previous, here]);
                    previous = here;
                }
            }
        }
        edges.push([previous, id[branch[branch.len() - 1]]]);
    }
    let axis_joints = adj.iter().filter(|a| a.len() != 2).count();
    (positions, radii, edges, axis_joints)
}

/// Cumulative arc length along `points`.
fn arc_lengths(points: &[DVec2]) -> Vec<f64> {
    let mut out = Vec::with_capacity(points.len());
    let mut s = 0.0;
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            s += p.distance(points[i - 1]);
        }
        out.push(s);
    }
    out
}

/// The skeleton of a tree of joints, breadth-first from the root: the junction of largest
/// radius among the first `axis_joints` (the axis graph's junction and terminal nodes), else
/// the axis joint of largest radius.
fn tree(
    positions: &[DVec2],
    radii: &[f64],
    edges: &[[usize; 2]],
    axis_joints: usize,
) -> (Skeleton, Vec<f64>) {
    let n = positions.len();
    let mut adj = vec![Vec::new(); n];
    for &[a, b] in edges {
        adj[a].push(b);
        adj[b].push(a);
    }
    let widest = |candidates: Vec<usize>| {
        candidates
            .into_iter()
            .max_by(|&a, &b| radii[a].total_cmp(&radii[b]).then(b.cmp(&a)))
    };
    let root = widest((0..axis_joints).filter(|&k| adj[k].len() >= 3).collect())
        .or_else(|| widest((0..axis_joints.min(n)).collect()))
        .unwrap_or(0);
    let mut order = vec![root];
    let mut parent = vec![usize::MAX; n];
    let mut seen = vec![false; n];
    seen[root] = true;
    let mut head = 0;
    while head < order.len() {
        let at = order[head];
        head += 1;
        for &next in &adj[at] {
            if !seen[next] {
                seen[next] = true;
                parent[next] = at;
                order.push(next);
            }
        }
    }
    let mut new_id = vec![usize::MAX; n];
    let mut joints = Vec::with_capacity(order.len());
    for (k, &old) in order.iter().enumerate() {
        new_id[old] = k;
        let name = if k == 0 {
            "root".to_string()
        } else {
            format!("joint_{k:03}")
        };
        let p = (parent[old] != usize::MAX).then(|| JointId(new_id[parent[old]]));
        joints.push(Joint::new(name, p, positions[old].extend(0.0)));
    }
    let radii = order.iter().map(|&k| radii[k]).collect();
    (with_frames(Skeleton { joints }), radii)
}

/// Sets each joint's frame: local z along the bone to its first child, or along its own bone
/// for a leaf; identity for a lone joint.
pub(crate) fn with_frames(mut skeleton: Skeleton) -> Skeleton {
    let n = skeleton.len();
    for k in 0..n {
        let id = JointId(k);
        let here = skeleton.joints[k].position;
        let dir = match skeleton.children(id).first() {
            Some(c) => skeleton.joints[c.0].position - here,
            None => match skeleton.joints[k].parent {
                Some(p) => here - skeleton.joints[p.0].position,
                None => DVec3::ZERO,
            },
        };
        skeleton.joints[k].frame = match dir.try_normalize() {
            Some(d) => DQuat::from_rotation_arc(DVec3::Z, d),
            None => DQuat::IDENTITY,
        };
    }
    skeleton
}

//! Topology-free skeleton distances from the auto-rigging literature (RigNet, Xu et al. 2020):
//! joint-to-joint, joint-to-bone and bone-to-bone symmetric chamfer distances.

use crate::skeleton::Skeleton;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Symmetric chamfer distances between two skeletons, in mesh units (or, after
/// [`ChamferDistances::normalised`], as a fraction of figure size).
///
/// With joint sets `P`, `Q` and bone segment sets `B(P)`, `B(Q)`:
/// * `j2j` = ½ (mean over p in P of min_q |p − q| + the same from Q to P) — RigNet CD-J2J;
/// * `j2b` = ½ (mean over p in P of the distance from p to the nearest bone of Q + the same from
///   Q to P) — CD-J2B;
/// * `b2b` = the same with points sampled uniformly along every bone (spacing given by
///   [`ChamferOptions::bone_sample_spacing`]) instead of joints — CD-B2B. Distances are taken
///   to the exact segments, so the only approximation is the sampling of the source bones.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct ChamferDistances {
    /// Joint-to-joint chamfer distance.
    pub j2j: f64,
    /// Joint-to-bone chamfer distance.
    pub j2b: f64,
    /// Bone-to-bone chamfer distance.
    pub b2b: f64,
}

impl ChamferDistances {
    /// Every distance divided by `size` (e.g. the figure height); unchanged when `size` is not
    /// positive.
    pub fn normalised(&self, size: f64) -> Self {
        if size > 0.0 {
            Self {
                j2j: self.j2j / size,
                j2b: self.j2b / size,
                b2b: self.b2b / size,
            }
        } else {
            *self
        }
    }
}

/// Options of [`chamfer`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChamferOptions {
    /// Distance between samples along bones for `b2b`, mesh units. Default 0.005 (5 mm for
    /// metre-scale figures); callers usually set it to a fraction of figure size (see
    /// `EvalOptions::bone_sample_fraction`).
    pub bone_sample_spacing: f64,
}

impl Default for ChamferOptions {
    fn default() -> Self {
        Self {
            bone_sample_spacing: 0.005,
        }
    }
}

/// Bones of `skeleton` as `(parent position, child position)` segments, one per joint with a
/// parent. A skeleton without bones yields one zero-length segment per joint, so that
/// distances to it stay defined.
pub fn bone_segments(skeleton: &Skeleton) -> Vec<(DVec3, DVec3)> {
    let bones: Vec<_> = skeleton
        .joints
        .iter()
        .filter_map(|j| {
            let parent = skeleton.joints.get(j.parent?.0)?;
            Some((parent.position, j.position))
        })
        .collect();
    if bones.is_empty() {
        skeleton
            .joints
            .iter()
            .map(|j| (j.position, j.position))
            .collect()
    } else {
        bones
    }
}

pub use crate::math::point_segment_distance;

/// Points along each segment, at most `spacing` apart, both ends included.
pub fn sample_segments(segments: &[(DVec3, DVec3)], spacing: f64) -> Vec<DVec3> {
    let mut points = Vec::new();
    for &(a, b) in segments {
        let length = a.distance(b);
        let steps = if spacing > 0.0 && length.is_finite() {
            // Bounded so that a tiny spacing cannot request billions of samples.
            ((length / spacing).ceil() as usize).clamp(1, 100_000)
        } else {
            1
        };
        points.extend((0..=steps).map(|i| a.lerp(b, i as f64 / steps as f64)));
    }
    points
}

fn mean_nearest_point(from: &[DVec3], to: &[DVec3]) -> f64 {
    mean(from.iter().map(|p| {
        to.iter()
            .map(|q| p.distance(*q))
            .fold(f64::INFINITY, f64::min)
    }))
}

fn mean_nearest_segment(from: &[DVec3], to: &[(DVec3, DVec3)]) -> f64 {
    mean(from.iter().map(|&p| {
        to.iter()
            .map(|&(a, b)| point_segment_distance(p, a, b))
            .fold(f64::INFINITY, f64::min)
    }))
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, count) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if count == 0 {
        0.0
    } else {
        sum / count as f64
    }
}

/// The three chamfer distances between skeletons `a` and `b` (all their joints; filter to
/// deforming joints first if wanted). Symmetric in `a` and `b`; zero for identical skeletons.
/// Empty skeletons give zero. Cost O(|A|·|B|) per term, fine for rigs of a few hundred joints.
pub fn chamfer(a: &Skeleton, b: &Skeleton, options: &ChamferOptions) -> ChamferDistances {
    let joints_a: Vec<DVec3> = a.joints.iter().map(|j| j.position).collect();
    let joints_b: Vec<DVec3> = b.joints.iter().map(|j| j.position).collect();
    if joints_a.is_empty() || joints_b.is_empty() {
        return ChamferDistances::default();
    }
    let bones_a = bone_segments(a);
    let bones_b = bone_segments(b);
    let samples_a = sample_segments(&bones_a, options.bone_sample_spacing);
    let samples_b = sample_segments(&bones_b, options.bone_sample_spacing);
    ChamferDistances {
        j2j: 0.5
            * (mean_nearest_point(&joints_a, &joints_b) + mean_nearest_point(&joints_b, &joints_a)),
        j2b: 0.5
            * (mean_nearest_segment(&joints_a, &bones_b)
                + mean_nearest_segment(&joints_b, &bones_a)),
        b2b: 0.5
            * (mean_nearest_segment(&samples_a, &bones_b)
                + mean_nearest_segment(&samples_b, &bones_a)),
    }
}

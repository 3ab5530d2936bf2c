//! The head joint (seed 004, 3.1, fig. 2): the perimeter-weighted head centroid projected to the
//! nose-level slice, averaged with the centre of the circle fitted to the back of the head.

use super::frame::{BodyFrame, HeadSlices};
use super::geometry::fit_circle;
use super::RefineOptions;
use glam::DVec3;

/// The head joint and the cranial roof above it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadJoint {
    /// The joint between head and spine, mesh units.
    pub joint: DVec3,
    /// The head joint moved to the top of the skull along the transverse normal (the head's
    /// leaf, seed 004, 3.1).
    pub roof: DVec3,
    /// Perimeter-weighted centroid of the head slices.
    pub centroid: DVec3,
}

/// Computes the head joint from the head slices in the body frame. `None` when the slices have
/// no length or the back of the head gives no circle.
pub fn head_joint(
    frame: &BodyFrame,
    head: &HeadSlices,
    options: &RefineOptions,
) -> Option<HeadJoint> {
    let (sum, weight) = head
        .slices
        .iter()
        .fold((DVec3::ZERO, 0.0), |(s, w), slice| {
            let p = slice.perimeter();
            (s + slice.centroid().unwrap_or(DVec3::ZERO) * p, w + p)
        });
    if weight <= 0.0 {
        return None;
    }
    let centroid = sum / weight;
    // The slice reaching farthest forward: the nose.
    let nose = head.slices.iter().max_by(|a, b| {
        let reach = |s: &crate::mesh::SliceLoop| {
            s.points
                .iter()
                .map(|p| p.dot(frame.forward))
                .fold(f64::MIN, f64::max)
        };
        reach(a).total_cmp(&reach(b))
    })?;
    let height = frame.h(*nose.points.first()?);
    let projected = frame.at_height(centroid, height);
    let (front, back) = nose.points.iter().fold((f64::MIN, f64::MAX), |(f, b), p| {
        let t = p.dot(frame.forward);
        (f.max(t), b.min(t))
    });
    let limit = projected.dot(frame.forward) - options.head_back_fraction * (front - back);
    let rear: Vec<(f64, f64)> = nose
        .points
        .iter()
        .filter(|p| p.dot(frame.forward) < limit)
        .map(|p| (p.dot(frame.forward), p.dot(frame.left)))
        .collect();
    let ((cf, cl), _) = fit_circle(&rear)?;
    let circle = frame.up * height + frame.forward * cf + frame.left * cl;
    let joint = (projected + circle) * 0.5;
    Some(HeadJoint {
        joint,
        roof: frame.at_height(joint, frame.top),
        centroid,
    })
}

//! Body frame and head geometry (seed 004, 3.1): the transverse normal from the legs, head
//! slices from the top down, frontal and sagittal normals from the head's projected points.

use super::geometry::{enclosing_loop, pca_2d_curve, Segment2};
use super::RefineOptions;
use crate::mesh::{Mesh, PlaneSlicer, SliceLoop};
use glam::DVec3;

/// The body's orthonormal directions (seed 004, 3: transverse, frontal and sagittal plane
/// normals) and its vertical extent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyFrame {
    /// Normal of the transverse plane, pointing up (feet → head).
    pub up: DVec3,
    /// Normal of the frontal plane, pointing forward (the way the face looks).
    pub forward: DVec3,
    /// Normal of the sagittal plane, pointing to the figure's left: `up × forward`.
    pub left: DVec3,
    /// Height of the topmost mesh point along `up` (mesh units, `p · up`).
    pub top: f64,
    /// Height of the lowest mesh point along `up`.
    pub bottom: f64,
}

impl BodyFrame {
    /// A frame from `up` and the part of `forward` perpendicular to it, with the mesh's
    /// extent along `up`. `None` when they are parallel or the mesh has no vertices.
    pub fn new(mesh: &Mesh, up: DVec3, forward: DVec3) -> Option<Self> {
        let up = up.try_normalize()?;
        let forward = (forward - up * forward.dot(up)).try_normalize()?;
        let (bottom, top) = mesh
            .triangles
            .iter()
            .flatten()
            .map(|&i| mesh.positions[i as usize].dot(up))
            .fold(None, |acc: Option<(f64, f64)>, h| {
                Some(acc.map_or((h, h), |(lo, hi)| (lo.min(h), hi.max(h))))
            })?;
        Some(Self {
            up,
            forward,
            left: up.cross(forward),
            top,
            bottom,
        })
    }

    /// Figure height along `up`, mesh units.
    pub fn height(&self) -> f64 {
        self.top - self.bottom
    }

    /// Height of `p` along `up`.
    pub fn h(&self, p: DVec3) -> f64 {
        p.dot(self.up)
    }

    /// `p` moved along `up` to height `h`.
    pub fn at_height(&self, p: DVec3, h: f64) -> DVec3 {
        p + self.up * (h - self.h(p))
    }
}

/// The head as transverse slices from the top down to the chin-throat (or head-torso)
/// transfer.
#[derive(Debug, Clone, PartialEq)]
pub struct HeadSlices {
    /// The head's slices, top first, each the loop around the head at its height.
    pub slices: Vec<SliceLoop>,
    /// Index of the slice with the largest diameter.
    pub largest: usize,
    /// Which criterion ended the head: `true` for the diameter shrink, `false` for the turned
    /// principal axes (or the depth limit).
    pub ended_by_shrink: bool,
}

/// Slices the head from the top of `frame` downwards (seed 004, 3.1). `near` is a point of the
/// rough skeleton inside the head, used to pick the head's loop where a slice has several
/// (hands raised above the head). The head is the figure's one median part: a slice counts only
/// when a loop of it crosses the median plane through `near` (normal `frame.left`), so the
/// slices begin below a pair of ears, horns or raised hands that mirror each other, and the
/// depths are measured from the first slice that counts. The slices go down `head_max_depth`
/// of the height, or to `shoulders` (the rough shoulder joints' height) when that is lower: a
/// helmet or a cartoon's big head reaches further down than a human head, but no head reaches
/// below the shoulders. `None` when no head-like sequence of slices is found.
pub fn head_slices(
    mesh: &Mesh,
    frame: &BodyFrame,
    near: DVec3,
    shoulders: Option<f64>,
    options: &RefineOptions,
) -> Option<HeadSlices> {
    let step = options.head_slice_step * frame.height();
    let lowest = shoulders.map_or(frame.top, |s| s.min(frame.top));
    let turn_cos = options.head_turn_degrees.to_radians().cos();
    let median = near.dot(frame.left);
    let crosses = |l: &SliceLoop| {
        let (lo, hi) = l.points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
            (lo.min(p.dot(frame.left)), hi.max(p.dot(frame.left)))
        });
        lo <= median && median <= hi
    };
    let slicer = PlaneSlicer::new(mesh, frame.up);
    let mut slices: Vec<SliceLoop> = Vec::new();
    let mut largest: Option<(usize, f64, DVec3, f64)> = None; // index, diameter, axis, elongation
    let mut previous = near;
    let mut start: Option<f64> = None; // height of the first slice that counts
    for k in 1.. {
        let h = frame.top - step * k as f64;
        let depth = start.map_or(0.0, |s| s - h);
        if h < frame.bottom || (depth > options.head_max_depth * frame.height() && h < lowest) {
            break;
        }
        let loops: Vec<SliceLoop> = slicer
            .slice(frame.up * h)
            .into_iter()
            .filter(crosses)
            .collect();
        let guess = frame.at_height(previous, h);
        let Some(slice) = enclosing_loop(&loops, frame.up, guess) else {
            continue;
        };
        let Some(axes) = slice.principal_axes() else {
            continue;
        };
        let start = *start.get_or_insert(h);
        let elongation = axes.major_diameter / axes.minor_diameter.max(f64::MIN_POSITIVE);
        let checked = start - h + step > options.head_min_depth * frame.height();
        if let (true, Some((_, diameter, axis, e))) = (checked, largest) {
            if axes.major_diameter < options.head_shrink_ratio * diameter {
                return finish(slices, largest, true);
            }
            let turned = axes.major.dot(axis).abs() < turn_cos;
            let elongated =
                elongation > options.head_min_elongation && e > options.head_min_elongation;
            if turned && elongated {
                return finish(slices, largest, false);
            }
        }
        if largest.is_none_or(|(_, d, _, _)| axes.major_diameter > d) {
            largest = Some((slices.len(), axes.major_diameter, axes.major, elongation));
        }
        previous = slice.centroid().unwrap_or(guess);
        slices.push(slice.clone());
    }
    None
}

fn finish(
    slices: Vec<SliceLoop>,
    largest: Option<(usize, f64, DVec3, f64)>,
    ended_by_shrink: bool,
) -> Option<HeadSlices> {
    let (largest, ..) = largest?;
    (slices.len() >= 3).then_some(HeadSlices {
        slices,
        largest,
        ended_by_shrink,
    })
}

/// The most the head's long axis may turn from the facing the refinement was given and still
/// set the frontal plane ([`frame_from_head`]). The facing found from the feet and the body's
/// symmetry, or the file's own axis, is off by a few degrees at most (a figure turned 3° is
/// found turned), and the head corrects it within that. A head's axis further off says more
/// about the head than about the body: a head turned on its neck, lopsided with hair, or
/// carrying a visor, headphones or a hat brim that turns its slices' principal axes (the
/// adventurer's head 4.8° off its facing, quaternius_cyberpunk_character's 6° off once the
/// figure was turned 1°, which moved its armpits' frontal slices and its shoulders 7 cm).
pub const MAX_HEAD_TURN_DEGREES: f64 = 3.0;

/// Frontal and sagittal normals from the head (seed 004, 3.1): the principal axes of all head
/// slices projected into one transverse plane (as curves, length-weighted, not as their
/// vertices). The seed takes the longer axis as forward; here forward is whichever principal
/// axis lies nearer `forward_hint` (the longer one on a human head, the shorter one on a head
/// wider than deep), its sign taken from the hint. Returns the frame with `forward` and `left`
/// replaced, or `None` when the head is too round to tell, or when its axis turns more than
/// `MAX_HEAD_TURN_DEGREES` (3°) from `frame.forward`: such a head is turned on its neck or made
/// lopsided by what it wears (hair cards hanging to one side, a ponytail, a hat, a visor), and
/// the body's own facing is the better frontal plane for slicing it.
pub fn frame_from_head(
    frame: &BodyFrame,
    head: &HeadSlices,
    forward_hint: DVec3,
) -> Option<BodyFrame> {
    let flat = |p: DVec3| (p.dot(frame.forward), p.dot(frame.left));
    let segments: Vec<Segment2> = head
        .slices
        .iter()
        .flat_map(|s| s.segments())
        .map(|(a, b)| (flat(a), flat(b)))
        .collect();
    let (major, ratio) = pca_2d_curve(&segments)?;
    if ratio < 1.02 {
        return None;
    }
    let major = (frame.forward * major.0 + frame.left * major.1).normalize();
    // A head wider than deep (a cartoon's) has its long axis across: forward is then the
    // principal axis nearer the hint, not always the longer one.
    let minor = frame.up.cross(major);
    let mut forward = if major.dot(forward_hint).abs() >= minor.dot(forward_hint).abs() {
        major
    } else {
        minor
    };
    if forward.dot(forward_hint) < 0.0 {
        forward = -forward;
    }
    if forward.dot(frame.forward) < MAX_HEAD_TURN_DEGREES.to_radians().cos() {
        return None;
    }
    Some(BodyFrame {
        forward,
        left: frame.up.cross(forward),
        ..*frame
    })
}

//! The head joint. Two conventions ([`HeadLevel`]): at the top of the neck, where the neck's
//! section widens into the head (game and engine rigs: Mixamo, Unreal, Unity, Quaternius,
//! GDQuest), or at nose level (seed 004, 3.1, fig. 2: the perimeter-weighted head centroid
//! projected to the nose-level slice, averaged with the centre of the circle fitted to the back
//! of the head; MakeHuman's rigs).

use super::frame::{BodyFrame, HeadSlices};
use super::geometry::enclosing_loop;
use super::geometry::fit_circle;
use super::{HeadLevel, RefineOptions};
use crate::mesh::{slice_plane_outer, Mesh, SliceLoop};
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
    /// Whether the head sits on the trunk with no neck between: no section above the narrowest
    /// one below the head widens to `head_neck_widening` times it (a cartoon's big head), so
    /// the joint is at that junction, the trunk's top.
    pub on_trunk: bool,
}

/// Computes the head joint from the head slices in the body frame, at the level
/// `options.head_level` asks for; `shoulders` is the rough shoulder joints' height, below which
/// no neck is searched. `None` when the slices have no length, the back of the head
/// gives no circle (nose level) and no neck is found below the head (neck top).
pub fn head_joint(
    mesh: &Mesh,
    frame: &BodyFrame,
    head: &HeadSlices,
    shoulders: Option<f64>,
    options: &RefineOptions,
) -> Option<HeadJoint> {
    match options.head_level {
        HeadLevel::NoseLevel => nose_level(frame, head, options),
        HeadLevel::NeckTop => neck_top(mesh, frame, head, shoulders, options),
        HeadLevel::Auto if has_face(frame, head, options) => nose_level(frame, head, options)
            .or_else(|| neck_top(mesh, frame, head, shoulders, options)),
        HeadLevel::Auto => neck_top(mesh, frame, head, shoulders, options)
            .or_else(|| nose_level(frame, head, options)),
    }
}

/// Whether the head's forward-most slice is a nose: above the head's lowest slice (there it is
/// a chin or a collar), in the lower part of the head, at most `head_nose_max` of the
/// sliced length up (a nose tip is about a third of the way up from the chin; higher, the
/// forward-most part is a visor, a hat brim or hair), and narrow ([`is_narrow_tip`]: the front
/// of a round cartoon head is the cap of a sphere, no nose). A head sliced down further than
/// `head_max_depth` of the height (longer than a child's head: a helmet or a stylised big head)
/// has no face either: its narrow front is a visor's edge or a snout, and such figures' rigs
/// put the head joint at the neck's top. A head sliced down less than [`FACE_MIN_DEPTH`] shows
/// too little of itself to tell.
fn has_face(frame: &BodyFrame, head: &HeadSlices, options: &RefineOptions) -> bool {
    let (Some(nose), Some(top), Some(bottom)) = (
        forward_most(frame, head),
        head.slices.first().and_then(|s| s.points.first()),
        head.slices.last().and_then(|s| s.points.first()),
    ) else {
        return false;
    };
    let (top, bottom) = (frame.h(*top), frame.h(*bottom));
    let depth = top - bottom;
    if depth > options.head_max_depth * frame.height() || depth < FACE_MIN_DEPTH * frame.height() {
        return false;
    }
    let Some(tip) = nose.points.first() else {
        return false;
    };
    let t = (frame.h(*tip) - bottom) / (top - bottom).max(f64::MIN_POSITIVE);
    t >= options.head_nose_min && t <= options.head_nose_max && is_narrow_tip(frame, nose)
}

/// The least depth of the head's slices, as a fraction of the height, that can show a face: a
/// head is an eighth of an adult's height or more (0.12-0.14 on the MakeHuman bodies, more on a
/// child or a cartoon), so slices ending higher stopped at the hair or the crown (the shrink
/// or turn of a strand's slice ended them) and their forward-most slice is no nose: a
/// quaternius_women_formal re-posed with her arms lowered 30 degrees ended her head 0.06 of the
/// height down and read a narrow front in those slices as a nose.
const FACE_MIN_DEPTH: f64 = 0.09;

/// The front [`NOSE_DEPTH`] of a nose's slice (by depth, from its forward-most point) spans at
/// most this fraction of the slice's width: the MakeHuman noses span 0.20-0.22 of the head's
/// width there, the cap of a circle 0.6 (0.46 on the low-poly sphere of a cartoon's head,
/// measured on the slice's vertices).
const NOSE_WIDTH: f64 = 0.35;

/// See [`NOSE_WIDTH`]: the band's depth as a fraction of the slice's depth.
const NOSE_DEPTH: f64 = 0.1;

/// Whether the front of `slice` is a narrow protrusion ([`NOSE_WIDTH`]).
fn is_narrow_tip(frame: &BodyFrame, slice: &SliceLoop) -> bool {
    let span = |points: &mut dyn Iterator<Item = f64>| {
        points.fold((f64::MAX, f64::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)))
    };
    let (back, front) = span(&mut slice.points.iter().map(|p| p.dot(frame.forward)));
    let (right, left) = span(&mut slice.points.iter().map(|p| p.dot(frame.left)));
    let limit = front - NOSE_DEPTH * (front - back);
    let (lo, hi) = span(
        &mut slice
            .points
            .iter()
            .filter(|p| p.dot(frame.forward) >= limit)
            .map(|p| p.dot(frame.left)),
    );
    hi - lo <= NOSE_WIDTH * (left - right)
}

/// The head slice reaching farthest forward.
fn forward_most<'a>(frame: &BodyFrame, head: &'a HeadSlices) -> Option<&'a SliceLoop> {
    let reach = |s: &SliceLoop| {
        s.points
            .iter()
            .map(|p| p.dot(frame.forward))
            .fold(f64::MIN, f64::max)
    };
    head.slices
        .iter()
        .max_by(|a, b| reach(a).total_cmp(&reach(b)))
}

/// The head joint at the top of the neck. Slicing down from the head's first slice for
/// `head_max_depth + head_neck_search` of the height, the neck is the slice below the head's
/// widest slice that is narrowest against the widest slice above it (the deepest valley of the diameter profile, so that the small
/// slices at the crown do not count; the search stops at the height of the rough shoulder
/// joints, `shoulders`, below which the torso and arms are no neck); going up from it, the
/// first slice whose diameter reaches `head_neck_widening` times the neck's is where the head
/// begins (the neck itself when none does). The joint is at that height on the neck's axis (the slice's own centroid takes in
/// the jaw, in front of the spine), brought forward when that lies far behind the skull above
/// it ([`not_behind_skull`]).
fn neck_top(
    mesh: &Mesh,
    frame: &BodyFrame,
    head: &HeadSlices,
    shoulders: Option<f64>,
    options: &RefineOptions,
) -> Option<HeadJoint> {
    let centroid = perimeter_centroid(head)?;
    let step = options.head_slice_step * frame.height();
    let first = head.slices.first()?;
    let mut previous = first.centroid()?;
    let mut h = frame.h(*first.points.first()?);
    let lowest = h - (options.head_max_depth + options.head_neck_search) * frame.height();
    let lowest = shoulders.map_or(lowest, |s| lowest.min(s));
    // (height, major diameter, centroid), top down.
    let mut column: Vec<(f64, f64, DVec3)> = Vec::new();
    while h > lowest {
        let origin = frame.at_height(previous, h);
        h -= step;
        let loops = slice_plane_outer(mesh, origin, frame.up);
        let Some(slice) = enclosing_loop(&loops, frame.up, origin).filter(|l| l.closed) else {
            continue;
        };
        let (Some(axes), Some(c)) = (slice.principal_axes(), slice.centroid()) else {
            continue;
        };
        column.push((frame.h(origin), axes.major_diameter, c));
        previous = c;
    }
    // The neck lies below the head's widest slice: above it, a small piece at the crown (a
    // hair strand, a visor's edge) can make a deeper valley than a thick neck does.
    let widest = head
        .slices
        .get(head.largest)
        .and_then(|s| s.points.first())
        .map_or(f64::INFINITY, |p| frame.h(*p));
    let mut widest_above = 0.0_f64;
    let mut neck: Option<(usize, f64)> = None; // index, valley ratio
    for (i, &(h, d, _)) in column.iter().enumerate() {
        if shoulders.is_some_and(|s| h < s) {
            break;
        }
        let ratio = widest_above / d.max(f64::MIN_POSITIVE);
        if h < widest && neck.is_none_or(|(_, r)| ratio > r) {
            neck = Some((i, ratio));
        }
        widest_above = widest_above.max(d);
    }
    let (neck, _) = neck?;
    let (valley, narrowest, axis) = column[neck];
    // A head that never widens to `head_neck_widening` times its narrowest section sits on the
    // trunk with no neck between (a cartoon's big head): the joint is at that section, where
    // head and trunk meet.
    let widened = column[..neck]
        .iter()
        .rev()
        .find(|&&(_, d, _)| d >= options.head_neck_widening * narrowest);
    let joint = frame.at_height(axis, widened.map_or(valley, |&(h, _, _)| h));
    let joint = skull_centroid(frame, head, frame.h(joint))
        .map_or(joint, |skull| not_behind_skull(frame, head, joint, skull));
    Some(HeadJoint {
        joint,
        roof: frame.at_height(joint, frame.top),
        centroid,
        on_trunk: widened.is_none(),
    })
}

/// How far behind the skull's centroid (as a fraction of the head's depth) the joint at the
/// top of the neck can lie: the head's centre of mass is 1-2 cm in front of the occipital
/// condyles on which it balances (a head 19-20 cm deep), about a tenth of the head's depth.
pub const CONDYLES_BEHIND_CENTROID: f64 = 0.1;

/// `joint` (on the neck's axis) moved forward to [`CONDYLES_BEHIND_CENTROID`] of the head's
/// depth behind the skull's `centroid` when it lies farther back: the skull balances on the
/// top of the neck. The neck's section is then not the neck's alone: hair, a hood or a
/// helmet hanging down the nape reaches as far back as the skull and pulls its centroid behind
/// the spine (a knight's helmet put the joint 4 % of the height behind the reference). A joint
/// within that distance, or in front of the centroid (a head tilted back over its neck), keeps
/// the neck's axis. The head's depth is that of its widest slice.
fn not_behind_skull(frame: &BodyFrame, head: &HeadSlices, joint: DVec3, centroid: DVec3) -> DVec3 {
    let Some(widest) = head.slices.get(head.largest) else {
        return joint;
    };
    let (back, front) = widest
        .points
        .iter()
        .fold((f64::MAX, f64::MIN), |(b, f), p| {
            let t = p.dot(frame.forward);
            (b.min(t), f.max(t))
        });
    let limit = centroid.dot(frame.forward) - CONDYLES_BEHIND_CENTROID * (front - back).max(0.0);
    let depth = joint.dot(frame.forward);
    if depth < limit {
        joint + frame.forward * (limit - depth)
    } else {
        joint
    }
}

/// The perimeter-weighted centroid of the head slices above height `h` (the skull above the
/// neck's top, without the collar, hood or shoulders the lower slices can reach). `None`
/// when no slice lies above `h`.
fn skull_centroid(frame: &BodyFrame, head: &HeadSlices, h: f64) -> Option<DVec3> {
    let (sum, weight) = head
        .slices
        .iter()
        .filter(|s| s.points.first().is_some_and(|p| frame.h(*p) > h))
        .fold((DVec3::ZERO, 0.0), |(s, w), slice| match slice.centroid() {
            Some(c) => (s + c * slice.perimeter(), w + slice.perimeter()),
            None => (s, w),
        });
    (weight > 0.0).then(|| sum / weight)
}

/// The perimeter-weighted centroid of the head slices.
fn perimeter_centroid(head: &HeadSlices) -> Option<DVec3> {
    let (sum, weight) = head
        .slices
        .iter()
        .fold((DVec3::ZERO, 0.0), |(s, w), slice| {
            let p = slice.perimeter();
            (s + slice.centroid().unwrap_or(DVec3::ZERO) * p, w + p)
        });
    (weight > 0.0).then(|| sum / weight)
}

/// The head joint at nose level (seed 004, 3.1, fig. 2).
fn nose_level(frame: &BodyFrame, head: &HeadSlices, options: &RefineOptions) -> Option<HeadJoint> {
    let centroid = perimeter_centroid(head)?;
    let nose = forward_most(frame, head)?;
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
        on_trunk: false,
    })
}

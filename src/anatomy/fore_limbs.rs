//! Short fore limbs of a biped (issue 21, item 2): a pair of mirror-symmetric protrusions
//! either side of the median plane, ahead of the hind legs, is the fore-limb pair even when it
//! is too short for the arm rule's length (a raptor's or a tyrannosaur's arms).
//!
//! Bilateral symmetry is the principle: a vertebrate's paired limbs mirror each other across
//! the median plane, a single bump or a part on that plane (a jaw, a dewlap) does not. Limbs hang
//! from the trunk or reach sideways in a rest pose; paired parts that rise (ears, horns,
//! antlers) are the head's, and they sit on the head, at its far end, not where the neck leaves
//! the chest.
//!
//! Two places hold such a pair. Short arms joining the trunk are sections of their own
//! ([`fore_pair`] among them). When the heart lies at the hips, the trunk stops there and the
//! arms branch off the head's section, between the trunk and the neck: [`chest_junction`]
//! finds where, so that the trunk is carried on to it and the arms become sections.

use super::rules::MedianPlane;
use super::sections::section;
use super::{Frame, LevelGraph, Section};
use crate::medial::MedialSurface;
use glam::DVec3;

/// Where "ahead of the hind legs" is: past the hind legs' attachment along the body's
/// anterior axis, from the hind legs towards the head. The head gives that axis rather than the
/// frame's forward, which is only a first guess while the up direction is being tried.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Ahead {
    /// Unit anterior axis, perpendicular to up.
    axis: DVec3,
    /// The hind legs' attachment farthest along `axis`.
    behind: f64,
}

impl Ahead {
    /// From the hind legs' attachment points (`hind`, mesh units) towards `head` (the head's
    /// distal point; `frame.forward` without a head or when the head is not off the hind legs
    /// across up).
    pub fn new(hind: &[DVec3], head: Option<DVec3>, frame: &Frame) -> Self {
        let mid = hind.iter().sum::<DVec3>() / hind.len().max(1) as f64;
        let axis = head
            .and_then(|h| {
                let d = h - mid;
                (d - frame.up * d.dot(frame.up)).try_normalize()
            })
            .unwrap_or(frame.forward);
        let behind = hind
            .iter()
            .map(|p| p.dot(axis))
            .fold(f64::NEG_INFINITY, f64::max);
        Self { axis, behind }
    }

    /// Whether `p` lies ahead of the hind legs.
    fn contains(&self, p: DVec3) -> bool {
        p.dot(self.axis) > self.behind
    }
}

/// Whether `section` leaves its attachment vertex's centroid `from` as a rest-pose limb does:
/// at least as far sideways or down as up (ears, horns and antlers rise).
pub(super) fn hangs_or_reaches_sideways(section: &Section, from: DVec3, frame: &Frame) -> bool {
    let d = section.distal - from;
    let (side, up) = (d.dot(frame.left).abs(), d.dot(frame.up));
    side.max(-up) >= up
}

/// Whether sections `a` and `b` mirror each other across the median plane through `centre`
/// (normal `frame.left`): comparable lengths (the shorter at least half the longer), each voxel
/// mean off the plane and on opposite sides by more than a third of the longer length, and `b`'s
/// mean reflected across the plane within that third of `a`'s.
pub(super) fn mirror_pair(a: &Section, b: &Section, frame: &Frame, centre: DVec3) -> bool {
    let plane = MedianPlane::new(frame, centre);
    let offset = |p: DVec3| plane.offset(p);
    let longer = a.length.max(b.length);
    let tolerance = longer / 3.0;
    let reflected = plane.reflect(b.mean);
    a.length.min(b.length) >= 0.5 * longer
        && offset(a.mean).abs() > tolerance
        && offset(b.mean).abs() > tolerance
        && offset(a.mean) * offset(b.mean) < 0.0
        && reflected.distance(a.mean) <= tolerance
}

/// The fore-limb pair among `candidates` (indices into `sections` of `graph`): two sections
/// that mirror each other ([`mirror_pair`]), both leaving the body (their attachment vertex's
/// centroid, which their length is measured from) `ahead` of the hind legs and neither rising ([`hangs_or_reaches_sideways`]). Of several such
/// pairs the one whose means mirror best (then the longer) is taken; `None` when there is none.
pub(super) fn fore_pair(
    candidates: &[usize],
    sections: &[Section],
    graph: &LevelGraph,
    frame: &Frame,
    centre: DVec3,
    ahead: &Ahead,
) -> Option<(usize, usize)> {
    let from = |s: usize| graph.vertices[sections[s].attachment_vertex].centroid;
    let limb_like = |s: usize| {
        ahead.contains(from(s)) && hangs_or_reaches_sideways(&sections[s], from(s), frame)
    };
    let offset = |p: DVec3| (p - centre).dot(frame.left);
    let mut best: Option<(f64, f64, usize, usize)> = None;
    for (i, &a) in candidates.iter().enumerate() {
        for &b in &candidates[i + 1..] {
            let (sa, sb) = (&sections[a], &sections[b]);
            if !(limb_like(a) && limb_like(b) && mirror_pair(sa, sb, frame, centre)) {
                continue;
            }
            let reflected = sb.mean - frame.left * (2.0 * offset(sb.mean));
            let misfit = reflected.distance(sa.mean) / sa.length.max(sb.length);
            let length = sa.length + sb.length;
            let better = match best {
                None => true,
                Some((m, l, _, _)) => misfit < m || (misfit == m && length > l),
            };
            if better {
                best = Some((misfit, length, a, b));
            }
        }
    }
    best.map(|(_, _, a, b)| (a, b))
}

/// Where a short fore-limb pair branches off the head's section `head` (a section of `graph`
/// hanging off the trunk): the level-graph vertex to carry the trunk on to, or `None`.
///
/// The head's main path runs from its top to the vertex holding its distal voxel; every subtree
/// leaving that path within the proximal half of the head section's length (the chest and the
/// base of the neck, not the head where ears and horns sit) is a candidate branch, measured as
/// a section from the path vertex it leaves. With them, the trunk's unlabelled sections `loose`
/// are candidates too: one arm of an asymmetrically tessellated pair may leave the trunk while
/// its partner leaves the head's section. A [`fore_pair`] `ahead` of the hind legs with at least
/// one branch gives the junction: the most distal path
/// vertex its branches leave from.
pub(super) fn chest_junction(
    graph: &LevelGraph,
    surface: &MedialSurface,
    head: &Section,
    loose: &[&Section],
    frame: &Frame,
    centre: DVec3,
    ahead: &Ahead,
) -> Option<usize> {
    let tip = head.vertices.iter().copied().max_by(|&a, &b| {
        let top = |v: usize| {
            graph.vertices[v]
                .voxels
                .iter()
                .map(|&p| graph.heart_values[p])
                .fold(f64::NEG_INFINITY, f64::max)
        };
        top(a).total_cmp(&top(b)).then(b.cmp(&a))
    })?;
    let mut path: Vec<usize> = graph
        .ancestors(tip)
        .into_iter()
        .take_while(|&v| v != head.attachment_vertex)
        .collect();
    path.reverse();
    let root = graph.vertices[head.attachment_vertex].centroid;
    let proximal = 0.5 * head.length;
    // Candidates, each with the index on `path` of the vertex it leaves (`None`: the trunk).
    let mut branches: Vec<Section> = loose.iter().map(|&s| s.clone()).collect();
    let mut leaves: Vec<Option<usize>> = vec![None; branches.len()];
    for (k, &v) in path.iter().enumerate() {
        if graph.vertices[v].centroid.distance(root) > proximal {
            continue;
        }
        let next = path.get(k + 1).copied();
        for &c in &graph.vertices[v].children {
            if Some(c) != next && !graph.vertices[c].insignificant {
                branches.push(section(graph, surface, v, c));
                leaves.push(Some(k));
            }
        }
    }
    let candidates: Vec<usize> = (0..branches.len()).collect();
    let (a, b) = fore_pair(&candidates, &branches, graph, frame, centre, ahead)?;
    let k = leaves[a].max(leaves[b])?;
    Some(path[k])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anatomy::{Extremes, Reach};

    /// A section from `attachment` to `distal` whose voxel mean is halfway.
    fn section_to(attachment: DVec3, distal: DVec3) -> Section {
        Section {
            top: 0,
            attachment_vertex: 0,
            vertices: vec![0],
            voxels: 4,
            weight: 0.01,
            attachment,
            distal,
            length: attachment.distance(distal),
            mean: 0.5 * (attachment + distal),
            reach: Reach::EMPTY,
            extreme: Extremes::default(),
            linear_fraction: 0.0,
            insignificant: false,
        }
    }

    fn frame() -> Frame {
        Frame::new(DVec3::Y, DVec3::Z).unwrap()
    }

    #[test]
    fn arms_hanging_or_held_out_sideways_are_limb_like_and_ears_are_not() {
        let from = DVec3::new(0.2, 1.0, 0.5);
        let hanging = section_to(from, DVec3::new(0.3, 0.6, 0.7));
        let held_out = section_to(from, DVec3::new(0.8, 1.1, 0.5));
        let ear = section_to(from, DVec3::new(0.3, 1.5, 0.5));
        assert!(hangs_or_reaches_sideways(&hanging, from, &frame()));
        assert!(hangs_or_reaches_sideways(&held_out, from, &frame()));
        assert!(!hangs_or_reaches_sideways(&ear, from, &frame()));
    }

    #[test]
    fn ahead_of_the_hind_legs_is_towards_the_head_whatever_the_forward_guess() {
        let hind = [DVec3::new(0.2, 1.0, 0.0), DVec3::new(-0.2, 1.0, 0.0)];
        let backwards = Frame::new(DVec3::Y, -DVec3::Z).unwrap();
        let ahead = Ahead::new(&hind, Some(DVec3::new(0.0, 1.5, 1.2)), &backwards);
        assert!(ahead.contains(DVec3::new(0.2, 1.0, 0.5)));
        assert!(!ahead.contains(DVec3::new(0.2, 1.0, -0.5)));
        // Without a head (or one straight above the hips) the frame's forward is used.
        let no_head = Ahead::new(&hind, None, &backwards);
        assert!(no_head.contains(DVec3::new(0.2, 1.0, -0.5)));
        let above = Ahead::new(&hind, Some(DVec3::new(0.0, 2.0, 0.0)), &frame());
        assert!(above.contains(DVec3::new(0.2, 1.0, 0.5)));
    }

    #[test]
    fn a_mirror_pair_lies_on_both_sides_of_the_median_plane() {
        let arm = |x: f64| section_to(DVec3::new(0.2 * x, 1.0, 0.5), DVec3::new(0.3 * x, 0.6, 0.7));
        let (left, right) = (arm(1.0), arm(-1.0));
        assert!(mirror_pair(&left, &right, &frame(), DVec3::ZERO));
        // Both on one side, or one on the median plane (a jaw), or one twice as long: no pair.
        assert!(!mirror_pair(&left, &left, &frame(), DVec3::ZERO));
        let median = section_to(DVec3::new(0.0, 1.0, 0.5), DVec3::new(0.0, 0.6, 0.7));
        assert!(!mirror_pair(&left, &median, &frame(), DVec3::ZERO));
        let long = section_to(DVec3::new(-0.2, 1.0, 0.5), DVec3::new(-0.5, 0.0, 1.0));
        assert!(!mirror_pair(&left, &long, &frame(), DVec3::ZERO));
        // The plane through a centre off the origin.
        let shift = DVec3::new(1.0, 0.0, 0.0);
        let moved = |s: &Section| section_to(s.attachment + shift, s.distal + shift);
        assert!(mirror_pair(&moved(&left), &moved(&right), &frame(), shift));
    }
}

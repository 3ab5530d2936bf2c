//! The tail rule of the labelling (dissertation ch.7.3.3): the spine's continuation past the
//! pelvis.

use super::rules::{Assignment, UNLABELLED};
use super::{FigureClass, Frame, Label, LevelGraph, Section};
use glam::DVec3;

/// What the tail rule looks at.
pub(super) struct TailRule<'a> {
    pub graph: &'a LevelGraph,
    pub sections: &'a [Section],
    pub frame: &'a Frame,
    pub figure: FigureClass,
    /// The trunk's DMS voxel centres.
    pub trunk_points: &'a [DVec3],
    /// Leg pairs, most anterior first.
    pub pairs: &'a [(usize, usize)],
    /// Farthest a tail may join the trunk from the posterior pair, mesh units.
    pub limit: f64,
    /// Shortest tail, mesh units.
    pub min_length: f64,
}

impl TailRule<'_> {
    fn attachment(&self, s: usize) -> DVec3 {
        self.graph.vertices[self.sections[s].attachment_vertex].centroid
    }

    /// For an upright figure with arms: whether section `t` leaves the trunk nearer the height
    /// where its legs leave it than where its arms do, each measured where the section itself
    /// leaves the trunk (its top vertex), not at the trunk vertex it joins. A trunk vertex can
    /// span the whole lower back, so a backpack and the legs may join the same one; where they
    /// leave the trunk still tells a tail (at the crotch) from a backpack (between the
    /// shoulder blades). True for other figures.
    fn roots_nearer_the_legs(&self, t: usize, assign: &[Assignment]) -> bool {
        let up = self.frame.up;
        let root = |s: usize| self.sections[s].attachment.dot(up);
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        let arms: Vec<f64> = (0..assign.len())
            .filter(|&a| assign[a].label == Some(Label::Arm))
            .map(root)
            .collect();
        match (self.figure, self.pairs.last()) {
            (FigureClass::HumanLike, Some(&(a, b))) if !arms.is_empty() => {
                let (legs, arms, at) = (mean(&[root(a), root(b)]), mean(&arms), root(t));
                (at - legs).abs() < (at - arms).abs()
            }
            _ => true,
        }
    }

    /// The tail: of `candidates` (unlabelled sections) and the unpaired legs, the one reaching
    /// farthest back, when it extends rearward, is long enough, and roots at the pelvic end of
    /// the trunk: within the distance limit of the posterior pair's attachments and nearer to
    /// them than to the anterior end of the trunk (the fore pair's attachments, else the
    /// trunk's highest point for a human-like figure, its most forward point otherwise). A
    /// tail is the spine's continuation past the pelvis, so a protrusion from the upper back
    /// (a backpack, a head leaning back) or a shoulder (a T-posed arm) is never one; an upright
    /// figure's also leaves the trunk nearer its legs' roots than its arms'
    /// ([`Self::roots_nearer_the_legs`]).
    pub fn assign(
        &self,
        assign: &mut [Assignment],
        single_legs: &mut Vec<usize>,
        candidates: &[usize],
    ) {
        let (sections, frame) = (self.sections, self.frame);
        let mut candidates: Vec<usize> = candidates.to_vec();
        candidates.extend(single_legs.iter().copied());
        candidates.sort_by(|&a, &b| {
            sections[a]
                .reach
                .hindmost
                .total_cmp(&sections[b].reach.hindmost)
                .then(a.cmp(&b))
        });
        let Some(&t) = candidates.first() else {
            return;
        };
        let s = &sections[t];
        let attach = self.attachment(t);
        let mid = |&(a, b): &(usize, usize)| (self.attachment(a) + self.attachment(b)) / 2.0;
        let posterior = self.pairs.last().map(mid);
        // An upright figure's anterior end is where its arms join the trunk, when it has arms:
        // a tail roots nearer to the legs than to the arms.
        let arms: Vec<DVec3> = (0..assign.len())
            .filter(|&a| assign[a].label == Some(Label::Arm))
            .map(|a| self.attachment(a))
            .collect();
        let anterior = if self.pairs.len() >= 2 {
            self.pairs.first().map(mid)
        } else if self.figure == FigureClass::HumanLike && !arms.is_empty() {
            Some(arms.iter().sum::<DVec3>() / arms.len() as f64)
        } else {
            let towards = match self.figure {
                FigureClass::HumanLike => frame.up,
                _ => frame.forward,
            };
            self.trunk_points
                .iter()
                .copied()
                .max_by(|a, b| a.dot(towards).total_cmp(&b.dot(towards)))
        };
        let rearward = s.distal.dot(frame.forward) < attach.dot(frame.forward);
        let near = posterior.is_none_or(|p| p.distance(attach) <= self.limit);
        let pelvic_end = match (posterior, anterior) {
            (Some(p), Some(a)) => p.distance(attach) < a.distance(attach),
            _ => true,
        } && self.roots_nearer_the_legs(t, assign);
        let long = s.length >= self.min_length;
        if s.extreme.backward && rearward && near && pelvic_end && long {
            assign[t] = Assignment {
                label: Some(Label::Tail),
                ..UNLABELLED
            };
            single_legs.retain(|&l| l != t);
        }
    }
}

//! Labelling the level graph (dissertation ch.7.3.3): trunk, legs, wings, tail, head, arms,
//! leftovers.

use super::fore_limbs::{chest_junction, fore_pair, Ahead};
use super::sections::sections;
use super::tail::TailRule;
use super::trunk::{trunk, Trunk};
use super::{
    AnatomyWarning, FigureClass, Frame, Label, LevelGraph, LimbPair, Reach, RuleOptions, Section,
    Side,
};
use crate::medial::MedialSurface;
use glam::DVec3;

/// The label of one section, before parts are built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Assignment {
    /// `None`: merged into the trunk.
    pub label: Option<Label>,
    /// Side of a paired part.
    pub side: Option<Side>,
    /// Girdle of a limb.
    pub limb_pair: Option<LimbPair>,
    /// The pair partner (section index).
    pub partner: Option<usize>,
}

/// A section merged into the trunk (no label yet).
pub(super) const UNLABELLED: Assignment = Assignment {
    label: None,
    side: None,
    limb_pair: None,
    partner: None,
};

/// The labelled level graph before overrides.
#[derive(Debug, Clone)]
pub struct Draft {
    /// Figure class.
    pub figure: FigureClass,
    /// Trunk principal axis and its angle to up (degrees).
    pub trunk_axis: DVec3,
    /// Angle of the trunk axis to up, degrees.
    pub trunk_angle: f64,
    /// Whether each level-graph vertex belongs to the trunk proper.
    pub trunk: Vec<bool>,
    /// The sections.
    pub sections: Vec<Section>,
    /// One assignment per section.
    pub assignments: Vec<Assignment>,
    /// What could not be identified.
    pub warnings: Vec<AnatomyWarning>,
}

/// The median plane a pair's two parts mirror each other across: through `centre`, normal
/// `left`.
#[derive(Debug, Clone, Copy)]
pub(super) struct MedianPlane {
    pub centre: DVec3,
    pub left: DVec3,
}

impl MedianPlane {
    /// The plane through `centre` across `frame`'s left.
    pub fn new(frame: &Frame, centre: DVec3) -> Self {
        Self {
            centre,
            left: frame.left,
        }
    }

    /// How far `p` lies off the plane, signed (positive on the left).
    pub fn offset(&self, p: DVec3) -> f64 {
        (p - self.centre).dot(self.left)
    }

    /// The mirror image of `p` across the plane.
    pub fn reflect(&self, p: DVec3) -> DVec3 {
        p - self.left * (2.0 * self.offset(p))
    }

    /// The distance of `a` from the mirror image of `b` (symmetric in `a` and `b`).
    fn mirror_distance(&self, a: DVec3, b: DVec3) -> f64 {
        a.distance(self.reflect(b))
    }
}

/// Greedy pairing of `items` (section indices): paired parts mirror each other across the
/// median plane, so the pair whose attachments (where they leave the trunk) are nearest to each
/// other's mirror image first, the pairs `preferred` accepts before all others; ties by the
/// attachment distance. Only parts whose trunk vertices lie within `max_distance` of each other
/// pair. Returns the pairs and the unpaired items.
///
/// Mirroring, not the attachments' distance, tells the partner: the legs along one side of a
/// spider or an insect leave the trunk closer to each other than to their partners across it.
fn pair_up(
    items: &[usize],
    sections: &[Section],
    graph: &LevelGraph,
    plane: MedianPlane,
    max_distance: f64,
    preferred: &dyn Fn(&Section, &Section) -> bool,
) -> (Vec<(usize, usize)>, Vec<usize>) {
    let mut candidates = Vec::new();
    for (i, &a) in items.iter().enumerate() {
        for &b in &items[i + 1..] {
            let (sa, sb) = (&sections[a], &sections[b]);
            let d = graph.vertices[sa.attachment_vertex]
                .centroid
                .distance(graph.vertices[sb.attachment_vertex].centroid);
            let mirror = plane.mirror_distance(sa.attachment, sb.attachment);
            let d2 = sa.attachment.distance(sb.attachment);
            if d <= max_distance {
                candidates.push((!preferred(sa, sb), mirror, d, d2, a, b));
            }
        }
    }
    candidates.sort_by(|x, y| {
        x.0.cmp(&y.0)
            .then(x.1.total_cmp(&y.1))
            .then(x.2.total_cmp(&y.2))
            .then(x.3.total_cmp(&y.3))
            .then((x.4, x.5).cmp(&(y.4, y.5)))
    });
    let mut used = vec![false; sections.len()];
    let mut pairs = Vec::new();
    for (_, _, _, _, a, b) in candidates {
        if !used[a] && !used[b] {
            used[a] = true;
            used[b] = true;
            pairs.push((a, b));
        }
    }
    let rest = items.iter().copied().filter(|&i| !used[i]).collect();
    (pairs, rest)
}

/// Whether two sections are of comparable length, the shorter at least half the longer: the
/// limbs of a pair mirror each other ([`mirrored`] asks the same).
fn comparable_length(a: &Section, b: &Section) -> bool {
    a.length.min(b.length) >= 0.5 * a.length.max(b.length)
}

/// How many of `pairs` leg pairs, ordered front to back, are fore legs: the anterior half
/// (rounded down), so one pair is a biped's hind legs, two a quadruped's fore and hind legs,
/// an insect's three one fore pair and two hind, a spider's four two and two. The region rule
/// of reference rigs (`reference.rs`) divides unnamed leg chains the same way.
pub(crate) fn fore_pairs(pairs: usize) -> usize {
    pairs / 2
}

/// Any two sections may pair.
fn any_pair(_: &Section, _: &Section) -> bool {
    true
}

/// Left/right of a pair: the one whose voxels lie farther along `left` is L.
fn sides(a: usize, b: usize, sections: &[Section], frame: &Frame) -> [(usize, Side); 2] {
    let la = sections[a].mean.dot(frame.left);
    let lb = sections[b].mean.dot(frame.left);
    if la >= lb {
        [(a, Side::Left), (b, Side::Right)]
    } else {
        [(a, Side::Right), (b, Side::Left)]
    }
}

/// Whether section `s` has a mirror partner among `candidates`: another section of comparable
/// length (within a factor of two) whose voxel mean, reflected across the median plane through
/// `centre` (normal `left`), lies within a third of the longer one's length of `s`'s mean, with
/// `s` off that plane by more than the same tolerance (a median part mirrors onto itself).
fn mirrored(
    s: usize,
    candidates: &[usize],
    sections: &[Section],
    frame: &Frame,
    centre: DVec3,
) -> bool {
    let a = &sections[s];
    let plane = MedianPlane::new(frame, centre);
    candidates.iter().any(|&t| {
        let b = &sections[t];
        let longer = a.length.max(b.length);
        let tolerance = longer / 3.0;
        let comparable = comparable_length(a, b);
        let reflected = plane.reflect(b.mean);
        t != s
            && comparable
            && plane.offset(a.mean).abs() > tolerance
            && reflected.distance(a.mean) <= tolerance
    })
}

/// Whether another of `candidates` mirrors section `s` across `plane`: of comparable length,
/// its voxel mean's mirror image within a third of the longer's length of `s`'s mean and nearer
/// to it than half their distance (two sections on the plane mirror each other only
/// trivially).
fn has_mirror_image(
    s: usize,
    candidates: &[usize],
    sections: &[Section],
    plane: MedianPlane,
) -> bool {
    let a = &sections[s];
    candidates.iter().any(|&t| {
        let b = &sections[t];
        let reflected = plane.reflect(b.mean).distance(a.mean);
        t != s
            && comparable_length(a, b)
            && reflected <= a.length.max(b.length) / 3.0
            && reflected < 0.5 * a.mean.distance(b.mean)
    })
}

/// Whether a section leaves the trunk the way a rest-pose arm does: from its attachment to its
/// distal end it goes at least as far sideways or down as it goes up, and as it goes forward.
fn reaches_like_an_arm(section: &Section, frame: &Frame) -> bool {
    let d = section.distal - section.attachment;
    let (side, up, forward) = (
        d.dot(frame.left).abs(),
        d.dot(frame.up),
        d.dot(frame.forward).abs(),
    );
    let out = side.max(-up);
    out >= up && out >= forward
}

/// Labels the level graph (ch.7.3.3), a phase per step: the trunk and the figure class
/// (`trunk.rs`), the sections hanging off the trunk (`sections.rs`), then legs, wings, the tail
/// (an animal's before the head, a human-like figure's after the head and the arms), the head,
/// the lower jaw, arms (none on an animal standing on two leg pairs), an animal biped's short fore limbs
/// (`fore_limbs.rs`), lone arms, unpaired legs, and the leftovers merged into the trunk.
///
/// An animal standing on one leg pair whose short fore limbs branch off the head's section
/// (the heart at the hips ends the trunk there) is labelled again with the trunk carried on to
/// where they branch (`fore_limbs::chest_junction`); the second labelling is kept when it finds them.
pub fn label_graph(
    graph: &LevelGraph,
    surface: &MedialSurface,
    frame: &Frame,
    options: &RuleOptions,
) -> Draft {
    let mut trunk = trunk(graph, surface, frame, options);
    let draft = label_with_trunk(graph, surface, frame, options, &trunk);
    let Some(junction) = chest_of_a_biped(&draft, graph, surface, frame, trunk.centre()) else {
        return draft;
    };
    trunk.extend_to(junction, graph, surface);
    let extended = label_with_trunk(graph, surface, frame, options, &trunk);
    if fore_limbs_of(&extended) == 2 {
        extended
    } else {
        draft
    }
}

/// Sections labelled as a fore limb (leg or arm of the fore girdle) in `draft`.
fn fore_limbs_of(draft: &Draft) -> usize {
    draft
        .assignments
        .iter()
        .filter(|a| a.label.is_some_and(Label::is_limb) && a.limb_pair == Some(LimbPair::Fore))
        .count()
}

/// Where the trunk of an animal biped (animal-like, one leg pair, no fore limbs, a head) should
/// be carried on so that short fore limbs branching off the head's section become sections:
/// [`chest_junction`] of the head's section ahead of the hind legs' attachment. `None` for
/// every other figure.
fn chest_of_a_biped(
    draft: &Draft,
    graph: &LevelGraph,
    surface: &MedialSurface,
    frame: &Frame,
    centre: DVec3,
) -> Option<usize> {
    let labelled = |label: Label| {
        (0..draft.sections.len()).filter(move |&s| draft.assignments[s].label == Some(label))
    };
    let legs: Vec<usize> = labelled(Label::Leg).collect();
    let paired = legs.len() == 2 && legs.iter().all(|&s| draft.assignments[s].partner.is_some());
    if draft.figure != FigureClass::AnimalLike
        || !paired
        || fore_limbs_of(draft) > 0
        || labelled(Label::Arm).next().is_some()
        || labelled(Label::Wing).next().is_some()
    {
        return None;
    }
    let head = labelled(Label::Head).next()?;
    let hind: Vec<DVec3> = legs
        .iter()
        .map(|&s| graph.vertices[draft.sections[s].attachment_vertex].centroid)
        .collect();
    let ahead = Ahead::new(&hind, Some(draft.sections[head].distal), frame);
    let loose: Vec<&Section> = (0..draft.sections.len())
        .filter(|&s| draft.assignments[s].label.is_none() && !draft.sections[s].insignificant)
        .map(|s| &draft.sections[s])
        .collect();
    chest_junction(
        graph,
        surface,
        &draft.sections[head],
        &loose,
        frame,
        centre,
        &ahead,
    )
}

/// [`label_graph`]'s phases on a given trunk.
fn label_with_trunk(
    graph: &LevelGraph,
    surface: &MedialSurface,
    frame: &Frame,
    options: &RuleOptions,
    trunk: &Trunk,
) -> Draft {
    let mut warnings = Vec::new();
    if !trunk.has_junction {
        warnings.push(AnatomyWarning::NoMajorJunction);
    }
    let sections = sections(graph, surface, &trunk.vertices);
    let mut rules = Rules {
        graph,
        sections: &sections,
        frame,
        options,
        figure: trunk.figure,
        radius: graph.heart_radius.max(f64::MIN_POSITIVE),
        significant: (0..sections.len())
            .filter(|&s| !sections[s].insignificant)
            .collect(),
        assign: vec![UNLABELLED; sections.len()],
        warnings,
    };

    let centre = trunk.centre();
    let mut legs = rules.legs(centre);
    rules.wings(centre);
    // Tail: an animal's before the head (its tail may reach as high as its head); a human-like
    // figure's after the head and the arms, which it may never take (a T-posed arm reaching
    // back, a head leaning back).
    // The tail looks at the leg pairs found so far (the fore limbs found later are ahead).
    let leg_pairs = legs.pairs.clone();
    let tail = TailRule {
        graph,
        sections: &sections,
        frame,
        figure: trunk.figure,
        trunk_points: &trunk.points,
        pairs: &leg_pairs,
        limit: options.tail_distance * rules.radius,
        min_length: options.tail_length * rules.radius,
    };
    let human_like = trunk.figure == FigureClass::HumanLike;
    if !human_like {
        rules.tail(&tail, &mut legs.single);
    }
    rules.head(trunk.has_junction, centre);
    rules.jaw(centre);
    // An animal standing on two leg pairs has no further limb pair of a vertebrate body plan:
    // its other paired protrusions (ears, horns, antlers, a thigh's bulge) are not arms.
    let arms = if trunk.figure == FigureClass::AnimalLike && legs.pairs.len() >= 2 {
        Vec::new()
    } else {
        rules.arms(centre)
    };
    if trunk.figure == FigureClass::AnimalLike && legs.pairs.len() == 1 {
        rules.short_fore_limbs(&mut legs, centre);
    }
    if human_like {
        rules.tail(&tail, &mut legs.single);
        rules.lone_arms(&arms, centre);
    }
    rules.unpaired_legs(&legs, centre);
    rules.leg_warnings(&legs, trunk.has_junction);
    rules.leftovers();

    let Rules {
        assign, warnings, ..
    } = rules;
    Draft {
        figure: trunk.figure,
        trunk_axis: trunk.axis,
        trunk_angle: trunk.angle,
        trunk: trunk.vertices.clone(),
        sections,
        assignments: assign,
        warnings,
    }
}

/// The labelled legs.
struct Legs {
    /// Leg pairs, most anterior first.
    pairs: Vec<(usize, usize)>,
    /// Legs without a partner.
    single: Vec<usize>,
}

/// The labelling in progress: the sections, one assignment per section, the warnings.
struct Rules<'a> {
    graph: &'a LevelGraph,
    sections: &'a [Section],
    frame: &'a Frame,
    options: &'a RuleOptions,
    figure: FigureClass,
    /// The heart radius (mesh units, positive): the unit of the length thresholds.
    radius: f64,
    /// The significant sections.
    significant: Vec<usize>,
    assign: Vec<Assignment>,
    warnings: Vec<AnatomyWarning>,
}

impl Rules<'_> {
    /// The significant sections without a label yet.
    fn unlabelled(&self) -> Vec<usize> {
        self.significant
            .iter()
            .copied()
            .filter(|&s| self.assign[s].label.is_none())
            .collect()
    }

    /// The median plane through `centre`.
    fn median(&self, centre: DVec3) -> MedianPlane {
        MedianPlane::new(self.frame, centre)
    }

    /// Labels both sections of a pair, left and right by [`sides`].
    fn label_pair(&mut self, (a, b): (usize, usize), label: Label, pair: LimbPair) {
        for (s, side) in sides(a, b, self.sections, self.frame) {
            self.assign[s] = Assignment {
                label: Some(label),
                side: Some(side),
                limb_pair: Some(pair),
                partner: Some(if s == a { b } else { a }),
            };
        }
    }

    /// Projection of a section's attachment vertex on the figure's anterior direction (up for
    /// a human-like figure, forward otherwise).
    fn anterior(&self, s: usize) -> f64 {
        let a = self.graph.vertices[self.sections[s].attachment_vertex].centroid;
        match self.figure {
            FigureClass::HumanLike => a.dot(self.frame.up),
            _ => a.dot(self.frame.forward),
        }
    }

    /// Legs: sections reaching the bottom of the figure, paired by where they join the trunk.
    /// With two or more pairs the anterior half of them are fore, the others hind
    /// ([`fore_pairs`]). Paired limbs
    /// mirror each other across the median plane (through `centre`): a section reaching the
    /// back of the figure along that plane (a tail resting on the ground) is nobody's partner
    /// and stays single, for the tail rule to consider.
    fn legs(&mut self, centre: DVec3) -> Legs {
        let legs: Vec<usize> = self
            .unlabelled()
            .into_iter()
            .filter(|&s| self.sections[s].extreme.down)
            .collect();
        let (median, lateral): (Vec<usize>, Vec<usize>) = legs.iter().partition(|&&s| {
            self.sections[s].extreme.backward && self.on_median_plane(s, &legs, centre)
        });
        // Paired limbs mirror each other: of comparable length, on either side of the median
        // plane (an arm hanging beside its own leg may join the trunk at the same place).
        let plane = self.median(centre);
        let across = |a: &Section, b: &Section| {
            comparable_length(a, b) && plane.offset(a.mean) * plane.offset(b.mean) < 0.0
        };
        let (mut pairs, mut single) = pair_up(
            &lateral,
            self.sections,
            self.graph,
            plane,
            f64::INFINITY,
            &across,
        );
        // Beside a biped's one leg pair, a lateral section reaching down less than half as
        // long as its shorter leg is a fold or stub (a skirt's at the hip), not a leg: it
        // stays unlabelled. Figures of more leg pairs (spiders) keep their odd legs.
        if let [(a, b)] = pairs[..] {
            let shorter = self.sections[a].length.min(self.sections[b].length);
            single.retain(|&s| self.sections[s].length >= 0.5 * shorter);
        }
        single.extend(median);
        pairs.sort_by(|x, y| {
            (self.anterior(y.0) + self.anterior(y.1))
                .total_cmp(&(self.anterior(x.0) + self.anterior(x.1)))
        });
        // An upright figure stands on its lowest pair: another pair joining the trunk above
        // it is a pair of arms hanging down (an A-pose on short legs reaches the ground's
        // band), left for the arm rule; a pelvis is never above the arm roots.
        if self.figure == FigureClass::HumanLike {
            self.keep_standing_pair(&mut pairs);
        }
        let fore = fore_pairs(pairs.len());
        for (k, &pair) in pairs.iter().enumerate() {
            let limb_pair = if k < fore {
                LimbPair::Fore
            } else {
                LimbPair::Hind
            };
            self.label_pair(pair, Label::Leg, limb_pair);
        }
        for &s in &single {
            self.assign[s] = Assignment {
                label: Some(Label::Leg),
                ..UNLABELLED
            };
        }
        Legs { pairs, single }
    }

    /// Of several leg pairs of an upright figure, keeps the one it stands on (the lowest
    /// reach) and the pairs joining the trunk no higher than it; the pairs joining higher up
    /// (arms hanging into the ground's band) are dropped, unlabelled.
    fn keep_standing_pair(&self, pairs: &mut Vec<(usize, usize)>) {
        let lowest = |&(a, b): &(usize, usize)| {
            self.sections[a]
                .reach
                .lowest
                .min(self.sections[b].reach.lowest)
        };
        // Where each section itself leaves the trunk: an arm and a leg on one side can share
        // the level-graph vertex they branch from.
        let up = self.frame.up;
        let height = |&(a, b): &(usize, usize)| {
            0.5 * (self.sections[a].attachment + self.sections[b].attachment).dot(up)
        };
        let Some(standing) = pairs
            .iter()
            .min_by(|x, y| lowest(x).total_cmp(&lowest(y)))
            .copied()
        else {
            return;
        };
        let base = height(&standing);
        pairs.retain(|p| *p == standing || height(p) <= base);
    }

    /// Whether section `s` lies on the median plane through `centre` (normal `left`) where the
    /// other sections of `among` stand off it: its voxel mean and its distal end are nearer to
    /// the plane than a quarter of the farthest other section's mean. Paired limbs stand off
    /// the plane by about the trunk's half-width on both sides; a median part mirrors onto
    /// itself. Never with no other section to compare with.
    fn on_median_plane(&self, s: usize, among: &[usize], centre: DVec3) -> bool {
        let plane = self.median(centre);
        let offset = |p: DVec3| plane.offset(p).abs();
        let apart = among
            .iter()
            .filter(|&&t| t != s)
            .map(|&t| offset(self.sections[t].mean))
            .fold(0.0, f64::max);
        let section = &self.sections[s];
        let tolerance = 0.25 * apart;
        apart > 0.0 && offset(section.mean) < tolerance && offset(section.distal) < tolerance
    }

    /// Wings: long sections with mostly linear cross-sections, in pairs.
    fn wings(&mut self, centre: DVec3) {
        let (options, radius) = (self.options, self.radius);
        let wings: Vec<usize> = self
            .unlabelled()
            .into_iter()
            .filter(|&s| {
                self.sections[s].linear_fraction >= options.wing_fraction
                    && self.sections[s].length >= options.limb_length * radius
            })
            .collect();
        let (pairs, _) = pair_up(
            &wings,
            self.sections,
            self.graph,
            self.median(centre),
            f64::INFINITY,
            &any_pair,
        );
        for pair in pairs {
            self.label_pair(pair, Label::Wing, LimbPair::Fore);
        }
    }

    /// The tail among the unlabelled sections and the unpaired legs ([`TailRule::assign`]).
    fn tail(&mut self, rule: &TailRule, single_legs: &mut Vec<usize>) {
        let candidates = self.unlabelled();
        rule.assign(&mut self.assign, single_legs, &candidates);
    }

    /// Head: the unlabelled section reaching farthest up (human-like), forward (animal-like),
    /// else both; none without a major junction. The head is the figure's one median part: a
    /// section mirrored by another across the median plane (through `centre`) is one of a pair
    /// (ears, horns, raised arms) and is not taken while an unpaired section remains. A
    /// human-like figure's unpaired section standing off the plane is not taken while one on it
    /// remains (mean and tip within a third of its length of the plane, as
    /// [`jaw`](Self::jaw)'s): quaternius_platformer_character with its arms 45 degrees down had
    /// one ear merged into its big head and took the other for the head (20 % of the height
    /// off). An animal's head may turn to one side.
    fn head(&mut self, has_junction: bool, centre: DVec3) {
        let all = self
            .sections
            .iter()
            .fold(Reach::EMPTY, |r, s| r.union(s.reach));
        let score = |s: usize| -> f64 {
            let reach = &self.sections[s].reach;
            let up =
                (reach.highest - all.lowest) / (all.highest - all.lowest).max(f64::MIN_POSITIVE);
            let fw = (reach.foremost - all.hindmost)
                / (all.foremost - all.hindmost).max(f64::MIN_POSITIVE);
            match self.figure {
                FigureClass::HumanLike => up,
                FigureClass::AnimalLike => fw,
                FigureClass::Unknown => up + fw,
            }
        };
        let candidates = self.unlabelled();
        let unpaired: Vec<usize> = candidates
            .iter()
            .copied()
            .filter(|&s| !mirrored(s, &candidates, self.sections, self.frame, centre))
            .collect();
        let pool = if unpaired.is_empty() {
            candidates
        } else {
            unpaired
        };
        // An upright figure's head mirrors onto itself: an unpaired section standing off the
        // median plane is one of a pair whose partner merged into the trunk (a big head's ear),
        // not the head, while a section on the plane remains.
        let plane = self.median(centre);
        let on_plane: Vec<usize> = pool
            .iter()
            .copied()
            .filter(|&s| {
                let section = &self.sections[s];
                [section.mean, section.distal]
                    .iter()
                    .all(|&p| plane.offset(p).abs() <= section.length / 3.0)
            })
            .collect();
        let pool = if self.figure == FigureClass::HumanLike && !on_plane.is_empty() {
            on_plane
        } else {
            pool
        };
        let head = pool
            .into_iter()
            .max_by(|&a, &b| score(a).total_cmp(&score(b)).then(b.cmp(&a)));
        match head {
            Some(h) if has_junction => {
                self.assign[h] = Assignment {
                    label: Some(Label::Head),
                    ..UNLABELLED
                }
            }
            _ => self.warnings.push(AnatomyWarning::NoHead),
        }
    }

    /// The lower jaw: beside the head, an unlabelled significant section leaving the trunk
    /// where the head does (the same trunk vertex), on the median plane (its voxel mean and its
    /// tip within a third of its length of the plane through `centre`: a lone arm whose partner
    /// is missing stands off it), reaching the front of the figure, its tip below the head's
    /// (an open mouth's mandible), and with no mirror image among the other candidates
    /// ([`has_mirror_image`]: arms hanging close against the body, cut apart from it by
    /// [`super::separate_arms`], leave the trunk where the head does too). Without it the
    /// mandible merges into the trunk. The longest such section.
    fn jaw(&mut self, centre: DVec3) {
        let Some(head) =
            (0..self.sections.len()).find(|&s| self.assign[s].label == Some(Label::Head))
        else {
            return;
        };
        let h = &self.sections[head];
        let up = self.frame.up;
        let plane = self.median(centre);
        let candidates = self.unlabelled();
        let jaw = candidates
            .iter()
            .copied()
            .filter(|&s| {
                let section = &self.sections[s];
                section.attachment_vertex == h.attachment_vertex
                    && section.extreme.forward
                    && section.distal.dot(up) < h.distal.dot(up)
                    && [section.mean, section.distal]
                        .iter()
                        .all(|&p| plane.offset(p).abs() <= section.length / 3.0)
                    && !has_mirror_image(s, &candidates, self.sections, plane)
            })
            .max_by(|&a, &b| {
                self.sections[a]
                    .length
                    .total_cmp(&self.sections[b].length)
                    .then(b.cmp(&a))
            });
        if let Some(s) = jaw {
            self.assign[s] = Assignment {
                label: Some(Label::Jaw),
                ..UNLABELLED
            };
        }
    }

    /// Arms: remaining long sections joining the trunk at about the same place, in pairs.
    /// Returns the long sections (the candidates, paired or not).
    fn arms(&mut self, centre: DVec3) -> Vec<usize> {
        let (options, radius) = (self.options, self.radius);
        let arms: Vec<usize> = self
            .unlabelled()
            .into_iter()
            .filter(|&s| self.sections[s].length >= options.limb_length * radius)
            .collect();
        let (pairs, _) = pair_up(
            &arms,
            self.sections,
            self.graph,
            self.median(centre),
            options.pair_distance * radius,
            &any_pair,
        );
        // In a rest pose (T, A or arms down) arms reach sideways or down from the trunk, not
        // up or forward: with several candidate pairs, those that point up (ears, horns) or
        // forward (a snout, a visor) are not arms while a sideways or hanging pair remains.
        let human_like = self.figure == FigureClass::HumanLike;
        let rest_pose = |&(a, b): &(usize, usize)| {
            [a, b]
                .iter()
                .all(|&s| reaches_like_an_arm(&self.sections[s], self.frame))
        };
        let keep: Vec<(usize, usize)> = if human_like && pairs.iter().any(rest_pose) {
            pairs.into_iter().filter(rest_pose).collect()
        } else {
            pairs
        };
        for pair in keep {
            self.label_pair(pair, Label::Arm, LimbPair::Fore);
        }
        arms
    }

    /// The short fore limbs of an animal on one leg pair (`legs`) with no arms or wings (a
    /// bird's fore limbs are its wings): the
    /// [`fore_pair`] among the unlabelled significant sections, ahead of the hind legs'
    /// attachment, labelled as the fore leg pair (the quadruped template's fore-leg chain) and
    /// put first in `legs.pairs`. No length threshold: bilateral symmetry, not length, tells a
    /// limb pair from a bump (issue 21).
    fn short_fore_limbs(&mut self, legs: &mut Legs, centre: DVec3) {
        if self
            .assign
            .iter()
            .any(|a| matches!(a.label, Some(Label::Arm | Label::Wing)))
        {
            return;
        }
        let Some(&(h0, h1)) = legs.pairs.first() else {
            return;
        };
        let hind =
            [h0, h1].map(|s| self.graph.vertices[self.sections[s].attachment_vertex].centroid);
        let head = (0..self.sections.len())
            .find(|&s| self.assign[s].label == Some(Label::Head))
            .map(|s| self.sections[s].distal);
        let ahead = Ahead::new(&hind, head, self.frame);
        let candidates = self.unlabelled();
        if let Some(pair) = fore_pair(
            &candidates,
            self.sections,
            self.graph,
            self.frame,
            centre,
            &ahead,
        ) {
            self.label_pair(pair, Label::Leg, LimbPair::Fore);
            legs.pairs.insert(0, pair);
        }
    }

    /// Left or right of the trunk's centre line (through `centre`).
    fn side_of(&self, s: usize, centre: DVec3) -> Side {
        if self.median(centre).offset(self.sections[s].mean) >= 0.0 {
            Side::Left
        } else {
            Side::Right
        }
    }

    /// A lone arm of a human-like figure: a long section (of `arms`) left unpaired that joins
    /// the upper half of the trunk (its partner is missing, or too far away to pair).
    /// Once a pair of arms is labelled, a section pointing up or forward (see
    /// [`reaches_like_an_arm`]) is not a lone arm.
    fn lone_arms(&mut self, arms: &[usize], centre: DVec3) {
        let paired = self.assign.iter().any(|a| a.label == Some(Label::Arm));
        for &s in arms {
            if self.assign[s].label.is_none()
                && self.sections[s].attachment.dot(self.frame.up) > centre.dot(self.frame.up)
                && (!paired || reaches_like_an_arm(&self.sections[s], self.frame))
            {
                let side = self.side_of(s, centre);
                self.assign[s] = Assignment {
                    label: Some(Label::Arm),
                    side: Some(side),
                    limb_pair: Some(LimbPair::Fore),
                    partner: None,
                };
                self.warnings
                    .push(AnatomyWarning::SingleArm { section: s, side });
            }
        }
    }

    /// Unpaired legs: side from the trunk's centre line, girdle from the nearest leg pair.
    fn unpaired_legs(&mut self, legs: &Legs, centre: DVec3) {
        let sections = self.sections;
        for &s in &legs.single {
            self.assign[s].side = Some(self.side_of(s, centre));
            let nearest = legs.pairs.iter().min_by(|x, y| {
                let dx = sections[x.0].attachment.distance(sections[s].attachment);
                let dy = sections[y.0].attachment.distance(sections[s].attachment);
                dx.total_cmp(&dy)
            });
            self.assign[s].limb_pair = nearest
                .and_then(|&(a, _)| self.assign[a].limb_pair)
                .or(Some(LimbPair::Hind));
        }
    }

    /// Warnings for an odd number of legs, more than two leg pairs, or no legs.
    fn leg_warnings(&mut self, legs: &Legs, has_junction: bool) {
        let leg_count = self
            .assign
            .iter()
            .filter(|a| a.label == Some(Label::Leg))
            .count();
        if leg_count % 2 == 1 {
            self.warnings.push(AnatomyWarning::OddLegs {
                legs: leg_count,
                unpaired: legs.single.len(),
            });
        }
        if legs.pairs.len() > 2 {
            self.warnings.push(AnatomyWarning::TooManyLegPairs {
                pairs: legs.pairs.len(),
            });
        }
        if leg_count == 0 && has_junction {
            self.warnings.push(AnatomyWarning::NoLegs);
        }
    }

    /// Leftovers stay merged into the trunk; long ones are named for the user.
    fn leftovers(&mut self) {
        for s in self.unlabelled() {
            let section = &self.sections[s];
            if section.length >= self.options.leftover_length * self.radius {
                self.warnings.push(AnatomyWarning::UnidentifiedProtrusion {
                    section: s,
                    voxels: section.voxels,
                    reach: section.distal,
                });
            }
        }
    }
}

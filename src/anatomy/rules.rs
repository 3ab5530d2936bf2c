//! Labelling the level graph (dissertation ch.7.3.3): trunk, legs, wings, tail, head, arms,
//! leftovers.

use super::{
    AnatomyWarning, FigureClass, Frame, Label, LevelGraph, LimbPair, RuleOptions, Section, Side,
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

const UNLABELLED: Assignment = Assignment {
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

/// Sections of `graph` given its trunk vertices: every non-trunk child of a trunk vertex roots
/// one section.
pub fn sections(graph: &LevelGraph, surface: &MedialSurface, trunk: &[bool]) -> Vec<Section> {
    let mut out = Vec::new();
    for t in 0..graph.vertices.len() {
        if !trunk[t] {
            continue;
        }
        for &c in &graph.vertices[t].children {
            if trunk[c] {
                continue;
            }
            let vertices = graph.subtree(c);
            let mut count = 0usize;
            let mut sum = DVec3::ZERO;
            let mut reach = [
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
            ];
            let mut extreme = [false; 4];
            let (mut best, mut best_h) = (DVec3::ZERO, f64::NEG_INFINITY);
            let (mut significant, mut linear) = (0usize, 0usize);
            for &v in &vertices {
                let lv = &graph.vertices[v];
                let m = lv.marks;
                for (e, b) in extreme
                    .iter_mut()
                    .zip([m.up, m.down, m.forward, m.backward])
                {
                    *e |= b;
                }
                if !lv.insignificant {
                    significant += 1;
                    linear += usize::from(m.linear);
                }
                let r = lv.reach;
                reach = [
                    reach[0].max(r[0]),
                    reach[1].min(r[1]),
                    reach[2].max(r[2]),
                    reach[3].min(r[3]),
                ];
                for &p in &lv.voxels {
                    let x = surface.centre(p);
                    count += 1;
                    sum += x;
                    let h = graph.heart_values[p];
                    if h > best_h {
                        (best, best_h) = (x, h);
                    }
                }
            }
            let top = &graph.vertices[c];
            out.push(Section {
                top: c,
                attachment_vertex: t,
                voxels: count,
                weight: top.weight,
                attachment: top.centroid,
                distal: best,
                length: best.distance(graph.vertices[t].centroid),
                mean: sum / count.max(1) as f64,
                reach,
                extreme,
                linear_fraction: if significant > 0 {
                    linear as f64 / significant as f64
                } else {
                    0.0
                },
                insignificant: top.insignificant,
                vertices,
            });
        }
    }
    out
}

/// Principal axis (unit) of `points` by power iteration on their covariance, deterministic.
fn principal_axis(points: &[DVec3]) -> DVec3 {
    if points.len() < 2 {
        return DVec3::ZERO;
    }
    let mean = points.iter().sum::<DVec3>() / points.len() as f64;
    let mut cov = [[0.0f64; 3]; 3];
    for p in points {
        let d = (*p - mean).to_array();
        for i in 0..3 {
            for j in 0..3 {
                cov[i][j] += d[i] * d[j];
            }
        }
    }
    let m = glam::DMat3::from_cols_array_2d(&cov);
    let mut v = DVec3::new(1.0, 0.7, 0.3).normalize();
    for _ in 0..100 {
        match (m * v).try_normalize() {
            Some(next) => v = next,
            None => return DVec3::ZERO,
        }
    }
    v
}

/// Greedy pairing of `items` (section indices) by attachment distance: the closest pair first.
/// Returns the pairs and the unpaired items.
fn pair_up(
    items: &[usize],
    sections: &[Section],
    graph: &LevelGraph,
    max_distance: f64,
) -> (Vec<(usize, usize)>, Vec<usize>) {
    let mut candidates = Vec::new();
    for (i, &a) in items.iter().enumerate() {
        for &b in &items[i + 1..] {
            let (sa, sb) = (&sections[a], &sections[b]);
            let d = graph.vertices[sa.attachment_vertex]
                .centroid
                .distance(graph.vertices[sb.attachment_vertex].centroid);
            let d2 = sa.attachment.distance(sb.attachment);
            if d <= max_distance {
                candidates.push((d, d2, a, b));
            }
        }
    }
    candidates.sort_by(|x, y| {
        x.0.total_cmp(&y.0)
            .then(x.1.total_cmp(&y.1))
            .then((x.2, x.3).cmp(&(y.2, y.3)))
    });
    let mut used = vec![false; sections.len()];
    let mut pairs = Vec::new();
    for (_, _, a, b) in candidates {
        if !used[a] && !used[b] {
            used[a] = true;
            used[b] = true;
            pairs.push((a, b));
        }
    }
    let rest = items.iter().copied().filter(|&i| !used[i]).collect();
    (pairs, rest)
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

/// What the tail rule looks at.
struct TailContext<'a> {
    graph: &'a LevelGraph,
    sections: &'a [Section],
    frame: &'a Frame,
    figure: FigureClass,
    trunk_points: &'a [DVec3],
    /// Leg pairs, most anterior first.
    pairs: &'a [(usize, usize)],
    /// Farthest a tail may join the trunk from the posterior pair, mesh units.
    limit: f64,
    /// Shortest tail, mesh units.
    min_length: f64,
}

impl TailContext<'_> {
    fn attachment(&self, s: usize) -> DVec3 {
        self.graph.vertices[self.sections[s].attachment_vertex].centroid
    }

    /// The tail: of `candidates` (unlabelled sections) and the unpaired legs, the one reaching
    /// farthest back, when it extends rearward, is long enough, and roots at the pelvic end of
    /// the trunk: within the distance limit of the posterior pair's attachments and nearer to
    /// them than to the anterior end of the trunk (the fore pair's attachments, else the
    /// trunk's highest point for a human-like figure, its most forward point otherwise). A
    /// tail is the spine's continuation past the pelvis, so a protrusion from the upper back
    /// (a backpack, a head leaning back) or a shoulder (a T-posed arm) is never one.
    fn assign(
        &self,
        assign: &mut [Assignment],
        single_legs: &mut Vec<usize>,
        candidates: &[usize],
    ) {
        let (sections, frame) = (self.sections, self.frame);
        let mut candidates: Vec<usize> = candidates.to_vec();
        candidates.extend(single_legs.iter().copied());
        candidates.sort_by(|&a, &b| {
            sections[a].reach[3]
                .total_cmp(&sections[b].reach[3])
                .then(a.cmp(&b))
        });
        let Some(&t) = candidates.first() else {
            return;
        };
        let s = &sections[t];
        let attach = self.attachment(t);
        let mid = |&(a, b): &(usize, usize)| (self.attachment(a) + self.attachment(b)) / 2.0;
        let posterior = self.pairs.last().map(mid);
        let anterior = if self.pairs.len() >= 2 {
            self.pairs.first().map(mid)
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
        };
        let long = s.length >= self.min_length;
        if s.extreme[3] && rearward && near && pelvic_end && long {
            assign[t] = Assignment {
                label: Some(Label::Tail),
                ..UNLABELLED
            };
            single_legs.retain(|&l| l != t);
        }
    }
}

/// Labels the level graph (ch.7.3.3). `trunk_centre` is used for the side of unpaired limbs.
pub fn label_graph(
    graph: &LevelGraph,
    surface: &MedialSurface,
    frame: &Frame,
    options: &RuleOptions,
) -> Draft {
    let mut warnings = Vec::new();
    let n = graph.vertices.len();
    let radius = graph.heart_radius.max(f64::MIN_POSITIVE);
    // The trunk: the major junctions, the root, and the tree paths joining them.
    let mut trunk = vec![false; n];
    if n > 0 {
        trunk[graph.root] = true;
    }
    let junctions: Vec<usize> = (0..n)
        .filter(|&v| graph.vertices[v].major_junction)
        .collect();
    for &j in &junctions {
        for a in graph.ancestors(j) {
            if trunk[a] {
                break;
            }
            trunk[a] = true;
        }
    }
    if junctions.is_empty() {
        warnings.push(AnatomyWarning::NoMajorJunction);
    }
    let trunk_points: Vec<DVec3> = (0..n)
        .filter(|&v| trunk[v])
        .flat_map(|v| graph.vertices[v].voxels.iter().map(|&p| surface.centre(p)))
        .collect();
    let trunk_axis = principal_axis(&trunk_points);
    let trunk_angle = if trunk_axis == DVec3::ZERO {
        f64::NAN
    } else {
        trunk_axis.dot(frame.up).abs().min(1.0).acos().to_degrees()
    };
    let figure = if junctions.is_empty() || trunk_angle.is_nan() {
        FigureClass::Unknown
    } else if trunk_angle <= options.vertical_angle {
        FigureClass::HumanLike
    } else if trunk_angle >= options.horizontal_angle {
        FigureClass::AnimalLike
    } else {
        FigureClass::Unknown
    };
    let sections = sections(graph, surface, &trunk);
    let mut assign = vec![UNLABELLED; sections.len()];
    let significant: Vec<usize> = (0..sections.len())
        .filter(|&s| !sections[s].insignificant)
        .collect();
    let unlabelled = |assign: &[Assignment]| -> Vec<usize> {
        significant
            .iter()
            .copied()
            .filter(|&s| assign[s].label.is_none())
            .collect()
    };

    // Legs: sections reaching the bottom of the figure, paired by where they join the trunk.
    let legs: Vec<usize> = unlabelled(&assign)
        .into_iter()
        .filter(|&s| sections[s].extreme[1])
        .collect();
    let (leg_pairs, mut single_legs) = pair_up(&legs, &sections, graph, f64::INFINITY);
    // Fore/hind: with two or more pairs the most anterior pair is fore, the others hind.
    let anterior = |s: usize| -> f64 {
        let a = graph.vertices[sections[s].attachment_vertex].centroid;
        match figure {
            FigureClass::HumanLike => a.dot(frame.up),
            _ => a.dot(frame.forward),
        }
    };
    let mut ordered = leg_pairs.clone();
    ordered.sort_by(|x, y| {
        (anterior(y.0) + anterior(y.1)).total_cmp(&(anterior(x.0) + anterior(x.1)))
    });
    for (k, &(a, b)) in ordered.iter().enumerate() {
        let pair = if ordered.len() >= 2 && k == 0 {
            LimbPair::Fore
        } else {
            LimbPair::Hind
        };
        for (s, side) in sides(a, b, &sections, frame) {
            assign[s] = Assignment {
                label: Some(Label::Leg),
                side: Some(side),
                limb_pair: Some(pair),
                partner: Some(if s == a { b } else { a }),
            };
        }
    }
    for &s in &single_legs {
        assign[s] = Assignment {
            label: Some(Label::Leg),
            ..UNLABELLED
        };
    }

    // Wings: mostly linear cross-sections, in pairs.
    let wings: Vec<usize> = unlabelled(&assign)
        .into_iter()
        .filter(|&s| {
            sections[s].linear_fraction >= options.wing_fraction
                && sections[s].length >= options.limb_length * radius
        })
        .collect();
    let (wing_pairs, _) = pair_up(&wings, &sections, graph, f64::INFINITY);
    for &(a, b) in &wing_pairs {
        for (s, side) in sides(a, b, &sections, frame) {
            assign[s] = Assignment {
                label: Some(Label::Wing),
                side: Some(side),
                limb_pair: Some(LimbPair::Fore),
                partner: Some(if s == a { b } else { a }),
            };
        }
    }

    // Tail: an animal's before the head (its tail may reach as high as its head); a human-like
    // figure's after the head and the arms, which it may never take (a T-posed arm reaching
    // back, a head leaning back).
    let tail_context = TailContext {
        graph,
        sections: &sections,
        frame,
        figure,
        trunk_points: &trunk_points,
        pairs: &ordered,
        limit: options.tail_distance * radius,
        min_length: options.tail_length * radius,
    };
    if figure != FigureClass::HumanLike {
        let candidates = unlabelled(&assign);
        tail_context.assign(&mut assign, &mut single_legs, &candidates);
    }

    // Head: upward extreme (human-like), forward extreme (animal-like), else both.
    let (up_lo, up_hi, fw_lo, fw_hi) = sections.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), s| {
            (
                a.min(s.reach[1]),
                b.max(s.reach[0]),
                c.min(s.reach[3]),
                d.max(s.reach[2]),
            )
        },
    );
    let score = |s: usize| -> f64 {
        let sec = &sections[s];
        let up = (sec.reach[0] - up_lo) / (up_hi - up_lo).max(f64::MIN_POSITIVE);
        let fw = (sec.reach[2] - fw_lo) / (fw_hi - fw_lo).max(f64::MIN_POSITIVE);
        match figure {
            FigureClass::HumanLike => up,
            FigureClass::AnimalLike => fw,
            FigureClass::Unknown => up + fw,
        }
    };
    let head = unlabelled(&assign)
        .into_iter()
        .max_by(|&a, &b| score(a).total_cmp(&score(b)).then(b.cmp(&a)));
    match head {
        Some(h) if !junctions.is_empty() => {
            assign[h] = Assignment {
                label: Some(Label::Head),
                ..UNLABELLED
            }
        }
        _ => warnings.push(AnatomyWarning::NoHead),
    }

    // Arms: remaining long sections joining the trunk at about the same place, in pairs.
    let arms: Vec<usize> = unlabelled(&assign)
        .into_iter()
        .filter(|&s| sections[s].length >= options.limb_length * radius)
        .collect();
    let (arm_pairs, _) = pair_up(&arms, &sections, graph, options.pair_distance * radius);
    for &(a, b) in &arm_pairs {
        for (s, side) in sides(a, b, &sections, frame) {
            assign[s] = Assignment {
                label: Some(Label::Arm),
                side: Some(side),
                limb_pair: Some(LimbPair::Fore),
                partner: Some(if s == a { b } else { a }),
            };
        }
    }

    if figure == FigureClass::HumanLike {
        let candidates = unlabelled(&assign);
        tail_context.assign(&mut assign, &mut single_legs, &candidates);
    }

    let centre = if trunk_points.is_empty() {
        DVec3::ZERO
    } else {
        trunk_points.iter().sum::<DVec3>() / trunk_points.len() as f64
    };
    let side_of = |s: usize| {
        if (sections[s].mean - centre).dot(frame.left) >= 0.0 {
            Side::Left
        } else {
            Side::Right
        }
    };
    // A lone arm of a human-like figure: a long section left unpaired that joins the upper
    // half of the trunk (its partner is missing, or too far away to pair).
    if figure == FigureClass::HumanLike {
        for s in arms {
            if assign[s].label.is_none()
                && sections[s].attachment.dot(frame.up) > centre.dot(frame.up)
            {
                let side = side_of(s);
                assign[s] = Assignment {
                    label: Some(Label::Arm),
                    side: Some(side),
                    limb_pair: Some(LimbPair::Fore),
                    partner: None,
                };
                warnings.push(AnatomyWarning::SingleArm { section: s, side });
            }
        }
    }

    // Unpaired legs: side from the trunk's centre line, pair from the nearest leg pair.
    for &s in &single_legs {
        assign[s].side = Some(side_of(s));
        let nearest = ordered.iter().min_by(|x, y| {
            let dx = sections[x.0].attachment.distance(sections[s].attachment);
            let dy = sections[y.0].attachment.distance(sections[s].attachment);
            dx.total_cmp(&dy)
        });
        assign[s].limb_pair = nearest
            .and_then(|&(a, _)| assign[a].limb_pair)
            .or(Some(LimbPair::Hind));
    }
    let leg_count = assign
        .iter()
        .filter(|a| a.label == Some(Label::Leg))
        .count();
    if leg_count % 2 == 1 {
        warnings.push(AnatomyWarning::OddLegs {
            legs: leg_count,
            unpaired: single_legs.len(),
        });
    }
    if ordered.len() > 2 {
        warnings.push(AnatomyWarning::TooManyLegPairs {
            pairs: ordered.len(),
        });
    }
    if leg_count == 0 && !junctions.is_empty() {
        warnings.push(AnatomyWarning::NoLegs);
    }

    // Leftovers: merged into the trunk; long ones are named for the user.
    for s in unlabelled(&assign) {
        if sections[s].length >= options.leftover_length * radius {
            let d = sections[s].distal;
            warnings.push(AnatomyWarning::UnidentifiedProtrusion {
                section: s,
                voxels: sections[s].voxels,
                reach: d,
            });
        }
    }
    Draft {
        figure,
        trunk_axis,
        trunk_angle,
        trunk,
        sections,
        assignments: assign,
        warnings,
    }
}

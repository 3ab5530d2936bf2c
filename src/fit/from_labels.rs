//! From body-part labels to the fit's geometry (dissertation 8.1-8.2): centralised paths over
//! the discrete medial surface between the labelled parts' extreme points.
//!
//! ```text
//! Labelling ─▶ each part's distal DMS voxel (highest heart value)
//!           ─▶ limb pairs: left and right of a label/girdle, matched along the body
//!           ─▶ limb-to-limb paths (weighted Dijkstra, 1/d³), their midpoints = attach points
//!           ─▶ head-to-tail path: head tip → tail tip, or → the hindmost pair's midpoint
//!           ─▶ unpaired limbs: path to the head-to-tail path; digits: wrist → digit tip
//!           ─▶ ends extended to the skin by their inscribed radius; points and radii in mesh units
//!           ─▶ leg tips out to the skin along rays through the voxels (`reach.rs`)
//!           ─▶ ears, when the template places them (`ears.rs`)
//! ```

use super::ears::{ears, EarOptions};
use super::reach::{reach_the_skin, ReachOptions};
use super::{
    AxialPath, DigitInput, DorsalProbe, FitError, FitInput, FitInputWarning, LimbInput, Side,
};
use crate::anatomy::{FigureClass, Label, Labelling, LimbPair, Part};
use crate::distance::DistanceMap;
use crate::math::upper_median;
use crate::medial::MedialSurface;
use crate::options::{Checks, OptionProblems};
use crate::paths::{DmsGraph, Search};
use crate::template::{LimbKind, Template};
use glam::DVec3;

/// Options of [`fit_input`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitInputOptions {
    /// Exponent `k` of the path weight `step / d^k` (`d` the distance to the surface, voxel
    /// units): centralised paths keep to the thick middle of the figure. Default 3 (ch.5.2.4,
    /// 8.1: "weighted by 1/d^3").
    pub weight_exponent: f64,
    /// Each free path end (head, tail, limb and digit tips) lies inside the figure by about
    /// its inscribed radius, because the medial surface stops there; it is extended along its
    /// end direction by this multiple of that radius so that Table 8.1 divides the whole limb.
    /// Default 1.0 (to the skin); 0 keeps the medial-surface ends (the dissertation).
    pub end_extension: f64,
    /// Points at the end of a path used for its end direction. Default 4 voxels.
    pub end_direction_points: usize,
    /// Make the roots of a limb pair mirror images of each other in the sagittal plane
    /// through the pair's attach point (the labelled sections of the two sides start at
    /// slightly different places). Default true (measured, see `reports/rig/`).
    pub symmetric_roots: bool,
    /// A limb whose path is shorter than this many times its median inscribed radius is named
    /// in a warning: it is a stub (a box's corner, a bump), not a limb, and the labels should
    /// be checked. Default 4 (the reference limbs measure 10-20: a fox's leg about 10, a human
    /// arm about 17; a cube's corners about 3.5).
    pub min_limb_slenderness: f64,
    /// Leg tips out to the skin along rays through the voxels, past where the medial surface
    /// stops ([`ReachOptions`]).
    pub reach: ReachOptions,
    /// Ear detection ([`super::ears`], run by [`fit_input`] when the template places ears).
    pub ears: EarOptions,
}

impl FitInputOptions {
    /// Checks every option, the reach and ear options included.
    ///
    /// # Errors
    /// Every option out of range.
    pub fn validate(&self) -> Result<(), OptionProblems> {
        let mut c = Checks::default();
        c.range("weight_exponent", self.weight_exponent, 0.0, 20.0);
        c.range("end_extension", self.end_extension, 0.0, 10.0);
        c.range(
            "min_limb_slenderness",
            self.min_limb_slenderness,
            0.0,
            1000.0,
        );
        c.nested("reach", self.reach.validate());
        c.nested("ears", self.ears.validate());
        c.finish()
    }
}

impl Default for FitInputOptions {
    fn default() -> Self {
        Self {
            weight_exponent: 3.0,
            end_extension: 1.0,
            end_direction_points: 4,
            symmetric_roots: true,
            min_limb_slenderness: 4.0,
            reach: ReachOptions::default(),
            ears: EarOptions::default(),
        }
    }
}

/// The fit's whole input from a labelling and the voxel stages it was made from (one grid), in
/// mesh units and frame (dissertation 8.1-8.2): centralised DMS paths between the labelled
/// parts, their free ends extended to the skin, the leg tips carried out to the skin along rays
/// through `skin` (the figure's inside, e.g. [`crate::voxel::Solid`]; `distance` its distance
/// map), and the ears when `template` places them (none without a template: the general
/// control skeleton's fallback). Returns the input and what could not be built (a missing
/// head, an unreachable limb).
///
/// Up and forward are the labelling's frame. Paths run through the labelled (largest) DMS
/// component only.
///
/// # Errors
/// [`FitError::InvalidInputOptions`] with every option out of range.
pub fn fit_input(
    labelling: &Labelling,
    surface: &MedialSurface,
    skin: &dyn DorsalProbe,
    distance: &DistanceMap,
    template: Option<&Template>,
    options: &FitInputOptions,
) -> Result<(FitInput, Vec<FitInputWarning>), FitError> {
    options.validate()?;
    let (mut input, warnings) = centralised_paths(labelling, surface, distance, options);
    reach_the_skin(&mut input, options, skin, distance);
    if template.is_some_and(|t| t.placed("ear").is_some()) {
        input.ears = ears(labelling, distance, &input.axial, &options.ears);
    }
    Ok((input, warnings))
}

/// Centralised DMS paths between the labelled parts, their free ends extended by
/// [`FitInputOptions::end_extension`]: the input of [`fit_input`] before the leg tips reach the
/// skin and without ears, and what could not be built.
fn centralised_paths(
    labelling: &Labelling,
    surface: &MedialSurface,
    distance: &DistanceMap,
    options: &FitInputOptions,
) -> (FitInput, Vec<FitInputWarning>) {
    let graph = DmsGraph::new(surface);
    let paths = Paths {
        graph: &graph,
        surface,
        distance,
        labelling,
        options,
    };
    let mut warnings = Vec::new();

    // Limb pairs and their limb-to-limb paths.
    let (mut limbs, midpoints, unpaired) = paired_limbs(&paths, &mut warnings);
    // Head-to-tail path.
    let (axial_positions, points, radii, tail) = head_to_tail(&paths, &midpoints, &mut warnings);
    // Unpaired limbs hang from the head-to-tail path.
    if !unpaired.is_empty() {
        unpaired_limbs(
            &paths,
            &axial_positions,
            unpaired,
            &mut limbs,
            &mut warnings,
        );
    }
    stub_warnings(&limbs, options, &mut warnings);

    // A labelled jaw: from where it leaves the head to its tip.
    let jaw = labelling.part(Label::Jaw, None).and_then(|p| {
        let base = paths.nearest(p, p.attachment);
        let path = paths.centralised(base, paths.distal(p))?;
        Some(paths.points(&path).0)
    });

    let input = FitInput {
        up: labelling.frame.up,
        forward: labelling.frame.forward,
        axial: AxialPath {
            points,
            radii,
            sections: None,
            tail,
        },
        limbs,
        jaw,
        ears: Vec::new(),
    };
    (input, warnings)
}

/// A limb pair: its pair index and the DMS position of its limb-to-limb path's midpoint.
type Midpoint = (usize, usize);

/// A limb without a partner: its part, kind and pair number.
type Unpaired = (usize, LimbKind, usize);

/// The limbs of each labelled pair from the pair's limb-to-limb path (roots mirrored when
/// `symmetric_roots`), the pairs' midpoints, and the limbs without a partner.
fn paired_limbs(
    paths: &Paths,
    warnings: &mut Vec<FitInputWarning>,
) -> (Vec<LimbInput>, Vec<Midpoint>, Vec<Unpaired>) {
    let (labelling, surface, options) = (paths.labelling, paths.surface, paths.options);
    let parts = &labelling.parts;
    let pairs = limb_pairs(labelling);
    let mut limbs: Vec<LimbInput> = Vec::new();
    let mut midpoints: Vec<(usize, usize)> = Vec::new(); // (pair index, DMS position)
    let mut unpaired: Vec<(usize, LimbKind, usize)> = Vec::new();
    for (n, pair) in pairs.iter().enumerate() {
        let (Some(l), Some(r)) = (pair.left, pair.right) else {
            for part in [pair.left, pair.right].into_iter().flatten() {
                unpaired.push((part, pair.kind, pair.number));
            }
            continue;
        };
        let (a, b) = (paths.wrist(l), paths.wrist(r));
        let Some(path) = paths.centralised(a, b) else {
            warnings.push(FitInputWarning::UnjoinedPair {
                label: parts[l].label,
            });
            continue;
        };
        let mid = paths.midpoint(&path);
        midpoints.push((n, path[mid]));
        let attach = surface.centre(path[mid]);
        let mut left_half: Vec<usize> = path[..=mid].to_vec();
        left_half.reverse();
        let right_half = path[mid..].to_vec();
        // Paired limbs mirror each other: a medial path that breaks off in one hand or foot
        // (a thin palm a few voxels across, where the grid falls a little differently on the
        // two sides) is carried on through its part's voxels as far as its partner's reaches.
        let (reach_l, reach_r) = (paths.reach(&left_half), paths.reach(&right_half));
        let short_of =
            |own: f64, partner: f64| (own < (1.0 - MIRROR_SHORTFALL) * partner).then_some(partner);
        let mut left = paths.limb(
            l,
            pair.kind,
            pair.number,
            Side::Left,
            attach,
            &left_half,
            short_of(reach_l, reach_r),
        );
        let mut right = paths.limb(
            r,
            pair.kind,
            pair.number,
            Side::Right,
            attach,
            &right_half,
            short_of(reach_r, reach_l),
        );
        if options.symmetric_roots {
            // Bilateral symmetry: each root is the mean of itself and its partner's mirror
            // image in the sagittal plane halfway between them.
            let n = labelling.frame.left;
            if let (Some(a), Some(b)) = (left.root, right.root) {
                let m = 0.5 * (a + b);
                let mirror = |p: DVec3| p - n * (2.0 * (p - m).dot(n));
                let a2 = 0.5 * (a + mirror(b));
                left.root = Some(a2);
                right.root = Some(mirror(a2));
            }
        }
        limbs.push(left);
        limbs.push(right);
    }

    (limbs, midpoints, unpaired)
}

/// A limb's medial path is carried on to its partner's reach (from the figure's heart to the
/// path's end) when it falls short of it by more than this fraction ([`paired_limbs`]); closer
/// than that, the grid's steps.
const MIRROR_SHORTFALL: f64 = 0.05;

/// How many times the limb's thickness (twice its median inscribed radius) its part goes on
/// beyond the end of its medial path for the path to count as broken off ([`Paths::limb`]).
const BREAK_OFF_THICKNESSES: f64 = 2.0;

/// Ends the points from index `from` on (a path carried on beyond its medial end) at the
/// first that lies `reach` from `root` (the heart), moved back onto that distance; points that
/// never get that far all stay.
fn reach_from(points: &mut Vec<DVec3>, radii: &mut Vec<f64>, from: usize, root: DVec3, reach: f64) {
    let Some(k) = (from.max(1)..points.len()).find(|&k| points[k].distance(root) >= reach) else {
        return;
    };
    let (a, b) = (points[k - 1].distance(root), points[k].distance(root));
    let t = if b > a {
        ((reach - a) / (b - a)).clamp(0.0, 1.0)
    } else {
        1.0
    };
    points[k] = points[k - 1].lerp(points[k], t);
    radii[k] = radii[k - 1] + t * (radii[k] - radii[k - 1]);
    points.truncate(k + 1);
    radii.truncate(k + 1);
}

/// The head-to-tail path: from the head's tip (else the top or front trunk voxel) to the tail's
/// tip, else the farthest pair midpoint, else the trunk voxel farthest from the head; its DMS
/// positions, points and radii (ends extended to the skin where they are free ends).
fn head_to_tail(
    paths: &Paths,
    midpoints: &[Midpoint],
    warnings: &mut Vec<FitInputWarning>,
) -> (Vec<usize>, Vec<DVec3>, Vec<f64>, bool) {
    let (labelling, surface) = (paths.labelling, paths.surface);
    let parts = &labelling.parts;
    let head = labelling.part(Label::Head, None).map(|p| paths.head_tip(p));
    let start = head.unwrap_or_else(|| {
        let dir = match labelling.figure {
            FigureClass::HumanLike => labelling.frame.up,
            _ => labelling.frame.forward,
        };
        warnings.push(FitInputWarning::NoHead);
        paths.extreme(&parts[0], dir)
    });
    let from_head = paths.search(start);
    let tail_part = labelling.find(Label::Tail).first().copied();
    let tail = tail_part.map(|p| paths.distal(&parts[p]));
    let end = tail
        .filter(|&t| from_head.cost[t].is_finite())
        .or_else(|| {
            midpoints
                .iter()
                .map(|&(_, p)| p)
                .filter(|&p| from_head.cost[p].is_finite())
                .max_by(|&a, &b| from_head.cost[a].total_cmp(&from_head.cost[b]))
        })
        .unwrap_or_else(|| {
            // No tail and no pair: the trunk voxel farthest from the head.
            parts[0]
                .voxels
                .iter()
                .copied()
                .filter(|&p| from_head.cost[p].is_finite())
                .max_by(|&a, &b| {
                    from_head.cost[a]
                        .total_cmp(&from_head.cost[b])
                        .then(b.cmp(&a))
                })
                .unwrap_or(start)
        });
    let mut axial_positions = from_head.path_to_source(end);
    axial_positions.reverse(); // head first
    let (mut points, mut radii) = paths.points(&axial_positions);
    if head.is_some() {
        paths.extend_start(&mut points, &mut radii);
    }
    let ends_in_tail = tail_part.is_some() && tail == Some(end);
    if let Some(part) = tail_part.filter(|_| ends_in_tail) {
        paths.thin_end(part, end, &mut points, &mut radii);
        paths.extend_end(&mut points, &mut radii);
    }
    if points.len() == 1 {
        // A one-voxel path (a figure without parts): give the fit a segment to work with.
        points.push(points[0] + labelling.frame.up * surface.grid.voxel_size);
        radii.push(radii[0]);
    }

    (axial_positions, points, radii, ends_in_tail)
}

/// The limbs without a partner, each from the head-to-tail path (`axial_positions`) to its tip.
fn unpaired_limbs(
    paths: &Paths,
    axial_positions: &[usize],
    unpaired: Vec<Unpaired>,
    limbs: &mut Vec<LimbInput>,
    warnings: &mut Vec<FitInputWarning>,
) {
    let parts = &paths.labelling.parts;
    let surface = paths.surface;
    let to_axis = paths.search_many(axial_positions);
    for (part, kind, number) in unpaired {
        let tip = paths.wrist(part);
        let mut path = to_axis.path_to_source(tip);
        if path.len() < 2 {
            warnings.push(FitInputWarning::UnreachedLimb {
                side: parts[part].side,
                label: parts[part].label,
            });
            continue;
        }
        path.reverse(); // axis first
        let side = parts[part].side.unwrap_or(Side::Left);
        let attach = surface.centre(path[0]);
        limbs.push(paths.limb(part, kind, number, side, attach, &path, None));
    }
}

/// The median of `values` ([`upper_median`]), 0 for none.
fn median(values: &[f64]) -> f64 {
    upper_median(values.to_vec()).unwrap_or(0.0)
}

/// A warning per limb shorter than `min_limb_slenderness` times its median radius.
fn stub_warnings(
    limbs: &[LimbInput],
    options: &FitInputOptions,
    warnings: &mut Vec<FitInputWarning>,
) {
    for limb in limbs {
        let length: f64 = limb.path.windows(2).map(|w| w[0].distance(w[1])).sum();
        let median = median(&limb.radii);
        if median > 0.0 && length < options.min_limb_slenderness * median {
            warnings.push(FitInputWarning::Stub {
                side: limb.side,
                kind: limb.kind,
                slenderness: length / median,
            });
        }
    }
}

/// A limb pair: parts of one label and girdle matched left to right along the body.
struct PairParts {
    kind: LimbKind,
    number: usize,
    left: Option<usize>,
    right: Option<usize>,
}

/// Groups the limb parts by label and girdle; within a group, left and right parts are sorted
/// along the body (forward for animal-like figures, up otherwise, head end first) and matched in
/// that order; pair numbers count within a kind.
fn limb_pairs(labelling: &Labelling) -> Vec<PairParts> {
    let along = match labelling.figure {
        FigureClass::AnimalLike => labelling.frame.forward,
        _ => labelling.frame.up,
    };
    let mut out = Vec::new();
    for label in [Label::Arm, Label::Wing, Label::Leg] {
        for girdle in [Some(LimbPair::Fore), Some(LimbPair::Hind), None] {
            let kind = match (label, girdle) {
                (Label::Arm, _) => LimbKind::Arm,
                (Label::Wing, _) => LimbKind::Wing,
                (_, Some(LimbPair::Fore)) => LimbKind::ForeLeg,
                (_, Some(LimbPair::Hind)) => LimbKind::HindLeg,
                _ => LimbKind::Leg,
            };
            let sorted = |side: Side| {
                let mut v: Vec<usize> = (0..labelling.parts.len())
                    .filter(|&i| {
                        let p = &labelling.parts[i];
                        p.label == label && p.limb_pair == girdle && p.side == Some(side)
                    })
                    .collect();
                v.sort_by(|&a, &b| {
                    let key = |i: usize| -labelling.parts[i].attachment.dot(along);
                    key(a).total_cmp(&key(b)).then(a.cmp(&b))
                });
                v
            };
            let (lefts, rights) = (sorted(Side::Left), sorted(Side::Right));
            let count = lefts.len().max(rights.len());
            let first = out.iter().filter(|p: &&PairParts| p.kind == kind).count();
            for k in 0..count {
                out.push(PairParts {
                    kind,
                    number: first + k,
                    left: lefts.get(k).copied(),
                    right: rights.get(k).copied(),
                });
            }
        }
    }
    out
}

/// Path searches over the DMS of one labelling.
struct Paths<'a> {
    graph: &'a DmsGraph,
    surface: &'a MedialSurface,
    distance: &'a DistanceMap,
    labelling: &'a Labelling,
    options: &'a FitInputOptions,
}

impl Paths<'_> {
    /// The cost of entering DMS position `q` over a step of `step` voxels.
    fn weight(&self, q: usize, step: f64) -> f64 {
        let d = self.surface.distance(q).max(0.5);
        step / d.powf(self.options.weight_exponent)
    }

    fn search_many(&self, sources: &[usize]) -> Search {
        let mut s = Search::new(self.graph.len());
        s.add_sources(self.graph, sources.iter().copied(), |q, step| {
            self.weight(q, step)
        });
        s
    }

    fn search(&self, source: usize) -> Search {
        self.search_many(&[source])
    }

    /// The centralised path from `a` to `b` (both included, `a` first), `None` when they are
    /// not connected.
    fn centralised(&self, a: usize, b: usize) -> Option<Vec<usize>> {
        let path = self.search(b).path_to_source(a);
        (!path.is_empty()).then_some(path)
    }

    /// The part's DMS voxel of highest heart value (its distal extreme); for a limb with
    /// digits the digits are separate parts, so this is the wrist/ankle.
    fn distal(&self, part: &Part) -> usize {
        let hv = &self.labelling.level_graph.heart_values;
        part.voxels
            .iter()
            .copied()
            .max_by(|&a, &b| hv[a].total_cmp(&hv[b]).then(b.cmp(&a)))
            .unwrap_or(self.labelling.level_graph.heart)
    }

    /// The tip of the head: its voxel farthest up for human-like figures, farthest forward for
    /// animal-like ones (the crown and the snout, 7.3.3's extreme marks), else its distal
    /// extreme. The distal extreme alone wanders over a round head (chin, nose or crown).
    fn head_tip(&self, part: &Part) -> usize {
        match self.labelling.figure {
            FigureClass::HumanLike => self.extreme(part, self.labelling.frame.up),
            FigureClass::AnimalLike => self.extreme(part, self.labelling.frame.forward),
            FigureClass::Unknown => self.distal(part),
        }
    }

    /// The distal end of limb part `i` (the wrist/ankle when it has digits).
    fn wrist(&self, i: usize) -> usize {
        self.distal(&self.labelling.parts[i])
    }

    /// The part's DMS voxel farthest along `dir` (any DMS voxel for a part without voxels).
    fn extreme(&self, part: &Part, dir: DVec3) -> usize {
        let along = |p: usize| self.surface.centre(p).dot(dir);
        let farther = |a: &usize, b: &usize| along(*a).total_cmp(&along(*b)).then(b.cmp(a));
        let found = if part.voxels.is_empty() {
            (0..self.surface.len()).max_by(farther)
        } else {
            part.voxels.iter().copied().max_by(farther)
        };
        found.unwrap_or(self.labelling.level_graph.heart)
    }

    /// The part's DMS voxel nearest `p`.
    fn nearest(&self, part: &Part, p: DVec3) -> usize {
        part.voxels
            .iter()
            .copied()
            .min_by(|&a, &b| {
                let (da, db) = (
                    self.surface.centre(a).distance_squared(p),
                    self.surface.centre(b).distance_squared(p),
                );
                da.total_cmp(&db).then(a.cmp(&b))
            })
            .unwrap_or(self.labelling.level_graph.heart)
    }

    /// Index of the point halfway along `path` by length.
    fn midpoint(&self, path: &[usize]) -> usize {
        let cum: Vec<f64> = std::iter::once(0.0)
            .chain(path.windows(2).scan(0.0, |acc, w| {
                *acc += self
                    .surface
                    .centre(w[0])
                    .distance(self.surface.centre(w[1]));
                Some(*acc)
            }))
            .collect();
        let half = cum.last().copied().unwrap_or(0.0) / 2.0;
        cum.iter()
            .position(|&c| c >= half)
            .unwrap_or(0)
            .min(path.len() - 1)
    }

    /// Points and radii (mesh units) of DMS positions.
    fn points(&self, path: &[usize]) -> (Vec<DVec3>, Vec<f64>) {
        let h = self.surface.grid.voxel_size;
        path.iter()
            .map(|&p| (self.surface.centre(p), self.surface.distance(p) * h))
            .unzip()
    }

    /// Carries a path ending at DMS position `end` of part `part` on through the part's
    /// interior voxels to its tip when its medial surface stops short of it
    /// ([`thin_end`](super::thin_end::thin_end)): a thin tail.
    fn thin_end(&self, part: usize, end: usize, points: &mut Vec<DVec3>, radii: &mut Vec<f64>) {
        let grid = self.surface.grid;
        let Some(beyond) =
            super::thin_end::thin_end(self.labelling, part, self.surface.voxels[end])
        else {
            return;
        };
        for index in beyond {
            points.push(grid.centre(grid.coords(index)));
            radii.push(self.distance.distance(index) * grid.voxel_size);
        }
    }

    /// Prepends a point beyond `points[0]`, continuing the path's start direction by
    /// `end_extension` times the start's radius.
    fn extend_start(&self, points: &mut Vec<DVec3>, radii: &mut Vec<f64>) {
        let k = self.options.end_direction_points.min(points.len() - 1);
        let length = self.options.end_extension * radii[0];
        if k == 0 || length <= 0.0 {
            return;
        }
        let Some(dir) = (points[0] - points[k]).try_normalize() else {
            return;
        };
        points.insert(0, points[0] + dir * length);
        radii.insert(0, 0.0);
    }

    /// Appends a point beyond the last one, as [`Self::extend_start`] does at the start.
    fn extend_end(&self, points: &mut Vec<DVec3>, radii: &mut Vec<f64>) {
        points.reverse();
        radii.reverse();
        self.extend_start(points, radii);
        points.reverse();
        radii.reverse();
    }

    /// The figure's heart (the centre of its medial surface), from which paired limbs' reaches
    /// are compared: one point for both sides, on the median plane of a symmetric figure.
    fn heart(&self) -> DVec3 {
        self.surface.centre(self.labelling.level_graph.heart)
    }

    /// How far a limb whose path is `path` reaches: from the figure's heart ([`Self::heart`])
    /// to the path's last DMS position, mesh units.
    fn reach(&self, path: &[usize]) -> f64 {
        path.last()
            .map_or(0.0, |&end| self.surface.centre(end).distance(self.heart()))
    }

    /// A limb from its DMS path (proximal first): the fit's limb input, with digits from the
    /// wrist/ankle to each digit tip. With `reach` (its partner's, [`Self::reach`]), a limb
    /// without digits whose medial path stops short is carried on through its part's interior
    /// voxels towards its tip ([`Self::thin_end`]), to at most that far from the heart.
    #[allow(clippy::too_many_arguments)]
    fn limb(
        &self,
        part: usize,
        kind: LimbKind,
        number: usize,
        side: Side,
        attach: DVec3,
        path: &[usize],
        reach: Option<f64>,
    ) -> LimbInput {
        let p = &self.labelling.parts[part];
        let (mut points, mut radii) = self.points(path);
        let wrist = *path.last().unwrap_or(&self.labelling.level_graph.heart);
        let mut digits = Vec::new();
        if p.digits.is_empty() {
            if let (Some(reach), Some(&end)) = (reach, path.last()) {
                let medial = points.len();
                self.thin_end(part, end, &mut points, &mut radii);
                // A break in the medial path: the part goes on for more than twice the limb's
                // thickness (an open hand or a foot, two to three times as long as the forearm
                // or shin is thick), not just to the skin around the path's end or over the
                // cap of a fist (about as long as the arm is thick).
                let thickness = 2.0 * median(&radii[..medial]);
                let beyond = points[medial - 1].distance(points[points.len() - 1]);
                if beyond > BREAK_OFF_THICKNESSES * thickness {
                    reach_from(&mut points, &mut radii, medial, self.heart(), reach);
                } else {
                    points.truncate(medial);
                    radii.truncate(medial);
                }
            }
            self.extend_end(&mut points, &mut radii);
        } else {
            let from_wrist = self.search(wrist);
            for &d in &p.digits {
                let mut dp = from_wrist.path_to_source(self.distal(&self.labelling.parts[d]));
                if dp.len() < 2 {
                    continue;
                }
                dp.reverse();
                let (mut dpts, mut dr) = self.points(&dp);
                self.extend_end(&mut dpts, &mut dr);
                digits.push(DigitInput { path: dpts });
            }
        }
        LimbInput {
            kind,
            side,
            pair: number,
            attach,
            path: points,
            radii,
            digits,
            root: Some(p.attachment),
        }
    }
}

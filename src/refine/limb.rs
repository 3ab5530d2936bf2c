//! Plumber-style sphere slicing of a limb (seed 004, 3.3; Mortara et al. 2004): slices along
//! the limb from a seed on the pre-aligned skeleton, with barycentre, perimeter and principal
//! diameters per slice, interpolated by cubic B-splines.

use super::RefineOptions;
use crate::math::point_segment_distance;
use crate::mesh::{slice_plane_outer, Mesh, SliceLoop, SphereSlicer};
use bspline::BSpline;
use glam::DVec3;
use std::f64::consts::TAU;

/// One sphere slice of a limb.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimbSlice {
    /// Barycentre of the intersection curve, mesh units.
    pub centre: DVec3,
    /// Length of the intersection curve.
    pub perimeter: f64,
    /// Largest principal diameter (the width at the wrist).
    pub major: f64,
    /// Second principal diameter (the thickness at the wrist).
    pub minor: f64,
    /// Arc length along the centroid curve from the first slice.
    pub arc: f64,
}

/// A limb's slices from the proximal end (next to the torso) to the distal end (into hand or
/// foot), smoothed by cubic B-splines over arc length.
#[derive(Debug, Clone, PartialEq)]
pub struct LimbProfile {
    /// The slices in order, proximal first, `arc` increasing.
    pub slices: Vec<LimbSlice>,
}

impl LimbProfile {
    /// Total arc length of the centroid curve.
    pub fn length(&self) -> f64 {
        self.slices.last().map_or(0.0, |s| s.arc)
    }

    /// The slice properties at arc length `s` from cubic B-splines through the slices'
    /// values (uniform clamped knots over the slice index, so the value follows the
    /// slices closely); `None` for fewer than four slices.
    pub fn at(&self, s: f64) -> Option<LimbSlice> {
        let n = self.slices.len();
        if n < 4 {
            return None;
        }
        let s = s.clamp(0.0, self.length());
        // Index parameter of arc length s (piecewise linear inverse).
        let k = self.slices.partition_point(|x| x.arc < s).clamp(1, n - 1);
        let (a, b) = (self.slices[k - 1], self.slices[k]);
        let f = if b.arc > a.arc {
            (s - a.arc) / (b.arc - a.arc)
        } else {
            0.0
        };
        let t = (k - 1) as f64 + f;
        let spline = |value: &dyn Fn(&LimbSlice) -> DVec3| {
            let points: Vec<DVec3> = self.slices.iter().map(value).collect();
            interpolate(&points, t)
        };
        let centre = spline(&|x| x.centre);
        let measures = spline(&|x| DVec3::new(x.perimeter, x.major, x.minor));
        Some(LimbSlice {
            centre,
            perimeter: measures.x,
            major: measures.y,
            minor: measures.z,
            arc: s,
        })
    }

    /// Samples of [`LimbProfile::at`] every `step` of arc length.
    pub fn dense(&self, step: f64) -> Vec<LimbSlice> {
        let n = (self.length() / step).ceil().max(1.0) as usize;
        (0..=n)
            .filter_map(|i| self.at(self.length() * i as f64 / n as f64))
            .collect()
    }
}

/// Cubic B-spline with control points `points` (ends repeated so the curve starts and ends at
/// the first and last point), evaluated at index parameter `t` in `[0, n − 1]`.
fn interpolate(points: &[DVec3], t: f64) -> DVec3 {
    let n = points.len();
    let degree = 3;
    let mut knots = vec![0.0; degree];
    knots.extend((0..n - degree + 1).map(|i| i as f64));
    knots.extend(std::iter::repeat_n((n - degree) as f64, degree));
    let spline = BSpline::new(degree, points.to_vec(), knots);
    let (lo, hi) = spline.knot_domain();
    let u = lo + (hi - lo) * (t / (n - 1) as f64);
    spline.point(u.clamp(lo, hi))
}

/// Traces a limb along the rough joint chain `chain` (proximal → distal, at least two points,
/// e.g. shoulder, elbow, wrist): seeded at the middle of the first segment, marched towards the
/// torso up to the first chain point or until the sphere merges with the torso, and outwards until beyond the last chain point by
/// `distal_overshoot` of the last segment or until the limb splits into digits. `height` is the
/// figure's height. `None` when the seed is not inside a limb-like tube.
pub fn trace_limb(
    mesh: &Mesh,
    chain: &[DVec3],
    height: f64,
    options: &RefineOptions,
) -> Option<LimbProfile> {
    if chain.len() < 2 {
        return None;
    }
    let seed = chain[0].lerp(chain[1], 0.5);
    let axis = (chain[1] - chain[0]).try_normalize()?;
    // Initial radius: the plane slice across the limb at the seed.
    let loops = slice_plane_outer(mesh, seed, axis);
    let first = super::geometry::nearest_loop(&loops, seed)?;
    let radius = first.perimeter() / TAU;
    // March from the slice's barycentre: a seed off the limb's axis would cut one side only.
    let seed = first.centroid()?;
    let step = options.limb_step * height;
    // Length budget: the chain plus the overshoot.
    let last = chain.len() - 1;
    let chain_length: f64 = chain.windows(2).map(|w| w[0].distance(w[1])).sum::<f64>()
        + options.distal_overshoot * chain[last].distance(chain[last - 1]);
    let seed_to_end = chain_length - chain[0].distance(chain[1]) * 0.5;
    // Gaps are crossed only short of the chain's last point: past it the limb may end.
    let seed_to_last =
        seed_to_end - options.distal_overshoot * chain[last].distance(chain[last - 1]);
    let slicer = SphereSlicer::new(mesh);
    let outward = march(
        &slicer,
        seed,
        axis,
        radius,
        step,
        (seed_to_end, seed_to_last),
        chain,
        false,
        options,
    );
    let inward = march(
        &slicer,
        seed,
        -axis,
        radius,
        step,
        (0.5 * chain[0].distance(chain[1]), 0.0),
        chain,
        true,
        options,
    );
    let mut centres: Vec<(DVec3, f64, f64, f64)> = inward.into_iter().rev().collect();
    centres.extend(outward);
    if centres.len() < 4 {
        return None;
    }
    let mut arc = 0.0;
    let mut slices = Vec::with_capacity(centres.len());
    for (i, &(centre, perimeter, major, minor)) in centres.iter().enumerate() {
        if i > 0 {
            arc += centres[i - 1].0.distance(centre);
        }
        slices.push(LimbSlice {
            centre,
            perimeter,
            major,
            minor,
            arc,
        });
    }
    Some(LimbProfile { slices })
}

/// Slices in a row that an outward march steps over when their perimeter jumps above
/// `merge_ratio` times the previous one (before it takes the jump as the limb's end).
const MAX_SKIPS: usize = 2;

/// The widest gap an outward march steps across, in limb diameters (the limb's perimeter over
/// π): a limb built of separate pieces (a robot's forearm apart from its upper arm) leaves a
/// gap at the joint, which the joined surface closes by a thin bridge only, or not at all; a
/// gap wider than the limb is thick is no joint of one limb.
const MAX_GAP_DIAMETERS: f64 = 1.0;

/// Slices a march must take past a gap it crossed before it may cross another or end: the
/// limb found again, not the rim of a piece's end.
const SLICES_PAST_GAP: usize = 3;

/// Marches spheres from `start` along `direction` for at most `budget.0` of path
/// (`towards_torso` for the proximal march): returns (barycentre, perimeter, major, minor) per
/// slice. Outwards, within `budget.1` of path (short of the chain's last point, where the
/// limb is known to go on), a slice that loses the limb (no loop ahead, or one thinner than
/// `split_ratio` of the last) is stepped over when a slice at most [`MAX_GAP_DIAMETERS`]
/// further along the tube finds it again, as thick as it was: a gap between two pieces of one
/// limb, not its end. The march must have kept to its limb up to the gap, within the limb's
/// radius of the rough `chain`: one that has left it (drifted into a tunic over both legs)
/// is not sent on. A crossing counts once [`SLICES_PAST_GAP`] slices follow it; a march that
/// loses the limb again sooner drops them and ends at the gap.
#[allow(clippy::too_many_arguments)]
fn march(
    slicer: &SphereSlicer,
    start: DVec3,
    direction: DVec3,
    radius: f64,
    step: f64,
    budget: (f64, f64),
    chain: &[DVec3],
    towards_torso: bool,
    options: &RefineOptions,
) -> Vec<(DVec3, f64, f64, f64)> {
    let (budget, jump_budget) = budget;
    let mut out: Vec<(DVec3, f64, f64, f64)> = Vec::new();
    let (mut centre, mut dir, mut radius) = (start, direction, radius);
    let mut travelled = 0.0;
    let mut previous: Option<(f64, f64)> = None;
    let mut skipped = 0;
    // Slices before the last gap crossed, while the limb has not been found again past it.
    let mut before_gap: Option<usize> = None;
    let mut spent = false;
    let max_steps = (budget / step).ceil() as usize + 1;
    for _ in 0..max_steps {
        let rho = (options.sphere_radius_factor * radius).max(step);
        let ahead = (rho * rho - radius * radius).max(0.0).sqrt();
        let expected = centre + dir * ahead;
        let loops = slicer.slice(centre, rho);
        let mut slice = forward_loop(&loops, centre, dir, expected).cloned();
        // The limb is lost to a gap when the sphere meets nothing ahead, or only a sliver of
        // the limb (the rim of a piece's end, a thin bridge).
        let lost = |s: &Option<SliceLoop>| match (s, previous) {
            (None, Some(_)) => true,
            (Some(s), Some((p, _))) => s.perimeter() < options.split_ratio * p,
            (_, None) => false,
        };
        let settled = before_gap.is_none_or(|k| out.len() >= k + SLICES_PAST_GAP);
        if !towards_torso && travelled < jump_budget && settled && lost(&slice) {
            // The limb's section before it began to close (a piece's rounded end narrows
            // over the last slices).
            let before = out[out.len().saturating_sub(SLICES_PAST_GAP + 2)..]
                .iter()
                .map(|s| s.1)
                .fold(None, |m: Option<f64>, p| Some(m.map_or(p, |m| m.max(p))));
            let on_limb = before.filter(|&p| from_chain(chain, centre) <= p / TAU);
            if let Some(p) = on_limb {
                if let Some((jumped, found)) = across_gap(slicer, centre, dir, step, p, options) {
                    travelled += jumped.distance(centre);
                    centre = jumped;
                    slice = Some(found);
                    before_gap = Some(out.len());
                }
            }
        }
        let Some(slice) = slice else {
            break;
        };
        let (Some(g), Some(axes)) = (slice.centroid(), slice.principal_axes()) else {
            break;
        };
        let perimeter = slice.perimeter();
        // Towards the torso, merging is judged against the thinnest slice so far (the sphere
        // grows with the slices, so the torso can be entered in steps each below the ratio);
        // outwards against the previous slice, so that the trace turns into hand and foot.
        if let Some((p, thinnest)) = previous {
            let reference = if towards_torso { thinnest } else { p };
            let merged = perimeter > options.merge_ratio * reference;
            if merged && !towards_torso && skipped < MAX_SKIPS {
                // Outwards, a lone jump is a flaw of the surface (a sliver or a fold the sphere
                // caught): step over it along the tube and look again.
                skipped += 1;
                centre += dir * step;
                travelled += step;
                continue;
            }
            if merged || perimeter < options.split_ratio * p {
                break;
            }
        }
        skipped = 0;
        let thinnest = previous.map_or(perimeter, |(_, t)| t.min(perimeter));
        previous = Some((perimeter, thinnest));
        out.push((g, perimeter, axes.major_diameter, axes.minor_diameter));
        let Some(new_dir) = (g - centre).try_normalize() else {
            break;
        };
        // Follow the tube, but never turn back.
        if new_dir.dot(dir) <= 0.0 {
            break;
        }
        dir = new_dir;
        radius = perimeter / TAU;
        centre = g - dir * (g.distance(centre) - step).max(0.0);
        travelled += step;
        if travelled > budget {
            spent = true;
            break;
        }
    }
    // A gap that led nowhere (the limb lost again within a few slices) was no gap of this
    // limb: its slices are dropped, and the trace ends where it first lost the limb.
    if let Some(k) = before_gap {
        if !spent && out.len() < k + SLICES_PAST_GAP {
            out.truncate(k);
        }
    }
    out
}

/// The distance from `q` to the polyline `chain`.
fn from_chain(chain: &[DVec3], q: DVec3) -> f64 {
    chain
        .windows(2)
        .map(|w| point_segment_distance(q, w[0], w[1]))
        .fold(f64::INFINITY, f64::min)
}

/// The first slice past a gap: spheres as wide as the march's for a limb of `perimeter` (its
/// section before the gap), centred `step`, 2 `step`, ... further
/// from `centre` along `dir`, up to [`MAX_GAP_DIAMETERS`] limb diameters (`perimeter` over
/// π), until one finds a loop ahead between `split_ratio` and `merge_ratio` times `perimeter`
/// (the limb as thick as before the gap), and on while the loop still grows by more than
/// [`STILL_GROWING`] a step: the sphere first meets the next piece's rounded or capped end,
/// and takes the piece's whole section a little further on. Returns the sphere's centre and
/// the loop.
fn across_gap(
    slicer: &SphereSlicer,
    centre: DVec3,
    dir: DVec3,
    step: f64,
    perimeter: f64,
    options: &RefineOptions,
) -> Option<(DVec3, SliceLoop)> {
    let radius = perimeter / TAU;
    let rho = (options.sphere_radius_factor * radius).max(step);
    let ahead = (rho * rho - radius * radius).max(0.0).sqrt();
    let widest = MAX_GAP_DIAMETERS * perimeter / std::f64::consts::PI;
    let tries = (widest / step).floor() as usize;
    let probe = |k: usize| {
        let at = centre + dir * (k as f64 * step);
        let loops = slicer.slice(at, rho);
        let found = forward_loop(&loops, at, dir, at + dir * ahead)?.clone();
        let p = found.perimeter();
        (p >= options.split_ratio * perimeter && p <= options.merge_ratio * perimeter)
            .then_some((at, found))
    };
    let (mut k, mut best) = (1..=tries).find_map(|k| Some((k, probe(k)?)))?;
    while k < 2 * tries.max(1) {
        match probe(k + 1) {
            Some(next) if next.1.perimeter() > STILL_GROWING * best.1.perimeter() => {
                best = next;
                k += 1;
            }
            _ => break,
        }
    }
    Some(best)
}

/// A loop past a gap that grows by more than this factor from one step to the next is still
/// the next piece's end, not its section ([`across_gap`]).
const STILL_GROWING: f64 = 1.05;

/// The closed loop ahead of `centre` along `dir` whose barycentre is nearest `expected`.
fn forward_loop(
    loops: &[SliceLoop],
    centre: DVec3,
    dir: DVec3,
    expected: DVec3,
) -> Option<&SliceLoop> {
    loops
        .iter()
        .filter(|l| l.closed && l.points.len() >= 3)
        .filter_map(|l| Some((l, l.centroid()?)))
        .filter(|(_, g)| (*g - centre).dot(dir) > 0.0)
        .min_by(|a, b| {
            a.1.distance_squared(expected)
                .total_cmp(&b.1.distance_squared(expected))
        })
        .map(|(l, _)| l)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two closed capsules of radius 0.05 along -Y, the upper from y 1.0 to 0.5, the lower
    /// from `0.5 - gap` down to `0.05 - gap`: a limb of two pieces with a gap at its joint.
    fn two_pieces(gap: f64) -> Mesh {
        let upper = Mesh::capsule(DVec3::new(0.0, 0.75, 0.0), 0.05, 0.2, 6, 24);
        let lower = Mesh::capsule(DVec3::new(0.0, 0.25 - gap, 0.0), 0.05, 0.2, 6, 24);
        let base = upper.positions.len() as u32;
        let mut positions = upper.positions.clone();
        positions.extend(&lower.positions);
        let mut triangles = upper.triangles.clone();
        triangles.extend(lower.triangles.iter().map(|t| t.map(|i| i + base)));
        // Short edges: a sphere slice cuts only triangles with a corner inside it.
        let mut mesh = Mesh::new(positions, triangles).unwrap();
        for _ in 0..4 {
            mesh = mesh.subdivided();
        }
        mesh
    }

    fn lowest_slice(gap: f64) -> f64 {
        let mesh = two_pieces(gap);
        let chain = [
            DVec3::new(0.0, 0.95, 0.0),
            DVec3::new(0.0, 0.5 - 0.5 * gap, 0.0),
            DVec3::new(0.0, 0.1 - gap, 0.0),
        ];
        let profile = trace_limb(&mesh, &chain, 1.0, &RefineOptions::default()).unwrap();
        profile
            .slices
            .iter()
            .map(|s| s.centre.y)
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn a_limb_of_two_pieces_is_traced_across_the_gap_at_its_joint_but_not_across_a_wider_one() {
        // Half the limb's thickness apart: the slices go on into the lower piece.
        let across = lowest_slice(0.05);
        assert!(across < 0.2, "the trace stopped at {across}");
        // Twice its thickness apart: two limbs, not one; the trace ends with the upper piece.
        let stopped = lowest_slice(0.2);
        assert!(stopped > 0.45, "the trace crossed to {stopped}");
    }
}

//! Plumber-style sphere slicing of a limb (seed 004, 3.3; Mortara et al. 2004): slices along
//! the limb from a seed on the pre-aligned skeleton, with barycentre, perimeter and principal
//! diameters per slice, interpolated by cubic B-splines.

use super::RefineOptions;
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
    let slicer = SphereSlicer::new(mesh);
    let outward = march(
        &slicer,
        seed,
        axis,
        radius,
        step,
        seed_to_end,
        false,
        options,
    );
    let inward = march(
        &slicer,
        seed,
        -axis,
        radius,
        step,
        0.5 * chain[0].distance(chain[1]),
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

/// Marches spheres from `start` along `direction` for at most `budget` of path (`towards_torso`
/// for the proximal march): returns
/// (barycentre, perimeter, major, minor) per slice.
#[allow(clippy::too_many_arguments)]
fn march(
    slicer: &SphereSlicer,
    start: DVec3,
    direction: DVec3,
    radius: f64,
    step: f64,
    budget: f64,
    towards_torso: bool,
    options: &RefineOptions,
) -> Vec<(DVec3, f64, f64, f64)> {
    let mut out = Vec::new();
    let (mut centre, mut dir, mut radius) = (start, direction, radius);
    let mut travelled = 0.0;
    let mut previous: Option<(f64, f64)> = None;
    let mut skipped = 0;
    let max_steps = (budget / step).ceil() as usize + 1;
    for _ in 0..max_steps {
        let rho = (options.sphere_radius_factor * radius).max(step);
        let ahead = (rho * rho - radius * radius).max(0.0).sqrt();
        let expected = centre + dir * ahead;
        let loops = slicer.slice(centre, rho);
        let Some(slice) = forward_loop(&loops, centre, dir, expected) else {
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
            break;
        }
    }
    out
}

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

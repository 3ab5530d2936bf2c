//! BoundedDP (seed 003, 3.1, Algorithms 1 and 2): joints along a branch chosen by the axis and
//! the shape, with every simplified edge kept inside the branch's general cylinder.

use super::BoundedDpOptions;
use glam::DVec2;

/// A slice of the outline perpendicular to a branch's axis at one sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slice {
    /// The axis sample, outline units.
    pub centre: DVec2,
    /// Unit direction of the slice, to the left of the axis direction.
    pub normal: DVec2,
    /// Distance from the centre to the outline along `+normal` (outline units).
    pub left: f64,
    /// Distance from the centre to the outline along `-normal`.
    pub right: f64,
}

/// Uniform samples of a Catmull-Rom spline through `polyline`, about `spacing` apart (at least
/// two, the ends, which stay exactly at the polyline's ends; at most
/// [`MAX_RESAMPLED_POINTS`](super::MAX_RESAMPLED_POINTS)).
pub fn spline_samples(polyline: &[DVec2], spacing: f64) -> Vec<DVec2> {
    let n = polyline.len();
    if n < 2 {
        return polyline.to_vec();
    }
    const DENSE: usize = 8;
    let mut dense = Vec::with_capacity((n - 1) * DENSE + 1);
    for i in 0..n - 1 {
        let p0 = polyline[i.saturating_sub(1)];
        let (p1, p2) = (polyline[i], polyline[i + 1]);
        let p3 = polyline[(i + 2).min(n - 1)];
        for k in 0..DENSE {
            let t = k as f64 / DENSE as f64;
            let (t2, t3) = (t * t, t * t * t);
            dense.push(
                0.5 * ((2.0 * p1)
                    + (p2 - p0) * t
                    + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2
                    + (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3),
            );
        }
    }
    dense.push(polyline[n - 1]);
    let lengths: Vec<f64> = std::iter::once(0.0)
        .chain(dense.windows(2).scan(0.0, |s, w| {
            *s += w[0].distance(w[1]);
            Some(*s)
        }))
        .collect();
    let total = *lengths.last().unwrap_or(&0.0);
    let count = ((total / spacing.max(f64::MIN_POSITIVE))
        .round()
        .min(super::MAX_RESAMPLED_POINTS as f64) as usize)
        .max(1);
    let mut out = Vec::with_capacity(count + 1);
    let mut j = 0usize;
    for k in 0..=count {
        let s = total * k as f64 / count as f64;
        while j + 1 < lengths.len() - 1 && lengths[j + 1] < s {
            j += 1;
        }
        let span = lengths[j + 1] - lengths[j];
        let t = if span > 0.0 {
            ((s - lengths[j]) / span).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(dense[j].lerp(dense[j + 1], t));
    }
    out
}

/// The slice of `outline` (a closed polygon) through each sample, perpendicular to the
/// samples' polyline. A side that meets no edge gets distance 0.
pub fn slices(samples: &[DVec2], outline: &[DVec2]) -> Vec<Slice> {
    let n = samples.len();
    (0..n)
        .map(|i| {
            let a = samples[i.saturating_sub(1)];
            let b = samples[(i + 1).min(n - 1)];
            let normal = (b - a).normalize_or_zero().perp();
            let centre = samples[i];
            Slice {
                centre,
                normal,
                left: ray_distance(centre, normal, outline),
                right: ray_distance(centre, -normal, outline),
            }
        })
        .collect()
}

/// Distance along the ray from `origin` in direction `dir` to the nearest outline edge.
fn ray_distance(origin: DVec2, dir: DVec2, outline: &[DVec2]) -> f64 {
    let m = outline.len();
    let mut best = f64::INFINITY;
    for i in 0..m {
        let (a, b) = (outline[i], outline[(i + 1) % m]);
        let e = b - a;
        let denom = dir.perp_dot(e);
        if denom == 0.0 {
            continue;
        }
        let w = a - origin;
        let s = w.perp_dot(e) / denom;
        let u = w.perp_dot(dir) / denom;
        if s >= 0.0 && (0.0..=1.0).contains(&u) && s < best {
            best = s;
        }
    }
    if best.is_finite() {
        best
    } else {
        0.0
    }
}

/// Which samples BoundedDP keeps as joints (Algorithm 2): Algorithm 1 with threshold
/// `epsilon` (outline units), lowered by `options.reduction` until every simplified edge stays
/// inside the general cylinder of the slices (at most [`MAX_THRESHOLD_STEPS`] reductions, after
/// which every sample is kept). The ends are always kept.
pub fn bounded_dp(slices: &[Slice], epsilon: f64, options: &BoundedDpOptions) -> Vec<bool> {
    let n = slices.len();
    let mut epsilon = epsilon;
    let scale = slices
        .iter()
        .map(|s| s.left + s.right)
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for _ in 0..MAX_THRESHOLD_STEPS {
        let keep = select(slices, epsilon, options.shape_weight);
        if n <= 2 || inside(slices, &keep) || epsilon < 1e-9 * scale {
            return keep;
        }
        epsilon *= options.reduction.clamp(0.0, 0.99);
    }
    vec![true; n]
}

/// The most threshold reductions of [`bounded_dp`]'s Algorithm 2.
pub const MAX_THRESHOLD_STEPS: usize = 500;

/// Algorithm 1: the point of largest combined error `E = d⊥ + α (d⁺ + d⁻)` in each range
/// is kept, and the range split there while `E > epsilon`.
fn select(slices: &[Slice], epsilon: f64, alpha: f64) -> Vec<bool> {
    let n = slices.len();
    let mut keep = vec![false; n];
    if n == 0 {
        return keep;
    }
    keep[0] = true;
    keep[n - 1] = true;
    let arc: Vec<f64> = std::iter::once(0.0)
        .chain(slices.windows(2).scan(0.0, |s, w| {
            *s += w[0].centre.distance(w[1].centre);
            Some(*s)
        }))
        .collect();
    let mut stack = vec![(0usize, n - 1)];
    while let Some((st, en)) = stack.pop() {
        if en <= st + 1 {
            continue;
        }
        let (a, b) = (slices[st], slices[en]);
        let span = (arc[en] - arc[st]).max(f64::MIN_POSITIVE);
        let mut best = (st, 0.0);
        for i in st + 1..en {
            let s = &slices[i];
            let axis = crate::math::point_segment_distance(
                s.centre.extend(0.0),
                a.centre.extend(0.0),
                b.centre.extend(0.0),
            );
            let u = (arc[i] - arc[st]) / span;
            let shape = (s.left - (a.left + (b.left - a.left) * u)).abs()
                + (s.right - (a.right + (b.right - a.right) * u)).abs();
            let e = axis + alpha * shape;
            if e > best.1 {
                best = (i, e);
            }
        }
        if best.1 > epsilon {
            keep[best.0] = true;
            stack.push((st, best.0));
            stack.push((best.0, en));
        }
    }
    keep
}

/// Whether each simplified edge crosses every slice between its ends within the slice's
/// extent (the general cylinder Ω).
fn inside(slices: &[Slice], keep: &[bool]) -> bool {
    let kept: Vec<usize> = (0..slices.len()).filter(|&i| keep[i]).collect();
    for w in kept.windows(2) {
        let (p, q) = (slices[w[0]].centre, slices[w[1]].centre);
        let e = q - p;
        for s in &slices[w[0] + 1..w[1]] {
            let denom = s.normal.perp_dot(e);
            if denom.abs() < 1e-12 {
                return false;
            }
            let d = p - s.centre;
            let offset = d.perp_dot(e) / denom;
            let tolerance = 1e-9 * (s.left + s.right);
            if offset > s.left + tolerance || offset < -s.right - tolerance {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn strip(bend: f64) -> (Vec<DVec2>, Vec<DVec2>) {
        // A strip of half-width 1 around the axis y = bend * sin(pi x / 10), x in [0, 10].
        let axis: Vec<DVec2> = (0..=20)
            .map(|k| {
                let x = k as f64 * 0.5;
                DVec2::new(x, bend * (std::f64::consts::PI * x / 10.0).sin())
            })
            .collect();
        let mut outline: Vec<DVec2> = axis.iter().map(|p| *p - DVec2::Y).collect();
        outline.extend(axis.iter().rev().map(|p| *p + DVec2::Y));
        outline[0].x -= 1.0;
        outline[20].x += 1.0;
        let last = outline.len() - 1;
        outline[21].x += 1.0;
        outline[last].x -= 1.0;
        (axis, outline)
    }

    #[test]
    fn a_straight_strip_keeps_only_its_ends() {
        let (axis, outline) = strip(0.0);
        let samples = spline_samples(&axis, 0.25);
        let s = slices(&samples, &outline);
        let keep = bounded_dp(&s, 0.5, &BoundedDpOptions::default());
        assert_eq!(keep.iter().filter(|&&k| k).count(), 2);
    }

    #[test]
    fn a_bent_strip_gets_inner_joints_that_stay_inside() {
        let (axis, outline) = strip(3.0);
        let samples = spline_samples(&axis, 0.25);
        let s = slices(&samples, &outline);
        // Even with a huge threshold the chord would leave the strip: Algorithm 2 lowers it.
        let keep = bounded_dp(&s, 100.0, &BoundedDpOptions::default());
        assert!(keep.iter().filter(|&&k| k).count() >= 3);
        assert!(inside(&s, &keep));
    }
}

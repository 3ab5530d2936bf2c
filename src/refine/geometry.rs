//! Small geometric helpers shared by the refinement steps: loop choice, 2-D PCA, circle fit,
//! polyline resampling, line fit.

use crate::math::{point_covariance, principal_axes, principal_axis_2d};
use crate::mesh::SliceLoop;
use glam::DVec3;

/// The closed loop (or, without one, any piece) whose centroid is nearest `guess`.
pub fn nearest_loop(loops: &[SliceLoop], guess: DVec3) -> Option<&SliceLoop> {
    let best = |closed: bool| {
        loops
            .iter()
            .filter(|l| l.closed == closed)
            .filter_map(|l| Some((l, l.centroid()?.distance_squared(guess))))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(l, _)| l)
    };
    best(true).or_else(|| best(false))
}

/// The closed loop of a transverse slice (normal `up`) that encloses `guess` seen along `up`
/// (the largest such when pieces overlap), else [`nearest_loop`]: a head or neck made of many
/// shells (hair strands, eyes, a visor) has small loops whose centroids lie nearer the axis
/// than the head's own outline does.
pub fn enclosing_loop(loops: &[SliceLoop], up: DVec3, guess: DVec3) -> Option<&SliceLoop> {
    let u = up.any_orthonormal_vector();
    let v = up.cross(u);
    let flat = |p: DVec3| glam::DVec2::new(p.dot(u), p.dot(v));
    loops
        .iter()
        .filter(|l| l.closed)
        .filter(|l| {
            let polygon: Vec<glam::DVec2> = l.points.iter().map(|&p| flat(p)).collect();
            crate::outline::input::contains(&polygon, flat(guess))
        })
        .max_by(|a, b| a.perimeter().total_cmp(&b.perimeter()))
        .or_else(|| nearest_loop(loops, guess))
}

/// A 2-D segment `(start, end)`.
pub type Segment2 = ((f64, f64), (f64, f64));

/// Principal direction (unit) of 2-D polylines, and the ratio of the standard deviations
/// along the major and minor axes. The polylines count as uniform curves, not as their
/// vertices: each segment `(a, b)` counts with its length and its exact second moment, so
/// where a mesh happens to be finely or coarsely tessellated does not pull the axes (a 3k
/// simplification's head vertices turned the head's axis by 7 degrees). `None` when the
/// segments have no length or no spread.
pub fn pca_2d_curve(segments: &[Segment2]) -> Option<((f64, f64), f64)> {
    let length: f64 = segments.iter().map(|&(a, b)| dist(a, b)).sum();
    if length.is_nan() || length <= 0.0 {
        return None;
    }
    let (mx, my) = segments.iter().fold((0.0, 0.0), |(x, y), &(a, b)| {
        let w = dist(a, b) / length;
        (x + w * 0.5 * (a.0 + b.0), y + w * 0.5 * (a.1 + b.1))
    });
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for &(a, b) in segments {
        let w = dist(a, b) / length;
        let (p, q) = ((a.0 - mx, a.1 - my), (b.0 - mx, b.1 - my));
        // The integral of u v over the segment, divided by its length.
        let moment = |u: (f64, f64), v: (f64, f64)| {
            (2.0 * u.0 * u.1 + 2.0 * v.0 * v.1 + u.0 * v.1 + u.1 * v.0) / 6.0
        };
        sxx += w * moment((p.0, p.0), (q.0, q.0));
        syy += w * moment((p.1, p.1), (q.1, q.1));
        sxy += w * moment((p.0, p.1), (q.0, q.1));
    }
    principal_axis_2d((sxx, sxy, syy))
}

fn dist(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - b.0).hypot(a.1 - b.1)
}

/// Least-squares circle (Kåsa fit) through 2-D points: `(centre, radius)`, or `None` for fewer
/// than three points or collinear ones.
pub fn fit_circle(points: &[(f64, f64)]) -> Option<((f64, f64), f64)> {
    if points.len() < 3 {
        return None;
    }
    // Centre the data for conditioning, then solve the 3x3 normal equations of
    // x² + y² + D x + E y + F = 0.
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
    let mut m = nalgebra::Matrix3::<f64>::zeros();
    let mut v = nalgebra::Vector3::<f64>::zeros();
    for p in points {
        let (x, y) = (p.0 - mx, p.1 - my);
        let row = nalgebra::Vector3::new(x, y, 1.0);
        m += row * row.transpose();
        v += row * -(x * x + y * y);
    }
    let s = m.lu().solve(&v)?;
    let (cx, cy) = (-s[0] / 2.0, -s[1] / 2.0);
    let r2 = cx * cx + cy * cy - s[2];
    (r2 > 0.0 && cx.is_finite() && cy.is_finite()).then(|| ((cx + mx, cy + my), r2.sqrt()))
}

/// Points every `step` (arc length) along the polyline `points` (closed when `closed`).
pub fn resample(points: &[DVec3], closed: bool, step: f64) -> Vec<DVec3> {
    if points.len() < 2 || step <= 0.0 {
        return points.to_vec();
    }
    let mut path = points.to_vec();
    if closed {
        path.push(points[0]);
    }
    let mut out = vec![path[0]];
    let mut carry = 0.0;
    for w in path.windows(2) {
        let length = w[0].distance(w[1]);
        let mut t = step - carry;
        while t <= length {
            out.push(w[0].lerp(w[1], t / length));
            t += step;
        }
        carry = length - (t - step);
    }
    if closed && out.len() > 1 && out[out.len() - 1].distance(out[0]) < step * 0.5 {
        out.pop();
    }
    out
}

/// Least-squares line through `points`: `(point on line, unit direction)` with the direction
/// oriented from the first point towards the last; `None` for fewer than two distinct points.
pub fn fit_line(points: &[DVec3]) -> Option<(DVec3, DVec3)> {
    if points.len() < 2 {
        return None;
    }
    let (mean, covariance) = point_covariance(points);
    let [(_, major), ..] = principal_axes(covariance);
    let mut dir = major.try_normalize()?;
    if dir.dot(points[points.len() - 1] - points[0]) < 0.0 {
        dir = -dir;
    }
    Some((mean, dir))
}

/// Angle at `q` between the directions to `a` and `b`, radians (π for a straight line).
pub fn angle_at(a: DVec3, q: DVec3, b: DVec3) -> f64 {
    let (u, v) = (a - q, b - q);
    let denom = u.length() * v.length();
    if denom == 0.0 {
        std::f64::consts::PI
    } else {
        (u.dot(v) / denom).clamp(-1.0, 1.0).acos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed rectangle `w` × `h` as segments, its left side cut into `pieces` segments.
    fn rectangle(w: f64, h: f64, pieces: usize) -> Vec<Segment2> {
        let mut s = vec![
            ((0.0, 0.0), (w, 0.0)),
            ((w, 0.0), (w, h)),
            ((w, h), (0.0, h)),
        ];
        for k in 0..pieces {
            let y = |k: usize| h - h * k as f64 / pieces as f64;
            s.push(((0.0, y(k)), (0.0, y(k + 1))));
        }
        s
    }

    #[test]
    fn curve_axes_do_not_follow_where_the_points_are_dense() {
        // 2 wide, 1.6 high: the long axis is x however finely the short left side is cut
        // (the vertices' own PCA turns to y once that side holds most of them).
        let (_, whole) = pca_2d_curve(&rectangle(2.0, 1.6, 1)).unwrap();
        assert!(whole > 1.1, "{whole}");
        for pieces in [1, 10, 400] {
            let ((x, y), ratio) = pca_2d_curve(&rectangle(2.0, 1.6, pieces)).unwrap();
            assert!(x.abs() > 0.999_999 && y.abs() < 1e-3, "{pieces}: {x} {y}");
            assert!((ratio - whole).abs() < 1e-9, "{pieces}: {ratio}");
        }
        // Major axis along the second coordinate.
        let ((x, y), _) = pca_2d_curve(&rectangle(1.6, 2.0, 7)).unwrap();
        assert!(y.abs() > 0.999_999 && x.abs() < 1e-3, "{x} {y}");
        assert!(pca_2d_curve(&[]).is_none());
        assert!(pca_2d_curve(&[((1.0, 1.0), (1.0, 1.0))]).is_none());
    }
}

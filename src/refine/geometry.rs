//! Small geometric helpers shared by the refinement steps: loop choice, 2-D PCA, circle fit,
//! polyline resampling, line fit.

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

/// Principal direction of 2-D points (unit) and the ratio of the standard deviations along the
/// major and minor axes; `None` for fewer than two distinct points.
pub fn pca_2d(points: &[(f64, f64)]) -> Option<((f64, f64), f64)> {
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for p in points {
        let (dx, dy) = (p.0 - mx, p.1 - my);
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    let trace = sxx + syy;
    let det = sxx * syy - sxy * sxy;
    let disc = (trace * trace / 4.0 - det).max(0.0).sqrt();
    let (l1, l2) = (trace / 2.0 + disc, trace / 2.0 - disc);
    if l1 <= 0.0 {
        return None;
    }
    let dir = if sxy.abs() > 1e-300 {
        (l1 - syy, sxy)
    } else if sxx >= syy {
        (1.0, 0.0)
    } else {
        (0.0, 1.0)
    };
    let len = (dir.0 * dir.0 + dir.1 * dir.1).sqrt();
    let ratio = (l1 / l2.max(l1 * 1e-12)).sqrt();
    Some(((dir.0 / len, dir.1 / len), ratio))
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
    let mean = points.iter().sum::<DVec3>() / points.len() as f64;
    let mut c = nalgebra::Matrix3::<f64>::zeros();
    for p in points {
        let d = *p - mean;
        let v = nalgebra::Vector3::new(d.x, d.y, d.z);
        c += v * v.transpose();
    }
    let eigen = nalgebra::SymmetricEigen::new(c);
    let k = eigen.eigenvalues.imax();
    let e = eigen.eigenvectors.column(k);
    let mut dir = DVec3::new(e[0], e[1], e[2]).try_normalize()?;
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

//! Principal component analysis: the covariance of a point set, the principal axes of a 3×3
//! covariance (and its major axis alone by power iteration), and the closed-form principal
//! axis of a 2×2 one.
//!
//! Callers build the covariance that suits their data (a point set, or a curve whose segments
//! count with their length and exact second moment, `mesh::SliceLoop::principal_axes`) and
//! share the decomposition.

use glam::DVec3;
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// Mean of `points` and the sum over them of the outer product of their deviation from it (the
/// covariance times the number of points). `points` must not be empty.
pub(crate) fn point_covariance(points: &[DVec3]) -> (DVec3, Matrix3<f64>) {
    let mean = points.iter().sum::<DVec3>() / points.len() as f64;
    let mut covariance = Matrix3::<f64>::zeros();
    for p in points {
        let d = *p - mean;
        let v = Vector3::new(d.x, d.y, d.z);
        covariance += v * v.transpose();
    }
    (mean, covariance)
}

/// Principal axes of the symmetric `covariance` (any positive scale): `(eigenvalue,
/// eigenvector)` pairs from the largest eigenvalue down, ties in the decomposition's order.
/// The eigenvectors are the decomposition's unit columns; callers that need a guaranteed unit
/// or non-zero axis normalise them as suits them.
pub(crate) fn principal_axes(covariance: Matrix3<f64>) -> [(f64, DVec3); 3] {
    let eigen = SymmetricEigen::new(covariance);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| eigen.eigenvalues[j].total_cmp(&eigen.eigenvalues[i]));
    order.map(|k| {
        let c = eigen.eigenvectors.column(k);
        (eigen.eigenvalues[k], DVec3::new(c[0], c[1], c[2]))
    })
}

/// Major axis (unit) of the symmetric `covariance` by 100 steps of power iteration from
/// `(1, 0.7, 0.3)`: deterministic in sign (towards the start), `None` when an iterate
/// vanishes (no spread along the start). The labelling's trunk axis; its angle to up is written
/// at full precision (labels.json `trunk_angle_deg`), which [`principal_axes`]'
/// decomposition would move in the last digits.
pub(crate) fn major_axis_by_iteration(covariance: Matrix3<f64>) -> Option<DVec3> {
    let m = glam::DMat3::from_cols_slice(covariance.as_slice());
    let mut v = DVec3::new(1.0, 0.7, 0.3).normalize();
    for _ in 0..100 {
        v = (m * v).try_normalize()?;
    }
    Some(v)
}

/// Principal axis of the 2×2 symmetric covariance `(sxx, sxy, syy)` in closed form: the major
/// direction (unit) and the ratio of the standard deviations along the major and minor axes
/// (capped at 10⁶ for a flat spread). `None` when there is no spread; `((1, 0), 1)` for an
/// isotropic one.
pub(crate) fn principal_axis_2d((sxx, sxy, syy): (f64, f64, f64)) -> Option<((f64, f64), f64)> {
    let trace = sxx + syy;
    let det = sxx * syy - sxy * sxy;
    let disc = (trace * trace / 4.0 - det).max(0.0).sqrt();
    let (l1, l2) = (trace / 2.0 + disc, trace / 2.0 - disc);
    if l1 <= 0.0 {
        return None;
    }
    // Two forms of the same eigenvector; the longer one is the well-conditioned one (the
    // first vanishes when the major axis is the second coordinate's, the second when it is
    // the first's).
    let (a, b) = ((l1 - syy, sxy), (sxy, l1 - sxx));
    let dir = if a.0.hypot(a.1) >= b.0.hypot(b.1) {
        a
    } else {
        b
    };
    if dir.0.hypot(dir.1) <= 0.0 {
        return Some(((1.0, 0.0), 1.0));
    }
    let len = (dir.0 * dir.0 + dir.1 * dir.1).sqrt();
    let ratio = (l1 / l2.max(l1 * 1e-12)).sqrt();
    Some(((dir.0 / len, dir.1 / len), ratio))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_along_a_line_have_one_principal_axis() {
        let points: Vec<DVec3> = (0..5)
            .map(|k| DVec3::new(1.0, 2.0, 2.0) * k as f64)
            .collect();
        let (mean, covariance) = point_covariance(&points);
        assert!((mean - DVec3::new(2.0, 4.0, 4.0)).length() < 1e-12);
        let [(major, axis), (second, _), (third, _)] = principal_axes(covariance);
        assert!(major > 0.0 && second.abs() < 1e-9 && third.abs() < 1e-9);
        assert!((axis.dot(DVec3::new(1.0, 2.0, 2.0) / 3.0).abs() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_2d_spread_gives_its_major_direction_and_ratio() {
        let ((x, y), ratio) = principal_axis_2d((4.0, 0.0, 1.0)).unwrap();
        assert_eq!((x.abs(), y), (1.0, 0.0));
        assert!((ratio - 2.0).abs() < 1e-12);
        assert_eq!(principal_axis_2d((1.0, 0.0, 1.0)), Some(((1.0, 0.0), 1.0)));
        assert!(principal_axis_2d((0.0, 0.0, 0.0)).is_none());
    }
}

//! Uniform resampling of a closed stroke by arc length (seed 003, 3.1: "uniformly discretizing
//! the raw line by a small length" smooths out the noise of unsteady strokes).

use glam::DVec2;

/// The most points [`resample`] produces, however small the spacing.
pub const MAX_RESAMPLED_POINTS: usize = 1 << 20;

/// Points at equal arc-length steps of about `spacing` along the closed polyline `points`
/// (outline units), starting at `points[0]`. The step is adjusted so the perimeter divides into
/// a whole number (at least 3, at most [`MAX_RESAMPLED_POINTS`]) of equal steps. Returns the
/// input unchanged when it has fewer than 3 points or `spacing` is not positive.
pub fn resample(points: &[DVec2], spacing: f64) -> Vec<DVec2> {
    let n = points.len();
    let perimeter = super::input::perimeter(points);
    if n < 3 || spacing.is_nan() || spacing <= 0.0 || perimeter.is_nan() || perimeter <= 0.0 {
        return points.to_vec();
    }
    let count = ((perimeter / spacing)
        .round()
        .min(MAX_RESAMPLED_POINTS as f64) as usize)
        .max(3);
    let step = perimeter / count as f64;
    let mut out = Vec::with_capacity(count);
    let mut edge = 0usize;
    let mut edge_start = 0.0; // arc length at points[edge]
    let mut edge_length = points[0].distance(points[1 % n]);
    for k in 0..count {
        let s = k as f64 * step;
        while s > edge_start + edge_length && edge + 1 < n {
            edge_start += edge_length;
            edge += 1;
            edge_length = points[edge].distance(points[(edge + 1) % n]);
        }
        let t = if edge_length > 0.0 {
            ((s - edge_start) / edge_length).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(points[edge].lerp(points[(edge + 1) % n], t));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_resampled_has_equal_steps_on_its_boundary() {
        let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
        let r = resample(&square, 0.1);
        assert_eq!(r.len(), 40);
        for i in 0..r.len() {
            let d = r[i].distance(r[(i + 1) % r.len()]);
            // Steps across a corner are shorter (the chord of the two legs).
            assert!(d <= 0.1 + 1e-12 && d > 0.07, "{d}");
            let p = r[i];
            let on = p.x.abs() < 1e-12
                || p.y.abs() < 1e-12
                || (p.x - 1.0).abs() < 1e-12
                || (p.y - 1.0).abs() < 1e-12;
            assert!(on);
        }
    }
}

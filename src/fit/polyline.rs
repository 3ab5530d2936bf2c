//! Arc-length parameterised polylines: evaluation, projection, sphere exit, smoothing.

use glam::DVec3;

/// A polyline with cumulative arc lengths (mesh units).
#[derive(Debug, Clone)]
pub(crate) struct Polyline {
    pub points: Vec<DVec3>,
    pub cum: Vec<f64>,
}

impl Polyline {
    /// A polyline through `points` (at least one).
    pub fn new(points: Vec<DVec3>) -> Self {
        let mut cum = Vec::with_capacity(points.len());
        let mut s = 0.0;
        for (k, p) in points.iter().enumerate() {
            if k > 0 {
                s += p.distance(points[k - 1]);
            }
            cum.push(s);
        }
        Self { points, cum }
    }

    pub fn length(&self) -> f64 {
        self.cum.last().copied().unwrap_or(0.0)
    }

    /// Segment index and parameter in it for arc length `s` (clamped).
    fn locate(&self, s: f64) -> (usize, f64) {
        let n = self.points.len();
        if n < 2 {
            return (0, 0.0);
        }
        let s = s.clamp(0.0, self.length());
        let k = self.cum.partition_point(|&c| c <= s).clamp(1, n - 1) - 1;
        let len = self.cum[k + 1] - self.cum[k];
        let t = if len > 0.0 {
            (s - self.cum[k]) / len
        } else {
            0.0
        };
        (k, t)
    }

    /// The point at arc length `s` (clamped to the ends).
    pub fn at(&self, s: f64) -> DVec3 {
        if self.points.len() < 2 {
            return self.points.first().copied().unwrap_or(DVec3::ZERO);
        }
        let (k, t) = self.locate(s);
        self.points[k].lerp(self.points[k + 1], t)
    }

    /// Linear interpolation of per-point `values` at arc length `s`.
    pub fn value_at(&self, values: &[f64], s: f64) -> f64 {
        if values.len() < 2 || self.points.len() < 2 {
            return values.first().copied().unwrap_or(0.0);
        }
        let (k, t) = self.locate(s);
        values[k] * (1.0 - t) + values[k + 1] * t
    }

    /// Unit direction of increasing arc length at `s` (the first non-degenerate segment at or
    /// after it, else before it); zero for a single point.
    pub fn tangent(&self, s: f64) -> DVec3 {
        let n = self.points.len();
        if n < 2 {
            return DVec3::ZERO;
        }
        let (k, _) = self.locate(s);
        (k..n - 1)
            .chain((0..k).rev())
            .map(|i| self.points[i + 1] - self.points[i])
            .find_map(|d| d.try_normalize())
            .unwrap_or(DVec3::ZERO)
    }

    /// Arc length of the point of the polyline nearest `p` (first one on ties).
    pub fn project(&self, p: DVec3) -> f64 {
        if self.points.len() < 2 {
            return 0.0;
        }
        let mut best = (f64::INFINITY, 0.0);
        for k in 0..self.points.len() - 1 {
            let a = self.points[k];
            let d = self.points[k + 1] - a;
            let len2 = d.length_squared();
            let t = if len2 > 0.0 {
                ((p - a).dot(d) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let dist = (a + d * t).distance_squared(p);
            if dist < best.0 {
                best = (dist, self.cum[k] + t * (self.cum[k + 1] - self.cum[k]));
            }
        }
        best.1
    }

    /// Arc length where the polyline first leaves the sphere `(centre, radius)`: 0 when it
    /// starts outside, `None` when it never leaves.
    pub fn sphere_exit(&self, centre: DVec3, radius: f64) -> Option<f64> {
        let first = *self.points.first()?;
        if first.distance(centre) >= radius {
            return Some(0.0);
        }
        for k in 0..self.points.len().saturating_sub(1) {
            let a = self.points[k];
            let b = self.points[k + 1];
            if b.distance(centre) < radius {
                continue;
            }
            // |a + t (b - a) - c| = r, a inside, b outside: the larger root in [0, 1].
            let d = b - a;
            let f = a - centre;
            let qa = d.length_squared();
            let qb = 2.0 * f.dot(d);
            let qc = f.length_squared() - radius * radius;
            let disc = (qb * qb - 4.0 * qa * qc).max(0.0);
            let t = if qa > 0.0 {
                ((-qb + disc.sqrt()) / (2.0 * qa)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            return Some(self.cum[k] + t * (self.cum[k + 1] - self.cum[k]));
        }
        None
    }
}

/// Cumulative boundaries of `weights` normalised to `[0, 1]`: `weights.len() + 1` values
/// starting at 0 and ending at 1.
pub(crate) fn boundaries(weights: &[f64]) -> Vec<f64> {
    let total: f64 = weights.iter().sum();
    let mut out = vec![0.0];
    let mut acc = 0.0;
    for w in weights {
        acc += w;
        out.push(if total > 0.0 { acc / total } else { 0.0 });
    }
    if let Some(last) = out.last_mut() {
        *last = 1.0;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bent() -> Polyline {
        Polyline::new(vec![
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
        ])
    }

    #[test]
    fn arc_length_evaluation_and_projection() {
        let p = bent();
        assert_eq!(p.length(), 3.0);
        assert!((p.at(2.0) - DVec3::new(1.0, 1.0, 0.0)).length() < 1e-12);
        assert!((p.at(9.0) - DVec3::new(1.0, 2.0, 0.0)).length() < 1e-12);
        assert!((p.project(DVec3::new(3.0, 1.5, 0.0)) - 2.5).abs() < 1e-12);
        assert_eq!(p.tangent(2.0), DVec3::Y);
        assert!((p.value_at(&[0.0, 1.0, 3.0], 2.0) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn sphere_exit_is_on_the_sphere() {
        let p = bent();
        let s = p.sphere_exit(DVec3::ZERO, 1.5).unwrap();
        assert!((p.at(s).length() - 1.5).abs() < 1e-9);
        assert_eq!(p.sphere_exit(DVec3::new(-5.0, 0.0, 0.0), 1.0), Some(0.0));
        assert_eq!(p.sphere_exit(DVec3::ZERO, 10.0), None);
    }

    #[test]
    fn boundaries_are_normalised() {
        let b = boundaries(&[1.0, 3.0]);
        assert_eq!(b, vec![0.0, 0.25, 1.0]);
    }
}

//! The moving average (box filter) of polylines: chain smoothing (dissertation Figure 5.6),
//! the fit's spine and limb paths, ear paths.

use glam::DVec3;

/// How [`moving_average`] treats the two ends of a polyline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Ends {
    /// The window shrinks symmetrically near the ends (a box filter limited at the ends,
    /// dissertation Figure 5.6), so each end point is the average of itself alone: the ends
    /// stay where they are (up to the sign of a zero coordinate).
    Shrink,
    /// The end points are copied as they are, as is the whole polyline when it has fewer than
    /// three points or `half` is 0; the inner points are averaged as with [`Ends::Shrink`].
    Keep,
}

/// Moving average of `points` over `half` neighbours each side (`2 half + 1` points), the
/// window shrinking symmetrically near the ends so that it stays centred; `ends` says what the
/// end points become. The output has as many points as the input.
pub(crate) fn moving_average(points: &[DVec3], half: usize, ends: Ends) -> Vec<DVec3> {
    let n = points.len();
    if ends == Ends::Keep && (half == 0 || n < 3) {
        return points.to_vec();
    }
    let mut out: Vec<DVec3> = (0..n)
        .map(|k| {
            let h = half.min(k).min(n - 1 - k);
            let sum: DVec3 = points[k - h..=k + h].iter().copied().sum();
            sum / (2 * h + 1) as f64
        })
        .collect();
    if ends == Ends::Keep {
        out[0] = points[0];
        out[n - 1] = points[n - 1];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smoothing_follows_figure_5_6() {
        let p: Vec<DVec3> = (0..12)
            .map(|i| DVec3::new(i as f64, (i % 2) as f64, 0.0))
            .collect();
        let s = moving_average(&p, 2, Ends::Shrink);
        assert_eq!(s[0], p[0]);
        assert_eq!(s[11], p[11]);
        assert_eq!(s[1], (p[0] + p[1] + p[2]) / 3.0);
        assert_eq!(s[5], (p[3] + p[4] + p[5] + p[6] + p[7]) / 5.0);
    }

    #[test]
    fn smoothing_keeps_lines_and_ends() {
        let line: Vec<DVec3> = (0..10).map(|k| DVec3::X * k as f64).collect();
        assert_eq!(moving_average(&line, 3, Ends::Shrink), line);
        assert_eq!(moving_average(&line, 3, Ends::Keep), line);
    }

    #[test]
    fn kept_ends_keep_the_sign_of_zero() {
        let p = vec![
            DVec3::new(-0.0, 1.0, 0.0),
            DVec3::X,
            DVec3::new(2.0, -0.0, 0.0),
        ];
        let kept = moving_average(&p, 1, Ends::Keep);
        assert!(kept[0].x.is_sign_negative() && kept[2].y.is_sign_negative());
        let shrunk = moving_average(&p, 1, Ends::Shrink);
        assert!(shrunk[0].x.is_sign_positive());
        assert_eq!(moving_average(&p, 0, Ends::Keep), p);
    }
}

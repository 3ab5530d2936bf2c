//! Numeric helpers shared by several stages.

use glam::DVec3;

/// Moving average over `half` neighbours each side, the window shrinking symmetrically near the
/// ends so the end points stay fixed (a box filter limited at the ends, dissertation Figure
/// 5.6).
pub(crate) fn moving_average(points: &[DVec3], half: usize) -> Vec<DVec3> {
    let n = points.len();
    (0..n)
        .map(|k| {
            let h = half.min(k).min(n - 1 - k);
            let sum: DVec3 = points[k - h..=k + h].iter().copied().sum();
            sum / (2 * h + 1) as f64
        })
        .collect()
}

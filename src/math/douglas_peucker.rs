//! Douglas-Peucker simplification of polylines and closed polygons (Douglas & Peucker 1973;
//! seed 003, 3.1).

use glam::DVec3;

/// Distance from `p` to the segment `ab`.
pub fn point_segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    p.distance(closest_on_segment(p, a, b).1)
}

/// The parameter in `[0, 1]` and the point of segment `ab` nearest `p` (`(0, a)` when
/// `a == b`).
pub fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> (f64, DVec3) {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2 == 0.0 {
        return (0.0, a);
    }
    let t = ((p - a).dot(ab) / len2).clamp(0.0, 1.0);
    (t, a + ab * t)
}

/// Which points of the open polyline `points` Douglas-Peucker keeps for tolerance `epsilon`
/// (same units as the points): the ends always, and recursively the point farthest from the
/// chord of its range while that distance exceeds `epsilon`. The kept set only shrinks as
/// `epsilon` grows (the farthest point of a range does not depend on `epsilon`).
pub fn douglas_peucker(points: &[DVec3], epsilon: f64) -> Vec<bool> {
    let n = points.len();
    let mut keep = vec![false; n];
    if n == 0 {
        return keep;
    }
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0usize, n - 1)];
    while let Some((start, end)) = stack.pop() {
        if end <= start + 1 {
            continue;
        }
        let (a, b) = (points[start], points[end]);
        let mut best = (start, 0.0);
        for (i, p) in points.iter().enumerate().take(end).skip(start + 1) {
            let d = point_segment_distance(*p, a, b);
            if d > best.1 {
                best = (i, d);
            }
        }
        if best.1 > epsilon {
            keep[best.0] = true;
            stack.push((start, best.0));
            stack.push((best.0, end));
        }
    }
    keep
}

/// Douglas-Peucker on a closed polygon: the polygon is cut at its first point and the point
/// farthest from it, and each half is simplified as an open polyline. Returns the indices of
/// the kept points in order.
pub fn douglas_peucker_closed(points: &[DVec3], epsilon: f64) -> Vec<usize> {
    let n = points.len();
    if n <= 3 {
        return (0..n).collect();
    }
    let far = (1..n)
        .max_by(|&a, &b| {
            points[a]
                .distance_squared(points[0])
                .total_cmp(&points[b].distance_squared(points[0]))
                .then(b.cmp(&a))
        })
        .unwrap_or(n / 2);
    let first: Vec<DVec3> = points[..=far].to_vec();
    let mut second: Vec<DVec3> = points[far..].to_vec();
    second.push(points[0]);
    let keep_first = douglas_peucker(&first, epsilon);
    let keep_second = douglas_peucker(&second, epsilon);
    let mut out: Vec<usize> = (0..=far).filter(|&i| keep_first[i]).collect();
    out.extend((far + 1..n).filter(|&i| keep_second[i - far]));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_zigzag_keeps_its_corners_and_drops_collinear_points() {
        let pts: Vec<DVec3> = [0.0, 1.0, 2.0, 3.0, 4.0]
            .iter()
            .map(|&x| DVec3::new(x, if x == 2.0 { 1.0 } else { 0.0 }, 0.0))
            .chain([DVec3::new(5.0, 0.0, 0.0)])
            .collect();
        let keep = douglas_peucker(&pts, 0.7);
        assert_eq!(keep, vec![true, false, true, false, false, true]);
        assert_eq!(
            douglas_peucker(&pts, 2.0),
            vec![true, false, false, false, false, true]
        );
    }

    #[test]
    fn a_dense_circle_becomes_a_polygon_within_tolerance() {
        let pts: Vec<DVec3> = (0..400)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 400.0;
                DVec3::new(a.cos(), a.sin(), 0.0)
            })
            .collect();
        let kept = douglas_peucker_closed(&pts, 0.01);
        assert!(kept.len() > 10 && kept.len() < 40, "{}", kept.len());
        for (k, &i) in kept.iter().enumerate() {
            let j = kept[(k + 1) % kept.len()];
            let mid = (pts[i] + pts[j]) * 0.5;
            assert!(1.0 - mid.length() <= 0.0101);
        }
    }
}

//! Simplicity of a closed polygon: the first pair of crossing or touching edges, found through
//! a uniform grid of edge bounding boxes (about linear time for evenly spaced outlines).

use glam::DVec2;
use std::collections::HashMap;

/// Whether segments `a0a1` and `b0b1` intersect (touching counts); the intersection point.
pub(crate) fn segment_intersection(a0: DVec2, a1: DVec2, b0: DVec2, b1: DVec2) -> Option<DVec2> {
    let r = a1 - a0;
    let s = b1 - b0;
    let denom = r.perp_dot(s);
    let qp = b0 - a0;
    if denom == 0.0 {
        // Parallel: overlapping collinear segments intersect.
        if qp.perp_dot(r) != 0.0 {
            return None;
        }
        let rr = r.length_squared();
        if rr == 0.0 {
            return None;
        }
        let t0 = qp.dot(r) / rr;
        let t1 = (b1 - a0).dot(r) / rr;
        let (lo, hi) = (t0.min(t1), t0.max(t1));
        if hi < 0.0 || lo > 1.0 {
            return None;
        }
        return Some(a0 + r * lo.clamp(0.0, 1.0));
    }
    let t = qp.perp_dot(s) / denom;
    let u = qp.perp_dot(r) / denom;
    if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u) {
        Some(a0 + r * t)
    } else {
        None
    }
}

/// The first pair of non-adjacent edges of the closed polygon `points` that intersect (edge
/// `i` runs from point `i` to point `i + 1`), or adjacent edges that overlap; `None` for a
/// simple polygon.
pub(crate) fn first_crossing(points: &[DVec2]) -> Option<(usize, usize, DVec2)> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let (lo, hi) = super::input::bounds(points);
    let mean = super::input::perimeter(points) / n as f64;
    let extent = (hi - lo).max_element();
    let cell = mean.max(extent / 1024.0).max(f64::MIN_POSITIVE);
    let key = |p: DVec2| -> (i64, i64) {
        let c = ((p - lo) / cell).floor();
        (c.x as i64, c.y as i64)
    };
    let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        let (k0, k1) = (key(a.min(b)), key(a.max(b)));
        for x in k0.0..=k1.0 {
            for y in k0.1..=k1.1 {
                cells.entry((x, y)).or_default().push(i);
            }
        }
    }
    let mut best: Option<(usize, usize, DVec2)> = None;
    for list in cells.values() {
        for (u, &i) in list.iter().enumerate() {
            for &j in &list[u + 1..] {
                let (i, j) = (i.min(j), i.max(j));
                if best.is_some_and(|(bi, bj, _)| (bi, bj) <= (i, j)) {
                    continue;
                }
                let adjacent = j == i + 1 || (i == 0 && j == n - 1);
                let (a0, a1) = (points[i], points[(i + 1) % n]);
                let (b0, b1) = (points[j], points[(j + 1) % n]);
                let hit = if adjacent {
                    adjacent_overlap(a0, a1, b0, b1, j == i + 1)
                } else {
                    segment_intersection(a0, a1, b0, b1)
                };
                if let Some(p) = hit {
                    best = Some((i, j, p));
                }
            }
        }
    }
    best
}

/// Adjacent edges share a point; they only make a polygon non-simple when they fold back onto
/// each other (a spike of zero width).
fn adjacent_overlap(a0: DVec2, a1: DVec2, b0: DVec2, b1: DVec2, forward: bool) -> Option<DVec2> {
    let (shared, p, q) = if forward { (a1, a0, b1) } else { (a0, a1, b0) };
    let (u, v) = (p - shared, q - shared);
    (u.perp_dot(v) == 0.0 && u.dot(v) > 0.0).then_some(shared)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_star_polygon_is_simple_and_a_bow_tie_is_not() {
        let star: Vec<DVec2> = (0..200)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 200.0;
                let r = if k % 2 == 0 { 1.0 } else { 0.5 };
                DVec2::new(a.cos(), a.sin()) * r
            })
            .collect();
        assert!(first_crossing(&star).is_none());
        let bow = [DVec2::ZERO, DVec2::ONE, DVec2::X, DVec2::Y];
        let (i, j, p) = first_crossing(&bow).unwrap();
        assert_eq!((i, j), (0, 2));
        assert!((p - DVec2::splat(0.5)).length() < 1e-12);
        let spike = [DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::X, DVec2::Y];
        assert!(first_crossing(&spike).is_some());
    }
}

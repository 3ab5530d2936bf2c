//! Characteristic points of the torso on its median-plane silhouette (seed 004, 3.2) and the
//! hips from the transverse slice between crotch and sacroiliac heights (3.3, fig. 4a).

use super::frame::BodyFrame;
use super::geometry::resample;
use super::RefineOptions;
use crate::mesh::{slice_plane_outer, Mesh, PlaneSlicer, SliceLoop};
use bspline::BSpline;
use glam::DVec3;

/// Heights (along the body's up) of the rough skeleton that bound the searches on the
/// silhouette.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorsoBounds {
    /// Height of the (refined) head joint.
    pub head: f64,
    /// Mean height of the rough shoulders.
    pub shoulders: f64,
    /// Mean height of the rough hips.
    pub hips: f64,
}

/// The characteristic points of the torso silhouette (seed 004, 3.2, fig. 3c), mesh units.
#[derive(Debug, Clone, PartialEq)]
pub struct TorsoPoints {
    /// Back of the neck: local maximum of the forward coordinate on the back.
    pub neck: DVec3,
    /// Upper back: local minimum (the thoracic bulge).
    pub back: DVec3,
    /// Lower back: local maximum (the lumbar hollow).
    pub lumbar: DVec3,
    /// Buttocks: local minimum below the lumbar point.
    pub sacroiliac: DVec3,
    /// Front of the neck: least forward point between the back point and the head.
    pub throat: DVec3,
    /// Lowest point of the silhouette.
    pub crotch: DVec3,
    /// The trunk's width across the body at the heights of `back`, `lumbar` and `sacroiliac`:
    /// the widest closed loop of the transverse slice there that crosses the median plane
    /// (`None` where none does).
    pub widths: [Option<f64>; 3],
    /// The smoothed silhouette (closed), for pictures and checks.
    pub silhouette: Vec<DVec3>,
}

/// Slices the mesh with the median plane (through `centre`, normal `frame.left`), smooths the
/// torso's loop with a closed cubic B-spline and finds the characteristic points. `None` when
/// no loop spans from below the waist (halfway between the rough hips and shoulders) to the
/// shoulders or a point is missing.
pub fn torso_points(
    mesh: &Mesh,
    frame: &BodyFrame,
    centre: DVec3,
    bounds: &TorsoBounds,
    options: &RefineOptions,
) -> Option<TorsoPoints> {
    let loops = slice_plane_outer(mesh, centre, frame.left);
    // The torso's loop spans the shoulders and reaches below the waist. Not necessarily below
    // the rough hips: clothing that joins the thighs' tops to the trunk (a cape's or coat's
    // hem behind the legs) starts the legs' labels, and the rough hips, lower than the crotch.
    let torso = loops
        .iter()
        .filter(|l| l.closed)
        .filter(|l| {
            let (lo, hi) = l.points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
                (lo.min(frame.h(*p)), hi.max(frame.h(*p)))
            });
            lo < 0.5 * (bounds.hips + bounds.shoulders) && hi > bounds.shoulders
        })
        .max_by(|a, b| a.perimeter().total_cmp(&b.perimeter()))?;
    let step = options.silhouette_step * frame.height();
    let points = resample(&torso.points, true, step);
    let silhouette = smooth_closed(&points)?;
    let n = silhouette.len();
    let h = |i: usize| frame.h(silhouette[i]);
    let f = |i: usize| silhouette[i].dot(frame.forward);
    let top = (0..n).max_by(|&a, &b| h(a).total_cmp(&h(b)))?;
    let bottom = (0..n).min_by(|&a, &b| h(a).total_cmp(&h(b)))?;
    // The two arcs from top to bottom.
    let arc = |forward_walk: bool| -> Vec<usize> {
        let mut out = vec![top];
        let mut i = top;
        while i != bottom {
            i = if forward_walk {
                (i + 1) % n
            } else {
                (i + n - 1) % n
            };
            out.push(i);
        }
        out
    };
    let (a, b) = (arc(true), arc(false));
    let mean = |v: &[usize]| v.iter().map(|&i| f(i)).sum::<f64>() / v.len() as f64;
    let (front, back) = if mean(&a) > mean(&b) { (a, b) } else { (b, a) };
    let pick = |arc: &[usize], lo: f64, hi: f64, largest: bool| -> Option<usize> {
        let within = arc.iter().copied().filter(|&i| h(i) >= lo && h(i) <= hi);
        if largest {
            within.max_by(|&x, &y| f(x).total_cmp(&f(y)))
        } else {
            within.min_by(|&x, &y| f(x).total_cmp(&f(y)))
        }
    };
    let crotch = bottom;
    let neck_top = bounds.shoulders + options.neck_window * (bounds.head - bounds.shoulders);
    let neck = pick(&back, bounds.shoulders, neck_top, true)?;
    let back_point = pick(
        &back,
        (bounds.hips + bounds.shoulders) * 0.5,
        h(neck),
        false,
    )?;
    let lumbar = pick(&back, bounds.hips, h(back_point), true)?;
    // A back without a lumbar hollow has its forward maximum at an end of the window: at the
    // lower end, on the hips, for a cartoon's straight or convex back, which leaves no room for
    // the sacrum below; at the upper end, on the back point itself, for a back that flares out
    // downwards all the way (a cape, a tunic, a coat's skirt), which leaves no curve between
    // the two. The lumbar point is then the back's point halfway up the window.
    let at_end = |i: usize| h(i) <= bounds.hips + 2.0 * step || h(i) >= h(back_point) - 2.0 * step;
    let lumbar = if at_end(lumbar) {
        let mid = 0.5 * (bounds.hips + h(back_point));
        back.iter()
            .copied()
            .min_by(|&x, &y| (h(x) - mid).abs().total_cmp(&(h(y) - mid).abs()))?
    } else {
        lumbar
    };
    let sacroiliac = pick(&back, h(crotch), h(lumbar), false)?;
    let throat = pick(&front, h(back_point), neck_top, false)?;
    let slicer = PlaneSlicer::once(mesh, frame.up);
    let widths = [back_point, lumbar, sacroiliac]
        .map(|i| trunk_width(&slicer, frame, frame.at_height(centre, h(i))));
    Some(TorsoPoints {
        widths,
        neck: silhouette[neck],
        back: silhouette[back_point],
        lumbar: silhouette[lumbar],
        sacroiliac: silhouette[sacroiliac],
        throat: silhouette[throat],
        crotch: silhouette[crotch],
        silhouette,
    })
}

/// The trunk's width across the body (along `frame.left`) in the transverse slice through
/// `at` (a point of the median plane): the widest closed outer loop whose extent across holds
/// `at`. An arm touching the trunk there widens it; `None` when no loop crosses the median
/// plane.
pub fn trunk_width(slicer: &PlaneSlicer, frame: &BodyFrame, at: DVec3) -> Option<f64> {
    let middle = at.dot(frame.left);
    slicer
        .slice_outer(at)
        .iter()
        .filter(|l| l.closed)
        .filter_map(|l| {
            let (lo, hi) = l.points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
                (lo.min(p.dot(frame.left)), hi.max(p.dot(frame.left)))
            });
            (lo <= middle && middle <= hi).then_some(hi - lo)
        })
        .max_by(f64::total_cmp)
}

/// Closed uniform cubic B-spline with `points` as control points, evaluated once per control
/// point (seed 004, 3.2: "interpolated by a cubic B-spline curve"). `None` for fewer than four.
fn smooth_closed(points: &[DVec3]) -> Option<Vec<DVec3>> {
    let n = points.len();
    if n < 4 {
        return None;
    }
    let degree = 3;
    let mut control = points.to_vec();
    control.extend_from_slice(&points[..degree]);
    let knots: Vec<f64> = (0..control.len() + degree + 1).map(|i| i as f64).collect();
    let spline = BSpline::new(degree, control, knots);
    Some((0..n).map(|i| spline.point((degree + i) as f64)).collect())
}

/// The hips (seed 004, 3.3): the transverse slice at height `height`, restricted to the loops
/// whose centroid lies within `reach` of `centre` across the body, split by the median plane
/// (normal `frame.left`); each side's length-weighted centroid. Returns `(left, right)`. The
/// median plane passes through the length-weighted centroid of the kept loops (found again
/// after each split), not through `centre`: the rough pelvis can sit a centimetre off the
/// body's middle, which moved one hip in and the other out.
pub fn hips(
    mesh: &Mesh,
    frame: &BodyFrame,
    centre: DVec3,
    height: f64,
    reach: f64,
) -> Option<(DVec3, DVec3)> {
    let origin = frame.at_height(centre, height);
    let slicer = PlaneSlicer::once(mesh, frame.up);
    let segments: Vec<(DVec3, f64)> = loops_near(&slicer, frame, origin, reach)
        .iter()
        .flat_map(|l| l.segments())
        .map(|(a, b)| ((a + b) * 0.5, a.distance(b)))
        .collect();
    let total: f64 = segments.iter().map(|s| s.1).sum();
    if total <= 0.0 {
        return None;
    }
    let middle = segments.iter().map(|(m, w)| *m * *w).sum::<DVec3>() / total;
    let mut sums = [(DVec3::ZERO, 0.0); 2];
    for (mid, w) in &segments {
        let k = usize::from((*mid - middle).dot(frame.left) < 0.0);
        sums[k].0 += *mid * *w;
        sums[k].1 += *w;
    }
    if sums[0].1 <= 0.0 || sums[1].1 <= 0.0 {
        return None;
    }
    Some((sums[0].0 / sums[0].1, sums[1].0 / sums[1].1))
}

/// Whether the transverse slice at height `h` still cuts the legs apart: among the closed loops
/// whose centroid lies within `reach` of `centre` across the body, the second longest is at
/// least half as long as the longest (two thighs; above the crotch one pelvis loop dwarfs any
/// hand or arm beside it).
fn legs_apart(slicer: &PlaneSlicer, frame: &BodyFrame, centre: DVec3, h: f64, reach: f64) -> bool {
    let mut perimeters: Vec<f64> = loops_near(slicer, frame, frame.at_height(centre, h), reach)
        .iter()
        .filter(|l| l.closed)
        .map(|l| l.perimeter())
        .collect();
    perimeters.sort_by(|a, b| b.total_cmp(a));
    perimeters.len() >= 2 && perimeters[1] >= 0.5 * perimeters[0]
}

/// Whether the legs stand apart anywhere below height `top`: a transverse slice at one of
/// eight heights between the figure's lowest point and `top` cuts two comparable loops (see
/// [`legs_apart`]). A skirt or gown hides the crotch but shows the legs or feet apart below
/// the knees; a blob or a sack shows none.
pub fn legs_apart_below(
    mesh: &Mesh,
    frame: &BodyFrame,
    centre: DVec3,
    top: f64,
    reach: f64,
) -> bool {
    let bottom = mesh
        .positions
        .iter()
        .map(|&v| frame.h(v))
        .fold(f64::INFINITY, f64::min);
    if bottom.is_nan() || bottom >= top {
        return false;
    }
    let slicer = PlaneSlicer::new(mesh, frame.up);
    (1..=8).any(|i| {
        let h = bottom + (top - bottom) * f64::from(i) / 9.0;
        legs_apart(&slicer, frame, centre, h, reach)
    })
}

/// Height of the crotch as the top of the gap between the legs: the highest height, going up
/// from `from` (where the legs must be apart) towards `to`, below which every transverse slice
/// cuts the legs into two loops of comparable length; found by steps of `step` then
/// bisection to `step / 16`. `None` when the legs are not apart at `from` (legs touching, a
/// skirt) or never join below `to`.
///
/// The lowest point of the median-plane silhouette (the seed's crotch) rests on the few
/// triangles the median plane happens to cut; a simplification that pinches one vertex of the
/// perineum drops it by several millimetres and sends the hips down with it. The leg split
/// depends on whole cross-sections and moves by about a millimetre on the same meshes.
pub fn leg_split_height(
    mesh: &Mesh,
    frame: &BodyFrame,
    centre: DVec3,
    from: f64,
    to: f64,
    step: f64,
    reach: f64,
) -> Option<f64> {
    let ordered = step > 0.0 && to > from;
    if !ordered {
        return None;
    }
    let slicer = PlaneSlicer::new(mesh, frame.up);
    if !legs_apart(&slicer, frame, centre, from, reach) {
        return None;
    }
    let mut below = from;
    let above = loop {
        let h = below + step;
        if h > to {
            return None;
        }
        if !legs_apart(&slicer, frame, centre, h, reach) {
            break h;
        }
        below = h;
    };
    let (mut lo, mut hi) = (below, above);
    for _ in 0..4 {
        let mid = 0.5 * (lo + hi);
        if legs_apart(&slicer, frame, centre, mid, reach) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// A hem, not a crotch, when the section just above a leg split reaches this many times as
/// far as the two legs' sections just below it, across the body or in depth: where the legs
/// leave the trunk the outline runs on (1.06-1.09 on MakeHuman, CesiumMan, the knight and the
/// short-legged platformer character, measured 0.01 of height either side), while a skirt or
/// coat stands out around the legs it hides (1.35 across, 2.0 in depth at a dress's hem).
pub const HEM_FLARE: f64 = 1.2;

/// How many times as far the transverse section at `split + gap` reaches as the two largest
/// loops at `split - gap` together (the larger ratio of the extents across the body and in
/// depth), the loops taken within `reach` of `centre` across the body. `None` when either
/// slice has no closed loop there.
pub fn split_flare(
    mesh: &Mesh,
    frame: &BodyFrame,
    centre: DVec3,
    split: f64,
    gap: f64,
    reach: f64,
) -> Option<f64> {
    let slicer = PlaneSlicer::once(mesh, frame.up);
    let extents = |h: f64, pieces: usize| -> Option<(f64, f64)> {
        let mut loops: Vec<SliceLoop> =
            loops_near(&slicer, frame, frame.at_height(centre, h), reach)
                .into_iter()
                .filter(|l| l.closed)
                .collect();
        loops.sort_by(|a, b| b.perimeter().total_cmp(&a.perimeter()));
        loops.truncate(pieces);
        let span = |axis: DVec3| {
            let (lo, hi) = loops
                .iter()
                .flat_map(|l| l.points.iter())
                .fold((f64::MAX, f64::MIN), |(lo, hi), p| {
                    (lo.min(p.dot(axis)), hi.max(p.dot(axis)))
                });
            hi - lo
        };
        (!loops.is_empty()).then(|| (span(frame.left), span(frame.forward)))
    };
    let (above_across, above_depth) = extents(split + gap, 1)?;
    let (below_across, below_depth) = extents(split - gap, 2)?;
    let ratio = |a: f64, b: f64| a / b.max(f64::MIN_POSITIVE);
    Some(ratio(above_across, below_across).max(ratio(above_depth, below_depth)))
}

/// The pieces of the transverse slice through `origin` whose centroid lies within `reach` of
/// it across the body (the torso and legs, not hands hanging beside them).
fn loops_near(
    slicer: &PlaneSlicer,
    frame: &BodyFrame,
    origin: DVec3,
    reach: f64,
) -> Vec<SliceLoop> {
    slicer
        .slice_outer(origin)
        .into_iter()
        .filter(|l| {
            l.centroid().is_some_and(|g| {
                let across = g - origin;
                (across - frame.up * across.dot(frame.up)).length() <= reach
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A prism across the figure (x from -0.2 to 0.2) of the median profile `(forward, up)`,
    /// fanned from its centroid.
    fn prism(profile: &[(f64, f64)]) -> Mesh {
        let n = profile.len();
        let c = profile
            .iter()
            .fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
        let c = (c.0 / n as f64, c.1 / n as f64);
        let mut positions = Vec::new();
        for x in [-0.2, 0.2] {
            positions.push(DVec3::new(x, c.1, c.0));
            positions.extend(profile.iter().map(|&(z, y)| DVec3::new(x, y, z)));
        }
        let (a, b) = (0u32, n as u32 + 1);
        let mut triangles = Vec::new();
        for i in 0..n as u32 {
            let j = (i + 1) % n as u32;
            triangles.push([a, a + 1 + j, a + 1 + i]);
            triangles.push([b, b + 1 + i, b + 1 + j]);
            triangles.push([a + 1 + i, a + 1 + j, b + 1 + j]);
            triangles.push([a + 1 + i, b + 1 + j, b + 1 + i]);
        }
        Mesh::new(positions, triangles).unwrap()
    }

    #[test]
    fn the_trunk_width_is_the_loop_across_the_median_plane() {
        let mesh = prism(&[(0.1, 0.0), (0.1, 1.0), (-0.1, 1.0), (-0.1, 0.0)]);
        let frame = BodyFrame::new(&mesh, DVec3::Y, DVec3::Z).unwrap();
        let slicer = PlaneSlicer::new(&mesh, frame.up);
        let width = trunk_width(&slicer, &frame, DVec3::new(0.0, 0.5, 0.0)).unwrap();
        assert!((width - 0.4).abs() < 1e-9, "{width}");
        // A median point beside the trunk (or above it) has none.
        assert!(trunk_width(&slicer, &frame, DVec3::new(0.5, 0.5, 0.0)).is_none());
        assert!(trunk_width(&slicer, &frame, DVec3::new(0.0, 1.5, 0.0)).is_none());
    }

    #[test]
    fn a_back_flaring_out_downwards_gets_its_lumbar_point_between_hips_and_back() {
        // Facing +z; the back runs straight from the neck (z -0.1 at 1.5) out to a cape's
        // hem (z -0.4 at 0.5), so the back point (its rearmost point above the waist) sits at
        // the window's lower end and the lumbar window's forward maximum on it.
        let mesh = prism(&[
            (0.15, 0.0),
            (0.15, 1.5),
            (0.05, 1.7),
            (-0.1, 1.7),
            (-0.1, 1.5),
            (-0.4, 0.5),
            (-0.4, 0.0),
        ]);
        let frame = BodyFrame::new(&mesh, DVec3::Y, DVec3::Z).unwrap();
        let bounds = TorsoBounds {
            head: 1.65,
            shoulders: 1.4,
            hips: 0.6,
        };
        let options = RefineOptions::default();
        let t = torso_points(&mesh, &frame, DVec3::ZERO, &bounds, &options).unwrap();
        let step = options.silhouette_step * frame.height();
        let (back, lumbar, sacrum) = (t.back.y, t.lumbar.y, t.sacroiliac.y);
        assert!(
            lumbar < back - 2.0 * step && lumbar > bounds.hips + 2.0 * step,
            "back {back}, lumbar {lumbar}"
        );
        assert!(sacrum < lumbar, "lumbar {lumbar}, sacroiliac {sacrum}");
    }
}

//! Ears: a mirrored pair of protrusions of the head, found in the voxelized figure.
//!
//! Thin ears hold no medial-surface voxels (their distance to the skin is a voxel or two), so
//! they are not labelled parts; they are found from the interior voxels around the head:
//!
//! ```text
//! head-to-tail path ─▶ its inscribed balls cover the skull, neck and trunk
//!                   ─▶ geodesic distance g of every interior voxel near the head from that cover
//!                   ─▶ maxima of g and their persistence (how far each rises above the level
//!                      where it joins a higher one): the tips of protrusions
//!                   ─▶ tips long and prominent for the head's radius, rising from the skull
//!                   ─▶ the most prominent pair that mirror each other across the median plane
//!                   ─▶ each tip's shortest path back to the cover, base first
//! ```
//!
//! A head without such a pair (humans, most birds, a fox with ears laid back) gets none.

use super::{AxialPath, EarInput, Side};
use crate::anatomy::{Frame, Label, Labelling};
use crate::distance::DistanceMap;
use crate::math::{moving_average, Ends};
use crate::options::{Checks, OptionProblems};
use crate::paths::Search;
use crate::voxel::NEIGHBOURS_26;
use glam::DVec3;

/// Options of [`ears`]. Lengths are multiples of the radius of the head-to-tail path's
/// inscribed ball nearest the ear's base (the skull's radius there).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EarOptions {
    /// A tip counts when its geodesic distance from the covered skull is at least this many
    /// radii. Default 0.75 (measured ears: wolf 1.1, fox 1.2-1.5, horse 1.9, alpaca 2.5, deer
    /// 2.7 radii; bumps such as brows and cheeks stay below 0.5).
    pub min_length: f64,
    /// A tip counts when it rises at least this many radii above the level where its region
    /// joins the region of a higher tip (its persistence). Default 0.5.
    pub min_prominence: f64,
    /// The base-to-tip direction's least component along up: ears rise from the skull; legs
    /// and a chin hang down. Default 0.25 (about 15° above horizontal).
    pub min_rise: f64,
    /// Largest mirror mismatch of a pair (distance between the left tip and the mirrored right
    /// tip, plus the same for the bases) as a fraction of the mean ear length. Default 0.5.
    pub max_asymmetry: f64,
    /// The search box is the head part's medial-surface box grown by this many times the
    /// head's largest inscribed radius. Default 4 (ears reach about 3.5 radii from the skull's
    /// centre line).
    pub reach: f64,
    /// Half-width (points) of the moving average smoothing each ear path. Default 2.
    pub smoothing: usize,
}

impl EarOptions {
    /// Checks every option.
    ///
    /// # Errors
    /// Every option out of range.
    pub fn validate(&self) -> Result<(), OptionProblems> {
        let mut c = Checks::default();
        c.range("min_length", self.min_length, 0.0, 100.0);
        c.range("min_prominence", self.min_prominence, 0.0, 100.0);
        c.range("min_rise", self.min_rise, -1.0, 1.0);
        c.range("max_asymmetry", self.max_asymmetry, 0.0, 100.0);
        c.range("reach", self.reach, 0.0, 100.0);
        c.finish()
    }
}

impl Default for EarOptions {
    fn default() -> Self {
        Self {
            min_length: 0.75,
            min_prominence: 0.5,
            min_rise: 0.25,
            max_asymmetry: 0.5,
            reach: 4.0,
            smoothing: 2,
        }
    }
}

/// A box of grid voxels with its own linear indices.
struct Window {
    lo: [usize; 3],
    dims: [usize; 3],
}

impl Window {
    fn len(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    fn coords(&self, i: usize) -> [usize; 3] {
        let [nx, ny, _] = self.dims;
        [
            self.lo[0] + i % nx,
            self.lo[1] + (i / nx) % ny,
            self.lo[2] + i / (nx * ny),
        ]
    }

    fn local(&self, c: [i64; 3]) -> Option<usize> {
        let mut l = [0usize; 3];
        for a in 0..3 {
            let x = c[a] - self.lo[a] as i64;
            if x < 0 || x >= self.dims[a] as i64 {
                return None;
            }
            l[a] = x as usize;
        }
        Some(l[0] + self.dims[0] * (l[1] + self.dims[1] * l[2]))
    }

    fn neighbours(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let c = self.coords(i);
        NEIGHBOURS_26.iter().filter_map(move |n| {
            let q = [
                c[0] as i64 + n.offset[0] as i64,
                c[1] as i64 + n.offset[1] as i64,
                c[2] as i64 + n.offset[2] as i64,
            ];
            self.local(q).map(|j| (j, n.distance))
        })
    }
}

/// A protrusion tip with its path back to the cover.
struct Candidate {
    /// Window voxels from the tip down to the first covered voxel.
    chain: Vec<usize>,
    tip: DVec3,
    base: DVec3,
    /// Geodesic length, mesh units.
    length: f64,
}

/// The ears of a labelled figure: the most prominent pair of mirrored protrusions rising from
/// the head, each as a path from the skull to the tip (left first), or nothing.
///
/// `labelling` gives the head part and the body frame, `distance` the interior (and its grid,
/// the labelling's), `axial` the head-to-tail path whose inscribed balls are the skull. Runs in
/// time linear in the interior voxels of a box around the head (Dijkstra with a binary heap).
pub fn ears(
    labelling: &Labelling,
    distance: &DistanceMap,
    axial: &AxialPath,
    options: &EarOptions,
) -> Vec<EarInput> {
    let Some(head) = labelling.part(Label::Head, None) else {
        return Vec::new();
    };
    let grid = &distance.grid;
    if head.voxels.is_empty() || axial.points.len() < 2 || grid != &labelling.grid {
        return Vec::new();
    }
    let h = grid.voxel_size;

    let window = head_window(labelling, &head.voxels, distance, options.reach);
    let n = window.len();
    let index = |i: usize| grid.index(window.coords(i));
    let inside: Vec<bool> = (0..n).map(|i| distance.squared[index(i)] > 0).collect();
    let centre = |i: usize| grid.centre(window.coords(i));

    let covered = cover(distance, &window, &inside, axial);

    let Some(search) = geodesic(&window, &inside, &covered) else {
        return Vec::new();
    };
    let g = &search.cost;

    let tips = persistent_maxima(&window, g);

    // Candidates: long, prominent tips rising from the head's part of the path.
    let head_end = nearest_point(&axial.points, head.attachment);
    let frame = &labelling.frame;
    let mut candidates = Vec::new();
    for (tip, persistence) in tips {
        let chain = search.path_to_source(tip);
        let (t, b) = (centre(tip), centre(*chain.last().unwrap_or(&tip)));
        let k = nearest_point(&axial.points, b);
        let skull = axial.radii[k] / h;
        let rises = (t - b)
            .try_normalize()
            .is_some_and(|d| d.dot(frame.up) >= options.min_rise);
        if k <= head_end
            && skull > 0.0
            && g[tip] >= options.min_length * skull
            && persistence >= options.min_prominence * skull
            && rises
        {
            candidates.push(Candidate {
                chain,
                tip: t,
                base: b,
                length: g[tip] * h,
            });
        }
    }

    let best = mirrored_pair(&candidates, &axial.points[..=head_end], frame, options);
    let Some((_, _, a, b)) = best else {
        return Vec::new();
    };
    [(a, Side::Left), (b, Side::Right)]
        .into_iter()
        .map(|(c, side)| {
            let chain: Vec<DVec3> = candidates[c]
                .chain
                .iter()
                .rev()
                .map(|&i| centre(i))
                .collect();
            let path = moving_average(&chain, options.smoothing, Ends::Keep);
            EarInput { side, path }
        })
        .collect()
}

/// The window: the box of the head's medial voxels (`head_voxels`, indices into the
/// labelling's DMS voxels), grown by `reach` head radii and clipped to the grid.
fn head_window(
    labelling: &Labelling,
    head_voxels: &[usize],
    distance: &DistanceMap,
    reach: f64,
) -> Window {
    let grid = &distance.grid;
    let mut lo = [usize::MAX; 3];
    let mut hi = [0usize; 3];
    let mut radius: f64 = 0.0;
    for &p in head_voxels {
        let index = labelling.dms_voxels[p];
        let c = grid.coords(index);
        for a in 0..3 {
            lo[a] = lo[a].min(c[a]);
            hi[a] = hi[a].max(c[a]);
        }
        radius = radius.max(distance.distance(index));
    }
    let grow = (reach * radius).ceil() as usize;
    for a in 0..3 {
        lo[a] = lo[a].saturating_sub(grow);
        hi[a] = (hi[a] + grow).min(grid.dims[a] - 1);
    }
    Window {
        lo,
        dims: [hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1],
    }
}

/// The cover: the window's interior voxels inside the axial path's inscribed balls.
fn cover(distance: &DistanceMap, window: &Window, inside: &[bool], axial: &AxialPath) -> Vec<bool> {
    let grid = &distance.grid;
    let h = grid.voxel_size;
    let n = window.len();
    let lo = window.lo;
    let hi: [usize; 3] = std::array::from_fn(|a| window.lo[a] + window.dims[a] - 1);
    let centre = |i: usize| grid.centre(window.coords(i));
    let mut covered = vec![false; n];
    for (c, &r) in axial.points.iter().zip(&axial.radii) {
        if r <= 0.0 {
            continue;
        }
        let v = grid.to_voxel(*c);
        let rv = r / h + 1.0;
        let range = |a: usize| {
            let from = (v[a] - rv).floor().max(lo[a] as f64);
            let to = (v[a] + rv).ceil().min(hi[a] as f64);
            (from as i64)..=(to as i64)
        };
        for z in range(2) {
            for y in range(1) {
                for x in range(0) {
                    if let Some(i) = window.local([x, y, z]) {
                        if inside[i] && centre(i).distance(*c) <= r {
                            covered[i] = true;
                        }
                    }
                }
            }
        }
    }
    covered
}

/// Geodesic distance (voxel units, [`Search::cost`]) from the cover through the window's
/// interior, with each voxel's path back to the cover; `None` without a cover.
fn geodesic(window: &Window, inside: &[bool], covered: &[bool]) -> Option<Search> {
    let mut search = Search::new(window.len());
    let mut sources = 0;
    for i in (0..window.len()).filter(|&i| covered[i]) {
        search.seed(i, 0.0);
        sources += 1;
    }
    if sources == 0 {
        return None;
    }
    search.relax(
        |i| window.neighbours(i).filter(|&(j, _)| inside[j]),
        |_, _| {},
    );
    Some(search)
}

/// Maxima of `g` and their persistence (voxel units): voxels from the highest down, joined by
/// union-find; when two regions meet, the one with the lower peak ends there. `(peak voxel,
/// persistence)` pairs.
fn persistent_maxima(window: &Window, g: &[f64]) -> Vec<(usize, f64)> {
    let n = window.len();
    let mut order: Vec<usize> = (0..n).filter(|&i| g[i].is_finite() && g[i] > 0.0).collect();
    order.sort_by(|&a, &b| g[b].total_cmp(&g[a]).then(a.cmp(&b)));
    let mut set = vec![usize::MAX; n];
    let mut peak = vec![usize::MAX; n];
    let find = |set: &mut Vec<usize>, mut x: usize| {
        while set[x] != x {
            set[x] = set[set[x]];
            x = set[x];
        }
        x
    };
    let higher = |a: usize, b: usize| g[a] > g[b] || (g[a] == g[b] && a < b);
    let mut tips: Vec<(usize, f64)> = Vec::new(); // (peak voxel, persistence in voxels)
    for &v in &order {
        let joined: Vec<usize> = window
            .neighbours(v)
            .map(|(j, _)| j)
            .filter(|&j| set[j] != usize::MAX)
            .collect();
        let mut roots: Vec<usize> = joined.into_iter().map(|j| find(&mut set, j)).collect();
        roots.sort_unstable();
        roots.dedup();
        let Some(&top) = roots
            .iter()
            .reduce(|a, b| if higher(peak[*a], peak[*b]) { a } else { b })
        else {
            set[v] = v;
            peak[v] = v;
            continue;
        };
        set[v] = top;
        for &r in roots.iter().filter(|&&r| r != top) {
            tips.push((peak[r], g[peak[r]] - g[v]));
            set[r] = top;
        }
    }
    for &v in &order {
        if set[v] == v {
            tips.push((peak[v], g[peak[v]]));
        }
    }
    tips
}

/// The most prominent mirrored pair of `candidates` about the median plane of the head's part
/// of the path (`points`): `(shorter length, -mismatch, left, right)`.
fn mirrored_pair(
    candidates: &[Candidate],
    points: &[DVec3],
    frame: &Frame,
    options: &EarOptions,
) -> Option<(f64, f64, usize, usize)> {
    let count = points.len();
    let median = points.iter().map(|p| p.dot(frame.left)).sum::<f64>() / count as f64;
    let lateral = |p: DVec3| p.dot(frame.left) - median;
    let mirror = |p: DVec3| p - frame.left * (2.0 * lateral(p));
    let mut best: Option<(f64, f64, usize, usize)> = None;
    for (a, l) in candidates.iter().enumerate() {
        for (b, r) in candidates.iter().enumerate() {
            if lateral(l.tip) <= 0.0 || lateral(r.tip) >= 0.0 {
                continue;
            }
            let mismatch = l.tip.distance(mirror(r.tip)) + l.base.distance(mirror(r.base));
            let mean = 0.5 * (l.length + r.length);
            if mismatch > options.max_asymmetry * mean {
                continue;
            }
            let key = (l.length.min(r.length), -mismatch, a, b);
            if best.is_none_or(|q| key.0 > q.0 || (key.0 == q.0 && key.1 > q.1)) {
                best = Some(key);
            }
        }
    }
    best
}

/// Index of the point of `points` nearest `p` (the first on ties).
fn nearest_point(points: &[DVec3], p: DVec3) -> usize {
    points
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.distance_squared(p).total_cmp(&b.1.distance_squared(p)))
        .map_or(0, |(k, _)| k)
}

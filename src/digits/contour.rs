//! Level contours of the geodesic distance on the hand's surface and the tree they form (a
//! sampled Reeb graph): where a contour splits, digits part.

use super::surface::HandSurface;
use glam::DVec3;
use std::collections::BTreeMap;

/// One contour: a connected component of the level set at one level.
#[derive(Debug, Clone)]
pub(super) struct Contour {
    /// Level index (the level is `(level + 1 - phase) * step`).
    pub level: usize,
    /// Length-weighted centroid of the contour's segments, mesh frame.
    pub centre: DVec3,
    /// Contour length, mesh units.
    pub perimeter: f64,
    /// A triangle the contour crosses.
    rep: u32,
}

/// One digit branch: contours from the web to the tip, and the level it parted at.
#[derive(Debug, Clone)]
pub(super) struct Branch {
    /// Contour centres from the tip to the web (the split contour left out).
    pub path: Vec<DVec3>,
    /// Contour lengths along `path`.
    pub perimeters: Vec<f64>,
    /// Level index of the contour it parted from.
    pub split_level: usize,
    /// Contour centres from the one it parted from down to the lowest level (the palm's or
    /// sole's centre line back towards the wrist, through each contour's longest parent).
    pub stem: Vec<DVec3>,
}

impl Branch {
    /// Arc length of its path.
    pub fn free_length(&self) -> f64 {
        self.path.windows(2).map(|p| p[0].distance(p[1])).sum()
    }

    /// The path's web end (its last contour centre).
    pub fn base(&self) -> DVec3 {
        self.path[self.path.len() - 1]
    }
}

/// The leaf branches of the contour tree with levels `step` apart, the first at
/// `(1 - phase) * step` (`phase` in [0, 1)), shorter ones than `min_levels` pruned; only
/// branches that part from a split are returned (a mitten gives none).
pub(super) fn digit_branches(
    surface: &HandSurface,
    step: f64,
    phase: f64,
    min_levels: usize,
) -> Vec<Branch> {
    let far = surface.distance.iter().cloned().fold(0.0, f64::max);
    let levels = ((far / step + phase) as usize).min(10_000);
    let level = |k: usize| (k as f64 + 1.0 - phase) * step;
    let edges = EdgeGroups::new(&surface.triangles);
    let mut contours: Vec<Contour> = Vec::new();
    let mut by_level: Vec<Vec<usize>> = Vec::with_capacity(levels);
    for k in 0..levels {
        let found = level_contours(surface, &edges, level(k), k);
        by_level.push((contours.len()..contours.len() + found.len()).collect());
        contours.extend(found);
    }
    let mut children = vec![Vec::new(); contours.len()];
    let mut parents = vec![Vec::new(); contours.len()];
    for k in 0..levels.saturating_sub(1) {
        let (lo, hi) = (level(k), level(k + 1));
        let mut uf = UnionFind::new(surface.triangles.len());
        edges.unite_within(surface, &mut uf, |a, b| a.min(b) <= hi && a.max(b) >= lo);
        for &a in &by_level[k] {
            for &b in &by_level[k + 1] {
                if uf.find(contours[a].rep) == uf.find(contours[b].rep) {
                    children[a].push(b);
                    parents[b].push(a);
                }
            }
        }
    }
    prune_and_collect(&contours, &children, &parents, min_levels)
}

/// Leaf branches after pruning short ones, repeatedly (a pruned twig may leave its parent with
/// one child, merging two branches).
fn prune_and_collect(
    contours: &[Contour],
    children: &[Vec<usize>],
    parents: &[Vec<usize>],
    min_levels: usize,
) -> Vec<Branch> {
    let mut alive = vec![true; contours.len()];
    let kids = |alive: &[bool], n: usize| children[n].iter().filter(|&&c| alive[c]).count();
    loop {
        let mut branches: Vec<(Vec<usize>, Option<usize>)> = Vec::new();
        for leaf in (0..contours.len()).filter(|&n| alive[n] && kids(&alive, n) == 0) {
            let mut path = vec![leaf];
            let mut node = leaf;
            let split = loop {
                let parent = parents[node]
                    .iter()
                    .copied()
                    .filter(|&p| alive[p])
                    .max_by(|&a, &b| contours[a].perimeter.total_cmp(&contours[b].perimeter));
                let Some(p) = parent else { break None };
                if kids(&alive, p) > 1 {
                    break Some(p);
                }
                path.push(p);
                node = p;
            };
            branches.push((path, split));
        }
        let shortest = branches
            .iter()
            .filter(|(path, split)| split.is_some() && path.len() < min_levels)
            .min_by_key(|(path, _)| path.len());
        match shortest {
            Some((path, _)) => {
                for &n in path {
                    alive[n] = false;
                }
            }
            None => {
                return branches
                    .into_iter()
                    .filter_map(|(path, split)| {
                        let split = split?;
                        Some(Branch {
                            path: path.iter().map(|&n| contours[n].centre).collect(),
                            perimeters: path.iter().map(|&n| contours[n].perimeter).collect(),
                            split_level: contours[split].level,
                            stem: stem(contours, parents, &alive, split),
                        })
                    })
                    .collect()
            }
        }
    }
}

/// Contour centres from `from` down through each contour's longest live parent to one without
/// any (the lowest level the tree reaches there).
fn stem(contours: &[Contour], parents: &[Vec<usize>], alive: &[bool], from: usize) -> Vec<DVec3> {
    let mut centres = vec![contours[from].centre];
    let mut node = from;
    while let Some(p) = parents[node]
        .iter()
        .copied()
        .filter(|&p| alive[p])
        .max_by(|&a, &b| contours[a].perimeter.total_cmp(&contours[b].perimeter))
    {
        centres.push(contours[p].centre);
        node = p;
    }
    centres
}

/// The contours at level `t`: triangles crossing it joined across the edges crossing it.
fn level_contours(surface: &HandSurface, edges: &EdgeGroups, t: f64, level: usize) -> Vec<Contour> {
    let d = &surface.distance;
    let crosses = |a: u32, b: u32| {
        let (x, y) = (d[a as usize], d[b as usize]);
        x.min(y) < t && t <= x.max(y)
    };
    let mut uf = UnionFind::new(surface.triangles.len());
    edges.unite_within(surface, &mut uf, |x, y| x.min(y) < t && t <= x.max(y));
    let mut parts: BTreeMap<u32, (DVec3, f64, u32)> = BTreeMap::new();
    for (ti, tri) in surface.triangles.iter().enumerate() {
        let mut points = [DVec3::ZERO; 2];
        let mut found = 0;
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if crosses(a, b) && found < 2 {
                let (pa, pb) = (surface.positions[a as usize], surface.positions[b as usize]);
                let f = (t - d[a as usize]) / (d[b as usize] - d[a as usize]);
                points[found] = pa + (pb - pa) * f;
                found += 1;
            }
        }
        if found < 2 {
            continue;
        }
        let len = points[0].distance(points[1]);
        let entry = parts
            .entry(uf.find(ti as u32))
            .or_insert((DVec3::ZERO, 0.0, ti as u32));
        entry.0 += (points[0] + points[1]) * 0.5 * len;
        entry.1 += len;
    }
    parts
        .into_values()
        .filter(|(_, len, _)| *len > 0.0)
        .map(|(sum, len, rep)| Contour {
            level,
            centre: sum / len,
            perimeter: len,
            rep,
        })
        .collect()
}

/// The triangles around each edge.
struct EdgeGroups {
    /// `(corner a, corner b, triangles)` with `a < b`.
    groups: Vec<(u32, u32, Vec<u32>)>,
}

impl EdgeGroups {
    fn new(triangles: &[[u32; 3]]) -> Self {
        let mut all: Vec<(u32, u32, u32)> = Vec::with_capacity(triangles.len() * 3);
        for (ti, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                all.push((a.min(b), a.max(b), ti as u32));
            }
        }
        all.sort_unstable();
        let mut groups: Vec<(u32, u32, Vec<u32>)> = Vec::new();
        for (a, b, t) in all {
            match groups.last_mut() {
                Some(g) if g.0 == a && g.1 == b => g.2.push(t),
                _ => groups.push((a, b, vec![t])),
            }
        }
        Self { groups }
    }

    /// Unites the triangles around every edge whose corner distances `keep` accepts.
    fn unite_within(
        &self,
        surface: &HandSurface,
        uf: &mut UnionFind,
        keep: impl Fn(f64, f64) -> bool,
    ) {
        let d = &surface.distance;
        for (a, b, tris) in &self.groups {
            if tris.len() > 1 && keep(d[*a as usize], d[*b as usize]) {
                for w in tris.windows(2) {
                    uf.union(w[0], w[1]);
                }
            }
        }
    }
}

/// Union-find with path halving.
struct UnionFind(Vec<u32>);

impl UnionFind {
    fn new(n: usize) -> Self {
        Self((0..n as u32).collect())
    }

    fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let up = self.0[self.0[x as usize] as usize];
            self.0[x as usize] = up;
            x = up;
        }
        x
    }

    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.0[ra.max(rb) as usize] = ra.min(rb);
        }
    }
}

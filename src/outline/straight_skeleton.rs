//! The straight skeleton of a simple polygon by wavefront propagation (Aichholzer et al. 1995;
//! Felkel & Obdržálek 1998; seed 003, Algorithm 3).
//!
//! Every edge moves inward at unit speed along its normal; each wavefront vertex moves along
//! the bisector of its two edges with the velocity `w` that keeps it on both offset lines
//! (`w · n_left = w · n_right = 1`), so a vertex created at time `t0` at `p` is at
//! `p + (t - t0) w` at time `t`, and time equals offset distance. Two kinds of events change
//! the wavefront: an *edge event* when an edge shrinks to zero length (its two vertices meet),
//! and a *split event* when a reflex vertex runs into an opposite edge and splits its wavefront
//! polygon in two. Events wait in a priority queue ordered by time; an event whose vertices
//! are no longer active, or whose opposite edge no longer spans the split point, is dropped.
//! Whenever a vertex is created the queue gets its edge events, its split events when it is
//! reflex, and the split events of the other reflex vertices of its wavefront polygon against
//! the two edges it changed. Events at the same place and time share one skeleton node.

use super::OutlineError;
use glam::DVec2;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A node of the straight skeleton.
#[derive(Debug, Clone, PartialEq)]
pub struct SkeletonNode {
    /// Position, outline units.
    pub position: DVec2,
    /// Offset time at which the wavefront reached it (= its distance to each defining edge's
    /// line); 0 for polygon corners.
    pub time: f64,
    /// Indices of the polygon edges (edge `i` runs from corner `i` to corner `i + 1`) whose
    /// offset lines meet here, ascending.
    pub edges: Vec<usize>,
}

/// The straight skeleton of a polygon: the polygon's corners are nodes `0..corners`, the
/// skeleton nodes follow; arcs are the traces of wavefront vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct StraightSkeleton {
    /// Corners first (time 0), then the event nodes.
    pub nodes: Vec<SkeletonNode>,
    /// Arcs between nodes (earlier node, later node).
    pub arcs: Vec<[usize; 2]>,
    /// Number of polygon corners.
    pub corners: usize,
}

impl StraightSkeleton {
    /// Whether node `i` is a polygon corner (the outer end of a peripheral arc).
    pub fn is_corner(&self, i: usize) -> bool {
        i < self.corners
    }
}

#[derive(Debug, Clone, Copy)]
struct Line {
    point: DVec2,
    dir: DVec2,
    normal: DVec2,
}

#[derive(Debug, Clone)]
struct Vertex {
    origin: DVec2,
    velocity: DVec2,
    node: usize,
    left: usize,
    right: usize,
    prev: usize,
    next: usize,
    active: bool,
    reflex: bool,
}

impl Vertex {
    fn at(&self, t: f64) -> DVec2 {
        self.origin + self.velocity * t
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Edge { a: usize, b: usize },
    Split { v: usize, line: usize },
}

#[derive(Debug, Clone, Copy)]
struct Event {
    time: f64,
    point: DVec2,
    kind: Kind,
    seq: usize,
}

impl PartialEq for Event {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Event {}
impl PartialOrd for Event {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Event {
    /// Reversed, so the max-heap pops the earliest event; edge events before split events at
    /// equal times, then creation order.
    fn cmp(&self, other: &Self) -> Ordering {
        let rank = |k: &Kind| matches!(k, Kind::Split { .. }) as u8;
        other
            .time
            .total_cmp(&self.time)
            .then(rank(&other.kind).cmp(&rank(&self.kind)))
            .then(other.seq.cmp(&self.seq))
    }
}

struct Wavefront {
    lines: Vec<Line>,
    vertices: Vec<Vertex>,
    heap: BinaryHeap<Event>,
    seq: usize,
    now: f64,
    /// Length tolerance, outline units.
    eps: f64,
    out: StraightSkeleton,
}

/// The straight skeleton of the simple counter-clockwise polygon `corners` (outline units).
/// `tolerance` is relative to the bounding-box diagonal: events closer than that in time and
/// space share a node.
///
/// # Errors
/// [`OutlineError::TooFewPoints`] below 3 corners, [`OutlineError::StraightSkeleton`] when the
/// propagation does not finish (numerically degenerate input).
pub fn straight_skeleton(
    corners: &[DVec2],
    tolerance: f64,
) -> Result<StraightSkeleton, OutlineError> {
    let n = corners.len();
    if n < 3 {
        return Err(OutlineError::TooFewPoints { count: n });
    }
    let (lo, hi) = super::input::bounds(corners);
    let diagonal = (hi - lo).length().max(f64::MIN_POSITIVE);
    let lines: Vec<Line> = (0..n)
        .map(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % n]);
            let dir = (b - a).normalize_or_zero();
            Line {
                point: a,
                dir,
                normal: dir.perp(),
            }
        })
        .collect();
    let mut w = Wavefront {
        lines,
        vertices: Vec::with_capacity(3 * n),
        heap: BinaryHeap::new(),
        seq: 0,
        now: 0.0,
        eps: tolerance * diagonal,
        out: StraightSkeleton {
            nodes: corners
                .iter()
                .enumerate()
                .map(|(i, &p)| SkeletonNode {
                    position: p,
                    time: 0.0,
                    edges: sorted_unique(vec![(i + n - 1) % n, i]),
                })
                .collect(),
            arcs: Vec::new(),
            corners: n,
        },
    };
    for (i, &corner) in corners.iter().enumerate() {
        let v = w.vertex(corner, 0.0, i, (i + n - 1) % n, i);
        debug_assert_eq!(v, i);
    }
    for i in 0..n {
        w.vertices[i].prev = (i + n - 1) % n;
        w.vertices[i].next = (i + 1) % n;
    }
    for i in 0..n {
        w.edge_event(i, (i + 1) % n);
    }
    for i in 0..n {
        if w.vertices[i].reflex {
            for x in 0..n {
                w.split_event(i, x);
            }
        }
    }
    let max_vertices = 6 * n + 16;
    let mut events = 0usize;
    while let Some(event) = w.heap.pop() {
        events += 1;
        if w.vertices.len() > max_vertices {
            return Err(OutlineError::StraightSkeleton { events });
        }
        match event.kind {
            Kind::Edge { a, b } => {
                let (va, vb) = (&w.vertices[a], &w.vertices[b]);
                if !va.active || !vb.active || va.next != b {
                    continue;
                }
                w.now = w.now.max(event.time);
                w.edge_collapse(a, b, event.point);
            }
            Kind::Split { v, line } => {
                if !w.vertices[v].active {
                    continue;
                }
                if let Some(x) = w.opposite(v, line, event.time, event.point) {
                    w.now = w.now.max(event.time);
                    w.split(v, x, event.point);
                }
            }
        }
    }
    w.finish();
    Ok(w.out)
}

fn sorted_unique(mut v: Vec<usize>) -> Vec<usize> {
    v.sort_unstable();
    v.dedup();
    v
}

impl Wavefront {
    /// Adds an active vertex at `p` at time `t` between edge lines `left` and `right`; links
    /// are set by the caller.
    fn vertex(&mut self, p: DVec2, t: f64, node: usize, left: usize, right: usize) -> usize {
        let (l1, l2) = (self.lines[left], self.lines[right]);
        let det = l1.normal.perp_dot(l2.normal);
        let velocity = if det.abs() < 1e-9 {
            if l1.normal.dot(l2.normal) > 0.0 {
                l1.normal
            } else {
                DVec2::ZERO
            }
        } else {
            DVec2::new(l2.normal.y - l1.normal.y, l1.normal.x - l2.normal.x) / det
        };
        let reflex = l1.dir.perp_dot(l2.dir) < -1e-12 && velocity != DVec2::ZERO;
        self.vertices.push(Vertex {
            origin: p - velocity * t,
            velocity,
            node,
            left,
            right,
            prev: usize::MAX,
            next: usize::MAX,
            active: true,
            reflex,
        });
        self.vertices.len() - 1
    }

    fn push(&mut self, time: f64, point: DVec2, kind: Kind) {
        self.seq += 1;
        self.heap.push(Event {
            time,
            point,
            kind,
            seq: self.seq,
        });
    }

    /// Queues the collapse of the wavefront edge from `a` to its successor `b`.
    fn edge_event(&mut self, a: usize, b: usize) {
        let (va, vb) = (&self.vertices[a], &self.vertices[b]);
        let d = self.lines[va.right].dir;
        let closing = (va.velocity - vb.velocity).dot(d);
        if closing <= 1e-12 {
            return;
        }
        let t = (vb.origin - va.origin).dot(d) / closing;
        if !t.is_finite() || t < self.now - self.eps {
            return;
        }
        let t = t.max(self.now);
        let point = 0.5 * (va.at(t) + vb.at(t));
        self.push(t, point, Kind::Edge { a, b });
    }

    /// Queues the split event of reflex vertex `r` against the wavefront edge from `x` to its
    /// successor, if `r` reaches that edge's offset line within the edge's current span.
    fn split_event(&mut self, r: usize, x: usize) {
        let vr = &self.vertices[r];
        let vx = &self.vertices[x];
        let y = vx.next;
        if !vr.reflex || x == r || y == r || !vx.active {
            return;
        }
        let line = self.lines[vx.right];
        let approach = 1.0 - vr.velocity.dot(line.normal);
        if approach <= 1e-12 {
            return;
        }
        let t = (vr.origin - line.point).dot(line.normal) / approach;
        if !t.is_finite() || t < self.now - self.eps {
            return;
        }
        let t = t.max(self.now);
        let point = vr.at(t);
        if !self.spans(x, y, t, point) {
            return;
        }
        let kind = Kind::Split {
            v: r,
            line: vx.right,
        };
        self.push(t, point, kind);
    }

    /// Whether the wavefront edge `x → y` at time `t` spans `point` (within tolerance).
    fn spans(&self, x: usize, y: usize, t: f64, point: DVec2) -> bool {
        let d = self.lines[self.vertices[x].right].dir;
        let s = point.dot(d);
        let sx = self.vertices[x].at(t).dot(d);
        let sy = self.vertices[y].at(t).dot(d);
        s >= sx - self.eps && s <= sy + self.eps
    }

    /// The vertex `x` of `v`'s wavefront polygon whose outgoing edge lies on `line` and spans
    /// `point` at time `t`.
    fn opposite(&self, v: usize, line: usize, t: f64, point: DVec2) -> Option<usize> {
        let mut x = self.vertices[v].next;
        let mut guard = 0usize;
        while x != v && guard <= self.vertices.len() {
            let y = self.vertices[x].next;
            if self.vertices[x].right == line && y != v && self.spans(x, y, t, point) {
                return Some(x);
            }
            x = y;
            guard += 1;
        }
        None
    }

    /// The skeleton node at `point` and the current time, shared with an existing event node
    /// there; `edges` are added to its defining edges.
    fn node(&mut self, point: DVec2, edges: &[usize]) -> usize {
        let t = self.now;
        let corners = self.out.corners;
        let found = self.out.nodes[corners..]
            .iter()
            .position(|n| {
                (n.time - t).abs() <= self.eps * 10.0
                    && n.position.distance(point) <= self.eps * 10.0
            })
            .map(|k| k + corners);
        match found {
            Some(k) => {
                let node = &mut self.out.nodes[k];
                node.edges.extend_from_slice(edges);
                node.edges = sorted_unique(std::mem::take(&mut node.edges));
                k
            }
            None => {
                self.out.nodes.push(SkeletonNode {
                    position: point,
                    time: t,
                    edges: sorted_unique(edges.to_vec()),
                });
                self.out.nodes.len() - 1
            }
        }
    }

    fn arc(&mut self, from: usize, to: usize) {
        if from != to {
            let arc = [from.min(to), from.max(to)];
            if !self.out.arcs.contains(&arc) {
                self.out.arcs.push(arc);
            }
        }
    }

    fn retire(&mut self, v: usize, node: usize) {
        let from = self.vertices[v].node;
        self.arc(from, node);
        self.vertices[v].active = false;
    }

    fn edge_collapse(&mut self, a: usize, b: usize, point: DVec2) {
        let (va, vb) = (&self.vertices[a], &self.vertices[b]);
        let edges = [va.left, va.right, vb.right];
        let (prev, next, left, right) = (va.prev, vb.next, va.left, vb.right);
        let node = self.node(point, &edges);
        self.retire(a, node);
        self.retire(b, node);
        if prev == b {
            return;
        }
        if prev == next {
            // The last triangle of this wavefront polygon closes at the node.
            self.retire(prev, node);
            return;
        }
        let c = self.vertex(point, self.now, node, left, right);
        self.link(prev, c, next);
        self.created(c);
    }

    fn split(&mut self, v: usize, x: usize, point: DVec2) {
        let vv = self.vertices[v].clone();
        let line = self.vertices[x].right;
        let y = self.vertices[x].next;
        let node = self.node(point, &[vv.left, vv.right, line]);
        self.retire(v, node);
        let v1 = self.vertex(point, self.now, node, vv.left, line);
        let v2 = self.vertex(point, self.now, node, line, vv.right);
        self.link(vv.prev, v1, y);
        self.link(x, v2, vv.next);
        for c in [v1, v2] {
            let other = self.vertices[c].next;
            if self.vertices[other].next == c {
                // A two-vertex wavefront polygon has no area: its vertices meet here.
                self.retire(other, node);
                self.vertices[c].active = false;
            } else {
                self.created(c);
            }
        }
    }

    fn link(&mut self, prev: usize, c: usize, next: usize) {
        self.vertices[prev].next = c;
        self.vertices[c].prev = prev;
        self.vertices[c].next = next;
        self.vertices[next].prev = c;
    }

    /// Queues the events a new vertex `c` brings or changes.
    fn created(&mut self, c: usize) {
        let (prev, next) = (self.vertices[c].prev, self.vertices[c].next);
        self.edge_event(prev, c);
        self.edge_event(c, next);
        let mut ring = vec![c];
        let mut x = next;
        while x != c && ring.len() <= self.vertices.len() {
            ring.push(x);
            x = self.vertices[x].next;
        }
        if self.vertices[c].reflex {
            for &x in &ring[1..] {
                self.split_event(c, x);
            }
        }
        for &r in &ring[1..] {
            if self.vertices[r].reflex {
                self.split_event(r, prev);
                self.split_event(r, c);
            }
        }
    }

    /// Connects whatever the queue left active (degenerate input only): each remaining
    /// wavefront polygon's vertices are joined to its first vertex's node.
    fn finish(&mut self) {
        for v in 0..self.vertices.len() {
            if !self.vertices[v].active {
                continue;
            }
            let t = self.now;
            let p = self.vertices[v].at(t);
            let edges = [self.vertices[v].left, self.vertices[v].right];
            let node = self.node(p, &edges);
            let mut x = v;
            let mut guard = 0usize;
            loop {
                self.retire(x, node);
                x = self.vertices[x].next;
                guard += 1;
                if x == v || !self.vertices[x].active || guard > self.vertices.len() {
                    break;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node_at(s: &StraightSkeleton, p: DVec2) -> usize {
        s.nodes
            .iter()
            .position(|n| n.position.distance(p) < 1e-9)
            .unwrap_or_else(|| panic!("no node at {p}: {:#?}", s.nodes))
    }

    #[test]
    fn rectangle_has_two_nodes_and_a_ridge() {
        let rect = [
            DVec2::ZERO,
            DVec2::new(4.0, 0.0),
            DVec2::new(4.0, 2.0),
            DVec2::new(0.0, 2.0),
        ];
        let s = straight_skeleton(&rect, 1e-9).unwrap();
        assert_eq!(s.nodes.len(), 6, "{:#?}", s);
        assert_eq!(s.arcs.len(), 5);
        let a = node_at(&s, DVec2::new(1.0, 1.0));
        let b = node_at(&s, DVec2::new(3.0, 1.0));
        assert!(s.arcs.contains(&[a.min(b), a.max(b)]));
        assert!((s.nodes[a].time - 1.0).abs() < 1e-12);
    }
}

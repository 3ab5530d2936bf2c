//! The hand's surface beyond the wrist and the geodesic distance over it.

use crate::mesh::Mesh;
use glam::DVec3;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The triangles of one hand with the geodesic distance of their corners from the wrist.
pub(super) struct HandSurface {
    /// Corner positions, mesh frame.
    pub positions: Vec<DVec3>,
    /// Geodesic distance from the wrist's cross-section, mesh units (finite).
    pub distance: Vec<f64>,
    /// Triangles over `positions`, every corner reached.
    pub triangles: Vec<[u32; 3]>,
}

/// The surface within `reach` of `wrist` on the distal side of the plane through
/// `wrist - band * axis` normal to `axis` (the forearm's direction, unit), and the geodesic
/// distance over its edges from the corners behind the wrist plane. Corners not connected to
/// the wrist (another body part in reach) are left out. `None` when nothing is reached.
pub(super) fn hand_surface(
    mesh: &Mesh,
    wrist: DVec3,
    axis: DVec3,
    reach: f64,
    band: f64,
) -> Option<HandSurface> {
    let n = mesh.positions.len();
    let mut local = vec![u32::MAX; n];
    let mut positions = Vec::new();
    let inside = |p: DVec3| (p - wrist).dot(axis) > -band && p.distance(wrist) < reach;
    for (i, &p) in mesh.positions.iter().enumerate() {
        if inside(p) {
            local[i] = positions.len() as u32;
            positions.push(p);
        }
    }
    let triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .filter_map(|t| {
            let l = t.map(|v| local[v as usize]);
            (l.iter().all(|&v| v != u32::MAX)).then_some(l)
        })
        .collect();
    let distance = geodesic(&positions, &triangles, |p| (p - wrist).dot(axis) <= 0.0);
    // Keep the reached part only.
    let mut keep = vec![u32::MAX; positions.len()];
    let mut kept_positions = Vec::new();
    let mut kept_distance = Vec::new();
    for (i, d) in distance.iter().enumerate() {
        if d.is_finite() {
            keep[i] = kept_positions.len() as u32;
            kept_positions.push(positions[i]);
            kept_distance.push(*d);
        }
    }
    let triangles: Vec<[u32; 3]> = triangles
        .iter()
        .filter_map(|t| {
            let l = t.map(|v| keep[v as usize]);
            (l.iter().all(|&v| v != u32::MAX)).then_some(l)
        })
        .collect();
    let far = kept_distance.iter().cloned().fold(0.0, f64::max);
    (!triangles.is_empty() && far > 0.0).then_some(HandSurface {
        positions: kept_positions,
        distance: kept_distance,
        triangles,
    })
}

/// Shortest distance along the triangles' edges from the corners `source` accepts (distance
/// 0); unreached corners are infinite. A Dijkstra on the surface mesh, which is not the DMS
/// graph of `paths::Search`.
fn geodesic(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    source: impl Fn(DVec3) -> bool,
) -> Vec<f64> {
    let mut edges: Vec<(u32, u32)> = Vec::with_capacity(triangles.len() * 6);
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.push((a, b));
            edges.push((b, a));
        }
    }
    edges.sort_unstable();
    edges.dedup();
    let mut start = vec![0usize; positions.len() + 1];
    for &(a, _) in &edges {
        start[a as usize + 1] += 1;
    }
    for i in 0..positions.len() {
        start[i + 1] += start[i];
    }
    let mut dist = vec![f64::INFINITY; positions.len()];
    let mut heap = BinaryHeap::new();
    for (i, &p) in positions.iter().enumerate() {
        if source(p) {
            dist[i] = 0.0;
            heap.push(Reverse((0u64, i as u32)));
        }
    }
    while let Some(Reverse((bits, u))) = heap.pop() {
        let d = f64::from_bits(bits);
        if d > dist[u as usize] {
            continue;
        }
        for &(_, v) in &edges[start[u as usize]..start[u as usize + 1]] {
            let nd = d + positions[u as usize].distance(positions[v as usize]);
            if nd < dist[v as usize] {
                dist[v as usize] = nd;
                // Non-negative f64 order as their bits.
                heap.push(Reverse((nd.to_bits(), v)));
            }
        }
    }
    dist
}

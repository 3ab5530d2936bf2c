//! The hand's surface beyond the wrist and the geodesic distance over it.

use crate::mesh::{vertex_pieces, Mesh};
use crate::paths::Search;
use glam::DVec3;

/// The triangles of one hand with the geodesic distance of their corners from the wrist.
pub(super) struct HandSurface {
    /// Corner positions, mesh frame.
    pub positions: Vec<DVec3>,
    /// Geodesic distance from the wrist's cross-section, mesh units (finite).
    pub distance: Vec<f64>,
    /// Triangles over `positions`, every corner reached.
    pub triangles: Vec<[u32; 3]>,
}

/// The surface within `reach` of `wrist` (plus the wrist's distance from the nearest corner, so
/// that a thick low-poly arm is reached) on the distal side of the plane through
/// `wrist - band * axis` normal to `axis` (the forearm's direction, unit), with the triangles
/// crossing the wrist plane whole (a coarse mesh has no corner within `band`), and the
/// geodesic distance over its edges from the wrist's cross-section behind the wrist plane (see
/// `wrist_band`). A hand modelled as a separate piece of the mesh (every corner of the piece in reach and beyond the wrist plane)
/// is measured from its own proximal cross-section instead: its corners within `band` of its
/// nearest one along `axis`. Corners connected to neither (another body part in reach) are
/// left out. `None` when nothing is reached.
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
    let skin = mesh
        .positions
        .iter()
        .map(|p| p.distance(wrist))
        .fold(f64::INFINITY, f64::min);
    let reach = reach + skin;
    let along = |p: DVec3| (p - wrist).dot(axis);
    let near = |v: u32| mesh.positions[v as usize].distance(wrist) < reach;
    let mut take = vec![false; n];
    for (i, &p) in mesh.positions.iter().enumerate() {
        take[i] = along(p) > -band && near(i as u32);
    }
    for t in &mesh.triangles {
        let a = t.map(|v| along(mesh.positions[v as usize]));
        let crosses = a.iter().any(|&x| x <= 0.0) && a.iter().any(|&x| x > 0.0);
        if crosses && t.iter().all(|&v| near(v)) {
            for &v in t {
                take[v as usize] = true;
            }
        }
    }
    for (i, &p) in mesh.positions.iter().enumerate() {
        if take[i] {
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
    let source = sources(mesh, &local, &positions, wrist, axis, band);
    let sources = source
        .iter()
        .enumerate()
        .filter(|(_, &s)| s)
        .map(|(i, _)| i);
    let distance = edge_geodesic(&positions, &triangles, sources, |_, _| {});
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

/// Which corners of the surface (`local[i]`: mesh corner `i`'s index in `positions`, or
/// `u32::MAX` when outside) start the geodesic distance: those behind the wrist plane, and on
/// each piece of the mesh that lies wholly in the surface without reaching behind the wrist
/// plane, the corners within `band` of its nearest one along `axis`.
fn sources(
    mesh: &Mesh,
    local: &[u32],
    positions: &[DVec3],
    wrist: DVec3,
    axis: DVec3,
    band: f64,
) -> Vec<bool> {
    let along = |p: DVec3| (p - wrist).dot(axis);
    let piece = vertex_pieces(mesh.positions.len(), &mesh.triangles);
    let mut source = wrist_band(mesh, local, positions, wrist, axis);
    // Per piece: wholly inside, nearest corner along the axis.
    let count = piece.iter().map(|&c| c as usize + 1).max().unwrap_or(0);
    let mut inside = vec![true; count];
    let mut nearest = vec![f64::INFINITY; count];
    for (i, &c) in piece.iter().enumerate() {
        let c = c as usize;
        match local[i] {
            u32::MAX => inside[c] = false,
            l if source[l as usize] => inside[c] = false,
            l => nearest[c] = nearest[c].min(along(positions[l as usize])),
        }
    }
    for (i, &c) in piece.iter().enumerate() {
        let c = c as usize;
        if inside[c] && local[i] != u32::MAX {
            let l = local[i] as usize;
            source[l] = along(positions[l]) <= nearest[c] + band;
        }
    }
    source
}

/// The corners behind the wrist plane (`local` index set, `along <= 0`) that belong to the
/// wrist's own cross-section. That band of surface splits into pieces over the triangles
/// touching it; the wrist's are the piece holding the corner nearest the wrist's axis and every piece
/// that encircles the axis (its corners' unit directions away from the axis average to less
/// than half a unit). A hip or thigh beside a hanging hand lies to one side of the axis.
fn wrist_band(
    mesh: &Mesh,
    local: &[u32],
    positions: &[DVec3],
    wrist: DVec3,
    axis: DVec3,
) -> Vec<bool> {
    let in_band = |l: u32| l != u32::MAX && (positions[l as usize] - wrist).dot(axis) <= 0.0;
    // Joined over the triangles touching the band (a thin band holds few whole triangles).
    let band: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .filter(|t| {
            t.iter().any(|&v| in_band(local[v as usize]))
                && t.iter().all(|&v| local[v as usize] != u32::MAX)
        })
        .copied()
        .collect();
    let piece = vertex_pieces(mesh.positions.len(), &band);
    let radial = |p: DVec3| {
        let d = p - wrist;
        d - axis * d.dot(axis)
    };
    let count = piece.iter().map(|&c| c as usize + 1).max().unwrap_or(0);
    let mut directions = vec![(DVec3::ZERO, 0usize); count];
    let mut nearest: Option<(f64, u32)> = None;
    for (i, &l) in local.iter().enumerate() {
        if in_band(l) {
            let r = radial(positions[l as usize]);
            let c = &mut directions[piece[i] as usize];
            c.0 += r.normalize_or_zero();
            c.1 += 1;
            if nearest.is_none_or(|(best, _)| r.length() < best) {
                nearest = Some((r.length(), piece[i]));
            }
        }
    }
    let wrist_piece = |c: u32| {
        let (sum, n) = directions[c as usize];
        Some(c) == nearest.map(|n| n.1) || (n > 0 && sum.length() < 0.5 * n as f64)
    };
    let mut source = vec![false; positions.len()];
    for (i, &l) in local.iter().enumerate() {
        if in_band(l) && wrist_piece(piece[i]) {
            source[l as usize] = true;
        }
    }
    source
}

/// Shortest distance along the triangles' edges from the `sources` (distance 0) over the
/// corners `positions` (a multi-source [`Search`] over the mesh's edges, which are not the DMS
/// graph); unreached corners are infinite. `lowered(u, v)` is called each time `v`'s distance
/// is lowered through its neighbour `u` (the last call names its predecessor).
pub(crate) fn edge_geodesic(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    sources: impl IntoIterator<Item = usize>,
    lowered: impl FnMut(usize, usize),
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
    let mut search = Search::costs_only(positions.len());
    for s in sources {
        search.seed(s, 0.0);
    }
    search.relax(
        |u| {
            edges[start[u]..start[u + 1]]
                .iter()
                .map(move |&(_, v)| (v as usize, positions[u].distance(positions[v as usize])))
        },
        lowered,
    );
    search.cost
}

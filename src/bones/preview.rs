//! SVG preview of bones: front, side and top orthographic projections side by side, the skin
//! as a light silhouette behind, bones shaded by kind.

use super::{BoneKind, Bones};
use crate::mesh::Mesh;
use crate::report::View;
use glam::{DVec2, DVec3};
use std::fmt::Write;

/// Fill colour of a bone kind: axial bones ivory, girdles sand, limbs bone-white.
fn colour(kind: BoneKind) -> &'static str {
    match kind {
        BoneKind::Cranium | BoneKind::AnimalCranium | BoneKind::Mandible => "#e8dcc0",
        BoneKind::Vertebra | BoneKind::TailVertebra | BoneKind::RibCage => "#eadfc8",
        BoneKind::Scapula | BoneKind::Pelvis => "#dccaa4",
        _ => "#f2ead8",
    }
}

/// Size of the grid the preview's points are snapped to, pixels: triangles smaller than a
/// cell collapse and are left out (vertex clustering), which keeps the file small (a 27k
/// triangle body with 32 bones: about 300 kB instead of 9 MB) without holes.
const CELL: f64 = 1.0;

/// A standalone SVG with the front, side and top views (see [`View`]) of `bones`, each
/// `width` pixels wide, over the outline of `skin` when given. Each bone is drawn as its
/// front-facing triangles, snapped to a one-pixel grid (triangles that collapse there are
/// left out), in one flat colour, and outlined along its silhouette; bones are painted back to
/// front. The skin is drawn as its silhouette edges. The same input gives the same text.
pub fn bones_svg(bones: &Bones, skin: Option<&Mesh>, width: f64) -> String {
    let margin = 10.0;
    let width = width.max(4.0 * margin);
    let mut out = String::new();
    let mut panels = String::new();
    let mut height: f64 = 0.0;
    for (k, view) in View::ALL.iter().enumerate() {
        let (right, up) = view.axes();
        let towards = right.cross(up);
        let project = |p: DVec3| DVec2::new(p.dot(right), p.dot(up));
        let all = skin
            .into_iter()
            .flat_map(|m| m.positions.iter())
            .chain(bones.bones.iter().flat_map(|b| b.mesh.positions.iter()));
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for p in all {
            let q = project(*p);
            lo = lo.min(q);
            hi = hi.max(q);
        }
        if !lo.is_finite() {
            (lo, hi) = (DVec2::ZERO, DVec2::ONE);
        }
        let extent = (hi - lo).max_element().max(f64::MIN_POSITIVE);
        let scale = (width - 2.0 * margin) / extent;
        let x0 = k as f64 * width;
        let pixel = |p: DVec3| {
            let q = project(p);
            DVec2::new(
                x0 + margin + (q.x - lo.x) * scale,
                margin + (hi.y - q.y) * scale,
            )
        };
        height = height.max((hi.y - lo.y) * scale + 2.0 * margin);
        let _ = writeln!(panels, "<g><title>{}</title>", view.name());
        let snap = |p: DVec3| {
            let q = pixel(p) / CELL;
            (q.x.round() as i64, q.y.round() as i64)
        };
        if let Some(m) = skin {
            let outline = silhouette_edges(m, towards, &snap);
            if !outline.is_empty() {
                let _ = writeln!(
                    panels,
                    "<path d=\"{}\" fill=\"none\" stroke=\"#b8b8b8\" stroke-width=\"0.8\" stroke-linejoin=\"round\"/>",
                    edges_path(&outline)
                );
            }
        }
        // Bones back to front by their mean depth; each one filled, then outlined.
        let mut order: Vec<(f64, usize)> = bones
            .bones
            .iter()
            .enumerate()
            .filter(|(_, b)| !b.mesh.positions.is_empty())
            .map(|(i, b)| {
                let depth = b.mesh.positions.iter().map(|p| p.dot(towards)).sum::<f64>()
                    / b.mesh.positions.len() as f64;
                (depth, i)
            })
            .collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for (_, i) in order {
            let bone = &bones.bones[i];
            let fill = front_triangles(&bone.mesh, towards, &snap);
            if fill.is_empty() {
                continue;
            }
            let mut d = String::new();
            // Each triangle as a move then two relative lines: short numbers.
            for [a, b, c] in &fill {
                let _ = write!(
                    d,
                    "M{}l{}l{}z",
                    point(*a),
                    point((b.0 - a.0, b.1 - a.1)),
                    point((c.0 - b.0, c.1 - b.1))
                );
            }
            let _ = writeln!(
                panels,
                "<g><title>{}</title><path d=\"{d}\" fill=\"{fill}\" stroke=\"{fill}\" stroke-width=\"0.3\"/><path d=\"{}\" fill=\"none\" stroke=\"#8a7a5a\" stroke-width=\"0.5\" stroke-linejoin=\"round\"/></g>",
                bone.name,
                edges_path(&silhouette_edges(&bone.mesh, towards, &snap)),
                fill = colour(bone.kind),
            );
        }
        panels.push_str("</g>\n");
    }
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0}\" height=\"{:.0}\" viewBox=\"0 0 {:.1} {:.1}\">",
        3.0 * width,
        height,
        3.0 * width,
        height
    );
    out.push_str("<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
    out.push_str(&panels);
    out.push_str("</svg>\n");
    out
}

/// A snapped point or offset (in [`CELL`] units) as SVG coordinates: `x y` (up to one
/// decimal).
fn point((x, y): (i64, i64)) -> String {
    let f = |v: i64| {
        let v = v as f64 * CELL;
        if v.fract() == 0.0 {
            format!("{v:.0}")
        } else {
            format!("{v:.1}")
        }
    };
    format!("{} {}", f(x), f(y))
}

/// The front-facing triangles of `mesh` (towards the viewer along `towards`) snapped by
/// `snap`, without those that collapse and without repeats, in the mesh's order.
fn front_triangles(
    mesh: &Mesh,
    towards: DVec3,
    snap: &impl Fn(DVec3) -> (i64, i64),
) -> Vec<[(i64, i64); 3]> {
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        if (b - a).cross(c - a).dot(towards) <= 0.0 {
            continue;
        }
        let tri = [snap(a), snap(b), snap(c)];
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            continue;
        }
        let mut key = tri;
        key.sort_unstable();
        if seen.insert(key) {
            out.push(tri);
        }
    }
    out
}

/// The silhouette of `mesh` seen along `towards`: edges between a front- and a back-facing
/// triangle, and open edges of front-facing ones, snapped by `snap`, without those that
/// collapse and without repeats.
fn silhouette_edges(
    mesh: &Mesh,
    towards: DVec3,
    snap: &impl Fn(DVec3) -> (i64, i64),
) -> Vec<[(i64, i64); 2]> {
    use std::collections::HashMap;
    let mut faces: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = mesh.corners(t);
        let front = (b - a).cross(c - a).dot(towards) > 0.0;
        for k in 0..3 {
            let (u, v) = (tri[k], tri[(k + 1) % 3]);
            let entry = faces.entry((u.min(v), u.max(v))).or_default();
            if front {
                entry.0 += 1;
            } else {
                entry.1 += 1;
            }
        }
    }
    let mut edges: Vec<[(i64, i64); 2]> = faces
        .into_iter()
        .filter(|(_, (front, back))| *front > 0 && (*back > 0 || *front == 1))
        .filter_map(|((u, v), _)| {
            let (p, q) = (
                snap(mesh.positions[u as usize]),
                snap(mesh.positions[v as usize]),
            );
            (p != q).then_some([p.min(q), p.max(q)])
        })
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// Edges as SVG path data, chained into polylines where one ends where the next begins.
fn edges_path(edges: &[[(i64, i64); 2]]) -> String {
    let mut d = String::new();
    let mut last = None;
    for [a, b] in edges {
        if last != Some(*a) {
            let _ = write!(d, "M{}", point(*a));
        }
        let _ = write!(d, "L{}", point(*b));
        last = Some(*b);
    }
    d
}

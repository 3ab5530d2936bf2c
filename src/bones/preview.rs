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

/// A standalone SVG with the front, side and top views (see [`View`]) of `bones`, each
/// `width` pixels wide, over the silhouette of `skin` when given. Triangles facing away from
/// the camera are skipped; the rest are drawn back to front. Coordinates are rounded to 0.1 px,
/// so the same input gives the same text.
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
        let mut triangles: Vec<(f64, String, &str)> = Vec::new();
        let mut add = |mesh: &Mesh, fill: &'static str| {
            for t in 0..mesh.triangles.len() {
                let [a, b, c] = mesh.corners(t);
                if (b - a).cross(c - a).dot(towards) <= 0.0 {
                    continue;
                }
                let depth = (a + b + c).dot(towards) / 3.0;
                let [pa, pb, pc] = [pixel(a), pixel(b), pixel(c)];
                triangles.push((
                    depth,
                    format!(
                        "{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}",
                        pa.x, pa.y, pb.x, pb.y, pc.x, pc.y
                    ),
                    fill,
                ));
            }
        };
        if let Some(m) = skin {
            add(m, "#f0f0f0");
        }
        for b in &bones.bones {
            add(&b.mesh, colour(b.kind));
        }
        let skin_count = skin.map_or(0, |m| {
            (0..m.triangles.len())
                .filter(|&t| {
                    let [a, b, c] = m.corners(t);
                    (b - a).cross(c - a).dot(towards) > 0.0
                })
                .count()
        });
        // The skin stays behind; bones are painted back to front.
        triangles[skin_count..].sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, points, fill) in &triangles {
            let stroke = if *fill == "#f0f0f0" {
                "none"
            } else {
                "#8a7a5a"
            };
            let _ = writeln!(
                panels,
                "<polygon points=\"{points}\" fill=\"{fill}\" stroke=\"{stroke}\" stroke-width=\"0.2\"/>"
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

//! labels.json, a per-vertex coloured PLY and an SVG picture of a labelling.

use super::{Label, Labelling, LimbPair, Part, Side};
use crate::mesh::Mesh;
use glam::{DVec2, DVec3};
use serde_json::{json, Value};
use std::fmt::Write;

/// Colour of a part as `[r, g, b]`: one hue per label, lighter for the right side.
pub fn part_colour(part: &Part) -> [u8; 3] {
    let right = part.side == Some(Side::Right);
    let pick = |l: [u8; 3], r: [u8; 3]| if right { r } else { l };
    match part.label {
        Label::Trunk => [127, 127, 127],
        Label::Head => [214, 39, 40],
        Label::Neck => [255, 152, 150],
        Label::Jaw => [255, 127, 14],
        Label::Tail => [140, 86, 75],
        Label::Arm => pick([31, 119, 180], [174, 199, 232]),
        Label::Leg if part.limb_pair == Some(LimbPair::Fore) => {
            pick([188, 189, 34], [219, 219, 141])
        }
        Label::Leg => pick([44, 160, 44], [152, 223, 138]),
        Label::Wing => pick([148, 103, 189], [197, 176, 213]),
        Label::Digit => pick([227, 119, 194], [247, 182, 210]),
    }
}

fn point(p: DVec3) -> Value {
    json!([p.x, p.y, p.z])
}

/// The labels.json document: figure class, frame, parts (label, side, limb pair, vertex count,
/// attachment and distal points, girdle and digits), sections, level-graph vertices, one part
/// index per mesh vertex (`vertex_labels`) and warnings.
///
/// `source` is the mesh file's vertex map from
/// [`load_with_source_map`](crate::mesh::load_with_source_map): with it, `vertex_labels` has
/// one entry per vertex of the file, in the file's order (`null` for a vertex no face uses;
/// welded duplicates share their vertex's part), so that it lines up with the user's own
/// mesh. Without it, one entry per vertex of the labelled [`Mesh`], in its order.
pub fn labels_json(l: &Labelling, source: Option<&[Option<u32>]>) -> Value {
    let parts: Vec<Value> = l
        .parts
        .iter()
        .map(|p| {
            json!({
                "label": p.label.name(),
                "side": p.side,
                "limb_pair": p.limb_pair,
                "vertex_count": p.vertex_count,
                "section": p.section,
                "parent": p.parent,
                "attachment_vertex": p.attachment_vertex,
                "attachment": point(p.attachment),
                "distal": point(p.distal),
                "girdle": p.girdle,
                "digits": p.digits,
                "level_vertices": p.vertices.len(),
                "dms_voxels": p.voxels.len(),
            })
        })
        .collect();
    let section_part = |s: usize| {
        l.parts
            .iter()
            .position(|p| p.section == Some(s) && p.label != Label::Digit)
            .unwrap_or(0)
    };
    let sections: Vec<Value> = l
        .sections
        .iter()
        .enumerate()
        .map(|(i, s)| {
            json!({
                "id": i,
                "part": section_part(i),
                "attachment_vertex": s.attachment_vertex,
                "attachment": point(s.attachment),
                "distal": point(s.distal),
                "length": s.length,
                "dms_voxels": s.voxels,
                "weight": s.weight,
                "linear_fraction": s.linear_fraction,
                "insignificant": s.insignificant,
            })
        })
        .collect();
    let vertices: Vec<Value> = l
        .level_graph
        .vertices
        .iter()
        .enumerate()
        .map(|(i, v)| {
            json!({
                "centroid": point(v.centroid),
                "parent": v.parent,
                "bin": v.bin,
                "dms_voxels": v.voxels.len(),
                "weight": v.weight,
                "part": l.vertex_parts[i],
                "major_junction": v.major_junction,
                "insignificant": v.insignificant,
                "marks": v.marks,
            })
        })
        .collect();
    json!({
        "format": "skelfit-labels-v1",
        "figure": l.figure.name(),
        "up": point(l.frame.up),
        "forward": point(l.frame.forward),
        "left": point(l.frame.left),
        "forward_guessed": l.forward_found.is_some(),
        "up_found": l.up_found,
        "forward_found": l.forward_found,
        "trunk_angle_deg": if l.trunk_angle.is_finite() { json!(l.trunk_angle) } else { Value::Null },
        "heart_radius": l.level_graph.heart_radius,
        "parts": parts,
        "sections": sections,
        "level_graph": {"root": l.level_graph.root, "vertices": vertices},
        "vertex_labels": match source {
            Some(source) => json!(source
                .iter()
                .map(|v| v.and_then(|v| l.mesh_parts.get(v as usize).copied()))
                .collect::<Vec<_>>()),
            None => json!(l.mesh_parts),
        },
        "warnings": l.warnings,
    })
}

/// An ASCII PLY of `mesh` with a colour per vertex by body part ([`part_colour`]).
pub fn labels_ply(mesh: &Mesh, l: &Labelling) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        "ply\nformat ascii 1.0\ncomment skelfit body-part labels\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.positions.len(),
        mesh.triangles.len()
    );
    for (i, p) in mesh.positions.iter().enumerate() {
        let part = l.mesh_parts.get(i).copied().unwrap_or(0) as usize;
        let c = l.parts.get(part).map(part_colour).unwrap_or([0, 0, 0]);
        let _ = writeln!(
            s,
            "{} {} {} {} {} {}",
            p.x as f32, p.y as f32, p.z as f32, c[0], c[1], c[2]
        );
    }
    for t in &mesh.triangles {
        let _ = writeln!(s, "3 {} {} {}", t[0], t[1], t[2]);
    }
    s
}

fn hex(c: [u8; 3]) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// An SVG picture: front, side and top projections (in the labelling's body frame) of the
/// mesh, triangles tinted by body part, with the level graph drawn on top (edges and vertices
/// coloured by part, major junctions larger) and a legend. `width` is the width of one view in
/// pixels.
pub fn labels_svg(mesh: &Mesh, l: &Labelling, width: f64) -> String {
    let f = l.frame;
    let views: [(&str, DVec3, DVec3); 3] = [
        ("front", f.left, f.up),
        ("side", f.forward, f.up),
        ("top", -f.left, f.forward),
    ];
    let margin = 10.0;
    let mut body = String::new();
    let mut x0 = 0.0;
    let mut height: f64 = 0.0;
    let colours: Vec<String> = l.parts.iter().map(|p| hex(part_colour(p))).collect();
    for (name, right, up) in views {
        let toward = right.cross(up);
        let proj = |p: DVec3| DVec2::new(p.dot(right), p.dot(up));
        let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for &p in &mesh.positions {
            lo = lo.min(proj(p));
            hi = hi.max(proj(p));
        }
        if !lo.is_finite() {
            (lo, hi) = (DVec2::ZERO, DVec2::ONE);
        }
        let extent = (hi - lo).max_element().max(f64::MIN_POSITIVE);
        let scale = (width - 2.0 * margin) / extent;
        let px = |p: DVec3| {
            let q = proj(p);
            DVec2::new(
                x0 + margin + (q.x - lo.x) * scale,
                margin + (hi.y - q.y) * scale,
            )
        };
        height = height.max((hi.y - lo.y) * scale + 2.0 * margin + 16.0);
        let _ = write!(body, "<g><title>{name}</title>");
        let mut tris: Vec<(f64, usize)> = mesh
            .triangles
            .iter()
            .enumerate()
            .filter_map(|(i, t)| {
                let [a, b, c] = t.map(|k| mesh.positions[k as usize]);
                let n = (b - a).cross(c - a);
                (n.dot(toward) > 0.0).then(|| (((a + b + c) / 3.0).dot(toward), i))
            })
            .collect();
        tris.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for (_, i) in tris {
            let t = mesh.triangles[i];
            let part = l.mesh_parts.get(t[0] as usize).copied().unwrap_or(0) as usize;
            let c = colours.get(part).map(String::as_str).unwrap_or("#000000");
            let [a, b, d] = t.map(|k| px(mesh.positions[k as usize]));
            let _ = write!(
                body,
                "<path d=\"M{:.1} {:.1}L{:.1} {:.1}L{:.1} {:.1}Z\" fill=\"{c}\" fill-opacity=\"0.35\"/>",
                a.x, a.y, b.x, b.y, d.x, d.y
            );
        }
        for (i, v) in l.level_graph.vertices.iter().enumerate() {
            if let Some(p) = v.parent {
                let (a, b) = (px(v.centroid), px(l.level_graph.vertices[p].centroid));
                let c = &colours[l.vertex_parts[i] as usize];
                let _ = write!(
                    body,
                    "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{c}\" stroke-width=\"1.5\"/>",
                    a.x, a.y, b.x, b.y
                );
            }
        }
        for (i, v) in l.level_graph.vertices.iter().enumerate() {
            let a = px(v.centroid);
            let c = &colours[l.vertex_parts[i] as usize];
            let r = if v.major_junction { 3.5 } else { 2.0 };
            let _ = write!(
                body,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"{r}\" fill=\"{c}\" stroke=\"#000\" stroke-width=\"0.4\"/>",
                a.x, a.y
            );
        }
        let _ = write!(
            body,
            "<text x=\"{:.1}\" y=\"{:.1}\" font-family=\"sans-serif\" font-size=\"11\">{name}</text></g>",
            x0 + margin,
            margin + 2.0
        );
        x0 += width;
    }
    let (legend, y) = legend(l, &colours, margin, height);
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0}\" height=\"{:.0}\" viewBox=\"0 0 {:.0} {:.0}\"><rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>{body}{legend}</svg>\n",
        x0, y, x0, y
    )
}

/// The legend of [`labels_svg`] below the views (which are `height` pixels high): a swatch
/// and a line per part, then the figure class. Returns it and the picture's height with it.
fn legend(l: &Labelling, colours: &[String], margin: f64, height: f64) -> (String, f64) {
    let mut legend = String::new();
    let mut y = height + 4.0;
    for (i, p) in l.parts.iter().enumerate() {
        let side = match p.side {
            Some(Side::Left) => " L",
            Some(Side::Right) => " R",
            None => "",
        };
        let pair = match p.limb_pair {
            Some(LimbPair::Fore) if p.label != Label::Arm => " fore",
            Some(LimbPair::Hind) if p.label != Label::Arm => " hind",
            _ => "",
        };
        let _ = write!(
            legend,
            "<rect x=\"{margin}\" y=\"{:.1}\" width=\"10\" height=\"10\" fill=\"{}\"/><text x=\"{:.1}\" y=\"{:.1}\" font-family=\"sans-serif\" font-size=\"11\">{i}: {}{side}{pair} ({} vertices)</text>",
            y,
            colours[i],
            margin + 14.0,
            y + 9.0,
            p.label.name(),
            p.vertex_count
        );
        y += 14.0;
    }
    let _ = write!(
        legend,
        "<text x=\"{margin}\" y=\"{:.1}\" font-family=\"sans-serif\" font-size=\"11\">figure: {}</text>",
        y + 9.0,
        l.figure.name()
    );
    y += 18.0;
    (legend, y)
}

//! A picture of an outline skeleton: outline, simplified polygon, straight skeleton and final
//! bones, as a self-contained SVG.

use super::OutlineSkeleton;
use glam::DVec2;
use std::fmt::Write;

/// SVG text showing the resampled outline (black), the Douglas-Peucker polygon (blue, dashed),
/// the straight skeleton (grey, peripheral arcs lighter), and the final bones (red) with their
/// joints. The picture is upright (+Y up) and scaled to 800 pixels across its longer side.
pub fn outline_svg(part: &OutlineSkeleton) -> String {
    const SIZE: f64 = 800.0;
    const MARGIN: f64 = 20.0;
    let (lo, hi) = part.outline.bounds();
    let extent = (hi - lo).max_element().max(f64::MIN_POSITIVE);
    let scale = (SIZE - 2.0 * MARGIN) / extent;
    let (w, h) = (
        (hi.x - lo.x) * scale + 2.0 * MARGIN,
        (hi.y - lo.y) * scale + 2.0 * MARGIN,
    );
    let map = |p: DVec2| DVec2::new(MARGIN + (p.x - lo.x) * scale, MARGIN + (hi.y - p.y) * scale);
    let polyline = |points: &[DVec2]| {
        points
            .iter()
            .map(|&p| {
                let q = map(p);
                format!("{:.2},{:.2}", q.x, q.y)
            })
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.2} {h:.2}">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r##"<polygon points="{}" fill="#f4f0e8" stroke="black" stroke-width="1.5"/>"##,
        polyline(&part.resampled)
    );
    let _ = writeln!(
        s,
        r##"<polygon points="{}" fill="none" stroke="#3060c0" stroke-width="1" stroke-dasharray="4 3"/>"##,
        polyline(&part.polygon)
    );
    for arc in &part.straight.arcs {
        let (a, b) = (
            map(part.straight.nodes[arc[0]].position),
            map(part.straight.nodes[arc[1]].position),
        );
        let peripheral = part.straight.is_corner(arc[0]) || part.straight.is_corner(arc[1]);
        let colour = if peripheral { "#c8c8c8" } else { "#808080" };
        let _ = writeln!(
            s,
            r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="{colour}" stroke-width="1"/>"#,
            a.x, a.y, b.x, b.y
        );
    }
    let joints = &part.skeleton.joints;
    for joint in joints {
        if let Some(p) = joint.parent {
            let (a, b) = (
                map(joints[p.0].position.truncate()),
                map(joint.position.truncate()),
            );
            let _ = writeln!(
                s,
                r##"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="#d02020" stroke-width="3"/>"##,
                a.x, a.y, b.x, b.y
            );
        }
    }
    for joint in joints {
        let q = map(joint.position.truncate());
        let _ = writeln!(
            s,
            r##"<circle cx="{:.2}" cy="{:.2}" r="5" fill="#d02020" stroke="white"><title>{}</title></circle>"##,
            q.x, q.y, joint.name
        );
    }
    s.push_str("</svg>\n");
    s
}

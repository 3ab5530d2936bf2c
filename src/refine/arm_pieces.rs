//! Shoulders of modular figures whose arm is a separate mesh piece pushed into the trunk.
//!
//! Game characters are often built from pieces: an arm modelled on its own, its rounded
//! proximal end sunk into the trunk so that no seam shows. Slicing the joined surface finds
//! the arm's root where the arm leaves the trunk's surface, but the arm piece turns about the
//! centre of its own buried end: the centre of the round cap that closes it, one arm radius in
//! from its proximal tip. [`shoulders_on_arm_pieces`] moves each shoulder there when the piece
//! carrying the elbow lies wholly on its side of the median plane (a one-surface body's
//! "piece" is the whole body) and reaches past the shoulder into the trunk by more than its
//! radius.

use super::frame::BodyFrame;
use crate::mesh::Mesh;
use glam::DVec3;

/// The shoulder of one arm: `component` the piece of every vertex of `pieces`
/// ([`crate::mesh::vertex_pieces`]), `elbow` and `shoulder` as placed so far, `centre` a point of the
/// median plane, `frame.left` its normal. The new shoulder, or `None` when the arm is not a
/// separate piece buried in the trunk.
pub(super) fn shoulder_on_arm_piece(
    pieces: &Mesh,
    component: &[u32],
    frame: &BodyFrame,
    centre: DVec3,
    elbow: DVec3,
    shoulder: DVec3,
) -> Option<DVec3> {
    let upper = shoulder - elbow;
    let length = upper.length();
    let axis = upper.try_normalize()?;
    // The piece carrying the elbow: the one of the vertex nearest it.
    let nearest = (0..pieces.positions.len()).min_by(|&a, &b| {
        pieces.positions[a]
            .distance_squared(elbow)
            .total_cmp(&pieces.positions[b].distance_squared(elbow))
    })?;
    let piece = component[nearest];
    let side = (shoulder - centre).dot(frame.left).signum();
    let mut reach = f64::NEG_INFINITY;
    let mut along = Vec::new();
    for (v, &p) in pieces.positions.iter().enumerate() {
        if component[v] != piece {
            continue;
        }
        // A piece crossing the median plane is a body, a shirt or a cape, not an arm.
        if (p - centre).dot(frame.left) * side <= 0.0 {
            return None;
        }
        let t = (p - elbow).dot(axis);
        reach = reach.max(t);
        along.push((t, (p - elbow - axis * t).length()));
    }
    // The upper arm's radius: the upper quartile of the distances from the axis of the piece's
    // vertices between the elbow and its tip (the caps' rings lie nearer the axis; a low-poly
    // cylinder has vertices only at its ends).
    let mut radii: Vec<f64> = along
        .iter()
        .filter(|&&(t, _)| t > 0.0 && t < reach)
        .map(|&(_, r)| r)
        .collect();
    if radii.len() < 3 {
        return None;
    }
    radii.sort_by(f64::total_cmp);
    let radius = radii[3 * radii.len() / 4];
    // Buried: the piece reaches past the shoulder by more than its radius; the cap's centre
    // is one radius in from its tip, on the piece's own axis there.
    if !(reach - radius > length && radius > 0.0) {
        return None;
    }
    let on_line = elbow + axis * (reach - radius);
    Some(on_line + cap_offset(pieces, component, piece, elbow, axis, reach - 2.0 * radius))
}

/// How far the piece's own axis lies from the line through `elbow` along `axis` at its buried
/// end: the mean offset, across that line, of the piece's vertices beyond `from` along it (the
/// round cap and the ring at its base lie evenly around the piece's axis). The line runs from
/// the elbow to the shoulder sliced where the arm leaves the trunk, which a chest or a head
/// shell around the arm's root can put off the piece's axis (the platformer character's
/// shoulders lay 0.1 behind the arm's axis, 2.8 % of its height).
fn cap_offset(
    pieces: &Mesh,
    component: &[u32],
    piece: u32,
    elbow: DVec3,
    axis: DVec3,
    from: f64,
) -> DVec3 {
    let (sum, count) = pieces
        .positions
        .iter()
        .zip(component)
        .filter(|&(_, &c)| c == piece)
        .map(|(&p, _)| (p - elbow, (p - elbow).dot(axis)))
        .filter(|&(_, t)| t >= from)
        .fold((DVec3::ZERO, 0usize), |(s, n), (d, t)| {
            (s + d - axis * t, n + 1)
        });
    if count == 0 {
        DVec3::ZERO
    } else {
        sum / count as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> BodyFrame {
        BodyFrame {
            up: DVec3::Y,
            forward: DVec3::Z,
            left: DVec3::X,
            top: 2.0,
            bottom: 0.0,
        }
    }

    /// A trunk (box across the median plane) and an arm capsule along +x from x0 to 1.5.
    fn figure(x0: f64) -> (Mesh, Vec<u32>) {
        let mut mesh = Mesh::cuboid(DVec3::new(-0.3, 0.5, -0.2), DVec3::new(0.3, 1.5, 0.2));
        let arm = Mesh::capsule(DVec3::ZERO, 0.08, 0.5 * (1.5 - x0) - 0.08, 8, 16);
        // The capsule stands along +y about the origin: lay it along +x from x0 to 1.5.
        let mid = 0.5 * (1.5 + x0);
        let offset = mesh.positions.len() as u32;
        mesh.positions.extend(
            arm.positions
                .iter()
                .map(|p| DVec3::new(mid + p.y, 1.3 + p.x, p.z)),
        );
        mesh.triangles
            .extend(arm.triangles.iter().map(|t| t.map(|i| i + offset)));
        let pieces = crate::mesh::vertex_pieces(mesh.positions.len(), &mesh.triangles);
        (mesh, pieces)
    }

    #[test]
    fn a_buried_arm_piece_turns_about_its_cap_and_a_flush_one_keeps_its_shoulder() {
        let (elbow, shoulder) = (DVec3::new(0.9, 1.3, 0.0), DVec3::new(0.45, 1.3, 0.0));
        let (mesh, component) = figure(0.1);
        let moved =
            shoulder_on_arm_piece(&mesh, &component, &frame(), DVec3::ZERO, elbow, shoulder)
                .expect("buried arm");
        // The capsule's proximal tip is near x = 0.1; its cap's centre one radius further out.
        assert!((moved.x - 0.18).abs() < 0.03, "{moved:?}");
        assert!((moved.y - 1.3).abs() < 1e-9);
        // A shoulder sliced off the piece's axis (behind it) still turns about the cap's
        // centre, on the piece's axis.
        let behind = DVec3::new(0.45, 1.3, -0.06);
        let moved = shoulder_on_arm_piece(&mesh, &component, &frame(), DVec3::ZERO, elbow, behind)
            .expect("buried arm");
        // (On the line it was 0.09 behind.)
        assert!(
            moved.z.abs() < 0.02 && (moved.y - 1.3).abs() < 0.01,
            "{moved:?}"
        );
        assert!((moved.x - 0.18).abs() < 0.08, "{moved:?}");
        // An arm piece that starts at the shoulder is not buried: no move.
        let (mesh, component) = figure(0.4);
        assert!(
            shoulder_on_arm_piece(&mesh, &component, &frame(), DVec3::ZERO, elbow, shoulder)
                .is_none()
        );
    }
}

//! Loose pieces lying apart from the figure (a helper object, a stray triangle far away) are
//! left out of the voxelization: the grid is sized on the figure's bounding box, and one such
//! piece would otherwise coarsen every voxel by the distance to it.

use crate::mesh::Mesh;
use glam::DVec3;

/// Share of the surface area the figure (the pieces around the largest one) must hold before
/// anything is left out (two figures of about one size far apart keep every piece).
const MAIN_SHARE: f64 = 0.6;

/// A piece is part of the figure when its bounding box meets the figure's, enlarged by this
/// fraction of the largest piece's longest side on every side.
const MARGIN: f64 = 0.1;

/// What [`figure_mesh`] left out.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct LeftOut {
    /// Connected pieces left out.
    pub pieces: usize,
    /// Their triangles.
    pub triangles: usize,
    /// Their share of the surface area.
    pub area_share: f64,
}

/// The mesh to voxelize: `mesh` with only the connected pieces (triangles sharing vertices)
/// that make the figure, `None` when nothing is left out.
///
/// The figure grows from the largest piece (by area): a piece joins when its bounding box
/// meets the figure's, enlarged on every side by [`MARGIN`] of the largest piece's longest
/// side, until no more piece joins (so a figure made of many pieces, a body with separate
/// head, hands and clothes, stays whole). The rest is left out when the figure holds at least
/// [`MAIN_SHARE`] of the area.
pub(super) fn figure_mesh(mesh: &Mesh) -> Option<(Mesh, LeftOut)> {
    let (component, count) = mesh.triangle_components();
    if count < 2 {
        return None;
    }
    let mut area = vec![0.0; count];
    let mut lo = vec![DVec3::splat(f64::INFINITY); count];
    let mut hi = vec![DVec3::splat(f64::NEG_INFINITY); count];
    for (t, &c) in component.iter().enumerate() {
        let c = c as usize;
        let [a, b, d] = mesh.corners(t);
        area[c] += (b - a).cross(d - a).length() * 0.5;
        for p in [a, b, d] {
            lo[c] = lo[c].min(p);
            hi[c] = hi[c].max(p);
        }
    }
    let total: f64 = area.iter().sum();
    let main = (0..count).max_by(|&a, &b| area[a].total_cmp(&area[b]).then(b.cmp(&a)))?;
    if total.is_nan() || total <= 0.0 || area[main] <= 0.0 {
        return None;
    }
    let margin = DVec3::splat(MARGIN * (hi[main] - lo[main]).max_element());
    let (mut box_lo, mut box_hi) = (lo[main] - margin, hi[main] + margin);
    let mut keep = vec![false; count];
    keep[main] = true;
    let mut kept_area = area[main];
    loop {
        let mut grown = false;
        for c in 0..count {
            if !keep[c] && lo[c].cmple(box_hi).all() && hi[c].cmpge(box_lo).all() {
                keep[c] = true;
                kept_area += area[c];
                box_lo = box_lo.min(lo[c] - margin);
                box_hi = box_hi.max(hi[c] + margin);
                grown = true;
            }
        }
        if !grown {
            break;
        }
    }
    if keep.iter().all(|&k| k) || kept_area < MAIN_SHARE * total {
        return None;
    }
    let mut left_out = LeftOut::default();
    for c in (0..count).filter(|&c| !keep[c]) {
        left_out.pieces += 1;
        left_out.area_share += area[c] / total;
    }
    let triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .zip(&component)
        .filter(|(_, &c)| keep[c as usize])
        .map(|(t, _)| *t)
        .collect();
    left_out.triangles = mesh.triangles.len() - triangles.len();
    let figure = Mesh {
        positions: mesh.positions.clone(),
        triangles,
    };
    Some((figure, left_out))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_piece_at(offset: DVec3, scale: f64) -> Mesh {
        let body = Mesh::capsule(DVec3::ZERO, 0.2, 1.0, 8, 16);
        let piece = Mesh::capsule(offset, 0.2 * scale, 1.0 * scale, 8, 16);
        let base = body.positions.len() as u32;
        let mut positions = body.positions.clone();
        positions.extend(&piece.positions);
        let mut triangles = body.triangles.clone();
        triangles.extend(piece.triangles.iter().map(|t| t.map(|i| i + base)));
        Mesh::new(positions, triangles).unwrap()
    }

    #[test]
    fn a_far_small_piece_is_left_out_and_a_near_one_kept_also_among_many_pieces() {
        let far = with_piece_at(DVec3::new(20.0, 0.0, 0.0), 0.1);
        let (kept, left_out) = figure_mesh(&far).unwrap();
        assert_eq!(left_out.pieces, 1);
        assert_eq!(
            kept.triangles.len() + left_out.triangles,
            far.triangles.len()
        );
        assert!(left_out.area_share > 0.0 && left_out.area_share < 0.05);
        // Beside the body (a separate hand, an eye): part of the figure.
        assert!(figure_mesh(&with_piece_at(DVec3::new(0.35, 0.0, 0.0), 0.3)).is_none());
        // Two equal figures: nothing is left out.
        assert!(figure_mesh(&with_piece_at(DVec3::new(20.0, 0.0, 0.0), 1.0)).is_none());
        // A figure of many pieces, none of them 60 % of the area, with a far fragment: the
        // fragment is left out, the pieces of the figure are kept.
        let mut many = Mesh::capsule(DVec3::ZERO, 0.2, 1.0, 8, 16);
        for k in 1..15 {
            let piece = Mesh::capsule(DVec3::new(0.3 * k as f64, 0.0, 0.0), 0.2, 1.0, 8, 16);
            let base = many.positions.len() as u32;
            many.positions.extend(&piece.positions);
            many.triangles
                .extend(piece.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        let pieces = many.triangles.len();
        let far = {
            let fragment = Mesh::capsule(DVec3::new(500.0, 0.0, 0.0), 0.02, 0.1, 8, 16);
            let base = many.positions.len() as u32;
            let mut m = many.clone();
            m.positions.extend(&fragment.positions);
            m.triangles
                .extend(fragment.triangles.iter().map(|t| t.map(|i| i + base)));
            m
        };
        let (kept, left_out) = figure_mesh(&far).unwrap();
        assert_eq!(left_out.pieces, 1);
        assert_eq!(kept.triangles.len(), pieces);
        assert!(figure_mesh(&many).is_none());
        // One piece: nothing to do.
        assert!(figure_mesh(&Mesh::capsule(DVec3::ZERO, 0.2, 1.0, 8, 16)).is_none());
    }
}

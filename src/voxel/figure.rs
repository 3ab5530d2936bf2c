//! Loose pieces lying apart from the figure (a helper object, a stray triangle far away) are
//! left out of the voxelization: the grid is sized on the figure's bounding box, and one such
//! piece would otherwise coarsen every voxel by the distance to it.

use crate::mesh::Mesh;
use glam::DVec3;
use nalgebra::{Matrix3, SymmetricEigen};
use serde::Serialize;

/// Share of the surface area the figure (the pieces around the largest one) must hold before
/// anything is left out (two figures of about one size far apart keep every piece).
const MAIN_SHARE: f64 = 0.6;

/// A piece is part of the figure when its bounding box meets the figure's, enlarged by this
/// fraction of the largest piece's longest side on every side.
const MARGIN: f64 = 0.1;

/// A held prop is at least this fraction of the mesh's longest side long...
const PROP_MIN_LENGTH: f64 = 0.2;
/// ...at most this fraction of it wide (a blade or a shaft; a limb of the slimmest adult is
/// 5 % of the height across, a finger is short)...
const PROP_MAX_WIDTH: f64 = 0.04;
/// ...at most this fraction of it thick (a blade 1.2 cm, a staff 3 cm on a 1.75 m figure: 0.007
/// and 0.017; a tail, even a thin one modelled apart, is thicker: a rat's 0.04, the toy
/// quadruped's 0.027)...
const PROP_MAX_THICKNESS: f64 = 0.02;
/// ...and at least this many times as long as it is wide.
const PROP_MIN_ELONGATION: f64 = 8.0;
/// Two pieces whose principal extents agree within this fraction are twins: mirrored parts of
/// the figure (a pair of peg legs, antennae), not something one hand holds.
const TWIN_TOLERANCE: f64 = 0.15;
/// Props may hold at most this share of the surface area: a figure built of rods is rods.
const PROP_MAX_SHARE: f64 = 0.25;

/// A small sheet, each at most this share of the surface area (a hair card, an eyelash, an
/// eyebrow: 0.3-1 % of a body's area for a card 6 cm wide and 10-30 cm long)...
const SHEET_MAX_SHARE: f64 = 0.01;
/// ...open (with boundary edges) and at most this fraction of the mesh's longest side thick
/// (a voxel at the default size), encloses nothing: it is left out of the voxels. Stacked,
/// such sheets still disturbed the inside/outside vote around a head, and the head's joint
/// moved 5 % of the height up.
const SHEET_MAX_THICKNESS: f64 = 0.01;

/// A thin, long, rigid piece the figure holds (a sword, a staff, a spear): left out of the
/// voxels, so that it makes no limb, and bound rigidly to the joint it touches when skinned.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Prop {
    /// The mesh vertices of the piece, ascending (not serialized; `vertex_count` is).
    #[serde(skip)]
    pub vertices: Vec<u32>,
    /// How many vertices the piece has.
    pub vertex_count: usize,
    /// Its largest principal extent, mesh units.
    pub length: f64,
    /// Its second principal extent (the width of a blade), mesh units.
    pub width: f64,
    /// The mean of its vertices, mesh units.
    pub centre: [f64; 3],
}

/// What [`figure_mesh`] left out.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct LeftOut {
    /// Connected pieces left out (props not counted).
    pub pieces: usize,
    /// Their triangles.
    pub triangles: usize,
    /// Their share of the surface area.
    pub area_share: f64,
    /// The held props left out ([`Prop`]).
    pub props: Vec<Prop>,
    /// Small open sheets left out ([`sheet_pieces`]: hair cards, lashes).
    pub sheets: usize,
    /// Their vertices, ascending.
    pub sheet_vertices: Vec<u32>,
}

/// Every piece's vertices (ascending) and principal extents ([`extents`]), for the `count`
/// pieces (`component` of every triangle).
fn piece_shapes(mesh: &Mesh, component: &[u32], count: usize) -> Vec<(Vec<u32>, [f64; 3])> {
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); count];
    for (t, &c) in component.iter().enumerate() {
        members[c as usize].extend_from_slice(&mesh.triangles[t]);
    }
    members
        .into_iter()
        .map(|mut v| {
            v.sort_unstable();
            v.dedup();
            let points: Vec<DVec3> = v.iter().map(|&i| mesh.positions[i as usize]).collect();
            let e = extents(&points);
            (v, e)
        })
        .collect()
}

/// Which of the pieces (`component` of every triangle, `shapes` from [`piece_shapes`]) are small open sheets: not the
/// largest piece (`main`), at most [`SHEET_MAX_SHARE`] of the area each, with a boundary edge
/// (an edge of one triangle only), and at most [`SHEET_MAX_THICKNESS`] of the mesh's longest
/// side `longest` thick. A sheet encloses no volume: crossed by a ray it only adds a vote
/// (hair cards over a scalp, layered, turn the vote around the head).
fn sheet_pieces(
    mesh: &Mesh,
    component: &[u32],
    shapes: &[(Vec<u32>, [f64; 3])],
    main: usize,
    area: &[f64],
    longest: f64,
) -> Vec<bool> {
    let count = shapes.len();
    let total: f64 = area.iter().sum();
    let small: Vec<bool> = (0..count)
        .map(|c| c != main && area[c] <= SHEET_MAX_SHARE * total)
        .collect();
    if !small.iter().any(|&b| b) {
        return small;
    }
    let mut edges: std::collections::HashMap<(u32, u32), u32> = std::collections::HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if !small[component[t] as usize] {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let mut open = vec![false; count];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let c = component[t] as usize;
        if !small[c] {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if edges.get(&(a.min(b), a.max(b))) == Some(&1) {
                open[c] = true;
            }
        }
    }
    (0..count)
        .map(|c| small[c] && open[c] && shapes[c].1[2] <= SHEET_MAX_THICKNESS * longest)
        .collect()
}

/// The principal extents of `points` (largest first): the spread of their projections on the
/// eigenvectors of their covariance.
fn extents(points: &[DVec3]) -> [f64; 3] {
    let n = points.len().max(1) as f64;
    let mean = points.iter().copied().sum::<DVec3>() / n;
    let mut cov = Matrix3::<f64>::zeros();
    for p in points {
        let d = *p - mean;
        let v = nalgebra::Vector3::new(d.x, d.y, d.z);
        cov += v * v.transpose();
    }
    let eigen = SymmetricEigen::new(cov / n);
    let mut out = [0.0; 3];
    for (k, e) in out.iter_mut().enumerate() {
        let axis = eigen.eigenvectors.column(k);
        let axis = DVec3::new(axis[0], axis[1], axis[2]);
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                let t = (*p - mean).dot(axis);
                (lo.min(t), hi.max(t))
            });
        *e = if hi >= lo { hi - lo } else { 0.0 };
    }
    out.sort_by(|a, b| b.total_cmp(a));
    out
}

/// Which of the pieces (`shapes` from [`piece_shapes`]) are held props: at least
/// [`PROP_MIN_LENGTH`] of the mesh's longest side `longest` long, at most [`PROP_MAX_WIDTH`]
/// of it wide and [`PROP_MAX_THICKNESS`] thick, [`PROP_MIN_ELONGATION`] times longer than
/// wide, not the largest piece
/// (`main`), and with no twin (another piece whose three principal extents agree within
/// [`TWIN_TOLERANCE`]: the figure's parts come in mirrored pairs, a held sword alone). None
/// when they would hold more than [`PROP_MAX_SHARE`] of the area.
fn prop_pieces(
    mesh: &Mesh,
    shapes: &[(Vec<u32>, [f64; 3])],
    main: usize,
    area: &[f64],
    longest: f64,
) -> Vec<Option<Prop>> {
    let count = shapes.len();
    let twins = |a: &[f64; 3], b: &[f64; 3]| {
        a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= TWIN_TOLERANCE * x.max(*y) + 1e-9 * longest)
    };
    let mut props: Vec<Option<Prop>> = vec![None; count];
    for (c, (vertices, e)) in shapes.iter().enumerate() {
        let [length, width, thickness] = *e;
        if c == main
            || length < PROP_MIN_LENGTH * longest
            || width > PROP_MAX_WIDTH * longest
            || thickness > PROP_MAX_THICKNESS * longest
            || length < PROP_MIN_ELONGATION * width
            || shapes
                .iter()
                .enumerate()
                .any(|(d, (_, f))| d != c && twins(e, f))
        {
            continue;
        }
        let centre = vertices
            .iter()
            .map(|&i| mesh.positions[i as usize])
            .sum::<DVec3>()
            / vertices.len().max(1) as f64;
        props[c] = Some(Prop {
            vertices: vertices.clone(),
            vertex_count: vertices.len(),
            length,
            width,
            centre: centre.to_array(),
        });
    }
    let total: f64 = area.iter().sum();
    let held: f64 = (0..count)
        .filter(|&c| props[c].is_some())
        .map(|c| area[c])
        .sum();
    if held > PROP_MAX_SHARE * total {
        return vec![None; count];
    }
    props
}

/// The mesh to voxelize: `mesh` with only the connected pieces (triangles sharing vertices)
/// that make the figure, `None` when nothing is left out.
///
/// Held props ([`prop_pieces`]: a sword, a staff) and small open sheets ([`sheet_pieces`]:
/// hair cards, lashes) are left out first. The figure grows from
/// the largest piece (by area): a piece joins when its bounding box meets the figure's,
/// enlarged on every side by [`MARGIN`] of the largest piece's longest side, until no more
/// piece joins (so a figure made of many pieces, a body with separate head, hands and clothes,
/// stays whole). The rest is left out when the figure holds at least [`MAIN_SHARE`] of the
/// area that is not props.
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
    let longest = (0..count).fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), c| {
        (a.min(lo[c]), b.max(hi[c]))
    });
    let longest = (longest.1 - longest.0).max_element();
    let shapes = piece_shapes(mesh, &component, count);
    let mut props = prop_pieces(mesh, &shapes, main, &area, longest);
    let is_sheet = sheet_pieces(mesh, &component, &shapes, main, &area, longest);
    // Props and sheets are left out alike below (never kept, not loose pieces).
    let is_prop: Vec<bool> = props
        .iter()
        .zip(&is_sheet)
        .map(|(p, &s)| p.is_some() || s)
        .collect();
    let prop_area: f64 = (0..count).filter(|&c| is_prop[c]).map(|c| area[c]).sum();
    let margin = DVec3::splat(MARGIN * (hi[main] - lo[main]).max_element());
    let (mut box_lo, mut box_hi) = (lo[main] - margin, hi[main] + margin);
    let mut keep = vec![false; count];
    keep[main] = true;
    let mut kept_area = area[main];
    loop {
        let mut grown = false;
        for c in 0..count {
            if !keep[c] && !is_prop[c] && lo[c].cmple(box_hi).all() && hi[c].cmpge(box_lo).all() {
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
    // Two figures of about one size far apart keep every piece but the props.
    if kept_area < MAIN_SHARE * (total - prop_area) {
        for (k, &p) in keep.iter_mut().zip(&is_prop) {
            *k = !p;
        }
    }
    if keep.iter().all(|&k| k) {
        return None;
    }
    let mut left_out = LeftOut::default();
    for c in (0..count).filter(|&c| !keep[c]) {
        match props[c].take() {
            Some(prop) => left_out.props.push(prop),
            None if is_sheet[c] => left_out.sheets += 1,
            None => {
                left_out.pieces += 1;
                left_out.area_share += area[c] / total;
            }
        }
    }
    let triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .zip(&component)
        .filter(|(_, &c)| keep[c as usize])
        .map(|(t, _)| *t)
        .collect();
    left_out.triangles = component
        .iter()
        .filter(|&&c| !keep[c as usize] && !is_prop[c as usize])
        .count();
    let mut sheet_vertices: Vec<u32> = mesh
        .triangles
        .iter()
        .zip(&component)
        .filter(|(_, &c)| is_sheet[c as usize] && !keep[c as usize])
        .flat_map(|(t, _)| *t)
        .collect();
    sheet_vertices.sort_unstable();
    sheet_vertices.dedup();
    left_out.sheet_vertices = sheet_vertices;
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

    /// A body capsule 1.8 tall with `pieces` added.
    fn body_with(pieces: &[Mesh]) -> Mesh {
        let mut m = Mesh::capsule(DVec3::new(0.0, 0.9, 0.0), 0.2, 0.7, 8, 16);
        for piece in pieces {
            let base = m.positions.len() as u32;
            m.positions.extend(&piece.positions);
            m.triangles
                .extend(piece.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        m
    }

    #[test]
    fn a_thin_long_piece_without_a_twin_is_a_held_prop_and_left_out() {
        let blade = |x: f64| {
            Mesh::cuboid(
                DVec3::new(x - 0.025, 0.1, -0.006),
                DVec3::new(x + 0.025, 1.1, 0.006),
            )
        };
        // A sword beside the body: a prop, left out, and named with its length and width.
        let armed = body_with(&[blade(0.3)]);
        let (kept, left_out) = figure_mesh(&armed).unwrap();
        assert_eq!((left_out.pieces, left_out.props.len()), (0, 1));
        let prop = &left_out.props[0];
        assert_eq!(prop.vertex_count, 8);
        assert!((prop.length - 1.0).abs() < 1e-9 && (prop.width - 0.05).abs() < 1e-9);
        assert_eq!(kept.triangles.len() + 12, armed.triangles.len());
        // Two mirrored blades (peg legs, antennae): twins, part of the figure.
        assert!(figure_mesh(&body_with(&[blade(0.3), blade(-0.3)])).is_none());
        // A thick piece as long (an arm) is no prop; nor is a short thin one (a finger).
        let arm = Mesh::cuboid(DVec3::new(0.25, 0.4, -0.05), DVec3::new(0.35, 1.3, 0.05));
        assert!(figure_mesh(&body_with(&[arm])).is_none());
        let finger = Mesh::cuboid(DVec3::new(0.25, 0.4, -0.01), DVec3::new(0.27, 0.55, 0.01));
        assert!(figure_mesh(&body_with(&[finger])).is_none());
        // A rod as thick as a tail (a thin tail modelled apart) is no prop either.
        let tail = Mesh::cuboid(DVec3::new(-0.03, 0.6, -1.2), DVec3::new(0.03, 0.66, -0.2));
        assert!(figure_mesh(&body_with(&[tail])).is_none());
        // A figure whose largest piece is itself a rod keeps it.
        let rod = Mesh::cuboid(DVec3::new(-0.02, 0.0, -0.02), DVec3::new(0.02, 2.0, 0.02));
        assert!(figure_mesh(&rod).is_none());
    }

    /// An open quad `w` wide and `h` high at height `y` in front of the body, one corner
    /// pulled `bend` forward out of its plane.
    fn card(y: f64, w: f64, h: f64, bend: f64) -> Mesh {
        Mesh {
            positions: vec![
                DVec3::new(-w / 2.0, y, 0.21),
                DVec3::new(w / 2.0, y, 0.21),
                DVec3::new(-w / 2.0, y - h, 0.21),
                DVec3::new(w / 2.0, y - h, 0.21 + bend),
            ],
            triangles: vec![[0, 2, 1], [1, 2, 3]],
        }
    }

    #[test]
    fn small_open_sheets_are_left_out_and_closed_or_large_or_thick_pieces_kept() {
        // Cards (hair, lashes): open, flat, small. Left out, not as loose pieces or props.
        let cards: Vec<Mesh> = (0..5)
            .map(|k| card(1.4 - 0.01 * k as f64, 0.05, 0.2, 0.0))
            .collect();
        let haired = body_with(&cards);
        let (kept, left_out) = figure_mesh(&haired).unwrap();
        assert_eq!(
            (left_out.sheets, left_out.pieces, left_out.props.len()),
            (5, 0, 0)
        );
        assert_eq!(left_out.sheet_vertices.len(), 20);
        assert_eq!(kept.triangles.len() + 10, haired.triangles.len());
        // A closed box of a card's size is a piece of the figure (an eye, a button).
        let box_ = Mesh::cuboid(DVec3::new(-0.025, 1.2, 0.2), DVec3::new(0.025, 1.4, 0.21));
        assert!(figure_mesh(&body_with(&[box_])).is_none());
        // An open sheet of a tenth of the area (a cape, a flap of a coat) stays.
        assert!(figure_mesh(&body_with(&[card(1.4, 0.6, 1.0, 0.0)])).is_none());
        // A small open piece bent well out of its plane (a cup, an open shell) stays.
        assert!(figure_mesh(&body_with(&[card(1.4, 0.05, 0.2, 0.1)])).is_none());
    }
}

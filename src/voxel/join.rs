//! Whole figures from many pieces: real characters are made of separate shells (a head, hands,
//! clothing, armour) whose interiors need not touch. Interior components lying near the figure
//! are joined to it by a bridge that closes the gap between them; only components clearly
//! apart are dropped, and named.
//!
//! The figure grows from the largest component. Each round measures, by a breadth-first search
//! through the outside voxels (6-connected steps, up to the largest gap allowed), how far every
//! other component lies from the figure; every component within reach is joined: the bridge
//! is every outside voxel `v` on a near-shortest path between the two,
//! `d_figure(v) + d_piece(v) - 1 <= gap + SLACK` (a closing restricted to the space between
//! the two pieces, so a head shell sitting on a neck with a gap all around is joined all
//! around, and nothing else of the figure changes). Rounds repeat until no component is in
//! reach (a hand joins the forearm piece that joined the body).

use super::components::label_components;
use super::Grid;
use glam::DVec3;
use serde::Serialize;
use std::collections::{BTreeMap, VecDeque};

/// Voxels of slack over the shortest gap that a bridge may take (how wide a bridge is).
const SLACK: usize = 1;

/// A component of the interior dropped because it lies too far from the figure.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DroppedPiece {
    /// Its voxels.
    pub voxels: usize,
    /// The mean of its voxel centres, in mesh units.
    pub centre: [f64; 3],
}

/// What [`join_pieces`] did.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Joining {
    /// 26-connected interior components before joining.
    pub components: usize,
    /// Components joined to the figure across a gap.
    pub joined: usize,
    /// The widest gap crossed, in voxels (outside voxels on the shortest path).
    pub widest_gap: usize,
    /// Outside voxels turned inside as bridges.
    pub bridge_voxels: usize,
    /// Components dropped (largest first).
    pub dropped: Vec<DroppedPiece>,
    /// Their voxels.
    pub dropped_voxels: usize,
}

const UNSEEN: u8 = u8::MAX;

/// The six face neighbours of `i`, skipping those off the grid.
fn face_neighbours(grid: &Grid, i: usize) -> impl Iterator<Item = usize> + '_ {
    let c = grid.coords(i);
    const STEPS: [[i32; 3]; 6] = [
        [-1, 0, 0],
        [1, 0, 0],
        [0, -1, 0],
        [0, 1, 0],
        [0, 0, -1],
        [0, 0, 1],
    ];
    STEPS.into_iter().filter_map(move |s| grid.offset(c, s))
}

/// Breadth-first distances through outside voxels from the voxels `sources` (inside voxels),
/// up to `limit` steps: the outside voxels next to a source get 1. Visited voxels are pushed to
/// `touched` (so the caller can reset `dist`). Calls `contact(d, voxel)` for every inside
/// voxel met from an outside voxel at distance `d`.
fn spread(
    grid: &Grid,
    inside: &[bool],
    sources: &[usize],
    limit: usize,
    dist: &mut [u8],
    touched: &mut Vec<usize>,
    mut contact: impl FnMut(usize, usize),
) {
    let mut queue = VecDeque::new();
    for &s in sources {
        for w in face_neighbours(grid, s) {
            if !inside[w] && dist[w] == UNSEEN {
                dist[w] = 1;
                touched.push(w);
                queue.push_back(w);
            }
        }
    }
    while let Some(v) = queue.pop_front() {
        let d = dist[v] as usize;
        for w in face_neighbours(grid, v) {
            if inside[w] {
                contact(d, w);
            } else if dist[w] == UNSEEN && d < limit {
                dist[w] = (d + 1) as u8;
                touched.push(w);
                queue.push_back(w);
            }
        }
    }
}

/// Voxels of every component but the `main` one (by component), and the main one's boundary
/// voxels; `label` is each voxel's component (`u32::MAX` outside).
fn piece_voxels(
    grid: &Grid,
    inside: &[bool],
    label: &[u32],
    main: usize,
    components: usize,
) -> (Vec<Vec<usize>>, Vec<usize>) {
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); components];
    let mut figure_boundary = Vec::new();
    for (i, &c) in label.iter().enumerate() {
        if c == u32::MAX {
            continue;
        }
        if c as usize == main {
            if face_neighbours(grid, i).any(|w| !inside[w]) {
                figure_boundary.push(i);
            }
        } else {
            members[c as usize].push(i);
        }
    }
    (members, figure_boundary)
}

/// Drops the pieces not joined to the figure (`in_figure`) from `inside` and records them in
/// `out`, largest first.
fn drop_pieces(
    grid: &Grid,
    inside: &mut [bool],
    members: &[Vec<usize>],
    in_figure: &[bool],
    out: &mut Joining,
) {
    for (c, voxels) in members.iter().enumerate() {
        if in_figure[c] || voxels.is_empty() {
            continue;
        }
        let mut centre = DVec3::ZERO;
        for &i in voxels {
            inside[i] = false;
            centre += grid.centre(grid.coords(i));
        }
        out.dropped_voxels += voxels.len();
        out.dropped.push(DroppedPiece {
            voxels: voxels.len(),
            centre: (centre / voxels.len() as f64).to_array(),
        });
    }
    out.dropped.sort_by(|a, b| {
        b.voxels
            .cmp(&a.voxels)
            .then(a.centre[0].total_cmp(&b.centre[0]))
    });
}

/// Joins the interior components of `inside` lying within `max_gap` voxels of the figure (see
/// the module docs) and drops the rest (`max_gap` 0: keeps the largest component only).
pub(crate) fn join_pieces(grid: &Grid, inside: &mut [bool], max_gap: usize) -> Joining {
    let max_gap = max_gap.min(UNSEEN as usize - 2 - SLACK);
    let (label, sizes) = label_components(grid, inside);
    let mut out = Joining {
        components: sizes.len(),
        ..Joining::default()
    };
    if sizes.len() < 2 {
        return out;
    }
    let main = (0..sizes.len())
        .max_by(|&a, &b| sizes[a].cmp(&sizes[b]).then(b.cmp(&a)))
        .unwrap_or(0);
    let (members, figure_boundary) = piece_voxels(grid, inside, &label, main, sizes.len());
    let mut in_figure = vec![false; sizes.len()];
    in_figure[main] = true;
    let mut from_figure = vec![UNSEEN; inside.len()];
    let mut from_piece = vec![UNSEEN; inside.len()];
    let mut touched_figure = Vec::new();
    let mut touched_piece = Vec::new();
    let mut sources = figure_boundary;
    if max_gap == 0 {
        // Joining is off: every piece but the largest is dropped below.
        sources.clear();
    }
    while !sources.is_empty() {
        // Distances from the figure as it stands, and the gap to every component in reach.
        for &v in &touched_figure {
            from_figure[v] = UNSEEN;
        }
        touched_figure.clear();
        let mut gaps: BTreeMap<usize, usize> = BTreeMap::new();
        spread(
            grid,
            inside,
            &sources,
            max_gap,
            &mut from_figure,
            &mut touched_figure,
            |d, w| {
                let c = label[w] as usize;
                if c != u32::MAX as usize && !in_figure[c] {
                    let g = gaps.entry(c).or_insert(d);
                    *g = (*g).min(d);
                }
            },
        );
        if gaps.is_empty() {
            break;
        }
        let mut new_sources = Vec::new();
        let mut bridges = Vec::new();
        for (&c, &gap) in &gaps {
            for &v in &touched_piece {
                from_piece[v] = UNSEEN;
            }
            touched_piece.clear();
            spread(
                grid,
                inside,
                &members[c],
                gap + SLACK,
                &mut from_piece,
                &mut touched_piece,
                |_, _| {},
            );
            for &v in &touched_piece {
                let (a, b) = (from_figure[v], from_piece[v]);
                if a != UNSEEN && (a as usize + b as usize) <= gap + 1 + SLACK {
                    bridges.push(v);
                }
            }
            in_figure[c] = true;
            out.joined += 1;
            out.widest_gap = out.widest_gap.max(gap);
            new_sources.extend(members[c].iter().copied());
        }
        bridges.sort_unstable();
        bridges.dedup();
        for &v in &bridges {
            inside[v] = true;
        }
        out.bridge_voxels += bridges.len();
        // The next round spreads from the joined pieces and bridges (the rest of the figure
        // has been searched already up to the same distance).
        new_sources.extend(bridges);
        sources = new_sources;
    }
    drop_pieces(grid, inside, &members, &in_figure, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(dims: [usize; 3]) -> Grid {
        Grid {
            dims,
            origin: DVec3::ZERO,
            voxel_size: 1.0,
        }
    }

    fn block(g: &Grid, inside: &mut [bool], lo: [usize; 3], hi: [usize; 3]) {
        for z in lo[2]..hi[2] {
            for y in lo[1]..hi[1] {
                for x in lo[0]..hi[0] {
                    inside[g.index([x, y, z])] = true;
                }
            }
        }
    }

    #[test]
    fn a_near_piece_is_bridged_a_far_one_dropped_and_named() {
        let g = grid([40, 12, 12]);
        let mut inside = vec![false; g.len()];
        // Body: x 2..14; head 3 voxels away: x 17..22; far piece: x 33..35.
        block(&g, &mut inside, [2, 2, 2], [14, 10, 10]);
        block(&g, &mut inside, [17, 4, 4], [22, 8, 8]);
        block(&g, &mut inside, [33, 5, 5], [35, 7, 7]);
        let before = inside.iter().filter(|&&b| b).count();
        let j = join_pieces(&g, &mut inside, 5);
        assert_eq!((j.components, j.joined, j.widest_gap), (3, 1, 3));
        assert_eq!(j.dropped.len(), 1);
        assert_eq!(j.dropped[0].voxels, 8);
        assert_eq!(j.dropped[0].centre, [34.0, 6.0, 6.0]);
        // The gap between body and head is closed across the head's whole face, and nothing
        // else grew.
        for y in 4..8 {
            for z in 4..8 {
                for x in 14..17 {
                    assert!(inside[g.index([x, y, z])], "{x} {y} {z}");
                }
            }
        }
        assert!(!inside[g.index([15, 2, 2])]);
        assert_eq!(
            inside.iter().filter(|&&b| b).count(),
            before - 8 + j.bridge_voxels
        );
        let (_, sizes) = label_components(&g, &inside);
        assert_eq!(sizes.len(), 1);
    }

    #[test]
    fn pieces_join_in_chains_and_one_component_is_left_alone() {
        let g = grid([40, 10, 10]);
        let mut inside = vec![false; g.len()];
        // Body, forearm 2 voxels away, hand 2 voxels beyond the forearm (4 + forearm from the
        // body: out of reach of the body alone).
        block(&g, &mut inside, [2, 2, 2], [14, 8, 8]);
        block(&g, &mut inside, [16, 4, 4], [24, 6, 6]);
        block(&g, &mut inside, [26, 3, 3], [29, 7, 7]);
        let j = join_pieces(&g, &mut inside, 3);
        assert_eq!((j.components, j.joined, j.dropped.len()), (3, 2, 0));
        let (_, sizes) = label_components(&g, &inside);
        assert_eq!(sizes.len(), 1);
        let copy = inside.clone();
        let j = join_pieces(&g, &mut inside, 3);
        assert_eq!((j.components, j.joined, j.bridge_voxels), (1, 0, 0));
        assert_eq!(copy, inside);
    }
}

//! Triangles that repeat another one (the same three vertices) are common in game assets:
//! modelling leftovers (a face extruded by zero, a piece duplicated in place) and double-sided
//! geometry (every face copied with its winding reversed, so that it renders from both sides).
//! Both disturb the winding-number vote of `voxel::winding`, which counts every crossing:
//!
//! - a copy with the **same** winding counts twice, so the winding number jumps by 2 across the
//!   patch instead of 1 and every column through it gets a wrong count: a band of doubled faces
//!   across a chest carves the trunk in two, one at the top of a head drills a column of
//!   "inside" down between the legs. No surface means "this side is inside twice", so such
//!   copies are always dropped (the first of the group is kept).
//! - a copy with the **opposite** winding cancels its twin. For a double-sided open sheet (a
//!   cape, a skirt or hair card drawn from both sides) that is right: a sheet encloses nothing.
//!   For a closed shell drawn from both sides (a whole eye or head made double-sided) it would
//!   make the piece vanish from the voxels, so when the faces kept from such pairs close into a
//!   shell with no boundary edge, the reversed twins are dropped and the shell keeps the
//!   winding of its first copies (the vote uses the absolute winding, so either orientation
//!   counts as inside).

use crate::math::{fast_map, FastMap};
use crate::mesh::{DisjointSets, Mesh};

/// Vertices this close (fraction of the bounding-box diagonal) count as one when comparing
/// triangles: exporters write copies whose coordinates differ in the last bits.
const SAME_VERTEX: f64 = 1e-6;

/// The triangle is a cyclic rotation of `[a, b, c]` with the smallest index first; the bool
/// says whether the orientation was reversed to get the sorted key.
fn key_of(t: [u32; 3]) -> ([u32; 3], bool) {
    let i = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
    let r = [t[i], t[(i + 1) % 3], t[(i + 2) % 3]];
    if r[1] <= r[2] {
        (r, false)
    } else {
        ([r[0], r[2], r[1]], true)
    }
}

/// For every triangle of `mesh`, whether the winding vote should skip it (see the module docs):
/// a repeat with the winding of an earlier copy, or the reversed twin within a closed
/// double-sided shell; vertices within [`SAME_VERTEX`] of the diagonal count as one. Returns
/// the mask and how many triangles it skips.
pub(super) fn redundant_triangles(mesh: &Mesh) -> (Vec<bool>, usize) {
    let n = mesh.triangles.len();
    let mut skip = vec![false; n];
    let representative = mesh.merge_within(SAME_VERTEX);
    let triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| representative[i as usize]))
        .collect();
    // First triangle of each orientation per vertex set.
    let mut first: FastMap<[u32; 3], [Option<usize>; 2]> = fast_map(n);
    for (t, &tri) in triangles.iter().enumerate() {
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            continue;
        }
        let (key, reversed) = key_of(tri);
        let slot = &mut first.entry(key).or_insert([None, None])[usize::from(reversed)];
        if slot.is_some() {
            skip[t] = true;
        } else {
            *slot = Some(t);
        }
    }
    // Opposite pairs: the earlier copy is kept; the later twin is dropped only when the kept
    // copies of a connected patch of pairs close into a shell.
    let pairs: Vec<(usize, usize)> = first
        .values()
        .filter_map(|slot| match *slot {
            [Some(a), Some(b)] => Some((a.min(b), a.max(b))),
            _ => None,
        })
        .collect();
    if !pairs.is_empty() {
        for (kept, twins) in closed_patches(&triangles, &pairs) {
            if kept {
                for t in twins {
                    skip[t] = true;
                }
            }
        }
    }
    let count = skip.iter().filter(|&&s| s).count();
    (skip, count)
}

/// Connected patches (through shared edges) of the kept copies of `pairs`, each with whether
/// it is closed (every edge used by exactly two of its triangles) and the twins of its pairs.
fn closed_patches(triangles: &[[u32; 3]], pairs: &[(usize, usize)]) -> Vec<(bool, Vec<usize>)> {
    let m = pairs.len();
    // Undirected edge -> patch triangles (indices into `pairs`) using it.
    let mut edges: FastMap<(u32, u32), Vec<usize>> = fast_map(3 * m);
    for (p, &(kept, _)) in pairs.iter().enumerate() {
        let t = triangles[kept];
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            edges.entry((a.min(b), a.max(b))).or_default().push(p);
        }
    }
    let mut sets = DisjointSets::new(m);
    for users in edges.values() {
        for w in users.windows(2) {
            sets.union(w[0] as u32, w[1] as u32);
        }
    }
    let mut closed: FastMap<u32, bool> = fast_map(0);
    for users in edges.values() {
        let root = sets.find(users[0] as u32);
        let ok = closed.entry(root).or_insert(true);
        *ok &= users.len() == 2;
    }
    let mut patches: FastMap<u32, Vec<usize>> = fast_map(0);
    for (p, &(_, twin)) in pairs.iter().enumerate() {
        patches.entry(sets.find(p as u32)).or_default().push(twin);
    }
    patches
        .into_iter()
        .map(|(root, twins)| (closed.get(&root).copied().unwrap_or(false), twins))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn tetra() -> Mesh {
        Mesh {
            positions: vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::Y,
                DVec3::Z,
                DVec3::new(3.0, 0.0, 0.0),
                DVec3::new(4.0, 0.0, 0.0),
                DVec3::new(3.0, 1.0, 0.0),
            ],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        }
    }

    #[test]
    fn a_repeat_with_the_same_winding_is_skipped_whatever_its_rotation() {
        let mut mesh = tetra();
        mesh.triangles.push([3, 0, 1]); // rotation of [0, 1, 3]
        let (skip, count) = redundant_triangles(&mesh);
        assert_eq!(count, 1);
        assert!(skip[4] && !skip[1]);
    }

    #[test]
    fn a_repeat_whose_coordinates_differ_in_the_last_bits_is_skipped() {
        let mut mesh = tetra();
        let copies = [
            DVec3::new(1e-12, 0.0, 0.0),
            DVec3::new(1.0, 1e-12, 0.0),
            DVec3::Z,
        ];
        mesh.positions.extend(copies);
        // [7, 8, 9] repeats [0, 1, 3] within a trillionth of the diagonal.
        mesh.triangles.push([7, 8, 9]);
        let (skip, count) = redundant_triangles(&mesh);
        assert_eq!(count, 1);
        assert!(skip[4]);
    }

    #[test]
    fn a_double_sided_open_sheet_keeps_both_sides_and_a_double_sided_shell_one() {
        let mut mesh = tetra();
        // An open sheet drawn from both sides: its sides cancel, as a sheet encloses nothing.
        mesh.triangles.push([4, 5, 6]);
        mesh.triangles.push([4, 6, 5]);
        let (skip, count) = redundant_triangles(&mesh);
        assert_eq!(count, 0, "{skip:?}");
        // The closed tetrahedron drawn from both sides: the reversed copies are skipped.
        let mut shell = tetra();
        for t in tetra().triangles {
            shell.triangles.push([t[0], t[2], t[1]]);
        }
        let (skip, count) = redundant_triangles(&shell);
        assert_eq!(count, 4);
        assert!(skip[4..].iter().all(|&s| s) && !skip[..4].iter().any(|&s| s));
    }
}

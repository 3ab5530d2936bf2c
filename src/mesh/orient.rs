//! Consistent outward orientation of triangles.

use super::Mesh;
use glam::DVec3;
use serde::Serialize;
use std::collections::VecDeque;

/// A patch whose boundary edges are at most this fraction of its edges counts as closed
/// enough for its signed volume to decide inside from outside (a body with a few small open
/// seams, such as refdata's quaternius_deer with 6 boundary edges among ~3000, qualifies;
/// a flat sheet does not).
pub const CLOSED_ISH_BOUNDARY_FRACTION: f64 = 0.05;

/// A closed-ish patch whose |signed volume| is at most this fraction of its bounding-box
/// diagonal cubed is flat (e.g. two triangles back to back): its volume sign is rounding noise,
/// so it is oriented like an open patch instead.
pub const FLAT_VOLUME_FRACTION: f64 = 1e-9;

/// What [`Mesh::oriented_outward`] changed.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize)]
pub struct OrientReport {
    /// Triangles whose winding was reversed.
    pub flipped_triangles: usize,
    /// Patches: triangles connected across manifold edges (edges used by exactly two
    /// triangles), each oriented as a unit.
    pub patches: usize,
    /// Patches that were turned inside out because their signed volume was negative.
    pub inverted_patches: usize,
    /// Manifold edges still wound inconsistently afterwards (non-orientable patches such as a
    /// Möbius strip); zero for orientable input.
    pub inconsistent_edges: usize,
}

impl Mesh {
    /// A copy whose triangles are wound consistently and outward (counter-clockwise seen from
    /// outside), with a report of what changed. Vertices are unchanged.
    ///
    /// 1. Triangles are grouped into patches connected across manifold edges; within a patch,
    ///    a breadth-first search from its first triangle flips each neighbour whose winding
    ///    disagrees across the shared edge.
    /// 2. A closed-ish patch (boundary edges at most [`CLOSED_ISH_BOUNDARY_FRACTION`] of its
    ///    edges) is turned inside out when its signed volume about its centroid is negative;
    ///    an open or flat (see [`FLAT_VOLUME_FRACTION`]) patch keeps the winding of the
    ///    majority of its input triangles (ties keep the input).
    ///
    /// Best effort: non-manifold edges (used by three or more triangles) separate patches, so
    /// pieces glued along such edges are oriented independently; a non-orientable patch keeps
    /// the first winding the search reached and its leftover conflicts are counted in
    /// [`OrientReport::inconsistent_edges`]. The result is deterministic.
    ///
    /// # Example
    /// ```
    /// use skelfit::mesh::Mesh;
    /// let cube = Mesh::cuboid(glam::DVec3::ZERO, glam::DVec3::ONE);
    /// let mut broken = cube.clone();
    /// broken.triangles[3].swap(0, 1);
    /// let (fixed, report) = broken.oriented_outward();
    /// assert_eq!(report.flipped_triangles, 1);
    /// assert!((fixed.signed_volume() - 1.0).abs() < 1e-12);
    /// ```
    pub fn oriented_outward(&self) -> (Mesh, OrientReport) {
        let count = self.triangles.len();
        let edges = self.half_edges();
        // Neighbours across manifold edges: (other triangle, whether the winding agrees).
        let mut neighbours: Vec<Vec<(u32, bool)>> = vec![Vec::new(); count];
        let mut boundary_uses = vec![0usize; count];
        for group in Mesh::edge_groups(&edges) {
            match group {
                [single] => boundary_uses[single.triangle as usize] += 1,
                [a, b] if a.triangle != b.triangle => {
                    let agree = a.forward != b.forward;
                    neighbours[a.triangle as usize].push((b.triangle, agree));
                    neighbours[b.triangle as usize].push((a.triangle, agree));
                }
                _ => {}
            }
        }

        let mut flip = vec![false; count];
        let mut patch_of = vec![u32::MAX; count];
        let mut patches: Vec<Vec<u32>> = Vec::new();
        let mut inconsistent_twice = 0usize;
        let mut queue = VecDeque::new();
        for seed in 0..count {
            if patch_of[seed] != u32::MAX {
                continue;
            }
            let id = patches.len() as u32;
            let mut members = vec![seed as u32];
            patch_of[seed] = id;
            queue.push_back(seed);
            while let Some(t) = queue.pop_front() {
                for &(n, agree) in &neighbours[t] {
                    let wanted = flip[t] ^ !agree;
                    if patch_of[n as usize] == u32::MAX {
                        patch_of[n as usize] = id;
                        flip[n as usize] = wanted;
                        members.push(n);
                        queue.push_back(n as usize);
                    } else if flip[n as usize] != wanted {
                        inconsistent_twice += 1;
                    }
                }
            }
            patches.push(members);
        }

        let mut inverted_patches = 0;
        for members in &patches {
            let half_edge_count: usize = members.len() * 3;
            let boundary: usize = members.iter().map(|&t| boundary_uses[t as usize]).sum();
            // Edges ≈ (half edges + boundary edges) / 2.
            let edge_count = (half_edge_count + boundary) as f64 / 2.0;
            let volume = self.patch_volume(members, &flip);
            let closed_ish = boundary as f64 <= CLOSED_ISH_BOUNDARY_FRACTION * edge_count;
            let invert = if closed_ish
                && volume.abs() > FLAT_VOLUME_FRACTION * self.patch_size(members).powi(3)
            {
                volume < 0.0
            } else {
                let flipped = members.iter().filter(|&&t| flip[t as usize]).count();
                2 * flipped > members.len()
            };
            if invert {
                inverted_patches += 1;
                for &t in members {
                    flip[t as usize] = !flip[t as usize];
                }
            }
        }

        let triangles = self
            .triangles
            .iter()
            .zip(&flip)
            .map(|(&[a, b, c], &f)| if f { [a, c, b] } else { [a, b, c] })
            .collect();
        let report = OrientReport {
            flipped_triangles: flip.iter().filter(|&&f| f).count(),
            patches: patches.len(),
            inverted_patches,
            inconsistent_edges: inconsistent_twice / 2,
        };
        let mesh = Mesh {
            positions: self.positions.clone(),
            triangles,
        };
        (mesh, report)
    }

    /// Bounding-box diagonal of the triangles `members`.
    fn patch_size(&self, members: &[u32]) -> f64 {
        let mut corners = members.iter().flat_map(|&t| self.corners(t as usize));
        let Some(first) = corners.next() else {
            return 0.0;
        };
        let (min, max) = corners.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)));
        (max - min).length()
    }

    /// Signed volume of the triangles `members` (with `flip` applied) about their centroid.
    fn patch_volume(&self, members: &[u32], flip: &[bool]) -> f64 {
        let corners = members.len() as f64 * 3.0;
        let centroid = members
            .iter()
            .flat_map(|&t| self.corners(t as usize))
            .sum::<DVec3>()
            / corners;
        members
            .iter()
            .map(|&t| {
                let [a, b, c] = self.corners(t as usize).map(|p| p - centroid);
                let volume = a.dot(b.cross(c)) / 6.0;
                if flip[t as usize] {
                    -volume
                } else {
                    volume
                }
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inside_out_sphere_is_turned_outward() {
        let sphere = Mesh::uv_sphere(DVec3::new(5.0, 0.0, 0.0), 1.0, 8, 12);
        let inverted = Mesh {
            positions: sphere.positions.clone(),
            triangles: sphere
                .triangles
                .iter()
                .map(|&[a, b, c]| [a, c, b])
                .collect(),
        };
        let (fixed, report) = inverted.oriented_outward();
        assert_eq!(fixed, sphere);
        assert_eq!(report.flipped_triangles, sphere.triangles.len());
        assert_eq!(report.inverted_patches, 1);
    }

    proptest::proptest! {
        #[test]
        fn any_pattern_of_flipped_triangles_is_repaired(
            flips in proptest::collection::vec(proptest::bool::ANY, 48),
        ) {
            let sphere = Mesh::uv_sphere(DVec3::new(0.0, 2.0, -1.0), 1.5, 4, 8);
            proptest::prop_assert_eq!(sphere.triangles.len(), flips.len());
            let mut broken = sphere.clone();
            for (tri, &flip) in broken.triangles.iter_mut().zip(&flips) {
                if flip {
                    tri.swap(1, 2);
                }
            }
            let (fixed, report) = broken.oriented_outward();
            proptest::prop_assert_eq!(&fixed, &sphere);
            proptest::prop_assert_eq!(report.flipped_triangles, flips.iter().filter(|&&f| f).count());
        }
    }

    #[test]
    fn consistent_mesh_is_unchanged() {
        let capsule = Mesh::capsule(DVec3::ZERO, 1.0, 2.0, 4, 8);
        let (fixed, report) = capsule.oriented_outward();
        assert_eq!(fixed, capsule);
        assert_eq!(report.flipped_triangles, 0);
        assert_eq!(report.patches, 1);
    }

    #[test]
    fn open_sheet_follows_the_majority() {
        // A 2x1 strip of four triangles in the z = 0 plane, one wound the other way.
        let p = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::X * 2.0,
            DVec3::Y,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
        ];
        let mesh = Mesh::new(p, vec![[0, 1, 4], [0, 4, 3], [1, 5, 2], [1, 5, 4]]).unwrap();
        let (fixed, report) = mesh.oriented_outward();
        assert_eq!(report.flipped_triangles, 1);
        assert_eq!(fixed.triangles[2], [1, 2, 5]);
    }

    #[test]
    fn mobius_strip_reports_a_conflict() {
        // A twisted band of 5 quads: the last quad joins the first with a half twist.
        let n = 5;
        let mut positions = Vec::new();
        for i in 0..n {
            let angle = std::f64::consts::TAU * i as f64 / n as f64;
            let twist = angle / 2.0;
            let centre = DVec3::new(angle.cos(), angle.sin(), 0.0) * 3.0;
            let radial = DVec3::new(angle.cos(), angle.sin(), 0.0);
            let offset = radial * twist.cos() + DVec3::Z * twist.sin();
            positions.push(centre + offset);
            positions.push(centre - offset);
        }
        let mut triangles = Vec::new();
        for i in 0..n as u32 {
            let (a, b) = (2 * i, 2 * i + 1);
            let (c, d) = if i + 1 < n as u32 {
                (2 * i + 2, 2 * i + 3)
            } else {
                (1, 0) // the half twist swaps the sides
            };
            triangles.push([a, b, d]);
            triangles.push([a, d, c]);
        }
        let mesh = Mesh::new(positions, triangles).unwrap();
        let (_, report) = mesh.oriented_outward();
        assert_eq!(report.patches, 1);
        assert!(report.inconsistent_edges >= 1);
    }
}

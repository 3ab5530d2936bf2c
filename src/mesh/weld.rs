//! Welding: merging coincident vertices.

use super::Mesh;
use crate::math::{fast_map, FastMap};
use glam::DVec3;

impl Mesh {
    /// A copy with coincident vertices merged.
    ///
    /// `tolerance` is a fraction of the bounding-box diagonal: two vertices closer than
    /// `tolerance × diagonal` are merged. `0.0` (what the loaders use) merges only vertices with
    /// exactly equal coordinates (`-0.0 == 0.0`), which reconnects seams that exporters split
    /// for UVs or normals without moving anything.
    ///
    /// With a positive tolerance the merge is greedy in vertex order: each vertex joins the
    /// first earlier kept vertex within range (not the transitive closure, so chains of close
    /// vertices are not collapsed into one) and takes its position.
    ///
    /// The output is deterministic: kept vertices stay in their original order, vertices no
    /// triangle uses are dropped, and triangles that end up with a repeated index are dropped;
    /// the other triangles keep their order and winding.
    ///
    /// # Example
    /// ```
    /// use glam::DVec3;
    /// use skelfit::mesh::Mesh;
    /// // Two triangles of a square whose shared edge was split (six vertices).
    /// let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    /// let mesh = Mesh::new(p.to_vec(), vec![[0, 1, 2], [3, 4, 5]]).unwrap();
    /// let welded = mesh.welded(0.0);
    /// assert_eq!(welded.positions.len(), 4);
    /// assert_eq!(welded.triangles, vec![[0, 1, 2], [1, 3, 2]]);
    /// ```
    pub fn welded(&self, tolerance: f64) -> Mesh {
        self.welded_with_map(tolerance).0
    }

    /// [`Mesh::welded`], and for every vertex of `self` the index of the welded vertex it
    /// became: its own or the one it merged into; `None` when that vertex is used by no
    /// kept triangle (dropped). A vertex no triangle uses still maps to the welded vertex at
    /// its position when it merged into one.
    ///
    /// # Example
    /// ```
    /// use glam::DVec3;
    /// use skelfit::mesh::Mesh;
    /// let p = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    /// let mesh = Mesh::new(p.to_vec(), vec![[0, 1, 2], [3, 4, 5]]).unwrap();
    /// let (welded, map) = mesh.welded_with_map(0.0);
    /// assert_eq!(welded.positions.len(), 4);
    /// assert_eq!(map, vec![Some(0), Some(1), Some(2), Some(1), Some(3), Some(2)]);
    /// ```
    pub fn welded_with_map(&self, tolerance: f64) -> (Mesh, Vec<Option<u32>>) {
        let representative = if tolerance > 0.0 {
            self.merge_within(tolerance)
        } else {
            self.merge_exact()
        };
        let mut used = vec![false; self.positions.len()];
        let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(self.triangles.len());
        for tri in &self.triangles {
            let [a, b, c] = tri.map(|i| representative[i as usize]);
            if a != b && b != c && a != c {
                for i in [a, b, c] {
                    used[i as usize] = true;
                }
                triangles.push([a, b, c]);
            }
        }
        let mut new_index = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::new();
        for (i, &p) in self.positions.iter().enumerate() {
            if used[i] {
                new_index[i] = positions.len() as u32;
                positions.push(p);
            }
        }
        for tri in &mut triangles {
            *tri = tri.map(|i| new_index[i as usize]);
        }
        let map = representative
            .iter()
            .map(|&r| Some(new_index[r as usize]).filter(|&i| i != u32::MAX))
            .collect();
        (
            Mesh {
                positions,
                triangles,
            },
            map,
        )
    }

    /// For every vertex, the lowest-index vertex with exactly the same coordinates.
    fn merge_exact(&self) -> Vec<u32> {
        let mut first: FastMap<[u64; 3], u32> = fast_map(self.positions.len());
        self.positions
            .iter()
            .enumerate()
            .map(|(i, p)| *first.entry(exact_key(*p)).or_insert(i as u32))
            .collect()
    }

    /// For every vertex, the first earlier kept vertex within `tolerance × diagonal`, or itself.
    pub(crate) fn merge_within(&self, tolerance: f64) -> Vec<u32> {
        let diagonal = self
            .bounding_box()
            .map_or(0.0, |(min, max)| (max - min).length());
        let radius = tolerance * diagonal;
        if !(radius > 0.0 && radius.is_finite()) {
            return self.merge_exact();
        }
        // Cells twice the radius wide: the points within the radius of a vertex lie in the
        // one or two cells per axis that its reach (the radius and a margin for rounding)
        // spans, at most 8 cells instead of the 27 around a radius-wide cell.
        let size = 2.0 * radius;
        let cell_of = |p: DVec3| (p / size).floor().as_i64vec3().to_array();
        let reach = |p: DVec3| DVec3::splat(radius * (1.0 + 1e-9) + 1e-12 * p.abs().max_element());
        // The kept vertices of each cell as a linked list: the cell's last kept vertex, and
        // for each kept vertex the one kept before it in its cell (`NONE` ends the list).
        const NONE: u32 = u32::MAX;
        let n = self.positions.len();
        let mut last_in_cell: FastMap<[i64; 3], u32> = fast_map(n);
        let mut earlier_in_cell = vec![NONE; n];
        let mut representative = Vec::with_capacity(n);
        for (i, &p) in self.positions.iter().enumerate() {
            let [cx, cy, cz] = cell_of(p);
            let (lo, hi) = (cell_of(p - reach(p)), cell_of(p + reach(p)));
            let mut found = None;
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        let Some(&last) = last_in_cell.get(&[x, y, z]) else {
                            continue;
                        };
                        let mut k = last;
                        while k != NONE {
                            if self.positions[k as usize].distance(p) <= radius
                                && found.is_none_or(|f: u32| k < f)
                            {
                                found = Some(k);
                            }
                            k = earlier_in_cell[k as usize];
                        }
                    }
                }
            }
            match found {
                Some(k) => representative.push(k),
                None => {
                    let last = last_in_cell.entry([cx, cy, cz]).or_insert(NONE);
                    earlier_in_cell[i] = *last;
                    *last = i as u32;
                    representative.push(i as u32);
                }
            }
        }
        representative
    }
}

/// Bit pattern of a position with `-0.0` normalised to `0.0`, for exact hashing.
fn exact_key(p: DVec3) -> [u64; 3] {
    (p + DVec3::ZERO).to_array().map(f64::to_bits)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_weld_reconnects_a_split_cube() {
        let cube = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        // Split every corner: one vertex per triangle corner.
        let positions: Vec<DVec3> = (0..cube.triangles.len())
            .flat_map(|t| cube.corners(t))
            .collect();
        let triangles = (0..cube.triangles.len() as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect();
        let soup = Mesh::new(positions, triangles).unwrap();
        let welded = soup.welded(0.0);
        assert_eq!(welded.positions.len(), 8);
        assert_eq!(welded.triangles.len(), 12);
        assert!((welded.signed_volume() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn merging_within_a_tolerance_matches_brute_force() {
        // Clusters of near points (some just inside, some just outside the radius) far from
        // and near the origin.
        let mut positions = Vec::new();
        let mut x = 5u64;
        let mut next = || {
            x = x
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for offset in [DVec3::ZERO, DVec3::new(40.0, -7.0, 3.0)] {
            for _ in 0..60 {
                let centre = offset + DVec3::new(next(), next(), next()) * 2.0;
                for _ in 0..4 {
                    positions.push(centre + DVec3::new(next(), next(), next()) * 4e-4);
                }
            }
        }
        let n = positions.len() as u32;
        let mesh = Mesh {
            triangles: (0..n - 2).map(|i| [i, i + 1, i + 2]).collect(),
            positions,
        };
        for tolerance in [1e-6, 1e-5, 1e-4] {
            let diagonal = mesh
                .bounding_box()
                .map_or(0.0, |(min, max)| (max - min).length());
            let radius = tolerance * diagonal;
            let mut brute: Vec<u32> = Vec::new();
            for (i, p) in mesh.positions.iter().enumerate() {
                let kept = (0..i)
                    .find(|&k| brute[k] == k as u32 && mesh.positions[k].distance(*p) <= radius);
                brute.push(kept.unwrap_or(i) as u32);
            }
            let merged = mesh.merge_within(tolerance);
            assert_eq!(merged, brute, "tolerance {tolerance}");
            assert!(merged.iter().enumerate().any(|(i, &r)| r != i as u32));
        }
    }

    #[test]
    fn negative_zero_welds_with_zero() {
        let p = vec![DVec3::new(-0.0, 0.0, 0.0), DVec3::X, DVec3::Y, DVec3::ZERO];
        let mesh = Mesh::new(p, vec![[0, 1, 2], [3, 2, 1]]).unwrap();
        assert_eq!(mesh.welded(0.0).positions.len(), 3);
    }

    #[test]
    fn tolerance_weld_merges_near_vertices_and_drops_collapsed_triangles() {
        let p = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::new(1e-9, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
        ];
        // Triangle 1 collapses onto vertex 0 (indices 0 and 3 merge).
        let mesh = Mesh::new(p, vec![[0, 1, 2], [0, 3, 2], [3, 1, 4]]).unwrap();
        let exact = mesh.welded(0.0);
        assert_eq!(exact.triangles.len(), 3);
        let loose = mesh.welded(1e-6);
        assert_eq!(loose.triangles, vec![[0, 1, 2], [0, 1, 3]]);
        assert_eq!(loose.positions.len(), 4);
    }

    #[test]
    fn unused_vertices_are_dropped_in_order() {
        let p = vec![DVec3::Z, DVec3::ZERO, DVec3::X, DVec3::Y];
        let mesh = Mesh::new(p, vec![[1, 2, 3]]).unwrap();
        let welded = mesh.welded(0.0);
        assert_eq!(welded.positions, vec![DVec3::ZERO, DVec3::X, DVec3::Y]);
        assert_eq!(welded.triangles, vec![[0, 1, 2]]);
    }
}

//! Changing a mesh's tessellation without changing its shape: decimation (meshoptimizer's
//! quadric edge collapse) and midpoint subdivision, for tessellation-robustness studies.

use super::Mesh;

impl Mesh {
    /// A copy with about `ratio` times the triangles (`0 < ratio <= 1`), by meshoptimizer's
    /// topology-preserving quadric edge collapse. Vertices keep their positions (collapses move
    /// onto existing vertices); unused vertices are dropped. The simplifier may stop above the
    /// target where topology forbids further collapses.
    pub fn decimated(&self, ratio: f64) -> Mesh {
        let ratio = ratio.clamp(0.0, 1.0);
        if ratio >= 1.0 || self.triangles.is_empty() {
            return self.clone();
        }
        let positions: Vec<[f32; 3]> = self
            .positions
            .iter()
            .map(|p| p.as_vec3().to_array())
            .collect();
        let indices: Vec<u32> = self.triangles.iter().flatten().copied().collect();
        let target = ((self.triangles.len() as f64 * ratio).round() as usize).max(1) * 3;
        let Ok(adapter) = meshopt::VertexDataAdapter::new(
            meshopt::typed_to_bytes(&positions),
            std::mem::size_of::<[f32; 3]>(),
            0,
        ) else {
            return self.clone();
        };
        // Error bound 1.0 (relative to the mesh extent) lets the triangle target decide.
        let kept = meshopt::simplify(
            &indices,
            &adapter,
            target,
            1.0,
            meshopt::SimplifyOptions::None,
            None,
        );
        let triangles: Vec<[u32; 3]> = kept.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
        Mesh {
            positions: self.positions.clone(),
            triangles,
        }
        .compacted()
    }

    /// A copy with every triangle split into four at its edge midpoints (shared edges share
    /// their midpoint, so a closed mesh stays closed). The surface is unchanged.
    pub fn subdivided(&self) -> Mesh {
        let mut positions = self.positions.clone();
        let mut midpoint: std::collections::HashMap<(u32, u32), u32> =
            std::collections::HashMap::with_capacity(self.triangles.len() * 3 / 2);
        let mut triangles = Vec::with_capacity(self.triangles.len() * 4);
        for &[a, b, c] in &self.triangles {
            let mut mid = |p: u32, q: u32| -> u32 {
                let key = (p.min(q), p.max(q));
                *midpoint.entry(key).or_insert_with(|| {
                    positions.push((positions[p as usize] + positions[q as usize]) * 0.5);
                    positions.len() as u32 - 1
                })
            };
            let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
            triangles.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
        }
        Mesh {
            positions,
            triangles,
        }
    }

    /// A copy with about `ratio` times the triangles: decimation below 1, midpoint subdivision
    /// (then decimation to the exact target) above 1.
    pub fn retessellated(&self, ratio: f64) -> Mesh {
        if ratio <= 1.0 {
            return self.decimated(ratio);
        }
        let target = self.triangles.len() as f64 * ratio;
        let mut mesh = self.clone();
        while (mesh.triangles.len() as f64) < target {
            mesh = mesh.subdivided();
        }
        mesh.decimated(target / mesh.triangles.len() as f64)
    }

    /// A copy without the vertices no triangle uses (order of the kept vertices preserved).
    pub fn compacted(&self) -> Mesh {
        let mut remap = vec![u32::MAX; self.positions.len()];
        let mut positions = Vec::new();
        for &i in self.triangles.iter().flatten() {
            if remap[i as usize] == u32::MAX {
                remap[i as usize] = 0;
            }
        }
        for (i, slot) in remap.iter_mut().enumerate() {
            if *slot == 0 {
                *slot = positions.len() as u32;
                positions.push(self.positions[i]);
            }
        }
        let triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|i| remap[i as usize]))
            .collect();
        Mesh {
            positions,
            triangles,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn decimation_and_subdivision_keep_the_shape_and_closedness() {
        let sphere = Mesh::uv_sphere(DVec3::ZERO, 1.0, 32, 64);
        let n = sphere.triangles.len();
        let half = sphere.decimated(0.5);
        assert!(
            half.triangles.len() <= n * 6 / 10,
            "{}",
            half.triangles.len()
        );
        assert!(half.stats().closed);
        assert!(
            (half.signed_volume() - sphere.signed_volume()).abs() / sphere.signed_volume() < 0.03
        );
        let fine = sphere.subdivided();
        assert_eq!(fine.triangles.len(), 4 * n);
        assert!(fine.stats().closed);
        assert!((fine.signed_volume() - sphere.signed_volume()).abs() < 1e-12);
        let double = sphere.retessellated(2.0);
        let ratio = double.triangles.len() as f64 / n as f64;
        assert!((1.8..=2.2).contains(&ratio), "{ratio}");
        assert!(double.stats().closed);
    }
}

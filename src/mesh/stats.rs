//! Summary statistics of a mesh: counts, topology, extent, area and volume.

use super::Mesh;
use serde::Serialize;

/// What a mesh is made of, for reports and for choosing how to treat it (e.g. whether the
/// inside of an open or non-manifold mesh needs a winding-number test).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeshStats {
    /// Number of vertex positions.
    pub vertices: usize,
    /// Number of triangles.
    pub triangles: usize,
    /// Connected components (triangles are connected when they share a vertex).
    pub components: usize,
    /// Components when triangles connect only across manifold edges (used by exactly two
    /// triangles): trimesh's "bodies", what refdata's README calls "parts"; at least
    /// `components`, more where pieces meet only at non-manifold edges or single vertices.
    pub manifold_components: usize,
    /// Undirected edges used by exactly one triangle (holes, open seams).
    pub boundary_edges: usize,
    /// Undirected edges used by more than two triangles.
    pub non_manifold_edges: usize,
    /// Whether the surface is closed: triangles, no boundary and no non-manifold edges.
    pub closed: bool,
    /// Minimum corner of the bounding box of the triangles' vertices, mesh units; `None` without
    /// triangles.
    pub bbox_min: Option<[f64; 3]>,
    /// Maximum corner of the bounding box, mesh units; `None` without triangles.
    pub bbox_max: Option<[f64; 3]>,
    /// Enclosed volume (positive when wound outward), mesh units cubed; only for a closed mesh.
    pub signed_volume: Option<f64>,
    /// Total triangle area, mesh units squared.
    pub surface_area: f64,
    /// Triangles with a repeated index or (near) zero area, see
    /// [`DEGENERATE_AREA_FRACTION`](super::DEGENERATE_AREA_FRACTION).
    pub degenerate_triangles: usize,
}

impl Mesh {
    /// Counts, topology and extent of the mesh; see [`MeshStats`].
    ///
    /// # Example
    /// ```
    /// use skelfit::mesh::Mesh;
    /// let stats = Mesh::cuboid(glam::DVec3::ZERO, glam::DVec3::ONE).stats();
    /// assert_eq!((stats.vertices, stats.triangles, stats.components), (8, 12, 1));
    /// assert!(stats.closed);
    /// assert!((stats.signed_volume.unwrap() - 1.0).abs() < 1e-12);
    /// ```
    pub fn stats(&self) -> MeshStats {
        let edges = self.half_edges();
        let mut boundary_edges = 0;
        let mut non_manifold_edges = 0;
        for group in Mesh::edge_groups(&edges) {
            match group.len() {
                1 => boundary_edges += 1,
                2 => {}
                _ => non_manifold_edges += 1,
            }
        }
        let closed = !self.triangles.is_empty() && boundary_edges == 0 && non_manifold_edges == 0;
        let bbox = self.bounding_box();
        MeshStats {
            vertices: self.positions.len(),
            triangles: self.triangles.len(),
            components: self.triangle_components().1,
            manifold_components: self.manifold_components().1,
            boundary_edges,
            non_manifold_edges,
            closed,
            bbox_min: bbox.map(|b| b.0.to_array()),
            bbox_max: bbox.map(|b| b.1.to_array()),
            signed_volume: closed.then(|| self.signed_volume()),
            surface_area: self.area(),
            degenerate_triangles: self.degenerate_triangles().iter().filter(|&&d| d).count(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn open_box_has_boundary_and_no_volume() {
        let mut cube = Mesh::cuboid(DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0));
        cube.triangles.truncate(10); // remove the +x face
        let stats = cube.stats();
        assert_eq!(stats.boundary_edges, 4);
        assert_eq!(stats.non_manifold_edges, 0);
        assert!(!stats.closed);
        assert_eq!(stats.signed_volume, None);
        assert!((stats.surface_area - (2.0 * (2.0 + 3.0 + 6.0) - 6.0)).abs() < 1e-12);
        assert_eq!(stats.bbox_max, Some([1.0, 2.0, 3.0]));
    }

    #[test]
    fn three_triangles_on_one_edge_are_non_manifold() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z, -DVec3::Y];
        let mesh = Mesh::new(p, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]).unwrap();
        let stats = mesh.stats();
        assert_eq!(stats.non_manifold_edges, 1);
        assert_eq!(stats.boundary_edges, 6);
        assert_eq!(stats.components, 1);
    }

    #[test]
    fn stats_serialize_to_json() {
        let stats = Mesh::cuboid(DVec3::ZERO, DVec3::ONE).stats();
        let json = serde_json::to_value(&stats).unwrap();
        assert_eq!(json["triangles"], 12);
        assert_eq!(json["bbox_max"], serde_json::json!([1.0, 1.0, 1.0]));
    }
}

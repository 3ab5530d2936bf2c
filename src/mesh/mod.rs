//! Triangle meshes: the [`Mesh`] type, loaders for OBJ, glTF/GLB, STL and PLY, welding of
//! coincident vertices and [`MeshStats`].
//!
//! Positions are kept in the input file's units and frame (f64). Every loader validates what it
//! read ([`Mesh::new`]): non-finite coordinates and out-of-range indices are errors, never a panic.
//! Loaders weld exactly coincident vertices ([`Mesh::welded`]), so seams that exporters split
//! for UVs or normals come back connected.
//!
//! - [`load`] dispatches on the extension to [`load_obj`], [`load_gltf`], [`load_stl`],
//!   [`load_ply`]; [`load_gltf_scene`] also returns a glTF skin's joints in the bind pose;
//!   [`load_model`] also keeps what the file held beyond the triangles ([`SourceModel`]: glTF
//!   primitives, UVs, materials, textures; OBJ UVs and MTL materials) for the output.
//! - [`Mesh::stats`] gives [`MeshStats`] (components, boundary and non-manifold edges, volume).
//! - [`slice_plane`] and [`slice_sphere`] cut a mesh into [`SliceLoop`]s with centroid,
//!   perimeter and [`PrincipalAxes`] (seed 004).
//! - [`Mesh::oriented_outward`] repairs inconsistent winding ([`OrientReport`]).

mod error;
mod gltf;
mod gltf_accessor;
mod gltf_buffers;
mod gltf_model;
mod gltf_nodes;
mod gltf_skin;
mod load;
mod model;
mod mtl;
mod obj;
mod obj_model;
mod orient;
mod ply;
mod retessellate;
mod shapes;
mod slice;
mod slice_plane;
mod slice_sphere;
mod stats;
mod stl;
mod topology;
mod weld;
mod winding;

pub use self::gltf::{load_gltf, load_gltf_scene, GltfScene};
pub use error::MeshError;
pub use load::{load, load_with_source_map};
pub use model::{load_model, ModelWarning, SourceInstance, SourceModel, SourcePrimitive};
pub use obj::load_obj;
pub use orient::{OrientReport, CLOSED_ISH_BOUNDARY_FRACTION, FLAT_VOLUME_FRACTION};
pub use ply::load_ply;
pub use slice::{PrincipalAxes, SliceLoop};
pub(crate) use slice_plane::contains as point_in_polygon;
pub use slice_plane::{slice_plane, slice_plane_outer, PlaneSlicer};
pub use slice_sphere::{slice_sphere, SphereSlicer};
pub use stats::MeshStats;
pub use stl::load_stl;
pub use topology::DEGENERATE_AREA_FRACTION;
pub(crate) use topology::{vertex_pieces, DisjointSets};
pub use winding::winding_number;

use glam::DVec3;

/// A triangle mesh: vertex positions and counter-clockwise (outward) triangles.
///
/// `positions` is `#V` points in mesh units; `triangles` is `#F` triples of indices into
/// `positions`. Meshes built through [`Mesh::new`] or a loader have finite coordinates and
/// in-range indices.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, mesh units, input frame.
    pub positions: Vec<DVec3>,
    /// Triangles as indices into `positions`; outward-facing when counter-clockwise.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// Builds a mesh after checking that every coordinate is finite and every index in range.
    ///
    /// # Errors
    /// [`MeshError::NonFinite`] for a NaN/inf coordinate, [`MeshError::IndexOutOfRange`] for a
    /// triangle index not below `positions.len()`.
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite {
                vertex,
                value: positions[vertex].to_array(),
            });
        }
        let count = positions.len();
        for (triangle, tri) in triangles.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= count) {
                return Err(MeshError::IndexOutOfRange {
                    triangle,
                    index: index as usize,
                    vertex_count: count,
                });
            }
        }
        Ok(Self {
            positions,
            triangles,
        })
    }

    /// Axis-aligned bounding box `(min, max)` of the vertices referenced by triangles, or `None`
    /// for a mesh without triangles.
    pub fn bounding_box(&self) -> Option<(DVec3, DVec3)> {
        let mut iter = self.triangles.iter().flatten();
        let first = self.positions[*iter.next()? as usize];
        let mut min = first;
        let mut max = first;
        for &i in iter {
            let p = self.positions[i as usize];
            min = min.min(p);
            max = max.max(p);
        }
        Some((min, max))
    }

    /// The three corner positions of triangle `t`.
    pub fn corners(&self, t: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// Total surface area, mesh units squared.
    pub fn area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.corners(t);
                (b - a).cross(c - a).length() * 0.5
            })
            .sum()
    }

    /// Signed volume enclosed by the triangles (divergence theorem), mesh units cubed. Positive
    /// for a closed outward-wound surface; meaningless for an open one.
    pub fn signed_volume(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.corners(t);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// Applies `f` to every position (e.g. a rigid transform for a rotation study).
    pub fn transformed(&self, f: impl Fn(DVec3) -> DVec3) -> Mesh {
        Mesh {
            positions: self.positions.iter().map(|&p| f(p)).collect(),
            triangles: self.triangles.clone(),
        }
    }
}

//! Loading a mesh file by extension, and the checks every loader shares.

use super::{Mesh, MeshError};
use glam::DVec3;
use std::path::{Path, PathBuf};

/// Reads a triangle mesh from `path`, choosing the reader by extension (case-insensitive):
/// `.obj` ([`load_obj`](super::load_obj)), `.gltf`/`.glb` ([`load_gltf`](super::load_gltf)),
/// `.stl` ([`load_stl`](super::load_stl)) or `.ply` ([`load_ply`](super::load_ply)).
///
/// The result is in the file's units and frame, validated ([`Mesh::new`]) and welded: vertices
/// at exactly the same position are merged ([`Mesh::welded`] with tolerance 0), so that seams
/// split for UVs or normals become connected.
///
/// # Errors
/// [`MeshError::UnknownFormat`] for another extension; otherwise whatever the format's loader
/// reports: [`MeshError::Io`], [`MeshError::Parse`], [`MeshError::NonFinite`],
/// [`MeshError::IndexOutOfRange`], [`MeshError::Empty`] or [`MeshError::Degenerate`].
///
/// # Example
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("tri.OBJ");
/// std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
/// let mesh = skelfit::mesh::load(&path).unwrap();
/// assert_eq!(mesh.triangles.len(), 1);
/// ```
pub fn load(path: &Path) -> Result<Mesh, MeshError> {
    load_with_source_map(path).map(|(mesh, _)| mesh)
}

/// Reads a mesh like [`load`], and says where each vertex of the file went: entry `i` is the
/// index in the returned mesh of the file's vertex `i`, `None` for a vertex no (non-degenerate)
/// face uses. Vertices welded together map to the same index. Use it to write per-vertex
/// results in the file's own vertex order (`skelfit label` does).
///
/// The file's vertices are, in order: OBJ `v` statements; PLY `vertex` elements; STL facet
/// corners (three per facet); glTF: the `POSITION`s of every triangle primitive, in the order
/// [`load_gltf`](super::load_gltf) visits the scene's nodes (a mesh instanced by two nodes
/// counts twice).
///
/// # Errors
/// As [`load`].
///
/// # Example
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("quad.obj");
/// // Vertex 3 is used by no face; the faces use the others in the order 4, 2, 1, 0.
/// std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 5 5 5\nv 0 1 0\nf 5 3 2\nf 5 2 1\n").unwrap();
/// let (mesh, source) = skelfit::mesh::load_with_source_map(&path).unwrap();
/// assert_eq!(source, vec![Some(0), Some(1), Some(2), None, Some(3)]);
/// assert_eq!(mesh.positions[3], glam::DVec3::new(0.0, 1.0, 0.0));
/// ```
pub fn load_with_source_map(path: &Path) -> Result<(Mesh, Vec<Option<u32>>), MeshError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => super::obj::read_obj(path),
        Some("gltf") | Some("glb") => {
            super::load_gltf_scene(path).map(|scene| (scene.mesh, scene.source_vertices))
        }
        Some("stl") => super::stl::read_stl(path),
        Some("ply") => super::ply::read_ply(path),
        _ => Err(MeshError::UnknownFormat {
            path: path.to_path_buf(),
        }),
    }
}

/// Reads the whole file; an empty file is [`MeshError::Empty`].
pub(super) fn read_bytes(path: &Path) -> Result<Vec<u8>, MeshError> {
    let bytes = std::fs::read(path).map_err(|cause| MeshError::Io {
        path: path.to_path_buf(),
        cause,
    })?;
    if bytes.is_empty() {
        return Err(MeshError::Empty {
            detail: format!(" ({} is an empty file)", path.display()),
        });
    }
    Ok(bytes)
}

/// A [`MeshError::Parse`] for `path` in `format`.
pub(super) fn parse_error(path: &Path, format: &'static str, message: impl ToString) -> MeshError {
    MeshError::Parse {
        path: PathBuf::from(path),
        format,
        message: message.to_string(),
    }
}

/// Runs a third-party parser, turning a panic on malformed input into [`MeshError::Parse`].
///
/// Last resort only: the loaders validate sizes and indices before calling parsers, so this
/// should never trigger; it keeps the "no panic on user input" promise if a parser has a bug.
pub(super) fn guarded<T>(
    path: &Path,
    format: &'static str,
    parse: impl FnOnce() -> Result<T, MeshError>,
) -> Result<T, MeshError> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(parse)).unwrap_or_else(|_| {
        Err(parse_error(
            path,
            format,
            "the reader failed on malformed data; re-export the file",
        ))
    })
}

/// The common tail of every loader: validates, rejects meshes without triangles, welds
/// exactly coincident vertices and rejects meshes whose triangles all have zero area.
///
/// `detail` is appended to the [`MeshError::Empty`] message (e.g. what the file held instead).
///
/// Also returns, for every input position, the index of the welded vertex it became
/// ([`Mesh::welded_with_map`]).
pub(super) fn finish(
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    detail: &str,
) -> Result<(Mesh, Vec<Option<u32>>), MeshError> {
    let raw = Mesh::new(positions, triangles)?;
    if raw.triangles.is_empty() {
        return Err(MeshError::Empty {
            detail: detail.to_string(),
        });
    }
    let (mesh, map) = raw.welded_with_map(0.0);
    let degenerate = mesh.degenerate_triangles();
    if mesh.triangles.is_empty() || degenerate.iter().all(|&d| d) {
        return Err(MeshError::Degenerate {
            triangles: raw.triangles.len(),
        });
    }
    Ok((mesh, map))
}

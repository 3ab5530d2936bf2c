use std::path::PathBuf;
use thiserror::Error;

/// Errors from reading or validating a mesh. Messages name the problem and what to do.
#[derive(Debug, Error)]
pub enum MeshError {
    /// The file could not be opened or read.
    #[error("cannot read {path}: {cause}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying I/O error (part of the message, hence not a `source()`, which would
        /// print it twice in an error chain).
        cause: std::io::Error,
    },
    /// The file extension is not one skelfit reads.
    #[error("unknown mesh format for {path}: expected .obj, .gltf, .glb, .stl or .ply")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// The file is not valid in its format.
    #[error("{path} is not a valid {format} file: {message}")]
    Parse {
        /// The file.
        path: PathBuf,
        /// The format that was expected (obj, gltf, stl, ply).
        format: &'static str,
        /// What the parser reported.
        message: String,
    },
    /// The mesh has no triangles.
    #[error("the mesh has no triangles{detail}: export a triangle or polygon surface")]
    Empty {
        /// Extra context (e.g. " (the file holds only points or lines)"), may be empty.
        detail: String,
    },
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate {value:?}: fix or remove it in the modelling tool")]
    NonFinite {
        /// Index of the offending vertex.
        vertex: usize,
        /// Its coordinates.
        value: [f64; 3],
    },
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {index} counting from 0 (vertex {} counting from 1, as OBJ files do) but the mesh has only {vertex_count} vertices: the file is corrupt", index.saturating_add(1))]
    IndexOutOfRange {
        /// Index of the offending triangle.
        triangle: usize,
        /// The out-of-range vertex index.
        index: usize,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// Every triangle has zero area, so the mesh encloses nothing.
    #[error("all {triangles} triangles have zero area: the mesh is degenerate")]
    Degenerate {
        /// Number of triangles.
        triangles: usize,
    },
}

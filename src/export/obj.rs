//! Wavefront OBJ of a (posed) mesh.

use super::{io_error, ExportError};
use crate::mesh::Mesh;
use std::fmt::Write as _;
use std::path::Path;

/// The mesh as OBJ text: one `v x y z` line per vertex, then one `f a b c` line per triangle
/// (1-based). Coordinates are printed in the shortest form that reads back to the same `f64`,
/// so the same mesh gives the same text.
pub fn obj_text(mesh: &Mesh) -> String {
    let mut out = String::from("# skelfit\n");
    for p in &mesh.positions {
        let [x, y, z] = p.to_array().map(|v| if v == 0.0 { 0.0 } else { v });
        let _ = writeln!(out, "v {x:?} {y:?} {z:?}");
    }
    for [a, b, c] in &mesh.triangles {
        let _ = writeln!(out, "f {} {} {}", a + 1, b + 1, c + 1);
    }
    out
}

/// Writes [`obj_text`] to `path` atomically.
///
/// # Errors
/// [`ExportError::Io`] when the file cannot be written.
pub fn write_obj(path: &Path, mesh: &Mesh) -> Result<(), ExportError> {
    crate::output::write_atomic(path, obj_text(mesh).as_bytes())
        .map_err(|cause| io_error(path, cause))
}

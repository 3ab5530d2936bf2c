//! Wavefront OBJ reading (through `tobj`).

use super::load::{finish, guarded, parse_error, read_bytes};
use super::{Mesh, MeshError};
use glam::DVec3;
use std::path::Path;

const FORMAT: &str = "obj";

/// Reads a Wavefront OBJ file: all objects and groups merged into one mesh, polygons
/// triangulated as fans, points and lines ignored, materials not read. Welded and validated
/// like every loader (see [`load`](super::load)).
///
/// # Errors
/// [`MeshError::Io`] if the file cannot be read; [`MeshError::Empty`] for an empty file or one
/// without faces; [`MeshError::Parse`] for bytes that are not OBJ text;
/// [`MeshError::IndexOutOfRange`] for a face vertex index that does not exist (the triangle
/// number counts the triangles the faces before it produce); [`MeshError::NonFinite`] for a
/// `nan`/`inf` coordinate of a vertex some face uses (the vertex number counts vertices in
/// order of first use by a face); [`MeshError::Degenerate`] when every face has zero area.
pub fn load_obj(path: &Path) -> Result<Mesh, MeshError> {
    let bytes = read_bytes(path)?;
    let text = std::str::from_utf8(&bytes)
        .map_err(|e| parse_error(path, FORMAT, format!("not OBJ text ({e})")))?;
    let scan = scan(path, text)?;
    if scan.vertex_lines == 0 && scan.faces == 0 {
        return Err(parse_error(
            path,
            FORMAT,
            "no vertex (v) or face (f) statements found",
        ));
    }
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let models = guarded(path, FORMAT, || {
        let mut reader = std::io::Cursor::new(text.as_bytes());
        tobj::load_obj_buf(&mut reader, &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .map(|(models, _materials)| models)
        .map_err(|e| parse_error(path, FORMAT, e))
    })?;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for model in &models {
        let offset = positions.len() as u32;
        positions.extend(
            model
                .mesh
                .positions
                .chunks_exact(3)
                .map(|p| DVec3::new(p[0].into(), p[1].into(), p[2].into())),
        );
        triangles.extend(
            model
                .mesh
                .indices
                .chunks_exact(3)
                .map(|t| [t[0] + offset, t[1] + offset, t[2] + offset]),
        );
    }
    finish(positions, triangles, " (the OBJ file has no faces)")
}

/// What a quick pass over the OBJ text found.
struct Scan {
    vertex_lines: usize,
    faces: usize,
}

/// Counts vertices and faces and checks every face index before `tobj` sees it (so that no
/// index can overflow its arithmetic), resolving relative (negative) indices as `tobj` does:
/// against the elements defined so far.
fn scan(path: &Path, text: &str) -> Result<Scan, MeshError> {
    let mut counts = [0usize; 3]; // v, vt, vn
    let mut faces = 0usize;
    let mut triangles_before = 0usize;
    for (line_number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => counts[0] += 1,
            Some("vt") => counts[1] += 1,
            Some("vn") => counts[2] += 1,
            Some(keyword @ ("f" | "l")) => {
                let corners: Vec<&str> = words.collect();
                for corner in &corners {
                    for (slot, field) in corner.split('/').enumerate().take(3) {
                        let Ok(index) = field.parse::<i64>() else {
                            continue; // empty (v//vn) or a syntax error tobj reports
                        };
                        let count = counts[slot] as i64;
                        let resolved = if index < 0 { count + index } else { index - 1 };
                        if slot == 0 && keyword == "f" && resolved >= count {
                            return Err(MeshError::IndexOutOfRange {
                                triangle: triangles_before,
                                index: resolved as usize,
                                vertex_count: counts[0],
                            });
                        }
                        if resolved < 0 || resolved >= count {
                            return Err(parse_error(
                                path,
                                FORMAT,
                                format!(
                                    "line {}: index {index} in {corner:?} does not exist \
                                     (there are {count} so far; OBJ indices start at 1)",
                                    line_number + 1
                                ),
                            ));
                        }
                    }
                }
                if keyword == "f" {
                    faces += 1;
                    triangles_before += corners.len().saturating_sub(2);
                }
            }
            _ => {}
        }
    }
    Ok(Scan {
        vertex_lines: counts[0],
        faces,
    })
}

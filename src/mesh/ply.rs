//! PLY reading (through `ply-rs-bw`), ASCII and binary.

use super::load::{finish, guarded, parse_error, read_bytes};
use super::{Mesh, MeshError};
use glam::DVec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Property};
use std::path::Path;

const FORMAT: &str = "ply";

/// Reads a PLY file (ASCII, binary little- or big-endian): the `x`, `y`, `z` properties of the
/// `vertex` element and the `vertex_indices` (or `vertex_index`) lists of the `face` element;
/// polygons are triangulated as fans, faces with fewer than three corners ignored. Other
/// elements and properties (normals, colours, edges) are ignored. Welded and validated like
/// every loader (see [`load`](super::load)).
///
/// # Errors
/// [`MeshError::Io`], [`MeshError::Empty`] (empty file or no faces), [`MeshError::Parse`] (not
/// PLY, a missing `vertex` element or coordinate, a negative index),
/// [`MeshError::NonFinite`], [`MeshError::IndexOutOfRange`], [`MeshError::Degenerate`].
pub fn load_ply(path: &Path) -> Result<Mesh, MeshError> {
    read_ply(path).map(|(mesh, _)| mesh)
}

/// [`load_ply`] with the source map of [`load_with_source_map`](super::load_with_source_map).
pub(super) fn read_ply(path: &Path) -> Result<(Mesh, Vec<Option<u32>>), MeshError> {
    let bytes = read_bytes(path)?;
    let ply = guarded(path, FORMAT, || {
        Parser::<DefaultElement>::new()
            .read_ply(&mut std::io::Cursor::new(&bytes))
            .map_err(|e| parse_error(path, FORMAT, ply_message(&e)))
    })?;
    let vertices = ply
        .payload
        .get("vertex")
        .ok_or_else(|| parse_error(path, FORMAT, "there is no `vertex` element"))?;
    let mut positions = Vec::with_capacity(vertices.len());
    for (index, vertex) in vertices.iter().enumerate() {
        let coordinate = |name: &str| {
            vertex.get(name).and_then(scalar).ok_or_else(|| {
                parse_error(
                    path,
                    FORMAT,
                    format!("vertex {index} has no numeric `{name}` property"),
                )
            })
        };
        positions.push(DVec3::new(
            coordinate("x")?,
            coordinate("y")?,
            coordinate("z")?,
        ));
    }
    let mut triangles = Vec::new();
    for (index, face) in ply.payload.get("face").into_iter().flatten().enumerate() {
        let list = face
            .get("vertex_indices")
            .or_else(|| face.get("vertex_index"))
            .ok_or_else(|| {
                parse_error(
                    path,
                    FORMAT,
                    format!("face {index} has no `vertex_indices` list"),
                )
            })?;
        let corners = index_list(list).ok_or_else(|| {
            parse_error(
                path,
                FORMAT,
                format!("face {index}: `vertex_indices` must be a list of integers"),
            )
        })?;
        let mut corners_u32 = Vec::with_capacity(corners.len());
        for corner in corners {
            let corner = u32::try_from(corner).map_err(|_| {
                if corner < 0 {
                    parse_error(
                        path,
                        FORMAT,
                        format!("face {index}: negative index {corner}"),
                    )
                } else {
                    MeshError::IndexOutOfRange {
                        triangle: triangles.len(),
                        index: corner as usize,
                        vertex_count: positions.len(),
                    }
                }
            })?;
            corners_u32.push(corner);
        }
        for k in 2..corners_u32.len() {
            triangles.push([corners_u32[0], corners_u32[k - 1], corners_u32[k]]);
        }
    }
    finish(positions, triangles, " (the PLY file has no faces)")
}

/// A numeric scalar property as `f64`.
fn scalar(property: &Property) -> Option<f64> {
    Some(match *property {
        Property::Char(v) => v.into(),
        Property::UChar(v) => v.into(),
        Property::Short(v) => v.into(),
        Property::UShort(v) => v.into(),
        Property::Int(v) => v.into(),
        Property::UInt(v) => v.into(),
        Property::Float(v) => v.into(),
        Property::Double(v) => v,
        _ => return None,
    })
}

/// An integer list property as `i64`s.
fn index_list(property: &Property) -> Option<Vec<i64>> {
    fn widen<T: Copy + Into<i64>>(values: &[T]) -> Vec<i64> {
        values.iter().map(|&v| v.into()).collect()
    }
    Some(match property {
        Property::ListChar(v) => widen(v),
        Property::ListUChar(v) => widen(v),
        Property::ListShort(v) => widen(v),
        Property::ListUShort(v) => widen(v),
        Property::ListInt(v) => widen(v),
        Property::ListUInt(v) => widen(v),
        _ => return None,
    })
}

/// A one-line message for a `ply-rs` error: its line number, its summary and the offending
/// text, without the nested grammar dumps (`ParseError { location: ... }`) it carries.
fn ply_message(error: &ply_rs_bw::parser::ParseError) -> String {
    let text = error.to_string();
    let summary = text.lines().next().unwrap_or_default();
    let summary = match summary.split_once(": ") {
        Some((prefix, rest)) if prefix.starts_with("Line ") => rest,
        _ => summary,
    };
    let summary = summary.trim_end_matches('.');
    let mut summary = summary.to_string();
    if let Some(first) = summary.get(..1) {
        let lower = first.to_lowercase();
        summary.replace_range(..1, &lower);
    }
    let offending = text
        .split("String: '")
        .nth(1)
        .and_then(|s| s.split('\'').next())
        .map(str::trim)
        .filter(|s| !s.is_empty());
    let mut message = match error.line() {
        Some(line) => format!("line {line}: {summary}"),
        None => summary,
    };
    if let Some(offending) = offending {
        let shown: String = offending.chars().take(80).collect();
        message += &format!(" ({shown:?})");
    }
    message
}

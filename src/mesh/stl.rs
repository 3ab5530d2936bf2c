//! STL reading (through `stl_io`), ASCII and binary.

use super::load::{finish, guarded, parse_error, read_bytes};
use super::{Mesh, MeshError};
use glam::DVec3;
use std::io::Cursor;
use std::path::Path;

const FORMAT: &str = "stl";
/// Binary STL: 80-byte header and a little-endian `u32` triangle count.
const BINARY_HEADER_BYTES: usize = 84;
/// Binary STL: normal, three corners (12 `f32`) and a `u16` attribute per triangle.
const BINARY_TRIANGLE_BYTES: usize = 50;

/// Reads an ASCII or binary STL file. STL stores every triangle with its own corners, so the
/// corners are welded exactly (see [`load`](super::load)) to recover the connectivity.
///
/// A file that starts with `solid ` is read as ASCII; if that fails but its size fits the
/// binary layout (some exporters begin binary headers with `solid`), it is read as binary.
///
/// # Errors
/// [`MeshError::Io`], [`MeshError::Empty`] (empty file or no facets), [`MeshError::Parse`]
/// (neither valid ASCII nor binary STL, a binary triangle count that does not match the file
/// size, or a `nan`/`inf` in ASCII STL, which the parser rejects), [`MeshError::NonFinite`]
/// (a NaN/inf coordinate in binary STL), [`MeshError::Degenerate`].
pub fn load_stl(path: &Path) -> Result<Mesh, MeshError> {
    read_stl(path).map(|(mesh, _)| mesh)
}

/// [`load_stl`] with the source map of [`load_with_source_map`](super::load_with_source_map).
pub(super) fn read_stl(path: &Path) -> Result<(Mesh, Vec<Option<u32>>), MeshError> {
    let bytes = read_bytes(path)?;
    let binary_size_fits = binary_triangle_count(&bytes).is_some();
    let corners = if bytes.starts_with(b"solid ") {
        match read_triangles(path, &bytes) {
            Ok(corners) => corners,
            Err(_) if binary_size_fits => read_binary(path, &bytes)?,
            Err(error) => return Err(error),
        }
    } else {
        read_binary(path, &bytes)?
    };
    let triangles = (0..corners.len() as u32 / 3)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    finish(corners, triangles, " (the STL file has no facets)")
}

/// The triangle count of a binary STL whose size matches its header, else `None`.
/// Trailing bytes after the last triangle are tolerated.
fn binary_triangle_count(bytes: &[u8]) -> Option<usize> {
    let count_bytes: [u8; 4] = bytes
        .get(BINARY_HEADER_BYTES - 4..BINARY_HEADER_BYTES)?
        .try_into()
        .ok()?;
    let count = u32::from_le_bytes(count_bytes) as usize;
    let needed = count
        .checked_mul(BINARY_TRIANGLE_BYTES)?
        .checked_add(BINARY_HEADER_BYTES)?;
    (bytes.len() >= needed).then_some(count)
}

/// Reads a binary STL after checking that its size matches its triangle count.
fn read_binary(path: &Path, bytes: &[u8]) -> Result<Vec<DVec3>, MeshError> {
    if bytes.len() < BINARY_HEADER_BYTES {
        return Err(parse_error(
            path,
            FORMAT,
            format!(
                "{} bytes is too short for binary STL and it does not start with \"solid \"",
                bytes.len()
            ),
        ));
    }
    let Some(count) = binary_triangle_count(bytes) else {
        return Err(parse_error(
            path,
            FORMAT,
            format!(
                "the binary header announces more triangles than the {} bytes hold \
                 (the file is truncated or not STL)",
                bytes.len()
            ),
        ));
    };
    let end = BINARY_HEADER_BYTES + count * BINARY_TRIANGLE_BYTES;
    if bytes.starts_with(b"solid ") {
        // stl_io would take it for ASCII again; the binary layout is simple enough to decode.
        return Ok(decode_binary(&bytes[BINARY_HEADER_BYTES..end]));
    }
    read_triangles(path, &bytes[..end])
}

/// The corners of binary STL triangle records (`records.len()` a multiple of 50).
fn decode_binary(records: &[u8]) -> Vec<DVec3> {
    let float = |b: &[u8], at: usize| f32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]);
    records
        .chunks_exact(BINARY_TRIANGLE_BYTES)
        .flat_map(|r| {
            // Bytes 0..12 hold the normal, 12..48 the corners, 48..50 an attribute.
            (0..3).map(move |k| {
                let at = 12 + 12 * k;
                DVec3::new(
                    float(r, at).into(),
                    float(r, at + 4).into(),
                    float(r, at + 8).into(),
                )
            })
        })
        .collect()
}

/// All triangle corners, three per facet, through `stl_io` (which detects ASCII or binary).
fn read_triangles(path: &Path, bytes: &[u8]) -> Result<Vec<DVec3>, MeshError> {
    guarded(path, FORMAT, || {
        let mut cursor = Cursor::new(bytes);
        let reader =
            stl_io::create_stl_reader(&mut cursor).map_err(|e| parse_error(path, FORMAT, e))?;
        let mut corners = Vec::new();
        for (index, triangle) in reader.enumerate() {
            let triangle =
                triangle.map_err(|e| parse_error(path, FORMAT, format!("facet {index}: {e}")))?;
            corners.extend(
                triangle
                    .vertices
                    .iter()
                    .map(|v| DVec3::new(v[0].into(), v[1].into(), v[2].into())),
            );
        }
        Ok(corners)
    })
}

//! Wavefront OBJ reading: a small strict parser, coordinates in f64.

use super::load::{finish, parse_error, read_bytes};
use super::{Mesh, MeshError};
use crate::math::{fast_map, FastMap};
use glam::DVec3;
use std::path::Path;

const FORMAT: &str = "obj";

/// Reads a Wavefront OBJ file: all objects and groups merged into one mesh, polygons
/// triangulated as fans, points and lines ignored, materials not read (see
/// [`load_model`](super::load_model) for UVs and materials). Coordinates are read
/// as f64 (a figure far from the origin keeps its detail); `v x y z w` is divided by `w`. Welded and validated
/// like every loader (see [`load`](super::load)). The mesh keeps the file's vertex order
/// (less the vertices no face uses and those welded into an earlier one), so vertex `i` of a
/// file whose vertices all belong to faces and are distinct is vertex `i` of the mesh.
///
/// # Errors
/// [`MeshError::Io`] if the file cannot be read; [`MeshError::Empty`] for an empty file or one
/// without faces; [`MeshError::Parse`] for bytes that are not OBJ text or a malformed `v`/`f`
/// statement (the message gives the line number), `w = 0`;
/// [`MeshError::IndexOutOfRange`] for a face vertex index that does not exist (the triangle
/// number counts the triangles the faces before it produce); [`MeshError::NonFinite`] for a
/// `nan`/`inf` coordinate of a vertex some face uses (the vertex number is its 0-based
/// position among the file's `v` statements); [`MeshError::Degenerate`] when every face has
/// zero area.
pub fn load_obj(path: &Path) -> Result<Mesh, MeshError> {
    read_obj(path).map(|(mesh, _)| mesh)
}

/// [`load_obj`] with the source map of [`load_with_source_map`](super::load_with_source_map).
pub(super) fn read_obj(path: &Path) -> Result<(Mesh, Vec<Option<u32>>), MeshError> {
    welded(path, &parse_obj(path)?)
}

/// What the OBJ file at `path` says, not yet welded ([`welded`]).
pub(super) fn parse_obj(path: &Path) -> Result<ParsedObj, MeshError> {
    let bytes = read_bytes(path)?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        parse_error(
            path,
            FORMAT,
            format!("line {line}: not OBJ text (invalid UTF-8)"),
        )
    })?;
    parse(text)
        .map_err(|(line, message)| parse_error(path, FORMAT, format!("line {line}: {message}")))
}

/// The welded mesh of the parsed file and the map of its `v` statements onto it.
pub(super) fn welded(
    path: &Path,
    parsed: &ParsedObj,
) -> Result<(Mesh, Vec<Option<u32>>), MeshError> {
    let coordinates = &parsed.coordinates;
    let corners = &parsed.corners;
    if let Some(MeshError::IndexOutOfRange {
        triangle,
        index,
        vertex_count,
    }) = parsed.out_of_range
    {
        return Err(MeshError::IndexOutOfRange {
            triangle,
            index,
            vertex_count,
        });
    }
    if coordinates.is_empty() && corners.is_empty() {
        return Err(parse_error(
            path,
            FORMAT,
            "no vertex (v) or face (f) statements found",
        ));
    }
    // Raw vertices: the file vertices some face uses, in file order.
    let mut used = vec![false; coordinates.len()];
    for &c in corners {
        used[c as usize] = true;
    }
    let mut raw_of_file = vec![u32::MAX; used.len()];
    let mut file_of_raw = Vec::new();
    let mut positions = Vec::new();
    for (i, &u) in used.iter().enumerate() {
        if u {
            raw_of_file[i] = positions.len() as u32;
            file_of_raw.push(i);
            positions.push(coordinates[i]);
        }
    }
    let triangles = corners
        .chunks_exact(3)
        .map(|t| [0, 1, 2].map(|k| raw_of_file[t[k] as usize]))
        .collect();
    let (mesh, raw_map) = match finish(positions, triangles, " (the OBJ file has no faces)") {
        Ok(done) => done,
        Err(MeshError::NonFinite { vertex, value }) => {
            return Err(MeshError::NonFinite {
                vertex: file_of_raw.get(vertex).copied().unwrap_or(vertex),
                value,
            })
        }
        Err(e) => return Err(e),
    };
    // A file vertex no face uses maps to the mesh vertex at exactly its position, if any.
    let mut at_position: FastMap<[u64; 3], u32> = fast_map(mesh.positions.len());
    at_position.extend(
        mesh.positions
            .iter()
            .enumerate()
            .map(|(i, p)| (exact_key(*p), i as u32)),
    );
    let source = (0..used.len())
        .map(|i| match raw_of_file[i] {
            u32::MAX => at_position.get(&exact_key(coordinates[i])).copied(),
            raw => raw_map[raw as usize],
        })
        .collect();
    Ok((mesh, source))
}

/// Bit pattern of a position with `-0.0` normalised to `0.0`.
fn exact_key(p: DVec3) -> [u64; 3] {
    (p + DVec3::ZERO).to_array().map(f64::to_bits)
}

/// What [`parse`] read.
#[derive(Default)]
pub(super) struct ParsedObj {
    /// Every `v` statement's position (divided by its `w`), f64.
    pub coordinates: Vec<DVec3>,
    /// File vertex (0-based) of every triangle corner, three per triangle.
    pub corners: Vec<u32>,
    /// The first face index beyond the vertices defined before it, as a mesh error (the
    /// triangle number counts the triangles of the faces before it).
    out_of_range: Option<MeshError>,
    /// Every `vt` statement's `u v` (a missing or unreadable value is 0).
    pub uvs: Vec<[f64; 2]>,
    /// Every `vn` statement's vector (unreadable values are 0).
    pub normals: Vec<DVec3>,
    /// Per corner: its `vt` (0-based), `u32::MAX` for none.
    pub corner_uvs: Vec<u32>,
    /// Per corner: its `vn` (0-based), `u32::MAX` for none.
    pub corner_normals: Vec<u32>,
    /// Per triangle: index into `materials` of the `usemtl` in force, `u32::MAX` for none.
    pub triangle_materials: Vec<u32>,
    /// Material names in order of first `usemtl`.
    pub materials: Vec<String>,
    /// The `mtllib` file names, in order.
    pub libraries: Vec<String>,
    /// The material in force.
    current: Option<u32>,
}

/// Parses OBJ text: `v x y z [w]` (or `v x y z r g b`), and `f` faces of `v`, `v/vt`,
/// `v//vn` or `v/vt/vn` corners with 1-based or negative (relative) indices, triangulated as
/// fans. Every other statement (`vt`, `vn`, `l`, `p`, `g`, `o`, `s`, `usemtl`, ...) is
/// skipped; `#` starts a comment and a `\` at the end of a line continues it.
///
/// # Errors
/// `(line, message)` (line 1-based) for a malformed `v` or `f` statement.
fn parse(text: &str) -> Result<ParsedObj, (usize, String)> {
    let mut parsed = ParsedObj::default();
    let mut counts = [0usize; 3]; // v, vt, vn
    let mut pending = String::new();
    let mut pending_line = 0;
    // The corners of the face being read, reused from face to face.
    let mut face = Vec::new();
    for (k, raw_line) in text.lines().enumerate() {
        let line_number = k + 1;
        let content = raw_line.split('#').next().unwrap_or("");
        if let Some(continued) = content.trim_end().strip_suffix('\\') {
            if pending.is_empty() {
                pending_line = line_number;
            }
            pending.push_str(continued);
            pending.push(' ');
            continue;
        }
        let (line, line_number) = if pending.is_empty() {
            (content, line_number)
        } else {
            pending.push_str(content);
            (pending.as_str(), pending_line)
        };
        statement(line, &mut counts, &mut parsed, &mut face).map_err(|m| (line_number, m))?;
        pending.clear();
    }
    if !pending.is_empty() {
        let line = std::mem::take(&mut pending);
        statement(&line, &mut counts, &mut parsed, &mut face).map_err(|m| (pending_line, m))?;
    }
    Ok(parsed)
}

/// Reads one (comment-free, joined) statement into `parsed`; `face` is scratch space for the
/// corners of an `f` statement.
fn statement(
    line: &str,
    counts: &mut [usize; 3],
    parsed: &mut ParsedObj,
    face: &mut Vec<[u32; 3]>,
) -> Result<(), String> {
    let mut words = line.split_whitespace();
    match words.next() {
        Some("v") => {
            // x y z, then w or r g b: at most six values are read, the rest only counted.
            let mut values = [""; 6];
            let mut count = 0;
            for word in words {
                if let Some(slot) = values.get_mut(count) {
                    *slot = word;
                }
                count += 1;
            }
            let number = |word: &str| {
                word.parse::<f64>()
                    .map_err(|_| format!("vertex coordinate {word:?} is not a number"))
            };
            if count < 3 {
                return Err(format!("a vertex needs x, y and z, found {count} values"));
            }
            let mut p = DVec3::new(number(values[0])?, number(values[1])?, number(values[2])?);
            match count {
                3 | 6 => {} // plain, or with an RGB colour (ignored)
                4 => {
                    let w = number(values[3])?;
                    if w == 0.0 || !w.is_finite() {
                        return Err(format!(
                            "vertex weight w = {w}: a position needs a finite, nonzero w"
                        ));
                    }
                    if w != 1.0 {
                        p /= w;
                    }
                }
                n => {
                    return Err(format!(
                        "a vertex has x, y, z and then w or r g b, found {n} values"
                    ))
                }
            }
            counts[0] += 1;
            parsed.coordinates.push(p);
        }
        Some("vt") => {
            counts[1] += 1;
            let mut values = words.map(|w| w.parse::<f64>().unwrap_or(0.0));
            let u = values.next().unwrap_or(0.0);
            let v = values.next().unwrap_or(0.0);
            parsed.uvs.push([u, v]);
        }
        Some("vn") => {
            counts[2] += 1;
            let mut values = words.map(|w| w.parse::<f64>().unwrap_or(0.0));
            let mut next = || values.next().unwrap_or(0.0);
            parsed.normals.push(DVec3::new(next(), next(), next()));
        }
        Some("usemtl") => {
            let name = words.collect::<Vec<_>>().join(" ");
            let index = match parsed.materials.iter().position(|m| *m == name) {
                Some(i) => i,
                None => {
                    parsed.materials.push(name);
                    parsed.materials.len() - 1
                }
            };
            parsed.current = Some(index as u32);
        }
        Some("mtllib") => {
            parsed.libraries.push(words.collect::<Vec<_>>().join(" "));
        }
        Some("f") => {
            face.clear();
            for corner in words {
                face.push(corner_vertex(corner, counts, parsed)?);
            }
            if face.len() >= 3 {
                for i in 1..face.len() - 1 {
                    for [v, vt, vn] in [face[0], face[i], face[i + 1]] {
                        parsed.corners.push(v);
                        parsed.corner_uvs.push(vt);
                        parsed.corner_normals.push(vn);
                    }
                    parsed
                        .triangle_materials
                        .push(parsed.current.unwrap_or(u32::MAX));
                }
            }
        }
        _ => {}
    }
    Ok(())
}

/// The file vertex, texture coordinate and normal (0-based, `u32::MAX` for none) of one face
/// corner `v[/vt[/vn]]`; a vertex index beyond those defined so far is recorded in
/// `parsed.out_of_range` (and vertex 0 used meanwhile).
fn corner_vertex(
    corner: &str,
    counts: &[usize; 3],
    parsed: &mut ParsedObj,
) -> Result<[u32; 3], String> {
    const WHAT: [&str; 3] = ["vertex", "texture coordinate", "normal"];
    let mut vertex = [0u32, u32::MAX, u32::MAX];
    let mut fields = [""; 3];
    let mut count = 0;
    for field in corner.split('/') {
        let Some(slot) = fields.get_mut(count) else {
            return Err(format!("face corner {corner:?} has more than v/vt/vn"));
        };
        *slot = field;
        count += 1;
    }
    for (slot, field) in fields[..count].iter().enumerate() {
        if field.is_empty() && slot > 0 {
            continue; // v//vn or v/vt/
        }
        let index: i64 = field
            .parse()
            .map_err(|_| format!("face corner {corner:?}: {field:?} is not an index"))?;
        let count = counts[slot] as i64;
        let resolved = if index < 0 { count + index } else { index - 1 };
        if index == 0 || resolved < 0 || (slot > 0 && resolved >= count) {
            return Err(format!(
                "{} index {index} in {corner:?} does not exist (there are {count} so far; OBJ \
                 indices start at 1, negative ones count back from the last)",
                WHAT[slot]
            ));
        }
        if slot == 0 {
            if resolved >= count || resolved > i64::from(u32::MAX) {
                if parsed.out_of_range.is_none() {
                    parsed.out_of_range = Some(MeshError::IndexOutOfRange {
                        triangle: parsed.corners.len() / 3,
                        index: usize::try_from(resolved).unwrap_or(usize::MAX),
                        vertex_count: counts[0],
                    });
                }
            } else {
                vertex[0] = resolved as u32;
            }
        } else {
            vertex[slot] = resolved as u32;
        }
    }
    Ok(vertex)
}

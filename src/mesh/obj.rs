//! Wavefront OBJ reading (through `tobj`).

use super::load::{finish, guarded, parse_error, read_bytes};
use super::{Mesh, MeshError};
use glam::DVec3;
use std::collections::HashMap;
use std::path::Path;

const FORMAT: &str = "obj";

/// Reads a Wavefront OBJ file: all objects and groups merged into one mesh, polygons
/// triangulated as fans, points and lines ignored, materials not read. Welded and validated
/// like every loader (see [`load`](super::load)). The mesh keeps the file's vertex order
/// (less the vertices no face uses and those welded into an earlier one), so vertex `i` of a
/// file whose vertices all belong to faces and are distinct is vertex `i` of the mesh.
///
/// # Errors
/// [`MeshError::Io`] if the file cannot be read; [`MeshError::Empty`] for an empty file or one
/// without faces; [`MeshError::Parse`] for bytes that are not OBJ text;
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
    // `tobj` keeps each object's vertices in the order its faces first use them; put them
    // back in the file's order. A vertex is found among the file's `v` statements by its
    // exact coordinates as `tobj` parsed them (the same text parsed to the same float type).
    let like = models.first().map_or(&[][..], |m| &m.mesh.positions[..]);
    let coordinates: Vec<[u64; 3]> = scan
        .coordinates
        .iter()
        .map(|c| c.map(|word| parsed_like(like, word)))
        .collect();
    let mut file_index: HashMap<[u64; 3], u32> = HashMap::new();
    for (i, p) in coordinates.iter().enumerate() {
        file_index.entry(*p).or_insert(i as u32);
    }
    let mut corners: Vec<u32> = Vec::new(); // file vertex per triangle corner
    let mut used: Vec<Option<DVec3>> = vec![None; coordinates.len()];
    for model in &models {
        let mut to_file = Vec::with_capacity(model.mesh.positions.len() / 3);
        for p in model.mesh.positions.chunks_exact(3) {
            let key = [p[0], p[1], p[2]].map(|c| f64::from(c).to_bits());
            let Some(&i) = file_index.get(&key) else {
                return Err(parse_error(
                    path,
                    FORMAT,
                    "a vertex read by the OBJ parser matches no `v` statement; re-export the file",
                ));
            };
            used[i as usize] = Some(DVec3::new(p[0].into(), p[1].into(), p[2].into()));
            to_file.push(i);
        }
        corners.extend(model.mesh.indices.iter().map(|&k| to_file[k as usize]));
    }
    // Raw vertices: the used file vertices, in file order.
    let mut raw_of_file = vec![u32::MAX; used.len()];
    let mut file_of_raw = Vec::new();
    let mut positions = Vec::new();
    for (i, p) in used.iter().enumerate() {
        if let Some(p) = p {
            raw_of_file[i] = positions.len() as u32;
            file_of_raw.push(i);
            positions.push(*p);
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
    let at_position: HashMap<[u64; 3], u32> = mesh
        .positions
        .iter()
        .enumerate()
        .map(|(i, p)| (exact_key(*p), i as u32))
        .collect();
    let source = (0..used.len())
        .map(|i| match raw_of_file[i] {
            u32::MAX => {
                let c = coordinates[i].map(f64::from_bits);
                at_position.get(&exact_key(DVec3::from_array(c))).copied()
            }
            raw => raw_map[raw as usize],
        })
        .collect();
    Ok((mesh, source))
}

/// Bit pattern of a position with `-0.0` normalised to `0.0`.
fn exact_key(p: DVec3) -> [u64; 3] {
    (p + DVec3::ZERO).to_array().map(f64::to_bits)
}

/// What a quick pass over the OBJ text found.
struct Scan<'a> {
    vertex_lines: usize,
    faces: usize,
    /// The coordinate words of every `v` statement (empty when missing).
    coordinates: Vec<[&'a str; 3]>,
}

/// The bits of `word` parsed as the float type `tobj` returns (the element type of `like`),
/// widened to `f64`; NaN bits when it does not parse (`tobj` rejects such a file first).
fn parsed_like<T: std::str::FromStr + Into<f64>>(_like: &[T], word: &str) -> u64 {
    word.parse::<T>().map_or(f64::NAN, Into::into).to_bits()
}

/// Counts vertices and faces and checks every face index before `tobj` sees it (so that no
/// index can overflow its arithmetic), resolving relative (negative) indices as `tobj` does:
/// against the elements defined so far.
fn scan<'a>(path: &Path, text: &'a str) -> Result<Scan<'a>, MeshError> {
    let mut counts = [0usize; 3]; // v, vt, vn
    let mut faces = 0usize;
    let mut triangles_before = 0usize;
    let mut coordinates = Vec::new();
    for (line_number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                counts[0] += 1;
                let mut c = [""; 3];
                for (slot, word) in c.iter_mut().zip(words.by_ref()) {
                    *slot = word;
                }
                coordinates.push(c);
            }
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
        coordinates,
    })
}

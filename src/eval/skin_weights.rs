//! A reference model's own skin weights, read from the skinned glTF its mesh and rig were made
//! from (refdata `source.glb`), and carried onto the vertices of its `mesh.obj`.

use super::{EvalError, ReferenceRig};
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use glam::{DMat4, DVec3};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// Tolerance for finding a `mesh.obj` vertex among the glTF's vertices, as a fraction of the
/// mesh's bounding-box diagonal: refdata welded the glTF's vertices by position within 1e-6
/// (README "glTF models"), so the same point is found again within that.
pub const VERTEX_MATCH_FRACTION: f64 = 1e-6;

/// The artists' skin of a reference model, per vertex of its `mesh.obj`.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceSkin {
    /// The glTF skin's joints (bind pose, file units; every joint of the reference rig is
    /// among them by name).
    pub skeleton: Skeleton,
    /// The reference rig's canonical keys, mapped onto `skeleton` by joint name.
    pub canonical: BTreeMap<String, JointId>,
    /// For every vertex of the mesh, its `(joint of skeleton, weight)` list, normalised to sum
    /// to one; empty for a vertex not found in the glTF or without weights.
    pub weights: Vec<Vec<(JointId, f64)>>,
    /// Vertices of the mesh that were found in the glTF with weights.
    pub matched: usize,
}

/// The skin weights of refdata model folder `model` for the vertices of `mesh` (its
/// `mesh.obj`): read from `model/source.glb`, whose bind-pose mesh times `scale_applied`, then
/// moved by `post_transform_matrix` (both from `model/provenance.json`; default 1 and the
/// identity; the matrix row-major, acting on column vectors) is the mesh; each mesh vertex
/// takes the weights of the glTF vertex at its position (within [`VERTEX_MATCH_FRACTION`] of
/// the mesh's diagonal).
///
/// `Ok(None)` when there is no `source.glb`, it has no skin, or `rig` is not its skin (a joint
/// of `rig` is missing from it).
///
/// # Errors
/// [`EvalError::Mesh`] when `source.glb` exists but cannot be read.
pub fn reference_skin(
    model: &Path,
    rig: &ReferenceRig,
    mesh: &Mesh,
) -> Result<Option<ReferenceSkin>, EvalError> {
    let source = model.join("source.glb");
    if !source.is_file() {
        return Ok(None);
    }
    let scene = crate::mesh::load_gltf_scene(&source)?;
    let (Some(skeleton), Some(weights)) = (scene.skeleton, scene.weights) else {
        return Ok(None);
    };
    if rig
        .skeleton
        .joints
        .iter()
        .any(|j| skeleton.find(&j.name).is_none())
    {
        return Ok(None);
    }
    let canonical = rig
        .canonical
        .iter()
        .filter_map(|(key, id)| {
            let name = &rig.skeleton.joints.get(id.0)?.name;
            Some((key.clone(), skeleton.find(name)?))
        })
        .collect();
    let provenance = std::fs::read(model.join("provenance.json"))
        .ok()
        .and_then(|b| serde_json::from_slice::<serde_json::Value>(&b).ok())
        .unwrap_or_default();
    let scale = provenance["scale_applied"].as_f64().unwrap_or(1.0);
    let post = post_transform(&provenance["post_transform_matrix"]);
    let Some((lo, hi)) = mesh.bounding_box() else {
        return Ok(None);
    };
    let tolerance = VERTEX_MATCH_FRACTION * (hi - lo).length().max(f64::MIN_POSITIVE);
    let points: Vec<DVec3> = scene
        .mesh
        .positions
        .iter()
        .map(|p| post.transform_point3(*p * scale))
        .collect();
    let found = nearest_within(&points, &mesh.positions, tolerance);
    let weights: Vec<Vec<(JointId, f64)>> = found
        .iter()
        .map(|i| i.map(|i| weights[i].clone()).unwrap_or_default())
        .collect();
    let matched = weights.iter().filter(|w| !w.is_empty()).count();
    Ok(Some(ReferenceSkin {
        skeleton,
        canonical,
        weights,
        matched,
    }))
}

/// The 4×4 matrix of a row-major JSON array of four rows; the identity when absent or not a
/// finite 4×4 array.
fn post_transform(rows: &serde_json::Value) -> DMat4 {
    let rows: Option<Vec<Vec<f64>>> = rows.as_array().map(|rows| {
        rows.iter()
            .map(|r| {
                r.as_array()
                    .map(|r| r.iter().filter_map(serde_json::Value::as_f64).collect())
                    .unwrap_or_default()
            })
            .collect()
    });
    match rows {
        Some(rows) if rows.len() == 4 && rows.iter().all(|r| r.len() == 4) => {
            let m = DMat4::from_cols_array_2d(&std::array::from_fn(|c| {
                std::array::from_fn(|r| rows[r][c])
            }));
            if m.is_finite() {
                m
            } else {
                DMat4::IDENTITY
            }
        }
        _ => DMat4::IDENTITY,
    }
}

/// For every query point, the index of the nearest of `points` within `tolerance` (a hash grid
/// of cells `4 tolerance` wide, the 27 cells around the query searched).
fn nearest_within(points: &[DVec3], queries: &[DVec3], tolerance: f64) -> Vec<Option<usize>> {
    let cell = |p: DVec3| (p / (4.0 * tolerance)).floor().as_i64vec3().to_array();
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, p) in points.iter().enumerate() {
        grid.entry(cell(*p)).or_default().push(i);
    }
    queries
        .iter()
        .map(|&q| {
            let [x, y, z] = cell(q);
            let mut best: Option<(f64, usize)> = None;
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        for &i in grid.get(&[x + dx, y + dy, z + dz]).into_iter().flatten() {
                            let d = points[i].distance(q);
                            if d <= tolerance && best.is_none_or(|(b, _)| d < b) {
                                best = Some((d, i));
                            }
                        }
                    }
                }
            }
            best.map(|(_, i)| i)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn post_transform_reads_rows_and_falls_back_to_the_identity() {
        let rows = serde_json::json!([
            [0.0, 0.0, -1.0, 0.5],
            [0.0, 1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0, 1.0]
        ]);
        let m = post_transform(&rows);
        assert_eq!(
            m.transform_point3(DVec3::new(1.0, 2.0, 3.0)),
            DVec3::new(-2.5, 2.0, 1.0)
        );
        assert_eq!(post_transform(&serde_json::Value::Null), DMat4::IDENTITY);
        assert_eq!(post_transform(&serde_json::json!([[1.0]])), DMat4::IDENTITY);
    }

    #[test]
    fn nearest_within_finds_only_points_inside_the_tolerance() {
        let points = [
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1e-7, 0.0),
        ];
        let queries = [
            DVec3::new(1e-7, 0.0, 0.0),
            DVec3::new(1.0, 0.9e-7, 0.0),
            DVec3::new(0.5, 0.0, 0.0),
        ];
        assert_eq!(
            nearest_within(&points, &queries, 1e-6),
            vec![Some(0), Some(2), None]
        );
    }
}

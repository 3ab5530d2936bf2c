//! Skinned binary glTF (`.glb`): the mesh, its engine weights and the armature in one file.

use super::{check_skeleton, io_error, ExportError};
use crate::mesh::Mesh;
use crate::skeleton::Skeleton;
use crate::skin::{Skin, MAX_ENGINE_INFLUENCES};
use glam::{DAffine3, DMat4, DQuat, DVec3};
use serde_json::{json, Value};
use std::path::Path;

/// Name of the node that holds the root joints of a skeleton with several roots.
pub const FOREST_ROOT_NAME: &str = "skeleton_root";
/// glTF component type: unsigned short.
pub(super) const UNSIGNED_SHORT: u32 = 5123;
/// glTF component type: unsigned int.
const UNSIGNED_INT: u32 = 5125;
/// glTF component type: float.
pub(super) const FLOAT: u32 = 5126;
/// Buffer view target of vertex attributes.
pub(super) const ARRAY_BUFFER: u32 = 34962;
/// Buffer view target of indices.
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// GLB header magic `glTF`.
const GLB_MAGIC: u32 = 0x4654_6C67;
/// GLB chunk type of the JSON chunk.
const CHUNK_JSON: u32 = 0x4E4F_534A;
/// GLB chunk type of the binary chunk.
const CHUNK_BIN: u32 = 0x004E_4942;

// The engine weights hold exactly this many influences per vertex (one JOINTS_0/WEIGHTS_0 set).
const _: () = assert!(MAX_ENGINE_INFLUENCES == 4);

/// Options of [`glb_bytes`] and [`write_glb`].
#[derive(Debug, Clone, PartialEq)]
pub struct GltfOptions {
    /// Name of the mesh and of its node. Default `"skin"`.
    pub mesh_name: String,
    /// Value of `asset.generator`. Default `"skelfit <version>"`.
    pub generator: String,
}

impl Default for GltfOptions {
    fn default() -> Self {
        Self {
            mesh_name: "skin".into(),
            generator: format!("skelfit {}", env!("CARGO_PKG_VERSION")),
        }
    }
}

/// The bytes of a skinned binary glTF 2.0 file of `mesh` bound to `skeleton` by `skin`.
///
/// Layout: one node per joint (node index = joint index, named after the joint), with its
/// rest transform relative to its parent as translation + rotation (rotation from
/// [`Joint::frame`](crate::skeleton::Joint::frame)); one skin listing every joint in joint order
/// with inverse bind matrices (the inverse of each joint's world rest transform, column-major
/// `f32`); one mesh with `POSITION` (`f32`, with `min`/`max`), `NORMAL` (area-weighted vertex
/// normals, `+Y` for isolated vertices), `JOINTS_0` (`u16`) and `WEIGHTS_0` (`f32`,
/// [`Skin::engine`]) and `u32` indices; the skinned mesh node sits at the scene root beside the
/// root joint. A skeleton with several root joints gets one extra plain node,
/// [`FOREST_ROOT_NAME`], holding them (glTF wants the joints of a skin under a common root);
/// it comes after the mesh node and is not a joint. Positions are in the mesh's units and frame. The same input gives the same
/// bytes.
///
/// # Errors
/// [`ExportError::EmptySkeleton`], [`ExportError::InvalidSkeleton`],
/// [`ExportError::SizeMismatch`] when `skin` was made for another mesh,
/// [`ExportError::EmptyMesh`] without triangles, [`ExportError::NonFinite`] for a NaN or
/// infinite position or weight (or a negative weight), [`ExportError::TooLarge`] beyond 4 GiB or
/// 65535 joints.
pub fn glb_bytes(
    mesh: &Mesh,
    skeleton: &Skeleton,
    skin: &Skin,
    options: &GltfOptions,
) -> Result<Vec<u8>, ExportError> {
    glb_bytes_with(Some((mesh, skin)), skeleton, &[], options)
}

/// A rigid mesh attached to a joint (a bone, say): written as a child node of the joint's node,
/// so it poses with the skeleton.
#[derive(Debug, Clone, PartialEq)]
pub struct Attachment {
    /// The joint it moves with.
    pub joint: crate::skeleton::JointId,
    /// Name of its node and mesh.
    pub name: String,
    /// The mesh in the joint's rest local frame (see
    /// [`Joint::rest_transform`](crate::skeleton::Joint::rest_transform)).
    pub mesh: Mesh,
}

/// [`glb_bytes`] with an optional skinned mesh and rigid `attachments`: each attachment is one
/// more mesh (`POSITION`, `NORMAL`, indices) on a node that is a child of its joint's node,
/// after the skinned mesh node and the forest root; joint nodes list their attachment nodes
/// after their child joints. Without a skinned mesh the file holds the armature (plain nodes,
/// no skin) and the attachments. With a skinned mesh and no attachments the bytes equal
/// [`glb_bytes`]'s.
///
/// # Errors
/// As [`glb_bytes`]; [`ExportError::SizeMismatch`] for an attachment on a joint that does not
/// exist, [`ExportError::EmptyMesh`] or [`ExportError::NonFinite`] for an attachment mesh
/// without triangles or with a non-finite position.
pub fn glb_bytes_with(
    skinned: Option<(&Mesh, &Skin)>,
    skeleton: &Skeleton,
    attachments: &[Attachment],
    options: &GltfOptions,
) -> Result<Vec<u8>, ExportError> {
    check_skeleton(skeleton)?;
    let joint_count = skeleton.len();
    check_inputs(skinned, joint_count, attachments)?;

    let mut bin = Binary::default();
    let mut accessors = Vec::new();
    let mut meshes = Vec::new();
    if let Some((mesh, skin)) = skinned {
        push_skinned(&mut bin, mesh, skin, skeleton, &mut accessors);
        meshes.push(json!({
            "name": options.mesh_name,
            "primitives": [{
                "attributes": {"POSITION": 1, "NORMAL": 2, "JOINTS_0": 3, "WEIGHTS_0": 4},
                "indices": 0,
                "mode": 4,
            }],
        }));
    }

    // Attachment node indices per joint, in attachment order.
    let mut attached: Vec<Vec<usize>> = vec![Vec::new(); joint_count];
    let mut nodes = joint_nodes(skeleton);
    let mut scene_nodes = Vec::new();
    let mesh_node = skinned.map(|_| {
        nodes.push(json!({"name": options.mesh_name, "mesh": 0, "skin": 0}));
        nodes.len() - 1
    });
    let skeleton_root = skeleton_root(&mut nodes, skeleton);
    scene_nodes.push(skeleton_root);
    scene_nodes.extend(mesh_node);
    for a in attachments {
        push_attachment(&mut bin, a, &mut accessors, &mut meshes);
        nodes.push(json!({"name": a.name, "mesh": meshes.len() - 1}));
        attached[a.joint.0].push(nodes.len() - 1);
    }
    link_children(&mut nodes, skeleton, &attached);

    let bin_len = bin.bytes.len();
    let mut document = json!({
        "asset": {"version": "2.0", "generator": options.generator},
        "scene": 0,
        "scenes": [{"name": "scene", "nodes": scene_nodes}],
        "nodes": nodes,
        "accessors": accessors,
        "bufferViews": bin.views,
        "buffers": [{"byteLength": bin_len}],
    });
    if !meshes.is_empty() {
        document["meshes"] = json!(meshes);
    }
    if skinned.is_some() {
        document["skins"] = json!([{
            "joints": (0..joint_count).collect::<Vec<_>>(),
            "inverseBindMatrices": 5,
            "name": "armature",
            "skeleton": skeleton_root,
        }]);
    }
    if accessors_empty(&document) {
        if let Some(map) = document.as_object_mut() {
            map.remove("accessors");
            map.remove("bufferViews");
            map.remove("buffers");
        }
    }
    let json_bytes = serde_json::to_vec(&document).map_err(|e| ExportError::TooLarge {
        what: "the glTF document",
        format: "JSON",
        detail: e.to_string(),
    })?;
    pack_glb(json_bytes, bin.bytes)
}

/// The checks of [`glb_bytes_with`] beyond the skeleton's: joint count, skinned mesh,
/// attachments.
fn check_inputs(
    skinned: Option<(&Mesh, &Skin)>,
    joint_count: usize,
    attachments: &[Attachment],
) -> Result<(), ExportError> {
    if joint_count > usize::from(u16::MAX) {
        return Err(ExportError::TooLarge {
            what: "the skeleton",
            format: "glTF",
            detail: format!("{joint_count} joints, JOINTS_0 holds at most 65535"),
        });
    }
    if let Some((mesh, skin)) = skinned {
        check_skinned(mesh, skin, joint_count)?;
    }
    for a in attachments {
        if a.joint.0 >= joint_count {
            return Err(ExportError::SizeMismatch {
                what: "an attachment's joint index",
                expected: joint_count,
                found: a.joint.0 + 1,
            });
        }
        if a.mesh.triangles.is_empty() || a.mesh.positions.is_empty() {
            return Err(ExportError::EmptyMesh);
        }
        if let Some(index) = a.mesh.positions.iter().position(|p| !p.is_finite()) {
            return Err(ExportError::NonFinite {
                what: "attachment vertex",
                index,
            });
        }
    }
    Ok(())
}

/// The skinned mesh's buffers (indices, positions, normals, joints, weights, inverse bind
/// matrices) into `bin` and their accessors (0 to 5) into `accessors`.
fn push_skinned(
    bin: &mut Binary,
    mesh: &Mesh,
    skin: &Skin,
    skeleton: &Skeleton,
    accessors: &mut Vec<Value>,
) {
    let vertices = mesh.positions.len();
    let (index_view, position_view, normal_view, min, max) = push_geometry(bin, mesh);
    let joints_view = bin.push(
        skin.engine
            .joints
            .iter()
            .flatten()
            .flat_map(|j| j.to_le_bytes()),
        Some(ARRAY_BUFFER),
    );
    let weights_view = bin.push(
        skin.engine
            .weights
            .iter()
            .flatten()
            .flat_map(|w| w.to_le_bytes()),
        Some(ARRAY_BUFFER),
    );
    let ibm_view = bin.push(
        skeleton.joints.iter().flat_map(|j| {
            let m = DMat4::from(j.rest_transform().inverse());
            m.as_mat4()
                .to_cols_array()
                .into_iter()
                .flat_map(f32::to_le_bytes)
        }),
        None,
    );
    let mut position_accessor = accessor(position_view, FLOAT, vertices, "VEC3");
    position_accessor["min"] = json!(min.map(f64::from));
    position_accessor["max"] = json!(max.map(f64::from));
    accessors.extend([
        accessor(index_view, UNSIGNED_INT, mesh.triangles.len() * 3, "SCALAR"),
        position_accessor,
        accessor(normal_view, FLOAT, vertices, "VEC3"),
        accessor(joints_view, UNSIGNED_SHORT, vertices, "VEC4"),
        accessor(weights_view, FLOAT, vertices, "VEC4"),
        accessor(ibm_view, FLOAT, skeleton.len(), "MAT4"),
    ]);
}

/// The node at the root of the joint nodes (which come first in `nodes`, one per joint): the
/// root joint, or, since glTF requires the joints of a skin to share a root node, a plain
/// (identity) node pushed to hang a skeleton's several root joints under.
pub(super) fn skeleton_root(nodes: &mut Vec<Value>, skeleton: &Skeleton) -> usize {
    let roots: Vec<usize> = (0..skeleton.len())
        .filter(|&k| skeleton.joints[k].parent.is_none())
        .collect();
    match roots[..] {
        [root] => root,
        _ => {
            nodes.push(json!({"name": FOREST_ROOT_NAME, "children": roots}));
            nodes.len() - 1
        }
    }
}

/// A node per joint: its name and its rest transform relative to its parent's.
pub(super) fn joint_nodes(skeleton: &Skeleton) -> Vec<Value> {
    skeleton
        .joints
        .iter()
        .map(|joint| {
            let local = match joint.parent {
                Some(p) => skeleton.joint(p).rest_transform().inverse() * joint.rest_transform(),
                None => joint.rest_transform(),
            };
            let (translation, rotation) = trs(
                &local,
                joint.frame,
                joint.parent.map(|p| skeleton.joint(p).frame),
            );
            json!({"name": joint.name, "translation": translation, "rotation": rotation})
        })
        .collect()
}

/// An attachment's buffers into `bin`, its accessors (indices, positions, normals) into
/// `accessors` and its mesh into `meshes`.
fn push_attachment(
    bin: &mut Binary,
    a: &Attachment,
    accessors: &mut Vec<Value>,
    meshes: &mut Vec<Value>,
) {
    let vertices = a.mesh.positions.len();
    let (index_view, position_view, normal_view, min, max) = push_geometry(bin, &a.mesh);
    let first = accessors.len();
    let mut position_accessor = accessor(position_view, FLOAT, vertices, "VEC3");
    position_accessor["min"] = json!(min.map(f64::from));
    position_accessor["max"] = json!(max.map(f64::from));
    accessors.extend([
        accessor(
            index_view,
            UNSIGNED_INT,
            a.mesh.triangles.len() * 3,
            "SCALAR",
        ),
        position_accessor,
        accessor(normal_view, FLOAT, vertices, "VEC3"),
    ]);
    meshes.push(json!({
        "name": a.name,
        "primitives": [{
            "attributes": {"POSITION": first + 1, "NORMAL": first + 2},
            "indices": first,
            "mode": 4,
        }],
    }));
}

/// Each joint node's `children`: its child joints, then its attachment nodes (`attached`).
pub(super) fn link_children(nodes: &mut [Value], skeleton: &Skeleton, attached: &[Vec<usize>]) {
    for (k, extra) in attached.iter().enumerate() {
        let mut children: Vec<usize> = skeleton
            .children(crate::skeleton::JointId(k))
            .iter()
            .map(|c| c.0)
            .collect();
        children.extend(extra);
        if !children.is_empty() {
            nodes[k]["children"] = json!(children);
        }
    }
}

/// Whether the document has no accessors (an armature without meshes).
fn accessors_empty(document: &Value) -> bool {
    document["accessors"].as_array().is_some_and(Vec::is_empty)
}

/// An accessor object.
pub(super) fn accessor(view: usize, component: u32, count: usize, kind: &str) -> Value {
    json!({"bufferView": view, "componentType": component, "count": count, "type": kind})
}

/// Pushes a mesh's indices, positions and normals; returns their views and the position bounds.
fn push_geometry(bin: &mut Binary, mesh: &Mesh) -> (usize, usize, usize, [f32; 3], [f32; 3]) {
    let index_view = bin.push(
        mesh.triangles
            .iter()
            .flatten()
            .flat_map(|i| i.to_le_bytes()),
        Some(ELEMENT_ARRAY_BUFFER),
    );
    let positions: Vec<[f32; 3]> = mesh
        .positions
        .iter()
        .map(|p| p.as_vec3().to_array())
        .collect();
    let (min, max) = bounds(&positions);
    let position_view = bin.push(
        positions.iter().flatten().flat_map(|x| x.to_le_bytes()),
        Some(ARRAY_BUFFER),
    );
    let normals = vertex_normals(mesh);
    let normal_view = bin.push(
        normals.iter().flatten().flat_map(|x| x.to_le_bytes()),
        Some(ARRAY_BUFFER),
    );
    (index_view, position_view, normal_view, min, max)
}

/// Checks a skinned mesh against its skin and the skeleton's joint count.
fn check_skinned(mesh: &Mesh, skin: &Skin, joint_count: usize) -> Result<(), ExportError> {
    let vertices = mesh.positions.len();
    for (what, found) in [
        ("the skin's engine joints", skin.engine.joints.len()),
        ("the skin's engine weights", skin.engine.weights.len()),
    ] {
        if found != vertices {
            return Err(ExportError::SizeMismatch {
                what,
                expected: vertices,
                found,
            });
        }
    }
    if mesh.triangles.is_empty() || vertices == 0 {
        return Err(ExportError::EmptyMesh);
    }
    if let Some(index) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(ExportError::NonFinite {
            what: "vertex",
            index,
        });
    }
    check_engine_rows(skin, joint_count)
}

/// The engine rows of a skin: finite non-negative weights on joints below `joint_count`.
pub(super) fn check_engine_rows(skin: &Skin, joint_count: usize) -> Result<(), ExportError> {
    if let Some(index) = skin
        .engine
        .weights
        .iter()
        .position(|w| w.iter().any(|x| !x.is_finite() || *x < 0.0))
    {
        return Err(ExportError::NonFinite {
            what: "weight of vertex",
            index,
        });
    }
    if let Some(&bad) = skin
        .engine
        .joints
        .iter()
        .flatten()
        .find(|&&j| usize::from(j) >= joint_count)
    {
        return Err(ExportError::SizeMismatch {
            what: "a skin joint index",
            expected: joint_count,
            found: usize::from(bad) + 1,
        });
    }
    Ok(())
}

/// Writes [`glb_bytes`] to `path` atomically ([`crate::output::write_atomic`]).
///
/// # Errors
/// As [`glb_bytes`], and [`ExportError::Io`] when the file cannot be written.
pub fn write_glb(
    path: &Path,
    mesh: &Mesh,
    skeleton: &Skeleton,
    skin: &Skin,
    options: &GltfOptions,
) -> Result<(), ExportError> {
    let bytes = glb_bytes(mesh, skeleton, skin, options)?;
    crate::output::write_atomic(path, &bytes).map_err(|cause| io_error(path, cause))
}

/// Translation and unit rotation of a local rest transform. The rotation is computed from the
/// frames directly (`parent⁻¹ · frame`) and normalised, so it is unit length in `f32`.
fn trs(local: &DAffine3, frame: DQuat, parent: Option<DQuat>) -> ([f64; 3], [f64; 4]) {
    let rotation = match parent {
        Some(p) => p.inverse() * frame,
        None => frame,
    }
    .normalize();
    let rotation = if rotation.is_finite() {
        rotation
    } else {
        DQuat::IDENTITY
    };
    let t: DVec3 = local.translation;
    (clean(t.to_array()), clean(rotation.to_array()))
}

/// Replaces negative zeros by zeros so that equal transforms print equally.
fn clean<const N: usize>(values: [f64; N]) -> [f64; N] {
    values.map(|v| if v == 0.0 { 0.0 } else { v })
}

/// Component-wise bounds of `f32` points.
fn bounds(points: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for p in points {
        for a in 0..3 {
            min[a] = min[a].min(p[a]);
            max[a] = max[a].max(p[a]);
        }
    }
    (min, max)
}

/// Unit vertex normals: the sum of the (area-weighted) normals of the triangles around each
/// vertex, normalised; `+Y` where that sum vanishes (isolated vertices, degenerate fans).
fn vertex_normals(mesh: &Mesh) -> Vec<[f32; 3]> {
    let mut sums = vec![DVec3::ZERO; mesh.positions.len()];
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        let n = (b - a).cross(c - a);
        for &i in &mesh.triangles[t] {
            sums[i as usize] += n;
        }
    }
    sums.iter()
        .map(|n| n.try_normalize().unwrap_or(DVec3::Y).as_vec3().to_array())
        .collect()
}

/// The binary chunk under construction and its buffer views.
#[derive(Default)]
pub(super) struct Binary {
    pub(super) bytes: Vec<u8>,
    pub(super) views: Vec<Value>,
}

impl Binary {
    /// Appends one buffer view (4-byte aligned) and returns its index.
    pub(super) fn push(&mut self, data: impl Iterator<Item = u8>, target: Option<u32>) -> usize {
        while self.bytes.len() % 4 != 0 {
            self.bytes.push(0);
        }
        let offset = self.bytes.len();
        self.bytes.extend(data);
        let mut view =
            json!({"buffer": 0, "byteOffset": offset, "byteLength": self.bytes.len() - offset});
        if let Some(target) = target {
            view["target"] = json!(target);
        }
        self.views.push(view);
        self.views.len() - 1
    }
}

/// Packs a JSON document and binary data into a GLB container (glTF 2.0 §4.4): a 12-byte
/// header, the JSON chunk padded with spaces and the BIN chunk padded with zeros to 4 bytes.
///
/// # Errors
/// [`ExportError::TooLarge`] when the container (and so its binary chunk, whose length the
/// document's `buffers[0].byteLength` also states) would not fit the format's 32-bit sizes.
pub(super) fn pack_glb(mut json: Vec<u8>, mut bin: Vec<u8>) -> Result<Vec<u8>, ExportError> {
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let too_large = || ExportError::TooLarge {
        what: "the file",
        format: "GLB",
        detail: format!(
            "{total} bytes ({} of binary data), a GLB holds under 4 GiB",
            bin.len()
        ),
    };
    let total32 = u32::try_from(total).map_err(|_| too_large())?;
    let mut out = Vec::with_capacity(total);
    out.extend(GLB_MAGIC.to_le_bytes());
    out.extend(2u32.to_le_bytes());
    out.extend(total32.to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(CHUNK_JSON.to_le_bytes());
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(CHUNK_BIN.to_le_bytes());
    out.extend(bin);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glb_container_is_aligned_and_sized() {
        let bytes = pack_glb(b"{}".to_vec(), vec![1, 2, 3]).unwrap();
        assert_eq!(bytes.len() % 4, 0);
        assert_eq!(
            u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize,
            bytes.len()
        );
        assert_eq!(&bytes[0..4], b"glTF");
        assert_eq!(u32::from_le_bytes(bytes[12..16].try_into().unwrap()), 4);
    }

    #[test]
    fn normals_are_unit_with_a_fallback() {
        let mut mesh = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        mesh.positions.push(DVec3::splat(5.0));
        let normals = vertex_normals(&mesh);
        for n in &normals {
            let len = glam::Vec3::from_array(*n).length();
            assert!((len - 1.0).abs() < 1e-6);
        }
        assert_eq!(*normals.last().unwrap(), [0.0, 1.0, 0.0]);
    }
}

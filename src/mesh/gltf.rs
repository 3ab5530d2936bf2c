//! glTF 2.0 (`.gltf` + buffers, `.glb`) reading, with skinned meshes in their bind pose.

use super::gltf_accessor;
use super::gltf_buffers;
use super::gltf_nodes::NodeTree;
use super::gltf_skin::{vertex_weights, SkinBind};
use super::load::{finish, guarded, parse_error, read_bytes};
use super::{Mesh, MeshError};
use crate::skeleton::{JointId, Skeleton};
use glam::{DMat4, DVec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;
use gltf::Semantic;
use std::path::Path;

const FORMAT: &str = "gltf";

/// A glTF scene read by [`load_gltf_scene`]: the mesh and, for a skinned file, its skeleton.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfScene {
    /// All triangle primitives of the scene in the bind pose, welded (see [`load_gltf`]).
    pub mesh: Mesh,
    /// The joints of the first skin used by a mesh node of the scene, in the same frame as
    /// `mesh`; `None` when no mesh node is skinned.
    ///
    /// Joint `j` sits at `B · inv(IBM_j) · 0` (the bind pose, see [`load_gltf`]); its parent
    /// is the nearest ancestor node that is a joint of the skin; its name is the node name, or
    /// `joint_<node index>` for an unnamed node (`<name>_<node index>` if the name is already
    /// taken); `deform` is true iff some vertex has a nonzero weight on it in a
    /// `JOINTS_n`/`WEIGHTS_n` pair (of any skin listing the joint's node).
    /// A joint's `frame` is the rotation of its bind-pose transform, so written back its node
    /// turns as the artist's did (identity where that transform mirrors, shears or scales
    /// unevenly). Joints are in skin order, moved only where needed to put
    /// parents before children.
    pub skeleton: Option<Skeleton>,
    /// Names that several joints of the skin share, in skeleton order: the first joint keeps
    /// the name, every later one is renamed `<name>_<node index>` in `skeleton`. Empty when
    /// the names are unique. Animations and engines find joints by name, so a caller that
    /// writes the skeleton back (`skelfit skin`) refuses such a file.
    pub duplicate_joint_names: Vec<String>,
    /// For every vertex of the file's triangle primitives, in reading order, its index in
    /// `mesh` (`None`: used by no face); see
    /// [`load_with_source_map`](super::load_with_source_map).
    pub source_vertices: Vec<Option<u32>>,
    /// Skin weights of each vertex of `mesh` to the joints of `skeleton` (`JOINTS_n` /
    /// `WEIGHTS_n` of the skinned primitives, zero weights left out, normalised to sum to
    /// one), as the artist painted them; `None` when no mesh node is skinned. Primitives
    /// skinned by another skin (modular characters give each piece its own skin over the
    /// same joints) count through the joint nodes both skins list; weights on nodes that are
    /// not joints of the rig's skin are dropped. A vertex of an unskinned primitive (a rigid
    /// part attached to a joint node), or whose weights are all zero, has an empty list;
    /// welded vertices take the weights of their first copy.
    pub weights: Option<Vec<Vec<(JointId, f64)>>>,
}

/// Reads the mesh of a glTF 2.0 file (`.gltf` with external or embedded buffers, or `.glb`).
/// Images are not loaded.
///
/// Every mesh primitive of the default scene (or the first scene; all root nodes without a
/// scene) is included: triangles, triangle strips and fans (converted to triangles); points
/// and lines are skipped. Unskinned primitives get their node's world transform. Skinned
/// primitives are returned in the bind pose `B · v` with `B = W_root(rest) · IBM_root`, where
/// `root` is the first joint of the skin whose parent node is not a joint of the skin, `W` the
/// rest-pose world transform and `IBM` the inverse bind matrix (the node transform of a
/// skinned mesh is ignored, as the glTF spec requires); when the file's rest pose is an
/// animation frame far from the bind pose (the joints' `W · IBM` disagree), `B` is the world
/// transform of the node above the root instead (the armature), so the figure keeps its
/// modelled pose and axes rather than the posed pelvis's tilt. An unskinned mesh attached below a
/// joint of the rig's skin follows that joint into the bind pose. Triangles of nodes with a
/// mirroring transform (negative determinant) are reversed so they stay outward-wound.
/// The result is welded and validated like every loader (see [`load`](super::load)).
///
/// External buffers are read only from `data:` URIs and from relative paths to regular files
/// inside the folder of `path` (symbolic links and `..` resolved first), at most `byteLength`
/// bytes each: absolute paths, `file:` and other schemes, paths leading outside the folder,
/// devices and FIFOs are refused, so a hostile file cannot make skelfit read other files.
///
/// # Errors
/// [`MeshError::Io`] (the file itself cannot be read), [`MeshError::Empty`] (empty file, no
/// triangle primitives), [`MeshError::Parse`] (invalid or truncated glTF/GLB; a buffer that is
/// refused, missing or shorter than its `byteLength`, the message naming its URI; accessors out
/// of bounds or of the wrong type, e.g. quantized positions), [`MeshError::NonFinite`],
/// [`MeshError::IndexOutOfRange`] (an index beyond its primitive's vertices),
/// [`MeshError::Degenerate`].
pub fn load_gltf(path: &Path) -> Result<Mesh, MeshError> {
    Ok(load_gltf_scene(path)?.mesh)
}

/// Reads a glTF 2.0 file like [`load_gltf`], and also the skeleton of its skin in the bind
/// pose, in the same frame as the mesh (see [`GltfScene::skeleton`]). This is how reference
/// rigs are read: for the refdata glTF models it reproduces `mesh.obj` (up to the recorded
/// scale) and `rig_gltf.json`.
///
/// # Errors
/// As [`load_gltf`]; also [`MeshError::Parse`] for a singular inverse bind matrix or a joint
/// index beyond the skin.
pub fn load_gltf_scene(path: &Path) -> Result<GltfScene, MeshError> {
    let (_, raw, mesh, source_vertices) = read_welded(path)?;
    let weights = raw.skeleton.as_ref().map(|_| {
        let mut weights = vec![None; mesh.positions.len()];
        for (raw_vertex, welded) in source_vertices.iter().enumerate() {
            if let Some(w) = welded {
                let slot = &mut weights[*w as usize];
                if slot.is_none() {
                    *slot = Some(normalised(&raw.weights[raw_vertex]));
                }
            }
        }
        weights.into_iter().map(Option::unwrap_or_default).collect()
    });
    Ok(GltfScene {
        mesh,
        skeleton: raw.skeleton,
        duplicate_joint_names: raw.duplicate_joint_names,
        source_vertices,
        weights,
    })
}

/// The file's bytes, what [`read`] made of them and the welded mesh with its source map.
#[allow(clippy::type_complexity)]
pub(super) fn read_welded(
    path: &Path,
) -> Result<(Vec<u8>, RawScene, Mesh, Vec<Option<u32>>), MeshError> {
    let bytes = read_bytes(path)?;
    let mut raw = guarded(path, FORMAT, || read(path, &bytes))?;
    let detail = if raw.skipped_primitives > 0 {
        " (the glTF scene holds only points or lines)"
    } else {
        " (the glTF scene has no mesh primitives)"
    };
    let positions = std::mem::take(&mut raw.positions);
    let triangles = std::mem::take(&mut raw.triangles);
    let (mesh, source_vertices) = finish(positions, triangles, detail)?;
    Ok((bytes, raw, mesh, source_vertices))
}

/// Joint weights summed per joint, zeros dropped, scaled to sum to one (empty if all zero).
fn normalised(weights: &[(JointId, f64)]) -> Vec<(JointId, f64)> {
    let mut sum: std::collections::BTreeMap<JointId, f64> = Default::default();
    for &(j, w) in weights {
        if w > 0.0 && w.is_finite() {
            *sum.entry(j).or_default() += w;
        }
    }
    let total: f64 = sum.values().sum();
    if total <= 0.0 {
        return Vec::new();
    }
    sum.into_iter().map(|(j, w)| (j, w / total)).collect()
}

/// Everything read from the file before welding.
pub(super) struct RawScene {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    skipped_primitives: usize,
    skeleton: Option<Skeleton>,
    /// Names several joints of the rig's skin share.
    duplicate_joint_names: Vec<String>,
    /// Per position: weights to skin joints of the rig (skin joint indices until the skeleton
    /// is built, then skeleton ids).
    weights: Vec<Vec<(JointId, f64)>>,
    /// Every mesh node read, in reading order, with the transform applied to its positions.
    pub instances: Vec<RawInstance>,
    /// The data of every buffer of the file, in buffer order.
    pub buffers: Vec<Vec<u8>>,
}

/// A mesh node as read: which mesh, the transform its positions got, and for every triangle
/// primitive (in mesh order) its index and vertex count.
pub(super) struct RawInstance {
    pub node: usize,
    pub mesh: usize,
    pub transform: DMat4,
    pub primitives: Vec<(usize, usize)>,
}

fn read(path: &Path, bytes: &[u8]) -> Result<RawScene, MeshError> {
    let error = |message: String| parse_error(path, FORMAT, message);
    let gltf::Gltf { document, blob } =
        gltf::Gltf::from_slice_without_validation(bytes).map_err(|e| error(e.to_string()))?;
    let json = document.into_json();
    check_attribute_indices(&json).map_err(error)?;
    let document = gltf::Document::from_json(json).map_err(|e| error(e.to_string()))?;
    let owned = gltf_buffers::buffers(&document, path, blob).map_err(error)?;
    let buffers: Vec<&[u8]> = owned.iter().map(Vec::as_slice).collect();
    let tree = NodeTree::new(&document).map_err(error)?;
    let roots: Vec<usize> = match document
        .default_scene()
        .or_else(|| document.scenes().next())
    {
        Some(scene) => scene.nodes().map(|n| n.index()).collect(),
        None => tree.roots(),
    };
    let nodes: Vec<gltf::Node> = document.nodes().collect();
    let mesh_nodes: Vec<usize> = tree
        .preorder(&document, &roots)
        .into_iter()
        .filter(|&n| nodes[n].mesh().is_some())
        .collect();

    // The rig: the first skin used by a mesh node of the scene.
    let mut binds: Vec<SkinBind> = Vec::new();
    for &n in &mesh_nodes {
        if let Some(skin) = nodes[n].skin() {
            if !binds.iter().any(|b| b.skin == skin.index()) {
                binds.push(SkinBind::new(&skin, &buffers, &tree).map_err(error)?);
            }
        }
    }
    let rig = binds.first();

    let mut raw = RawScene {
        positions: Vec::new(),
        triangles: Vec::new(),
        skipped_primitives: 0,
        skeleton: None,
        duplicate_joint_names: Vec::new(),
        weights: Vec::new(),
        instances: Vec::new(),
        buffers: Vec::new(),
    };
    for &n in &mesh_nodes {
        let node = &nodes[n];
        let transform = match node.skin() {
            Some(skin) => binds
                .iter()
                .find(|b| b.skin == skin.index())
                .map_or(DMat4::IDENTITY, |b| b.bind),
            None => match rig.and_then(|r| r.joint_ancestor(n, &tree).map(|k| (r, k))) {
                Some((rig, k)) => {
                    rig.joint_bind_world(k).map_err(error)?
                        * tree.world[rig.joints[k]].inverse()
                        * tree.world[n]
                }
                None => tree.world[n],
            },
        };
        // Joint indices of this node's skin → the rig's: the rig's own skin as it is, another
        // skin through the joint nodes both list (modular characters give every piece its own
        // skin over the same joints).
        let joint_map: Option<Vec<Option<usize>>> = match (rig, node.skin()) {
            (Some(rig), Some(skin)) => Some(
                skin.joints()
                    .map(|j| rig.joint_of_node.get(&j.index()).copied())
                    .collect(),
            ),
            _ => None,
        };
        if let Some(mesh) = node.mesh() {
            let skin = node.skin().map_or(0, |s| s.index());
            let weights = joint_map.as_deref().map(|map| (map, skin));
            let primitives = append_mesh(&mesh, transform, weights, &buffers, &mut raw).map_err(
                |e| match e {
                    Failure::Message(m) => error(m),
                    Failure::Mesh(e) => e,
                },
            )?;
            raw.instances.push(RawInstance {
                node: n,
                mesh: mesh.index(),
                transform,
                primitives,
            });
        }
    }
    drop(buffers);

    if let Some(rig) = rig {
        // A joint deforms iff some vertex of a skinned primitive has weight on it.
        let mut deform = vec![false; rig.joints.len()];
        for &(j, _) in raw.weights.iter().flatten() {
            deform[j.0] = true;
        }
        let (skeleton, id_of, shared) = rig.skeleton(&document, &tree, &deform).map_err(error)?;
        raw.duplicate_joint_names = shared;
        for weights in &mut raw.weights {
            for (j, _) in weights.iter_mut() {
                // In range: `deforming` checked every joint index with a nonzero weight.
                *j = JointId(id_of.get(j.0).copied().unwrap_or(usize::MAX));
            }
            weights.retain(|(j, _)| j.0 != usize::MAX);
        }
        raw.skeleton = Some(skeleton);
    }
    raw.buffers = owned;
    Ok(raw)
}

/// Checks that every primitive attribute names an existing accessor, which the `gltf` crate's
/// own validation assumes (it indexes the accessors of `POSITION` before checking the index).
fn check_attribute_indices(json: &gltf::json::Root) -> Result<(), String> {
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for (semantic, index) in &primitive.attributes {
                if index.value() >= json.accessors.len() {
                    return Err(format!(
                        "mesh {m} primitive {p}: attribute {semantic:?} names accessor {} \
                         but there are {}",
                        index.value(),
                        json.accessors.len()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Why reading a primitive failed: a message for [`MeshError::Parse`] or a finished error.
enum Failure {
    Message(String),
    Mesh(MeshError),
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Failure::Message(message)
    }
}

/// Appends the triangle primitives of `mesh`, transformed by `transform`; returns the index and
/// vertex count of each primitive appended.
/// `skinned` is given when the node is skinned: the rig's joint index of each joint of the
/// node's skin (`None`: not a joint of the rig) and the skin's index (for messages); its
/// vertices' `JOINTS_n` / `WEIGHTS_n` are kept as rig skin joint indices, weights on joints
/// outside the rig dropped.
fn append_mesh(
    mesh: &gltf::Mesh,
    transform: DMat4,
    skinned: Option<(&[Option<usize>], usize)>,
    buffers: &[&[u8]],
    raw: &mut RawScene,
) -> Result<Vec<(usize, usize)>, Failure> {
    let mirrored = transform.determinant() < 0.0;
    let mut appended = Vec::new();
    for primitive in mesh.primitives() {
        let what = format!("mesh {} primitive {}", mesh.index(), primitive.index());
        let mode = primitive.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            raw.skipped_primitives += 1;
            continue;
        }
        let positions_accessor = primitive
            .get(&Semantic::Positions)
            .ok_or_else(|| format!("{what} has no POSITION attribute"))?;
        gltf_accessor::check(
            &positions_accessor,
            buffers,
            &[DataType::F32],
            Dimensions::Vec3,
            &format!("POSITION of {what}"),
        )
        .map_err(|m| match positions_accessor.data_type() {
            DataType::F32 => m,
            _ => format!("{m} (quantized positions are not supported)"),
        })?;
        let reader = primitive.reader(|b| buffers.get(b.index()).copied());
        let positions: Vec<DVec3> = reader
            .read_positions()
            .ok_or_else(|| format!("POSITION of {what} has no data"))?
            .map(|p| transform.transform_point3(DVec3::from_array(p.map(f64::from))))
            .collect();
        let vertex_count = positions.len();
        let indices: Vec<u32> = match primitive.indices() {
            Some(accessor) => {
                gltf_accessor::check(
                    &accessor,
                    buffers,
                    &[DataType::U8, DataType::U16, DataType::U32],
                    Dimensions::Scalar,
                    &format!("indices of {what}"),
                )?;
                reader
                    .read_indices()
                    .ok_or_else(|| format!("indices of {what} have no data"))?
                    .into_u32()
                    .collect()
            }
            None => (0..vertex_count as u32).collect(),
        };
        let offset = raw.positions.len() as u32;
        for tri in assemble(mode, &indices) {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= vertex_count) {
                return Err(Failure::Mesh(MeshError::IndexOutOfRange {
                    triangle: raw.triangles.len(),
                    index: index as usize,
                    vertex_count,
                }));
            }
            let [a, b, c] = tri.map(|i| i + offset);
            raw.triangles
                .push(if mirrored { [a, c, b] } else { [a, b, c] });
        }
        raw.positions.extend(positions);
        let mut weights = vec![Vec::new(); vertex_count];
        if let Some((map, skin)) = skinned {
            for (vertex, list) in vertex_weights(&primitive, buffers, &what)?
                .into_iter()
                .enumerate()
                .take(vertex_count)
            {
                let mut mapped = Vec::with_capacity(list.len());
                for (j, w) in list {
                    let joint = map.get(usize::from(j)).ok_or_else(|| {
                        format!(
                            "a JOINTS attribute of {what} names joint {j} but skin {skin} has {} \
                             joints",
                            map.len()
                        )
                    })?;
                    if let Some(joint) = joint {
                        mapped.push((JointId(*joint), f64::from(w)));
                    }
                }
                weights[vertex] = mapped;
            }
        }
        raw.weights.extend(weights);
        appended.push((primitive.index(), vertex_count));
    }
    Ok(appended)
}

/// Triangles of a triangle-list, strip or fan index sequence, wound as the glTF spec defines.
fn assemble(mode: Mode, indices: &[u32]) -> Vec<[u32; 3]> {
    let strip_len = indices.len().saturating_sub(2);
    match mode {
        Mode::Triangles => indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect(),
        Mode::TriangleStrip => (0..strip_len)
            .map(|i| {
                let odd = i % 2;
                [indices[i], indices[i + 1 + odd], indices[i + 2 - odd]]
            })
            .collect(),
        Mode::TriangleFan => (0..strip_len)
            .map(|i| [indices[i + 1], indices[i + 2], indices[0]])
            .collect(),
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_keep_a_consistent_winding() {
        let indices = [0, 1, 2, 3, 4];
        assert_eq!(
            assemble(Mode::TriangleStrip, &indices),
            vec![[0, 1, 2], [1, 3, 2], [2, 3, 4]]
        );
        assert_eq!(
            assemble(Mode::TriangleFan, &indices),
            vec![[1, 2, 0], [2, 3, 0], [3, 4, 0]]
        );
        assert_eq!(assemble(Mode::Triangles, &indices), vec![[0, 1, 2]]);
        assert!(assemble(Mode::TriangleStrip, &[0, 1]).is_empty());
        assert!(assemble(Mode::Lines, &indices).is_empty());
    }
}

//! The user's own model, skinned: a binary glTF that keeps the input's meshes, primitives,
//! vertex order, attributes, materials, textures and images, adding JOINTS_0/WEIGHTS_0, the
//! joint nodes and the skin.

use super::frame::OutputFrame;
use super::gltf::{
    accessor, check_engine_rows, joint_nodes, link_children, pack_glb, skeleton_root, Binary,
    GltfOptions, ARRAY_BUFFER, FLOAT, UNSIGNED_SHORT,
};
use super::{check_skeleton, ExportError};
use crate::mesh::{SourceInstance, SourceModel};
use crate::skeleton::Skeleton;
use crate::skin::Skin;
use glam::DMat4;
use serde_json::{json, Value};
use std::collections::HashMap;

/// Top-level properties of the input document written back unchanged.
const KEPT: [&str; 8] = [
    "extensionsUsed",
    "extensionsRequired",
    "extensions",
    "extras",
    "materials",
    "textures",
    "samplers",
    "images",
];

/// The bytes of a skinned binary glTF 2.0 file of the user's model (`model`, from
/// [`crate::mesh::load_model`]) bound to `skeleton` by `skin`.
///
/// `skeleton` and `skin` belong to the welded mesh the model was loaded with (the skin has one
/// row per welded vertex); every vertex of every triangle primitive takes the weights of the
/// welded vertex it became (a vertex no face used is bound to joint 0). `frame` takes the
/// rig's frame (the loaded mesh's) to the file's: joints are written turned and scaled, and
/// the inverse bind matrices bring each instance's own vertex positions, which are written
/// back as they were, to the joint's frame through the transform the loader gave them, so the
/// rest pose draws the input exactly (in the file's frame).
///
/// The document keeps the input's materials, textures, samplers, images (embedded in the
/// binary chunk), extensions and the accessors and buffer views its meshes use (copied, other
/// ones dropped); primitives that are not triangles, the input's skins, animations, cameras
/// and other nodes are left out. Each mesh node becomes a root node named as in the input,
/// with a mesh of its own (a mesh that several nodes share is copied, since the weights differ)
/// and a skin (one per distinct loader transform) over every joint. Joint nodes come first,
/// as in [`glb_bytes`](super::glb_bytes). The same input gives the same bytes.
///
/// # Errors
/// [`ExportError::EmptySkeleton`], [`ExportError::InvalidSkeleton`],
/// [`ExportError::SizeMismatch`] when `skin` was made for another mesh,
/// [`ExportError::InvalidSource`] for a buffer view outside its buffer,
/// [`ExportError::NonFinite`] for a non-finite weight, [`ExportError::TooLarge`] beyond 4 GiB
/// or 65535 joints.
pub fn model_glb_bytes(
    model: &SourceModel,
    skeleton: &Skeleton,
    skin: &Skin,
    frame: &OutputFrame,
    options: &GltfOptions,
) -> Result<Vec<u8>, ExportError> {
    check_skeleton(skeleton)?;
    check_skin(model, skeleton, skin)?;
    let placed = frame.skeleton(skeleton);
    let source = &model.document;
    let mut copy = Copier::new(model);
    let mut accessors_out: Vec<Value> = Vec::new();
    let mut meshes = Vec::new();
    let mut nodes = joint_nodes(&placed);
    let joint_count = placed.len();
    let mut skins: Vec<(DMat4, Value)> = Vec::new();
    let mut mesh_nodes = Vec::new();
    for instance in &model.instances {
        let mut mesh = source["meshes"][instance.mesh].clone();
        let mut primitives = Vec::with_capacity(instance.primitives.len());
        for primitive in &instance.primitives {
            let original = &source["meshes"][instance.mesh]["primitives"][primitive.index];
            let mut out = copy.primitive(original, &mut accessors_out)?;
            let (joints, weights) = copy.skin_attributes(&primitive.vertices, skin);
            let count = primitive.vertices.len();
            accessors_out.push(accessor(joints, UNSIGNED_SHORT, count, "VEC4"));
            out["attributes"]["JOINTS_0"] = json!(accessors_out.len() - 1);
            accessors_out.push(accessor(weights, FLOAT, count, "VEC4"));
            out["attributes"]["WEIGHTS_0"] = json!(accessors_out.len() - 1);
            primitives.push(out);
        }
        mesh["primitives"] = Value::Array(primitives);
        meshes.push(mesh);
        let skin_index = skin_of(
            instance,
            &placed,
            frame,
            &mut skins,
            &mut copy,
            &mut accessors_out,
        );
        let mut node = json!({"mesh": meshes.len() - 1, "skin": skin_index});
        if let Some(name) = &instance.name {
            node["name"] = json!(name);
        }
        nodes.push(node);
        mesh_nodes.push(nodes.len() - 1);
    }
    let skeleton_root = skeleton_root(&mut nodes, &placed);
    link_children(&mut nodes, &placed, &vec![Vec::new(); joint_count]);
    let skins: Vec<Value> = skins
        .into_iter()
        .map(|(_, mut s)| {
            s["skeleton"] = json!(skeleton_root);
            s
        })
        .collect();

    let mut document = json!({
        "asset": asset(source, options),
        "scene": 0,
        "scenes": [{"name": "scene", "nodes": std::iter::once(skeleton_root).chain(mesh_nodes).collect::<Vec<_>>()}],
        "nodes": nodes,
        "meshes": meshes,
        "skins": skins,
    });
    for key in KEPT {
        if let Some(value) = source.get(key) {
            document[key] = value.clone();
        }
    }
    if let Some(images) = document.get_mut("images").and_then(Value::as_array_mut) {
        for image in images {
            if let Some(view) = image.get("bufferView").and_then(Value::as_u64) {
                image["bufferView"] = json!(copy.view(view as usize)?);
            }
        }
    }
    let Copier { bin, .. } = copy;
    let bin_len = bin.bytes.len();
    document["accessors"] = Value::Array(accessors_out);
    document["bufferViews"] = Value::Array(bin.views);
    document["buffers"] = json!([{"byteLength": bin_len}]);
    let json_bytes = serde_json::to_vec(&document).map_err(|e| ExportError::TooLarge {
        what: "the glTF document",
        format: "JSON",
        detail: e.to_string(),
    })?;
    pack_glb(json_bytes, bin.bytes)
}

/// `asset` of the output: the input's (copyright, version), generator naming skelfit.
fn asset(source: &Value, options: &GltfOptions) -> Value {
    let mut asset = source.get("asset").cloned().unwrap_or_else(|| json!({}));
    let generator = match source["asset"]["generator"].as_str() {
        Some(from) => format!("{} (from {from})", options.generator),
        None => options.generator.clone(),
    };
    asset["generator"] = json!(generator);
    asset["version"] = json!("2.0");
    if let Some(map) = asset.as_object_mut() {
        map.remove("minVersion");
    }
    asset
}

/// The skin of `instance`: an existing one made for the same loader transform, or a new one
/// whose inverse bind matrices take the instance's own positions to each joint's frame.
fn skin_of(
    instance: &SourceInstance,
    placed: &Skeleton,
    frame: &OutputFrame,
    skins: &mut Vec<(DMat4, Value)>,
    copy: &mut Copier,
    accessors: &mut Vec<Value>,
) -> usize {
    if let Some(k) = skins.iter().position(|(m, _)| *m == instance.transform) {
        return k;
    }
    let to_file = DMat4::from(frame.affine()) * instance.transform;
    let view = copy.bin.push(
        placed.joints.iter().flat_map(|j| {
            let m = DMat4::from(j.rest_transform().inverse()) * to_file;
            m.as_mat4()
                .to_cols_array()
                .into_iter()
                .flat_map(f32::to_le_bytes)
        }),
        None,
    );
    accessors.push(accessor(view, FLOAT, placed.len(), "MAT4"));
    skins.push((
        instance.transform,
        json!({
            "joints": (0..placed.len()).collect::<Vec<_>>(),
            "inverseBindMatrices": accessors.len() - 1,
            "name": "armature",
        }),
    ));
    skins.len() - 1
}

/// Checks that the skin has a row for every welded vertex the model's primitives name, with
/// finite non-negative weights on existing joints.
fn check_skin(model: &SourceModel, skeleton: &Skeleton, skin: &Skin) -> Result<(), ExportError> {
    let joint_count = skeleton.len();
    if joint_count > usize::from(u16::MAX) {
        return Err(ExportError::TooLarge {
            what: "the skeleton",
            format: "glTF",
            detail: format!("{joint_count} joints, JOINTS_0 holds at most 65535"),
        });
    }
    let rows = skin.engine.joints.len().min(skin.engine.weights.len());
    let needed = model
        .instances
        .iter()
        .flat_map(|i| &i.primitives)
        .flat_map(|p| p.vertices.iter().flatten())
        .map(|&w| w as usize + 1)
        .max()
        .unwrap_or(0);
    if rows < needed {
        return Err(ExportError::SizeMismatch {
            what: "the skin's engine weights",
            expected: needed,
            found: rows,
        });
    }
    check_engine_rows(skin, joint_count)
}

/// Copies the accessors and buffer views the output uses from the input into one binary
/// chunk, each once, remembering their new indices.
struct Copier<'a> {
    model: &'a SourceModel,
    bin: Binary,
    accessors: HashMap<usize, usize>,
    views: HashMap<usize, usize>,
}

impl<'a> Copier<'a> {
    fn new(model: &'a SourceModel) -> Self {
        Self {
            model,
            bin: Binary::default(),
            accessors: HashMap::new(),
            views: HashMap::new(),
        }
    }

    /// A primitive with its accessors copied, the input's JOINTS_n/WEIGHTS_n left out.
    fn primitive(&mut self, original: &Value, out: &mut Vec<Value>) -> Result<Value, ExportError> {
        let mut primitive = original.clone();
        let mut attributes = serde_json::Map::new();
        if let Some(map) = original["attributes"].as_object() {
            for (semantic, index) in map {
                if semantic.starts_with("JOINTS_") || semantic.starts_with("WEIGHTS_") {
                    continue;
                }
                attributes.insert(semantic.clone(), json!(self.accessor(index, out)?));
            }
        }
        primitive["attributes"] = Value::Object(attributes);
        if let Some(index) = original.get("indices") {
            primitive["indices"] = json!(self.accessor(index, out)?);
        }
        if let Some(targets) = original.get("targets").and_then(Value::as_array) {
            let mut copied = Vec::with_capacity(targets.len());
            for target in targets {
                let mut t = serde_json::Map::new();
                for (semantic, index) in target.as_object().into_iter().flatten() {
                    t.insert(semantic.clone(), json!(self.accessor(index, out)?));
                }
                copied.push(Value::Object(t));
            }
            primitive["targets"] = Value::Array(copied);
        }
        Ok(primitive)
    }

    /// The output index of input accessor `index` (a JSON number), copying it on first use.
    fn accessor(&mut self, index: &Value, out: &mut Vec<Value>) -> Result<usize, ExportError> {
        let index = index
            .as_u64()
            .ok_or_else(|| invalid(format!("accessor index {index}")))?
            as usize;
        if let Some(&done) = self.accessors.get(&index) {
            return Ok(done);
        }
        let mut copied = self.model.document["accessors"]
            .get(index)
            .cloned()
            .ok_or_else(|| invalid(format!("accessor {index} does not exist")))?;
        if let Some(view) = copied.get("bufferView").and_then(Value::as_u64) {
            copied["bufferView"] = json!(self.view(view as usize)?);
        }
        for part in ["indices", "values"] {
            if let Some(view) = copied["sparse"][part]["bufferView"].as_u64() {
                copied["sparse"][part]["bufferView"] = json!(self.view(view as usize)?);
            }
        }
        out.push(copied);
        self.accessors.insert(index, out.len() - 1);
        Ok(out.len() - 1)
    }

    /// The output index of input buffer view `index`, copying its bytes on first use (at the
    /// same offset modulo 4, so the accessors in it stay aligned).
    fn view(&mut self, index: usize) -> Result<usize, ExportError> {
        if let Some(&done) = self.views.get(&index) {
            return Ok(done);
        }
        let view = self.model.document["bufferViews"]
            .get(index)
            .ok_or_else(|| invalid(format!("buffer view {index} does not exist")))?;
        let buffer = view["buffer"].as_u64().unwrap_or(u64::MAX) as usize;
        let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
        let length = view["byteLength"].as_u64().unwrap_or(0) as usize;
        let data = self
            .model
            .buffers
            .get(buffer)
            .and_then(|b| b.get(offset..offset.checked_add(length)?))
            .ok_or_else(|| {
                invalid(format!(
                    "buffer view {index} (bytes {offset}..+{length} of buffer {buffer}) lies outside its buffer"
                ))
            })?;
        while self.bin.bytes.len() % 4 != offset % 4 {
            self.bin.bytes.push(0);
        }
        let start = self.bin.bytes.len();
        self.bin.bytes.extend_from_slice(data);
        let mut copied = view.clone();
        copied["buffer"] = json!(0);
        copied["byteOffset"] = json!(start);
        self.bin.views.push(copied);
        let new = self.bin.views.len() - 1;
        self.views.insert(index, new);
        Ok(new)
    }

    /// JOINTS_0 (`u16`) and WEIGHTS_0 (`f32`) views of a primitive whose vertex `v` became
    /// welded vertex `vertices[v]` (joint 0 with weight 1 for `None`).
    fn skin_attributes(&mut self, vertices: &[Option<u32>], skin: &Skin) -> (usize, usize) {
        let rows: Vec<([u16; 4], [f32; 4])> = vertices
            .iter()
            .map(|w| match w {
                Some(w) => (
                    skin.engine.joints[*w as usize],
                    skin.engine.weights[*w as usize],
                ),
                None => ([0; 4], [1.0, 0.0, 0.0, 0.0]),
            })
            .collect();
        let joints = self.bin.push(
            rows.iter()
                .flat_map(|(j, _)| j.iter().flat_map(|x| x.to_le_bytes())),
            Some(ARRAY_BUFFER),
        );
        let weights = self.bin.push(
            rows.iter()
                .flat_map(|(_, w)| w.iter().flat_map(|x| x.to_le_bytes())),
            Some(ARRAY_BUFFER),
        );
        (joints, weights)
    }
}

/// An [`ExportError::InvalidSource`].
fn invalid(message: String) -> ExportError {
    ExportError::InvalidSource { message }
}

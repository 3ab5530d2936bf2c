//! The [`SourceModel`] of an OBJ file: a glTF document with a primitive per material, a vertex
//! per distinct position/UV/normal corner, and the MTL materials with their images.

use super::model::{image_file, ModelWarning, SourceInstance, SourceModel, SourcePrimitive};
use super::mtl::{read_libraries, MtlMaterial};
use super::obj::{parse_obj, welded, ParsedObj};
use super::{Mesh, MeshError};
use crate::math::{fast_map, FastMap};
use glam::DMat4;
use serde_json::{json, Value};
use std::collections::HashMap;
use std::path::Path;

/// No index (a corner without UV or normal, a triangle without material).
const NONE: u32 = u32::MAX;

/// Reads an OBJ file like [`load_obj`](super::load_obj) and builds its glTF model: one
/// primitive per `usemtl` material (in order of first use; faces before any `usemtl` form a
/// primitive without material), one vertex per distinct `v/vt/vn` corner (in order of first
/// use), `POSITION`, `NORMAL` (when every corner of the primitive has one) and `TEXCOORD_0`
/// (when some corner has one; `v` flipped to glTF's top-left origin, missing ones 0). The
/// `mtllib` materials become glTF materials: `Kd` → `baseColorFactor`, `d`/`Tr` → its alpha
/// (blended below 1), `map_Kd` → `baseColorTexture` with the image embedded, `Pm`/`Pr` →
/// metallic/roughness (default 0 and 1). Material files and images are read only inside the
/// OBJ's folder (see [`load_model`](super::load_model)); what cannot be read is left out with
/// a warning.
///
/// # Errors
/// As [`load_obj`](super::load_obj).
pub(super) fn load_obj_model(path: &Path) -> Result<(Mesh, SourceModel), MeshError> {
    let parsed = parse_obj(path)?;
    // The mesh is welded on one core while the model is built on the other: only the
    // primitives' map onto the welded vertices needs both.
    let (mesh, model) = rayon::join(|| welded(path, &parsed), || model_of(&parsed, path));
    let (mesh, source) = mesh?;
    let (mut model, corner_keys) = model;
    for (primitive, keys) in model.instances[0].primitives.iter_mut().zip(corner_keys) {
        primitive.vertices = keys.iter().map(|k| source[k[0] as usize]).collect();
    }
    Ok((mesh, model))
}

/// The glTF model of the parsed OBJ file at `path` (see [`load_obj_model`]) with every
/// primitive's `vertices` still empty, and each primitive's distinct `v/vt/vn` corners (file
/// indices) in vertex order.
fn model_of(parsed: &ParsedObj, path: &Path) -> (SourceModel, Vec<Vec<[u32; 3]>>) {
    let mut warnings = Vec::new();
    let library = read_libraries(&parsed.libraries, path, &mut warnings);
    let mut bin: Vec<u8> = Vec::new();
    let mut views: Vec<Value> = Vec::new();
    let mut accessors: Vec<Value> = Vec::new();
    let mut images = Images::default();
    let materials: Vec<Value> = parsed
        .materials
        .iter()
        .map(|name| {
            let found = library.iter().find(|m| m.name == *name);
            if found.is_none() {
                warnings.push(ModelWarning::MaterialUndefined { name: name.clone() });
            }
            material(
                name,
                found,
                path,
                &mut images,
                &mut bin,
                &mut views,
                &mut warnings,
            )
        })
        .collect();

    let mut groups: Vec<u32> = Vec::new();
    for &m in &parsed.triangle_materials {
        if !groups.contains(&m) {
            groups.push(m);
        }
    }
    let mut primitives_json = Vec::new();
    let mut primitives = Vec::new();
    let mut corner_keys = Vec::new();
    for (index, &group) in groups.iter().enumerate() {
        let (json, keys) = primitive(parsed, group, &mut bin, &mut views, &mut accessors);
        primitives_json.push(json);
        primitives.push(SourcePrimitive {
            index,
            vertices: Vec::new(),
        });
        corner_keys.push(keys);
    }
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "mesh".into());
    let mut document = json!({
        "asset": {"version": "2.0", "generator": "OBJ"},
        "meshes": [{"name": name, "primitives": primitives_json}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len()}],
    });
    if !materials.is_empty() {
        document["materials"] = Value::Array(materials);
    }
    if !images.list.is_empty() {
        document["images"] = Value::Array(images.list);
        document["textures"] = Value::Array(images.textures);
    }
    (
        SourceModel {
            document,
            buffers: vec![bin],
            instances: vec![SourceInstance {
                name: Some(name),
                mesh: 0,
                transform: DMat4::IDENTITY,
                primitives,
            }],
            warnings,
        },
        corner_keys,
    )
}

/// Images embedded so far (one per file name) and a texture for each.
#[derive(Default)]
struct Images {
    list: Vec<Value>,
    textures: Vec<Value>,
    by_name: HashMap<String, usize>,
}

/// A glTF material from an MTL one (white when `found` is `None`).
fn material(
    name: &str,
    found: Option<&MtlMaterial>,
    obj: &Path,
    images: &mut Images,
    bin: &mut Vec<u8>,
    views: &mut Vec<Value>,
    warnings: &mut Vec<ModelWarning>,
) -> Value {
    let default = MtlMaterial::default();
    let m = found.unwrap_or(&default);
    let colour = m.diffuse.unwrap_or([1.0; 3]);
    let alpha = m.alpha.unwrap_or(1.0).clamp(0.0, 1.0);
    let mut pbr = json!({
        "baseColorFactor": [colour[0], colour[1], colour[2], alpha],
        "metallicFactor": m.metallic.unwrap_or(0.0).clamp(0.0, 1.0),
        "roughnessFactor": m.roughness.unwrap_or(1.0).clamp(0.0, 1.0),
    });
    if let Some(file) = &m.diffuse_map {
        let texture = match images.by_name.get(file) {
            Some(&t) => Some(t),
            None => match image_file(file, obj) {
                Ok((data, mime)) => {
                    let view = push_view(bin, views, &data, None);
                    images
                        .list
                        .push(json!({"bufferView": view, "mimeType": mime, "name": file}));
                    images
                        .textures
                        .push(json!({"source": images.list.len() - 1}));
                    images
                        .by_name
                        .insert(file.clone(), images.textures.len() - 1);
                    Some(images.textures.len() - 1)
                }
                Err(reason) => {
                    warnings.push(ModelWarning::TextureUnreadable {
                        material: name.to_string(),
                        file: file.clone(),
                        reason,
                    });
                    None
                }
            },
        };
        if let Some(t) = texture {
            pbr["baseColorTexture"] = json!({"index": t});
        }
    }
    let mut out = json!({"name": name, "pbrMetallicRoughness": pbr});
    if alpha < 1.0 {
        out["alphaMode"] = json!("BLEND");
    }
    out
}

/// The primitive of the triangles with material `group`: its JSON (accessors appended) and the
/// `v/vt/vn` corner (file indices) of each of its vertices.
fn primitive(
    parsed: &ParsedObj,
    group: u32,
    bin: &mut Vec<u8>,
    views: &mut Vec<Value>,
    accessors: &mut Vec<Value>,
) -> (Value, Vec<[u32; 3]>) {
    let corners = 3 * parsed
        .triangle_materials
        .iter()
        .filter(|&&m| m == group)
        .count();
    let mut corner_vertex: FastMap<[u32; 3], u32> = fast_map(corners);
    let mut keys: Vec<[u32; 3]> = Vec::new();
    let mut indices: Vec<u32> = Vec::new();
    for (t, _) in parsed
        .triangle_materials
        .iter()
        .enumerate()
        .filter(|(_, &m)| m == group)
    {
        for c in 3 * t..3 * t + 3 {
            let key = [
                parsed.corners[c],
                parsed.corner_uvs[c],
                parsed.corner_normals[c],
            ];
            let next = keys.len() as u32;
            let v = *corner_vertex.entry(key).or_insert_with(|| {
                keys.push(key);
                next
            });
            indices.push(v);
        }
    }
    let count = keys.len();
    let positions: Vec<[f32; 3]> = keys
        .iter()
        .map(|k| parsed.coordinates[k[0] as usize].as_vec3().to_array())
        .collect();
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for p in &positions {
        for a in 0..3 {
            min[a] = min[a].min(p[a]);
            max[a] = max[a].max(p[a]);
        }
    }
    let mut attributes = serde_json::Map::new();
    let view = push_view(
        bin,
        views,
        &f32_bytes(positions.iter().flatten()),
        Some(34962),
    );
    accessors.push(
        json!({"bufferView": view, "componentType": 5126, "count": count,
        "type": "VEC3", "min": min, "max": max}),
    );
    attributes.insert("POSITION".into(), json!(accessors.len() - 1));
    if keys.iter().all(|k| k[2] != NONE) {
        let normals: Vec<[f32; 3]> = keys
            .iter()
            .map(|k| {
                let n = parsed.normals[k[2] as usize];
                n.try_normalize()
                    .unwrap_or(glam::DVec3::Y)
                    .as_vec3()
                    .to_array()
            })
            .collect();
        let view = push_view(
            bin,
            views,
            &f32_bytes(normals.iter().flatten()),
            Some(34962),
        );
        accessors.push(
            json!({"bufferView": view, "componentType": 5126, "count": count, "type": "VEC3"}),
        );
        attributes.insert("NORMAL".into(), json!(accessors.len() - 1));
    }
    if keys.iter().any(|k| k[1] != NONE) {
        let uvs: Vec<[f32; 2]> = keys
            .iter()
            .map(|k| match parsed.uvs.get(k[1] as usize) {
                Some(&[u, v]) => [u as f32, (1.0 - v) as f32],
                None => [0.0, 0.0],
            })
            .collect();
        let view = push_view(bin, views, &f32_bytes(uvs.iter().flatten()), Some(34962));
        accessors.push(
            json!({"bufferView": view, "componentType": 5126, "count": count, "type": "VEC2"}),
        );
        attributes.insert("TEXCOORD_0".into(), json!(accessors.len() - 1));
    }
    let index_bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
    let view = push_view(bin, views, &index_bytes, Some(34963));
    accessors.push(json!({"bufferView": view, "componentType": 5125, "count": indices.len(), "type": "SCALAR"}));
    let mut json = json!({"attributes": attributes, "indices": accessors.len() - 1, "mode": 4});
    if group != NONE {
        json["material"] = json!(group);
    }
    (json, keys)
}

/// Little-endian bytes of `f32` values.
fn f32_bytes<'a>(values: impl Iterator<Item = &'a f32>) -> Vec<u8> {
    values.flat_map(|x| x.to_le_bytes()).collect()
}

/// Appends `data` (4-byte aligned) as a buffer view of buffer 0; returns its index.
fn push_view(bin: &mut Vec<u8>, views: &mut Vec<Value>, data: &[u8], target: Option<u32>) -> usize {
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let mut view = json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": data.len()});
    if let Some(target) = target {
        view["target"] = json!(target);
    }
    bin.extend_from_slice(data);
    views.push(view);
    views.len() - 1
}

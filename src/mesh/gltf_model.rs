//! The [`SourceModel`] of a glTF/GLB file: its own JSON and buffers, external images embedded.

use super::gltf::read_welded;
use super::load::parse_error;
use super::model::{
    image_file, ModelWarning, SourceInstance, SourceModel, SourcePrimitive, PLACEHOLDER_PNG,
};
use super::{Mesh, MeshError};
use serde_json::{json, Value};
use std::path::Path;

/// Reads a glTF/GLB file like [`load_gltf`](super::load_gltf) and keeps its document for the
/// output: the JSON as written, the buffers, and every mesh node with the map of its
/// primitives' vertices onto the welded mesh. The input's skins and animations are removed
/// (the rig replaces its skeleton), with a warning; external images are embedded (see
/// [`load_model`](super::load_model)).
///
/// # Errors
/// As [`load_gltf`](super::load_gltf).
pub(super) fn load_gltf_model(path: &Path) -> Result<(Mesh, SourceModel), MeshError> {
    let (bytes, raw, mesh, source_vertices) = read_welded(path)?;
    let json_bytes: Vec<u8> = if bytes.starts_with(b"glTF") {
        gltf::Glb::from_slice(&bytes)
            .map_err(|e| parse_error(path, "gltf", e.to_string()))?
            .json
            .into_owned()
    } else {
        bytes
    };
    let mut document: Value =
        serde_json::from_slice(&json_bytes).map_err(|e| parse_error(path, "gltf", e))?;
    let mut buffers = raw.buffers;
    let mut warnings = Vec::new();
    for (key, why) in [
        (
            "animations",
            "they move the input's own skeleton, which the rig replaces",
        ),
        ("skins", "the rig's skin replaces them"),
    ] {
        let count = document
            .get(key)
            .and_then(Value::as_array)
            .map_or(0, Vec::len);
        if count > 0 {
            warnings.push(ModelWarning::LeftOut {
                count,
                what: key,
                why,
            });
        }
        if let Some(map) = document.as_object_mut() {
            map.remove(key);
        }
    }
    embed_images(&mut document, &mut buffers, path, &mut warnings);

    let mut next = 0usize;
    let mut instances = Vec::with_capacity(raw.instances.len());
    for instance in &raw.instances {
        let node = &document["nodes"][instance.node];
        let primitives = instance
            .primitives
            .iter()
            .map(|&(index, count)| {
                let vertices = source_vertices[next..next + count].to_vec();
                next += count;
                SourcePrimitive { index, vertices }
            })
            .collect::<Vec<_>>();
        let total = document["meshes"][instance.mesh]["primitives"]
            .as_array()
            .map_or(0, Vec::len);
        if total > primitives.len() {
            warnings.push(ModelWarning::NotTriangles {
                mesh: instance.mesh,
                primitives: total - primitives.len(),
            });
        }
        instances.push(SourceInstance {
            name: node["name"].as_str().map(str::to_string),
            mesh: instance.mesh,
            transform: instance.transform,
            primitives,
        });
    }
    Ok((
        mesh,
        SourceModel {
            document,
            buffers,
            instances,
            warnings,
        },
    ))
}

/// Replaces every image `uri` that is not a `data:` URI by a buffer view of its bytes, read
/// safely from the input's folder; a refused or unreadable image becomes a 1×1 white PNG,
/// with a warning.
fn embed_images(
    document: &mut Value,
    buffers: &mut Vec<Vec<u8>>,
    input: &Path,
    warnings: &mut Vec<ModelWarning>,
) {
    let Some(images) = document.get("images").and_then(Value::as_array).cloned() else {
        return;
    };
    let mut views: Vec<Value> = document
        .get("bufferViews")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    let mut changed = false;
    let mut out = Vec::with_capacity(images.len());
    for (i, mut image) in images.into_iter().enumerate() {
        let uri = image.get("uri").and_then(Value::as_str).map(str::to_string);
        if let Some(uri) = uri.filter(|u| !u.starts_with("data:")) {
            let (data, mime) = image_file(&uri, input).unwrap_or_else(|reason| {
                warnings.push(ModelWarning::ImageUnreadable {
                    image: i,
                    uri: uri.clone(),
                    reason,
                });
                (PLACEHOLDER_PNG.to_vec(), "image/png")
            });
            views.push(json!({"buffer": buffers.len(), "byteOffset": 0, "byteLength": data.len()}));
            buffers.push(data);
            if let Some(map) = image.as_object_mut() {
                map.remove("uri");
                map.insert("bufferView".into(), json!(views.len() - 1));
                map.insert("mimeType".into(), json!(mime));
            }
            changed = true;
        }
        out.push(image);
    }
    if changed {
        document["images"] = Value::Array(out);
        document["bufferViews"] = Value::Array(views);
    }
}

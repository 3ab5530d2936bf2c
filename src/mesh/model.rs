//! What a mesh file held beyond its triangles (primitives, vertex order, UVs, normals, colours,
//! materials, textures), kept so that the rigged output gives it back.

use super::{Mesh, MeshError};
use glam::DMat4;
use std::path::Path;

/// The user's model as a glTF document, with, for every vertex of every triangle primitive,
/// the vertex of the welded [`Mesh`] it became.
///
/// For a glTF/GLB input the document is the file's own JSON; for an OBJ input it is built from
/// the OBJ and its MTL materials (one primitive per material, a vertex per distinct
/// position/UV/normal corner). The writer ([`crate::export::model_glb_bytes`]) keeps the meshes,
/// primitives, vertex order, attributes, materials, textures and images, and adds the skin.
#[derive(Debug, Clone, PartialEq)]
pub struct SourceModel {
    /// The glTF 2.0 JSON document. Every image refers to a buffer view or holds a `data:` URI
    /// (external image files were read into `buffers`).
    pub document: serde_json::Value,
    /// The data of every buffer of `document`, in buffer order.
    pub buffers: Vec<Vec<u8>>,
    /// Every mesh node of the scene, in the loader's reading order.
    pub instances: Vec<SourceInstance>,
    /// What could not be kept (an image that could not be read, primitives that are not
    /// triangles, the input's skins and animations).
    pub warnings: Vec<ModelWarning>,
}

/// A mesh node of the input: its mesh and how its vertices map onto the welded mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct SourceInstance {
    /// The node's name, if it has one.
    pub name: Option<String>,
    /// Index of its mesh in `document["meshes"]`.
    pub mesh: usize,
    /// The transform the loader gave the mesh's own (local) positions: local → frame of the
    /// welded [`Mesh`] (the node's world transform, or a skinned mesh's bind pose).
    pub transform: DMat4,
    /// The mesh's triangle primitives (others are dropped on output).
    pub primitives: Vec<SourcePrimitive>,
}

/// A triangle primitive of an instance.
#[derive(Debug, Clone, PartialEq)]
pub struct SourcePrimitive {
    /// Index of the primitive in its mesh's `primitives`.
    pub index: usize,
    /// For each vertex of the primitive, the welded mesh vertex it became (`None`: used by no
    /// face that survived welding).
    pub vertices: Vec<Option<u32>>,
}

/// Reads a mesh like [`load`](super::load) and, for glTF/GLB and OBJ files, the
/// [`SourceModel`] that lets the output keep what the file held; `None` for STL and PLY.
///
/// External images (a `.gltf`'s image URIs, an MTL's `map_Kd`) are read only from relative
/// paths to regular files inside the input's own folder; an image that is refused or missing
/// is replaced by a 1×1 white placeholder, with a warning in [`SourceModel::warnings`].
///
/// # Errors
/// As [`load`](super::load).
pub fn load_model(path: &Path) -> Result<(Mesh, Option<SourceModel>), MeshError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("gltf") | Some("glb") => {
            super::gltf_model::load_gltf_model(path).map(|(m, s)| (m, Some(s)))
        }
        Some("obj") => super::obj_model::load_obj_model(path).map(|(m, s)| (m, Some(s))),
        _ => super::load(path).map(|m| (m, None)),
    }
}

/// A 1×1 white PNG, standing in for an image that could not be embedded.
pub(super) const PLACEHOLDER_PNG: [u8; 69] = [
    137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 73, 72, 68, 82, 0, 0, 0, 1, 0, 0, 0, 1, 8, 2, 0,
    0, 0, 144, 119, 83, 222, 0, 0, 0, 12, 73, 68, 65, 84, 120, 156, 99, 248, 255, 255, 63, 0, 5,
    254, 2, 254, 13, 239, 70, 184, 0, 0, 0, 0, 73, 69, 78, 68, 174, 66, 96, 130,
];

/// Largest image file read from the input's folder, bytes.
pub(super) const MAX_IMAGE_BYTES: u64 = 256 << 20;

/// The MIME type of image bytes (PNG, JPEG, WebP, KTX2 by signature), else from the file
/// name's extension; `None` when neither says.
pub(super) fn image_mime_type(bytes: &[u8], name: &str) -> Option<&'static str> {
    if bytes.starts_with(&[0x89, b'P', b'N', b'G']) {
        return Some("image/png");
    }
    if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
        return Some("image/jpeg");
    }
    if bytes.len() >= 12 && &bytes[0..4] == b"RIFF" && &bytes[8..12] == b"WEBP" {
        return Some("image/webp");
    }
    if bytes.starts_with(&[0xAB, b'K', b'T', b'X', b' ', b'2', b'0']) {
        return Some("image/ktx2");
    }
    let lower = name.to_ascii_lowercase();
    [
        (".png", "image/png"),
        (".jpg", "image/jpeg"),
        (".jpeg", "image/jpeg"),
        (".webp", "image/webp"),
        (".ktx2", "image/ktx2"),
    ]
    .into_iter()
    .find(|(ext, _)| lower.ends_with(ext))
    .map(|(_, mime)| mime)
}

/// The bytes and MIME type of an image file named by a relative `uri` inside `folder` of the
/// input file, read without trusting the name (see [`super::gltf_buffers::resolve_file`]); an
/// explanation when it is refused, missing, too large or not an image glTF allows.
pub(super) fn image_file(uri: &str, input: &Path) -> Result<(Vec<u8>, &'static str), String> {
    let folder = super::gltf_buffers::folder_of(input)?;
    let target = super::gltf_buffers::resolve_file(uri, &folder)?;
    let size = std::fs::metadata(&target).map_or(0, |m| m.len());
    if size > MAX_IMAGE_BYTES {
        return Err(format!(
            "is refused: {size} bytes, more than the {MAX_IMAGE_BYTES} an image may have"
        ));
    }
    let data = super::gltf_buffers::read_at_most(&target, MAX_IMAGE_BYTES)?;
    let mime = image_mime_type(&data, uri).ok_or_else(|| {
        "is not a PNG, JPEG, WebP or KTX2 image, which glTF needs (convert it)".to_string()
    })?;
    Ok((data, mime))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placeholder_is_a_png() {
        assert_eq!(image_mime_type(&PLACEHOLDER_PNG, ""), Some("image/png"));
        assert_eq!(image_mime_type(b"xx", "a.JPG"), Some("image/jpeg"));
        assert_eq!(image_mime_type(b"xx", "a.tga"), None);
    }
}

/// What [`load_model`](super::load_model) could not keep of the user's file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ModelWarning {
    /// Top-level glTF objects dropped because the rig replaces them (`animations`, `skins`).
    LeftOut {
        /// How many.
        count: usize,
        /// The glTF key.
        what: &'static str,
        /// Why.
        why: &'static str,
    },
    /// Primitives of points or lines (only triangles are skinned).
    NotTriangles {
        /// The glTF mesh index.
        mesh: usize,
        /// How many primitives.
        primitives: usize,
    },
    /// An image file that could not be read; a 1×1 white placeholder stands in for it.
    ImageUnreadable {
        /// The glTF image index.
        image: usize,
        /// Its URI.
        uri: String,
        /// Why it could not be read.
        reason: String,
    },
    /// An OBJ material used but defined by no material library; written white.
    MaterialUndefined {
        /// The material's name.
        name: String,
    },
    /// A material's `map_Kd` image that could not be read; the material has no texture.
    TextureUnreadable {
        /// The material's name.
        material: String,
        /// The image file as written in the MTL.
        file: String,
        /// Why it could not be read.
        reason: String,
    },
    /// A material library (`mtllib`) that could not be read; its materials are written white.
    LibraryUnreadable {
        /// The library's file name.
        name: String,
        /// Why it could not be read.
        reason: String,
    },
}

impl ModelWarning {
    /// A stable snake_case id.
    pub fn code(&self) -> &'static str {
        match self {
            Self::LeftOut { .. } => "left_out",
            Self::NotTriangles { .. } => "not_triangles",
            Self::ImageUnreadable { .. } => "image_unreadable",
            Self::MaterialUndefined { .. } => "material_undefined",
            Self::TextureUnreadable { .. } => "texture_unreadable",
            Self::LibraryUnreadable { .. } => "library_unreadable",
        }
    }

    /// How much it matters: what the rig replaces is worth knowing; a lost image, texture or
    /// material degrades the output.
    pub fn severity(&self) -> crate::warning::Severity {
        match self {
            Self::LeftOut { .. } | Self::NotTriangles { .. } => crate::warning::Severity::Info,
            _ => crate::warning::Severity::Degraded,
        }
    }
}

impl std::fmt::Display for ModelWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::LeftOut { count, what, why } => {
                write!(f, "the input's {count} {what} were left out: {why}")
            }
            Self::NotTriangles { mesh, primitives } => write!(
                f,
                "mesh {mesh}: {primitives} primitives of points or lines were left out (only \
                 triangles are skinned)"
            ),
            Self::ImageUnreadable { image, uri, reason } => write!(
                f,
                "image {image} (uri \"{uri}\") {reason}; a 1x1 white placeholder stands in for it"
            ),
            Self::MaterialUndefined { name } => write!(
                f,
                "material {name:?} is used but no material library defines it; it is written \
                 white"
            ),
            Self::TextureUnreadable {
                material,
                file,
                reason,
            } => write!(
                f,
                "material {material:?}: image \"{file}\" {reason}; the material is written \
                 without it"
            ),
            Self::LibraryUnreadable { name, reason } => write!(
                f,
                "material library \"{name}\" {reason}; its materials are written white"
            ),
        }
    }
}

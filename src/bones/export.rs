//! Writing bones: OBJ of all bones at the rest pose, GLB of the armature with every bone as a
//! child node of its joint (so it poses with the skeleton).

use super::Bones;
use crate::export::{glb_bytes_with, write_obj, Attachment, ExportError, GltfOptions};
use crate::mesh::Mesh;
use crate::skeleton::Skeleton;
use crate::skin::Skin;
use std::path::Path;

impl Bones {
    /// One [`Attachment`] per bone: its mesh in its joint's rest local frame, named after the
    /// bone. Pass them to [`glb_bytes_with`] beside a skinned mesh for a rig with bones.
    pub fn attachments(&self, skeleton: &Skeleton) -> Vec<Attachment> {
        self.bones
            .iter()
            .filter(|b| !b.mesh.triangles.is_empty())
            .map(|b| Attachment {
                joint: b.joint,
                name: b.name.clone(),
                mesh: b.local_mesh(skeleton),
            })
            .collect()
    }
}

/// GLB bytes of the armature of `skeleton` with `bones` as child nodes of their joints, and,
/// when given, the skinned mesh.
///
/// # Errors
/// As [`glb_bytes_with`].
pub fn bones_glb_bytes(
    skeleton: &Skeleton,
    bones: &Bones,
    skinned: Option<(&Mesh, &Skin)>,
    options: &GltfOptions,
) -> Result<Vec<u8>, ExportError> {
    glb_bytes_with(skinned, skeleton, &bones.attachments(skeleton), options)
}

/// Writes [`bones_glb_bytes`] to `path` atomically.
///
/// # Errors
/// As [`glb_bytes_with`], and [`ExportError::Io`] when the file cannot be written.
pub fn write_bones_glb(
    path: &Path,
    skeleton: &Skeleton,
    bones: &Bones,
    skinned: Option<(&Mesh, &Skin)>,
    options: &GltfOptions,
) -> Result<(), ExportError> {
    let bytes = bones_glb_bytes(skeleton, bones, skinned, options)?;
    crate::output::write_atomic(path, &bytes).map_err(|cause| ExportError::Io {
        path: path.to_owned(),
        cause,
    })
}

/// Writes every bone, merged at the rest pose in the mesh frame, as OBJ.
///
/// # Errors
/// [`ExportError::Io`] when the file cannot be written.
pub fn write_bones_obj(path: &Path, bones: &Bones) -> Result<(), ExportError> {
    write_obj(path, &bones.world_mesh())
}

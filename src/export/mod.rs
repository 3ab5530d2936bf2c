//! Export: files a person can open in Blender or a game engine.
//!
//! - [`glb_bytes`] / [`write_glb`]: a skinned binary glTF 2.0 file (mesh, engine weights,
//!   armature with rest frames, inverse bind matrices) that the Khronos validator accepts.
//! - [`glb_bytes_with`]: the same with rigid [`Attachment`]s (bone meshes) as child nodes of
//!   joints, with or without the skinned mesh.
//! - [`gltf_text_from_glb`]: the `.gltf` (JSON, data embedded) form of any of these GLBs.
//! - [`model_glb_bytes`]: the user's own glTF or OBJ model ([`crate::mesh::SourceModel`]) with
//!   its primitives, vertex order, UVs, materials and textures, skinned.
//! - [`OutputFrame`]: the turn and scale from the mesh's frame to the file's (glTF's +Y up,
//!   +Z forward, metres).
//! - [`skeleton_json`] / [`write_skeleton_json`]: skelfit's own `skelfit-skeleton-v1` JSON,
//!   read back by [`crate::eval::load_skeleton`].
//! - [`bvh_text`] / [`write_bvh`]: a BVH hierarchy with one rest frame.
//! - [`obj_text`] / [`write_obj`]: a (posed) mesh as OBJ.
//!
//! Every writer produces the same bytes for the same input (fixed float formatting, no
//! timestamps, no hash-map order) and writes through [`crate::output::write_atomic`], so a
//! failed export never leaves a half-written file. Outputs are in the input mesh's units and
//! frame.

mod bvh;
mod error;
mod frame;
mod gltf;
mod gltf_text;
mod json;
mod model;
mod obj;

pub use bvh::{bvh_text, write_bvh, BvhOptions};
pub use error::ExportError;
use error::{check_skeleton, io_error};
pub use frame::{OutputFrame, Units, UnitsGuess};
pub use gltf::{glb_bytes, glb_bytes_with, write_glb, Attachment, GltfOptions, FOREST_ROOT_NAME};
pub use gltf_text::gltf_text_from_glb;
pub use json::{skeleton_json, write_skeleton_json, JsonOptions, SKELETON_FORMAT};
pub use model::model_glb_bytes;
pub use obj::{obj_text, write_obj};

//! The crate error: one enum per stage boundary, wrapped here with `#[from]`.

use thiserror::Error;

/// Any error skelfit's library returns. Each variant wraps the error enum of one stage; its
/// message names the problem and what to do about it.
#[derive(Debug, Error)]
pub enum Error {
    /// Reading, parsing or validating an input mesh failed.
    #[error(transparent)]
    Mesh(#[from] crate::mesh::MeshError),
    /// Voxelizing a mesh failed.
    #[error(transparent)]
    Voxel(#[from] crate::voxel::VoxelError),
    /// Building the discrete medial surface failed.
    #[error(transparent)]
    Medial(#[from] crate::medial::MedialError),
    /// Growing the path tree failed.
    #[error(transparent)]
    Paths(#[from] crate::paths::PathError),
    /// Building the general control skeleton failed.
    #[error(transparent)]
    General(#[from] crate::general::GeneralError),
    /// Building the level graph or labelling body parts failed.
    #[error(transparent)]
    Anatomy(#[from] crate::anatomy::AnatomyError),
    /// Loading or comparing skeletons failed.
    #[error(transparent)]
    Eval(#[from] crate::eval::EvalError),
    /// Skinning a mesh to a skeleton failed.
    #[error(transparent)]
    Skin(#[from] crate::skin::SkinError),
    /// Writing a rig (glTF, BVH, JSON, OBJ) failed.
    #[error(transparent)]
    Export(#[from] crate::export::ExportError),
    /// Loading or validating a template, or applying a naming preset, failed.
    #[error(transparent)]
    Template(#[from] crate::template::TemplateError),
    /// Fitting an anatomical skeleton failed.
    #[error(transparent)]
    Fit(#[from] crate::fit::FitError),
    /// Refining a humanoid skeleton by slicing failed.
    #[error(transparent)]
    Refine(#[from] crate::refine::RefineError),
    /// Generating bone meshes failed.
    #[error(transparent)]
    Bones(#[from] crate::bones::BoneError),
    /// Reading an outline or building its skeleton or mesh failed.
    #[error(transparent)]
    Outline(#[from] crate::outline::OutlineError),
    /// A level-of-detail operation on a skeleton failed.
    #[error(transparent)]
    Lod(#[from] crate::lod::LodError),
    /// Writing a report or picture failed.
    #[error(transparent)]
    Report(#[from] crate::report::ReportError),
    /// Options of several stages are invalid: each stage's error.
    #[error("{}", .0.iter().map(ToString::to_string).collect::<Vec<_>>().join("; "))]
    Options(Vec<Error>),
}

/// `Result` with the crate [`Error`](enum@Error).
pub type Result<T, E = Error> = std::result::Result<T, E>;

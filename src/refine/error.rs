//! Errors of the refinement stage.

use glam::DVec3;

/// Why a skeleton could not be refined at all. Problems with single joints are warnings in
/// [`super::Refinement::warnings`] instead.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RefineError {
    /// Options out of range (every one).
    #[error("refine options: {0}")]
    InvalidOptions(#[from] crate::options::OptionProblems),
    /// The mesh has no triangles.
    #[error("the mesh has no triangles: refinement needs a surface to slice")]
    EmptyMesh,
    /// `up` or `forward` is zero, not finite, or they are parallel.
    #[error("up {up} and forward {forward} must be finite, non-zero and not parallel")]
    BadDirections {
        /// The up direction given.
        up: DVec3,
        /// The forward direction given.
        forward: DVec3,
    },
    /// `spine: Full` with an engine preset, whose skeleton has no vertebrae.
    #[error("--spine full needs --preset anatomical: the {preset} preset is an engine's fixed skeleton without vertebrae (use --spine coarse with it)")]
    FullSpineWithPreset {
        /// The preset asked for.
        preset: String,
    },
    /// `spine: Full` with the refinement switched off: the full spine is the refinement's.
    #[error("--spine full needs the refinement (--refine on): the vertebrae are found by slicing the body")]
    FullSpineWithoutRefinement,
    /// A canonical key points outside the skeleton.
    #[error("canonical joint {key} has id {id}, but the skeleton has {len} joints")]
    BadJointId {
        /// The canonical key.
        key: String,
        /// The id given.
        id: usize,
        /// Number of joints in the skeleton.
        len: usize,
    },
}

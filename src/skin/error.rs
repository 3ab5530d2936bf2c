//! Errors and warnings of the skinning stage.

use serde::Serialize;

/// Why skinning could not be done.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SkinError {
    /// The skeleton has no joints.
    #[error("the skeleton has no joints: build or load a skeleton before skinning")]
    EmptySkeleton,
    /// The skeleton breaks its invariants.
    #[error("the skeleton is invalid: {message}")]
    InvalidSkeleton {
        /// The problems found, joined.
        message: String,
    },
    /// More joints than a 16-bit joint index can address (glTF `JOINTS_0` as unsigned short).
    #[error("the skeleton has {count} joints; at most 65535 can be skinned: merge or drop joints")]
    TooManyJoints {
        /// Number of joints.
        count: usize,
    },
    /// The solid and the distance map were computed on different grids.
    #[error("the distance map was computed on another grid than the solid: run distance::edt on this solid")]
    GridMismatch,
    /// A segment names a joint the skeleton does not have.
    #[error("segment {segment} names joint {joint}, but the skeleton has {joints} joints: build segments from this skeleton")]
    UnknownJoint {
        /// Index of the segment.
        segment: usize,
        /// The joint index given.
        joint: usize,
        /// Number of joints in the skeleton.
        joints: usize,
    },
    /// A segment lists a voxel index outside the grid.
    #[error("segment {segment} lists voxel {voxel}, but the grid has {voxels} voxels: build segments on this grid")]
    VoxelOutOfRange {
        /// Index of the segment.
        segment: usize,
        /// The voxel index given.
        voxel: usize,
        /// Number of voxels of the grid.
        voxels: usize,
    },
    /// No segment covers any interior voxel, so no vertex can be anchored.
    #[error("no segment reaches inside the figure: check that the skeleton lies inside the mesh and uses its units and frame")]
    NoInfluence,
    /// A pose or a skin does not fit the skeleton or mesh it is used with.
    #[error("{what} has {found} entries but {expected} are needed: use the skin, skeleton and mesh it was made for")]
    SizeMismatch {
        /// Which input.
        what: &'static str,
        /// Entries needed.
        expected: usize,
        /// Entries given.
        found: usize,
    },
    /// An option is out of its valid range.
    #[error("skin option {name} is {value}; {expected}")]
    InvalidOption {
        /// The field of [`SkinOptions`](super::SkinOptions).
        name: &'static str,
        /// The value given.
        value: f64,
        /// What is allowed.
        expected: &'static str,
    },
    /// A mesh vertex is not finite.
    #[error("mesh vertex {vertex} is not finite: load meshes through skelfit::mesh, which rejects NaN and infinite coordinates")]
    NonFiniteVertex {
        /// Index of the vertex.
        vertex: usize,
    },
    /// A pose rotation is not finite.
    #[error("the pose rotation of joint {joint} is not finite: give finite unit quaternions")]
    NonFinitePose {
        /// Index of the joint.
        joint: usize,
    },
}

/// Something skinning had to work around; returned with the result, never printed.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SkinWarning {
    /// A segment covers no interior voxel (its chain voxels are all outside the figure), so it
    /// influences no vertex directly.
    SegmentOutside {
        /// Index of the segment.
        segment: usize,
        /// Name of the joint that moves it.
        joint: String,
    },
    /// Vertices whose voxel the propagation did not reach (outside the grid, or in a part of
    /// the surface not connected to the interior); each was bound to its nearest segment.
    UnreachedVertices {
        /// How many.
        count: usize,
        /// The first such vertex.
        first: usize,
    },
    /// Vertices with more than four influencing joints: the engine weights keep the four
    /// largest, so engine deformation differs slightly from the anchor weights there.
    TruncatedInfluences {
        /// How many vertices.
        count: usize,
        /// The largest total anchor weight dropped at one vertex.
        max_dropped: f64,
    },
}

impl std::fmt::Display for SkinWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SkinWarning::SegmentOutside { segment, joint } => write!(
                f,
                "segment {segment} (moved by {joint}) lies outside the figure and influences no vertex directly"
            ),
            SkinWarning::UnreachedVertices { count, first } => write!(
                f,
                "{count} vertices (first: {first}) are not connected to the interior; each was bound to its nearest segment"
            ),
            SkinWarning::TruncatedInfluences { count, max_dropped } => write!(
                f,
                "{count} vertices have more than four influences; engine weights keep the four largest (at most {:.1} % of a vertex's weight dropped)",
                100.0 * max_dropped
            ),
        }
    }
}

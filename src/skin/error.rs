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
    /// No joint of the skeleton deforms the skin (all are control joints).
    #[error("none of the skeleton's {joints} joints deforms the skin (all have deform: false): mark the bones that carry the skin deform: true")]
    NoDeformingJoint {
        /// Number of joints.
        joints: usize,
    },
    /// The skeleton's size is far from the figure's, as when skeleton and mesh are in
    /// different units.
    #[error("the skeleton is {ratio:.3} times the size of the figure (bounding boxes of its deforming joints and of the mesh's interior; about 0.8 is usual): it looks {} times too {} ({units}); scale the skeleton's positions by {} or export skeleton and mesh in the same units", trimmed(factor.max(1.0 / factor)), if *factor > 1.0 { "large" } else { "small" }, trimmed(1.0 / factor))]
    UnitMismatch {
        /// Skeleton size over figure size.
        ratio: f64,
        /// The likely factor between the units (skeleton over mesh; above 1: too large).
        factor: f64,
        /// Which units usually differ by that factor.
        units: &'static str,
    },
    /// Too few deforming joints lie inside the figure: the skeleton is in another place or
    /// frame than the mesh.
    #[error("only {inside} of the skeleton's {deforming} deforming joints lie inside the mesh (outside: {}; skeleton centre [{:.4}, {:.4}, {:.4}], mesh centre [{:.4}, {:.4}, {:.4}]): give a skeleton in the mesh's frame (same origin, same up axis) and units", listed(outside, deforming - inside), skeleton_centre[0], skeleton_centre[1], skeleton_centre[2], figure_centre[0], figure_centre[1], figure_centre[2])]
    SkeletonOutside {
        /// Deforming joints inside the figure.
        inside: usize,
        /// Names of the first deforming joints outside the figure (at most five), in joint
        /// order.
        outside: Vec<String>,
        /// Deforming joints.
        deforming: usize,
        /// Centre of the deforming joints' bounding box, mesh frame.
        skeleton_centre: [f64; 3],
        /// Centre of the figure's interior, mesh frame.
        figure_centre: [f64; 3],
    },
    /// A pose rotation is not finite.
    #[error("the pose rotation of joint {joint} is not finite: give finite unit quaternions")]
    NonFinitePose {
        /// Index of the joint.
        joint: usize,
    },
}

/// Most joints named in [`SkinError::SkeletonOutside`].
pub(crate) const OUTSIDE_LISTED: usize = 5;

/// `names` joined by commas, with how many of `total` are left unnamed.
fn listed(names: &[String], total: usize) -> String {
    let mut text = names.join(", ");
    if total > names.len() {
        text += &format!(" and {} more", total - names.len());
    }
    text
}

/// A number with at most six decimals, trailing zeros cut: `100`, `2.54`, `0.01`.
fn trimmed(value: f64) -> String {
    let text = format!("{value:.6}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
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
    /// Deforming joints of a given skeleton that lie outside the figure
    /// ([`placement`](super::placement)): bones near them are bound through the nearest
    /// interior voxels, or not at all.
    JointsOutside {
        /// Their names, in joint order.
        joints: Vec<String>,
        /// Number of deforming joints.
        deforming: usize,
    },
    /// A joint sits on its parent: the bone between them has no length, so the parent's
    /// weights come from that point and its other bones only.
    ZeroLengthBone {
        /// The parent joint.
        parent: String,
        /// The joint sitting on it.
        joint: String,
    },
    /// A bone between two joints inside the figure runs through empty space (between the
    /// legs, from a hand to the hip): its voxels on either side get its joint's weight.
    BoneOutside {
        /// The bone's parent joint.
        parent: String,
        /// The bone's child joint.
        joint: String,
        /// The longest stretch outside as a share of the bone's length.
        share: f64,
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
            SkinWarning::JointsOutside { joints, deforming } => {
                const SHOWN: usize = 12;
                let mut names = joints[..joints.len().min(SHOWN)].join(", ");
                if joints.len() > SHOWN {
                    names.push_str(&format!(" and {} more", joints.len() - SHOWN));
                }
                write!(
                    f,
                    "{} of {deforming} deforming joints lie outside the mesh: {names}; their bones are bound through the nearest interior voxels (or not at all): check their placement",
                    joints.len()
                )
            }
            SkinWarning::ZeroLengthBone { parent, joint } => write!(
                f,
                "joint {joint} sits on its parent {parent} (a bone of zero length): {parent}'s skin comes from that point and its other bones only"
            ),
            SkinWarning::BoneOutside {
                parent,
                joint,
                share,
            } => write!(
                f,
                "the bone {parent} -> {joint} runs through empty space ({:.0} % of its length outside the mesh): the skin on both sides follows {parent}; check the hierarchy",
                100.0 * share
            ),
        }
    }
}

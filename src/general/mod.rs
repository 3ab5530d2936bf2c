//! The general control skeleton (dissertation ch.5.2.5).
//!
//! [`control_skeleton`] turns a [`PathTree`] into a [`Skeleton`]:
//!
//! - [`skeletal_graph`] (`graph.rs`): one straight edge per chain, split by a global heap on the
//!   approximation error within the min/max-fraction lengths (Figure 5.8);
//! - joints and segments (`joints.rs`): the root on a deep edge (or at the lowest end point),
//!   coincident joints at branches, end effectors at the leaves, and per segment the path-tree
//!   voxels of its chain section for the skinning stage;
//! - joint frames (`frames.rs`): z along the distal segment, x normal to the proximal/distal
//!   plane with the ancestor/descendant search.
//!
//! [`crate::pipeline::general_skeleton`] runs the whole chain from a mesh.

mod error;
mod frames;
mod graph;
mod joints;
mod options;

pub use error::GeneralError;
pub use graph::{skeletal_graph, SkeletalEdge, SkeletalGraph};
pub use joints::Segment;
pub use options::GeneralOptions;

use crate::paths::PathTree;
use crate::skeleton::{JointId, Skeleton};
use serde::Serialize;

/// A general control skeleton with what it was built from.
#[derive(Debug, Clone, Serialize)]
pub struct GeneralSkeleton {
    /// The skeleton: `root`, `joint_NNN` and `end_NNN` joints, positions in mesh units and
    /// frame, frames per ch.5.2.5, three free rotations per joint (none for end effectors).
    pub skeleton: Skeleton,
    /// The control segments, each with its proximal joint and its path-tree voxels.
    pub segments: Vec<Segment>,
    /// The skeletal graph the segments come from.
    pub graph: SkeletalGraph,
    /// The path tree the skeleton approximates.
    pub path_tree: PathTree,
    /// Wall-clock time per stage in milliseconds, in pipeline order (filled by
    /// [`general_skeleton`](crate::pipeline::general_skeleton); empty from
    /// [`control_skeleton`]).
    pub timings: Vec<(String, f64)>,
    /// Things worth telling the user, from every stage that ran.
    pub warnings: Vec<String>,
}

impl GeneralSkeleton {
    /// The end effectors: joints with no children.
    pub fn end_effectors(&self) -> Vec<JointId> {
        let mut has_child = vec![false; self.skeleton.len()];
        for joint in &self.skeleton.joints {
            if let Some(parent) = joint.parent {
                has_child[parent.0] = true;
            }
        }
        (0..self.skeleton.len())
            .filter(|&j| !has_child[j])
            .map(JointId)
            .collect()
    }
}

/// Builds the general control skeleton of `tree` (ch.5.2.5): the skeletal graph
/// ([`skeletal_graph`]), then segments, joints and joint frames. A path tree without chains (a
/// single voxel) gives a one-joint skeleton with a warning.
///
/// # Errors
/// [`GeneralError`] when an option is out of its Table 5.2 range.
pub fn control_skeleton(
    tree: PathTree,
    options: &GeneralOptions,
) -> Result<GeneralSkeleton, GeneralError> {
    options.validate()?;
    let graph = skeletal_graph(&tree, options);
    let mut assembly = joints::assemble(&tree, &graph, options);
    frames::set_frames(
        &mut assembly.skeleton,
        &assembly.incoming,
        &assembly.outgoing,
    );
    debug_assert!(assembly.skeleton.validate().is_ok());
    let mut warnings = tree.warnings.clone();
    warnings.extend(graph.warnings.iter().cloned());
    if graph.edges.is_empty() {
        warnings.push("the skeleton has a single joint: the path tree has no chain".to_string());
    }
    Ok(GeneralSkeleton {
        skeleton: assembly.skeleton,
        segments: assembly.segments,
        graph,
        path_tree: tree,
        timings: Vec::new(),
        warnings,
    })
}

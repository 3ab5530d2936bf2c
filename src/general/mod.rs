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
mod warning;

pub use error::GeneralError;
pub use graph::{skeletal_graph, SkeletalEdge, SkeletalGraph};
pub use joints::Segment;
pub use options::GeneralOptions;
pub use warning::GeneralWarning;

use crate::paths::PathTree;
use crate::skeleton::{JointId, Skeleton};
use crate::warning::Warning;
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
    pub warnings: Vec<Warning>,
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
    let mut warnings: Vec<Warning> = tree.warnings.iter().cloned().map(Into::into).collect();
    warnings.extend(graph.warnings.iter().cloned().map(Warning::General));
    if graph.edges.is_empty() {
        warnings.push(GeneralWarning::SingleJoint.into());
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::paths::testing::surface;
    use crate::paths::{path_tree, PathOptions};

    /// A T of one-voxel lines: a bar along x and a stem along y from its middle.
    fn t_shape() -> PathTree {
        let mut coords = Vec::new();
        for i in 1..30 {
            coords.push([i, 2, 2]);
        }
        for j in 3..20 {
            coords.push([15, j, 2]);
        }
        path_tree(&surface([31, 21, 5], &coords, 1), &PathOptions::default()).unwrap()
    }

    #[test]
    fn a_branch_gets_coincident_joints_and_every_leaf_an_end_effector() {
        let tree = t_shape();
        assert_eq!(tree.chains.len(), 3);
        let options = GeneralOptions {
            min_fraction: 1.0,
            max_fraction: 1.0,
            ..Default::default()
        };
        let general = control_skeleton(tree, &options).unwrap();
        let s = &general.skeleton;
        assert!(s.validate().is_ok());
        // root + 2 coincident joints at the junction (3 edges meet) + 3 end effectors.
        assert_eq!(s.len(), 6, "{:#?}", s.joints);
        assert_eq!(general.end_effectors().len(), 3);
        let junction = s.joints.iter().filter(|j| j.name.starts_with("joint_"));
        let positions: Vec<_> = junction.map(|j| j.position).collect();
        assert_eq!(positions.len(), 2);
        assert_eq!(positions[0], positions[1]);
        // Two root halves and one segment per distal edge; every voxel list is non-empty.
        assert_eq!(general.segments.len(), 4);
        assert!(general.segments.iter().all(|seg| !seg.voxels.is_empty()));
        for joint in &s.joints {
            let m = glam::DMat3::from_quat(joint.frame);
            assert!((m.determinant() - 1.0).abs() < 1e-9);
        }
        assert!(s
            .joints
            .iter()
            .filter(|j| !j.deform)
            .all(|j| j.dofs.is_empty()));
    }

    #[test]
    fn splitting_respects_the_segment_limit_and_lowest_root_option() {
        let options = GeneralOptions {
            approximation_error: 0.0,
            min_fraction: 0.0,
            max_fraction: 0.0,
            segments: Some(6),
            root_at_lowest: true,
            up: glam::DVec3::Y,
        };
        let general = control_skeleton(t_shape(), &options).unwrap();
        assert_eq!(general.graph.edges.len(), 6);
        // The lowest end vertex is the left or right end of the bar (y = 2), not the stem tip.
        let root = general.skeleton.joints[0].position;
        assert_eq!(root.y, 2.5);
        assert_eq!(
            general.skeleton.children(crate::skeleton::JointId(0)).len(),
            1
        );
    }

    #[test]
    fn a_single_voxel_tree_gives_one_joint_and_a_warning() {
        let tree = path_tree(
            &surface([3, 3, 3], &[[1, 1, 1]], 1),
            &PathOptions::default(),
        );
        let general = control_skeleton(tree.unwrap(), &GeneralOptions::default()).unwrap();
        assert_eq!(general.skeleton.len(), 1);
        assert!(general.segments.is_empty());
        assert!(!general.warnings.is_empty());
    }
}

//! The output of bone generation: bone meshes attached to joints.

use super::{BoneKind, BoneWarning};
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use glam::{DQuat, DVec3};

/// One bone mesh, rigidly attached to a joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Bone {
    /// What it is.
    pub kind: BoneKind,
    /// Unique name, e.g. `humerus_L`, `vertebra_03`, `phalanx_L_2_1`.
    pub name: String,
    /// The joint it moves with: the proximal joint of its segment (whose rotation turns the
    /// segment), the root for the pelvis, a trunk joint for a rib cage.
    pub joint: JointId,
    /// Closed, outward-wound mesh in the mesh frame at the skeleton's rest pose, mesh units.
    pub mesh: Mesh,
}

/// A sphere where bones articulate (a joint of the skeleton or the jaw hinge): bones may touch
/// or overlap inside it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Articulation {
    /// Centre, mesh frame.
    pub centre: DVec3,
    /// Radius, mesh units.
    pub radius: f64,
}

/// All bones of a figure.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Bones {
    /// The bones, axial first (cranium, mandible, vertebrae, rib cages), then limbs.
    pub bones: Vec<Bone>,
    /// Where bones meet (joints and jaw hinges).
    pub articulations: Vec<Articulation>,
    /// What could not be made, or was made smaller than measured, and why.
    pub warnings: Vec<BoneWarning>,
}

impl Bone {
    /// The bone's mesh in its joint's rest local frame (the frame of the joint's glTF node).
    pub fn local_mesh(&self, skeleton: &Skeleton) -> Mesh {
        let inverse = skeleton.joint(self.joint).rest_transform().inverse();
        self.mesh.transformed(|p| inverse.transform_point3(p))
    }
}

impl Bones {
    /// All bones merged into one mesh (rest pose, mesh frame), in bone order.
    pub fn world_mesh(&self) -> Mesh {
        super::shapes::merge(self.bones.iter().map(|b| b.mesh.clone()))
    }

    /// Every bone moved rigidly with its joint to `pose` (one local rotation per joint, as
    /// [`Skeleton::world_transforms`]), merged into one mesh in bone order.
    pub fn posed_mesh(&self, skeleton: &Skeleton, pose: &[DQuat]) -> Mesh {
        let world = skeleton.world_transforms(pose);
        super::shapes::merge(self.bones.iter().map(|b| {
            let m = world[b.joint.0] * skeleton.joint(b.joint).rest_transform().inverse();
            b.mesh.transformed(|p| m.transform_point3(p))
        }))
    }

    /// Number of bones of `kind`.
    pub fn count(&self, kind: BoneKind) -> usize {
        self.bones.iter().filter(|b| b.kind == kind).count()
    }
}

//! Skeletons: named joints in a tree with rest positions and frames in the input mesh frame,
//! rotational degrees of freedom with limits, and forward kinematics.

use glam::{DAffine3, DMat3, DQuat, DVec3};
use serde::{Deserialize, Serialize};

pub mod canonical;
pub use canonical::{Canonical, Side};

/// Index of a joint in [`Skeleton::joints`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct JointId(pub usize);

/// An axis of a joint's local frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum LocalAxis {
    /// Local x: perpendicular to the plane of the proximal and distal segments (dissertation
    /// 5.2.5); the hinge axis of elbows and knees.
    X,
    /// Local y: completes the right-handed frame.
    Y,
    /// Local z: along the distal segment.
    Z,
}

/// One rotational degree of freedom: rotation about a local axis within `[min, max]` radians.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Dof {
    /// The local axis rotated about.
    pub axis: LocalAxis,
    /// Lower limit, radians.
    pub min: f64,
    /// Upper limit, radians.
    pub max: f64,
}

impl Dof {
    /// An unlimited rotation about `axis` (`[-pi, pi]`).
    pub fn free(axis: LocalAxis) -> Self {
        Self {
            axis,
            min: -std::f64::consts::PI,
            max: std::f64::consts::PI,
        }
    }
}

/// The dissertation's default: three rotational degrees of freedom, about x, then y, then z
/// (5.2.5), unlimited.
pub fn ball_dofs() -> Vec<Dof> {
    vec![
        Dof::free(LocalAxis::X),
        Dof::free(LocalAxis::Y),
        Dof::free(LocalAxis::Z),
    ]
}

/// One joint: a name, its parent, its rest position and frame, and its degrees of freedom.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Joint {
    /// Unique name (anatomical by default, e.g. `elbow_L`).
    pub name: String,
    /// Parent joint; `None` for the root. Parents come before their children.
    pub parent: Option<JointId>,
    /// Rest position, mesh units, input mesh frame.
    pub position: DVec3,
    /// Whether the joint deforms the skin (false for control joints such as IK targets).
    #[serde(default = "default_true")]
    pub deform: bool,
    /// Rest orientation: rotates the joint's local axes onto the mesh frame (local z along the
    /// distal segment where the skeleton builder knows it). Identity when unknown.
    #[serde(default = "DQuat::default")]
    pub frame: DQuat,
    /// Rotational degrees of freedom in the local frame, applied in this order.
    #[serde(default = "ball_dofs")]
    pub dofs: Vec<Dof>,
}

fn default_true() -> bool {
    true
}

impl Default for Joint {
    fn default() -> Self {
        Self {
            name: String::new(),
            parent: None,
            position: DVec3::ZERO,
            deform: true,
            frame: DQuat::IDENTITY,
            dofs: ball_dofs(),
        }
    }
}

impl Joint {
    /// A deforming joint with identity frame and three free rotations.
    pub fn new(name: impl Into<String>, parent: Option<JointId>, position: DVec3) -> Self {
        Self {
            name: name.into(),
            parent,
            position,
            ..Default::default()
        }
    }

    /// The rest transform: local joint space → mesh frame.
    pub fn rest_transform(&self) -> DAffine3 {
        DAffine3::from_rotation_translation(self.frame, self.position)
    }
}

/// Problems that make a joint list not a valid skeleton.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SkeletonError {
    /// A parent index points at or after its child, or out of range.
    #[error("joint {joint} ({name}) has parent {parent}, which does not come before it: order joints parents first")]
    ParentOrder {
        /// Index of the joint.
        joint: usize,
        /// Its name.
        name: String,
        /// The parent index given.
        parent: usize,
    },
    /// Two joints share a name.
    #[error("two joints are called {name}: joint names must be unique")]
    DuplicateName {
        /// The name.
        name: String,
    },
    /// A position or frame is not finite.
    #[error("joint {name} has a non-finite position or frame")]
    NonFinite {
        /// The joint's name.
        name: String,
    },
}

/// A pose: one local rotation per joint, applied after the rest frame (identity = rest).
pub type Pose = Vec<DQuat>;

/// A skeleton: joints ordered parents before children.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Skeleton {
    /// The joints, parents before children.
    pub joints: Vec<Joint>,
}

impl Skeleton {
    /// The id of the joint called `name`, if any.
    pub fn find(&self, name: &str) -> Option<JointId> {
        self.joints.iter().position(|j| j.name == name).map(JointId)
    }

    /// The joint with id `id`.
    pub fn joint(&self, id: JointId) -> &Joint {
        &self.joints[id.0]
    }

    /// Number of joints.
    pub fn len(&self) -> usize {
        self.joints.len()
    }

    /// True without joints.
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty()
    }

    /// The children of `id`, in joint order.
    pub fn children(&self, id: JointId) -> Vec<JointId> {
        (0..self.joints.len())
            .filter(|&k| self.joints[k].parent == Some(id))
            .map(JointId)
            .collect()
    }

    /// Checks the invariants: parents before children, unique names, finite values. Reports
    /// every problem.
    ///
    /// # Errors
    /// The list of problems found, in joint order.
    pub fn validate(&self) -> Result<(), Vec<SkeletonError>> {
        let mut problems = Vec::new();
        let mut names = std::collections::BTreeSet::new();
        for (k, j) in self.joints.iter().enumerate() {
            if let Some(p) = j.parent {
                if p.0 >= k {
                    problems.push(SkeletonError::ParentOrder {
                        joint: k,
                        name: j.name.clone(),
                        parent: p.0,
                    });
                }
            }
            if !names.insert(j.name.as_str()) {
                problems.push(SkeletonError::DuplicateName {
                    name: j.name.clone(),
                });
            }
            if !j.position.is_finite() || !j.frame.is_finite() {
                problems.push(SkeletonError::NonFinite {
                    name: j.name.clone(),
                });
            }
        }
        if problems.is_empty() {
            Ok(())
        } else {
            Err(problems)
        }
    }

    /// The rest pose (all local rotations identity).
    pub fn rest_pose(&self) -> Pose {
        vec![DQuat::IDENTITY; self.joints.len()]
    }

    /// Forward kinematics: the world transform (local joint space → mesh frame) of every joint
    /// in `pose`. At the rest pose this is each joint's [`Joint::rest_transform`].
    ///
    /// A joint's posed transform is its parent's posed transform, times its rest transform
    /// relative to the parent, times its local rotation.
    pub fn world_transforms(&self, pose: &[DQuat]) -> Vec<DAffine3> {
        let mut world: Vec<DAffine3> = Vec::with_capacity(self.joints.len());
        for (k, joint) in self.joints.iter().enumerate() {
            let rotation = pose.get(k).copied().unwrap_or(DQuat::IDENTITY);
            let rest = joint.rest_transform();
            let local = DAffine3::from_quat(rotation);
            let t = match joint.parent {
                Some(p) => {
                    let parent_rest = self.joints[p.0].rest_transform();
                    world[p.0] * (parent_rest.inverse() * rest) * local
                }
                None => rest * local,
            };
            world.push(t);
        }
        world
    }

    /// Skinning matrices for `pose`: for each joint, the transform taking a point of the rest
    /// mesh to its posed position if it moved rigidly with that joint. Exactly the identity for
    /// every joint when the pose is the rest pose and the chain above it is at rest.
    pub fn skinning_matrices(&self, pose: &[DQuat]) -> Vec<DAffine3> {
        let mut out: Vec<DAffine3> = Vec::with_capacity(self.joints.len());
        for (k, joint) in self.joints.iter().enumerate() {
            let rotation = pose.get(k).copied().unwrap_or(DQuat::IDENTITY);
            let own = if rotation == DQuat::IDENTITY {
                DAffine3::IDENTITY
            } else {
                let rest = joint.rest_transform();
                rest * DAffine3::from_quat(rotation) * rest.inverse()
            };
            let m = match joint.parent {
                Some(p) if out[p.0] != DAffine3::IDENTITY => out[p.0] * own,
                _ => own,
            };
            out.push(m);
        }
        out
    }

    /// The rotation matrix of a joint's rest frame (columns: local x, y, z in the mesh frame).
    pub fn frame_matrix(&self, id: JointId) -> DMat3 {
        DMat3::from_quat(self.joints[id.0].frame)
    }
}

/// A skeleton of `(name, parent index, position)` joints, all deforming (unit tests).
#[cfg(test)]
pub(crate) fn test_skeleton(joints: &[(&str, Option<usize>, [f64; 3])]) -> Skeleton {
    Skeleton {
        joints: joints
            .iter()
            .map(|&(name, parent, p)| Joint {
                name: name.into(),
                parent: parent.map(JointId),
                position: DVec3::from_array(p),
                deform: true,
                ..Default::default()
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chain() -> Skeleton {
        Skeleton {
            joints: vec![
                Joint::new("root", None, DVec3::ZERO),
                Joint::new("mid", Some(JointId(0)), DVec3::new(0.0, 1.0, 0.0)),
                Joint::new("tip", Some(JointId(1)), DVec3::new(0.0, 2.0, 0.0)),
            ],
        }
    }

    #[test]
    fn rest_pose_gives_rest_transforms_and_identity_skinning() {
        let s = chain();
        let world = s.world_transforms(&s.rest_pose());
        for (w, j) in world.iter().zip(&s.joints) {
            assert!((w.translation - j.position).length() < 1e-12);
        }
        assert!(s
            .skinning_matrices(&s.rest_pose())
            .iter()
            .all(|m| *m == DAffine3::IDENTITY));
    }

    #[test]
    fn rotating_the_middle_joint_moves_the_tip_about_it() {
        let s = chain();
        let mut pose = s.rest_pose();
        pose[1] = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
        let world = s.world_transforms(&pose);
        // The tip, one unit above "mid", swings to -x.
        assert!((world[2].translation - DVec3::new(-1.0, 1.0, 0.0)).length() < 1e-12);
        let m = s.skinning_matrices(&pose);
        assert!(
            (m[2].transform_point3(DVec3::new(0.0, 2.0, 0.0)) - DVec3::new(-1.0, 1.0, 0.0))
                .length()
                < 1e-12
        );
        assert_eq!(m[0], DAffine3::IDENTITY);
    }

    #[test]
    fn validation_reports_every_problem() {
        let mut s = chain();
        s.joints[0].parent = Some(JointId(2));
        s.joints[2].name = "mid".into();
        s.joints[1].position.x = f64::NAN;
        let problems = s.validate().unwrap_err();
        assert_eq!(problems.len(), 3);
    }
}

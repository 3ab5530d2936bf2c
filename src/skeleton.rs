//! Skeletons: named joints in a tree with rest positions in the input mesh frame.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Index of a joint in [`Skeleton::joints`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct JointId(pub usize);

/// One joint: a name, its parent and its rest position.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Joint {
    /// Unique name (anatomical by default, e.g. `elbow_L`).
    pub name: String,
    /// Parent joint; `None` for the root. Parents come before their children.
    pub parent: Option<JointId>,
    /// Rest position, mesh units, input mesh frame.
    pub position: DVec3,
    /// Whether the joint deforms the skin (false for control joints such as IK targets).
    pub deform: bool,
}

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
}

//! The bind pose of a glTF skin and its joints as a [`Skeleton`].

use super::gltf_accessor;
use super::gltf_nodes::NodeTree;
use crate::skeleton::{Joint, JointId, Skeleton};
use glam::{DMat4, DQuat, DVec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::{Document, Semantic, Skin};
use std::collections::HashMap;

/// A skin placed in its bind pose.
pub(super) struct SkinBind {
    /// Index of the skin in the document.
    pub skin: usize,
    /// Node index of every joint, in skin order.
    pub joints: Vec<usize>,
    /// Inverse bind matrix of every joint (identity when the file gives none).
    pub inverse_bind: Vec<DMat4>,
    /// `B`: maps bind-space vertices into the world ([`bind_of`]): `W_root(rest) · IBM_root`,
    /// where `root` is the first joint whose parent node is not a joint of the skin, unless the
    /// rest pose is a posed frame.
    pub bind: DMat4,
    /// Joint index (into `joints`) of every node that is a joint of this skin.
    pub joint_of_node: HashMap<usize, usize>,
}

/// A rest pose whose joints lie, at the median, farther than this share of the skeleton's
/// extent from where `W_root(rest) · IBM_root` puts their bind positions is a posed frame,
/// not the bind pose. (Files whose rest pose is a frame close to the bind pose, as many game
/// exports are, stay within a few hundredths; an animation frame stored as the rest pose moves
/// the median joint by a fifth of the figure.)
const POSED_REST: f64 = 0.1;

/// The transform that places the skin's bind space in the world. When the file's rest pose is
/// its bind pose (the usual case), every joint's `W_k(rest) · IBM_k` is one and the same
/// matrix, the root's: it carries the armature's units and axes (a Mixamo export's 0.01 scale
/// and Z-up turn) and any placement of the whole figure, and is returned. When the rest pose is
/// an animation frame (the joints' matrices disagree: the median joint's rest position lies
/// more than [`POSED_REST`] of the skeleton's extent from where the root's matrix puts its bind
/// position), the root's matrix is only the pose of the pelvis in that frame (a figure tilted
/// by 40 degrees); the modelled figure is then placed by the world transform of the node above
/// the root (the armature), identity when the root has no parent.
fn bind_of(joints: &[usize], inverse_bind: &[DMat4], tree: &NodeTree, root: usize) -> DMat4 {
    let by_root = tree.world[joints[root]] * inverse_bind[root];
    let rest: Vec<DVec3> = joints
        .iter()
        .map(|&node| tree.world[node].transform_point3(DVec3::ZERO))
        .collect();
    let (lo, hi) = rest.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let extent = (hi - lo).length();
    let mut deviations: Vec<f64> = joints
        .iter()
        .enumerate()
        .filter_map(|(k, _)| {
            let ibm = inverse_bind[k];
            (ibm.determinant() != 0.0).then(|| {
                let bind_position = ibm.inverse().transform_point3(DVec3::ZERO);
                by_root.transform_point3(bind_position).distance(rest[k])
            })
        })
        .filter(|d| d.is_finite())
        .collect();
    if deviations.len() < 3 || !(extent > 0.0 && extent.is_finite()) {
        return by_root;
    }
    deviations.sort_by(f64::total_cmp);
    let median = deviations[deviations.len() / 2];
    if median <= POSED_REST * extent {
        return by_root;
    }
    tree.parent[joints[root]].map_or(DMat4::IDENTITY, |parent| tree.world[parent])
}

impl SkinBind {
    /// Reads the joints and inverse bind matrices of `skin` and computes `B`.
    pub fn new(skin: &Skin, buffers: &[&[u8]], tree: &NodeTree) -> Result<Self, String> {
        let joints: Vec<usize> = skin.joints().map(|n| n.index()).collect();
        if joints.is_empty() {
            return Err(format!("skin {} has no joints", skin.index()));
        }
        let inverse_bind = match skin.inverse_bind_matrices() {
            None => vec![DMat4::IDENTITY; joints.len()],
            Some(accessor) => {
                let what = format!("inverseBindMatrices of skin {}", skin.index());
                gltf_accessor::check(
                    &accessor,
                    buffers,
                    &[DataType::F32],
                    Dimensions::Mat4,
                    &what,
                )?;
                let matrices: Vec<DMat4> = skin
                    .reader(|b| buffers.get(b.index()).copied())
                    .read_inverse_bind_matrices()
                    .ok_or_else(|| format!("{what} has no data"))?
                    .map(|m| DMat4::from_cols_array_2d(&m.map(|c| c.map(f64::from))))
                    .collect();
                if matrices.len() < joints.len() {
                    return Err(format!(
                        "{what} holds {} matrices for {} joints",
                        matrices.len(),
                        joints.len()
                    ));
                }
                matrices
            }
        };
        let joint_of_node: HashMap<usize, usize> = joints
            .iter()
            .enumerate()
            .rev() // the first occurrence wins for a (malformed) repeated joint
            .map(|(k, &node)| (node, k))
            .collect();
        let root = joints
            .iter()
            .position(|&node| {
                tree.parent[node].is_none_or(|parent| !joint_of_node.contains_key(&parent))
            })
            .unwrap_or(0);
        let bind = bind_of(&joints, &inverse_bind, tree, root);
        Ok(Self {
            skin: skin.index(),
            joints,
            inverse_bind,
            bind,
            joint_of_node,
        })
    }

    /// The bind-pose world transform of joint `k`: `B · inv(IBM_k)`.
    pub fn joint_bind_world(&self, k: usize) -> Result<DMat4, String> {
        let ibm = self.inverse_bind[k];
        let inverse = ibm.inverse();
        if ibm.determinant() == 0.0 || !inverse.is_finite() {
            return Err(format!(
                "the inverse bind matrix of joint {k} (node {}) of skin {} is singular",
                self.joints[k], self.skin
            ));
        }
        Ok(self.bind * inverse)
    }

    /// The nearest ancestor of `node` (itself excluded) that is a joint of this skin.
    pub fn joint_ancestor(&self, node: usize, tree: &NodeTree) -> Option<usize> {
        let mut current = tree.parent[node];
        let mut steps = 0;
        while let Some(n) = current {
            if let Some(&k) = self.joint_of_node.get(&n) {
                return Some(k);
            }
            steps += 1;
            if steps > tree.parent.len() {
                return None;
            }
            current = tree.parent[n];
        }
        None
    }

    /// The skin's joints in the bind pose as a [`Skeleton`], parents before children, the
    /// skeleton index of each skin joint, and the names several joints share (in skeleton
    /// order; every later joint of such a name is renamed `<name>_<node index>`).
    pub fn skeleton(
        &self,
        document: &Document,
        tree: &NodeTree,
        deform: &[bool],
    ) -> Result<(Skeleton, Vec<usize>, Vec<String>), String> {
        let nodes: Vec<_> = document.nodes().collect();
        let count = self.joints.len();
        let mut positions = Vec::with_capacity(count);
        let mut frames = Vec::with_capacity(count);
        for k in 0..count {
            let world = self.joint_bind_world(k)?;
            positions.push(world.transform_point3(DVec3::ZERO));
            frames.push(bind_frame(&world));
        }
        let parents: Vec<Option<usize>> = self
            .joints
            .iter()
            .map(|&node| self.joint_ancestor(node, tree))
            .collect();
        // Stable topological order: skin order, each joint after its parent.
        let mut order = Vec::with_capacity(count);
        let mut placed = vec![false; count];
        while order.len() < count {
            let before = order.len();
            for k in 0..count {
                if !placed[k] && parents[k].is_none_or(|p| placed[p] || p == k) {
                    placed[k] = true;
                    order.push(k);
                }
            }
            if order.len() == before {
                return Err(format!("the joints of skin {} form a cycle", self.skin));
            }
        }
        let mut id_of = vec![0; count];
        for (id, &k) in order.iter().enumerate() {
            id_of[k] = id;
        }
        let mut taken = std::collections::HashSet::new();
        let mut shared: Vec<String> = Vec::new();
        let joints = order
            .iter()
            .map(|&k| {
                let node = self.joints[k];
                let base = nodes[node]
                    .name()
                    .filter(|n| !n.is_empty())
                    .map_or_else(|| format!("joint_{node}"), str::to_string);
                let name = if taken.contains(&base) {
                    if !shared.contains(&base) {
                        shared.push(base.clone());
                    }
                    format!("{base}_{node}")
                } else {
                    base
                };
                taken.insert(name.clone());
                Joint {
                    name,
                    parent: parents[k].filter(|&p| p != k).map(|p| JointId(id_of[p])),
                    position: positions[k],
                    deform: deform[k],
                    frame: frames[k],
                    ..Default::default()
                }
            })
            .collect();
        Ok((Skeleton { joints }, id_of, shared))
    }
}

/// Largest relative difference between the scale factors of a joint's bind transform for it
/// to count as a rotation times a uniform scale.
const UNIFORM_SCALE_TOLERANCE: f64 = 1e-3;

/// The rotation of a joint's bind-pose world transform: its rest orientation, so that the
/// joint's frame (and the node rotations an exporter writes from it) is the artist's. Identity
/// when the transform mirrors, shears or scales unevenly (no rotation describes it).
fn bind_frame(world: &DMat4) -> DQuat {
    let (scale, rotation, _) = world.to_scale_rotation_translation();
    let (low, high) = (scale.min_element(), scale.max_element());
    let uniform = low > 0.0 && (high - low) <= UNIFORM_SCALE_TOLERANCE * high;
    if uniform && rotation.is_finite() {
        // Shears show as a rotation that does not map the axes onto the matrix's columns.
        let rebuilt = DMat4::from_scale_rotation_translation(scale, rotation, DVec3::ZERO);
        let linear = |m: &DMat4| {
            [
                m.x_axis.truncate(),
                m.y_axis.truncate(),
                m.z_axis.truncate(),
            ]
        };
        let close = linear(&rebuilt)
            .iter()
            .zip(linear(world))
            .all(|(a, b)| (*a - b).length() <= UNIFORM_SCALE_TOLERANCE * high);
        if close {
            return rotation.normalize();
        }
    }
    DQuat::IDENTITY
}

/// The nonzero `(joint, weight)` pairs of every vertex of `primitive`, over all its
/// `JOINTS_n`/`WEIGHTS_n` sets (joint indices into the skin; weights as stored, normalised
/// integer weights read as fractions). `what` names the primitive in errors.
pub(super) fn vertex_weights(
    primitive: &gltf::Primitive,
    buffers: &[&[u8]],
    what: &str,
) -> Result<Vec<Vec<(u16, f32)>>, String> {
    let reader = primitive.reader(|b| buffers.get(b.index()).copied());
    let mut out: Vec<Vec<(u16, f32)>> = Vec::new();
    for set in 0.. {
        let (Some(joints), Some(weights)) = (
            primitive.get(&Semantic::Joints(set)),
            primitive.get(&Semantic::Weights(set)),
        ) else {
            break;
        };
        gltf_accessor::check(
            &joints,
            buffers,
            &[DataType::U8, DataType::U16],
            Dimensions::Vec4,
            &format!("JOINTS_{set} of {what}"),
        )?;
        gltf_accessor::check(
            &weights,
            buffers,
            &[DataType::F32, DataType::U8, DataType::U16],
            Dimensions::Vec4,
            &format!("WEIGHTS_{set} of {what}"),
        )?;
        let (Some(joints), Some(weights)) = (reader.read_joints(set), reader.read_weights(set))
        else {
            break;
        };
        for (vertex, (js, ws)) in joints.into_u16().zip(weights.into_f32()).enumerate() {
            if out.len() <= vertex {
                out.resize(vertex + 1, Vec::new());
            }
            out[vertex].extend(js.into_iter().zip(ws).filter(|&(_, w)| w > 0.0));
        }
    }
    Ok(out)
}

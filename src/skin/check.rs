//! The deformation check: pose a skinned mesh joint by joint through a standard sweep and
//! count the mesh edges that linear blend skinning stretches past 1.5× and 2× their rest
//! length.
//!
//! Each pose turns one joint (and everything below it) about the joint's own position; the
//! axes come from the figure's up and forward directions and the bone's own direction, so
//! the sweep needs no joint frames and poses any skeleton the same way: skelfit's, an
//! artist's, an engine's. A tear in the skin (a vertex left behind by its neighbours) shows
//! as a few edges stretched several times their length; a smooth weight field stretches
//! none past 2× under these moderate poses.

use super::SkinError;
use crate::mesh::Mesh;
use crate::skeleton::canonical::{Canonical, CanonicalJoints, Side, Tail};
use crate::skeleton::{JointId, Skeleton};
use glam::{DAffine3, DQuat, DVec3};
use rayon::prelude::*;
use serde::Serialize;

/// Which standard sweep to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepKind {
    /// Shoulder raise 80°, elbow flex 90°, wrist twist 90°, hip flex 60°, hip abduct 45°,
    /// knee bend 90° (both sides), chest twist 30°, neck twist 30°.
    Humanoid,
    /// Leg swings 45° (fore and hind, both sides), elbow and knee flex 60°, neck down 35°,
    /// spine twist 20°, tail raise 40°.
    Animal,
}

/// One pose of a sweep: `joint` and its descendants turned by `angle` about `axis` through
/// the joint's rest position.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepPose {
    /// Human-readable name, e.g. `shoulder raise 80° L`.
    pub name: String,
    /// The joint turned.
    #[serde(skip)]
    pub joint: JointId,
    /// Unit rotation axis in the mesh frame.
    #[serde(skip)]
    pub axis: DVec3,
    /// Rotation angle, radians.
    #[serde(skip)]
    pub angle: f64,
}

/// The stretch one pose causes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PoseStretch {
    /// The pose's name.
    pub pose: String,
    /// Edges longer than 1.5× their rest length.
    pub over_1_5: usize,
    /// Edges longer than 2× their rest length.
    pub over_2: usize,
    /// Largest posed / rest length ratio.
    pub worst: f64,
}

/// The result of [`check_deformation`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeformationCheck {
    /// Which sweep ran.
    pub sweep: SweepKind,
    /// Mesh edges measured (each undirected edge once, zero-length edges left out).
    pub edges: usize,
    /// One entry per pose of the sweep that could be posed.
    pub poses: Vec<PoseStretch>,
    /// Poses of the sweep left out because the skeleton has no joint for them (e.g. `tail
    /// raise 40°` on a figure without a tail).
    pub missing: Vec<String>,
}

impl DeformationCheck {
    /// Edges past 2× summed over the poses.
    pub fn total_over_2(&self) -> usize {
        self.poses.iter().map(|p| p.over_2).sum()
    }

    /// Edges past 1.5× summed over the poses.
    pub fn total_over_1_5(&self) -> usize {
        self.poses.iter().map(|p| p.over_1_5).sum()
    }

    /// The largest stretch ratio of any pose (1 when nothing was posed).
    pub fn worst(&self) -> f64 {
        self.poses.iter().map(|p| p.worst).fold(1.0, f64::max)
    }
}

/// The poses of `kind` for `skeleton`, given its canonical map (shoulders, elbows, chest,
/// tail base... → joint; keyed as written in files or by [`Canonical`]) and the figure's `up` and `forward`
/// directions (the figure's left is `up × forward`). Returns the poses and the names of those
/// the map has no joint for.
pub fn sweep(
    skeleton: &Skeleton,
    canonical: &dyn CanonicalJoints,
    kind: SweepKind,
    up: DVec3,
    forward: DVec3,
) -> (Vec<SweepPose>, Vec<String>) {
    let up = up.normalize_or(DVec3::Y);
    let forward = (forward - up * forward.dot(up)).normalize_or(DVec3::Z);
    let mut poser = Poser {
        skeleton,
        canonical,
        up,
        forward,
        left: up.cross(forward),
        poses: Vec::new(),
        missing: Vec::new(),
    };
    for side in Side::BOTH {
        match kind {
            SweepKind::Humanoid => poser.humanoid_limbs(side),
            SweepKind::Animal => poser.animal_limbs(side),
        }
    }
    match kind {
        SweepKind::Humanoid => poser.humanoid_trunk(),
        SweepKind::Animal => poser.animal_trunk(),
    }
    (poser.poses, poser.missing)
}

/// The poses of a sweep as they are collected, with the skeleton, its canonical map and the
/// figure's directions (unit, `left = up × forward`).
struct Poser<'a> {
    skeleton: &'a Skeleton,
    canonical: &'a dyn CanonicalJoints,
    up: DVec3,
    forward: DVec3,
    left: DVec3,
    poses: Vec<SweepPose>,
    missing: Vec<String>,
}

impl Poser<'_> {
    /// The joint of a canonical key, if the map has one in the skeleton.
    fn key(&self, key: Canonical) -> Option<JointId> {
        self.canonical
            .joint_of(key)
            .filter(|j| j.0 < self.skeleton.len())
    }

    /// The unit direction of the bone from `joint` towards `towards`, else towards its
    /// farthest child; `None` for a leaf or a zero-length bone.
    fn bone(&self, joint: JointId, towards: Option<JointId>) -> Option<DVec3> {
        let skeleton = self.skeleton;
        let start = skeleton.joint(joint).position;
        let end = towards.map(|t| skeleton.joint(t).position).or_else(|| {
            skeleton
                .children(joint)
                .into_iter()
                .map(|c| skeleton.joint(c).position)
                .max_by(|a, b| (*a - start).length().total_cmp(&(*b - start).length()))
        })?;
        let d = end - start;
        (d.length() > 0.0).then(|| d.normalize())
    }

    /// Adds the pose `name` (turning `joint` by `degrees` about `axis`), or notes it missing
    /// when the joint or the axis is unknown.
    fn push(&mut self, name: String, joint: Option<JointId>, axis: Option<DVec3>, degrees: f64) {
        match (joint, axis) {
            (Some(joint), Some(axis)) => self.poses.push(SweepPose {
                name,
                joint,
                axis,
                angle: degrees.to_radians(),
            }),
            _ => self.missing.push(name),
        }
    }

    /// Shoulder raise, elbow flex, wrist twist, hip flex, hip abduct and knee bend of one side.
    fn humanoid_limbs(&mut self, side: Side) {
        let (up, forward, left) = (self.up, self.forward, self.left);
        let outward = left * side.sign();
        let s = side.letter();
        let shoulder = self.key(Canonical::Shoulder(side));
        let elbow = self.key(Canonical::Elbow(side));
        let wrist = self.key(Canonical::Wrist(side));
        let hip = self.key(Canonical::Hip(side));
        let knee = self.key(Canonical::Knee(side));
        let ankle = self.key(Canonical::Ankle(side));
        let v = shoulder.and_then(|j| self.bone(j, elbow));
        let axis = v.map(|v| hinge(v, up, forward, up));
        self.push(format!("shoulder raise 80° {s}"), shoulder, axis, 80.0);
        let v = elbow.and_then(|j| self.bone(j, wrist));
        let axis = v.map(|v| hinge(v, forward, up, forward));
        self.push(format!("elbow flex 90° {s}"), elbow, axis, 90.0);
        let twist = match (elbow, wrist) {
            (Some(e), Some(w)) => {
                (self.skeleton.joint(w).position - self.skeleton.joint(e).position).try_normalize()
            }
            _ => None,
        };
        self.push(format!("wrist twist 90° {s}"), wrist, twist, 90.0);
        let v = hip.and_then(|j| self.bone(j, knee));
        let axis = v.map(|v| hinge(v, forward, left, forward));
        self.push(format!("hip flex 60° {s}"), hip, axis, 60.0);
        let axis = v.map(|v| hinge(v, outward, forward, outward));
        self.push(format!("hip abduct 45° {s}"), hip, axis, 45.0);
        let v = knee.and_then(|j| self.bone(j, ankle));
        let axis = v.map(|v| hinge(v, forward, left, -forward));
        self.push(format!("knee bend 90° {s}"), knee, axis, 90.0);
    }

    /// Chest twist and neck twist.
    fn humanoid_trunk(&mut self) {
        let chest = self
            .key(Canonical::Chest)
            .or_else(|| self.key(Canonical::Spine));
        self.push("chest twist 30°".into(), chest, Some(self.up), 30.0);
        let neck = self.key(Canonical::Neck);
        self.push("neck twist 30°".into(), neck, Some(self.up), 30.0);
    }

    /// Fore and hind leg swings, elbow and knee flex of one side.
    fn animal_limbs(&mut self, side: Side) {
        type Key = fn(Side) -> Canonical;
        let limbs: [(Key, Key, &str, f64, bool); 4] = [
            (
                Canonical::Shoulder,
                Canonical::Elbow,
                "fore leg swing",
                45.0,
                false,
            ),
            (
                Canonical::Hip,
                Canonical::Knee,
                "hind leg swing",
                45.0,
                false,
            ),
            (
                Canonical::Elbow,
                Canonical::Wrist,
                "elbow flex",
                60.0,
                false,
            ),
            (Canonical::Knee, Canonical::Ankle, "knee flex", 60.0, true),
        ];
        for (part, towards, name, degrees, back) in limbs {
            let joint = self.key(part(side));
            let v = joint.and_then(|j| self.bone(j, self.key(towards(side))));
            let towards = if back { -self.forward } else { self.forward };
            let axis = v.map(|v| hinge(v, self.forward, self.left, towards));
            self.push(
                format!("{name} {degrees}° {}", side.letter()),
                joint,
                axis,
                degrees,
            );
        }
    }

    /// Neck down, spine twist and tail raise.
    fn animal_trunk(&mut self) {
        let (up, forward, left) = (self.up, self.forward, self.left);
        let neck = self.key(Canonical::Neck);
        let v = neck.and_then(|j| self.bone(j, self.key(Canonical::Head)));
        self.push(
            "neck down 35°".into(),
            neck,
            v.map(|v| hinge(v, up, left, -up)),
            35.0,
        );
        let chest = self
            .key(Canonical::Chest)
            .or_else(|| self.key(Canonical::Spine));
        self.push("spine twist 20°".into(), chest, Some(forward), 20.0);
        let tail = self.key(Canonical::Tail(Tail::Base));
        let v = tail.and_then(|j| self.bone(j, None));
        self.push(
            "tail raise 40°".into(),
            tail,
            v.map(|v| hinge(v, up, left, up)),
            40.0,
        );
    }
}

/// A hinge axis perpendicular to the bone direction `v` and to `plane` (`fallback` when they
/// are parallel), turned so the bone's tip moves towards `towards`.
fn hinge(v: DVec3, plane: DVec3, fallback: DVec3, towards: DVec3) -> DVec3 {
    let axis = v.cross(plane).try_normalize().unwrap_or(fallback);
    if axis.cross(v).dot(towards) < 0.0 {
        -axis
    } else {
        axis
    }
}

/// World-space skinning matrices of one sweep pose: the joint's subtree turned about the
/// joint's rest position, every other joint at rest (identity).
pub fn pose_matrices(skeleton: &Skeleton, pose: &SweepPose) -> Vec<DAffine3> {
    let pivot = skeleton.joint(pose.joint).position;
    let turn = DAffine3::from_translation(pivot)
        * DAffine3::from_quat(DQuat::from_axis_angle(pose.axis, pose.angle))
        * DAffine3::from_translation(-pivot);
    let mut moved = vec![false; skeleton.len()];
    let mut matrices = vec![DAffine3::IDENTITY; skeleton.len()];
    for (k, joint) in skeleton.joints.iter().enumerate() {
        moved[k] = k == pose.joint.0 || joint.parent.is_some_and(|p| p.0 < k && moved[p.0]);
        if moved[k] {
            matrices[k] = turn;
        }
    }
    matrices
}

/// Linear blend skinning of `positions` with world-space `matrices` (one per joint):
/// `p + Σ w_j (M_j p − p)`, so a vertex whose joints are all at rest stays exactly where it
/// is.
pub fn blend(
    positions: &[DVec3],
    weights: &[Vec<(JointId, f64)>],
    matrices: &[DAffine3],
) -> Vec<DVec3> {
    positions
        .par_iter()
        .zip(weights)
        .map(|(&p, w)| {
            let mut moved = DVec3::ZERO;
            for &(joint, weight) in w {
                if let Some(m) = matrices.get(joint.0) {
                    if *m != DAffine3::IDENTITY {
                        moved += weight * (m.transform_point3(p) - p);
                    }
                }
            }
            p + moved
        })
        .collect()
}

/// Every undirected edge of `mesh` once, `(a, b)` with `a < b`, sorted.
pub fn mesh_edges(mesh: &Mesh) -> Vec<(u32, u32)> {
    let mut edges: Vec<(u32, u32)> = mesh
        .triangles
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .filter(|(a, b)| a != b)
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// Poses `mesh`, skinned to `skeleton` with per-vertex `weights` (joint, weight; summing to
/// one), through `poses` and counts the stretched edges of each.
///
/// # Errors
/// [`SkinError::SizeMismatch`] when `weights` has another length than the mesh's vertices.
pub fn check_deformation(
    mesh: &Mesh,
    skeleton: &Skeleton,
    weights: &[Vec<(JointId, f64)>],
    sweep: SweepKind,
    poses: &[SweepPose],
    missing: Vec<String>,
) -> Result<DeformationCheck, SkinError> {
    if weights.len() != mesh.positions.len() {
        return Err(SkinError::SizeMismatch {
            what: "the weights",
            expected: mesh.positions.len(),
            found: weights.len(),
        });
    }
    let edges: Vec<(u32, u32, f64)> = mesh_edges(mesh)
        .into_iter()
        .filter_map(|(a, b)| {
            let rest = mesh.positions[a as usize].distance(mesh.positions[b as usize]);
            (rest > 0.0).then_some((a, b, rest))
        })
        .collect();
    let poses = poses
        .iter()
        .map(|pose| {
            let matrices = pose_matrices(skeleton, pose);
            let posed = blend(&mesh.positions, weights, &matrices);
            let (mut over_1_5, mut over_2, mut worst) = (0, 0, 1.0f64);
            for &(a, b, rest) in &edges {
                let ratio = posed[a as usize].distance(posed[b as usize]) / rest;
                over_1_5 += usize::from(ratio > 1.5);
                over_2 += usize::from(ratio > 2.0);
                worst = worst.max(ratio);
            }
            PoseStretch {
                pose: pose.name.clone(),
                over_1_5,
                over_2,
                worst,
            }
        })
        .collect();
    Ok(DeformationCheck {
        sweep,
        edges: edges.len(),
        poses,
        missing,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::Joint;
    use std::collections::BTreeMap;
    use Side::Left;

    /// A vertical tube from y = 0 to y = 2 around two bones meeting at y = 1.
    fn tube() -> (Mesh, Skeleton) {
        let rings: Vec<(f64, f64)> = (0..=40).map(|r| (0.2, 1.0 - r as f64 / 20.0)).collect();
        let mesh = Mesh::lathe(DVec3::new(0.0, 1.0, 0.0), 1.0, &rings, -1.0, 16);
        let skeleton = Skeleton {
            joints: vec![
                Joint::new(
                    Canonical::Hip(Left).as_str(),
                    None,
                    DVec3::new(0.0, 2.0, 0.0),
                ),
                Joint::new(
                    Canonical::Knee(Left).as_str(),
                    Some(JointId(0)),
                    DVec3::new(0.0, 1.0, 0.0),
                ),
                Joint::new(
                    Canonical::Ankle(Left).as_str(),
                    Some(JointId(1)),
                    DVec3::new(0.0, 0.0, 0.0),
                ),
            ],
        };
        (mesh, skeleton)
    }

    fn canonical(skeleton: &Skeleton) -> BTreeMap<String, JointId> {
        skeleton
            .joints
            .iter()
            .enumerate()
            .map(|(k, j)| (j.name.clone(), JointId(k)))
            .collect()
    }

    #[test]
    fn a_hard_weight_boundary_tears_and_a_blended_one_does_not() {
        let (mesh, skeleton) = tube();
        let (poses, missing) = sweep(
            &skeleton,
            &canonical(&skeleton),
            SweepKind::Humanoid,
            DVec3::Y,
            DVec3::Z,
        );
        assert!(missing.iter().any(|m| m.starts_with("shoulder raise")));
        let knee: Vec<SweepPose> = poses
            .into_iter()
            .filter(|p| p.name.starts_with("knee bend"))
            .collect();
        assert_eq!(knee.len(), 1);
        // Hard: every vertex on one bone, split at the knee.
        let hard: Vec<Vec<(JointId, f64)>> = mesh
            .positions
            .iter()
            .map(|p| vec![(JointId(if p.y > 1.0 { 0 } else { 1 }), 1.0)])
            .collect();
        // Blended linearly over 0.6 around the knee.
        let soft: Vec<Vec<(JointId, f64)>> = mesh
            .positions
            .iter()
            .map(|p| {
                let t = ((p.y - 0.7) / 0.6).clamp(0.0, 1.0);
                vec![(JointId(0), t), (JointId(1), 1.0 - t)]
            })
            .collect();
        let run = |w: &[Vec<(JointId, f64)>]| {
            check_deformation(&mesh, &skeleton, w, SweepKind::Humanoid, &knee, vec![]).unwrap()
        };
        let hard = run(&hard);
        let soft = run(&soft);
        assert!(hard.poses[0].over_1_5 > 0, "{hard:?}");
        assert_eq!(soft.poses[0].over_2, 0, "{soft:?}");
        assert!(soft.poses[0].worst < hard.poses[0].worst);
    }

    #[test]
    fn a_knee_bends_backwards_and_a_hip_flexes_forwards() {
        let (_, skeleton) = tube();
        let (poses, _) = sweep(
            &skeleton,
            &canonical(&skeleton),
            SweepKind::Humanoid,
            DVec3::Y,
            DVec3::Z,
        );
        let tip = |name: &str| {
            let pose = poses.iter().find(|p| p.name.starts_with(name)).unwrap();
            pose_matrices(&skeleton, pose)[2].transform_point3(skeleton.joints[2].position)
        };
        assert!(tip("knee bend").z < -0.9);
        assert!(tip("hip flex").z > 0.5);
        assert!(tip("hip abduct").x > 0.5);
    }

    #[test]
    fn the_rest_pose_stretches_nothing() {
        let (mesh, skeleton) = tube();
        let weights = vec![vec![(JointId(1), 1.0)]; mesh.positions.len()];
        let pose = SweepPose {
            name: "none".into(),
            joint: JointId(1),
            axis: DVec3::X,
            angle: 0.0,
        };
        let check = check_deformation(
            &mesh,
            &skeleton,
            &weights,
            SweepKind::Animal,
            &[pose],
            vec![],
        )
        .unwrap();
        assert_eq!(check.total_over_1_5(), 0);
        assert!((check.worst() - 1.0).abs() < 1e-12);
    }
}

//! How far two sets of skin weights on the same skeleton move the mesh apart: the mean vertex
//! distance between the two skinned meshes over seeded random poses (the deformation error
//! RigNet reports against artists' weights, Xu et al. 2020).

use super::check::blend;
use super::SkinError;
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use glam::{DQuat, DVec3};
use serde::Serialize;

/// Options of [`pose_distance`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RandomPoseOptions {
    /// Number of random poses. Default 20.
    pub poses: usize,
    /// Largest rotation of a joint, degrees: every deforming joint turns about a uniformly
    /// random axis by an angle uniform in `[-max_degrees, max_degrees]`, relative to its
    /// parent. Default 30: well inside the range of every limb joint, so the poses stay
    /// plausible for humanoids and animals alike.
    pub max_degrees: f64,
    /// Seed of the pose generator (SplitMix64); the same seed gives the same poses.
    /// Default 20.
    pub seed: u64,
}

impl Default for RandomPoseOptions {
    fn default() -> Self {
        Self {
            poses: 20,
            max_degrees: 30.0,
            seed: 20,
        }
    }
}

/// The result of [`pose_distance`], in mesh units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PoseDistance {
    /// Mean over poses and vertices of the distance between the two posed meshes.
    pub mean: f64,
    /// Largest distance of one vertex in one pose.
    pub max: f64,
    /// Poses measured.
    pub poses: usize,
    /// Vertices measured: those both weightings bind (a vertex with no weight in either is
    /// left out, e.g. a rigid part the file attaches to a joint node instead of skinning it).
    pub vertices: usize,
}

/// The distance between `mesh` skinned to `skeleton` with weights `a` and with weights `b`
/// (per vertex `(joint, weight)` lists summing to one), over [`RandomPoseOptions::poses`]
/// seeded random poses (see [`random_pose`]), linear blend skinning as in
/// [`check_deformation`](super::check::check_deformation). Vertices without weights in `a`
/// or in `b` are left out.
///
/// # Errors
/// [`SkinError::SizeMismatch`] when `a` or `b` has another length than the mesh's vertices.
pub fn pose_distance(
    mesh: &Mesh,
    skeleton: &Skeleton,
    a: &[Vec<(JointId, f64)>],
    b: &[Vec<(JointId, f64)>],
    options: &RandomPoseOptions,
) -> Result<PoseDistance, SkinError> {
    for weights in [a, b] {
        if weights.len() != mesh.positions.len() {
            return Err(SkinError::SizeMismatch {
                what: "the weights",
                expected: mesh.positions.len(),
                found: weights.len(),
            });
        }
    }
    let measured: Vec<bool> = a
        .iter()
        .zip(b)
        .map(|(a, b)| !a.is_empty() && !b.is_empty())
        .collect();
    let mut random = SplitMix64(options.seed);
    let (mut sum, mut max, mut count) = (0.0, 0.0f64, 0usize);
    for _ in 0..options.poses {
        let pose = random_pose(skeleton, options.max_degrees, &mut random);
        let matrices = skeleton.skinning_matrices(&pose);
        let posed_a = blend(&mesh.positions, a, &matrices);
        let posed_b = blend(&mesh.positions, b, &matrices);
        for ((p, q), _) in posed_a
            .iter()
            .zip(&posed_b)
            .zip(&measured)
            .filter(|(_, &m)| m)
        {
            let d = p.distance(*q);
            sum += d;
            max = max.max(d);
            count += 1;
        }
    }
    Ok(PoseDistance {
        mean: if count > 0 { sum / count as f64 } else { 0.0 },
        max,
        poses: options.poses,
        vertices: measured.iter().filter(|&&m| m).count(),
    })
}

/// One random pose: every deforming joint turned about a uniformly random axis (in its local
/// frame) by an angle uniform in `[-max_degrees, max_degrees]`; control joints at rest.
pub fn random_pose(skeleton: &Skeleton, max_degrees: f64, random: &mut SplitMix64) -> Vec<DQuat> {
    skeleton
        .joints
        .iter()
        .map(|joint| {
            // Draw for every joint, so a joint's rotation does not depend on the deform flags
            // of the joints before it.
            let z = 2.0 * random.unit() - 1.0;
            let phi = std::f64::consts::TAU * random.unit();
            let angle = (2.0 * random.unit() - 1.0) * max_degrees.to_radians();
            let r = (1.0 - z * z).max(0.0).sqrt();
            let axis = DVec3::new(r * phi.cos(), r * phi.sin(), z);
            if joint.deform {
                DQuat::from_axis_angle(axis, angle)
            } else {
                DQuat::IDENTITY
            }
        })
        .collect()
}

/// The SplitMix64 generator (Steele, Lea & Flood 2014): small, seeded, the same numbers on
/// every platform.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number uniform in `[0, 1)` (53 random bits).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::Joint;

    fn rod() -> (Mesh, Skeleton) {
        let mesh = Mesh::capsule(DVec3::ZERO, 0.2, 1.0, 8, 12);
        let skeleton = Skeleton {
            joints: vec![
                Joint::new("a", None, DVec3::new(0.0, -1.0, 0.0)),
                Joint::new("b", Some(JointId(0)), DVec3::ZERO),
                Joint::new("c", Some(JointId(1)), DVec3::new(0.0, 1.0, 0.0)),
            ],
        };
        (mesh, skeleton)
    }

    #[test]
    fn equal_weights_are_zero_apart_and_different_ones_are_not() {
        let (mesh, skeleton) = rod();
        let split: Vec<Vec<(JointId, f64)>> = mesh
            .positions
            .iter()
            .map(|p| vec![(JointId(usize::from(p.y > 0.0)), 1.0)])
            .collect();
        let all_a = vec![vec![(JointId(0), 1.0)]; mesh.positions.len()];
        let options = RandomPoseOptions::default();
        let same = pose_distance(&mesh, &skeleton, &split, &split, &options).unwrap();
        assert_eq!(same.mean, 0.0);
        let apart = pose_distance(&mesh, &skeleton, &split, &all_a, &options).unwrap();
        // Half the vertices lie on b's bone, turned by up to 30° about b at 0..1 from it.
        assert!(apart.mean > 0.02 && apart.max < 1.2, "{apart:?}");
        assert_eq!(
            apart,
            pose_distance(&mesh, &skeleton, &split, &all_a, &options).unwrap()
        );
    }

    #[test]
    fn random_angles_stay_within_the_range() {
        let (_, skeleton) = rod();
        let mut random = SplitMix64(7);
        for _ in 0..100 {
            for q in random_pose(&skeleton, 30.0, &mut random) {
                assert!(q.to_axis_angle().1 <= 30f64.to_radians() + 1e-9);
            }
        }
    }
}

//! Posing a skinned mesh: linear blend skinning.

use super::{Skin, SkinError};
use crate::mesh::Mesh;
use crate::skeleton::Skeleton;
use glam::DQuat;

/// The mesh deformed by `pose` (one local rotation per joint, see
/// [`Skeleton::world_transforms`]) with linear blend skinning over the anchor weights of
/// `skin`: `p' = p + sum_j w_j (M_j p - p)` with `M_j` the [`Skeleton::skinning_matrices`].
///
/// This is the dissertation's anchoring (5.2.5): a vertex stored in each influencing
/// segment's local frame, `p_j = R_j^T (p - o_j)`, is carried back by the posed frame,
/// `o'_j + R'_j p_j = M_j p`, and the results are summed with the weights, `sum_j w_j M_j p`,
/// which equals the expression above because the weights sum to one. Writing it as a sum of
/// displacements makes a vertex whose joints are all at rest (identity matrices) come back
/// bit-for-bit unchanged, so the rest pose returns the input mesh exactly.
///
/// # Errors
/// [`SkinError::SizeMismatch`] when `skin` has another vertex count than `mesh` or `pose`
/// another joint count than `skeleton`, [`SkinError::NonFinitePose`] for a non-finite
/// rotation.
pub fn deform(
    mesh: &Mesh,
    skeleton: &Skeleton,
    skin: &Skin,
    pose: &[DQuat],
) -> Result<Mesh, SkinError> {
    if skin.weights.len() != mesh.positions.len() {
        return Err(SkinError::SizeMismatch {
            what: "the skin",
            expected: mesh.positions.len(),
            found: skin.weights.len(),
        });
    }
    if pose.len() != skeleton.len() {
        return Err(SkinError::SizeMismatch {
            what: "the pose",
            expected: skeleton.len(),
            found: pose.len(),
        });
    }
    if let Some(joint) = pose.iter().position(|q| !q.is_finite()) {
        return Err(SkinError::NonFinitePose { joint });
    }
    let matrices = skeleton.skinning_matrices(pose);
    let positions = super::check::blend(&mesh.positions, &skin.weights, &matrices);
    Ok(Mesh {
        positions,
        triangles: mesh.triangles.clone(),
    })
}

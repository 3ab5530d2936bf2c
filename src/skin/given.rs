//! Skinning a skeleton the user already has (an artist's rig, a BVH, an engine's skeleton):
//! the same weights as `skelfit rig`, after checking the skeleton fits the mesh.

use super::{placement, skin_from_bones, Placement, PlacementOptions, Skin, SkinOptions};
use crate::distance::edt;
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use crate::voxel::{voxelize_figure, Solid, VoxelOptions};
use crate::warning::Warning;

/// Options of [`skin_skeleton`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SkeletonSkinOptions {
    /// The voxel grid (default: as `skelfit rig`, 1 % of the longest side).
    pub voxel: VoxelOptions,
    /// The weights (default: as `skelfit rig`, geodesic).
    pub skin: SkinOptions,
    /// Tolerances of the placement checks.
    pub placement: PlacementOptions,
}

/// A mesh skinned to a given skeleton.
#[derive(Debug, Clone)]
pub struct SkinnedSkeleton {
    /// The weights, indexed by the given skeleton's joints; joints with `deform == false`
    /// carry none.
    pub skin: Skin,
    /// The voxelized figure the weights were computed on.
    pub solid: Solid,
    /// How the skeleton sits in the figure.
    pub placement: Placement,
    /// Warnings of the voxelization, the placement checks and the skin.
    pub warnings: Vec<Warning>,
}

/// Skins `mesh` to `skeleton` as it is: same units and frame as the mesh, joint names,
/// order and hierarchy untouched. Runs the stages of `skelfit rig`'s skinning (voxelize,
/// [`edt`], [`skin_from_bones`] with `options.skin`) after [`placement`] has checked the
/// skeleton against the voxelized figure.
///
/// Joints with `deform == false` (IK and pole targets, roots, end markers) get no weight.
/// A control joint hanging from a deforming joint that has deforming children of its own (a
/// pole target parented to the body, a weapon socket on a hand) is not one of its parent's
/// bones: only bones to deforming children, or to the one control child of a chain's last
/// deforming joint (an end marker), carry the parent's region.
///
/// # Errors
/// [`crate::Error::Skin`] for an empty or invalid skeleton (duplicate names, parents after
/// children), no deforming joint, a skeleton in other units or misplaced ([`placement`]), or
/// no bone inside the figure; [`crate::Error::Voxel`] when the mesh does not voxelize.
pub fn skin_skeleton(
    mesh: &Mesh,
    skeleton: &Skeleton,
    options: &SkeletonSkinOptions,
) -> Result<SkinnedSkeleton, crate::Error> {
    super::bind::check_skeleton(skeleton)?;
    options.skin.validate()?;
    options.placement.validate()?;
    options.voxel.validate()?;
    let solid = voxelize_figure(mesh, &options.voxel)?;
    let placed = placement(skeleton, &solid, &options.placement)?;
    let distance = edt(&solid);
    let skin = skin_from_bones(
        mesh,
        &bones_only(skeleton),
        &solid,
        &distance,
        &options.skin,
    )?;
    debug_assert!(skin
        .weights
        .iter()
        .flatten()
        .all(|&(j, _)| skeleton.joint(j).deform));
    let warnings = solid
        .report
        .warnings()
        .into_iter()
        .map(Warning::Voxel)
        .chain(placed.warnings.iter().cloned().map(Warning::Skin))
        .chain(skin.warnings.iter().cloned().map(Warning::Skin))
        .collect();
    Ok(SkinnedSkeleton {
        skin,
        solid,
        placement: placed,
        warnings,
    })
}

/// `skeleton` with every control joint detached (made a root) whose parent has deforming
/// children: [`skin_from_bones`] then builds no bone towards it. Joint ids are unchanged.
fn bones_only(skeleton: &Skeleton) -> Skeleton {
    let mut deforming_children = vec![0usize; skeleton.len()];
    for joint in &skeleton.joints {
        if let Some(p) = joint.parent.filter(|_| joint.deform) {
            deforming_children[p.0] += 1;
        }
    }
    let mut bones = skeleton.clone();
    for joint in &mut bones.joints {
        if !joint.deform
            && joint
                .parent
                .is_some_and(|p: JointId| deforming_children[p.0] > 0)
        {
            joint.parent = None;
        }
    }
    bones
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::Joint;
    use glam::DVec3;

    #[test]
    fn control_joints_get_no_bone_and_no_weight() {
        let mesh = Mesh::capsule(DVec3::ZERO, 0.5, 1.5, 8, 16);
        let mut pole = Joint::new("pole", Some(JointId(1)), DVec3::new(0.0, 0.0, 3.0));
        pole.deform = false;
        let skeleton = Skeleton {
            joints: vec![
                Joint::new("root", None, DVec3::new(0.0, -1.5, 0.0)),
                Joint::new("mid", Some(JointId(0)), DVec3::ZERO),
                Joint::new("tip", Some(JointId(1)), DVec3::new(0.0, 1.5, 0.0)),
                pole,
            ],
        };
        let bones = bones_only(&skeleton);
        assert_eq!(bones.joints[3].parent, None);
        assert_eq!(bones.joints[2].parent, Some(JointId(1)));
        let skinned = skin_skeleton(&mesh, &skeleton, &SkeletonSkinOptions::default()).unwrap();
        assert!(skinned
            .skin
            .weights
            .iter()
            .flatten()
            .all(|&(j, w)| j != JointId(3) && w > 0.0));
        assert_eq!(skinned.placement.outside, Vec::<JointId>::new());
    }
}

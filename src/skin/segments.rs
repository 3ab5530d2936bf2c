//! Control segments with the chain voxels at the core of their regions of influence.

use super::SkinOptions;
use crate::distance::DistanceMap;
use crate::skeleton::{JointId, Skeleton};
use crate::voxel::Solid;
use glam::DVec3;

/// One control segment and the voxels at the core of its region of influence (dissertation
/// 5.2.5: the path-tree chain the segment was derived from; 8.3: the voxels the segment passes
/// through).
#[derive(Debug, Clone, PartialEq)]
pub struct SegmentVoxels {
    /// The joint that moves this segment (its proximal joint).
    pub joint: JointId,
    /// The distal joint: the segment's line runs from `joint` to `child`.
    pub child: Option<JointId>,
    /// Distal end (mesh units, mesh frame) when there is no `child` (a leaf segment); ignored
    /// when `child` is set. Without both, the segment is the point at `joint`.
    pub tip: Option<DVec3>,
    /// Linear grid indices of the chain voxels, ascending.
    pub voxels: Vec<usize>,
}

impl SegmentVoxels {
    /// The segment's line `(start, end)` in mesh units and frame, used for the distances of the
    /// weight formula. The joints must exist in `skeleton`.
    pub fn line(&self, skeleton: &Skeleton) -> (DVec3, DVec3) {
        let start = skeleton.joint(self.joint).position;
        let end = match (self.child, self.tip) {
            (Some(child), _) => skeleton.joint(child).position,
            (None, Some(tip)) => tip,
            (None, None) => start,
        };
        (start, end)
    }
}

/// Segments derived from the bones of a skeleton alone, for skeletons that come without path
/// tree chains (the anatomical fit, reference rigs, tests).
///
/// Every deforming joint gets one segment per child (the bone from it to the child); a
/// deforming leaf joint gets a segment continuing its parent bone's direction for at most
/// [`SkinOptions::leaf_extension`] of its length, to the end of its body part (see
/// `leaf_tip`: where the figure ends or another bone's part begins). The chain
/// voxels are the interior voxels nearest to sample points every
/// [`SkinOptions::bone_sample_spacing`] voxels along the segment (searched within
/// [`SkinOptions::bone_search_radius`]). Segments come in joint order, children in joint order.
/// Joints must be valid ids of `skeleton` (parents before children).
pub fn bone_segments(
    skeleton: &Skeleton,
    solid: &Solid,
    distance: &DistanceMap,
    options: &SkinOptions,
) -> Vec<SegmentVoxels> {
    let mut children: Vec<Vec<JointId>> = vec![Vec::new(); skeleton.len()];
    for (k, joint) in skeleton.joints.iter().enumerate() {
        if let Some(p) = joint.parent.filter(|p| p.0 < k) {
            children[p.0].push(JointId(k));
        }
    }
    // Every bone of a deforming joint, as (proximal, distal) joints: what a leaf's extension
    // must not run into.
    let bones: Vec<(JointId, JointId)> = children
        .iter()
        .enumerate()
        .filter(|(k, _)| skeleton.joints[*k].deform)
        .flat_map(|(k, c)| c.iter().map(move |&c| (JointId(k), c)))
        .collect();
    let mut segments = Vec::new();
    for (k, joint) in skeleton.joints.iter().enumerate() {
        if !joint.deform {
            continue;
        }
        let id = JointId(k);
        if children[k].is_empty() {
            let tip = leaf_tip(skeleton, id, &bones, solid, distance, options);
            let voxels = chain_voxels(joint.position, tip, solid, distance, options);
            segments.push(SegmentVoxels {
                joint: id,
                child: None,
                tip: Some(tip),
                voxels,
            });
        }
        for &child in &children[k] {
            let end = skeleton.joint(child).position;
            let voxels = chain_voxels(joint.position, end, solid, distance, options);
            segments.push(SegmentVoxels {
                joint: id,
                child: Some(child),
                tip: None,
                voxels,
            });
        }
    }
    segments
}

/// The distal end of a leaf joint's segment: along the parent bone, at most
/// `leaf_extension` of its length, stopping at the last interior sample before the figure's
/// surface or before another bone (one of `bones` not ending at the leaf joint) comes within
/// the local radius (the inscribed ball of the sample holds part of that bone: the
/// extension has left the leaf's body part and entered another's).
///
/// A leaf bone carries the end of the figure it points into (a head beyond a short neck, a
/// hoof below the lower leg), however long that end is, but not a part that another bone
/// carries: a torso joint that ends a chain midway along the body, or a lower leg whose
/// continuation holds a foot bone of its own (an IK foot joint outside the leg's chain).
fn leaf_tip(
    skeleton: &Skeleton,
    id: JointId,
    bones: &[(JointId, JointId)],
    solid: &Solid,
    distance: &DistanceMap,
    options: &SkinOptions,
) -> DVec3 {
    let joint = skeleton.joint(id);
    let Some(parent) = joint.parent.filter(|p| p.0 < id.0) else {
        return joint.position;
    };
    let bone = joint.position - skeleton.joint(parent).position;
    // No farther than across the grid: the figure ends before.
    let grid_size =
        (DVec3::from(solid.grid.dims.map(|d| d as f64)) * solid.grid.voxel_size).length();
    let reach = (bone.length() * options.leaf_extension.max(0.0)).min(grid_size);
    let far = joint.position + bone.normalize_or_zero() * reach;
    let grid = &solid.grid;
    let steps = samples(
        joint.position,
        far,
        grid.voxel_size,
        options.bone_sample_spacing,
    );
    let others: Vec<(DVec3, DVec3)> = bones
        .iter()
        .filter(|&&(a, b)| a != id && b != id)
        .map(|&(a, b)| (skeleton.joint(a).position, skeleton.joint(b).position))
        .collect();
    // How far (voxels) the extension may run outside the figure and still go on: a gap
    // between two shells (a head modelled apart from the neck) as narrow as a bone may lie
    // outside and still find its chain voxels.
    let max_gap = options.bone_search_radius as f64;
    let step = (far - joint.position).length() / grid.voxel_size / steps as f64;
    let mut gap = 0.0;
    let mut tip = joint.position;
    for s in 1..=steps {
        let p = joint.position.lerp(far, s as f64 / steps as f64);
        let Some(index) = grid
            .voxel_at(p)
            .map(|c| grid.index(c))
            .filter(|&i| solid.inside[i])
        else {
            gap += step;
            if gap > max_gap {
                break;
            }
            continue;
        };
        gap = 0.0;
        let radius = distance.distance(index) * grid.voxel_size;
        if others
            .iter()
            .any(|&(a, b)| point_segment_distance(p, a, b) < radius)
        {
            break;
        }
        tip = p;
    }
    tip
}

/// Distance from `p` to the segment `a..b`.
fn point_segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + ab * t).distance(p)
}

/// Number of sample intervals along `a..b` for a spacing of `spacing` voxels.
fn samples(a: DVec3, b: DVec3, voxel_size: f64, spacing: f64) -> usize {
    let length = (b - a).length() / voxel_size;
    let spacing = if spacing.is_finite() && spacing > 0.0 {
        spacing
    } else {
        SkinOptions::default().bone_sample_spacing
    };
    ((length / spacing).ceil() as usize).clamp(1, 1 << 20)
}

/// The interior voxels nearest to samples along `a..b`, ascending and without repeats.
fn chain_voxels(
    a: DVec3,
    b: DVec3,
    solid: &Solid,
    distance: &DistanceMap,
    options: &SkinOptions,
) -> Vec<usize> {
    let grid = &solid.grid;
    let steps = samples(a, b, grid.voxel_size, options.bone_sample_spacing);
    let mut voxels: Vec<usize> = (0..=steps)
        .filter_map(|s| {
            let p = a.lerp(b, s as f64 / steps as f64);
            nearest_interior(p, solid, distance, options.bone_search_radius)
        })
        .collect();
    voxels.sort_unstable();
    voxels.dedup();
    voxels
}

/// The interior voxel whose centre is nearest to `p` within a cube of `radius` voxels around
/// the voxel containing `p` (ties: the lowest index), or `None`.
fn nearest_interior(
    p: DVec3,
    solid: &Solid,
    distance: &DistanceMap,
    radius: usize,
) -> Option<usize> {
    let grid = &solid.grid;
    let v = grid.to_voxel(p).floor();
    let r = radius as i64;
    let mut best: Option<(f64, usize)> = None;
    for dz in -r..=r {
        for dy in -r..=r {
            for dx in -r..=r {
                let c = [v.x as i64 + dx, v.y as i64 + dy, v.z as i64 + dz];
                if (0..3).any(|a| c[a] < 0 || c[a] >= grid.dims[a] as i64) {
                    continue;
                }
                let coords = [c[0] as usize, c[1] as usize, c[2] as usize];
                let index = grid.index(coords);
                if !solid.inside[index] || distance.squared[index] == 0 {
                    continue;
                }
                let d = (grid.centre(coords) - p).length_squared();
                if best.is_none_or(|(bd, bi)| d < bd || (d == bd && index < bi)) {
                    best = Some((d, index));
                }
            }
        }
    }
    best.map(|(_, index)| index)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distance::edt;
    use crate::mesh::Mesh;
    use crate::skeleton::Joint;
    use crate::voxel::{voxelize, VoxelOptions, VoxelSize};

    /// Regression (issue 20): a head beyond a short neck took only one neck length of segment,
    /// and the neck shared the head's skin. The leaf runs to the end of the figure, and stops
    /// where another bone's part begins.
    #[test]
    fn a_leaf_runs_to_the_end_of_its_part_but_not_into_another_bone() {
        // A box 4 long in y: a short "neck" bone 1.0 -> 1.2, its leaf "head" runs to the top.
        let mesh = Mesh::cuboid(DVec3::new(-0.5, 0.0, -0.5), DVec3::new(0.5, 4.0, 0.5));
        let options = VoxelOptions {
            size: VoxelSize::Absolute(0.1),
            ..Default::default()
        };
        let solid = voxelize(&mesh, &options).unwrap();
        let distance = edt(&solid);
        let mut skeleton = Skeleton {
            joints: vec![
                Joint::new("neck", None, DVec3::new(0.0, 1.0, 0.0)),
                Joint::new("head", Some(JointId(0)), DVec3::new(0.0, 1.2, 0.0)),
            ],
        };
        let tip = |skeleton: &Skeleton| {
            let segments = bone_segments(skeleton, &solid, &distance, &SkinOptions::default());
            segments
                .iter()
                .find(|s| s.joint == JointId(1))
                .unwrap()
                .tip
                .unwrap()
        };
        let head = tip(&skeleton);
        assert!(head.y > 3.8, "the head's segment ends at {head}");
        // A bone of another chain in the way (an IK foot joint and its bone at y 3..3.3):
        // the leaf stops about the local radius (0.5) before it.
        skeleton
            .joints
            .push(Joint::new("ik", None, DVec3::new(0.0, 3.0, 0.0)));
        skeleton.joints.push(Joint::new(
            "toe",
            Some(JointId(2)),
            DVec3::new(0.0, 3.3, 0.0),
        ));
        let head = tip(&skeleton);
        assert!(
            head.y > 2.2 && head.y < 2.7,
            "the head's segment ends at {head}"
        );
    }

    #[test]
    fn bones_get_interior_chains_and_leaves_stop_at_the_surface() {
        // A box 4 long in y; the chain ends 1 below the top.
        let mesh = Mesh::cuboid(DVec3::new(-0.5, 0.0, -0.5), DVec3::new(0.5, 4.0, 0.5));
        let options = VoxelOptions {
            size: VoxelSize::Absolute(0.1),
            ..Default::default()
        };
        let solid = voxelize(&mesh, &options).unwrap();
        let distance = edt(&solid);
        let skeleton = Skeleton {
            joints: vec![
                Joint::new("a", None, DVec3::new(0.0, 1.0, 0.0)),
                Joint::new("b", Some(JointId(0)), DVec3::new(0.0, 3.0, 0.0)),
            ],
        };
        let segments = bone_segments(&skeleton, &solid, &distance, &SkinOptions::default());
        assert_eq!(segments.len(), 2);
        assert_eq!(segments[0].child, Some(JointId(1)));
        assert!(segments[0].voxels.len() >= 20);
        assert!(segments[0].voxels.iter().all(|&v| solid.inside[v]));
        assert!(segments[0].voxels.windows(2).all(|w| w[0] < w[1]));
        // The leaf continues upwards by at most one bone length and stops inside the box.
        let tip = segments[1].tip.unwrap();
        assert!(tip.y > 3.8 && tip.y < 4.0, "tip at {tip}");
        assert!(segments[1].voxels.iter().all(|&v| solid.inside[v]));
    }
}

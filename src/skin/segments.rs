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
/// deforming leaf joint gets a segment continuing its parent bone's direction for
/// [`SkinOptions::leaf_extension`] of its length, cut where it leaves the figure. The chain
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
    let mut segments = Vec::new();
    for (k, joint) in skeleton.joints.iter().enumerate() {
        if !joint.deform {
            continue;
        }
        let id = JointId(k);
        if children[k].is_empty() {
            let tip = leaf_tip(skeleton, id, solid, options);
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
/// `leaf_extension` of its length, stopping at the last interior sample.
fn leaf_tip(skeleton: &Skeleton, id: JointId, solid: &Solid, options: &SkinOptions) -> DVec3 {
    let joint = skeleton.joint(id);
    let Some(parent) = joint.parent.filter(|p| p.0 < id.0) else {
        return joint.position;
    };
    let bone = joint.position - skeleton.joint(parent).position;
    let far = joint.position + bone * options.leaf_extension.max(0.0);
    let grid = &solid.grid;
    let steps = samples(
        joint.position,
        far,
        grid.voxel_size,
        options.bone_sample_spacing,
    );
    let mut tip = joint.position;
    for s in 1..=steps {
        let p = joint.position.lerp(far, s as f64 / steps as f64);
        match grid.voxel_at(p) {
            Some(c) if solid.inside[grid.index(c)] => tip = p,
            _ => break,
        }
    }
    tip
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

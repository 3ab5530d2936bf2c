//! How a skeleton that did not come from skelfit sits in the figure it is to skin: units,
//! placement, joints outside the skin, zero-length bones and bones crossing empty space.
//!
//! A skeleton fitted by skelfit lies inside its figure by construction. One brought by the
//! user (an artist's rig, a BVH, a game engine's skeleton) may be in other units, another
//! frame, or only roughly placed; skinning it anyway gives weights that look plausible in the
//! file and tear in the engine. [`placement`] measures it against the voxelized figure and
//! returns errors for what cannot give a usable skin and warnings naming every joint and bone
//! that will skin poorly.

use super::{SkinError, SkinWarning};
use crate::skeleton::{JointId, Skeleton};
use crate::voxel::Solid;
use glam::DVec3;

/// Tolerances of [`placement`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlacementOptions {
    /// How far (voxels, Chebyshev radius) a deforming joint may lie from the nearest interior
    /// voxel and still count as inside. Default 2: joints of thin fingers and joints that the
    /// artist put on the skin count as inside, the refdata rigs' face bones (eye sockets,
    /// mouth cavity) and misplaced joints do not.
    pub joint_tolerance: usize,
    /// Largest ratio of the skeleton's size to the figure's (bounding-box diagonals of the
    /// deforming joints and of the interior voxels) taken as the same units. Default 1.6:
    /// the joints lie inside the figure, so the ratio is below 1 for every refdata rig
    /// (0.60-0.99); a skeleton in inches on a mesh in centimetres gives ~2.
    pub max_size_ratio: f64,
    /// Smallest such ratio taken as the same units. Default 0.1: a skeleton a tenth of its
    /// figure's size is one in metres on a mesh in centimetres or millimetres (0.008 or less)
    /// rather than a partial rig (the refdata rigs: 0.60 and more).
    pub min_size_ratio: f64,
    /// Smallest share of the deforming joints that must lie inside for the skeleton to count as
    /// placed in the figure; below it the skeleton is refused as misplaced. Default 0.5: the
    /// refdata rigs have 88-100 % inside.
    pub min_inside_share: f64,
    /// A bone shorter than this (voxels) is reported as zero-length. Default 0.01.
    pub zero_length: f64,
    /// A bone between two joints inside the figure whose longest stretch outside is at least
    /// this share of its length (and at least [`Self::empty_min_voxels`]) is reported as
    /// crossing empty space. Default 0.25.
    pub empty_share: f64,
    /// The shortest stretch outside (voxels) reported as empty space. Default 3: a bone that
    /// grazes a concave surface (a clavicle along the top of the shoulder) is not reported;
    /// no bone of the refdata rigs is.
    pub empty_min_voxels: f64,
}

impl Default for PlacementOptions {
    fn default() -> Self {
        Self {
            joint_tolerance: 2,
            max_size_ratio: 1.6,
            min_size_ratio: 0.1,
            min_inside_share: 0.5,
            zero_length: 0.01,
            empty_share: 0.25,
            empty_min_voxels: 3.0,
        }
    }
}

/// What [`placement`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct Placement {
    /// Size of the skeleton (bounding-box diagonal of its deforming joints) over the figure's
    /// (bounding-box diagonal of the interior voxels).
    pub size_ratio: f64,
    /// Deforming joints that lie outside the figure, in joint order.
    pub outside: Vec<JointId>,
    /// Joints that sit on their parent (a bone of zero length), in joint order.
    pub zero_length: Vec<JointId>,
    /// Bones (`parent`, `child`) that cross empty space, with the longest stretch outside as a
    /// share of the bone's length.
    pub empty_bones: Vec<(JointId, JointId, f64)>,
    /// One warning per kind of problem found, naming the joints.
    pub warnings: Vec<SkinWarning>,
}

/// Unit factors a skeleton and a mesh commonly differ by, with what they usually mean.
const UNIT_FACTORS: [(f64, &str); 5] = [
    (2.54, "centimetres against inches"),
    (10.0, "millimetres against centimetres"),
    (39.37, "inches against metres"),
    (100.0, "centimetres against metres"),
    (1000.0, "millimetres against metres"),
];

/// The size ratio the skeleton of a figure usually has (the refdata rigs' median, 0.8).
const TYPICAL_SIZE_RATIO: f64 = 0.8;

/// Measures `skeleton` against `solid`, the voxelization of the mesh it is to skin (same
/// units and frame).
///
/// # Errors
/// [`SkinError::NoDeformingJoint`] when no joint deforms; [`SkinError::UnitMismatch`] when
/// the skeleton's size is outside `[min_size_ratio, max_size_ratio]` of the figure's (with the
/// likely unit factor); [`SkinError::SkeletonOutside`] when fewer than `min_inside_share` of
/// the deforming joints lie inside the figure; [`SkinError::InvalidOption`] for a tolerance
/// out of range.
pub fn placement(
    skeleton: &Skeleton,
    solid: &Solid,
    options: &PlacementOptions,
) -> Result<Placement, SkinError> {
    options.validate()?;
    let deforming: Vec<JointId> = (0..skeleton.len())
        .map(JointId)
        .filter(|&j| skeleton.joint(j).deform)
        .collect();
    if deforming.is_empty() {
        return Err(SkinError::NoDeformingJoint {
            joints: skeleton.len(),
        });
    }
    let figure = interior_box(solid);
    let (low, high) = bounds(deforming.iter().map(|&j| skeleton.joint(j).position));
    let figure_size = (figure.1 - figure.0).length();
    let size_ratio = (high - low).length() / figure_size.max(f64::MIN_POSITIVE);
    // A single joint (or coincident joints) has no size to compare.
    let sized = deforming.len() >= 2 && high != low;
    if sized && !(options.min_size_ratio..=options.max_size_ratio).contains(&size_ratio) {
        let (factor, units) = unit_factor(size_ratio);
        return Err(SkinError::UnitMismatch {
            ratio: size_ratio,
            factor,
            units,
        });
    }
    let inside = |p: DVec3| near_interior(p, solid, options.joint_tolerance);
    let outside: Vec<JointId> = deforming
        .iter()
        .copied()
        .filter(|&j| !inside(skeleton.joint(j).position))
        .collect();
    let inside_count = deforming.len() - outside.len();
    if (inside_count as f64) < options.min_inside_share * deforming.len() as f64 {
        return Err(SkinError::SkeletonOutside {
            inside: inside_count,
            outside: outside
                .iter()
                .take(super::error::OUTSIDE_LISTED)
                .map(|&j| skeleton.joint(j).name.clone())
                .collect(),
            deforming: deforming.len(),
            skeleton_centre: ((low + high) * 0.5).to_array(),
            figure_centre: ((figure.0 + figure.1) * 0.5).to_array(),
        });
    }
    let voxel = solid.grid.voxel_size;
    let zero_length: Vec<JointId> = (0..skeleton.len())
        .map(JointId)
        .filter(|&j| {
            let joint = skeleton.joint(j);
            joint.deform
                && joint.parent.is_some_and(|p| {
                    (skeleton.joint(p).position - joint.position).length()
                        < options.zero_length * voxel
                })
        })
        .collect();
    let empty_bones = bones_crossing_empty_space(skeleton, solid, &deforming, &outside, options);
    let warnings = placement_warnings(
        skeleton,
        &outside,
        &zero_length,
        &empty_bones,
        deforming.len(),
    );
    Ok(Placement {
        size_ratio,
        outside,
        zero_length,
        empty_bones,
        warnings,
    })
}

/// The bones between two deforming joints inside the figure whose longest stretch outside
/// is at least [`PlacementOptions::empty_min_voxels`] and
/// [`PlacementOptions::empty_share`] of their length: `(parent, child, share outside)`.
fn bones_crossing_empty_space(
    skeleton: &Skeleton,
    solid: &Solid,
    deforming: &[JointId],
    outside: &[JointId],
    options: &PlacementOptions,
) -> Vec<(JointId, JointId, f64)> {
    let voxel = solid.grid.voxel_size;
    let mut empty_bones = Vec::new();
    for &child in deforming {
        let Some(parent) = skeleton.joint(child).parent else {
            continue;
        };
        if !skeleton.joint(parent).deform || outside.contains(&child) || outside.contains(&parent) {
            continue;
        }
        let (a, b) = (
            skeleton.joint(parent).position,
            skeleton.joint(child).position,
        );
        let length = (b - a).length() / voxel;
        let run = longest_outside_run(a, b, solid);
        if run >= options.empty_min_voxels && run >= options.empty_share * length {
            empty_bones.push((parent, child, run / length));
        }
    }
    empty_bones
}

/// One warning per kind of placement problem, naming the joints.
fn placement_warnings(
    skeleton: &Skeleton,
    outside: &[JointId],
    zero_length: &[JointId],
    empty_bones: &[(JointId, JointId, f64)],
    deforming: usize,
) -> Vec<SkinWarning> {
    let name = |j: JointId| skeleton.joint(j).name.clone();
    let mut warnings = Vec::new();
    if !outside.is_empty() {
        warnings.push(SkinWarning::JointsOutside {
            joints: outside.iter().map(|&j| name(j)).collect(),
            deforming,
        });
    }
    for &j in zero_length {
        if let Some(p) = skeleton.joint(j).parent {
            warnings.push(SkinWarning::ZeroLengthBone {
                parent: name(p),
                joint: name(j),
            });
        }
    }
    for &(parent, child, share) in empty_bones {
        warnings.push(SkinWarning::BoneOutside {
            parent: name(parent),
            joint: name(child),
            share,
        });
    }
    warnings
}

impl PlacementOptions {
    /// Checks every field is in range.
    ///
    /// # Errors
    /// [`SkinError::InvalidOption`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), SkinError> {
        let ratios = self.min_size_ratio > 0.0
            && self.min_size_ratio < self.max_size_ratio
            && self.max_size_ratio.is_finite();
        for (name, value, ok, expected) in [
            (
                "min_size_ratio",
                self.min_size_ratio,
                ratios,
                "give 0 < min_size_ratio < max_size_ratio, both finite",
            ),
            (
                "min_inside_share",
                self.min_inside_share,
                (0.0..=1.0).contains(&self.min_inside_share),
                "give a share from 0 to 1",
            ),
            (
                "zero_length",
                self.zero_length,
                self.zero_length >= 0.0 && self.zero_length.is_finite(),
                "give a finite number of voxels, zero or more",
            ),
            (
                "empty_share",
                self.empty_share,
                self.empty_share > 0.0 && self.empty_share <= 1.0,
                "give a share above 0 and at most 1",
            ),
            (
                "empty_min_voxels",
                self.empty_min_voxels,
                self.empty_min_voxels >= 0.0 && self.empty_min_voxels.is_finite(),
                "give a finite number of voxels, zero or more",
            ),
            (
                "joint_tolerance",
                self.joint_tolerance as f64,
                self.joint_tolerance <= 64,
                "give at most 64 voxels",
            ),
        ] {
            if !ok {
                return Err(SkinError::InvalidOption {
                    name,
                    value,
                    expected,
                });
            }
        }
        Ok(())
    }
}

/// The unit factor nearest to explaining `ratio` (the skeleton over the figure, against
/// [`TYPICAL_SIZE_RATIO`]): greater than one when the skeleton is too large. Without a common
/// factor within 1.5× the raw factor and `"units that differ"`.
fn unit_factor(ratio: f64) -> (f64, &'static str) {
    let wanted = ratio / TYPICAL_SIZE_RATIO;
    let best = UNIT_FACTORS
        .iter()
        .flat_map(|&(f, units)| [(f, units), (1.0 / f, units)])
        .min_by(|a, b| {
            (wanted / a.0)
                .ln()
                .abs()
                .total_cmp(&(wanted / b.0).ln().abs())
        });
    match best {
        Some((f, units)) if (wanted / f).ln().abs() < 1.5f64.ln() => (f, units),
        _ => (wanted, "units that differ"),
    }
}

/// The bounding box of the interior voxels' centres grown by half a voxel (mesh units); the
/// grid's box when nothing is inside.
fn interior_box(solid: &Solid) -> (DVec3, DVec3) {
    let grid = &solid.grid;
    let (low, high) = bounds(
        solid
            .inside
            .iter()
            .enumerate()
            .filter(|(_, &inside)| inside)
            .map(|(i, _)| grid.centre(grid.coords(i))),
    );
    if low.x > high.x {
        let size = DVec3::new(
            grid.dims[0] as f64,
            grid.dims[1] as f64,
            grid.dims[2] as f64,
        ) * grid.voxel_size;
        return (grid.origin, grid.origin + size);
    }
    let half = DVec3::splat(0.5 * grid.voxel_size);
    (low - half, high + half)
}

/// Component-wise minimum and maximum (`low > high` when empty).
fn bounds(points: impl Iterator<Item = DVec3>) -> (DVec3, DVec3) {
    points.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(low, high), p| (low.min(p), high.max(p)),
    )
}

/// True when an interior voxel lies within `radius` voxels (Chebyshev) of the voxel holding
/// `p`; false for points outside the grid.
fn near_interior(p: DVec3, solid: &Solid, radius: usize) -> bool {
    let grid = &solid.grid;
    let v = grid.to_voxel(p).floor();
    if !v.is_finite() {
        return false;
    }
    let r = radius as i64;
    let centre = [v.x as i64, v.y as i64, v.z as i64];
    for dz in -r..=r {
        for dy in -r..=r {
            for dx in -r..=r {
                let c = [centre[0] + dx, centre[1] + dy, centre[2] + dz];
                if (0..3).any(|a| c[a] < 0 || c[a] >= grid.dims[a] as i64) {
                    continue;
                }
                if solid.inside[grid.index([c[0] as usize, c[1] as usize, c[2] as usize])] {
                    return true;
                }
            }
        }
    }
    false
}

/// The longest stretch of `a..b` (voxels) whose samples (every half voxel) have no interior
/// voxel within one voxel.
fn longest_outside_run(a: DVec3, b: DVec3, solid: &Solid) -> f64 {
    let voxel = solid.grid.voxel_size;
    let length = (b - a).length() / voxel;
    let steps = ((length / 0.5).ceil() as usize).clamp(1, 1 << 20);
    let step = length / steps as f64;
    let (mut run, mut longest) = (0usize, 0usize);
    for s in 0..=steps {
        if near_interior(a.lerp(b, s as f64 / steps as f64), solid, 1) {
            run = 0;
        } else {
            run += 1;
            longest = longest.max(run);
        }
    }
    // `n` consecutive samples outside span `n - 1` steps (one sample: a point).
    longest.saturating_sub(1) as f64 * step
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::skeleton::Joint;
    use crate::voxel::{voxelize, VoxelOptions, VoxelSize};

    /// A U: two pillars 1 apart along x, each 1 × 4 × 1, standing on a bar 1 high (three
    /// overlapping boxes), voxels of 0.1.
    fn two_pillars() -> Solid {
        let mut a = Mesh::cuboid(DVec3::new(-1.5, 0.0, -0.5), DVec3::new(-0.5, 4.0, 0.5));
        for b in [
            Mesh::cuboid(DVec3::new(0.5, 0.0, -0.5), DVec3::new(1.5, 4.0, 0.5)),
            Mesh::cuboid(DVec3::new(-1.4, 0.1, -0.4), DVec3::new(1.4, 1.0, 0.4)),
        ] {
            let offset = a.positions.len() as u32;
            a.positions.extend(b.positions);
            a.triangles
                .extend(b.triangles.iter().map(|t| t.map(|i| i + offset)));
        }
        let options = VoxelOptions {
            size: VoxelSize::Absolute(0.1),
            ..Default::default()
        };
        voxelize(&a, &options).unwrap()
    }

    fn chain(points: &[(&str, DVec3)]) -> Skeleton {
        Skeleton {
            joints: points
                .iter()
                .enumerate()
                .map(|(k, &(name, p))| Joint::new(name, k.checked_sub(1).map(JointId), p))
                .collect(),
        }
    }

    #[test]
    fn a_skeleton_along_one_pillar_is_placed_without_warnings() {
        let solid = two_pillars();
        let skeleton = chain(&[
            ("a", DVec3::new(-1.0, 0.5, 0.0)),
            ("b", DVec3::new(-1.0, 2.0, 0.0)),
            ("c", DVec3::new(-1.0, 3.5, 0.0)),
        ]);
        let placed = placement(&skeleton, &solid, &PlacementOptions::default()).unwrap();
        assert!(placed.warnings.is_empty(), "{:?}", placed.warnings);
        assert!(placed.size_ratio > 0.5 && placed.size_ratio < 1.0);
    }

    #[test]
    fn a_bone_between_the_pillars_crosses_empty_space() {
        let solid = two_pillars();
        let skeleton = chain(&[
            ("a", DVec3::new(-1.0, 0.5, 0.0)),
            ("b", DVec3::new(-1.0, 3.5, 0.0)),
            ("c", DVec3::new(1.0, 3.5, 0.0)),
        ]);
        let placed = placement(&skeleton, &solid, &PlacementOptions::default()).unwrap();
        assert_eq!(placed.empty_bones.len(), 1);
        let (parent, child, share) = placed.empty_bones[0];
        assert_eq!((parent, child), (JointId(1), JointId(2)));
        // 1 of the bone's 2 units lies between the pillars (less the one-voxel margin).
        assert!(share > 0.35 && share < 0.55, "share {share}");
    }

    #[test]
    fn zero_length_bones_and_joints_outside_are_named() {
        let solid = two_pillars();
        let skeleton = chain(&[
            ("a", DVec3::new(-1.0, 0.5, 0.0)),
            ("b", DVec3::new(-1.0, 2.0, 0.0)),
            ("b_twin", DVec3::new(-1.0, 2.0, 0.0)),
            ("c", DVec3::new(-1.0, 3.5, 0.0)),
            ("far", DVec3::new(-1.0, 3.5, 3.0)),
        ]);
        let placed = placement(&skeleton, &solid, &PlacementOptions::default()).unwrap();
        assert_eq!(placed.zero_length, vec![JointId(2)]);
        assert_eq!(placed.outside, vec![JointId(4)]);
        let text: Vec<String> = placed.warnings.iter().map(ToString::to_string).collect();
        assert!(text.iter().any(|w| w.contains("far")), "{text:?}");
        assert!(text.iter().any(|w| w.contains("b_twin")), "{text:?}");
    }

    #[test]
    fn units_and_misplacement_are_errors() {
        let solid = two_pillars();
        let scaled = chain(&[
            ("a", DVec3::new(-100.0, 50.0, 0.0)),
            ("b", DVec3::new(-100.0, 350.0, 0.0)),
        ]);
        match placement(&scaled, &solid, &PlacementOptions::default()) {
            Err(SkinError::UnitMismatch { factor, .. }) => assert_eq!(factor, 100.0),
            other => panic!("expected a unit mismatch, got {other:?}"),
        }
        let moved = chain(&[
            ("a", DVec3::new(-1.0, 10.5, 0.0)),
            ("b", DVec3::new(-1.0, 13.5, 0.0)),
        ]);
        assert!(matches!(
            placement(&moved, &solid, &PlacementOptions::default()),
            Err(SkinError::SkeletonOutside { inside: 0, ref outside, .. }) if outside == &["a", "b"]
        ));
        let mut controls = moved.clone();
        controls.joints.iter_mut().for_each(|j| j.deform = false);
        assert!(matches!(
            placement(&controls, &solid, &PlacementOptions::default()),
            Err(SkinError::NoDeformingJoint { joints: 2 })
        ));
    }
}

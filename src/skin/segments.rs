//! Control segments with the chain voxels at the core of their regions of influence.

use super::SkinOptions;
use crate::distance::DistanceMap;
use crate::math::closest_on_segment;
use crate::skeleton::{JointId, Skeleton};
use crate::voxel::Solid;
use glam::{DQuat, DVec3};
use rayon::prelude::*;

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
/// Every deforming joint gets one segment per child (the bone from it to the child) and may
/// get one of its own into the part of the figure its child bones do not reach, along its bone
/// axis where the skeleton's rest frames give one (see [`SkinOptions::leaf_extension`]): every
/// deforming leaf (a head beyond a short neck; a lower leg down to the inscribed ball of the IK
/// foot joint below it), a joint with children whose axis leads away from them (a head whose
/// bones lead to the ears: into the snout), and a deforming leaf under a control root (a
/// foot), towards the part nearest to it where its frame tells nothing. The chain voxels are
/// the interior voxels nearest to sample points every [`SkinOptions::bone_sample_spacing`]
/// voxels along the segment (searched within [`SkinOptions::bone_search_radius`]). Segments
/// come in joint order, a joint's own segment before those to its children, children in joint
/// order. Joints must be valid ids of `skeleton` (parents before children).
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
    let tips = own_tips(skeleton, &children, solid, distance, options);
    let mut segments = Vec::new();
    for (k, joint) in skeleton.joints.iter().enumerate() {
        if !joint.deform {
            continue;
        }
        let id = JointId(k);
        if let Some(tip) = tips[k] {
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

/// Cosine of the smallest angle between a joint's bone axis and each of its child bones for an
/// own segment of a joint with children (30°: the axis leads elsewhere than its bones).
const AWAY_FROM_CHILDREN: f64 = 0.866_025_403_784_438_6;

/// Cosine of the largest angle between a joint's bone axis and its parent bone for an own
/// segment of a joint with children (100°: not back along the parent bone, as the frame of a
/// wrist whose axis was set for another purpose may point).
const AWAY_FROM_PARENT: f64 = -0.173_648_177_666_930_4;

/// A segment of the skeleton from `a` to `b`; `start` and `end` name the deforming joints at
/// its ends, if any (a point of the segment nearest to something, clamped to an end, is that
/// joint's point).
#[derive(Debug, Clone, Copy)]
struct Line {
    a: DVec3,
    b: DVec3,
    start: Option<JointId>,
    end: Option<JointId>,
}

impl Line {
    fn touches(&self, joint: JointId) -> bool {
        self.start == Some(joint) || self.end == Some(joint)
    }
}

/// The part of the figure nearest to each joint's point.
struct Regions {
    /// Per joint: its voxels, the sum of their offsets from the joint (mesh units).
    count: Vec<usize>,
    sum: Vec<DVec3>,
    /// Every voxel centre that belongs to a joint's region, with the joint.
    owned: Vec<(DVec3, JointId)>,
}

impl Regions {
    /// The interior voxels whose nearest point of `lines` and `points` (joints) is a joint's
    /// point: the end of a line (clamped there) or one of `points`.
    fn new(skeleton: &Skeleton, lines: &[Line], points: &[JointId], solid: &Solid) -> Self {
        let grid = &solid.grid;
        let owned: Vec<(DVec3, JointId)> = (0..grid.len())
            .into_par_iter()
            .with_min_len(4096)
            .filter(|&i| solid.inside[i])
            .filter_map(|i| {
                let x = grid.centre(grid.coords(i));
                let mut best = f64::INFINITY;
                let mut owner = None;
                for line in lines {
                    let (t, q) = closest_on_segment(x, line.a, line.b);
                    let d = q.distance_squared(x);
                    if d < best {
                        best = d;
                        owner = if t <= 0.0 {
                            line.start
                        } else if t >= 1.0 {
                            line.end
                        } else {
                            None
                        };
                    }
                }
                for &j in points {
                    let d = skeleton.joint(j).position.distance_squared(x);
                    if d < best {
                        best = d;
                        owner = Some(j);
                    }
                }
                owner.map(|j| (x, j))
            })
            .collect();
        let mut count = vec![0; skeleton.len()];
        let mut sum = vec![DVec3::ZERO; skeleton.len()];
        for &(x, j) in &owned {
            count[j.0] += 1;
            sum[j.0] += x - skeleton.joint(j).position;
        }
        Self { count, sum, owned }
    }

    /// The direction from `joint` to its region's centroid.
    fn centroid(&self, joint: JointId) -> Option<DVec3> {
        let n = self.count[joint.0];
        if n == 0 {
            return None;
        }
        (self.sum[joint.0] / n as f64).try_normalize()
    }

    /// How far the region of `joint` (at `origin`) reaches along the unit `direction`.
    fn reach(&self, joint: JointId, origin: DVec3, direction: DVec3) -> f64 {
        self.owned
            .iter()
            .filter(|(_, j)| *j == joint)
            .map(|(x, _)| (*x - origin).dot(direction))
            .fold(0.0, f64::max)
    }
}

/// The distal end of every deforming joint's own segment, `None` where it has none.
///
/// A leaf's segment runs along its bone's axis ([`bone_axes`]) or, where the skeleton's frames
/// do not give it, along its parent bone, to the end of its body part ([`Walker::walk`]: where
/// the figure ends, or up to the inscribed ball of another chain's joint ahead that carries the
/// rest, such as an IK foot joint below a lower leg), for at most
/// [`SkinOptions::leaf_extension`] of the parent bone's length. A joint with children gets one
/// along its bone's axis where that axis leads away from all its children (by 30° or more) and
/// not back along its parent bone (a head whose bones lead to the ears, its axis into the
/// snout). A deforming leaf without a deforming parent (a foot parented to a control root: its
/// parent bone means nothing) is placed last, along its axis or, without one, towards the part
/// of the figure nearer to its point than to every other segment ([`Regions`]).
fn own_tips(
    skeleton: &Skeleton,
    children: &[Vec<JointId>],
    solid: &Solid,
    distance: &DistanceMap,
    options: &SkinOptions,
) -> Vec<Option<DVec3>> {
    let n = skeleton.len();
    let deform = |j: JointId| skeleton.joint(j).deform;
    let position = |j: JointId| skeleton.joint(j).position;
    let parent_bone = |j: JointId| skeleton.joint(j).parent.filter(|p| p.0 < j.0 && deform(*p));
    let axes = bone_axes(skeleton, children);
    let mut lines: Vec<Line> = Vec::new();
    for (k, list) in children.iter().enumerate() {
        let joint = JointId(k);
        if deform(joint) {
            lines.extend(list.iter().map(|&c| Line {
                a: position(joint),
                b: position(c),
                start: Some(joint),
                end: deform(c).then_some(c),
            }));
        }
    }
    let points: Vec<JointId> = (0..n).map(JointId).filter(|&j| deform(j)).collect();
    // No farther than across the grid: the figure ends before.
    let grid_size =
        (DVec3::from(solid.grid.dims.map(|d| d as f64)) * solid.grid.voxel_size).length();
    let walker = Walker {
        skeleton,
        solid,
        distance,
        options,
    };
    let mut tips = vec![None; n];
    let mut placed = Vec::new();
    for &joint in &points {
        let Some(parent) = parent_bone(joint) else {
            continue;
        };
        let origin = position(joint);
        let (direction, limit, ignored) = if children[joint.0].is_empty() {
            let bone = origin - position(parent);
            let Some(direction) = axes[joint.0].or_else(|| bone.try_normalize()) else {
                tips[joint.0] = Some(origin);
                continue;
            };
            let limit = (bone.length() * options.leaf_extension.max(0.0)).min(grid_size);
            (direction, limit, Vec::new())
        } else {
            // Along the axis where it leads away from every child (30° or more) and not back
            // along the parent bone (within 100° of it).
            let forward = (origin - position(parent)).normalize_or_zero();
            let away = |axis: DVec3| {
                axis.dot(forward) > AWAY_FROM_PARENT
                    && children[joint.0].iter().all(|&c| {
                        (position(c) - origin)
                            .try_normalize()
                            .is_none_or(|to| to.dot(axis) < AWAY_FROM_CHILDREN)
                    })
            };
            let Some(axis) = axes[joint.0].filter(|&axis| away(axis)) else {
                continue;
            };
            // The joint's own descendants are not in the way: they carry parts of its body
            // part's surface (ears on a head).
            let below: Vec<JointId> = (joint.0..n)
                .map(JointId)
                .filter(|&j| descends(skeleton, j, joint))
                .collect();
            (axis, grid_size, below)
        };
        let (length, reached) = walker.walk(joint, direction, limit, &lines, &points, &ignored);
        let tip = origin + direction * length;
        tips[joint.0] = Some(tip);
        placed.push(Line {
            a: origin,
            b: tip,
            start: Some(joint),
            end: reached,
        });
    }
    let rootless: Vec<JointId> = points
        .iter()
        .copied()
        .filter(|&j| children[j.0].is_empty() && parent_bone(j).is_none())
        .collect();
    if rootless.is_empty() {
        return tips;
    }
    lines.extend(placed);
    let regions = rootless
        .iter()
        .any(|j| axes[j.0].is_none())
        .then(|| Regions::new(skeleton, &lines, &points, solid));
    for joint in rootless {
        let origin = position(joint);
        tips[joint.0] = Some(match (axes[joint.0], &regions) {
            (Some(axis), _) => {
                let (length, _) = walker.walk(joint, axis, grid_size, &lines, &points, &[]);
                origin + axis * length
            }
            (None, Some(regions)) => match regions.centroid(joint) {
                Some(direction) => origin + direction * regions.reach(joint, origin, direction),
                None => origin,
            },
            (None, None) => origin,
        });
    }
    tips
}

/// Each joint's bone axis in the mesh frame (unit), where the skeleton's rest frames follow
/// one convention for it: the signed local axis (Blender's and most exporters': +y) that
/// points along the bone to the only child, within 18°, for at least 90 % of the joints with
/// one child whose frame is not the identity (and at least three of them). `None` for every
/// joint otherwise: frames left at the identity, as in skeleton files without orientations,
/// tell nothing.
fn bone_axes(skeleton: &Skeleton, children: &[Vec<JointId>]) -> Vec<Option<DVec3>> {
    let bones: Vec<(DQuat, DVec3)> = children
        .iter()
        .enumerate()
        .filter(|(_, c)| c.len() == 1)
        .filter_map(|(k, c)| {
            let joint = &skeleton.joints[k];
            let along = (skeleton.joint(c[0]).position - joint.position).try_normalize()?;
            let turned = joint.frame.angle_between(DQuat::IDENTITY) > 1e-6;
            turned.then_some((joint.frame, along))
        })
        .collect();
    let agreeing = |axis: DVec3| {
        bones
            .iter()
            .filter(|(frame, along)| (*frame * axis).dot(*along) > 0.95)
            .count()
    };
    let axes = [
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        -DVec3::X,
        -DVec3::Y,
        -DVec3::Z,
    ];
    let best = axes.into_iter().max_by_key(|&axis| agreeing(axis));
    match best {
        Some(axis) if bones.len() >= 3 && agreeing(axis) * 10 >= bones.len() * 9 => skeleton
            .joints
            .iter()
            .map(|j| (j.frame * axis).try_normalize())
            .collect(),
        _ => vec![None; skeleton.len()],
    }
}

/// Whether `joint` is `ancestor` or below it.
fn descends(skeleton: &Skeleton, joint: JointId, ancestor: JointId) -> bool {
    let mut at = Some(joint);
    while let Some(j) = at {
        if j == ancestor {
            return true;
        }
        at = skeleton.joint(j).parent.filter(|p| p.0 < j.0);
    }
    false
}

/// What [`Walker::walk`] needs of the figure.
struct Walker<'a> {
    skeleton: &'a Skeleton,
    solid: &'a Solid,
    distance: &'a DistanceMap,
    options: &'a SkinOptions,
}

impl Walker<'_> {
    /// How far (mesh units) the own segment of `joint` runs along the unit `direction`, at
    /// most `limit`, and the joint whose point it ran into, if any: to the last interior
    /// sample before the figure's surface or, where a segment of another joint (one of `lines`
    /// not touching `joint`) or another joint's point (one of `points`) comes within the local
    /// radius ahead of the joint (the inscribed ball of the sample reaches it: the walk has
    /// left the joint's body part and entered another's; ears beside a head are not ahead of
    /// its snout), to the inscribed ball around that segment's or point's nearest point,
    /// projected on the walk: a lower leg runs down to the ball of the IK foot
    /// joint below it, which carries the hoof. Joints in `ignored` and their segments are not
    /// in the way.
    fn walk(
        &self,
        joint: JointId,
        direction: DVec3,
        limit: f64,
        lines: &[Line],
        points: &[JointId],
        ignored: &[JointId],
    ) -> (f64, Option<JointId>) {
        let skeleton = self.skeleton;
        let origin = skeleton.joint(joint).position;
        let far = origin + direction * limit;
        let grid = &self.solid.grid;
        let steps = samples(
            origin,
            far,
            grid.voxel_size,
            self.options.bone_sample_spacing,
        );
        let neighbours: Vec<JointId> = lines
            .iter()
            .filter(|l| l.touches(joint))
            .flat_map(|l| [l.start, l.end])
            .flatten()
            .collect();
        let free = |j: &Option<JointId>| j.is_none_or(|j| !ignored.contains(&j));
        let others: Vec<Line> = lines
            .iter()
            .filter(|l| !l.touches(joint) && free(&l.start) && free(&l.end))
            .copied()
            .chain(
                points
                    .iter()
                    .filter(|&&j| j != joint && !neighbours.contains(&j) && !ignored.contains(&j))
                    .map(|&j| Line {
                        a: skeleton.joint(j).position,
                        b: skeleton.joint(j).position,
                        start: Some(j),
                        end: Some(j),
                    }),
            )
            .collect();
        // How far (voxels) the walk may run outside the figure and still go on: a gap between
        // two shells (a head modelled apart from the neck) as narrow as a bone may lie outside
        // and still find its chain voxels.
        let max_gap = self.options.bone_search_radius as f64;
        let step = limit / grid.voxel_size / steps as f64;
        let mut gap = 0.0;
        let mut reached = 0.0;
        for s in 1..=steps {
            let t = limit * s as f64 / steps as f64;
            let p = origin + direction * t;
            let Some(index) = grid
                .voxel_at(p)
                .map(|c| grid.index(c))
                .filter(|&i| self.solid.inside[i])
            else {
                gap += step;
                if gap > max_gap {
                    break;
                }
                continue;
            };
            gap = 0.0;
            let radius = self.distance.distance(index) * grid.voxel_size;
            let near = others
                .iter()
                .map(|l| {
                    let (at, q) = closest_on_segment(p, l.a, l.b);
                    let hit = if at <= 0.0 {
                        l.start
                    } else if at >= 1.0 {
                        l.end
                    } else {
                        None
                    };
                    (q.distance(p), q, hit)
                })
                .filter(|&(d, q, _)| d < radius && (q - origin).dot(direction) > 0.0)
                .min_by(|a, b| a.0.total_cmp(&b.0));
            if let Some((_, q, hit)) = near {
                let before = (q - origin).dot(direction) - self.distance.radius_at(q);
                return (before.clamp(0.0, limit), hit);
            }
            reached = t;
        }
        (reached, None)
    }
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

    /// The solid and distance map of the union of the boxes `(min, max)`, voxels 0.1 wide.
    fn figure(boxes: &[(DVec3, DVec3)]) -> (Solid, DistanceMap) {
        let mut mesh = Mesh::default();
        for &(min, max) in boxes {
            let piece = Mesh::cuboid(min, max);
            let offset = mesh.positions.len() as u32;
            mesh.positions.extend(&piece.positions);
            mesh.triangles
                .extend(piece.triangles.iter().map(|t| t.map(|i| i + offset)));
        }
        let options = VoxelOptions {
            size: VoxelSize::Absolute(0.1),
            ..Default::default()
        };
        let solid = voxelize(&mesh, &options).unwrap();
        let distance = edt(&solid);
        (solid, distance)
    }

    /// A box 4 long in y.
    fn column() -> (Solid, DistanceMap) {
        figure(&[(DVec3::new(-0.5, 0.0, -0.5), DVec3::new(0.5, 4.0, 0.5))])
    }

    /// A leg 1 wide from y = 1 up to y = 6 on a foot from y = 0 to 1 reaching forward to
    /// z = 3.
    fn leg_and_foot() -> (Solid, DistanceMap) {
        figure(&[
            (DVec3::new(-0.5, 0.9, -0.5), DVec3::new(0.5, 6.0, 0.5)),
            (DVec3::new(-0.5, 0.0, -0.5), DVec3::new(0.5, 1.0, 3.0)),
        ])
    }

    /// A frame whose local +y is `along` (unit, in the y-z plane).
    fn y_along(along: DVec3) -> DQuat {
        DQuat::from_rotation_arc(DVec3::Y, along)
    }

    /// The distal end of `joint`'s own segment.
    fn own_tip(skeleton: &Skeleton, solid: &Solid, distance: &DistanceMap, joint: usize) -> DVec3 {
        bone_segments(skeleton, solid, distance, &SkinOptions::default())
            .iter()
            .find(|s| s.joint == JointId(joint) && s.child.is_none())
            .and_then(|s| s.tip)
            .unwrap_or_else(|| panic!("joint {joint} has no segment of its own"))
    }

    /// Regression (issue 20): a head beyond a short neck took only one neck length of segment,
    /// and the neck shared the head's skin. The leaf runs to the end of the figure, or up to
    /// the joint of another chain that carries the rest (an IK foot joint below a lower leg),
    /// which its segment then reaches.
    #[test]
    fn a_leaf_runs_to_the_end_of_its_part_or_up_to_the_next_chain() {
        let (solid, distance) = column();
        // A short "neck" bone 1.0 -> 1.2, its leaf "head" runs to the top.
        let mut skeleton = Skeleton {
            joints: vec![
                Joint::new("neck", None, DVec3::new(0.0, 1.0, 0.0)),
                Joint::new("head", Some(JointId(0)), DVec3::new(0.0, 1.2, 0.0)),
            ],
        };
        let head = own_tip(&skeleton, &solid, &distance, 1);
        assert!(head.y > 3.8, "the head's segment ends at {head}");
        // A bone of another chain in the way (an IK joint at y 3 and its bone to y 3.3): the
        // leaf stops where the IK joint's inscribed ball (radius 0.5) begins.
        skeleton
            .joints
            .push(Joint::new("ik", None, DVec3::new(0.0, 3.0, 0.0)));
        skeleton.joints.push(Joint::new(
            "toe",
            Some(JointId(2)),
            DVec3::new(0.0, 3.3, 0.0),
        ));
        let head = own_tip(&skeleton, &solid, &distance, 1);
        assert!(
            (head.y - 2.5).abs() < 0.06,
            "the head's segment ends at {head}"
        );
    }

    #[test]
    fn bones_get_interior_chains_and_leaves_stop_at_the_surface() {
        let (solid, distance) = column();
        // The chain ends 1 below the top.
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
        // The leaf continues upwards and stops inside the box.
        let tip = segments[1].tip.unwrap();
        assert!(tip.y > 3.8 && tip.y < 4.0, "tip at {tip}");
        assert!(segments[1].voxels.iter().all(|&v| solid.inside[v]));
    }

    /// A leg chain down to an ankle over a foot that reaches forward: `frames` gives each
    /// joint its rest frame with local +y along its bone (the ankle's: forward into the foot);
    /// without, every frame is the identity.
    fn leg(frames: bool) -> Skeleton {
        let down = if frames {
            y_along(-DVec3::Y)
        } else {
            DQuat::IDENTITY
        };
        let mut joints = vec![
            Joint::new("pelvis", None, DVec3::new(0.0, 5.5, 0.0)),
            Joint::new("hip", Some(JointId(0)), DVec3::new(0.0, 4.5, 0.0)),
            Joint::new("knee", Some(JointId(1)), DVec3::new(0.0, 3.0, 0.0)),
            Joint::new("ankle", Some(JointId(2)), DVec3::new(0.0, 0.5, 0.0)),
        ];
        for joint in &mut joints[..3] {
            joint.frame = down;
        }
        if frames {
            joints[3].frame = y_along(DVec3::Z);
        }
        Skeleton { joints }
    }

    #[test]
    fn a_leaf_follows_its_bone_axis_where_the_frames_give_one() {
        let (solid, distance) = leg_and_foot();
        // Frames with local +y along every bone: the ankle's segment runs into the foot.
        let ankle = own_tip(&leg(true), &solid, &distance, 3);
        assert!(
            ankle.z > 2.6 && (ankle.y - 0.5).abs() < 0.01,
            "the ankle's segment ends at {ankle}"
        );
        // Without frames, along the lower leg: down to the sole.
        let ankle = own_tip(&leg(false), &solid, &distance, 3);
        assert!(
            ankle.y < 0.1 && ankle.z.abs() < 0.01,
            "the ankle's segment ends at {ankle}"
        );
        // Identity frames do not follow a convention here (the bones point down).
        let mut children = vec![Vec::new(); 4];
        for k in 1..4 {
            children[k - 1].push(JointId(k));
        }
        assert!(bone_axes(&leg(false), &children)
            .iter()
            .all(Option::is_none));
        assert!(bone_axes(&leg(true), &children).iter().all(Option::is_some));
    }

    /// A lower leg without a foot bone, and a foot joint parented to a control root (the
    /// Quaternius animals' feet): the lower leg runs down to the foot joint's inscribed ball,
    /// and the foot's segment into the foot, along its axis or, without frames, towards the
    /// part of the figure nearest to it.
    #[test]
    fn a_foot_parented_to_a_control_root_gets_the_foot() {
        let (solid, distance) = leg_and_foot();
        for frames in [true, false] {
            let mut skeleton = leg(frames);
            let mut root = Joint::new("root", None, DVec3::ZERO);
            root.deform = false;
            skeleton.joints[3] = root;
            let mut foot = Joint::new("foot", Some(JointId(3)), DVec3::new(0.0, 0.5, 0.0));
            if frames {
                foot.frame = y_along(DVec3::Z);
            }
            skeleton.joints.push(foot);
            let knee = own_tip(&skeleton, &solid, &distance, 2);
            assert!(
                (knee.y - 1.0).abs() < 0.1,
                "frames {frames}: the lower leg ends at {knee}"
            );
            let foot = own_tip(&skeleton, &solid, &distance, 4);
            assert!(
                foot.z > 1.5,
                "frames {frames}: the foot's segment ends at {foot}"
            );
        }
    }

    /// A neck up to a head joint whose bones lead to two ears, the head's bulk (a snout)
    /// reaching forward: with the head's axis along the snout, the head gets a segment of its
    /// own into it; with its axis towards the ears, none.
    #[test]
    fn a_joint_with_children_gets_its_own_segment_along_an_axis_leading_elsewhere() {
        let (solid, distance) = figure(&[
            (DVec3::new(-0.5, 0.0, -0.5), DVec3::new(0.5, 3.1, 0.5)),
            (DVec3::new(-0.6, 3.0, -0.6), DVec3::new(0.6, 4.0, 3.0)),
            (DVec3::new(0.1, 3.9, -0.2), DVec3::new(0.5, 5.0, 0.2)),
            (DVec3::new(-0.5, 3.9, -0.2), DVec3::new(-0.1, 5.0, 0.2)),
        ]);
        // Every frame turned about its bone (as exporters leave them), local +y along it.
        let up = DQuat::from_rotation_y(0.5);
        let head = |frame: DQuat| {
            let mut head = Joint::new("head", Some(JointId(2)), DVec3::new(0.0, 3.3, 0.0));
            head.frame = frame;
            let mut joints = vec![
                Joint::new("neck0", None, DVec3::new(0.0, 0.5, 0.0)),
                Joint::new("neck1", Some(JointId(0)), DVec3::new(0.0, 1.5, 0.0)),
                Joint::new("neck2", Some(JointId(1)), DVec3::new(0.0, 2.5, 0.0)),
                head,
                Joint::new("ear_l", Some(JointId(3)), DVec3::new(0.3, 4.2, 0.0)),
                Joint::new("ear_l_tip", Some(JointId(4)), DVec3::new(0.3, 4.8, 0.0)),
                Joint::new("ear_r", Some(JointId(3)), DVec3::new(-0.3, 4.2, 0.0)),
                Joint::new("ear_r_tip", Some(JointId(6)), DVec3::new(-0.3, 4.8, 0.0)),
            ];
            for k in [0, 1, 2, 4, 5, 6, 7] {
                joints[k].frame = up;
            }
            Skeleton { joints }
        };
        let skeleton = head(y_along(DVec3::Z));
        let tip = own_tip(&skeleton, &solid, &distance, 3);
        assert!(tip.z > 2.6, "the head's segment ends at {tip}");
        let segments = bone_segments(&head(up), &solid, &distance, &SkinOptions::default());
        assert!(!segments
            .iter()
            .any(|s| s.joint == JointId(3) && s.child.is_none()));
    }
}

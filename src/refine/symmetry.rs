//! Bilateral symmetry: a figure whose body mirrors itself across its median plane gets paired
//! joints that mirror each other too.
//!
//! Every fitting and refining step places the left and right joints of a pair from their own
//! side's geometry, so noise (a hand shape, a sleeve, a slicing that stops one voxel early) makes
//! them disagree although the body is symmetric. When the voxelized figure is symmetric (at
//! least [`SYMMETRIC_SHARE`] of its interior voxels have their mirror image inside), each pair
//! `X_L`/`X_R` moves to the mean of one and the other's mirror image, the head and the joints from
//! the root to it move onto the median plane, and frames turn with their segments ([`carry`]). The median plane is the one across `left` halfway between the
//! figure's extremes along `left` (its mesh vertices in the voxel grid) (where a symmetric figure's extremes mirror each other). A figure that is not symmetric (a pose with one arm raised, a prop in one hand)
//! keeps its joints.

use super::carry;
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use crate::voxel::Solid;
use glam::DVec3;
use std::collections::BTreeMap;

/// Share of the interior voxels whose mirror image must be inside for a symmetric figure.
/// Chosen so that tessellation and voxel noise (a mirror falling one voxel off the surface) pass
/// and a raised arm or a one-sided prop (a tenth of the body or more) does not.
pub const SYMMETRIC_SHARE: f64 = 0.9;

/// What [`symmetrize`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct Symmetry {
    /// Share of the interior voxels whose mirror image is inside.
    pub share: f64,
    /// Whether the pairs were made to mirror each other.
    pub applied: bool,
    /// Pairs moved, with how far apart the two were from mirroring each other (mesh units).
    pub pairs: Vec<(String, f64)>,
    /// The skeleton (unchanged when not applied).
    pub skeleton: Skeleton,
}

/// Mirrors `p` across the plane through `origin` with unit normal `left`.
pub(super) fn mirror(p: DVec3, origin: DVec3, left: DVec3) -> DVec3 {
    p - 2.0 * (p - origin).dot(left) * left
}

/// Share of the interior voxel centres `interior` (of `solid`) whose mirror image across the
/// plane (`origin`, `left`) is inside.
fn symmetric_share(solid: &Solid, interior: &[DVec3], origin: DVec3, left: DVec3) -> f64 {
    let mirrored = interior
        .iter()
        .filter(|&&c| {
            solid
                .grid
                .voxel_at(mirror(c, origin, left))
                .is_some_and(|v| solid.inside[solid.grid.index(v)])
        })
        .count();
    mirrored as f64 / interior.len().max(1) as f64
}

/// What [`median_plane`] measures, gathered once for every plane tried: the figure's mesh
/// vertices in the voxel grid (loose pieces left out of the voxels are not the figure) and its
/// interior voxel centres.
struct Figure<'a> {
    solid: &'a Solid,
    vertices: Vec<DVec3>,
    interior: Vec<DVec3>,
}

impl<'a> Figure<'a> {
    fn new(mesh: &Mesh, solid: &'a Solid) -> Self {
        let mut used = vec![false; mesh.positions.len()];
        for &i in mesh.triangles.iter().flatten() {
            used[i as usize] = true;
        }
        let vertices = mesh
            .positions
            .iter()
            .zip(&used)
            .filter(|&(&p, &u)| u && solid.grid.voxel_at(p).is_some())
            .map(|(&p, _)| p)
            .collect();
        let interior = (0..solid.inside.len())
            .filter(|&i| solid.inside[i])
            .map(|i| solid.grid.centre(solid.grid.coords(i)))
            .collect();
        Self {
            solid,
            vertices,
            interior,
        }
    }
}

/// Turns (degrees) of the median plane about up tried beside the frame's own: the body frame
/// snaps to the file's axes ([`crate::anatomy::Forward::Auto`]), and a figure modelled a few
/// degrees off them mirrors itself across a plane turned as much.
const PLANE_TURNS_DEG: [f64; 10] = [-1.0, 1.0, -2.0, 2.0, -3.0, 3.0, -4.0, 4.0, -5.0, 5.0];

/// A turned plane replaces the frame's when this much larger a share of the interior voxels
/// mirrors across it (voxel noise moves the share by less).
const TURNED_PLANE_GAIN: f64 = 0.02;

/// Makes the paired joints of `skeleton` (names ending `_L` and `_R`) mirror each other across
/// the median plane of `mesh` (voxelized into `solid`), whose normal is `left` (or `left` turned
/// about `up` by up to five degrees, when the figure mirrors itself clearly better across that:
/// `PLANE_TURNS_DEG`), and puts `head` and its ancestors on that plane (see the module docs).
pub fn symmetrize(
    skeleton: &Skeleton,
    head: Option<JointId>,
    mesh: &Mesh,
    solid: &Solid,
    left: DVec3,
    up: DVec3,
) -> Symmetry {
    let unchanged = |share| Symmetry {
        share,
        applied: false,
        pairs: Vec::new(),
        skeleton: skeleton.clone(),
    };
    let Some(left) = left.try_normalize() else {
        return unchanged(0.0);
    };
    let figure = Figure::new(mesh, solid);
    let Some((origin, share)) = median_plane(&figure, left) else {
        return unchanged(0.0);
    };
    let (left, origin, share) = match up.try_normalize().filter(|u| u.dot(left).abs() < 0.5) {
        Some(up) => PLANE_TURNS_DEG
            .iter()
            .filter_map(|&deg| {
                let turned = glam::DQuat::from_axis_angle(up, deg.to_radians()) * left;
                median_plane(&figure, turned).map(|(o, s)| (turned, o, s))
            })
            .filter(|&(_, _, s)| s >= share + TURNED_PLANE_GAIN)
            .fold(
                (left, origin, share),
                |best, c| if c.2 > best.2 { c } else { best },
            ),
        None => (left, origin, share),
    };
    if share < SYMMETRIC_SHARE {
        return unchanged(share);
    }
    mirror_pairs(skeleton, head, left, origin, share)
}

/// The median plane across `left` (its point halfway between the figure's extremes along
/// `left`, its mesh vertices in the voxel grid) and the share of its interior voxels that
/// mirror across it; `None` when no vertex lies in the grid.
fn median_plane(figure: &Figure, left: DVec3) -> Option<(DVec3, f64)> {
    let (lo, hi) = figure
        .vertices
        .iter()
        .map(|p| p.dot(left))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
            (lo.min(t), hi.max(t))
        });
    if lo
        .partial_cmp(&hi)
        .is_none_or(|o| o == std::cmp::Ordering::Greater)
    {
        return None;
    }
    let origin = left * (lo + hi) / 2.0;
    Some((
        origin,
        symmetric_share(figure.solid, &figure.interior, origin, left),
    ))
}

/// [`symmetrize`]'s moves across the plane (`origin`, `left`).
fn mirror_pairs(
    skeleton: &Skeleton,
    head: Option<JointId>,
    left: DVec3,
    origin: DVec3,
    share: f64,
) -> Symmetry {
    let mut targets: BTreeMap<JointId, DVec3> = BTreeMap::new();
    let mut pairs = Vec::new();
    for (l, joint) in skeleton.joints.iter().enumerate() {
        let Some(stem) = joint.name.strip_suffix("_L") else {
            continue;
        };
        let Some(r) = skeleton.find(&format!("{stem}_R")) else {
            continue;
        };
        let (pl, pr) = (joint.position, skeleton.joints[r.0].position);
        let mirrored = mirror(pr, origin, left);
        let mean = (pl + mirrored) / 2.0;
        targets.insert(JointId(l), mean);
        targets.insert(r, mirror(mean, origin, left));
        pairs.push((stem.to_string(), pl.distance(mirrored)));
    }
    // The head and the chain from the root to it (pelvis, spine, neck) lie on the median
    // plane; other joints (a tail curving aside, a jaw) stay where they are.
    let mut axial = vec![false; skeleton.len()];
    let mut next = head.filter(|h| h.0 < skeleton.len());
    while let Some(j) = next {
        if std::mem::replace(&mut axial[j.0], true) {
            break;
        }
        next = skeleton.joints[j.0].parent;
    }
    for (j, joint) in skeleton.joints.iter().enumerate() {
        let p = joint.position;
        let on_plane = if axial[j] {
            p - (p - origin).dot(left) * left
        } else {
            p
        };
        targets.entry(JointId(j)).or_insert(on_plane);
    }
    Symmetry {
        share,
        applied: true,
        pairs,
        skeleton: carry(skeleton, &targets),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::{Canonical, Joint};
    use crate::voxel::{voxelize, VoxelOptions};

    fn figure(arm_raised: bool) -> crate::mesh::Mesh {
        // A trunk with two arms; the left one raised when asked.
        let mut mesh = crate::mesh::Mesh::capsule(DVec3::ZERO, 0.3, 1.6, 8, 16);
        let arm =
            |x: f64, y: f64| crate::mesh::Mesh::capsule(DVec3::new(x, y, 0.0), 0.1, 0.8, 8, 16);
        for part in [
            if arm_raised {
                arm(0.5, 1.0)
            } else {
                arm(0.5, 0.0)
            },
            arm(-0.5, 0.0),
        ] {
            let base = mesh.positions.len() as u32;
            mesh.positions.extend(&part.positions);
            mesh.triangles
                .extend(part.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        mesh
    }

    fn skeleton() -> Skeleton {
        let mut s = Skeleton::default();
        s.joints
            .push(Joint::new(Canonical::Pelvis.as_str(), None, DVec3::ZERO));
        s.joints.push(Joint::new(
            "hand_L",
            Some(JointId(0)),
            DVec3::new(0.55, 0.1, 0.0),
        ));
        s.joints.push(Joint::new(
            "hand_R",
            Some(JointId(0)),
            DVec3::new(-0.45, -0.1, 0.0),
        ));
        s
    }

    #[test]
    fn a_symmetric_figure_gets_mirrored_pairs_and_an_asymmetric_one_keeps_its_joints() {
        let solid = voxelize(&figure(false), &VoxelOptions::default()).unwrap();
        let s = symmetrize(
            &skeleton(),
            Some(JointId(0)),
            &figure(false),
            &solid,
            DVec3::X,
            DVec3::Y,
        );
        assert!(s.applied && s.share >= SYMMETRIC_SHARE, "{}", s.share);
        let (l, r) = (s.skeleton.joints[1].position, s.skeleton.joints[2].position);
        assert!(
            (l.x + r.x).abs() < 1e-9 && (l.y - r.y).abs() < 1e-9,
            "{l} {r}"
        );
        assert!((l.x - 0.5).abs() < 1e-9 && l.y.abs() < 1e-9, "{l}");
        assert_eq!(s.pairs.len(), 1);
        assert!((s.pairs[0].1 - 0.2236).abs() < 0.02, "{:?}", s.pairs);
        assert_eq!(s.skeleton.joints[0].position, DVec3::ZERO);
        // An axial joint off the plane moves onto it, along `left` only.
        let mut leaning = skeleton();
        leaning.joints[0].position = DVec3::new(0.07, 0.2, 0.01);
        let s = symmetrize(
            &leaning,
            Some(JointId(0)),
            &figure(false),
            &solid,
            DVec3::X,
            DVec3::Y,
        );
        let p = s.skeleton.joints[0].position;
        assert!(p.distance(DVec3::new(0.0, 0.2, 0.01)) < 1e-9, "{p}");

        let raised = voxelize(&figure(true), &VoxelOptions::default()).unwrap();
        let s = symmetrize(
            &skeleton(),
            Some(JointId(0)),
            &figure(true),
            &raised,
            DVec3::X,
            DVec3::Y,
        );
        assert!(!s.applied && s.share < SYMMETRIC_SHARE, "{}", s.share);
        assert_eq!(s.skeleton, skeleton());
    }

    /// A symmetric figure turned four degrees about up (its frame snapped to the file's axes)
    /// mirrors itself across the plane turned with it, not across the frame's: its pairs mirror
    /// each other across that plane.
    #[test]
    fn a_figure_a_few_degrees_off_the_axes_mirrors_across_its_own_plane() {
        let turn = glam::DQuat::from_rotation_y(4f64.to_radians());
        let mut mesh = figure(false);
        for p in &mut mesh.positions {
            *p = turn * *p;
        }
        let mut bones = skeleton();
        for j in &mut bones.joints {
            j.position = turn * j.position;
        }
        let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
        let frame = median_plane(&Figure::new(&mesh, &solid), DVec3::X)
            .unwrap()
            .1;
        let s = symmetrize(&bones, Some(JointId(0)), &mesh, &solid, DVec3::X, DVec3::Y);
        assert!(
            s.applied && s.share > frame + TURNED_PLANE_GAIN,
            "{} vs {frame}",
            s.share
        );
        let (l, r) = (s.skeleton.joints[1].position, s.skeleton.joints[2].position);
        let (l, r) = (turn.inverse() * l, turn.inverse() * r);
        // Within the one-degree steps tried (across the frame's plane they would be 0.07 apart).
        assert!(
            (l.x + r.x).abs() < 0.01 && (l.z - r.z).abs() < 0.03,
            "{l} {r}"
        );
    }
}

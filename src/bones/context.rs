//! State shared by the placement steps: the skeleton, distance map, body reading, options, and
//! the bones and warnings made so far.

use super::settle::{settle, Draft};
use super::structure::{perpendicular, Body};
use super::{Articulation, Bone, BoneOptions, BoneWarning};
use crate::distance::DistanceMap;
use crate::fit::Side;
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use glam::{DMat3, DVec3};

pub(crate) struct Context<'a> {
    pub skeleton: &'a Skeleton,
    pub map: &'a DistanceMap,
    /// The figure's surface, when given: digits thinner than the voxels are sized on it.
    pub surface: Option<&'a Mesh>,
    pub options: &'a BoneOptions,
    pub body: Body,
    /// The body's dorsal direction (the root frame's y).
    pub dorsal: DVec3,
    /// Width of neck and trunk vertebrae (9.1: 1/12 of the largest trunk sphere's diameter).
    pub vertebra_width: f64,
    pub bones: Vec<Bone>,
    /// Where bones may meet: a sphere per joint, jaw hinges added by the skull.
    pub articulations: Vec<Articulation>,
    pub warnings: Vec<BoneWarning>,
}

impl<'a> Context<'a> {
    pub fn new(
        skeleton: &'a Skeleton,
        map: &'a DistanceMap,
        surface: Option<&'a Mesh>,
        options: &'a BoneOptions,
        body: Body,
        warnings: Vec<BoneWarning>,
    ) -> Self {
        let dorsal = DMat3::from_quat(skeleton.joint(body.root).frame).y_axis;
        let dorsal = perpendicular(dorsal, body.forward.cross(body.up).normalize_or_zero())
            .unwrap_or(body.up);
        // The largest sphere within the figure is the trunk's for vertebrate-like figures.
        let largest = map.max_distance() * map.grid.voxel_size;
        let articulations = skeleton
            .joints
            .iter()
            .map(|j| Articulation {
                centre: j.position,
                radius: options.articulation * map.radius_at(j.position),
            })
            .collect();
        Self {
            articulations,
            skeleton,
            map,
            surface,
            options,
            vertebra_width: options.vertebra_width * 2.0 * largest,
            body,
            dorsal,
            bones: Vec::new(),
            warnings,
        }
    }

    /// Rest position of a joint.
    pub fn pos(&self, j: JointId) -> DVec3 {
        self.skeleton.joint(j).position
    }

    /// Fits the draft inside the figure and keeps it; returns its index in `bones`, `None`
    /// when it could not be fitted (a warning says why).
    pub fn keep(&mut self, draft: Draft) -> Option<usize> {
        self.keep_sized(draft, false)
    }

    /// [`Context::keep`] for a draft already sized inside the figure's surface
    /// (`on_surface`: a digit bone thinner than the voxels, whose inside the distance map
    /// cannot tell); it is still kept clear of the other bones.
    pub fn keep_sized(&mut self, draft: Draft, on_surface: bool) -> Option<usize> {
        let bone = settle(
            &draft,
            on_surface,
            self.map,
            self.options,
            &self.bones,
            &self.articulations,
            &mut self.warnings,
        )?;
        self.bones.push(bone);
        Some(self.bones.len() - 1)
    }

    /// Axial frame for a segment along `z`: y dorsal, x = y × z.
    pub fn axial_axes(&self, z: DVec3) -> [DVec3; 3] {
        let y = perpendicular(self.dorsal, z)
            .or_else(|| perpendicular(self.body.forward, z))
            .unwrap_or_else(|| z.any_orthonormal_vector());
        [y.cross(z), y, z]
    }

    /// Limb frame for a segment along `z`: y anterior (forward, or up for a segment along the
    /// forward direction), x lateral on `side` (a mirroring frame on the right).
    pub fn limb_axes(&self, z: DVec3, side: Side) -> [DVec3; 3] {
        let y = if self.body.forward.cross(z).length() > 0.3 {
            perpendicular(self.body.forward, z)
        } else {
            perpendicular(self.body.up, z)
        }
        .unwrap_or_else(|| z.any_orthonormal_vector());
        [y.cross(z) * side.sign(), y, z]
    }
}

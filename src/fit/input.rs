//! The geometry the fit consumes: a head-to-tail path and limb paths in mesh units, produced
//! by body-part labelling (dissertation ch.7) or given directly.

use crate::template::LimbKind;
use glam::DVec3;
use serde::{Deserialize, Serialize};

pub use crate::skeleton::Side;

/// Optional section boundaries on [`AxialPath::points`], as point indices, head tip first:
/// head `[0, head_end]`, neck `[head_end, neck_end]`, trunk `[neck_end, trunk_end]`, tail
/// `[trunk_end, last]` (empty when `trunk_end` is the last point).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct AxialSections {
    /// Last point of the head section (the head/neck boundary).
    pub head_end: usize,
    /// Neck/trunk boundary.
    pub neck_end: usize,
    /// Trunk/tail boundary (the hindmost limb pair).
    pub trunk_end: usize,
}

/// The centralised head-to-tail path (dissertation 8.1): from the tip of the head to the tip of
/// the tail, or without a tail to the midpoint of the hindmost limb pair's limb-to-limb path.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxialPath {
    /// Path points, head tip first, mesh units.
    pub points: Vec<DVec3>,
    /// Distance-map radius at each point (mesh units), same length as `points`.
    pub radii: Vec<f64>,
    /// Section boundaries; `None` derives them from the limb pairs (8.1).
    pub sections: Option<AxialSections>,
    /// Whether the path ends at the tip of a labelled tail. An upright template builds a tail
    /// chain only then; a horizontal one whenever the path runs past the hindmost limb pair.
    #[serde(default)]
    pub tail: bool,
}

/// One digit of a limb with separated digits: the centralised path from the wrist/ankle voxel
/// to the digit's end effector (8.2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DigitInput {
    /// Points, wrist/ankle first, mesh units.
    pub path: Vec<DVec3>,
}

/// One limb (8.2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LimbInput {
    /// Labelled kind.
    pub kind: LimbKind,
    /// Side of the figure.
    pub side: Side,
    /// Pair number from labelling (limbs with the same kind and pair form a pair).
    pub pair: usize,
    /// Midpoint of the pair's limb-to-limb path (on the body's centre), mesh units.
    pub attach: DVec3,
    /// This side's half of the limb-to-limb path, proximal (near `attach`) to distal: to the
    /// limb's extreme point, or to the wrist/ankle voxel when `digits` is not empty.
    pub path: Vec<DVec3>,
    /// Distance-map radius at each path point, mesh units.
    pub radii: Vec<f64>,
    /// Separated digits, any order (the first digit is found as the one nearest the centre
    /// line).
    pub digits: Vec<DigitInput>,
    /// Where the labelled limb leaves the trunk (its section's top, mesh units), if known.
    /// With [`FitOptions::root_from_labels`](super::FitOptions::root_from_labels) the limb's
    /// outer segmentation starts at the path point nearest it instead of at the girdle
    /// sphere's exit.
    #[serde(default)]
    pub root: Option<DVec3>,
}

/// One ear (or another mirrored protrusion of the head, such as an upright horn): the path from
/// where it leaves the skull to its tip.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EarInput {
    /// Side of the figure.
    pub side: Side,
    /// Points from the base (on the skull's inscribed balls) to the tip (inside the skin), mesh
    /// units.
    pub path: Vec<DVec3>,
}

/// Everything the fit needs, in mesh units and the mesh frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FitInput {
    /// The figure's up direction (need not be unit).
    pub up: DVec3,
    /// The direction the figure faces.
    pub forward: DVec3,
    /// Head-to-tail path.
    pub axial: AxialPath,
    /// Limbs found by labelling.
    pub limbs: Vec<LimbInput>,
    /// Jaw branch of the head, from the mandibular joint to the jaw tip, if one was found.
    pub jaw: Option<Vec<DVec3>>,
    /// Ears found on the head ([`super::ears`]): empty, or one per side.
    #[serde(default)]
    pub ears: Vec<EarInput>,
}

/// Casts a ray from inside the figure and returns the distance to the surface along it: used
/// for the S-shaped cervical replacement of animal-like figures (8.1). [`crate::voxel::Solid`]
/// implements it by marching through its inside mask; closures `Fn(origin, direction) ->
/// Option<f64>` do too.
pub trait DorsalProbe {
    /// Distance (mesh units) from `origin` along the unit `direction` to the figure's surface,
    /// `None` when unknown.
    fn depth(&self, origin: DVec3, direction: DVec3) -> Option<f64>;
}

impl<F: Fn(DVec3, DVec3) -> Option<f64>> DorsalProbe for F {
    fn depth(&self, origin: DVec3, direction: DVec3) -> Option<f64> {
        self(origin, direction)
    }
}

/// Points and distance-map radii of a voxel path (linear grid indices, e.g. a centralised DMS
/// path from `crate::paths`), in mesh units: the form [`AxialPath`], [`LimbInput`] and
/// [`DigitInput`] take.
///
/// # Errors
/// [`super::FitError::VoxelOutOfRange`] for an index outside the grid.
pub fn voxel_path(
    distance: &crate::distance::DistanceMap,
    voxels: &[usize],
) -> Result<(Vec<DVec3>, Vec<f64>), super::FitError> {
    let grid = &distance.grid;
    let mut points = Vec::with_capacity(voxels.len());
    let mut radii = Vec::with_capacity(voxels.len());
    for &v in voxels {
        if v >= grid.len() {
            return Err(super::FitError::VoxelOutOfRange {
                index: v,
                voxels: grid.len(),
            });
        }
        points.push(grid.centre(grid.coords(v)));
        radii.push(distance.distance(v) * grid.voxel_size);
    }
    Ok((points, radii))
}

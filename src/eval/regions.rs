//! The body region of each mesh vertex from a reference rig: the evaluation side of
//! [`crate::anatomy::skeleton_regions`], which holds the rule.

use super::ReferenceRig;
use crate::anatomy::{skeleton_regions, Region};
use crate::mesh::Mesh;

/// The region of each mesh vertex from the nearest bone of `rig`'s deforming joints (the rule
/// of [`crate::anatomy::skeleton_regions`]; control joints are dropped first,
/// [`ReferenceRig::deforming`]). `None` for every vertex when no joint has a region.
pub fn reference_regions(rig: &ReferenceRig, mesh: &Mesh) -> Vec<Option<Region>> {
    let rig = rig.deforming();
    skeleton_regions(&rig.skeleton, &rig.canonical, mesh)
}

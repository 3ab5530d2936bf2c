//! Per-vertex labels that follow a fitted skeleton: each mesh vertex takes the part of the
//! bones that move it (the heaviest region of its skin weights, [`super::weight_regions`]),
//! or of its nearest bone, by the same rule the accuracy table reads reference rigs with
//! ([`super::skeleton_regions`]).

use super::{part_region, Label, Labelling, Region};
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use std::collections::BTreeMap;

/// Replaces `labelling`'s per-mesh-vertex labels by the part of the nearest bone of
/// `skeleton` (fitted from this labelling, `canonical` its key → joint map), and recounts the
/// parts' vertices. With `weights` (the skin's, per mesh vertex), a vertex takes instead the
/// region whose joints carry most of its weight, where any does: the nearest bone is often
/// not the one that moves a vertex (a forearm lying against the waist, a bulky shoulder
/// pad), while the skin weights follow the figure's solid. A bone's region maps back to the labelled part standing for it (a limb's
/// own part, not one of its digits; the trunk for the trunk); a vertex whose nearest bone has
/// no such part keeps its label. Returns how many vertices changed part.
///
/// The level-graph, DMS-voxel and interior labels are left as they are: only the skin's
/// labels follow the bones, so that the part of a vertex agrees with the bone that moves it
/// (limb roots in particular, where the medial surface's limb pieces reach deep into the
/// trunk).
pub fn label_vertices_by_bones(
    labelling: &mut Labelling,
    mesh: &Mesh,
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    weights: Option<&[Vec<(JointId, f64)>]>,
) -> usize {
    if labelling.mesh_parts.len() != mesh.positions.len() || labelling.parts.is_empty() {
        return 0;
    }
    let mut part_of: BTreeMap<Region, usize> = BTreeMap::new();
    for (i, part) in labelling.parts.iter().enumerate() {
        if part.label == Label::Digit {
            continue;
        }
        part_of.entry(part_region(labelling, i)).or_insert(i);
    }
    part_of.insert(Region::Trunk, 0);
    let mut regions = super::skeleton_regions(skeleton, canonical, mesh);
    if let Some(w) = weights.filter(|w| w.len() == regions.len()) {
        for (r, by_weight) in regions
            .iter_mut()
            .zip(super::weight_regions(skeleton, canonical, w))
        {
            if by_weight.is_some() {
                *r = by_weight;
            }
        }
    }
    let mut changed = 0;
    for (label, region) in labelling.mesh_parts.iter_mut().zip(regions) {
        let Some(&part) = region.and_then(|r| part_of.get(&r)) else {
            continue;
        };
        if *label != part as u32 {
            *label = part as u32;
            changed += 1;
        }
    }
    for p in &mut labelling.parts {
        p.vertex_count = 0;
    }
    for &p in &labelling.mesh_parts {
        if let Some(part) = labelling.parts.get_mut(p as usize) {
            part.vertex_count += 1;
        }
    }
    changed
}

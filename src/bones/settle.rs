//! Fitting a drafted bone inside the figure: widths come from distance-map values (9.1); a bone
//! that still pokes out of the skin shrinks step by step about its axis or centre.

use super::collision::overlaps;
use super::measure::inside_fraction;
use super::shapes::place;
use super::{Articulation, Bone, BoneKind, BoneOptions, BoneWarning};
use crate::distance::DistanceMap;
use crate::mesh::Mesh;
use crate::skeleton::JointId;
use glam::DVec3;

/// How a bone shrinks when it does not fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Shrink {
    /// Scale local x and y about the local z axis (long bones, vertebrae: the length is the
    /// segment's and stays).
    CrossSection,
    /// Scale about a local point (skulls, rib cages, scapulae, pelvis, small bones).
    About(DVec3),
}

/// A bone in its local frame with its placement.
#[derive(Debug, Clone)]
pub(crate) struct Draft {
    pub kind: BoneKind,
    pub name: String,
    pub joint: JointId,
    pub local: Mesh,
    pub origin: DVec3,
    /// Local x, y, z in the mesh frame (may mirror).
    pub axes: [DVec3; 3],
    pub shrink: Shrink,
    /// A world direction (unit) and distance the bone may slide along, both ways, to fit.
    pub slide: Option<(DVec3, f64)>,
}

impl Draft {
    fn scaled(&self, s: f64, offset: DVec3) -> Mesh {
        let local = match self.shrink {
            Shrink::CrossSection => self
                .local
                .transformed(|p| DVec3::new(p.x * s, p.y * s, p.z)),
            Shrink::About(c) => self.local.transformed(|p| c + (p - c) * s),
        };
        place(&local, self.origin + offset, self.axes)
    }

    /// Candidate offsets: none, then along the slide direction alternately forwards and
    /// backwards in quarter steps.
    fn offsets(&self) -> Vec<DVec3> {
        let mut out = vec![DVec3::ZERO];
        if let Some((d, m)) = self.slide {
            for k in 1..=4 {
                let step = d * (m * k as f64 / 4.0);
                out.push(step);
                out.push(-step);
            }
        }
        out
    }
}

/// Places `draft`, shrinking it by [`BoneOptions::shrink_step`] (and at each size trying the
/// slide offsets) until at least [`BoneOptions::inside_fraction`] of its vertices lie in
/// interior voxels without overlapping a `kept` bone outside the articulations. After
/// [`BoneOptions::max_shrink_steps`] the best placement is kept with a warning, or left out
/// (`None`, with a warning) below [`BoneOptions::min_inside_fraction`] or when every placement
/// inside enough overlaps a kept bone. A draft sized `on_surface` (inside the figure's
/// surface by construction, thinner than the voxels) counts as wholly inside.
pub(crate) fn settle(
    draft: &Draft,
    on_surface: bool,
    map: &DistanceMap,
    options: &BoneOptions,
    kept: &[Bone],
    articulations: &[Articulation],
    warnings: &mut Vec<BoneWarning>,
) -> Option<Bone> {
    let offsets = draft.offsets();
    let mut best: Option<(f64, f64, Mesh)> = None;
    // Whether some placement was inside enough but touched a kept bone; whether a placement
    // that was not, but would have been the best so far, did.
    let mut touching = false;
    let mut touching_fallback = false;
    let mut clear = false;
    let mut scale = 1.0;
    'search: for _ in 0..=options.max_shrink_steps {
        for &offset in &offsets {
            let mesh = draft.scaled(scale, offset);
            let fraction = if on_surface {
                1.0
            } else {
                inside_fraction(map, &mesh.positions, options.clearance)
            };
            if fraction >= options.inside_fraction {
                let touches = kept.iter().any(|b| overlaps(&mesh, &b.mesh, articulations));
                if !touches {
                    best = Some((fraction, scale, mesh));
                    clear = true;
                    break 'search;
                }
                touching = true;
            } else if best.as_ref().is_none_or(|b| fraction > b.0) {
                // A fallback placement must not overlap a kept bone either.
                if kept.iter().any(|b| overlaps(&mesh, &b.mesh, articulations)) {
                    touching_fallback = true;
                } else {
                    best = Some((fraction, scale, mesh));
                }
            }
        }
        scale *= options.shrink_step;
    }
    if !clear && (touching || (touching_fallback && best.is_none())) {
        // Bones must not intersect outside the joints: a bone that overlaps a neighbour at
        // every size and offset is left out rather than kept intersecting.
        warnings.push(BoneWarning::Overlapping {
            bone: draft.name.clone(),
        });
        return None;
    }
    let (fraction, scale, mesh) = best?;
    if fraction < options.min_inside_fraction {
        warnings.push(BoneWarning::Outside {
            bone: draft.name.clone(),
            inside: fraction,
        });
        return None;
    }
    if fraction < options.inside_fraction {
        warnings.push(BoneWarning::PartlyOutside {
            bone: draft.name.clone(),
            inside: fraction,
            scale,
        });
    }
    Some(Bone {
        kind: draft.kind,
        name: draft.name.clone(),
        joint: draft.joint,
        mesh,
    })
}

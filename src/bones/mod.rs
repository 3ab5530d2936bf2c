//! Bone meshes from an anatomical skeleton (dissertation ch.9.1, with the procedural,
//! feature-preserving shapes 9.1.1 recommends).
//!
//! ```text
//! Fit (skeleton + canonical map) ─▶ body reading: column, head, jaw, tail, limbs and girdles
//!   ─▶ axial: cranium + mandible on the head (widths from distance values), a vertebra per
//!      vertebral segment (width 1/12 of the largest trunk sphere's diameter), tail vertebrae
//!      tapering by 10 % each
//!   ─▶ girdles: a rib cage per group of overlapping pectoral girdle spheres, a scapula per
//!      pectoral limb (half as wide as long, tangent to its rib cage), the pelvis at the root
//!      with its sockets at the hips
//!   ─▶ limbs: humerus/femur, radius+ulna / tibia+fibula (+ patella), carpals/tarsals,
//!      metacarpals/metatarsals and phalanges, scaled to segment lengths and distance widths
//!   ─▶ each bone shrinks until it lies inside the figure (distance map)
//! ```
//!
//! Every [`Bone`] is attached to a joint and stored in the mesh frame at the rest pose;
//! [`Bone::local_mesh`] gives it in the joint's rest frame (for glTF child nodes) and
//! [`Bones::posed_mesh`] moves every bone rigidly with its joint. Missing parts (no ribs region,
//! missing limbs, digit-less limbs) give warnings, never errors or panics.
//!
//! ```
//! use skelfit::bones::shapes::{femur, LongBone};
//! let bone = LongBone { length: 0.45, radius: 0.014, epiphysis: 1.7, rings: 12, segments: 16 };
//! let stats = femur(&bone).stats();
//! assert!(stats.closed && stats.signed_volume.unwrap() > 0.0);
//! ```

mod axial;
mod bone;
mod collision;
pub(crate) use collision::windings;
mod context;
mod error;
mod export;
mod girdles;
mod kind;
mod limbs;
mod measure;
mod options;
mod preview;
mod settle;
pub mod shapes;
mod structure;
mod warning;

pub use bone::{Articulation, Bone, Bones};
pub use error::BoneError;
pub use export::{bones_glb_bytes, write_bones_glb, write_bones_obj};
pub use kind::BoneKind;
pub use options::BoneOptions;
pub use preview::bones_svg;
pub use warning::BoneWarning;

use crate::distance::DistanceMap;
use crate::fit::Fit;
use crate::mesh::Mesh;
use context::Context;

/// Bones for the fitted skeleton `fit` of the figure whose distance map is `distance`
/// (dissertation 9.1). Meshes are in the mesh frame and units at the rest pose, each attached
/// to a joint of `fit.skeleton`.
///
/// # Errors
/// [`BoneError::BadOption`] for options out of range, [`BoneError::EmptySkeleton`],
/// [`BoneError::InvalidSkeleton`], [`BoneError::EmptyDistanceMap`]. Missing body parts are
/// warnings in [`Bones::warnings`].
pub fn bones(fit: &Fit, distance: &DistanceMap, options: &BoneOptions) -> Result<Bones, BoneError> {
    build(fit, distance, None, options)
}

/// [`bones`] with the figure's surface `mesh` (the mesh the rig was fitted to): metacarpals,
/// metatarsals and phalanges thinner than the voxels are sized on the surface (their shaft a
/// share of the distance to the nearest surface vertex, the last phalanx ending that far
/// short of the tip) instead of being left out as outside the voxel figure.
///
/// # Errors
/// As [`bones`].
pub fn bones_with_surface(
    fit: &Fit,
    distance: &DistanceMap,
    mesh: &Mesh,
    options: &BoneOptions,
) -> Result<Bones, BoneError> {
    build(fit, distance, Some(mesh), options)
}

fn build(
    fit: &Fit,
    distance: &DistanceMap,
    surface: Option<&Mesh>,
    options: &BoneOptions,
) -> Result<Bones, BoneError> {
    options.validate()?;
    let skeleton = &fit.skeleton;
    if skeleton.is_empty() {
        return Err(BoneError::EmptySkeleton);
    }
    skeleton
        .validate()
        .map_err(|problems| BoneError::InvalidSkeleton {
            message: problems
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; "),
        })?;
    if distance.squared.iter().all(|&d| d == 0) {
        return Err(BoneError::EmptyDistanceMap);
    }
    let mut warnings = Vec::new();
    let body = structure::body(fit, &mut warnings);
    let mut ctx = Context::new(skeleton, distance, surface, options, body, warnings);
    // Bones sized by their segments first; girdle bones then fit round them.
    axial::skull(&mut ctx);
    axial::column(&mut ctx);
    limbs::limbs(&mut ctx);
    let cages = girdles::rib_cages(&mut ctx);
    girdles::scapulae(&mut ctx, &cages);
    girdles::pelvic_girdle(&mut ctx);
    Ok(Bones {
        bones: ctx.bones,
        articulations: ctx.articulations,
        warnings: ctx.warnings,
    })
}

//! Digits of the hands at their own resolution (issue 25; dissertation 8.2).
//!
//! At the body's voxel size (1 % of the height) fingers do not separate, so the fit gives each
//! hand one finger chain. Once the refinement has placed the wrists, [`fit_hands`] looks at each
//! hand again on the mesh surface itself:
//!
//! 1. **Hand surface** (`surface.rs`): the triangles within reach of the wrist on its distal
//!    side, and the geodesic distance over them from the wrist's cross-section (the band of
//!    surface just behind the wrist plane that encircles the forearm's axis, not a hip beside
//!    a hanging hand). A hand that is a separate mesh piece lying wholly beyond the wrist is
//!    measured from its own proximal cross-section.
//! 2. **Contour tree** (`contour.rs`): the surface sliced by that distance into level contours
//!    a fraction of the forearm apart; contours of neighbouring levels joined through the slab
//!    between them (a sampled Reeb graph). Where a contour splits, digits part; a digit is a
//!    leaf branch, its path the contour centroids from the web to the tip. Branches shorter
//!    than a few levels are noise and pruned.
//! 3. **Digits** (`hands.rs`): branches shorter than their mean width are bumps, and branches
//!    with a contour centre outside the figure are not digits;
//!    the thumb parts from the palm first (the deepest web; at equal
//!    depth, the thinner branch); the fingers follow in the order of their bases from the
//!    thumb's. Five digits give `thumb_01..03` and `index_01..pinky_03` with a `_end` at each
//!    tip; fewer give the digits found with a warning, and a mitten (no separated fingers)
//!    keeps one finger chain, moved onto the mitten (plus a thumb when it separates), with the
//!    warning that the fingers are fused.
//! 4. **Joints** (`place.rs`): along each digit's path from the tip, at fractions of the
//!    digit's length from its base joint (the surface of smooth digits shows no creases; the
//!    fractions are options), the base extrapolated along the digit's axis behind the web.
//!    Frames: z along the digit, x the curl axis, so that a positive rotation about x bends the
//!    digit towards the palm.
//!
//! [`fit_feet`] does the same for an upright figure's feet (`feet.rs`): the foot's surface
//! below the ankle (as the hand's, measured from the shank's cross-section), its direction
//! horizontally towards the point farthest over the surface (the longest toe), the toe end at
//! the foot's front tip and the toe joint at the ball of the foot, the centre of the widest
//! cross-section between ankle and tip (the forefoot is widest across the metatarsal heads).
//! Toes are not separated: every human foot keeps one toe chain.
//!
//! [`fit_paws`] reads a horizontal figure's fore and hind feet as hands, but an animal's
//! foot has no thumb: the digits that separate (at least two; a hoof or a low-poly paw keeps
//! the fit's single digit chain, silently) are ordered across the foot and numbered by the
//! mammalian reduction pattern (`paws.rs`), hung from the metapodial joint.

mod contour;
mod feet;
mod hands;
mod options;
mod paws;
mod place;
mod surface;
mod warning;

pub use feet::fit_feet;
pub use hands::fit_hands;
pub use options::DigitOptions;
pub use paws::fit_paws;
pub(crate) use surface::edge_geodesic;

use crate::fit::Fit;
use crate::mesh::Mesh;
use crate::template::{Posture, Template};
use glam::DVec3;

/// The digit stage: [`fit_hands`], then [`fit_feet`] (`up`: the figure's up, `facing`: its
/// forward, where an upright figure's feet point); a horizontal figure's (an animal's) feet
/// [`fit_paws`] instead. Their warnings.
pub fn fit_digits(
    mesh: &Mesh,
    template: &Template,
    fit: &mut Fit,
    up: DVec3,
    facing: DVec3,
    options: &DigitOptions,
) -> Vec<DigitWarning> {
    if template.posture != Posture::Upright {
        return fit_paws(mesh, template, fit, up, options);
    }
    // Every hand and foot is read at once (each looks only at the mesh and its own limb's
    // joints); then the hands are rebuilt and the feet placed in order, as one after another.
    let (hands, feet) = rayon::join(
        || hands::read_hands(mesh, template, fit, options),
        || feet::read_feet(mesh, template, fit, up, facing, options),
    );
    let mut warnings = hands::place_hands(mesh, template, fit, options, hands);
    warnings.extend(feet::place_feet(
        mesh, template, fit, up, facing, options, feet,
    ));
    warnings
}
pub use warning::DigitWarning;

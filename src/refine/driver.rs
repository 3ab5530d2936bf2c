//! The refinement driver: body frame, head, torso, hips, legs, arms, spine, then the skeleton.
//! The arm and leg phases are in [`super::arms`] and [`super::legs`].

use super::arms::arm;
use super::carry::carry;
use super::frame::{frame_from_head, head_slices, BodyFrame};
use super::full_spine::{with_full_spine, SpineDetail};
use super::head::head_joint;
use super::joint_pieces::{joint_balls, place_on_balls};
use super::legs::leg;
use super::limb_joints::centre_in_depth;
use super::spine::{spine, Spine};
use super::symmetry::mirror;
use super::torso::{
    hips, leg_split_height, legs_apart_below, split_flare, torso_points, TorsoBounds, TorsoPoints,
    HEM_FLARE,
};
use super::{RefineError, RefineOptions, RefineWarning};
use crate::fit::{assign_trunk_keys, Fit};
use crate::mesh::{slice_plane_outer, Mesh};
use crate::skeleton::{Canonical, JointId, Side, Skeleton};
use crate::template::{AxialRules, RefineKind, Template};
use glam::DVec3;
use std::collections::BTreeMap;

/// The canonical joints the refinement places.
pub const REFINED: [Canonical; 15] = [
    Canonical::Pelvis,
    Canonical::Neck,
    Canonical::Head,
    Canonical::Shoulder(Side::Left),
    Canonical::Shoulder(Side::Right),
    Canonical::Elbow(Side::Left),
    Canonical::Elbow(Side::Right),
    Canonical::Wrist(Side::Left),
    Canonical::Wrist(Side::Right),
    Canonical::Hip(Side::Left),
    Canonical::Hip(Side::Right),
    Canonical::Knee(Side::Left),
    Canonical::Knee(Side::Right),
    Canonical::Ankle(Side::Left),
    Canonical::Ankle(Side::Right),
];

/// [`REFINED`] as written in files.
pub const REFINED_KEYS: [&str; 15] = {
    let mut out = [""; 15];
    let mut i = 0;
    while i < REFINED.len() {
        out[i] = REFINED[i].as_str();
        i += 1;
    }
    out
};

/// A refined skeleton and what the refinement found on the way.
#[derive(Debug, Clone, PartialEq)]
pub struct Refinement {
    /// The input skeleton with the refined canonical joints moved, the joints between them
    /// carried along (spine joints onto the spine curve) and frames turned with their segments.
    pub skeleton: Skeleton,
    /// Canonical key → joint of `skeleton`: the rough map, with `spine` and `chest` reassigned
    /// to the trunk joints where they ended up when the template's trunk rules were given
    /// ([`refine_fit`]; [`crate::fit::assign_trunk_keys`]).
    pub canonical: BTreeMap<String, JointId>,
    /// The full spine from the top: `C1`..`C7`, `T1`..`T12`, `L1`..`L5` (each the joint below
    /// that vertebra) and `sacrum`; empty when the spine was not found.
    pub spine: Vec<(String, DVec3)>,
    /// Per canonical key that moved: (rough position, refined position).
    pub moved: BTreeMap<String, (DVec3, DVec3)>,
    /// The body frame the analysis used.
    pub frame: BodyFrame,
    /// Characteristic torso points, when the median silhouette was found.
    pub torso: Option<TorsoPoints>,
    /// One warning per joint (or group of joints) that kept its rough position.
    pub warnings: Vec<RefineWarning>,
}

/// The refined positions found so far.
pub(super) type Found = BTreeMap<Canonical, DVec3>;

/// The rough skeleton's canonical joints.
pub(super) struct Rough<'a> {
    skeleton: &'a Skeleton,
    canonical: &'a BTreeMap<String, JointId>,
}

impl Rough<'_> {
    /// The rough position of `key`, when the skeleton has it.
    pub(super) fn at(&self, key: Canonical) -> Option<DVec3> {
        self.id(key).map(|id| self.skeleton.joint(id).position)
    }

    fn id(&self, key: Canonical) -> Option<JointId> {
        self.canonical.get(key.as_str()).copied()
    }

    /// The mean height in `frame` of the left and right `joint` the skeleton has.
    fn pair_height(&self, frame: &BodyFrame, joint: fn(Side) -> Canonical) -> Option<f64> {
        let hs: Vec<f64> = Side::BOTH
            .map(joint)
            .iter()
            .filter_map(|k| self.at(*k))
            .map(|p| frame.h(p))
            .collect();
        (!hs.is_empty()).then(|| hs.iter().sum::<f64>() / hs.len() as f64)
    }
}

/// What every phase after the head reads: the (fine enough) mesh, the body frame, the figure's
/// height, a point of the median plane, and the options.
#[derive(Clone, Copy)]
pub(super) struct Scene<'a> {
    pub(super) mesh: &'a Mesh,
    pub(super) frame: BodyFrame,
    pub(super) height: f64,
    pub(super) centre: DVec3,
    pub(super) options: &'a RefineOptions,
}

/// Refines `fit` as its template declares ([`Template::refinement`]): `mesh` is the surface
/// to slice (one closed shell), `pieces` the figure as modelled, with its separate pieces,
/// from which a jointed figure's joint balls are read ([`super::joint_balls`]; `mesh` again
/// when that is the figure's own surface). For
/// [`RefineKind::HumanSlicing`], [`refine`] of the fit's skeleton, with the canonical `spine`
/// and `chest` then reassigned by the template's trunk rules ([`Refinement::canonical`]).
/// `None` when the template declares no refinement. `up` and `forward` as for [`refine`].
/// With [`RefineOptions::spine`] [`SpineDetail::Full`], the full spine replaces the trunk and
/// neck joints ([`super::full_spine`]), or a [`RefineWarning::CoarseSpineKept`] says why not.
///
/// # Errors
/// As [`refine`].
pub fn refine_fit(
    mesh: &Mesh,
    pieces: &Mesh,
    fit: &Fit,
    template: &Template,
    up: DVec3,
    forward: DVec3,
    options: &RefineOptions,
) -> Option<Result<Refinement, RefineError>> {
    match template.refinement? {
        RefineKind::HumanSlicing => Some(
            refine_with(
                mesh,
                pieces,
                &fit.skeleton,
                &fit.canonical,
                Some(&template.axial),
                up,
                forward,
                options,
            )
            .map(|refined| match options.spine {
                SpineDetail::Coarse => refined,
                SpineDetail::Full => with_full_spine(refined, template),
            }),
        ),
    }
}

/// Refines a roughly aligned humanoid skeleton by slicing its mesh (seed 004).
///
/// * `mesh`: the body surface (closed or nearly so), any units and frame.
/// * `skeleton`, `canonical`: the rough skeleton and its canonical key → joint map (keys as in
///   [`REFINED_KEYS`]; `toe_*`, `spine`, `chest` and others are carried along).
/// * `up`, `forward`: the figure's up and facing directions in the mesh frame; `up` is
///   replaced by the legs' ankle→hip direction and `forward` by the head's long axis when
///   those are found (seed 004, 3.1).
///
/// Each joint that cannot be refined keeps its rough position and adds a warning that names it;
/// nothing panics on odd input.
///
/// # Errors
/// [`RefineError::InvalidOptions`] (checked first), [`RefineError::EmptyMesh`], [`RefineError::BadDirections`] for zero, non-finite or parallel
/// `up`/`forward`, [`RefineError::BadJointId`] for a canonical id outside the skeleton.
pub fn refine(
    mesh: &Mesh,
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    up: DVec3,
    forward: DVec3,
    options: &RefineOptions,
) -> Result<Refinement, RefineError> {
    refine_with(mesh, mesh, skeleton, canonical, None, up, forward, options)
}

/// [`refine`], reassigning the canonical `spine` and `chest` by `trunk` when given.
#[allow(clippy::too_many_arguments)]
fn refine_with(
    mesh: &Mesh,
    pieces: &Mesh,
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    trunk: Option<&AxialRules>,
    up: DVec3,
    forward: DVec3,
    options: &RefineOptions,
) -> Result<Refinement, RefineError> {
    check_input(mesh, skeleton, canonical, up, forward, options)?;
    let bad = || RefineError::BadDirections { up, forward };
    let rough = Rough {
        skeleton,
        canonical,
    };
    let mut warnings = Vec::new();
    let given = BodyFrame::new(mesh, up, forward).ok_or_else(bad)?;
    let mut frame = legs_frame(mesh, &rough, given).unwrap_or_else(|| {
        warnings.push(RefineWarning::NoUprightLegs);
        given
    });
    let height = frame.height();
    let fine = fine_enough(mesh, options.max_mean_edge * height);
    let mesh = fine.as_ref().unwrap_or(mesh);
    let mut found = Found::new();

    // 3.1 Head and body frame.
    let (on_trunk, head_top) = head(mesh, &mut frame, &rough, options, &mut found, &mut warnings);

    // 3.2 Torso points.
    let head_point = found
        .get(&Canonical::Head)
        .copied()
        .or_else(|| rough.at(Canonical::Head));
    let mut scene = Scene {
        mesh,
        frame,
        height,
        centre: DVec3::ZERO,
        options,
    };
    scene.centre = median_centre(&scene, &rough, head_point);
    let hips_h = rough.pair_height(&frame, Canonical::Hip);
    let shoulders_h = rough.pair_height(&frame, Canonical::Shoulder);
    // 3.3 Arms.
    let waist = match (hips_h, shoulders_h) {
        (Some(h), Some(s)) => Some((h + s) * 0.5),
        _ => None,
    };
    each_side(&mut found, &mut warnings, |side, found, warnings| {
        arm(&scene, &rough, side, waist, found, warnings);
    });

    let torso = torso(&scene, head_point, shoulders_h, hips_h, &found);
    if torso.is_none() {
        warnings.push(RefineWarning::NoTorsoSilhouette);
    }

    // 3.3 Hips and pelvis.
    let crotch_hidden = hips_and_pelvis(
        &scene,
        &rough,
        torso.as_ref(),
        hips_h,
        &mut found,
        &mut warnings,
    );

    // 3.3 Legs.
    each_side(&mut found, &mut warnings, |side, found, warnings| {
        leg(&scene, &rough, side, crotch_hidden, found, warnings);
    });

    // Jointed figures: a round piece at a limb joint is the joint.
    if options.joint_pieces {
        joints_on_balls(pieces, &scene, &rough, &mut found, &mut warnings);
        shoulders_on_arm_pieces(pieces, &scene, &rough, &mut found, &mut warnings);
    }

    // 3.2 Spine and neck.
    let spine_result = spine_and_neck(&scene, torso.as_ref(), on_trunk, &mut found, &mut warnings);

    let (mut targets, moved) = accepted(&rough, &found, &scene, &mut warnings);
    let spine_ends_moved = moved.contains_key(Canonical::Pelvis.as_str())
        && moved.contains_key(Canonical::Neck.as_str());
    if let (Some(s), true) = (&spine_result, spine_ends_moved) {
        for (id, p) in place_spine_joints(&rough, s) {
            targets.insert(id, p);
        }
    }
    let mut skeleton = carry(skeleton, &targets);
    if moved.contains_key(Canonical::Head.as_str()) {
        head_end_above_head(&mut skeleton, &rough, &scene.frame, head_top);
    }
    let mut canonical = canonical.clone();
    if let Some(rules) = trunk {
        assign_trunk_keys(&skeleton, &mut canonical, rules);
    }
    Ok(Refinement {
        skeleton,
        canonical,
        spine: spine_result.map(|s| s.joints).unwrap_or_default(),
        moved,
        frame,
        torso,
        warnings,
    })
}

/// Runs a limb phase for the left and then the right side, the two sides on two threads:
/// each side reads and writes only its own joints in `found` (an arm its shoulder, elbow and
/// wrist; a leg its hip, knee and ankle), so each runs on its own copy of `found` and the
/// results merge as if left had run before right: the joints each side placed or moved, then
/// left's warnings before right's. The same result as the loop over [`Side::BOTH`], in about
/// half the time on two cores.
fn each_side(
    found: &mut Found,
    warnings: &mut Vec<RefineWarning>,
    phase: impl Fn(Side, &mut Found, &mut Vec<RefineWarning>) + Sync,
) {
    let before: &Found = found;
    let run = |side: Side| {
        let mut own = before.clone();
        let mut said = Vec::new();
        phase(side, &mut own, &mut said);
        let placed: Vec<(Canonical, DVec3)> = own
            .into_iter()
            .filter(|(key, p)| before.get(key) != Some(p))
            .collect();
        debug_assert!(
            placed.iter().all(|(key, _)| key.side() == Some(side)),
            "a limb phase placed a joint of the other side"
        );
        (placed, said)
    };
    let ((left, left_said), (right, right_said)) =
        rayon::join(|| run(Side::Left), || run(Side::Right));
    found.extend(left.into_iter().chain(right));
    warnings.extend(left_said.into_iter().chain(right_said));
}

/// Moves each shoulder of a modular figure whose arm is a separate piece buried in the trunk
/// to the centre of that piece's buried end ([`super::arm_pieces`]), and drops the warnings
/// that said the shoulder was not found (no armpit: the arm piece is sunk into the trunk).
fn shoulders_on_arm_pieces(
    pieces: &Mesh,
    scene: &Scene,
    rough: &Rough,
    found: &mut Found,
    warnings: &mut Vec<RefineWarning>,
) {
    let component = crate::mesh::vertex_pieces(pieces.positions.len(), &pieces.triangles);
    let limit = scene.options.max_shift * scene.height;
    for side in Side::BOTH {
        let at = |key: Canonical| found.get(&key).copied().or_else(|| rough.at(key));
        let (Some(elbow), Some(shoulder)) =
            (at(Canonical::Elbow(side)), at(Canonical::Shoulder(side)))
        else {
            continue;
        };
        let Some(moved) = super::arm_pieces::shoulder_on_arm_piece(
            pieces,
            &component,
            &scene.frame,
            scene.centre,
            elbow,
            shoulder,
        ) else {
            continue;
        };
        if moved.distance(shoulder) > limit {
            continue;
        }
        found.insert(Canonical::Shoulder(side), moved);
        let key = Canonical::Shoulder(side);
        warnings.retain(|w| !(w.keys().len() == 1 && w.keys()[0] == key));
    }
}

/// Moves the limb joints of a jointed figure to the round pieces at them
/// ([`super::joint_pieces`]), from the balls of `pieces` as modelled (not the subdivided or
/// joined surface: midpoints of a sphere's edges lie inside it), and drops the warnings that
/// said those joints were not found. The joints' estimates are the refined positions that
/// [`accepted`] will take (within [`RefineOptions::max_shift`] of the rough ones), else the
/// rough ones.
fn joints_on_balls(
    pieces: &Mesh,
    scene: &Scene,
    rough: &Rough,
    found: &mut Found,
    warnings: &mut Vec<RefineWarning>,
) {
    let balls = joint_balls(pieces);
    if balls.is_empty() {
        return;
    }
    let limit = scene.options.max_shift * scene.height;
    let estimates: Found = REFINED
        .iter()
        .filter_map(|&key| {
            let from = rough.at(key);
            let refined = found.get(&key).copied().filter(|&to| {
                to.is_finite()
                    && from.is_none_or(|f| shift(rough, &scene.frame, key, f, to) <= limit)
            });
            Some((key, refined.or(from)?))
        })
        .collect();
    let placed = place_on_balls(&balls, &estimates, found);
    warnings.retain(|w| {
        let keys = match *w {
            // Placed by a fallback: they name no joint left rough, but say how it was placed.
            RefineWarning::NoKnee { side, .. } => vec![Canonical::Knee(side)],
            RefineWarning::NoAnkle { side, .. } => vec![Canonical::Ankle(side)],
            _ => w.keys(),
        };
        keys.is_empty() || !keys.iter().all(|k| placed.contains(k))
    });
}

/// Places the head joint, and turns `frame` to the head's axes when the head slices give them
/// (seed 004, 3.1). Returns whether the head sits on the trunk with no neck between
/// ([`super::HeadJoint::on_trunk`]) and the height of the head's top slice.
fn head(
    mesh: &Mesh,
    frame: &mut BodyFrame,
    rough: &Rough,
    options: &RefineOptions,
    found: &mut Found,
    warnings: &mut Vec<RefineWarning>,
) -> (bool, Option<f64>) {
    let near_head = rough
        .at(Canonical::Head)
        .unwrap_or_else(|| frame.at_height(DVec3::ZERO, frame.top));
    let shoulders = rough.pair_height(frame, Canonical::Shoulder);
    match head_slices(mesh, frame, near_head, shoulders, options) {
        Some(slices) => {
            if let Some(f) = frame_from_head(frame, &slices, frame.forward) {
                *frame = f;
            }
            let shoulders = rough.pair_height(frame, Canonical::Shoulder);
            let top = slices
                .slices
                .first()
                .and_then(|s| s.points.first())
                .map(|p| frame.h(*p));
            match head_joint(mesh, frame, &slices, shoulders, options) {
                Some(h) => {
                    found.insert(Canonical::Head, h.joint);
                    return (h.on_trunk, top);
                }
                None => warnings.push(RefineWarning::NoOccipitalCircle),
            }
        }
        None => warnings.push(RefineWarning::NoHead),
    }
    (false, None)
}

/// Puts the head's end joint (`head_end`, the head bone's tip) straight above the refined head
/// joint at `top`, the height of the head's top slice (seed 004, 3.1: the head's leaf at the
/// top of the skull). The fit leaves it at the end of the head's medial path, which wanders
/// over a round skull's dome with the voxel grid (up to a tenth of the height forward or back
/// between a figure and its Z-up copy). Nothing moves without a top above the head joint.
fn head_end_above_head(
    skeleton: &mut Skeleton,
    rough: &Rough,
    frame: &BodyFrame,
    top: Option<f64>,
) {
    let (Some(head), Some(top)) = (rough.id(Canonical::Head), top) else {
        return;
    };
    let joint = skeleton.joint(head).position;
    if top <= frame.h(joint) {
        return;
    }
    let end = skeleton
        .children(head)
        .into_iter()
        .find(|c| skeleton.joint(*c).name == "head_end");
    if let Some(end) = end {
        skeleton.joints[end.0].position = frame.at_height(joint, top);
    }
}

/// A head sitting on its trunk with no neck between ([`super::HeadJoint::on_trunk`]) has its
/// joint at the junction, which is the trunk's top: the neck joint rises to that height (at
/// the spine's depth), and the head joint goes above it by the neck's length as the spine gave
/// it (from C7 up to the junction), as such figures' rigs keep a neck bone inside the head's
/// base. Nothing moves unless the neck lies below the head.
fn neck_at_junction(frame: &BodyFrame, found: &mut Found) {
    let (Some(&head), Some(&neck)) = (found.get(&Canonical::Head), found.get(&Canonical::Neck))
    else {
        return;
    };
    let length = frame.h(head) - frame.h(neck);
    if length > 0.0 {
        found.insert(Canonical::Neck, frame.at_height(neck, frame.h(head)));
        found.insert(Canonical::Head, head + frame.up * length);
    }
}

/// The spine from the head joint and the torso silhouette, and the neck at its C7 (at the
/// silhouette's neck point when there is no spine); for a head `on_trunk`, the neck and head
/// then as [`neck_at_junction`] says.
fn spine_and_neck(
    scene: &Scene,
    torso: Option<&TorsoPoints>,
    on_trunk: bool,
    found: &mut Found,
    warnings: &mut Vec<RefineWarning>,
) -> Option<Spine> {
    let options = scene.options;
    let spine_result: Option<Spine> = match (torso, found.get(&Canonical::Head)) {
        (Some(t), Some(&h)) => spine(&scene.frame, scene.centre, h, t, options)
            .filter(|s| lumbar_above_pelvis(&scene.frame, s, found.get(&Canonical::Pelvis))),
        _ => None,
    };
    match (&spine_result, torso) {
        (Some(s), _) => {
            if let Some(c7) = s.joint("C7") {
                found.insert(Canonical::Neck, c7);
            }
        }
        (None, Some(t)) => {
            found.insert(Canonical::Neck, t.neck.lerp(t.throat, options.neck_depth));
            warnings.push(RefineWarning::SpineOutOfOrder);
        }
        (None, None) => warnings.push(RefineWarning::NoSpine),
    }
    if on_trunk {
        neck_at_junction(&scene.frame, found);
    }
    neck_under_head(&scene.frame, found);
    spine_result
}

/// Whether the spine's lumbar control point (L3/L4) lies above the `pelvis` joint (true without
/// one): the lumbar spine rises from the pelvis. Where clothing hides the crotch (a skirt), the
/// median silhouette's lower back and buttocks can be folds of the skirt far below the hips;
/// a curve through them is no spine, and the spine joints are carried along as when its
/// control points are out of order.
fn lumbar_above_pelvis(frame: &BodyFrame, spine: &Spine, pelvis: Option<&DVec3>) -> bool {
    match (spine.control.get(3), pelvis) {
        (Some(&lumbar), Some(&pelvis)) => frame.h(lumbar) > frame.h(pelvis),
        _ => true,
    }
}

/// The most the cervical column leans forward from C7 (the `neck` joint) up to the head
/// joint, degrees from the body's up: in an upright posture it rises about 20° forward of
/// vertical (the MakeHuman rigs 19-23°, the game rigs 0-17°).
pub const NECK_MAX_LEAN_DEGREES: f64 = 25.0;

/// The neck joint moved forward (along `frame.forward`, at its height) until the line up to
/// the head joint leans no more than [`NECK_MAX_LEAN_DEGREES`]. C7 is found on the trunk's
/// back silhouette, which a cartoon's head shell enveloping the neck, a hood or an armour
/// collar pushes back (the platformer character's neck leaned 54° back from its head, 4 % of
/// the height behind the reference; the knight's, CesiumMan's and the adventurer's 34-39°).
/// Nothing moves when the neck is not below the head.
fn neck_under_head(frame: &BodyFrame, found: &mut Found) {
    let (Some(&head), Some(&neck)) = (found.get(&Canonical::Head), found.get(&Canonical::Neck))
    else {
        return;
    };
    let rise = frame.h(head) - frame.h(neck);
    if rise <= 0.0 {
        return;
    }
    let behind = (head - neck).dot(frame.forward);
    let most = rise * NECK_MAX_LEAN_DEGREES.to_radians().tan();
    if behind > most {
        found.insert(Canonical::Neck, neck + frame.forward * (behind - most));
    }
}

/// The errors of [`refine`] that need no work: bad options, an empty mesh, non-finite
/// directions, canonical ids outside the skeleton.
fn check_input(
    mesh: &Mesh,
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    up: DVec3,
    forward: DVec3,
    options: &RefineOptions,
) -> Result<(), RefineError> {
    options.validate()?;
    if mesh.triangles.is_empty() {
        return Err(RefineError::EmptyMesh);
    }
    if !up.is_finite() || !forward.is_finite() {
        return Err(RefineError::BadDirections { up, forward });
    }
    for (key, id) in canonical {
        if id.0 >= skeleton.len() {
            return Err(RefineError::BadJointId {
                key: key.clone(),
                id: id.0,
                len: skeleton.len(),
            });
        }
    }
    Ok(())
}

/// The torso's characteristic points from the median silhouette between the hips and the
/// head, with the shoulders' height from the refined shoulders when both were found (else
/// the rough `shoulders_h`).
fn torso(
    scene: &Scene,
    head_point: Option<DVec3>,
    shoulders_h: Option<f64>,
    hips_h: Option<f64>,
    found: &Found,
) -> Option<TorsoPoints> {
    let frame = &scene.frame;
    let refined_shoulders = match (
        found.get(&Canonical::Shoulder(Side::Left)),
        found.get(&Canonical::Shoulder(Side::Right)),
    ) {
        (Some(l), Some(r)) => Some((frame.h(*l) + frame.h(*r)) * 0.5),
        _ => shoulders_h,
    };
    let bounds = match (head_point, refined_shoulders, hips_h) {
        (Some(h), Some(s), Some(p)) => Some(TorsoBounds {
            head: frame.h(h),
            shoulders: s,
            hips: p,
        }),
        _ => None,
    };
    bounds.and_then(|b| torso_points(scene.mesh, frame, scene.centre, &b, scene.options))
}

/// The body frame with `up` along the rough legs' ankle→hip direction, when the legs are
/// within [`MAX_LEGS_LEAN_DEGREES`] of `given.up`. Only its part in the median plane counts (the plane of
/// `given.up` and `given.forward`): a bilaterally symmetric figure's up lies in that plane, and
/// rough ankles at unequal heights (one foot's labels reaching higher than the other's) had
/// tilted a cartoon's frame 6° sideways, so that the head's slices cut one ear and missed the
/// other.
fn legs_frame(mesh: &Mesh, rough: &Rough, given: BodyFrame) -> Option<BodyFrame> {
    let legs = Side::BOTH
        .iter()
        .filter_map(|&s| Some(rough.at(Canonical::Hip(s))? - rough.at(Canonical::Ankle(s))?))
        .sum::<DVec3>();
    let legs_up = (legs - given.left * legs.dot(given.left))
        .try_normalize()
        .filter(|n| n.dot(given.up) > MAX_LEGS_LEAN_DEGREES.to_radians().cos());
    legs_up.and_then(|n| BodyFrame::new(mesh, n, given.forward))
}

/// The most the rough legs, together, may lean fore or aft from the given up and still set
/// the body's up ([`legs_frame`]). Standing figures' legs lean a few degrees from their file's
/// up (at most 8° on the reference humanoids, the cyberpunk character's tapered peg legs), and
/// a figure turned a little off its axes is found within that. Legs leaning further are not
/// a standing pair: an ankle-length robe leaves the labels only its wearer's feet and shins
/// below the hem, whose rough hips lay 11 cm behind the ankles and tilted every slice of the
/// refinement 21°.
const MAX_LEGS_LEAN_DEGREES: f64 = 15.0;

/// A point of the median plane (`scene.centre` is not read): half-way across between the rough pelvis and the head, moved
/// sideways to the middle of the waist's cross-section.
fn median_centre(scene: &Scene, rough: &Rough, head_point: Option<DVec3>) -> DVec3 {
    let Scene {
        mesh,
        frame,
        height,
        ..
    } = *scene;
    let frame = &frame;
    let pelvis_rough = rough.at(Canonical::Pelvis).or_else(|| {
        Some((rough.at(Canonical::Hip(Side::Left))? + rough.at(Canonical::Hip(Side::Right))?) * 0.5)
    });
    let centre = match (pelvis_rough, head_point) {
        (Some(p), Some(h)) => p + frame.left * ((h - p).dot(frame.left) * 0.5),
        (Some(p), None) => p,
        (None, Some(h)) => h,
        (None, None) => frame.at_height(DVec3::ZERO, frame.bottom + 0.5 * height),
    };
    // The median plane passes through the waist's cross-section: the rough pelvis can sit a
    // centimetre or two off the body's middle, and the spine and neck (found in that plane)
    // moved sideways with it.
    match (
        rough.pair_height(frame, Canonical::Hip),
        rough.pair_height(frame, Canonical::Shoulder),
    ) {
        (Some(hips_h), Some(shoulders_h)) => {
            let origin = frame.at_height(centre, 0.5 * (hips_h + shoulders_h));
            slice_plane_outer(mesh, origin, frame.up)
                .iter()
                .filter(|l| l.closed)
                .filter_map(|l| l.centroid())
                .min_by(|a, b| a.distance(origin).total_cmp(&b.distance(origin)))
                .map_or(centre, |g| {
                    centre + frame.left * (g - centre).dot(frame.left)
                })
        }
        _ => centre,
    }
}

/// Places both hips and the pelvis from a transverse slice at hip height (above the crotch's
/// leg split when the torso silhouette was found, by proportion when clothing hides the
/// crotch, else the rough hips' mean height `hips_h`). Returns whether clothing hides the
/// crotch.
fn hips_and_pelvis(
    scene: &Scene,
    rough: &Rough,
    torso: Option<&TorsoPoints>,
    hips_h: Option<f64>,
    found: &mut Found,
    warnings: &mut Vec<RefineWarning>,
) -> bool {
    let Scene {
        mesh,
        frame,
        height,
        centre,
        options,
    } = *scene;
    let reach = match (
        rough.at(Canonical::Hip(Side::Left)),
        rough.at(Canonical::Hip(Side::Right)),
    ) {
        (Some(l), Some(r)) => 1.5 * l.distance(r),
        _ => 0.15 * height,
    };
    let knees = rough.pair_height(&frame, Canonical::Knee);
    // The top of the gap between the legs, read once for both the hem test and the hips.
    let split = torso.and_then(|t| crotch_split(scene, frame.h(t.crotch), reach));
    let by_crotch = |t: &TorsoPoints| {
        let crotch = split.unwrap_or(frame.h(t.crotch));
        hips_above_crotch(rough, found, &frame, crotch, options.hip_above_crotch)
    };
    let from_arms = hips_from_arms(rough, found, &frame, knees);
    // A hem's flare where the legs part, with the hips it gives far below where the arms
    // put them: the flare is clothing's, not the trunk's.
    let below_arms = match (torso.and_then(by_crotch), from_arms) {
        (Some(c), Some(a)) => a - c,
        _ => 0.0,
    };
    let hem_too_low = below_arms > HEM_HIPS_BELOW_ARMS * height;
    // Hips that far below the arms' are no figure's: where the legs part below the
    // silhouette's lowest point, that point is not the crotch, whatever the outline does
    // there (an ankle-length robe, below whose hem the shins touch and the median silhouette
    // runs on down them). A blob, whose legs never part, is left to the rules below.
    let crotch_hidden = (split.is_some() && below_arms > HIPS_FAR_BELOW_ARMS * height)
        || crotch_hidden(scene, torso, split, knees, reach, hem_too_low);
    let hip_height = match torso {
        // A skirt, robe or long coat hides the crotch ([`crotch_hidden`]): the hips go where
        // the arm's length puts them.
        Some(_) if crotch_hidden => {
            warnings.push(RefineWarning::CrotchHidden {
                placed: from_arms.is_some(),
            });
            from_arms.or(hips_h)
        }
        Some(t) => by_crotch(t).or(hips_h),
        None => hips_h,
    };
    match hip_height.and_then(|h| hips(mesh, &frame, centre, h, reach)) {
        Some((l, r)) => {
            let in_depth = |p: DVec3| match options.hip_depth {
                Some(depth) => centre_in_depth(mesh, &frame, p, depth).unwrap_or(p),
                None => p,
            };
            let (l, r) = (in_depth(l), in_depth(r));
            found.insert(Canonical::Hip(Side::Left), l);
            found.insert(Canonical::Hip(Side::Right), r);
            found.insert(
                Canonical::Pelvis,
                (l + r) * 0.5 + frame.up * (options.pelvis_above_hips * height),
            );
        }
        None => warnings.push(RefineWarning::NoHipSlice),
    }
    crotch_hidden
}

/// The sections compared for a hem's flare ([`split_flare`]) lie this fraction of height
/// below and above the leg split: close enough that a crotch's outline barely changes between
/// them (the buttocks widen the MakeHuman bodies' depth by 15 % within 0.02 above it).
const FLARE_GAP: f64 = 0.01;

/// Whether clothing hides the crotch: the median silhouette runs down below the rough knees
/// while the legs show apart lower down (a skirt, robe or long coat; a blob's silhouette also
/// ends low but shows no legs apart), unless the legs' own sections leave the trunk at the
/// silhouette's lowest point without a hem's flare ([`split_flare`] at most [`HEM_FLARE`]):
/// there the crotch shows, and the rough knees are too high (short cartoon legs, whose rough
/// knees the adult leg ratios put above the crotch). Where the silhouette ends, wherever that
/// is, on a hem's flare (more than [`HEM_FLARE`]) that would put the hips far below where
/// the arms' length puts them (`hem_too_low`, [`HEM_HIPS_BELOW_ARMS`]), clothing hides the
/// crotch too: a skirt ending above the knees, or a long one whose median slice a figure
/// turned a few degrees off the file's axes cuts at its hem rather than down the legs
/// (women_formal turned 3°: its hips at the hem, 4.7 % of its height off). `split` is
/// [`crotch_split`] at the silhouette's lowest point.
fn crotch_hidden(
    scene: &Scene,
    torso: Option<&TorsoPoints>,
    split: Option<f64>,
    knees: Option<f64>,
    reach: f64,
    hem_too_low: bool,
) -> bool {
    let Scene {
        mesh,
        frame,
        height,
        centre,
        ..
    } = *scene;
    let Some(crotch) = torso.map(|t| frame.h(t.crotch)) else {
        return false;
    };
    let low = knees.is_some_and(|k| crotch < k && legs_apart_below(mesh, &frame, centre, k, reach));
    let flare =
        split.and_then(|split| split_flare(mesh, &frame, centre, split, FLARE_GAP * height, reach));
    let shows = flare.is_some_and(|flare| flare <= HEM_FLARE);
    let hem = hem_too_low && flare.is_some_and(|flare| flare > HEM_FLARE);
    (low && !shows) || hem
}

/// How far (fraction of the height) the hips the crotch gives may lie below the hips the arms
/// give ([`TRUNK_PER_ARM`]) before a hem's flare where the legs part counts as clothing hiding
/// the crotch. On the reference humanoids the arms put the hips at most 0.045 of the height
/// above the crotch's, the platformer character's cartoon proportions included; a jointed
/// robot's pelvis piece flares over its thighs like a hem, but its arms put the hips lower
/// (0.08 of the height), not higher. The women_formal dress turned 3° ended on its hem at
/// 0.15 of the height below.
const HEM_HIPS_BELOW_ARMS: f64 = 0.08;

/// How far (fraction of the height) the hips the crotch gives may lie below the hips the arms
/// give before the silhouette's lowest point counts as no crotch at all, hem or not: a
/// quarter of a standing figure's hip height (about half of it), and three times the most
/// seen on the reference humanoids, robots and cartoons included ([`HEM_HIPS_BELOW_ARMS`]).
/// An ankle-length robe put the crotch's hips 0.29 of the height below the arms'.
const HIPS_FAR_BELOW_ARMS: f64 = 0.125;

/// The top of the gap between the legs ([`leg_split_height`]) from 0.02 of height below the
/// median silhouette's lowest point `bottom` up to 0.1 above it.
fn crotch_split(scene: &Scene, bottom: f64, reach: f64) -> Option<f64> {
    let height = scene.height;
    leg_split_height(
        scene.mesh,
        &scene.frame,
        scene.centre,
        bottom - 0.02 * height,
        bottom + 0.1 * height,
        0.001 * height,
        reach,
    )
}

/// The hips' height when the crotch shows: `fraction` ([`RefineOptions::hip_above_crotch`]) of
/// the way from the crotch at height `crotch` up to the shoulders (refined, else rough). The
/// pelvis belongs to the trunk, so its height above the crotch scales with the trunk rather
/// than with the stature: a short-legged cartoon's legs take little of its height, and a
/// fraction of the height had put its hips 2 % of its height too high. `None` without
/// shoulders above the crotch.
fn hips_above_crotch(
    rough: &Rough,
    found: &Found,
    frame: &BodyFrame,
    crotch: f64,
    fraction: f64,
) -> Option<f64> {
    let refined = match (
        found.get(&Canonical::Shoulder(Side::Left)),
        found.get(&Canonical::Shoulder(Side::Right)),
    ) {
        (Some(l), Some(r)) => Some((frame.h(*l) + frame.h(*r)) * 0.5),
        _ => None,
    };
    let shoulders = refined.or_else(|| rough.pair_height(frame, Canonical::Shoulder))?;
    (shoulders > crotch).then_some(crotch + fraction * (shoulders - crotch))
}

/// The trunk from the shoulder joints down to the hip joints is this many times as long as the
/// arm from shoulder to wrist: 0.288 / 0.332 of the height in Drillis and Contini's segment
/// proportions (shoulder at 0.818, hip at 0.530; upper arm 0.186, forearm 0.146), about 0.9.
pub(super) const TRUNK_PER_ARM: f64 = 0.9;

/// The hips' height from the proportions when clothing hides the crotch: the shoulders' height
/// less [`TRUNK_PER_ARM`] times the mean arm length (shoulder, elbow, wrist as refined, else
/// rough). `None` without a complete arm, or when that height is not between the rough knees
/// and the shoulders.
fn hips_from_arms(
    rough: &Rough,
    found: &Found,
    frame: &BodyFrame,
    knees: Option<f64>,
) -> Option<f64> {
    let at = |key: Canonical| found.get(&key).copied().or_else(|| rough.at(key));
    let arms: Vec<(f64, f64)> = Side::BOTH
        .iter()
        .filter_map(|&side| {
            let s = at(Canonical::Shoulder(side))?;
            let e = at(Canonical::Elbow(side))?;
            let w = at(Canonical::Wrist(side))?;
            Some((frame.h(s), s.distance(e) + e.distance(w)))
        })
        .collect();
    if arms.is_empty() {
        return None;
    }
    let n = arms.len() as f64;
    let shoulders = arms.iter().map(|a| a.0).sum::<f64>() / n;
    let arm = arms.iter().map(|a| a.1).sum::<f64>() / n;
    let h = shoulders - TRUNK_PER_ARM * arm;
    (h < shoulders && knees.is_none_or(|k| h > k)).then_some(h)
}

/// How near (fraction of the height) a refined joint's mirror image across the median plane
/// must lie to its partner's accepted refined place for the joint to be accepted however far
/// it moved from its rough place: the two sides, found independently on the surface, agree,
/// so the rough one was wrong (a fit that put one elbow a third of the arm inward).
const MIRROR_AGREEMENT: f64 = 0.02;

/// The refined positions that stay near the rough ones, as carry targets (every refined key's
/// joint, at its rough position unless accepted), and the accepted moves. A refined joint far
/// from its rough place is accepted when it mirrors its partner's accepted refined place
/// across the median plane (within [`MIRROR_AGREEMENT`]), and the pelvis (placed between the
/// refined hips) when both hips are accepted. Joints that are not refined stay where they were
/// (not carried by their neighbours).
fn accepted(
    rough: &Rough,
    found: &Found,
    scene: &Scene,
    warnings: &mut Vec<RefineWarning>,
) -> (BTreeMap<JointId, DVec3>, BTreeMap<String, (DVec3, DVec3)>) {
    let (frame, options) = (&scene.frame, scene.options);
    let height = frame.height();
    let mut targets: BTreeMap<JointId, DVec3> = REFINED
        .iter()
        .filter_map(|key| rough.id(*key))
        .map(|id| (id, rough.skeleton.joint(id).position))
        .collect();
    let mut moved = BTreeMap::new();
    // The refined places near their rough ones, before any partner is consulted.
    let near = |key: Canonical| {
        let (id, &to) = (rough.id(key)?, found.get(&key)?);
        let from = rough.skeleton.joint(id).position;
        (to.is_finite() && shift(rough, frame, key, from, to) <= options.max_shift * height)
            .then_some(to)
    };
    let mirrors_partner = |key: Canonical, to: DVec3| {
        let mirrored = mirror(to, scene.centre, frame.left);
        key.mirrored()
            .filter(|p| !options.keep.iter().any(|k| k == p.as_str()))
            .and_then(near)
            .is_some_and(|other| mirrored.distance(other) <= MIRROR_AGREEMENT * height)
    };
    // The refined pelvis lies between the refined hips: when both hips are accepted, so is
    // the pelvis, however far the rough one lay (a long coat's labels put it in the coat's
    // back, 16 cm behind the body).
    let hips_accepted = Side::BOTH
        .iter()
        .all(|&side| near(Canonical::Hip(side)).is_some());
    for key in REFINED {
        if options.keep.iter().any(|k| k == key.as_str()) {
            continue;
        }
        let (Some(id), Some(&to)) = (rough.id(key), found.get(&key)) else {
            if rough.id(key).is_some() && !warnings.iter().any(|w| w.keys().contains(&key)) {
                warnings.push(RefineWarning::Kept(key));
            }
            continue;
        };
        let from = rough.skeleton.joint(id).position;
        if !to.is_finite()
            || (shift(rough, frame, key, from, to) > options.max_shift * height
                && !mirrors_partner(key, to)
                && !(key == Canonical::Pelvis && hips_accepted))
        {
            warnings.push(RefineWarning::TooFar {
                key,
                distance: from.distance(to),
            });
            continue;
        }
        targets.insert(id, to);
        moved.insert(key.to_string(), (from, to));
    }
    (targets, moved)
}

/// How far a refined joint moved from its rough position, for the [`RefineOptions::max_shift`]
/// test. The head counts only its move across the body while it stays above the rough
/// shoulders (no head reaches below them): the fit places it by template ratios along the head
/// part, the slices at the neck's top, and a big or hatted head puts the two far apart along
/// the same axis (a cartoon's head sitting on its trunk ends below the rough neck). Hips and pelvis likewise while they stay between the rough knees and
/// shoulders, and knees between the rough ankles and shoulders: the rough ones sit where the
/// leg labels begin, which a skirt, a coat or a backpack moves up or down the trunk, and the
/// knee follows the hip. An elbow counts only its move off the rough shoulder-wrist line while
/// it stays in the middle of it ([`ELBOW_SLIDE`]).
fn shift(rough: &Rough, frame: &BodyFrame, key: Canonical, from: DVec3, to: DVec3) -> f64 {
    let across = |d: DVec3| (d - frame.up * d.dot(frame.up)).length();
    let shoulders = rough.pair_height(frame, Canonical::Shoulder);
    match (
        key,
        shoulders.or_else(|| rough.at(Canonical::Neck).map(|n| frame.h(n))),
    ) {
        (Canonical::Head, Some(floor)) if (floor..=frame.top).contains(&frame.h(to)) => {
            across(to - from)
        }
        (Canonical::Hip(_) | Canonical::Pelvis | Canonical::Knee(_), _) => {
            let below = match key {
                Canonical::Knee(_) => Canonical::Ankle,
                _ => Canonical::Knee,
            };
            let floor = rough.pair_height(frame, below);
            match (floor, shoulders) {
                (Some(k), Some(s)) if (k..s).contains(&frame.h(to)) => across(to - from),
                _ => from.distance(to),
            }
        }
        (Canonical::Elbow(side), _) => {
            match (
                rough.at(Canonical::Shoulder(side)),
                rough.at(Canonical::Wrist(side)),
            ) {
                (Some(s), Some(w)) if (s - w).length() > 0.0 => {
                    let axis = (w - s).normalize();
                    let t = (to - s).dot(axis) / s.distance(w);
                    let d = to - from;
                    if (ELBOW_SLIDE.0..=ELBOW_SLIDE.1).contains(&t) {
                        (d - axis * d.dot(axis)).length()
                    } else {
                        d.length()
                    }
                }
                _ => from.distance(to),
            }
        }
        _ => from.distance(to),
    }
}

/// The part of the rough shoulder-to-wrist line (as fractions from the shoulder) along which a
/// refined elbow may slide however far from its rough place: the fit spaces the elbow by
/// template ratios and the path's bends, which a straight arm lacks and a jointed figure's
/// seams fake, while the slices find the crease; an elbow outside the middle of the arm or
/// off its line is still a misreading.
const ELBOW_SLIDE: (f64, f64) = (0.3, 0.7);

/// `mesh` split at edge midpoints until its mean edge is at most `max_edge` (at most three
/// rounds), or `None` when it already is: plane and sphere slices cut triangles by their
/// corners' sides, so a long triangle crossing a small sphere with all corners outside would be
/// missed.
fn fine_enough(mesh: &Mesh, max_edge: f64) -> Option<Mesh> {
    let mean_edge = |m: &Mesh| {
        let total: f64 = (0..m.triangles.len())
            .map(|t| {
                let [a, b, c] = m.corners(t);
                a.distance(b) + b.distance(c) + c.distance(a)
            })
            .sum();
        total / (3 * m.triangles.len().max(1)) as f64
    };
    let mut out: Option<Mesh> = None;
    for _ in 0..3 {
        let current = out.as_ref().unwrap_or(mesh);
        if mean_edge(current) <= max_edge {
            break;
        }
        out = Some(current.subdivided());
    }
    out
}

/// `p` moved across the body into the plane through `centre` with normal `frame.forward`.
pub(super) fn frame_point(frame: &BodyFrame, centre: DVec3, p: DVec3) -> DVec3 {
    p - frame.forward * (p - centre).dot(frame.forward)
}

/// The joints strictly between pelvis and neck on the skeleton's chain, placed on the spine
/// polyline from `L5` up to `C7` at their original fractions of the chain's length.
fn place_spine_joints(rough: &Rough, spine: &Spine) -> Vec<(JointId, DVec3)> {
    let skeleton = rough.skeleton;
    let (Some(pelvis), Some(neck)) = (rough.id(Canonical::Pelvis), rough.id(Canonical::Neck))
    else {
        return Vec::new();
    };
    let mut chain = Vec::new();
    let mut k = skeleton.joint(neck).parent;
    while let Some(p) = k {
        if p == pelvis {
            break;
        }
        chain.push(p);
        k = skeleton.joint(p).parent;
    }
    if k != Some(pelvis) || chain.is_empty() {
        return Vec::new();
    }
    chain.reverse(); // pelvis side first
    let path: Vec<DVec3> = std::iter::once(pelvis)
        .chain(chain.iter().copied())
        .chain(std::iter::once(neck))
        .map(|id| skeleton.joint(id).position)
        .collect();
    let total: f64 = path.windows(2).map(|w| w[0].distance(w[1])).sum();
    let curve: Vec<DVec3> = [
        "L5", "L4", "L3", "L2", "L1", "T12", "T11", "T10", "T9", "T8", "T7", "T6", "T5", "T4",
        "T3", "T2", "T1", "C7",
    ]
    .iter()
    .filter_map(|n| spine.joint(n))
    .collect();
    if total <= 0.0 || curve.len() < 2 {
        return Vec::new();
    }
    let lengths: Vec<f64> = curve.windows(2).map(|w| w[0].distance(w[1])).collect();
    let curve_total: f64 = lengths.iter().sum();
    let mut along = 0.0;
    let mut out = Vec::new();
    for (i, id) in chain.iter().enumerate() {
        along += path[i].distance(path[i + 1]);
        let mut s = along / total * curve_total;
        let mut p = curve[curve.len() - 1];
        for (w, l) in curve.windows(2).zip(&lengths) {
            if s <= *l {
                p = w[0].lerp(w[1], if *l > 0.0 { s / l } else { 0.0 });
                break;
            }
            s -= l;
        }
        out.push((*id, p));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> BodyFrame {
        let mesh = Mesh::cuboid(DVec3::new(-0.2, 0.0, -0.2), DVec3::new(0.2, 1.8, 0.2));
        BodyFrame::new(&mesh, DVec3::Y, DVec3::Z).unwrap()
    }

    /// A neck found far behind the head on a back the head's shell or a collar pushed back
    /// (the platformer character's leaned 54°) comes forward until the cervical column leans
    /// [`NECK_MAX_LEAN_DEGREES`], at its own height; one leaning less stays.
    #[test]
    fn a_neck_far_behind_the_head_comes_forward_to_the_cervical_lean() {
        let frame = frame();
        let head = DVec3::new(0.0, 1.6, 0.05);
        let mut found = Found::new();
        found.insert(Canonical::Head, head);
        found.insert(Canonical::Neck, DVec3::new(0.0, 1.5, -0.15));
        neck_under_head(&frame, &mut found);
        let neck = found[&Canonical::Neck];
        let lean = ((head.z - neck.z) / (head.y - neck.y)).atan().to_degrees();
        assert!((lean - NECK_MAX_LEAN_DEGREES).abs() < 1e-9, "lean {lean}");
        assert!((neck.y - 1.5).abs() < 1e-12 && neck.x == 0.0, "{neck}");

        let upright = DVec3::new(0.0, 1.5, 0.02);
        found.insert(Canonical::Neck, upright);
        neck_under_head(&frame, &mut found);
        assert_eq!(found[&Canonical::Neck], upright);

        // A neck above its head (no rise) is left alone.
        let above = DVec3::new(0.0, 1.7, -0.3);
        found.insert(Canonical::Neck, above);
        neck_under_head(&frame, &mut found);
        assert_eq!(found[&Canonical::Neck], above);
    }
}

//! The anatomical rig: mesh → labelled body parts → template fit → skin (dissertation ch.7-8).

use super::Laps;
use crate::anatomy::{
    hanging_arms, keep_arm_skins_apart, label_pieces, label_vertices_by_bones,
    label_with_overrides, separate_arms, AnatomyWarning, FigureClass, Forward, HangingArms, Label,
    LabelOptions, LabelPipelineOptions, Labelling, Overrides, Up,
};
use crate::digits::{fit_digits, DigitOptions};
use crate::distance::{edt, DistanceMap};
use crate::fit::{fit_input, fit_with_probe, Fit, FitError, FitInput, FitInputOptions, FitOptions};
use crate::general::{control_skeleton, GeneralOptions};
use crate::medial::{dms, MedialOptions, MedialSurface};
use crate::mesh::Mesh;
use crate::paths::{path_tree, PathOptions};
use crate::refine::{
    pull_inside, refine_fit, symmetrize, NoFullSpine, RefineError, RefineOptions, RefineWarning,
    SpineDetail,
};
use crate::skeleton::canonical::CanonicalJoints;
use crate::skeleton::{Canonical, JointId, Side};
use crate::skin::{digit_weights, skin_from_bones, Skin, SkinOptions};
use crate::template::{ExpectedPart, Preset, Template};
use crate::voxel::{boundary_mesh, voxelize_figure, Solid, VoxelOptions, VoxelSize};
use crate::warning::Warning;

pub use super::warning::{RigWarning, MEDIAL_FALLBACK};

/// Which template [`rig`] fits.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum TemplateChoice {
    /// Chosen from the labelling: human-like → `humanoid`; animal-like → `winged` when wings
    /// were labelled, else `quadruped`; unknown → by the limbs found (arms → `humanoid`, wings
    /// → `winged`, otherwise `quadruped`), with a warning.
    #[default]
    Auto,
    /// A built-in template by name (`humanoid`, `quadruped`, `winged`).
    Builtin(String),
    /// A template loaded by the caller (e.g. [`Template::load`]).
    Custom(Box<Template>),
}

/// All parameters of [`rig`], one options struct per stage, in pipeline order.
#[derive(Debug, Clone, PartialEq)]
pub struct RigOptions {
    /// Voxelization (default voxel size 0.01 of the longest side, Table 5.2).
    pub voxel: VoxelOptions,
    /// Discrete medial surface.
    pub medial: MedialOptions,
    /// Heart sampling for the level graph, and the path tree of the general fallback.
    pub paths: PathOptions,
    /// Level graph, labelling rules and orientation (`up`, `forward`; default up found from
    /// the figure, +Z forward).
    pub label: LabelOptions,
    /// User corrections of the labels (`skelfit label --labels`), applied before the fit.
    pub overrides: Option<Overrides>,
    /// The template. Default [`TemplateChoice::Auto`].
    pub template: TemplateChoice,
    /// How the labelled parts become the fit's paths.
    pub input: FitInputOptions,
    /// The fit (naming preset, geometric choices of 8.1-8.2).
    pub fit: FitOptions,
    /// Slicing-based refinement of humanoid joints after the fit (seed 004; on by default,
    /// `in_rig: false` switches it off). Default: [`RefineOptions::default`].
    pub refine: RefineOptions,
    /// The hands' digits and the feet's toes at their own resolution, after the refinement
    /// (issue 25).
    pub digits: DigitOptions,
    /// Regions of influence and weights (8.3).
    pub skin: SkinOptions,
    /// The general control skeleton (ch. 5) that a figure no template fits gets instead
    /// ([`no_template_fits`]; only with [`TemplateChoice::Auto`]).
    pub general: GeneralOptions,
}

impl RigOptions {
    /// Checks the options of every stage (voxel, medial, paths, labelling, the fit's input,
    /// the fit, the refinement, the skin, the general fallback) and collects every problem.
    ///
    /// # Errors
    /// The stage's error when one stage's options are invalid; [`crate::Error::Options`] with
    /// each stage's error when several are.
    pub fn validate(&self) -> crate::Result<()> {
        let mut errors: Vec<crate::Error> = Vec::new();
        let mut check = |result: crate::Result<()>| errors.extend(result.err());
        check(self.voxel.validate().map_err(Into::into));
        check(self.medial.validate().map_err(Into::into));
        check(self.paths.validate().map_err(Into::into));
        check(self.label.validate().map_err(Into::into));
        check(
            self.input
                .validate()
                .map_err(|e| FitError::InvalidInputOptions(e).into()),
        );
        check(self.fit.validate().map_err(Into::into));
        check(
            self.refine
                .validate()
                .map_err(|e| RefineError::InvalidOptions(e).into()),
        );
        check(
            self.digits
                .validate()
                .map_err(|e| RefineError::InvalidOptions(e).into()),
        );
        check(self.skin.validate().map_err(Into::into));
        check(self.general.validate().map_err(Into::into));
        check(self.full_spine_conflicts().map_err(Into::into));
        match errors.len() {
            0 => Ok(()),
            1 => Err(errors.remove(0)),
            _ => Err(crate::Error::Options(errors)),
        }
    }
}

impl RigOptions {
    /// The full spine ([`SpineDetail::Full`]) is the refinement's and anatomical: refused with
    /// an engine preset (a fixed skeleton without vertebrae) or the refinement off. Part of
    /// [`Self::validate`].
    ///
    /// # Errors
    /// [`RefineError::FullSpineWithPreset`], [`RefineError::FullSpineWithoutRefinement`].
    pub fn full_spine_conflicts(&self) -> Result<(), RefineError> {
        if self.refine.spine != SpineDetail::Full {
            return Ok(());
        }
        if self.fit.preset != Preset::Anatomical {
            return Err(RefineError::FullSpineWithPreset {
                preset: self.fit.preset.file_stem().to_string(),
            });
        }
        if !self.refine.in_rig {
            return Err(RefineError::FullSpineWithoutRefinement);
        }
        Ok(())
    }

    /// The options of the labelling stages alone ([`crate::anatomy::label`]).
    pub fn label_pipeline(&self) -> LabelPipelineOptions {
        LabelPipelineOptions {
            voxel: self.voxel,
            medial: self.medial,
            paths: self.paths,
            label: self.label,
        }
    }
}

impl From<LabelPipelineOptions> for RigOptions {
    /// The labelling stages' options, every other stage's default.
    fn from(stages: LabelPipelineOptions) -> Self {
        Self {
            voxel: stages.voxel,
            medial: stages.medial,
            paths: stages.paths,
            label: stages.label,
            ..Default::default()
        }
    }
}

impl Default for RigOptions {
    fn default() -> Self {
        Self {
            voxel: VoxelOptions::default(),
            medial: MedialOptions::default(),
            paths: PathOptions::default(),
            label: LabelOptions::default(),
            overrides: None,
            template: TemplateChoice::Auto,
            input: FitInputOptions::default(),
            fit: FitOptions::default(),
            refine: RefineOptions::default(),
            digits: DigitOptions::default(),
            skin: SkinOptions::default(),
            general: GeneralOptions::default(),
        }
    }
}

/// An anatomical rig: the fitted skeleton, the skin, and the pieces it was made from.
#[derive(Debug, Clone)]
pub struct Rig {
    /// The fitted skeleton with its canonical map and fit warnings.
    pub fit: Fit,
    /// Per-vertex weights to the fitted skeleton.
    pub skin: Skin,
    /// The body-part labelling.
    pub labelling: Labelling,
    /// The paths the template was fitted to.
    pub input: FitInput,
    /// The voxelized figure.
    pub solid: Solid,
    /// Its exact distance map.
    pub distance: DistanceMap,
    /// Wall-clock time per stage, `(stage, milliseconds)`, in stage order.
    pub timings: Vec<(String, f64)>,
    /// Warnings of every stage (labelling, paths, fit, refinement, skin), in stage order.
    pub warnings: Vec<Warning>,
    /// Body parts the template expects that the labelling did not find (`arm R`, `head`, ...;
    /// see [`missing_parts`]): the rig has no joints for them.
    pub missing: Vec<String>,
}

impl Rig {
    /// Its labelling with the per-mesh-vertex labels following the fitted bones, each vertex
    /// the part of its nearest bone ([`label_vertices_by_bones`]); `mesh` is the mesh it was
    /// rigged from. A rig on the general skeleton (no template fits) has no body parts on its
    /// joints and keeps the labelling's own per-vertex labels.
    pub fn into_bone_labels(self, mesh: &Mesh) -> Labelling {
        self.vertex_labels(mesh, false)
    }

    /// Like [`Rig::into_bone_labels`], but each vertex takes the part whose joints carry most
    /// of its skin weight (its nearest bone's where no weight lies on a joint with a part): the
    /// part of the bones that move it.
    pub fn into_skin_labels(self, mesh: &Mesh) -> Labelling {
        self.vertex_labels(mesh, true)
    }

    /// The labelling with per-vertex labels by skin weight (`by_weight`) or nearest bone; see
    /// [`Rig::into_skin_labels`] and [`Rig::into_bone_labels`].
    pub fn vertex_labels(&self, mesh: &Mesh, by_weight: bool) -> Labelling {
        let mut labelling = self.labelling.clone();
        if self.fit.template == GENERAL {
            return labelling;
        }
        label_vertices_by_bones(
            &mut labelling,
            mesh,
            &self.fit.skeleton,
            &self.fit.canonical,
            by_weight.then_some(self.skin.weights.as_slice()),
        );
        labelling
    }
}

/// Rigs `mesh` with an anatomical control skeleton (dissertation ch.7-8): voxelize, exact
/// distance map, medial surface, body-part labels, centralised paths between the labelled
/// parts ([`fit_input`]), the template fit ([`fit_with_probe`], dorsal rays through the
/// voxels), the refinement the template declares ([`refine_fit`]: the humanoid's slicing, seed 004), and skin weights from the fitted bones ([`skin_from_bones`]).
///
/// Missing body parts are warnings (the fit leaves their joints out); a figure the template does
/// not suit gets the template's best effort and the warnings say what is missing.
///
/// # Errors
/// Invalid options of any stage (checked before any work), an unknown built-in template, a mesh
/// that does not voxelize, an empty medial surface, a bad override, or a skeleton that no bone
/// of which passes inside the figure.
pub fn rig(mesh: &Mesh, options: &RigOptions) -> crate::Result<Rig> {
    let chosen = checked_template(options)?;
    let mut timings = Vec::new();
    let mut lap = Laps::start();

    // Whether the mesh is one closed shell (which surface the refinement slices,
    // [`refine_surface`]) is asked on the other core while the mesh voxelizes.
    let (solid, one_shell) = rayon::join(
        || voxelize_figure(mesh, &options.voxel),
        || options.refine.in_rig && mesh.is_one_closed_shell(),
    );
    let solid = solid?;
    lap.lap("voxelize", &mut timings);
    let distance = edt(&solid);
    lap.lap("distance", &mut timings);
    let surface = dms(&distance, &options.medial)?;
    lap.lap("medial", &mut timings);
    let labelling = label_pieces(
        mesh,
        &solid,
        &surface,
        &options.paths,
        &options.label,
        options.overrides.as_ref(),
    )?;
    let (solid, distance, surface, labelling, hanging) =
        match separated_arms(mesh, &solid, &labelling, options) {
            Some((solid, distance, surface, labelling, arms)) => {
                (solid, distance, surface, labelling, Some(arms))
            }
            None => (solid, distance, surface, labelling, None),
        };
    lap.lap("label", &mut timings);
    let resolved = resolve_template(chosen, &labelling)?;
    let (input, mut path_warnings) = fit_input(
        &labelling,
        &surface,
        &solid,
        &distance,
        resolved.template(),
        &options.input,
    )?;
    lap.lap("paths", &mut timings);
    let mut warnings = labelling.warnings.clone();
    warnings.extend(path_warnings.drain(..).map(Warning::FitInput));
    let template = match resolved {
        Resolved::Template(t, note) => {
            warnings.extend(note.map(Warning::Rig));
            *t
        }
        Resolved::General(reason) => {
            warnings.push(RigWarning::NoTemplateFits { reason }.into());
            return general_fallback(
                mesh, options, labelling, input, solid, distance, &surface, timings, warnings,
            );
        }
    };
    // Anatomical names through the refinement; the preset's names go on last, from the final
    // canonical keys (the refinement may move `spine` and `chest` to other joints).
    let anatomical = FitOptions {
        preset: Preset::Anatomical,
        ..options.fit.clone()
    };
    let mut fit = fit_with_probe(&input, &template, &anatomical, Some(&solid))?;
    warnings.extend(fit.warnings.iter().cloned().map(Warning::Fit));
    lap.lap("fit", &mut timings);
    // Held props and small sheets left out of the voxels are left out of the slicing too: a
    // body that is one closed shell but for the sword in its hand, or its hair cards, is
    // sliced itself.
    let left_out = !solid.report.props.is_empty() || solid.report.sheets > 0;
    let body = (!one_shell && options.refine.in_rig && left_out)
        .then(|| without_props(mesh, &solid.report))
        .filter(Mesh::is_one_closed_shell);
    if refine_stage(
        body.as_ref().unwrap_or(mesh),
        one_shell || body.is_some(),
        &solid,
        &labelling,
        &template,
        &input,
        &options.refine,
        &mut fit,
        &mut warnings,
    ) {
        lap.lap("refine", &mut timings);
    }
    if options.refine.symmetry {
        let head = fit.canonical.get(Canonical::Head.as_str()).copied();
        let left = input.up.cross(input.forward);
        let symmetry = symmetrize(&fit.skeleton, head, mesh, &solid, left, input.up);
        if symmetry.applied {
            fit.skeleton = symmetry.skeleton;
        }
        lap.lap("symmetry", &mut timings);
    }
    let digits = fit_digits(
        mesh,
        &template,
        &mut fit,
        input.up,
        input.forward,
        &options.digits,
    );
    warnings.extend(digits.into_iter().map(Warning::Digits));
    lap.lap("digits", &mut timings);
    fit.realign_frames();
    let before = fit.warnings.len();
    fit.name_joints(options.fit.preset, input.up, input.forward)?;
    warnings.extend(fit.warnings[before..].iter().cloned().map(Warning::Fit));
    let mut skin = skin_from_bones(mesh, &fit.skeleton, &solid, &distance, &options.skin)?;
    if options.digits.enabled {
        // Fingers are thinner than the voxels: their weights again over the hand's surface.
        let roots = digit_roots(&fit);
        skin.engine = digit_weights(mesh, &fit.skeleton, &roots, &mut skin.weights);
        // The hand's digit weights may reach a held prop's grip: bound again to it.
        if crate::skin::bind_props(mesh, &solid, &solid.report.props, &mut skin.weights) > 0 {
            skin.engine = crate::skin::engine_weights(&skin.weights).0;
        }
    }
    if let Some(arms) = &hanging {
        // Arms cut apart from the sides: their skin and the flank's keep apart in the weights.
        let skeleton = &fit.skeleton;
        let mask = |key: &str| {
            let mut below = vec![false; skeleton.len()];
            if let Some(&root) = fit.canonical.get(key) {
                for j in 0..skeleton.len() {
                    below[j] = j == root.0
                        || skeleton
                            .joint(JointId(j))
                            .parent
                            .is_some_and(|p| below[p.0]);
                }
            }
            below
        };
        let (left, right) = (mask("shoulder_L"), mask("shoulder_R"));
        let skins = arms.skins(mesh);
        if keep_arm_skins_apart(mesh, &skins, [&left, &right], &mut skin.weights) > 0 {
            skin.engine = crate::skin::engine_weights(&skin.weights).0;
        }
    }
    warnings.extend(skin.warnings.iter().cloned().map(Warning::Skin));
    lap.lap("skin", &mut timings);
    let missing = missing_parts(&template, &labelling);
    Ok(Rig {
        missing,
        fit,
        skin,
        labelling,
        input,
        solid,
        distance,
        timings,
        warnings,
    })
}

/// Voxels across an arm hanging against the body that [`separated_arms`] cuts it out of.
const ARM_DIAMETER_VOXELS: f64 = 6.0;

/// ...with voxels at most this much finer than the rig's own (about 15 times the voxels).
const MIN_ARMS_VOXEL: f64 = 0.4;

/// A figure whose labelling found no arms but a head and legs, with arms hanging against its
/// sides ([`hanging_arms`]): the solid with the arms cut apart from the body
/// ([`separate_arms`]), its distance map, medial surface and labelling (in the frame found the
/// first time, with its orientation warnings and [`AnatomyWarning::ArmsSeparated`]), when the
/// new labelling finds both arms; `None` otherwise, or when a stage of the second pass fails
/// (the first labelling stands).
fn separated_arms(
    mesh: &Mesh,
    solid: &Solid,
    labelling: &Labelling,
    options: &RigOptions,
) -> Option<(Solid, DistanceMap, MedialSurface, Labelling, HangingArms)> {
    if options.overrides.is_some() {
        return None;
    }
    let arms = hanging_arms(mesh, labelling)?;
    // The arms are cut out of a grid fine enough for them to keep a medial line: at least
    // ARM_DIAMETER_VOXELS across (the default grid gives an adult's arm about 3).
    let voxel = solid.grid.voxel_size;
    let fine = (2.0 * arms.radius() / ARM_DIAMETER_VOXELS).max(MIN_ARMS_VOXEL * voxel);
    let finer = (fine < voxel)
        .then(|| {
            let size = VoxelOptions {
                size: VoxelSize::Absolute(fine),
                ..options.voxel
            };
            voxelize_figure(mesh, &size).ok()
        })
        .flatten();
    let (cut, voxels) = separate_arms(finer.as_ref().unwrap_or(solid), &arms);
    if voxels == 0 {
        return None;
    }
    let distance = edt(&cut);
    let surface = dms(&distance, &options.medial).ok()?;
    let framed = LabelOptions {
        up: Up::Direction(labelling.frame.up),
        forward: Forward::Direction(labelling.frame.forward),
        ..options.label
    };
    let mut again = label_pieces(mesh, &cut, &surface, &options.paths, &framed, None).ok()?;
    if again.count(Label::Arm) != 2 {
        return None;
    }
    again.up_found = labelling.up_found.clone();
    again.forward_found = labelling.forward_found.clone();
    let orientation = labelling.warnings.iter().filter(|w| {
        matches!(
            w,
            Warning::Anatomy(
                AnatomyWarning::UpFound { .. } | AnatomyWarning::ForwardGuessed { .. }
            )
        )
    });
    let mut warnings: Vec<Warning> = orientation.cloned().collect();
    warnings.push(
        AnatomyWarning::ArmsSeparated {
            levels: arms.levels(),
            voxels,
        }
        .into(),
    );
    warnings.append(&mut again.warnings);
    again.warnings = warnings;
    Some((cut, distance, surface, again, arms))
}

/// The refinement the template declares ([`refine_fit`]; `options.in_rig: false` skips it):
/// `fit` takes the refined skeleton and canonical map, `warnings` the refinement's warnings
/// (or its failure). Returns whether it ran.
#[allow(clippy::too_many_arguments)]
fn refine_stage(
    mesh: &Mesh,
    one_shell: bool,
    solid: &Solid,
    labelling: &Labelling,
    template: &Template,
    input: &FitInput,
    options: &RefineOptions,
    fit: &mut Fit,
    warnings: &mut Vec<Warning>,
) -> bool {
    if !options.in_rig {
        return false;
    }
    let joined = template
        .refinement
        .is_some()
        .then(|| refine_surface(one_shell, solid, labelling, options))
        .flatten();
    let surface = joined.as_ref().unwrap_or(mesh);
    let Some(refined) = refine_fit(
        surface,
        mesh,
        fit,
        template,
        input.up,
        input.forward,
        options,
    ) else {
        if options.spine == SpineDetail::Full {
            warnings.push(Warning::Refine(RefineWarning::CoarseSpineKept(
                NoFullSpine::NotRefined,
            )));
        }
        return false;
    };
    match refined {
        Ok(refined) => {
            fit.skeleton = refined.skeleton;
            fit.canonical = refined.canonical;
            warnings.extend(refined.warnings.iter().cloned().map(Warning::Refine));
            if options.spine == SpineDetail::Full {
                let (skeleton, canonical) = (&mut fit.skeleton, &fit.canonical);
                let moved = pull_inside(skeleton, canonical, mesh, solid, input.forward);
                if !moved.is_empty() {
                    warnings.push(Warning::Refine(RefineWarning::VertebraeMovedInside(moved)));
                }
            }
        }
        Err(e) => warnings.push(
            RigWarning::RefineFailed {
                error: e.to_string(),
            }
            .into(),
        ),
    }
    true
}

/// `mesh` without the triangles of the held props ([`crate::voxel::Prop`]) and the small
/// sheets ([`crate::voxel::VoxelReport::sheets`]) the voxels left out.
fn without_props(mesh: &Mesh, report: &crate::voxel::VoxelReport) -> Mesh {
    let mut prop = vec![false; mesh.positions.len()];
    let props = report.props.iter().flat_map(|p| &p.vertices);
    for v in props.chain(&report.sheet_vertices) {
        if let Some(f) = prop.get_mut(*v as usize) {
            *f = true;
        }
    }
    Mesh {
        positions: mesh.positions.clone(),
        triangles: mesh
            .triangles
            .iter()
            .filter(|t| !t.iter().any(|&v| prop[v as usize]))
            .copied()
            .collect(),
    }
}

/// The surface the slicing refinement cuts: the input itself when it is one closed shell
/// (`one_shell`, [`Mesh::is_one_closed_shell`]) with no tail, else the smoothed boundary of
/// the joined voxel solid ([`boundary_mesh`]). Slices through a figure of many shells (head,
/// hands, eyes, clothes over a body) are many loops per plane, and the refinement's loop for a
/// body part would be one piece of clothing; the joined solid has one loop per part. A tail
/// ([`Label::Tail`], a humanoid's: a lizardfolk's, a cat person's) is taken out of that solid
/// first (its interior voxels, [`Labelling::interior_parts`]): in the median plane it
/// continues the torso's outline down past the crotch, and the hips followed it 9 % of the
/// height low.
fn refine_surface(
    one_shell: bool,
    solid: &Solid,
    labelling: &Labelling,
    options: &RefineOptions,
) -> Option<Mesh> {
    let tails: Vec<u32> = labelling
        .find(Label::Tail)
        .into_iter()
        .map(|p| p as u32)
        .collect();
    let cut = !tails.is_empty()
        && labelling.grid == solid.grid
        && labelling.interior_parts.len() == solid.inside.len();
    if cut {
        let mut body = solid.clone();
        for (inside, part) in body.inside.iter_mut().zip(&labelling.interior_parts) {
            if tails.contains(part) {
                *inside = false;
            }
        }
        if body.inside.iter().any(|&b| b) {
            return Some(boundary_mesh(&body, options.joined_smoothing));
        }
    }
    (!one_shell).then(|| boundary_mesh(solid, options.joined_smoothing))
}

/// The body parts `template` expects ([`Template::expects`], the `expects` list of its
/// header) that `labelling` lacks, in the template's order, each paired part with its side
/// (`head`, `arm R`, `fore leg L`, ...). Empty for a template that declares none.
pub fn missing_parts(template: &Template, labelling: &Labelling) -> Vec<String> {
    use crate::anatomy::{LimbPair, Side};
    let has = |label: Label, side: Option<Side>, pair: Option<LimbPair>| {
        labelling.parts.iter().any(|p| {
            p.label == label
                && (side.is_none() || p.side == side)
                && (pair.is_none() || p.limb_pair == pair)
        })
    };
    let mut missing = Vec::new();
    for &part in &template.expects {
        let (label, pair, name) = match part {
            ExpectedPart::Head => {
                if !has(Label::Head, None, None) {
                    missing.push(Label::Head.name().to_string());
                }
                continue;
            }
            ExpectedPart::Arms => (Label::Arm, None, "arm"),
            ExpectedPart::Legs => (Label::Leg, None, "leg"),
            ExpectedPart::ForeLegs => (Label::Leg, Some(LimbPair::Fore), "fore leg"),
            ExpectedPart::HindLegs => (Label::Leg, Some(LimbPair::Hind), "hind leg"),
            ExpectedPart::Wings => (Label::Wing, None, "wing"),
        };
        for side in Side::BOTH {
            if !has(label, Some(side), pair) {
                missing.push(format!("{name} {}", side.letter()));
            }
        }
    }
    missing
}

/// What [`rig`] fits to a labelled figure.
enum Resolved {
    /// A template, with a note when the automatic choice was unsure ([`auto_template`]).
    Template(Box<Template>, Option<RigWarning>),
    /// The general control skeleton, because no template fits ([`no_template_fits`]: why).
    General(String),
}

impl Resolved {
    fn template(&self) -> Option<&Template> {
        match self {
            Resolved::Template(t, _) => Some(t.as_ref()),
            Resolved::General(_) => None,
        }
    }
}

/// The chosen template, else the one the labelling suits, else the general skeleton.
///
/// # Errors
/// An unknown built-in template.
fn resolve_template(chosen: Option<Template>, labelling: &Labelling) -> crate::Result<Resolved> {
    if let Some(t) = chosen {
        return Ok(Resolved::Template(Box::new(t), None));
    }
    if let Some(reason) = no_template_fits(labelling) {
        return Ok(Resolved::General(reason));
    }
    let (name, note) = auto_template(labelling);
    let template = Template::builtin(name)?;
    if let Some(reason) = more_limbs_than(labelling, &template) {
        return Ok(Resolved::General(reason));
    }
    Ok(Resolved::Template(Box::new(template), note))
}

/// Why `template` does not fit the labelled figure because the figure has more limbs (legs,
/// arms, wings) than the template has places for (two per limb group), or `None`: forcing it
/// in drops the extra limbs and fits the rest where they do not belong (a wasp's six legs and
/// wings labelled as one leg and four arms, put into a quadruped's two leg pairs).
pub fn more_limbs_than(labelling: &Labelling, template: &Template) -> Option<String> {
    let limbs =
        labelling.count(Label::Leg) + labelling.count(Label::Arm) + labelling.count(Label::Wing);
    let places = 2 * template.limbs.len();
    (limbs > places).then(|| {
        format!(
            "the figure has {limbs} limbs and the {} template places {places}",
            template.name
        )
    })
}

/// Validates every stage's options and resolves the chosen template (`None` for
/// [`TemplateChoice::Auto`]), before any work.
fn checked_template(options: &RigOptions) -> crate::Result<Option<Template>> {
    options.validate()?;
    Ok(match &options.template {
        TemplateChoice::Builtin(name) => Some(Template::builtin(name)?),
        TemplateChoice::Custom(t) => Some((**t).clone()),
        TemplateChoice::Auto => None,
    })
}

/// Body-part labels whose per-mesh-vertex labels follow the fitted anatomical skeleton: [`rig`]
/// (refinement and skin included), then [`label_vertices_by_bones`] on its labelling with the
/// fitted skeleton, so each vertex takes the part of its nearest bone. The level-graph and
/// voxel labels are the medial surface's, as with [`crate::anatomy::label`].
///
/// When the rig fails after the labelling succeeded (no bone inside the figure, a skin that
/// cannot be bound), the medial surface's per-vertex labels are returned with a warning saying
/// so.
///
/// # Errors
/// Invalid options of any stage or an unknown built-in template (checked before any work), and
/// as [`crate::anatomy::label_with_overrides`] (a mesh that does not voxelize, an empty medial
/// surface, a bad override).
pub fn label_by_bones(mesh: &Mesh, options: &RigOptions) -> crate::Result<Labelling> {
    checked_template(options)?;
    bones_or_medial(mesh, options, rig(mesh, options), false)
}

/// The joints the digits of each hand and foot hang from: below each wrist and ankle, the
/// first joint with more than one child (the wrist of a human hand; an animal's metapodial
/// joint where its hoof or paw shows separate digits). A foot with a single digit chain has
/// none.
fn digit_roots(fit: &Fit) -> Vec<JointId> {
    let sk = &fit.skeleton;
    Side::BOTH
        .iter()
        .flat_map(|&side| [Canonical::Wrist(side), Canonical::Ankle(side)])
        .filter_map(|key| {
            let mut j = fit.canonical.joint_of(key)?;
            loop {
                match sk.children(j).as_slice() {
                    [] => return None,
                    [only] => j = *only,
                    _ => return Some(j),
                }
            }
        })
        .collect()
}

/// [`rig`], then the labels of [`Rig::into_skin_labels`]: each vertex the part of the bones
/// carrying most of its skin weight. The medial labels with a warning when the rig fails, as
/// [`label_by_bones`].
///
/// # Errors
/// As [`label_by_bones`].
pub fn label_by_skin(mesh: &Mesh, options: &RigOptions) -> crate::Result<Labelling> {
    checked_template(options)?;
    bones_or_medial(mesh, options, rig(mesh, options), true)
}

/// The bone-following labels of a fitted `rigged` (by skin weight or nearest bone), or the
/// medial ones with a warning when the rig failed.
fn bones_or_medial(
    mesh: &Mesh,
    options: &RigOptions,
    rigged: crate::Result<Rig>,
    by_weight: bool,
) -> crate::Result<Labelling> {
    match rigged {
        Ok(r) => Ok(r.vertex_labels(mesh, by_weight)),
        Err(e) => {
            let mut labelling =
                label_with_overrides(mesh, &options.label_pipeline(), options.overrides.as_ref())?;
            labelling.warnings.push(
                RigWarning::MedialLabels {
                    error: e.to_string(),
                }
                .into(),
            );
            Ok(labelling)
        }
    }
}

/// The rest of [`rig`] for a figure no template fits: the general control skeleton (ch. 5) of
/// the medial surface's path tree, skinned to its bones.
#[allow(clippy::too_many_arguments)]
fn general_fallback(
    mesh: &Mesh,
    options: &RigOptions,
    labelling: Labelling,
    input: FitInput,
    solid: Solid,
    distance: DistanceMap,
    surface: &MedialSurface,
    mut timings: Vec<(String, f64)>,
    mut warnings: Vec<Warning>,
) -> crate::Result<Rig> {
    let mut lap = Laps::start();
    let tree = path_tree(surface, &options.paths)?;
    let general = control_skeleton(tree, &options.general)?;
    warnings.extend(general.warnings.iter().cloned());
    lap.lap("fit", &mut timings);
    let fit = Fit {
        skeleton: general.skeleton,
        canonical: Default::default(),
        warnings: Vec::new(),
        template: GENERAL.to_string(),
    };
    let skin = skin_from_bones(mesh, &fit.skeleton, &solid, &distance, &options.skin)?;
    warnings.extend(skin.warnings.iter().cloned().map(Warning::Skin));
    lap.lap("skin", &mut timings);
    Ok(Rig {
        missing: Vec::new(),
        fit,
        skin,
        labelling,
        input,
        solid,
        distance,
        timings,
        warnings,
    })
}

/// The template name of a rig that got the general control skeleton ([`no_template_fits`]).
pub const GENERAL: &str = "general";

/// Legs from which a figure is not vertebrate-like: three pairs (an insect, a spider).
const NON_VERTEBRATE_LEGS: usize = 6;

/// Why no built-in template fits the labelled figure, or `None` when one does. The templates
/// are vertebrate body plans (a head, a trunk and up to two limb pairs), so a figure without
/// any limb (a snake, a worm) or with three leg pairs or more (a spider, an insect) fits none of
/// them: forcing it into one drops or merges limbs.
pub fn no_template_fits(labelling: &Labelling) -> Option<String> {
    let limbs =
        labelling.count(Label::Leg) + labelling.count(Label::Arm) + labelling.count(Label::Wing);
    let legs = labelling.count(Label::Leg);
    if limbs == 0 {
        Some("the figure has no limbs (a vertebrate template needs legs, arms or wings)".into())
    } else if legs >= NON_VERTEBRATE_LEGS {
        Some(format!(
            "the figure has {legs} legs (a vertebrate template has at most two pairs)"
        ))
    } else {
        None
    }
}

/// The built-in template for a labelled figure and, when the figure class was unknown, a
/// warning saying what was chosen and why.
pub fn auto_template(labelling: &Labelling) -> (&'static str, Option<RigWarning>) {
    let wings = labelling.count(Label::Wing) > 0;
    match labelling.figure {
        FigureClass::HumanLike => ("humanoid", None),
        FigureClass::AnimalLike if wings => ("winged", None),
        FigureClass::AnimalLike => ("quadruped", None),
        FigureClass::Unknown => {
            let name = if labelling.count(Label::Arm) > 0 {
                "humanoid"
            } else if wings {
                "winged"
            } else {
                "quadruped"
            };
            (
                name,
                Some(RigWarning::UnknownFigureClass {
                    template: name,
                    trunk_angle: labelling.trunk_angle,
                }),
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anatomy::{label, AnatomyError};
    use crate::refine::refine;

    #[test]
    fn a_failed_rig_leaves_the_medial_labels_with_a_warning() {
        let mesh = Mesh::capsule(glam::DVec3::ZERO, 0.2, 1.0, 8, 24);
        let options = RigOptions::default();
        let failed = Err(AnatomyError::EmptySurface.into());
        let labels = bones_or_medial(&mesh, &options, failed, true).unwrap();
        let medial = label(&mesh, &options.label_pipeline()).unwrap();
        assert_eq!(labels.mesh_parts, medial.mesh_parts);
        let warning = labels.warnings.last().unwrap();
        assert!(
            matches!(warning, Warning::Rig(RigWarning::MedialLabels { .. })),
            "{warning}"
        );
        assert!(
            warning.to_string().starts_with(MEDIAL_FALLBACK),
            "{warning}"
        );
    }

    #[test]
    fn head_slice_step_zero_is_an_error_not_a_hang() {
        let mesh = Mesh::capsule(glam::DVec3::ZERO, 0.2, 1.0, 8, 24);
        let mut options = RigOptions::default();
        options.refine.head_slice_step = 0.0;
        match rig(&mesh, &options) {
            Err(crate::Error::Refine(RefineError::InvalidOptions(p))) => {
                assert_eq!(p.0.len(), 1);
                assert_eq!(p.0[0].name, "head_slice_step");
            }
            other => panic!("expected the refine options' error, got {other:?}"),
        }
    }

    #[test]
    fn max_shift_nan_is_an_error_not_a_disabled_guard() {
        let mesh = Mesh::capsule(glam::DVec3::ZERO, 0.2, 1.0, 8, 24);
        let options = RefineOptions {
            max_shift: f64::NAN,
            ..Default::default()
        };
        let skeleton = crate::skeleton::Skeleton {
            joints: vec![crate::skeleton::Joint::new(
                crate::skeleton::Canonical::Pelvis.as_str(),
                None,
                glam::DVec3::ZERO,
            )],
        };
        let canonical = [(
            crate::skeleton::Canonical::Pelvis.to_string(),
            crate::skeleton::JointId(0),
        )]
        .into();
        let refined = refine(
            &mesh,
            &skeleton,
            &canonical,
            glam::DVec3::Y,
            glam::DVec3::Z,
            &options,
        );
        match refined {
            Err(RefineError::InvalidOptions(p)) => assert_eq!(p.0[0].name, "max_shift"),
            other => panic!("expected the refine options' error, got {other:?}"),
        }
    }

    #[test]
    fn rig_options_name_every_problem_of_every_stage() {
        let mut options = RigOptions::default();
        options.fit.axial_samples = 0;
        options.refine.limb_step = -1.0;
        options.refine.max_shift = f64::INFINITY;
        options.input.ears.reach = f64::NAN;
        let Err(crate::Error::Options(errors)) = options.validate() else {
            panic!("expected every stage's error");
        };
        assert_eq!(errors.len(), 3, "{errors:?}");
        let message = crate::Error::Options(errors).to_string();
        for name in ["axial_samples", "limb_step", "max_shift", "ears.reach"] {
            assert!(message.contains(name), "{name} missing from {message}");
        }
        assert!(RigOptions::default().validate().is_ok());
    }

    #[test]
    fn bad_options_are_errors_before_any_work() {
        let mesh = Mesh::capsule(glam::DVec3::ZERO, 0.2, 1.0, 8, 24);
        let options = RigOptions {
            template: TemplateChoice::Builtin("centaur".into()),
            ..Default::default()
        };
        assert!(label_by_bones(&mesh, &options).is_err());
    }
}

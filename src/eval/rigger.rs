//! The automatic rigging methods that `bench` and the studies measure: one enum, one entry
//! function. A new method (e.g. the anatomical rig) is a new [`RigMethod`] variant, its options
//! in [`RiggerOptions`] and one arm in [`rig_mesh`].

use crate::anatomy::{Forward, Up};
use crate::fit::FitWarning;
use crate::mesh::Mesh;
use crate::pipeline::{general_skeleton, rig, GeneralSkeletonOptions, RigOptions};
use crate::skeleton::{JointId, Skeleton};
use crate::warning::Warning;
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// An automatic rigging method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RigMethod {
    /// The general control skeleton (dissertation ch.5, [`general_skeleton`]): joints are not
    /// anatomically named, so evaluations of it are chamfer-only.
    #[default]
    General,
    /// The anatomical control skeleton from a template (dissertation ch.7-8,
    /// [`crate::pipeline::rig`]): canonical joints are evaluated per joint.
    Anatomical,
}

impl RigMethod {
    /// Every method, in documentation order.
    pub const ALL: &'static [RigMethod] = &[RigMethod::General, RigMethod::Anatomical];

    /// Lowercase name as used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            RigMethod::General => "general",
            RigMethod::Anatomical => "anatomical",
        }
    }
}

/// The figure's orientation, for methods that need it (the anatomical rig; the general
/// skeleton is orientation-free). Studies that rotate a mesh rotate these with it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Orientation {
    /// Up direction, unit vector. Default +Y (DESIGN.md, dissertation 7.1.2).
    pub up: DVec3,
    /// Direction the figure faces, unit vector. Default +Z.
    pub forward: DVec3,
}

impl Default for Orientation {
    fn default() -> Self {
        Self {
            up: DVec3::Y,
            forward: DVec3::Z,
        }
    }
}

impl Orientation {
    /// Both directions rotated by `rotation`.
    pub fn rotated(&self, rotation: DQuat) -> Self {
        Self {
            up: rotation * self.up,
            forward: rotation * self.forward,
        }
    }
}

/// Options of [`rig_mesh`]: the method and each method's parameters.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct RiggerOptions {
    /// Which method. Default [`RigMethod::General`].
    pub method: RigMethod,
    /// The figure's orientation (up/forward). Default +Y up, +Z forward.
    pub orientation: Orientation,
    /// Parameters of [`RigMethod::General`] (defaults: dissertation Table 5.2).
    pub general: GeneralSkeletonOptions,
    /// Parameters of [`RigMethod::Anatomical`] (its orientation is `orientation`).
    #[serde(skip)]
    pub anatomical: RigOptions,
}

/// A skeleton fitted by [`rig_mesh`], in the mesh's units and frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Rigged {
    /// The fitted skeleton.
    pub skeleton: Skeleton,
    /// Canonical anatomical key → joint, for methods that name anatomy (empty otherwise).
    pub canonical: BTreeMap<String, JointId>,
    /// Wall-clock time per pipeline stage, `(stage, milliseconds)`, in stage order.
    pub timings: Vec<(String, f64)>,
    /// Warnings of every stage.
    pub warnings: Vec<Warning>,
    /// What the anatomical rig found (`None` for methods without body parts).
    pub anatomy: Option<RigAnatomy>,
}

/// What [`RigMethod::Anatomical`] found in a figure, for reports.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct RigAnatomy {
    /// Figure class of the labelling (`human-like`, `animal-like`, `unknown`).
    pub figure: String,
    /// The template fitted (`humanoid`, `quadruped`, `winged`...).
    pub template: String,
    /// The labelled parts ([`crate::anatomy::Labelling::parts_summary`]).
    pub parts: String,
    /// Parts the template expects that the fit could not build: `arm R`, `leg pair`, `tail`
    /// (from the fit's missing-limb and missing-tail warnings).
    pub missing_parts: Vec<String>,
}

impl RigAnatomy {
    /// The anatomy of a rig from [`crate::pipeline::rig`].
    pub fn of(rig: &crate::pipeline::Rig) -> Self {
        let missing_parts = rig
            .fit
            .warnings
            .iter()
            .filter_map(|w| match w {
                FitWarning::MissingLimb { group, side } => Some(match side {
                    Some(side) => format!("{group} {}", side.letter()),
                    None => format!("{group} pair"),
                }),
                FitWarning::MissingTail => Some("tail".to_owned()),
                _ => None,
            })
            .collect();
        Self {
            figure: rig.labelling.figure.name().to_owned(),
            template: rig.fit.template.clone(),
            parts: rig.labelling.parts_summary(),
            missing_parts,
        }
    }
}

/// Fits a skeleton into `mesh` with `options.method`.
///
/// # Errors
/// The method's first failing stage (see [`general_skeleton`]).
pub fn rig_mesh(mesh: &Mesh, options: &RiggerOptions) -> crate::Result<Rigged> {
    match options.method {
        RigMethod::General => {
            let general = general_skeleton(mesh, &options.general)?;
            Ok(Rigged {
                skeleton: general.skeleton,
                canonical: BTreeMap::new(),
                timings: general.timings,
                warnings: general.warnings,
                anatomy: None,
            })
        }
        RigMethod::Anatomical => {
            let mut rig_options = options.anatomical.clone();
            rig_options.label.up = Up::Direction(options.orientation.up);
            rig_options.label.forward = Forward::Direction(options.orientation.forward);
            let rig = rig(mesh, &rig_options)?;
            let anatomy = Some(RigAnatomy::of(&rig));
            Ok(Rigged {
                anatomy,
                skeleton: rig.fit.skeleton,
                canonical: rig.fit.canonical,
                timings: rig.timings,
                warnings: rig.warnings,
            })
        }
    }
}

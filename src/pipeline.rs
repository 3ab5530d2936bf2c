//! Drivers that run the pipeline stages in order: [`general_skeleton`] / [`general_rig`] (any
//! figure, dissertation ch.5) and [`rig`] (the anatomical skeleton from a template, ch.7-8).

mod rig;
mod warning;

pub use rig::{
    auto_template, label_by_bones, label_by_skin, missing_parts, more_limbs_than, no_template_fits,
    rig, Rig, RigOptions, RigWarning, TemplateChoice, GENERAL, MEDIAL_FALLBACK,
};

use crate::distance::{edt, DistanceMap};
use crate::general::{control_skeleton, GeneralOptions, GeneralSkeleton};
use crate::medial::{dms, MedialOptions};
use crate::mesh::Mesh;
use crate::paths::{path_tree, PathOptions};
use crate::skin::{skin, skin_from_bones, SegmentVoxels, Skin, SkinError, SkinOptions};
use crate::voxel::{voxelize_figure, Grid, Solid, VoxelOptions, VoxelReport};
use crate::warning::Warning;
use serde::Serialize;
use std::time::Instant;

/// All parameters of [`general_skeleton`], one options struct per stage. Table 5.2 of the
/// dissertation maps onto them as: voxel-size → `voxel.size`, exposure threshold →
/// `medial.exposure_threshold`, closeness-of-fit → `paths.closeness`, approximation-error,
/// min-fraction, max-fraction, number-of-segments → `general`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct GeneralSkeletonOptions {
    /// Voxelization (default voxel size 0.01 of the longest bounding-box side).
    pub voxel: VoxelOptions,
    /// Discrete medial surface (default exposure threshold 0.5).
    pub medial: MedialOptions,
    /// Path tree (default closeness of fit 0.1).
    pub paths: PathOptions,
    /// Skeletal graph, joints and frames.
    pub general: GeneralOptions,
}

/// Fits a general control skeleton into `mesh` (dissertation ch.5): voxelize, exact distance
/// map, discrete medial surface, path tree, skeletal graph and joints. Stage timings are
/// recorded in [`GeneralSkeleton::timings`]; warnings of every stage are collected in
/// [`GeneralSkeleton::warnings`].
///
/// ```
/// use skelfit::mesh::Mesh;
/// use skelfit::pipeline::{general_skeleton, GeneralSkeletonOptions};
///
/// // A capsule: one chain along its axis, two end effectors.
/// let mesh = Mesh::capsule(glam::DVec3::ZERO, 0.2, 0.6, 8, 16);
/// let general = general_skeleton(&mesh, &GeneralSkeletonOptions::default()).unwrap();
/// assert_eq!(general.end_effectors().len(), 2);
/// assert_eq!(general.skeleton.joints[0].name, "root");
/// assert!(general.skeleton.validate().is_ok());
/// ```
///
/// # Errors
/// The first failing stage's error: invalid options of any stage (checked before any work),
/// a mesh that does not voxelize, an empty medial surface.
pub fn general_skeleton(
    mesh: &Mesh,
    options: &GeneralSkeletonOptions,
) -> crate::Result<GeneralSkeleton> {
    general_stages(mesh, options).map(|stages| stages.general)
}

/// Wall-clock laps of the pipeline stages: each [`Laps::lap`] records the milliseconds since
/// the previous one (or the start) under the stage's name.
pub(crate) struct Laps {
    clock: Instant,
}

impl Laps {
    /// Starts the clock.
    pub(crate) fn start() -> Self {
        Self {
            clock: Instant::now(),
        }
    }

    /// Pushes `(name, milliseconds since the last lap)` onto `timings` and restarts the clock.
    pub(crate) fn lap(&mut self, name: &str, timings: &mut Vec<(String, f64)>) {
        let now = Instant::now();
        timings.push((name.to_string(), (now - self.clock).as_secs_f64() * 1e3));
        self.clock = now;
    }
}

/// What the general stages produce, with the voxel data later stages (skinning) reuse.
struct GeneralStages {
    general: GeneralSkeleton,
    solid: Solid,
    distance: DistanceMap,
}

fn general_stages(mesh: &Mesh, options: &GeneralSkeletonOptions) -> crate::Result<GeneralStages> {
    options.medial.validate()?;
    options.paths.validate()?;
    options.general.validate()?;
    let mut timings = Vec::new();
    let mut lap = Laps::start();
    let solid = voxelize_figure(mesh, &options.voxel)?;
    lap.lap("voxelize", &mut timings);
    let distance = edt(&solid);
    lap.lap("distance", &mut timings);
    let surface = dms(&distance, &options.medial)?;
    lap.lap("medial", &mut timings);
    let tree = path_tree(&surface, &options.paths)?;
    lap.lap("paths", &mut timings);
    let mut general = control_skeleton(tree, &options.general)?;
    lap.lap("general", &mut timings);
    let mut warnings: Vec<Warning> = solid
        .report
        .warnings()
        .into_iter()
        .map(Into::into)
        .collect();
    warnings.extend(surface.warnings.into_iter().map(Warning::Medial));
    warnings.append(&mut general.warnings);
    general.warnings = warnings;
    general.timings = timings;
    Ok(GeneralStages {
        general,
        solid,
        distance,
    })
}

/// Options of [`general_rig`]: the skeleton's and the skin's.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GeneralRigOptions {
    /// Voxelization, medial surface, path tree and skeletal graph.
    pub skeleton: GeneralSkeletonOptions,
    /// Regions of influence and weights.
    pub skin: SkinOptions,
}

/// A general control skeleton with the mesh anchored to it (dissertation ch.5 end to end).
#[derive(Debug, Clone)]
pub struct GeneralRig {
    /// The skeleton, its segments and path tree; `timings` also holds the `skin` stage.
    pub general: GeneralSkeleton,
    /// Per-vertex weights (anchor weights and engine weights).
    pub skin: Skin,
    /// The voxel grid used.
    pub grid: Grid,
    /// What voxelization found (interior voxels, dropped parts).
    pub voxels: VoxelReport,
    /// Warnings of every stage, skinning included.
    pub warnings: Vec<Warning>,
}

/// Fits a general control skeleton into `mesh` and anchors the mesh to it: the stages of
/// [`general_skeleton`], then regions of influence from each segment's chain voxels and the
/// per-vertex weights of ch.5.2.5 ([`crate::skin::skin`]). A figure whose segments reach no
/// interior voxel (a sphere, a hollow shell: no limbs) is skinned to its bones instead
/// ([`crate::skin::skin_from_bones`]), with a warning.
///
/// # Errors
/// As [`general_skeleton`], plus [`crate::skin::SkinError`] for invalid skin options.
pub fn general_rig(mesh: &Mesh, options: &GeneralRigOptions) -> crate::Result<GeneralRig> {
    options.skin.validate()?;
    let GeneralStages {
        mut general,
        solid,
        distance,
    } = general_stages(mesh, &options.skeleton)?;
    let clock = Instant::now();
    let segments: Vec<SegmentVoxels> = general
        .segments
        .iter()
        .map(|s| SegmentVoxels {
            joint: s.joint,
            child: Some(s.child),
            tip: None,
            voxels: {
                let mut v = s.voxels.clone();
                v.sort_unstable();
                v.dedup();
                v
            },
        })
        .collect();
    let mut warnings = general.warnings.clone();
    let skin = match skin(
        mesh,
        &general.skeleton,
        &solid,
        &distance,
        &segments,
        &options.skin,
    ) {
        // A figure without limbs (a sphere, a hollow shell): its skeleton has no segment
        // whose chain voxels reach inside, so the mesh is skinned to the bones instead.
        Err(SkinError::NoInfluence) => {
            warnings.push(RigWarning::SkinnedToBones.into());
            skin_from_bones(mesh, &general.skeleton, &solid, &distance, &options.skin)?
        }
        result => result?,
    };
    general
        .timings
        .push(("skin".to_string(), clock.elapsed().as_secs_f64() * 1e3));
    warnings.extend(skin.warnings.iter().cloned().map(Warning::Skin));
    Ok(GeneralRig {
        grid: solid.grid,
        voxels: solid.report.clone(),
        general,
        skin,
        warnings,
    })
}

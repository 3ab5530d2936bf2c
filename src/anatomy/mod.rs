//! Body-part labelling (dissertation ch.7): the level graph of a figure's medial surface and
//! the labels trunk, head, tail, arms, legs, wings and digits.
//!
//! - [`level_graph`] (`level_graph.rs`): normalised heart values of the DMS voxels, strata of
//!   `bins` equal value ranges, one vertex per connected piece of a stratum, built bottom-up into
//!   a tree rooted at the heart's piece; distal fractions, insignificant vertices, major
//!   junctions; extreme up/down/forward/backward and linear/rounded cross-section marks
//!   (ch.7.3.1-7.3.2);
//! - [`label_graph`] (`rules.rs`): the trunk from the major junctions and its slope
//!   (human-like/animal-like, `trunk.rs`), the sections hanging off it (`sections.rs`), then
//!   legs, wings, tail (`tail.rs`), head, arms, an animal biped's short fore limbs
//!   (`fore_limbs.rs`), leftovers (ch.7.3.3), a phase per function;
//! - [`Overrides`] (`overrides.rs`): a JSON file of user corrections;
//! - `build.rs`: parts with girdles and digits; `neck.rs`: the trunk pieces between the
//!   pectoral limbs' and the head's junctions, which the per-vertex labels give to the head;
//!   `limb_root.rs`: arms' and fore legs' DMS voxels inside the trunk's balls, which the
//!   per-vertex labels give to the trunk;
//!   `project.rs`: labels per interior voxel and per mesh vertex; [`label_vertices_by_bones`]
//!   (`bone_labels.rs`): per-vertex labels from the nearest bone of a fitted skeleton instead
//!   (`skelfit label --vertex-labels bones`, [`crate::pipeline::label_by_bones`]); [`skeleton_regions`] (`reference.rs`, for reference rigs [`crate::eval::reference_regions`]): the body region of each mesh
//!   vertex from a reference rig, for the accuracy table, and [`weight_share`]: per-vertex
//!   labels scored against skin weights (girdle bones counting for trunk and limb); `output.rs`: labels.json, PLY, SVG.
//!
//! Determinism: the heart comes from deterministic sources and every step is sequential or
//! ordered by a total key, so labels are identical on any number of threads.
//!
//! ```
//! use skelfit::anatomy::{label, Label, LabelPipelineOptions};
//! use skelfit::mesh::Mesh;
//!
//! // A sphere has no trunk: a best effort with a warning, not an error.
//! let mesh = Mesh::uv_sphere(glam::DVec3::ZERO, 1.0, 16, 32);
//! let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
//! assert_eq!(labels.parts[0].label, Label::Trunk);
//! assert!(!labels.warnings.is_empty());
//! ```

mod bone_labels;
mod build;
mod error;
mod facing;
mod fore_limbs;
mod frame;
mod hanging_arms;
mod level_graph;
mod limb_root;
mod neck;
mod options;
mod orient;
mod output;
mod overrides;
mod parts;
mod project;
mod reference;
mod rules;
mod sections;
mod tail;
mod trunk;
mod warning;

pub use bone_labels::label_vertices_by_bones;
pub use error::AnatomyError;
pub use facing::ForwardChoice;
pub use frame::{parse_direction, Frame};
pub use hanging_arms::{hanging_arms, keep_arm_skins_apart, separate_arms, ArmSkin, HangingArms};
pub use level_graph::{level_graph, LevelGraph, LevelTree, LevelVertex, Marks, Reach, NO_VERTEX};
pub use options::{Forward, LabelOptions, LabelPipelineOptions, LevelOptions, RuleOptions, Up};
pub use orient::{find_up, UpChoice, UpScore};
pub use output::{labels_json, labels_ply, labels_svg, part_colour};
pub use overrides::{Overrides, SectionOverride};
pub use parts::{Extremes, FigureClass, Label, Labelling, LimbPair, Part, Section, Side};
pub use project::NO_PART;
pub use reference::{
    agreement, best_regions, girdle_limbs, joint_regions, part_region, skeleton_regions,
    vertex_regions, weight_regions, weight_share, Agreement, Region, WeightRegions, WeightShare,
};
pub use rules::{label_graph, Assignment, Draft};
pub use warning::AnatomyWarning;

use crate::distance::edt;
use crate::medial::{dms, MedialSurface};
use crate::mesh::Mesh;
use crate::paths::PathOptions;
use crate::voxel::{voxelize_figure, Solid};
use crate::warning::Warning;
use glam::DVec3;

/// Labels the body parts of `mesh` (dissertation ch.7): voxelize, distance map, medial
/// surface, then [`label_pieces`].
///
/// # Errors
/// Invalid options of any stage, a mesh that does not voxelize, an empty medial surface.
pub fn label(mesh: &Mesh, options: &LabelPipelineOptions) -> crate::Result<Labelling> {
    label_with_overrides(mesh, options, None)
}

/// [`label`] with a user's corrections applied before parts are built.
///
/// # Errors
/// As [`label`], plus [`AnatomyError::Override`] for an override naming a missing section.
pub fn label_with_overrides(
    mesh: &Mesh,
    options: &LabelPipelineOptions,
    overrides: Option<&Overrides>,
) -> crate::Result<Labelling> {
    options.validate()?;
    let solid = voxelize_figure(mesh, &options.voxel)?;
    let surface = dms(&edt(&solid), &options.medial)?;
    Ok(label_pieces(
        mesh,
        &solid,
        &surface,
        &options.paths,
        &options.label,
        overrides,
    )?)
}

/// Labels from already computed pipeline pieces (so that a caller running the voxel stages
/// anyway does not repeat them): the `solid` `mesh` was voxelized into and its medial
/// `surface`; `paths` samples the heart. Phases: body frame; level graph and marks ([`level_graph`]); labelling rules
/// ([`label_graph`]); overrides; parts, girdles and digits; labels per DMS voxel, interior
/// voxel and mesh vertex. With [`Forward::Auto`] the whole labelling runs twice, the second
/// time facing the guessed forward direction.
///
/// # Errors
/// [`AnatomyError`] for invalid options, pieces on different grids, an empty surface or a bad
/// override.
pub fn label_pieces(
    mesh: &Mesh,
    solid: &Solid,
    surface: &MedialSurface,
    paths: &PathOptions,
    options: &LabelOptions,
    overrides: Option<&Overrides>,
) -> Result<Labelling, AnatomyError> {
    options.validate()?;
    if surface.grid != solid.grid || solid.inside.len() != solid.grid.len() {
        return Err(AnatomyError::GridMismatch);
    }
    if surface.is_empty() {
        return Err(AnatomyError::EmptySurface);
    }
    // The level graph's frame-independent part, once for every frame tried below.
    let tree = LevelTree::new(surface, Some(solid), paths, &options.level);
    let up_found = match options.up {
        Up::Direction(_) => None,
        Up::Auto => Some(orient::find_up_in(&tree, solid, surface, options)),
    };
    let up = up_found.as_ref().map_or(options.up.or_default(), |c| c.up);
    // A figure found lying in the file (Z-up from Blender, CAD tools, scanners) faces where the
    // given forward points after the same turn that takes +Y to its up: +Z forward becomes -Y
    // for a Z-up file, Blender's convention.
    let forward = match options.forward {
        Forward::Direction(f) if up_found.is_some() => {
            Forward::Direction(glam::DQuat::from_rotation_arc(DVec3::Y, up) * f)
        }
        other => other,
    };
    let mut labelling = match forward {
        Forward::Direction(f) if f.cross(up).length_squared() > 1e-6 * f.length_squared() => {
            let frame = Frame::new(up, f)?;
            label_in_frame(mesh, solid, surface, &tree, options, overrides, frame)?
        }
        Forward::Direction(_) | Forward::Auto => {
            // The file's convention first (glTF's +Z, turned with the up found: -Y for a Z-up
            // file), or an axis across a given up along it; then where the figure faces.
            let prior = [
                glam::DQuat::from_rotation_arc(DVec3::Y, up) * DVec3::Z,
                DVec3::Z,
                DVec3::Y,
            ]
            .into_iter()
            .find(|f| f.cross(up).length_squared() > 0.01 * up.length_squared())
            .unwrap_or(DVec3::X);
            let frame = Frame::new(up, prior)?;
            let first = label_in_frame(mesh, solid, surface, &tree, options, overrides, frame)?;
            let choice = facing::find_forward(&first, mesh, prior);
            let same = choice.forward.dot(first.frame.forward) > 1.0 - 1e-12;
            let mut labelling = if same {
                first
            } else {
                let frame = Frame::new(up, choice.forward).unwrap_or(first.frame);
                label_in_frame(mesh, solid, surface, &tree, options, overrides, frame)?
            };
            if labelling.frame.forward.dot(choice.prior) < 1.0 - 1e-12 {
                labelling.warnings.push(
                    AnatomyWarning::ForwardGuessed {
                        forward: labelling.frame.forward,
                        confidence: choice.confidence,
                        reason: choice.note.clone(),
                    }
                    .into(),
                );
            }
            labelling.forward_found = Some(choice);
            labelling
        }
    };
    // What the voxelization left out comes first, then how up was found.
    if let Some(choice) = up_found.as_ref().filter(|c| c.up != DVec3::Y) {
        let found = AnatomyWarning::UpFound {
            up: choice.up,
            confidence: choice.confidence,
            note: choice.note.clone(),
        };
        labelling.warnings.insert(0, found.into());
    }
    labelling.up_found = up_found;
    labelling.warnings.splice(
        0..0,
        solid.report.warnings().into_iter().map(Warning::Voxel),
    );
    Ok(labelling)
}

/// The level graph of `surface` in `frame`, with the marks measured over `solid`'s interior
/// extent along up and forward.
fn graph_in_frame(
    solid: &Solid,
    surface: &MedialSurface,
    tree: &LevelTree,
    frame: &Frame,
) -> LevelGraph {
    let (mut up, mut fw) = (
        (f64::INFINITY, f64::NEG_INFINITY),
        (f64::INFINITY, f64::NEG_INFINITY),
    );
    for (index, &inside) in solid.inside.iter().enumerate() {
        if inside {
            let c = solid.grid.centre(solid.grid.coords(index));
            let (u, f) = (c.dot(frame.up), c.dot(frame.forward));
            up = (up.0.min(u), up.1.max(u));
            fw = (fw.0.min(f), fw.1.max(f));
        }
    }
    tree.in_frame(surface, frame, up, fw)
}

fn label_in_frame(
    mesh: &Mesh,
    solid: &Solid,
    surface: &MedialSurface,
    tree: &LevelTree,
    options: &LabelOptions,
    overrides: Option<&Overrides>,
    frame: Frame,
) -> Result<Labelling, AnatomyError> {
    let graph = graph_in_frame(solid, surface, tree, &frame);
    let mut draft = label_graph(&graph, surface, &frame, &options.rules);
    if let Some(o) = overrides {
        let centroids: Vec<DVec3> = graph.vertices.iter().map(|v| v.centroid).collect();
        o.apply(&mut draft, &centroids)?;
    }
    let mut warnings: Vec<Warning> = surface.warnings.iter().cloned().map(Into::into).collect();
    let graph_voxels = graph.voxels;
    if graph_voxels < surface.len() {
        warnings.push(
            AnatomyWarning::LargestPartOnly {
                labelled: graph_voxels,
                voxels: surface.len(),
            }
            .into(),
        );
    }
    warnings.extend(draft.warnings.drain(..).map(Warning::Anatomy));
    let (mut parts, vertex_parts) = build::build_parts(&draft, &graph, surface, &options.rules);
    let voxel_parts: Vec<u32> = graph
        .vertex_of
        .iter()
        .map(|&v| {
            if v == NO_VERTEX {
                NO_PART
            } else {
                vertex_parts[v as usize]
            }
        })
        .collect();
    // The interior-voxel and mesh-vertex labels give the neck to the head; the parts (and
    // `voxel_parts`, which the anatomical fit reads) keep it in the trunk.
    let mut region_parts = voxel_parts.clone();
    if options.rules.neck_in_head {
        if let Some(head) = parts.iter().position(|p| p.label == Label::Head) {
            let neck = neck::neck_vertices(&graph, &parts, &vertex_parts);
            for v in neck {
                for &p in &graph.vertices[v].voxels {
                    region_parts[p] = head as u32;
                }
            }
        }
    }
    // Arms' and fore legs' roots inside the trunk's balls count as trunk there.
    if options.rules.pectoral_root_scale > 0.0 {
        let roots = limb_root::pectoral_roots_in_trunk(
            surface,
            &parts,
            &region_parts,
            options.rules.pectoral_root_scale,
        );
        for p in roots {
            region_parts[p] = 0;
        }
    }
    let interior = tree
        .interior_parts(surface, solid, &region_parts)
        .unwrap_or_else(|| {
            project::interior_parts(solid, surface, &region_parts, options.level.radius_weight)
        });
    let mut mesh_parts = project::mesh_parts(mesh, solid, &interior);
    for p in &mut mesh_parts {
        if *p == NO_PART {
            *p = 0;
        }
        parts[*p as usize].vertex_count += 1;
    }
    Ok(Labelling {
        figure: draft.figure,
        frame,
        up_found: None,
        forward_found: None,
        trunk_axis: draft.trunk_axis,
        trunk_angle: draft.trunk_angle,
        parts,
        sections: draft.sections,
        level_graph: graph,
        vertex_parts,
        grid: surface.grid,
        dms_voxels: surface.voxels.clone(),
        voxel_parts,
        mesh_parts,
        interior_parts: interior,
        warnings,
    })
}

//! The skinning stage driver and its result.

use super::bind_props;
use super::coarse::{coarse_grid, coarse_segments, coarsening};
use super::geodesic::geodesic_weights;
use super::weights::{nearest_segment, segment_distance};
use super::{
    anchor_weights, bone_segments, engine_weights, influence, EngineWeights, SegmentVoxels,
    SkinError, SkinMethod, SkinOptions, SkinWarning,
};
use crate::distance::DistanceMap;
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use crate::voxel::Solid;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// A mesh bound to a skeleton.
#[derive(Debug, Clone, PartialEq)]
pub struct Skin {
    /// Anchor weights per mesh vertex (`#V` lists): `(joint, weight)` sorted by joint id,
    /// weights positive and summing to one. A joint's weight is the sum of the dissertation
    /// weights of the segments it moves ([`anchor_weights`]).
    pub weights: Vec<Vec<(JointId, f64)>>,
    /// The same weights limited to four per vertex for engines and glTF.
    pub engine: EngineWeights,
    /// What had to be worked around.
    pub warnings: Vec<SkinWarning>,
}

/// Skins `mesh` to `skeleton` from the chain voxels of its segments (dissertation 5.2.5, 8.3).
///
/// `mesh` and `skeleton` share units and frame; `solid` is the voxelization of `mesh` and
/// `distance` its [`edt`](crate::distance::edt). Each vertex takes the influence set of the
/// voxel containing it ([`influence`]), the weights of [`anchor_weights`] over those
/// segments with the distance from the vertex to each segment's line, summed per joint.
/// A vertex whose voxel no influence reached is bound to its nearest segment (a
/// [`SkinWarning::UnreachedVertices`]).
///
/// # Errors
/// [`SkinError::EmptySkeleton`], [`SkinError::InvalidSkeleton`], [`SkinError::TooManyJoints`],
/// [`SkinError::InvalidOption`], [`SkinError::NonFiniteVertex`],
/// [`SkinError::UnknownJoint`] for a segment naming a missing joint, and the errors of
/// [`influence`].
pub fn skin(
    mesh: &Mesh,
    skeleton: &Skeleton,
    solid: &Solid,
    distance: &DistanceMap,
    segments: &[SegmentVoxels],
    options: &SkinOptions,
) -> Result<Skin, SkinError> {
    check_skeleton(skeleton)?;
    options.validate()?;
    if let Some(vertex) = mesh.positions.iter().position(|p| !p.is_finite()) {
        return Err(SkinError::NonFiniteVertex { vertex });
    }
    for (segment, s) in segments.iter().enumerate() {
        for joint in std::iter::once(s.joint).chain(s.child) {
            if joint.0 >= skeleton.len() {
                return Err(SkinError::UnknownJoint {
                    segment,
                    joint: joint.0,
                    joints: skeleton.len(),
                });
            }
        }
    }
    let mut warnings = Vec::new();
    let (weights, unreached) = match options.method {
        SkinMethod::Geodesic => {
            for (segment, s) in segments.iter().enumerate() {
                if let Some(&voxel) = s.voxels.iter().find(|&&v| v >= solid.grid.len()) {
                    return Err(SkinError::VoxelOutOfRange {
                        segment,
                        voxel,
                        voxels: solid.grid.len(),
                    });
                }
                if s.voxels.is_empty() {
                    warnings.push(SkinWarning::SegmentOutside {
                        segment,
                        joint: skeleton.joint(s.joint).name.clone(),
                    });
                }
            }
            if segments.iter().all(|s| s.voxels.is_empty()) {
                return Err(SkinError::NoInfluence);
            }
            // A rig on a grid finer than the default: the weights at the default resolution
            // (`coarse.rs`), the segments carried over to it.
            match coarsening(solid) {
                Some(factor) => {
                    let (coarse, distance) = coarse_grid(solid, factor);
                    let segments = coarse_segments(segments, &solid.grid, &coarse.grid);
                    geodesic_weights(mesh, skeleton, &coarse, &distance, &segments, options)
                }
                None => geodesic_weights(mesh, skeleton, solid, distance, segments, options),
            }
        }
        SkinMethod::Anchor => anchor_skin(
            mesh,
            skeleton,
            solid,
            distance,
            segments,
            options,
            &mut warnings,
        )?,
    };
    if let Some(&first) = unreached.first() {
        warnings.push(SkinWarning::UnreachedVertices {
            count: unreached.len(),
            first,
        });
    }
    let (engine, dropped) = engine_weights(&weights);
    let truncated = dropped.iter().filter(|&&d| d > 0.0).count();
    if truncated > 0 {
        warnings.push(SkinWarning::TruncatedInfluences {
            count: truncated,
            max_dropped: dropped.iter().copied().fold(0.0, f64::max),
        });
    }
    debug_assert!(weights
        .iter()
        .all(|w| (w.iter().map(|(_, x)| x).sum::<f64>() - 1.0).abs() < 1e-9));
    Ok(Skin {
        weights,
        engine,
        warnings,
    })
}

/// Per-vertex weights and the vertices no influence reached.
type WeightsAndUnreached = (Vec<Vec<(JointId, f64)>>, Vec<usize>);

/// The dissertation's anchor weights ([`SkinMethod::Anchor`]): every vertex takes the
/// influence set of its voxel and [`anchor_weights`] over those segments. Returns the weights
/// and the vertices whose voxel no influence reached (bound to the nearest segment).
fn anchor_skin(
    mesh: &Mesh,
    skeleton: &Skeleton,
    solid: &Solid,
    distance: &DistanceMap,
    segments: &[SegmentVoxels],
    options: &SkinOptions,
    warnings: &mut Vec<SkinWarning>,
) -> Result<WeightsAndUnreached, SkinError> {
    let influence = influence(solid, distance, mesh, segments, options)?;
    let mut used = vec![false; segments.len()];
    for set in &influence.sets {
        for &s in set {
            used[s as usize] = true;
        }
    }
    for (segment, s) in segments.iter().enumerate() {
        if !used[segment] {
            warnings.push(SkinWarning::SegmentOutside {
                segment,
                joint: skeleton.joint(s.joint).name.clone(),
            });
        }
    }

    let lines: Vec<_> = segments.iter().map(|s| s.line(skeleton)).collect();
    let grid = influence.grid;
    let per_vertex: Vec<(Vec<(JointId, f64)>, bool)> = mesh
        .positions
        .par_iter()
        .map(|&p| {
            let set: Vec<u32> = grid
                .voxel_at(p)
                .map(|c| influence.at(grid.index(c)).to_vec())
                .unwrap_or_default();
            let (set, reached) = if set.is_empty() {
                let nearest = nearest_segment(p, &lines).map_or(0, |s| s as u32);
                (vec![nearest], false)
            } else {
                (set, true)
            };
            let distances: Vec<f64> = set
                .iter()
                .map(|&s| {
                    let (a, b) = lines[s as usize];
                    segment_distance(p, a, b)
                })
                .collect();
            let mut by_joint: BTreeMap<JointId, f64> = BTreeMap::new();
            for (&s, w) in set.iter().zip(anchor_weights(&distances)) {
                *by_joint.entry(segments[s as usize].joint).or_insert(0.0) += w;
            }
            let weights: Vec<(JointId, f64)> =
                by_joint.into_iter().filter(|&(_, w)| w > 0.0).collect();
            (weights, reached)
        })
        .collect();

    let unreached: Vec<usize> = (0..per_vertex.len())
        .filter(|&v| !per_vertex[v].1)
        .collect();
    Ok((per_vertex.into_iter().map(|(w, _)| w).collect(), unreached))
}

/// Skins `mesh` to `skeleton` with segments derived from its bones ([`bone_segments`]), for
/// skeletons without path-tree chains. See [`skin`] for the arguments. The held props the
/// voxelization left out ([`crate::voxel::Prop`]) are then bound wholly to the joint weighing
/// most at their grip (the vertex nearest the interior): they move rigidly with the joint
/// holding them.
///
/// # Errors
/// As [`skin`]; [`SkinError::NoInfluence`] when no bone passes inside the figure.
pub fn skin_from_bones(
    mesh: &Mesh,
    skeleton: &Skeleton,
    solid: &Solid,
    distance: &DistanceMap,
    options: &SkinOptions,
) -> Result<Skin, SkinError> {
    check_skeleton(skeleton)?;
    options.validate()?;
    if distance.grid != solid.grid {
        return Err(SkinError::GridMismatch);
    }
    // The geodesic weights of a rig on a grid finer than the default are computed at the
    // default resolution (`coarse.rs`): the bones' segments are found on that grid directly.
    let coarse = (options.method == SkinMethod::Geodesic)
        .then(|| coarsening(solid))
        .flatten()
        .map(|factor| coarse_grid(solid, factor));
    let (grid, distance) = match &coarse {
        Some((coarse, distance)) => (coarse, distance),
        None => (solid, distance),
    };
    let segments = bone_segments(skeleton, grid, distance, options);
    let mut bound = skin(mesh, skeleton, grid, distance, &segments, options)?;
    // Held props move rigidly with the joint that holds them.
    if bind_props(mesh, solid, &solid.report.props, &mut bound.weights) > 0 {
        bound.engine = engine_weights(&bound.weights).0;
    }
    Ok(bound)
}

/// Rejects empty, invalid or too large skeletons.
pub(crate) fn check_skeleton(skeleton: &Skeleton) -> Result<(), SkinError> {
    if skeleton.is_empty() {
        return Err(SkinError::EmptySkeleton);
    }
    if skeleton.len() > usize::from(u16::MAX) {
        return Err(SkinError::TooManyJoints {
            count: skeleton.len(),
        });
    }
    skeleton
        .validate()
        .map_err(|problems| SkinError::InvalidSkeleton {
            message: problems
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; "),
        })
}

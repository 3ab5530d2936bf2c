//! Geodesic voxel binding (after Dionne & de Lasa 2013, "Geodesic Voxel Binding for
//! Production Character Meshes"): weights that fall off with the distance from each bone
//! measured *through the solid*, so skin only follows bones it is connected to inside the
//! body (the torso under the armpit does not follow the arm lying against it), and that vary
//! continuously over the surface, so no edge is torn when a joint turns.
//!
//! ```text
//! bone voxels (SegmentVoxels, one label per joint); interior voxels, plus the air the
//! figure encloses (`enclosed_air`: the hollow inside a jacket modelled as a thin shell)
//!   │ K-nearest-label Dijkstra through the interior voxels (26-neighbourhood, lengths 1, √2,
//!   │ √3, each step costing its length × depth^-depth_exponent: shallow contacts cost more)
//!   ▼
//! per interior voxel: the K nearest joints and their geodesic distances
//!   │ each voxel around a vertex → its nearest interior voxel (breadth-first), distance +
//!   │ offset; w_j = f(d_j) tapered linearly to 0 where the joint's path is `blend_ratio`
//!   ▼ times as long as the nearest joint's, f(d) = d^(−falloff)
//! per voxel (interior, and around the vertices): ≤ 4 joints
//!   │ `voxel_smoothing_iterations` rounds of diffusion between face neighbours (outside
//!   │ voxels only where their nearest interior voxels touch), pruned to four each round,
//!   ▼ slower where the nearest joint's bones are thinner than `blend_radius`
//! per vertex: trilinear blend of the weight vectors of the 8 voxel centres around it
//!   │ every prune to four joints subtracts the fifth's weight, so a joint leaves the set
//!   ▼ with weight 0 (no jump)
//! ≤ 4 influences per vertex, normalised
//!   │ Laplacian smoothing over the mesh edges, each edge's share scaled by (voxel / length)²;
//!   ▼ weights under 1 % cut
//! per vertex weights
//!   │ a separate piece whose every vertex has its largest weight on one joint
//!   ▼ (a plate, an eye) bound wholly to that joint: it moves rigidly
//! weights
//! ```
//!
//! Why this and not the dissertation's anchor weights (5.2.5): those give each vertex the
//! equal-share weights of the influence set of its voxel, which changes abruptly between
//! neighbouring voxels (one vertex 100 % on one bone, its neighbour 25 % on four), and the
//! mesh tears when a joint turns. A weight field that is continuous in space cannot tear
//! under linear blend skinning, whatever the mesh's tessellation or its number of pieces;
//! measured with [`check`](super::check): `reports/deformation/`.

mod cell;
mod diffusion;
mod field;
mod rows;
mod surface;

use super::enclosed::with_enclosed_air;
use super::weights::nearest_segment;
use super::{SegmentVoxels, SkinOptions};
use crate::distance::DistanceMap;
use crate::mesh::Mesh;
use crate::skeleton::{JointId, Skeleton};
use crate::voxel::Solid;
use diffusion::smoothed_voxel_weights;
use field::field;
use rayon::prelude::*;
use rows::{prune, Row};
use surface::{corners, spread_to_unreached, vertex_rows, Adjacency, Smoothing};

/// Nearest joints kept per interior voxel: the four influences a vertex may keep, and one
/// more whose weight is subtracted so that joints enter and leave the set smoothly.
const LABELS: usize = super::MAX_ENGINE_INFLUENCES + 1;

/// A weight this small (of a vertex's total of one) is subtracted from every weight after
/// blending and smoothing, so that what smoothing carries along long edges or across a piece
/// fades to exactly zero instead of a trace of a far bone.
const NEGLIGIBLE: f64 = 0.01;

/// Geodesic weights of every vertex of `mesh` (at most [`MAX_ENGINE_INFLUENCES`] joints,
/// positive, summing to one), and the vertices that no bone reached through the interior
/// (bound to the nearest segment's joint instead).
///
/// [`MAX_ENGINE_INFLUENCES`]: super::MAX_ENGINE_INFLUENCES
pub(crate) fn geodesic_weights(
    mesh: &Mesh,
    skeleton: &Skeleton,
    solid: &Solid,
    distance: &DistanceMap,
    segments: &[SegmentVoxels],
    options: &SkinOptions,
) -> (Vec<Vec<(JointId, f64)>>, Vec<usize>) {
    // The figure with the air it encloses, which the weights may cross (a hollow jacket).
    let enclosed = with_enclosed_air(solid, options.enclosed_air).map(|solid| {
        let distance = crate::distance::edt(&solid);
        (solid, distance)
    });
    let (solid, distance) = enclosed.as_ref().map_or((solid, distance), |(s, d)| (s, d));
    let grid = solid.grid;
    let needed = voxels_around_vertices(mesh, solid);
    // The mesh's adjacency and its smoothing graph depend on the mesh alone: built beside the
    // shortest paths (one thread) and the diffusion, not after them.
    let (voxels, (adjacency, smoothing)) = rayon::join(
        || {
            let field = field(solid, distance, segments, options, &needed);
            let radius = bone_radius(skeleton, distance, segments);
            smoothed_voxel_weights(&field, &grid, &needed, options, &radius)
        },
        || {
            let adjacency = Adjacency::new(mesh);
            let smoothing = Smoothing::new(
                mesh,
                &adjacency,
                options.smoothing_iterations,
                grid.voxel_size,
            );
            (adjacency, smoothing)
        },
    );
    let mut rows = vertex_rows(&voxels, &grid, mesh);
    // A vertex the field does not reach (no joint reached any interior voxel near it) takes
    // the weights of the nearest weighted vertex of the same piece along the mesh's edges; a
    // piece with no weighted vertex at all follows the joint of its nearest bone.
    spread_to_unreached(&mut rows, &adjacency);
    let isolated = bind_isolated(mesh, skeleton, segments, &mut rows);
    smoothing.smooth(&mut rows);
    let mut weights = vertex_weights(&rows);
    rigid_pieces(mesh, &mut weights);
    (weights, isolated)
}

/// Binds each piece of `mesh` (a connected component over shared corners) that lies on one
/// side of every joint wholly to the joint its bone belongs to: where every vertex of the
/// piece has its largest weight on the same joint (an armour plate above the knee, an eye, a
/// buckle), the piece moves as one rigid body, as an artist binds it; the traces of a
/// neighbouring bone that diffusion leaves on it would only shear its small edges when that
/// joint turns (a thigh plate's 2.5 mm edges stretched past 2x by a 3 % knee weight). A piece
/// that spans a joint (its dominant joint changes across it: a sleeve over the elbow, a
/// skirt, the body itself) keeps its blended weights. No edge joins two pieces, so no edge
/// can stretch more than before.
fn rigid_pieces(mesh: &Mesh, weights: &mut [Vec<(JointId, f64)>]) {
    let (component, count) = mesh.triangle_components();
    if count < 2 {
        return;
    }
    // Per piece: its one dominant joint while every vertex agrees, `None` once one does not.
    let mut dominant: Vec<Option<Option<JointId>>> = vec![Some(None); count];
    let mut vertex_piece = vec![u32::MAX; weights.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for &v in tri {
            vertex_piece[v as usize] = component[t];
        }
    }
    for (v, w) in weights.iter().enumerate() {
        let Some(state) = dominant.get_mut(vertex_piece[v] as usize) else {
            continue; // a corner of no triangle
        };
        let Some(agreed) = *state else {
            continue;
        };
        let top = w.iter().max_by(|a, b| a.1.total_cmp(&b.1));
        *state = match (top, agreed) {
            (Some(&(j, _)), None) => Some(Some(j)),
            (Some(&(j, _)), Some(k)) if j == k => Some(Some(k)),
            _ => None,
        };
    }
    for (v, w) in weights.iter_mut().enumerate() {
        if let Some(Some(Some(j))) = dominant.get(vertex_piece[v] as usize) {
            *w = vec![(*j, 1.0)];
        }
    }
}

/// Per joint, the thickness of its bones' body part: the median inscribed radius (voxels) over
/// the chain voxels of its segments (0 without any).
fn bone_radius(
    skeleton: &Skeleton,
    distance: &DistanceMap,
    segments: &[SegmentVoxels],
) -> Vec<f64> {
    let mut per: Vec<Vec<f64>> = vec![Vec::new(); skeleton.len()];
    for s in segments {
        per[s.joint.0].extend(s.voxels.iter().map(|&v| distance.distance(v)));
    }
    per.into_iter()
        .map(|r| crate::math::upper_median(r).unwrap_or(0.0))
        .collect()
}

/// One flag per grid voxel: whether it is one of the eight voxels around a vertex.
fn voxels_around_vertices(mesh: &Mesh, solid: &Solid) -> Vec<bool> {
    use std::sync::atomic::{AtomicBool, Ordering};
    let needed: Vec<AtomicBool> = (0..solid.grid.len())
        .map(|_| AtomicBool::new(false))
        .collect();
    mesh.positions.par_iter().with_min_len(4096).for_each(|&p| {
        for (index, _) in corners(&solid.grid, p) {
            needed[index].store(true, Ordering::Relaxed);
        }
    });
    needed.into_iter().map(AtomicBool::into_inner).collect()
}

/// Binds every vertex still without weights to the joint of its nearest segment; returns
/// those vertices.
fn bind_isolated(
    mesh: &Mesh,
    skeleton: &Skeleton,
    segments: &[SegmentVoxels],
    rows: &mut [Row],
) -> Vec<usize> {
    let mut isolated = Vec::new();
    if rows.iter().all(|r| !r.is_empty()) {
        return isolated;
    }
    let lines: Vec<_> = segments.iter().map(|s| s.line(skeleton)).collect();
    for (v, row) in rows.iter_mut().enumerate() {
        if row.is_empty() {
            let p = mesh.positions[v];
            let nearest = nearest_segment(p, &lines).map_or(JointId(0), |s| segments[s].joint);
            *row = Row::EMPTY;
            row.joints[0] = nearest.0 as u32;
            row.weights[0] = 1.0;
            isolated.push(v);
        }
    }
    isolated
}

/// The rows as `(joint, weight)` lists, each pruned with weights under [`NEGLIGIBLE`] cut.
fn vertex_weights(rows: &[Row]) -> Vec<Vec<(JointId, f64)>> {
    rows.par_iter()
        .with_min_len(1024)
        .map(|row| {
            // The row's joints are distinct: what `Mixer::pruned` gives of the same entries.
            let used = row.entries().count();
            prune(&row.joints[..used], &row.weights[..used], NEGLIGIBLE)
                .entries()
                .map(|(j, w)| (JointId(j as usize), w))
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distance::edt;
    use crate::skeleton::canonical::{Canonical, Side};
    use crate::skeleton::Joint;
    use crate::skin::check::{check_deformation, sweep, SweepKind};
    use crate::skin::{deform, skin_from_bones};
    use crate::voxel::{voxelize, VoxelOptions, VoxelSize};
    use glam::DVec3;
    use std::collections::BTreeMap;

    /// A leg: a finely ringed tube from y = 0 to y = 2, hip at the top, knee in the middle,
    /// plus optional loose pieces.
    fn leg(pieces: &[Mesh]) -> (Mesh, Skeleton) {
        let rings: Vec<(f64, f64)> = (0..=60).map(|r| (0.2, 1.0 - r as f64 / 30.0)).collect();
        let mut mesh = Mesh::lathe(DVec3::new(0.0, 1.0, 0.0), 1.0, &rings, -1.0, 16);
        for piece in pieces {
            let offset = mesh.positions.len() as u32;
            mesh.positions.extend(&piece.positions);
            mesh.triangles
                .extend(piece.triangles.iter().map(|t| t.map(|i| i + offset)));
        }
        let skeleton = Skeleton {
            joints: vec![
                Joint::new(
                    Canonical::Hip(Side::Left).as_str(),
                    None,
                    DVec3::new(0.0, 1.95, 0.0),
                ),
                Joint::new(
                    Canonical::Knee(Side::Left).as_str(),
                    Some(JointId(0)),
                    DVec3::new(0.0, 1.0, 0.0),
                ),
                Joint::new(
                    Canonical::Ankle(Side::Left).as_str(),
                    Some(JointId(1)),
                    DVec3::new(0.0, 0.05, 0.0),
                ),
            ],
        };
        (mesh, skeleton)
    }

    fn skin_of(mesh: &Mesh, skeleton: &Skeleton, fraction: f64) -> crate::skin::Skin {
        let options = VoxelOptions {
            size: VoxelSize::Fraction(fraction),
            ..Default::default()
        };
        let solid = voxelize(mesh, &options).unwrap();
        let distance = edt(&solid);
        skin_from_bones(mesh, skeleton, &solid, &distance, &SkinOptions::default()).unwrap()
    }

    #[test]
    fn the_weights_change_gradually_along_the_leg_and_the_knee_bends_cleanly() {
        let (mesh, skeleton) = leg(&[]);
        let skin = skin_of(&mesh, &skeleton, 1.0 / 40.0);
        let weight = |v: usize, j: usize| {
            skin.weights[v]
                .iter()
                .find(|(k, _)| k.0 == j)
                .map_or(0.0, |w| w.1)
        };
        let mut worst_jump = 0.0f64;
        for (a, b) in crate::skin::check::mesh_edges(&mesh) {
            for j in 0..3 {
                worst_jump = worst_jump.max((weight(a as usize, j) - weight(b as usize, j)).abs());
            }
        }
        assert!(
            worst_jump < 0.25,
            "a weight jumps by {worst_jump} across one edge"
        );
        // Far from the knee the leg follows one bone; at the knee both share.
        let near = |y: f64| {
            (0..mesh.positions.len())
                .min_by(|&a, &b| {
                    let da = (mesh.positions[a] - DVec3::new(0.2, y, 0.0)).length();
                    let db = (mesh.positions[b] - DVec3::new(0.2, y, 0.0)).length();
                    da.total_cmp(&db)
                })
                .unwrap()
        };
        assert!(weight(near(1.7), 0) > 0.9, "{:?}", skin.weights[near(1.7)]);
        // The ankle's blend spreads about 4.6 voxels (0.23) up the shin
        // (`voxel_smoothing_iterations`): mid-shin follows the knee's bone alone.
        assert!(weight(near(0.5), 1) > 0.9, "{:?}", skin.weights[near(0.5)]);
        let knee = skin.weights[near(1.0)].clone();
        assert!(
            weight(near(1.0), 0) > 0.2 && weight(near(1.0), 1) > 0.2,
            "{knee:?}"
        );
        let canonical: BTreeMap<String, JointId> = skeleton
            .joints
            .iter()
            .enumerate()
            .map(|(k, j)| (j.name.clone(), JointId(k)))
            .collect();
        let (poses, missing) = sweep(
            &skeleton,
            &canonical,
            SweepKind::Humanoid,
            DVec3::Y,
            DVec3::Z,
        );
        let check = check_deformation(
            &mesh,
            &skeleton,
            &skin.weights,
            SweepKind::Humanoid,
            &poses,
            missing,
        )
        .unwrap();
        assert_eq!(check.total_over_2(), 0, "{check:?}");
    }

    /// A plate on the thigh above the knee (its own piece, every vertex mostly the hip bone.s)
    /// follows the hip's bone alone, rigidly; a sleeve over the knee (its own piece, spanning
    /// the joint) keeps blended weights.
    #[test]
    fn a_piece_within_one_bone_is_bound_rigidly_and_one_across_a_joint_blends() {
        let plate = Mesh::uv_sphere(DVec3::new(0.2, 1.3, 0.0), 0.06, 6, 8);
        let sleeve_rings: Vec<(f64, f64)> =
            (0..=16).map(|r| (0.23, 0.3 - r as f64 / 26.0)).collect();
        let sleeve = Mesh::lathe(DVec3::new(0.0, 1.0, 0.0), 0.32, &sleeve_rings, -0.34, 16);
        let (mesh, skeleton) = leg(&[plate.clone(), sleeve.clone()]);
        let skin = skin_of(&mesh, &skeleton, 1.0 / 40.0);
        let body = mesh.positions.len() - plate.positions.len() - sleeve.positions.len();
        let plate_vertices = body..body + plate.positions.len();
        let sleeve_vertices = body + plate.positions.len()..mesh.positions.len();
        for v in plate_vertices {
            assert_eq!(skin.weights[v], vec![(JointId(0), 1.0)], "plate vertex {v}");
        }
        let blended = sleeve_vertices
            .filter(|&v| skin.weights[v].len() > 1)
            .count();
        assert!(
            blended > 16,
            "the sleeve blends across the knee ({blended} vertices)"
        );
    }

    #[test]
    fn the_dissertation_anchor_weights_tear_the_same_knee() {
        let (mesh, skeleton) = leg(&[]);
        let options = VoxelOptions {
            size: VoxelSize::Fraction(1.0 / 40.0),
            ..Default::default()
        };
        let solid = voxelize(&mesh, &options).unwrap();
        let distance = edt(&solid);
        let anchor = SkinOptions {
            method: crate::skin::SkinMethod::Anchor,
            ..Default::default()
        };
        let skin = skin_from_bones(&mesh, &skeleton, &solid, &distance, &anchor).unwrap();
        let canonical: BTreeMap<String, JointId> = [
            (Canonical::Knee(Side::Left).to_string(), JointId(1)),
            (Canonical::Ankle(Side::Left).to_string(), JointId(2)),
        ]
        .into();
        let (poses, missing) = sweep(
            &skeleton,
            &canonical,
            SweepKind::Humanoid,
            DVec3::Y,
            DVec3::Z,
        );
        let anchor_check = check_deformation(
            &mesh,
            &skeleton,
            &skin.weights,
            SweepKind::Humanoid,
            &poses,
            missing.clone(),
        )
        .unwrap();
        let geodesic = skin_of(&mesh, &skeleton, 1.0 / 40.0);
        let geodesic_check = check_deformation(
            &mesh,
            &skeleton,
            &geodesic.weights,
            SweepKind::Humanoid,
            &poses,
            missing,
        )
        .unwrap();
        assert!(
            geodesic_check.worst() < anchor_check.worst(),
            "geodesic {geodesic_check:?} anchor {anchor_check:?}"
        );
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(16))]
        #[test]
        fn weights_are_a_partition_of_one_on_every_vertex(
            fraction in 1.0f64 / 48.0..1.0 / 16.0,
            knee_x in -0.1f64..0.1,
            piece in proptest::option::of((-1.0f64..1.0, -0.5f64..2.5, 0.02f64..0.2)),
        ) {
            let pieces: Vec<Mesh> = piece
                .map(|(x, y, r)| Mesh::uv_sphere(DVec3::new(x, y, 0.3), r, 6, 8))
                .into_iter()
                .collect();
            let (mesh, mut skeleton) = leg(&pieces);
            skeleton.joints[1].position.x = knee_x;
            let skin = skin_of(&mesh, &skeleton, fraction);
            proptest::prop_assert_eq!(skin.weights.len(), mesh.positions.len());
            for w in &skin.weights {
                proptest::prop_assert!(!w.is_empty() && w.len() <= crate::skin::MAX_ENGINE_INFLUENCES);
                proptest::prop_assert!(w.iter().all(|&(j, x)| x > 0.0 && x.is_finite() && j.0 < 3));
                proptest::prop_assert!((w.iter().map(|x| x.1).sum::<f64>() - 1.0).abs() < 1e-9);
            }
            let rest = deform(&mesh, &skeleton, &skin, &skeleton.rest_pose()).unwrap();
            proptest::prop_assert_eq!(rest, mesh);
        }
    }
}

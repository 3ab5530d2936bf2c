//! Regions of influence: which segments influence each voxel (dissertation 5.2.5, 8.3).

use super::{SegmentVoxels, SkinError, SkinOptions};
use crate::distance::DistanceMap;
use crate::mesh::Mesh;
use crate::voxel::{Grid, Solid};
use rayon::prelude::*;
use std::collections::HashMap;

/// Marker of a voxel without an influence set.
const NONE: u32 = u32::MAX;

/// The set of segments influencing each voxel of a grid.
///
/// Sets are interned: `sets` holds each distinct set once (segment indices ascending) and
/// `set_of` gives, per linear voxel index, the index of its set in `sets` or `u32::MAX` for
/// voxels no segment influences (the exterior away from mesh vertices).
#[derive(Debug, Clone, PartialEq)]
pub struct Influence {
    /// The grid of the solid.
    pub grid: Grid,
    /// Set index per voxel (linear index), `u32::MAX` for none.
    pub set_of: Vec<u32>,
    /// The distinct influence sets, as ascending indices into the segment list.
    pub sets: Vec<Vec<u32>>,
    /// Number of voxels covered directly by the spheres (before propagation).
    pub covered: usize,
}

impl Influence {
    /// The segments influencing voxel `index` (ascending), empty when none does.
    pub fn at(&self, index: usize) -> &[u32] {
        match self.set_of.get(index) {
            Some(&s) if s != NONE => &self.sets[s as usize],
            _ => &[],
        }
    }
}

/// Computes the regions of influence of `segments` on `solid`.
///
/// 1. Coverage: every chain voxel `c` of segment `s` is the centre of a sphere of radius
///    `sphere_scale * sqrt(distance.squared[c])` voxels (the inverse distance transform); every
///    interior voxel whose centre lies strictly inside it is influenced by `s`.
/// 2. Propagation: breadth-first, layer by layer, from the covered voxels into uncovered voxels
///    that are interior, touched by the surface, or contain a vertex of `mesh` (vertices lie on
///    the surface, often in exterior voxels). A voxel reached in a layer receives the union of
///    the sets of its already-labelled neighbours ([`SkinOptions::connectivity`]).
///
/// Every step is independent of the visiting order, so the result is the same on any number
/// of threads.
///
/// # Errors
/// [`SkinError::InvalidOption`] for options out of range, [`SkinError::GridMismatch`] when `distance` belongs to another grid,
/// [`SkinError::VoxelOutOfRange`] for a chain voxel outside the grid,
/// [`SkinError::NoInfluence`] when no segment covers any interior voxel.
pub fn influence(
    solid: &Solid,
    distance: &DistanceMap,
    mesh: &Mesh,
    segments: &[SegmentVoxels],
    options: &SkinOptions,
) -> Result<Influence, SkinError> {
    options.validate()?;
    let grid = solid.grid;
    if distance.grid != grid
        || distance.squared.len() != grid.len()
        || solid.inside.len() != grid.len()
    {
        return Err(SkinError::GridMismatch);
    }
    for (segment, s) in segments.iter().enumerate() {
        if let Some(&voxel) = s.voxels.iter().find(|&&v| v >= grid.len()) {
            return Err(SkinError::VoxelOutOfRange {
                segment,
                voxel,
                voxels: grid.len(),
            });
        }
    }
    let mut pairs = coverage(solid, distance, segments, options.sphere_scale);
    pairs.par_sort_unstable();
    pairs.dedup();
    if pairs.is_empty() {
        return Err(SkinError::NoInfluence);
    }

    let mut interner = Interner::default();
    let mut set_of = vec![NONE; grid.len()];
    let mut frontier = Vec::new();
    for group in pairs.chunk_by(|a, b| a.0 == b.0) {
        let voxel = group[0].0 as usize;
        let set: Vec<u32> = group.iter().map(|&(_, s)| s).collect();
        set_of[voxel] = interner.id(set);
        frontier.push(voxel);
    }
    let covered = frontier.len();

    let mut target: Vec<bool> = (0..grid.len())
        .map(|i| solid.inside[i] || solid.surface.get(i).copied().unwrap_or(false))
        .collect();
    for &p in &mesh.positions {
        if let Some(c) = grid.voxel_at(p) {
            target[grid.index(c)] = true;
        }
    }

    let neighbours = options.connectivity.neighbours();
    while !frontier.is_empty() {
        let mut next: Vec<usize> = frontier
            .par_iter()
            .flat_map_iter(|&v| {
                let c = grid.coords(v);
                neighbours
                    .iter()
                    .filter_map(move |n| grid.offset(c, n.offset))
                    .filter(|&u| target[u])
            })
            .filter(|&u| set_of[u] == NONE)
            .collect();
        next.par_sort_unstable();
        next.dedup();
        let unions: Vec<Vec<u32>> = next
            .par_iter()
            .map(|&u| {
                let c = grid.coords(u);
                let mut set: Vec<u32> = neighbours
                    .iter()
                    .filter_map(|n| grid.offset(c, n.offset))
                    .filter(|&w| set_of[w] != NONE)
                    .flat_map(|w| interner.sets[set_of[w] as usize].iter().copied())
                    .collect();
                set.sort_unstable();
                set.dedup();
                set
            })
            .collect();
        for (&u, set) in next.iter().zip(unions) {
            set_of[u] = interner.id(set);
        }
        frontier = next;
    }
    Ok(Influence {
        grid,
        set_of,
        sets: interner.sets,
        covered,
    })
}

/// `(voxel, segment)` pairs of the interior voxels inside each chain voxel's sphere.
fn coverage(
    solid: &Solid,
    distance: &DistanceMap,
    segments: &[SegmentVoxels],
    sphere_scale: f64,
) -> Vec<(u32, u32)> {
    let grid = solid.grid;
    let scale = sphere_scale;
    segments
        .par_iter()
        .enumerate()
        .flat_map_iter(|(s, segment)| {
            let mut covered: Vec<(u32, u32)> = Vec::new();
            for &c in &segment.voxels {
                let radius_sq = distance.squared[c] as f64 * scale * scale;
                if radius_sq <= 0.0 {
                    continue;
                }
                let r = radius_sq.sqrt().ceil() as i64;
                let centre = grid.coords(c);
                for dz in -r..=r {
                    for dy in -r..=r {
                        for dx in -r..=r {
                            let d2 = (dx * dx + dy * dy + dz * dz) as f64;
                            if d2 >= radius_sq {
                                continue;
                            }
                            let offset = [dx as i32, dy as i32, dz as i32];
                            if let Some(v) = grid.offset(centre, offset) {
                                if solid.inside[v] {
                                    covered.push((v as u32, s as u32));
                                }
                            }
                        }
                    }
                }
            }
            covered.sort_unstable();
            covered.dedup();
            covered
        })
        .collect()
}

/// Assigns each distinct set an index in order of first appearance.
#[derive(Default)]
struct Interner {
    sets: Vec<Vec<u32>>,
    ids: HashMap<Vec<u32>, u32>,
}

impl Interner {
    fn id(&mut self, set: Vec<u32>) -> u32 {
        if let Some(&id) = self.ids.get(&set) {
            return id;
        }
        let id = self.sets.len() as u32;
        self.sets.push(set.clone());
        self.ids.insert(set, id);
        id
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distance::edt;
    use crate::skeleton::JointId;
    use crate::voxel::{voxelize, VoxelOptions, VoxelSize};
    use glam::DVec3;

    fn cube() -> (Mesh, Solid, DistanceMap) {
        let mesh = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        let options = VoxelOptions {
            size: VoxelSize::Fraction(1.0 / 20.0),
            ..Default::default()
        };
        let solid = voxelize(&mesh, &options).unwrap();
        let distance = edt(&solid);
        (mesh, solid, distance)
    }

    fn segment(solid: &Solid, at: DVec3, joint: usize) -> SegmentVoxels {
        let c = solid.grid.voxel_at(at).unwrap();
        SegmentVoxels {
            joint: JointId(joint),
            child: None,
            tip: None,
            voxels: vec![solid.grid.index(c)],
        }
    }

    #[test]
    fn one_central_sphere_influences_the_whole_cube_and_its_vertices() {
        let (mesh, solid, distance) = cube();
        let centre = segment(&solid, DVec3::splat(0.5), 0);
        let influence =
            influence(&solid, &distance, &mesh, &[centre], &SkinOptions::default()).unwrap();
        // The ball of radius ~10 voxels covers about half the cube; propagation does the rest.
        assert!(influence.covered > 1000 && influence.covered < solid.interior_count());
        for i in solid.interior_indices() {
            assert_eq!(influence.at(i), &[0]);
        }
        for &p in &mesh.positions {
            let c = solid.grid.voxel_at(p).unwrap();
            assert_eq!(influence.at(solid.grid.index(c)), &[0], "vertex at {p}");
        }
    }

    #[test]
    fn two_spheres_split_the_cube_and_meet_in_the_middle() {
        let (mesh, solid, distance) = cube();
        let segments = [
            segment(&solid, DVec3::new(0.275, 0.525, 0.525), 0),
            segment(&solid, DVec3::new(0.725, 0.525, 0.525), 1),
        ];
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| {
                    influence(&solid, &distance, &mesh, &segments, &SkinOptions::default()).unwrap()
                })
        };
        let influence = run(1);
        assert_eq!(influence, run(3), "same result on any number of threads");
        let at = |p: DVec3| influence.at(solid.grid.index(solid.grid.voxel_at(p).unwrap()));
        assert_eq!(at(DVec3::new(0.125, 0.525, 0.525)), &[0]);
        assert_eq!(at(DVec3::new(0.875, 0.525, 0.525)), &[1]);
        assert_eq!(at(DVec3::new(0.525, 0.975, 0.525)), &[0, 1]);
        assert!(influence
            .sets
            .iter()
            .all(|s| [&[0][..], &[1], &[0, 1]].contains(&s.as_slice())));
    }

    #[test]
    fn bad_input_is_an_error() {
        let (mesh, solid, distance) = cube();
        let mut far = segment(&solid, DVec3::splat(0.5), 0);
        far.voxels = vec![solid.grid.len()];
        let options = SkinOptions::default();
        assert!(matches!(
            influence(&solid, &distance, &mesh, &[far], &options),
            Err(SkinError::VoxelOutOfRange { .. })
        ));
        assert_eq!(
            influence(&solid, &distance, &mesh, &[], &options),
            Err(SkinError::NoInfluence)
        );
        let bad = SkinOptions {
            sphere_scale: f64::NAN,
            ..options
        };
        let centre = segment(&solid, DVec3::splat(0.5), 0);
        assert!(matches!(
            influence(&solid, &distance, &mesh, &[centre], &bad),
            Err(SkinError::InvalidOption {
                name: "sphere_scale",
                ..
            })
        ));
    }
}

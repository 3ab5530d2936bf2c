//! Regions of influence: which segments influence each voxel (dissertation 5.2.5, 8.3).

use super::neighbourhood::Neighbourhood;
use super::{SegmentVoxels, SkinError, SkinOptions};
use crate::distance::DistanceMap;
use crate::mesh::Mesh;
use crate::voxel::{Grid, Solid};
use rayon::prelude::*;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU8, Ordering};

/// Marker of a voxel without an influence set.
const NONE: u32 = u32::MAX;

/// Number of slabs of consecutive voxels in which the covered voxels' sets are built in
/// parallel.
const SLABS: usize = 16;

/// Propagation states: not to be reached (not a target, or covered), not reached yet,
/// queued into a layer.
const BLOCKED: u8 = 0;
const OPEN: u8 = 1;
const TAKEN: u8 = 2;

/// Propagation layers smaller than this run on the calling thread: the thread-pool overhead
/// would exceed the work (layers through hands and feet are a few hundred voxels each). Both
/// paths compute the same sets.
const SEQUENTIAL_LAYER: usize = 4096;

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
    let lists = coverage(solid, distance, segments, options.sphere_scale);
    if lists.iter().all(Vec::is_empty) {
        return Err(SkinError::NoInfluence);
    }
    let (mut set_of, mut interner, covered) = covered_sets(&grid, &lists);
    let state = propagation_targets(solid, mesh, &set_of);
    let around = Neighbourhood::new(grid, options.connectivity.neighbours());
    propagate(&around, &state, &mut set_of, &mut interner);
    Ok(Influence {
        grid,
        set_of,
        sets: interner.sets,
        covered,
    })
}

/// The interned influence set of every voxel the spheres cover (`lists`: per segment, its
/// covered voxels ascending), `NONE` elsewhere, with the interner and the number of covered
/// voxels.
fn covered_sets(grid: &Grid, lists: &[Vec<u32>]) -> (Vec<u32>, Interner, usize) {
    // Each voxel's set grows segment by segment (ascending), through memoised transitions
    // (set, segment) -> set, in slabs of consecutive voxels (in parallel, each with its own
    // numbering); then the sets are renumbered in order of first appearance in voxel order,
    // so the result does not depend on how the work was split.
    let slab = grid.len().div_ceil(SLABS).max(1);
    let mut set_of = vec![NONE; grid.len()];
    let scratch: Vec<Interner> = set_of
        .par_chunks_mut(slab)
        .enumerate()
        .map(|(k, out)| {
            let first = (k * slab) as u32;
            let end = first + out.len() as u32;
            let mut scratch = Interner::default();
            let mut transitions: HashMap<(u32, u32), u32> = HashMap::new();
            for (s, list) in lists.iter().enumerate() {
                let s = s as u32;
                let from = list.partition_point(|&v| v < first);
                let to = list.partition_point(|&v| v < end);
                let mut last: Option<(u32, u32)> = None;
                for &v in &list[from..to] {
                    let at = &mut out[(v - first) as usize];
                    let old = *at;
                    *at = match last {
                        Some((from, to)) if from == old => to,
                        _ => {
                            let to = *transitions.entry((old, s)).or_insert_with(|| {
                                let mut set = if old == NONE {
                                    Vec::new()
                                } else {
                                    scratch.sets[old as usize].clone()
                                };
                                set.push(s);
                                scratch.id(&set)
                            });
                            last = Some((old, to));
                            to
                        }
                    };
                }
            }
            scratch
        })
        .collect();
    let mut interner = Interner::default();
    let mut covered = 0;
    for (ids, scratch) in set_of.chunks_mut(slab).zip(&scratch) {
        let mut renumber = vec![NONE; scratch.sets.len()];
        for id in ids.iter_mut() {
            if *id != NONE {
                if renumber[*id as usize] == NONE {
                    renumber[*id as usize] = interner.id(&scratch.sets[*id as usize]);
                }
                *id = renumber[*id as usize];
                covered += 1;
            }
        }
    }

    (set_of, interner, covered)
}

/// Propagation state per voxel: `OPEN` for the uncovered voxels that are interior, on the
/// surface or hold a vertex of `mesh`, `BLOCKED` for the rest.
fn propagation_targets(solid: &Solid, mesh: &Mesh, set_of: &[u32]) -> Vec<AtomicU8> {
    let grid = solid.grid;
    // Propagation state per voxel: OPEN for targets no layer has reached yet (uncovered
    // voxels that are interior, on the surface or hold a vertex), BLOCKED for the rest. A
    // voxel is TAKEN when it is queued into a layer, by exactly one thread.
    let state: Vec<AtomicU8> = (0..grid.len())
        .into_par_iter()
        .with_min_len(1 << 16)
        .map(|i| {
            let target = solid.inside[i] || solid.surface.get(i).copied().unwrap_or(false);
            AtomicU8::new(if target && set_of[i] == NONE {
                OPEN
            } else {
                BLOCKED
            })
        })
        .collect();
    for &p in &mesh.positions {
        if let Some(c) = grid.voxel_at(p) {
            let i = grid.index(c);
            if set_of[i] == NONE {
                state[i].store(OPEN, Ordering::Relaxed);
            }
        }
    }

    state
}

/// Breadth-first propagation, layer by layer, from the labelled voxels into the `OPEN` ones:
/// a voxel reached in a layer receives the union of the sets of its already-labelled
/// neighbours.
fn propagate(
    around: &Neighbourhood,
    state: &[AtomicU8],
    set_of: &mut [u32],
    interner: &mut Interner,
) {
    let grid_len = set_of.len();
    // The first layer is found from the unlabelled side: the covered voxels are most of the
    // interior, the uncovered targets a thin shell, so scanning the shell is far cheaper.
    let mut next: Vec<usize> = (0..grid_len)
        .into_par_iter()
        .with_min_len(4096)
        .filter(|&u| {
            state[u].load(Ordering::Relaxed) == OPEN && around.any(u, |w| set_of[w] != NONE)
        })
        .collect();
    for &u in &next {
        state[u].store(TAKEN, Ordering::Relaxed);
    }
    while !next.is_empty() {
        // One pass over each voxel's neighbours: its new set, the union of its labelled
        // neighbours' sets (as an existing set id when all of them share one, the common
        // case, else as a new list), and the open neighbours it queues for the next layer.
        // Voxels of this layer are still unlabelled here, so they do not see each other.
        let step = |u: usize, grown: &mut Vec<usize>| -> Result<u32, Vec<u32>> {
            let mut ids = [NONE; 26];
            let mut count = 0;
            around.for_each(u, |w| {
                let id = set_of[w];
                if id != NONE {
                    if !ids[..count].contains(&id) {
                        ids[count] = id;
                        count += 1;
                    }
                } else if state[w].load(Ordering::Relaxed) == OPEN
                    && state[w]
                        .compare_exchange(OPEN, TAKEN, Ordering::Relaxed, Ordering::Relaxed)
                        .is_ok()
                {
                    grown.push(w);
                }
            });
            if count == 1 {
                return Ok(ids[0]);
            }
            let ids = &ids[..count];
            let mut set: Vec<u32> = ids
                .iter()
                .flat_map(|&id| interner.sets[id as usize].iter().copied())
                .collect();
            set.sort_unstable();
            set.dedup();
            Err(set)
        };
        let run = |layer: &[usize]| {
            let mut grown = Vec::new();
            let unions: Vec<Result<u32, Vec<u32>>> =
                layer.iter().map(|&u| step(u, &mut grown)).collect();
            (unions, grown)
        };
        // Which thread queues a voxel varies, the sorted layer does not.
        let parts = if next.len() < SEQUENTIAL_LAYER {
            vec![run(&next)]
        } else {
            next.par_chunks(1024).map(run).collect()
        };
        let mut grown = Vec::new();
        let mut layer = next.iter();
        for (unions, part) in parts {
            for (set, &u) in unions.into_iter().zip(&mut layer) {
                set_of[u] = match set {
                    Ok(id) => id,
                    Err(set) => interner.id(&set),
                };
            }
            grown.extend(part);
        }
        if grown.len() < SEQUENTIAL_LAYER {
            grown.sort_unstable();
        } else {
            grown.par_sort_unstable();
        }
        next = grown;
    }
}

/// Per segment, the interior voxels inside its chain voxels' spheres, ascending.
///
/// The spheres of neighbouring chain voxels overlap almost entirely, so instead of visiting
/// every voxel of every sphere (`O(r^3)` per chain voxel) each sphere contributes one x-span per
/// grid row it crosses (`O(r^2)`), set as a run of bits in a bit mask over the segment's
/// bounding box (a word or two per span); the union is then read off the mask once, in voxel
/// order.
fn coverage(
    solid: &Solid,
    distance: &DistanceMap,
    segments: &[SegmentVoxels],
    sphere_scale: f64,
) -> Vec<Vec<u32>> {
    let grid = solid.grid;
    let [nx, ny, nz] = grid.dims.map(|d| d as i64);
    segments
        .par_iter()
        .map(|segment| {
            // The spheres: centre and squared radius, with the bounding box of them all.
            let spheres: Vec<([i64; 3], f64)> = segment
                .voxels
                .iter()
                .map(|&c| {
                    let radius_sq = distance.squared[c] as f64 * sphere_scale * sphere_scale;
                    (grid.coords(c).map(|v| v as i64), radius_sq)
                })
                .filter(|&(_, radius_sq)| radius_sq > 0.0)
                .collect();
            if spheres.is_empty() {
                return Vec::new();
            }
            let mut low = [i64::MAX; 3];
            let mut high = [i64::MIN; 3];
            for &(c, radius_sq) in &spheres {
                let r = radius_sq.sqrt().ceil() as i64;
                for a in 0..3 {
                    low[a] = low[a].min((c[a] - r).max(0));
                    high[a] = high[a].max((c[a] + r).min(grid.dims[a] as i64 - 1));
                }
            }
            let words = ((high[0] - low[0] + 1) as usize).div_ceil(64);
            let rows_y = (high[1] - low[1] + 1) as usize;
            let rows = rows_y * (high[2] - low[2] + 1) as usize;
            let mut mask = vec![0u64; rows * words];
            for &(c, radius_sq) in &spheres {
                let r = radius_sq.sqrt().ceil() as i64;
                let [cx, cy, cz] = c;
                for z in (cz - r).max(0)..=(cz + r).min(nz - 1) {
                    let dz = z - cz;
                    for y in (cy - r).max(0)..=(cy + r).min(ny - 1) {
                        let dy = y - cy;
                        // Voxels strictly inside: dx^2 < rest.
                        let rest = radius_sq - (dy * dy + dz * dz) as f64;
                        if rest <= 0.0 {
                            continue;
                        }
                        let mut w = rest.sqrt().floor() as i64;
                        while (((w + 1) * (w + 1)) as f64) < rest {
                            w += 1;
                        }
                        while w >= 0 && ((w * w) as f64) >= rest {
                            w -= 1;
                        }
                        if w < 0 {
                            continue;
                        }
                        let (x0, x1) = ((cx - w).max(0), (cx + w).min(nx - 1));
                        if x0 <= x1 {
                            let row = (y - low[1]) as usize + rows_y * (z - low[2]) as usize;
                            let bits = &mut mask[row * words..(row + 1) * words];
                            set_bits(bits, (x0 - low[0]) as usize, (x1 - low[0]) as usize);
                        }
                    }
                }
            }
            let mut covered: Vec<u32> = Vec::new();
            for (row, bits) in mask.chunks_exact(words).enumerate() {
                let (y, z) = (
                    low[1] as usize + row % rows_y,
                    low[2] as usize + row / rows_y,
                );
                let base = grid.index([low[0] as usize, y, z]);
                for (k, &word) in bits.iter().enumerate() {
                    let mut word = word;
                    while word != 0 {
                        let v = base + 64 * k + word.trailing_zeros() as usize;
                        word &= word - 1;
                        if solid.inside[v] {
                            covered.push(v as u32);
                        }
                    }
                }
            }
            covered
        })
        .collect()
}

/// Sets bits `first..=last` of a bit string stored in little-endian words.
fn set_bits(words: &mut [u64], first: usize, last: usize) {
    let (a, b) = (first / 64, last / 64);
    let low = u64::MAX << (first % 64);
    let high = u64::MAX >> (63 - last % 64);
    if a == b {
        words[a] |= low & high;
    } else {
        words[a] |= low;
        for word in &mut words[a + 1..b] {
            *word = u64::MAX;
        }
        words[b] |= high;
    }
}

/// Assigns each distinct set an index in order of first appearance.
#[derive(Default)]
struct Interner {
    sets: Vec<Vec<u32>>,
    ids: HashMap<Vec<u32>, u32>,
}

impl Interner {
    fn id(&mut self, set: &[u32]) -> u32 {
        if let Some(&id) = self.ids.get(set) {
            return id;
        }
        let id = self.sets.len() as u32;
        self.sets.push(set.to_vec());
        self.ids.insert(set.to_vec(), id);
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
    fn set_bits_sets_exactly_the_range() {
        for (first, last) in [
            (0, 0),
            (3, 9),
            (0, 63),
            (63, 64),
            (5, 130),
            (64, 127),
            (70, 191),
        ] {
            let mut words = [0u64; 3];
            set_bits(&mut words, first, last);
            for bit in 0..192 {
                let set = words[bit / 64] >> (bit % 64) & 1 == 1;
                assert_eq!(
                    set,
                    (first..=last).contains(&bit),
                    "{first}..={last} bit {bit}"
                );
            }
        }
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

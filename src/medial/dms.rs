//! Extraction of the discrete medial surface from the distance map (dissertation ch.4.3).

use super::bridging::{ascent, bridge, AdjacentGroups};
use super::contour::{ContourArrays, Levels};
use super::exposure::{exposure_from_largest, voxel_exposure};
use super::neighbourhood::{
    checked_interior_count, LinearNeighbours, ADJACENCY_CLASSES, CLASS_LENGTHS, NEIGHBOUR_COUNT,
};
use super::record::{Label, VoxelRecord};
use super::surface::{DmsKind, MedialSurface, NOT_MEDIAL};
use super::union_find::UnionFind;
use super::{MedialError, MedialOptions, MedialWarning};
use crate::distance::DistanceMap;
use rayon::prelude::*;

/// Typical range of useful exposure thresholds (ch.4.4: "threshold values above 1.0 or below
/// roughly 0.25 typically do not result in useful DMA/DMSs"); outside it [`dms`] warns.
const USEFUL_THRESHOLDS: std::ops::RangeInclusive<f64> = 0.25..=1.0;

/// Computes the discrete medial surface (DMS) of the figure described by `distance`
/// (dissertation ch.4).
///
/// `distance`: exact squared Euclidean distances in voxel units, 0 outside the figure, with at
/// least one exterior layer on every side of the grid (as [`edt`](crate::distance::edt) of a
/// [`voxelize`](crate::voxel::voxelize)d solid gives).
///
/// The phases:
/// 1. contour lists: interior voxels in decreasing distance order (counting sort, ch.4.5);
/// 2. each contour list is processed through its contour arrays, most processed neighbours
///    first. A processed voxel's local exposure ([`exposure`](super::exposure), ch.4.2) is
///    computed from the neighbour values read anyway. The voxel joins the union-find groups of
///    its processed 26-neighbours and records its steepest-ascent neighbour. With no adjacent
///    group it starts a group and is a DMS voxel; with one, it is a true DMS voxel if its
///    exposure meets the threshold, and a bridging path along steepest ascent connects it to
///    its group's DMS; with several, it is a saddle point, a DMS voxel whatever its exposure,
///    bridged into every group before the groups merge (ch.4.3).
/// 3. the labelled voxels are collected into a [`MedialSurface`].
///
/// Each group's DMS voxels stay 26-connected throughout, so the DMS of a 26-connected figure
/// is 26-connected. The time is `O(n lg n)` in the `n` interior voxels (path halving without
/// ranks; linear in practice) plus linear scans of the grid; working memory is an 8-byte
/// record per grid voxel (plus the output's 4-byte lookup). The processing is sequential
/// (only the per-voxel distance levels are computed in parallel), so the result is the same
/// on any number of threads.
///
/// Interpretation choices where ch.4 leaves room (see also [`MedialOptions`]):
/// - "1" voxels (ch.4.4) are those with squared distance exactly 1. With
///   [`MedialOptions::ignore_distance_one`] they are never true DMS voxels; saddle points
///   among them are bridging DMS voxels, and bridging paths may pass through them.
/// - The first voxel of a group is always a DMS voxel (true if its exposure suffices,
///   otherwise bridging), so that bridging paths always end; with thresholds at most 1 this
///   only affects ignored "1" voxels, i.e. figures nowhere thicker than about two voxels.
/// - A saddle point is a true DMS voxel when its own exposure suffices, bridging otherwise.
/// - Steepest ascent uses processed neighbours only; ties prefer a neighbour already in the
///   DMS, then faces over edges over corners.
/// - Ties in the contour order: ascending voxel index; within a contour array, last in first
///   out.
///
/// # Errors
/// [`MedialError::InvalidExposureThreshold`] for options out of range; for an unusable
/// distance map, [`MedialError::SizeMismatch`], [`MedialError::GridTooLarge`],
/// [`MedialError::EmptyFigure`] or [`MedialError::InteriorOnBorder`].
///
/// A degenerate figure is not an error: when every interior voxel is an ignored "1" voxel (a
/// figure one or two voxels thick, or a single voxel) the DMS is the single voxel that started
/// the only group, and [`MedialSurface::warnings`] says to use a smaller voxel size.
pub fn dms(distance: &DistanceMap, options: &MedialOptions) -> Result<MedialSurface, MedialError> {
    options.validate()?;
    let interior = checked_interior_count(distance)?;
    let levels = Levels::new(&distance.squared, interior)?;
    let order = levels.contour_order(&distance.squared);
    let mut extraction = Extraction::new(distance, levels, options);
    for contour in
        order.chunk_by(|&a, &b| distance.squared[a as usize] == distance.squared[b as usize])
    {
        extraction.process_contour(contour);
    }
    Ok(extraction.finish(distance, interior))
}

/// The state of the extraction while the contours are processed.
struct Extraction {
    options: MedialOptions,
    neighbours: LinearNeighbours,
    /// The distinct distances: records hold levels, slopes and exposures need the values.
    levels: Levels,
    /// Per grid voxel: the bookkeeping of ch.4.3, with the union-find of the groups of
    /// 26-connected processed voxels threaded through it.
    voxels: UnionFind,
    contour: ContourArrays,
    /// The groups adjacent to the voxel being processed (reused from voxel to voxel).
    adjacent: AdjacentGroups,
    saddles: Vec<usize>,
    /// Group founders whose exposure did not meet the threshold.
    forced_founders: usize,
}

impl Extraction {
    fn new(distance: &DistanceMap, levels: Levels, options: &MedialOptions) -> Self {
        let voxels = UnionFind::new(
            distance
                .squared
                .par_iter()
                .with_min_len(1 << 16)
                .map(|&s| levels.level(s)),
        );
        Self {
            options: *options,
            neighbours: LinearNeighbours::new(&distance.grid),
            levels,
            voxels,
            contour: ContourArrays::new(),
            adjacent: AdjacentGroups::new(),
            saddles: Vec::new(),
            forced_founders: 0,
        }
    }

    /// Processes one contour list through its contour arrays.
    fn process_contour(&mut self, contour: &[u32]) {
        self.contour.fill(contour, &mut self.voxels);
        while let Some(voxel) = self.contour.pop() {
            self.process_voxel(voxel as usize);
        }
    }

    /// Processes one voxel: one pass over its neighbours gathers the adjacent groups with
    /// their steepest-ascent neighbours and the largest neighbour distances per adjacency
    /// class (for the exposure) and notifies the unprocessed neighbours; then the three cases
    /// of ch.4.3 (no, one, several adjacent groups).
    fn process_voxel(&mut self, voxel: usize) {
        let level = self.voxels.item(voxel).level();
        let radius = self.levels.roots[level as usize];
        // All 26 records are read up front: independent loads that the processor overlaps
        // (the neighbourhood is rarely in cache). Only the levels, labels and processed
        // counts of this copy are used, and the loop below changes none of those except the
        // count of the neighbour it is at.
        let around: [VoxelRecord; NEIGHBOUR_COUNT] =
            std::array::from_fn(|k| self.voxels.item(self.neighbours.at(voxel, k)));
        let adjacent = &mut self.adjacent;
        adjacent.clear();
        let mut largest = [0u32; 3];
        for (class, range) in ADJACENCY_CLASSES.iter().enumerate() {
            for k in range.clone() {
                let record = around[k];
                let n_level = record.level();
                largest[class] = largest[class].max(n_level);
                if n_level == 0 {
                    continue;
                }
                let n = self.neighbours.at(voxel, k);
                match record.label() {
                    Label::Unprocessed => {
                        let from = record.processed();
                        self.voxels.item_mut(n).count_processed();
                        if n_level == level {
                            self.contour.promote(n as u32, from, &mut self.voxels);
                        }
                    }
                    label => {
                        let root = self.voxels.find(n);
                        let slope = ascent(
                            radius,
                            self.levels.roots[n_level as usize],
                            CLASS_LENGTHS[class],
                        );
                        adjacent.offer(root, n, k, slope, label.is_medial());
                    }
                }
            }
        }
        let squared = self.levels.values[level as usize];
        let ignored = self.options.ignore_distance_one && squared == 1;
        let sufficient = !ignored
            && exposure_from_largest(squared, largest.map(|l| self.levels.values[l as usize]))
                >= self.options.exposure_threshold;
        let medial = if sufficient {
            Label::True
        } else {
            Label::Bridging
        };
        match self.adjacent.len() {
            0 => {
                if !sufficient {
                    self.forced_founders += 1;
                }
                self.voxels
                    .item_mut(voxel)
                    .process(medial, None, voxel as u32);
            }
            1 => {
                // Joins the group: linked straight under its root.
                let (root, step, direction) = self.adjacent.groups().next().expect("one group");
                let label = if sufficient {
                    Label::True
                } else {
                    Label::NonMedial
                };
                self.voxels
                    .item_mut(voxel)
                    .process(label, Some(direction as usize), root as u32);
                if sufficient {
                    bridge(step, &mut self.voxels, &self.neighbours);
                }
            }
            _ => {
                let pointer = self.adjacent.steepest().map(|d| d as usize);
                self.voxels
                    .item_mut(voxel)
                    .process(medial, pointer, voxel as u32);
                self.saddles.push(voxel);
                for (root, step, _) in self.adjacent.groups() {
                    bridge(step, &mut self.voxels, &self.neighbours);
                    self.voxels.union(voxel, root);
                }
            }
        }
    }

    /// Collects the labelled voxels into the output.
    fn finish(mut self, distance: &DistanceMap, interior_voxels: usize) -> MedialSurface {
        let len = distance.squared.len();
        let mut voxels = Vec::new();
        let mut kinds = Vec::new();
        let mut slots = vec![NOT_MEDIAL; len];
        for (index, record) in self.voxels.items().iter().enumerate() {
            let kind = match record.label() {
                Label::True => DmsKind::True,
                Label::Bridging => DmsKind::Bridging,
                _ => continue,
            };
            slots[index] = voxels.len() as u32;
            voxels.push(index);
            kinds.push(kind);
        }
        let exposure = voxels
            .iter()
            .map(|&i| voxel_exposure(&distance.squared, i, &self.neighbours))
            .collect();
        let squared = voxels.iter().map(|&i| distance.squared[i]).collect();
        // Components numbered in order of their smallest voxel (lookups only: deterministic).
        let mut root_id = std::collections::HashMap::new();
        let component = voxels
            .iter()
            .map(|&i| {
                let root = self.voxels.find(i);
                let next = root_id.len() as u32;
                *root_id.entry(root).or_insert(next)
            })
            .collect();
        let components = root_id.len();
        self.saddles.sort_unstable();
        let warnings = self.warnings(voxels.len(), components, interior_voxels);
        MedialSurface {
            grid: distance.grid,
            voxels,
            kinds,
            exposure,
            squared,
            component,
            components,
            saddles: self.saddles,
            slots,
            exposure_threshold: self.options.exposure_threshold,
            interior_voxels,
            warnings,
        }
    }

    /// Warnings about the result: an unusual threshold, a degenerate DMS, several parts.
    fn warnings(
        &self,
        dms_voxels: usize,
        components: usize,
        interior: usize,
    ) -> Vec<MedialWarning> {
        let mut warnings = Vec::new();
        let threshold = self.options.exposure_threshold;
        if !USEFUL_THRESHOLDS.contains(&threshold) {
            warnings.push(MedialWarning::UnusualThreshold {
                threshold,
                useful: USEFUL_THRESHOLDS,
            });
        }
        if dms_voxels == 1 {
            warnings.push(MedialWarning::SingleVoxel {
                interior_voxels: interior,
            });
        } else if self.forced_founders > 0 {
            warnings.push(MedialWarning::ForcedFounders {
                count: self.forced_founders,
            });
        }
        if components > 1 {
            warnings.push(MedialWarning::SeveralComponents { components });
        }
        warnings
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::medial::testing::{box_map, distance_map, interior_components};
    use crate::medial::DmsKind;
    use glam::DVec3;
    use proptest::prelude::*;

    /// Structural invariants every result must satisfy.
    fn assert_invariants(distance: &DistanceMap, surface: &MedialSurface, options: &MedialOptions) {
        let n = surface.len();
        assert!(n > 0);
        assert!(surface.voxels.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(surface.kinds.len(), n);
        assert_eq!(surface.exposure.len(), n);
        assert_eq!(surface.squared.len(), n);
        assert_eq!(surface.component.len(), n);
        for (p, &i) in surface.voxels.iter().enumerate() {
            assert_eq!(surface.position(i), Some(p));
            assert!(distance.squared[i] > 0, "DMS voxel outside the figure");
            assert_eq!(surface.squared[p], distance.squared[i]);
            if surface.kinds[p] == DmsKind::True {
                assert!(surface.exposure[p] >= options.exposure_threshold);
                assert!(!(options.ignore_distance_one && surface.squared[p] == 1));
            }
        }
        let members = (0..distance.grid.len())
            .filter(|&i| surface.contains(i))
            .count();
        assert_eq!(members, n);
        assert!(surface.saddles.iter().all(|&s| surface.contains(s)));
        assert_eq!(surface.components, interior_components(distance));
        assert_eq!(
            surface.connected_component_sizes().len(),
            surface.components,
            "each part's DMS must be one 26-connected component"
        );
    }

    #[test]
    fn box_dms_is_one_connected_surface_containing_the_centre_plane() {
        for size in [[12, 7, 16], [12, 8, 16]] {
            let distance = box_map(size);
            let options = MedialOptions::default();
            let surface = dms(&distance, &options).unwrap();
            assert_invariants(&distance, &surface, &options);
            assert_eq!(surface.components, 1);
            assert!(surface.warnings.is_empty(), "{:?}", surface.warnings);
            // The centre plane(s) of the thinnest side, away from the box's edges.
            let grid = distance.grid;
            let planes: Vec<usize> = if size[1] % 2 == 1 {
                vec![1 + size[1] / 2]
            } else {
                vec![size[1] / 2, size[1] / 2 + 1]
            };
            for y in planes {
                for x in 5..=size[0] - 4 {
                    for z in 5..=size[2] - 4 {
                        assert!(surface.contains(grid.index([x, y, z])), "{:?}", [x, y, z]);
                    }
                }
            }
            // A surface, not a volume.
            let interior: usize = size.iter().product();
            assert!(
                surface.len() * 3 < interior,
                "{} of {interior}",
                surface.len()
            );
        }
    }

    /// Regression: exposures of plateau voxels rounded to just below 1.0, so a threshold of 1.0
    /// dropped them and forced group founders.
    #[test]
    fn threshold_one_keeps_plateau_voxels_true() {
        let distance = box_map([9, 7, 11]);
        let options = MedialOptions {
            exposure_threshold: 1.0,
            ..Default::default()
        };
        let surface = dms(&distance, &options).unwrap();
        assert_invariants(&distance, &surface, &options);
        assert!(surface.warnings.is_empty(), "{:?}", surface.warnings);
        let centre = surface.position(distance.grid.index([5, 4, 6])).unwrap();
        assert_eq!(surface.exposure[centre], 1.0);
        assert_eq!(surface.kinds[centre], DmsKind::True);
    }

    #[test]
    fn single_interior_voxel_gives_a_single_voxel_dms_with_a_warning() {
        let distance = box_map([1, 1, 1]);
        let surface = dms(&distance, &MedialOptions::default()).unwrap();
        assert_eq!(surface.voxels, vec![distance.grid.index([1, 1, 1])]);
        assert_eq!(surface.kinds, vec![DmsKind::Bridging]);
        assert!((surface.exposure[0] - 2.0).abs() < 1e-12);
        assert!(surface
            .warnings
            .iter()
            .any(|w| matches!(w, MedialWarning::SingleVoxel { .. })));
    }

    #[test]
    fn one_voxel_thick_plate_gives_a_single_voxel_dms_with_a_warning() {
        let distance = box_map([9, 1, 6]);
        let options = MedialOptions::default();
        let surface = dms(&distance, &options).unwrap();
        assert_invariants(&distance, &surface, &options);
        assert_eq!(surface.len(), 1);
        assert!(surface
            .warnings
            .iter()
            .any(|w| w.to_string().contains("smaller voxel size")));
        // Without the "1" voxel handling the plate's exposed voxels count.
        let options = MedialOptions {
            ignore_distance_one: false,
            ..Default::default()
        };
        let surface = dms(&distance, &options).unwrap();
        assert_invariants(&distance, &surface, &options);
        assert!(surface.len() > 1);
    }

    #[test]
    fn dumbbell_groups_meet_at_a_saddle_in_the_neck() {
        // Two balls of radius 6 joined along x by a neck that is narrowest (radius 2.5) in the
        // middle, so the distance map has a saddle there.
        let (left, right) = (DVec3::new(8.0, 9.0, 9.0), DVec3::new(26.0, 9.0, 9.0));
        let middle = 0.5 * (left.x + right.x);
        let distance = distance_map([34, 18, 18], |p| {
            let radius = 2.5 + 0.3 * (p.x - middle).abs();
            let bar = (p.x > left.x && p.x < right.x)
                && DVec3::new(0.0, p.y - 9.0, p.z - 9.0).length() < radius;
            (p - left).length() < 6.0 || (p - right).length() < 6.0 || bar
        });
        let options = MedialOptions::default();
        let surface = dms(&distance, &options).unwrap();
        assert_invariants(&distance, &surface, &options);
        assert_eq!(surface.components, 1);
        let grid = distance.grid;
        // The groups grown from the two ball centres merge at the neck's narrowest part.
        let at_waist = |i: usize| (grid.centre(grid.coords(i)).x - middle).abs() <= 2.0;
        let saddles: Vec<[usize; 3]> = surface.saddles.iter().map(|&s| grid.coords(s)).collect();
        assert!(surface.saddles.iter().any(|&s| at_waist(s)), "{saddles:?}");
        // The DMS runs through the whole neck.
        for x in (left.x as usize + 6)..(right.x as usize - 6) {
            assert!(
                surface.voxels.iter().any(|&i| grid.coords(i)[0] == x),
                "no DMS voxel in the neck slice x = {x}"
            );
        }
    }

    #[test]
    fn separate_parts_give_one_component_each_and_a_warning() {
        let distance = distance_map([24, 12, 12], |p| {
            (p - DVec3::new(6.0, 6.0, 6.0)).length() < 4.5
                || (p - DVec3::new(17.0, 6.0, 6.0)).length() < 4.5
        });
        let options = MedialOptions::default();
        let surface = dms(&distance, &options).unwrap();
        assert_invariants(&distance, &surface, &options);
        assert_eq!(surface.components, 2);
        assert!(surface
            .warnings
            .contains(&MedialWarning::SeveralComponents { components: 2 }));
    }

    #[test]
    fn out_of_range_threshold_is_an_error() {
        let distance = box_map([3, 3, 3]);
        let options = MedialOptions {
            exposure_threshold: 3.0,
            ..Default::default()
        };
        assert_eq!(
            dms(&distance, &options).unwrap_err(),
            MedialError::InvalidExposureThreshold { value: 3.0 }
        );
        let mut bad = box_map([3, 3, 3]);
        bad.squared.pop();
        assert!(matches!(
            dms(&bad, &MedialOptions::default()),
            Err(MedialError::SizeMismatch { .. })
        ));
    }

    #[test]
    fn same_result_on_one_and_many_threads() {
        let distance = distance_map([20, 18, 22], |p| {
            (p - DVec3::new(10.0, 9.0, 11.0)).length() < 7.5 || (p.x - 10.0).abs() < 2.0
        });
        let run = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| dms(&distance, &MedialOptions::default()).unwrap())
        };
        let (one, many) = (run(1), run(4));
        assert_eq!(one.voxels, many.voxels);
        assert_eq!(one.kinds, many.kinds);
        assert_eq!(one.exposure, many.exposure);
        assert_eq!(one.saddles, many.saddles);
    }

    #[test]
    fn higher_thresholds_give_leaner_surfaces() {
        let distance = distance_map([26, 18, 18], |p| {
            let axis = DVec3::new(p.x.clamp(6.0, 20.0), 9.0, 9.0);
            (p - axis).length() < 6.3
        });
        let sizes: Vec<usize> = [0.4, 0.5, 1.0]
            .iter()
            .map(|&t| {
                let options = MedialOptions {
                    exposure_threshold: t,
                    ..Default::default()
                };
                let surface = dms(&distance, &options).unwrap();
                assert_invariants(&distance, &surface, &options);
                surface.true_count()
            })
            .collect();
        assert!(sizes[0] >= sizes[1] && sizes[1] >= sizes[2], "{sizes:?}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        #[test]
        fn random_unions_of_balls_keep_every_part_connected(
            balls in prop::collection::vec((2.0..14.0f64, 2.0..14.0f64, 2.0..14.0f64, 0.8..5.0f64), 1..6),
            threshold in 0.0..=2.0f64,
            ignore in any::<bool>(),
        ) {
            let distance = distance_map([16, 16, 16], |p| {
                balls.iter().any(|&(x, y, z, r)| (p - DVec3::new(x, y, z)).length() < r)
            });
            prop_assume!(distance.squared.iter().any(|&s| s > 0));
            let options = MedialOptions { exposure_threshold: threshold, ignore_distance_one: ignore };
            let surface = dms(&distance, &options).unwrap();
            assert_invariants(&distance, &surface, &options);
        }

        /// The connectivity invariant does not rest on the map being a distance transform:
        /// arbitrary values (plateaus, jumps, pits) must neither panic nor disconnect a part.
        #[test]
        fn arbitrary_maps_keep_every_part_connected(
            values in prop::collection::vec(0u32..12, 8 * 8 * 8),
            threshold in 0.0..=2.0f64,
        ) {
            let grid = crate::voxel::Grid { dims: [10, 10, 10], origin: DVec3::ZERO, voxel_size: 1.0 };
            let mut squared = vec![0; grid.len()];
            for (k, &v) in values.iter().enumerate() {
                let c = [1 + k % 8, 1 + (k / 8) % 8, 1 + k / 64];
                squared[grid.index(c)] = v;
            }
            prop_assume!(squared.iter().any(|&s| s > 0));
            let distance = DistanceMap { grid, squared };
            let options = MedialOptions { exposure_threshold: threshold, ..Default::default() };
            let surface = dms(&distance, &options).unwrap();
            assert_invariants(&distance, &surface, &options);
        }
    }
}

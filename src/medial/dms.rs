//! Extraction of the discrete medial surface from the distance map (dissertation ch.4.3).

use super::bridging::{ascent, bridge, AdjacentGroups, Label, NO_VOXEL};
use super::contour::{contour_order, ContourArrays};
use super::exposure::local_exposure;
use super::neighbourhood::{checked_interior_count, LinearNeighbours, NEIGHBOUR_COUNT};
use super::surface::{DmsKind, MedialSurface, NOT_MEDIAL};
use super::union_find::UnionFind;
use super::{MedialError, MedialOptions};
use crate::distance::DistanceMap;
use crate::voxel::Grid;

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
/// 1. local exposure of every interior voxel ([`exposure`](super::exposure), ch.4.2, in
///    parallel);
/// 2. contour lists: interior voxels in decreasing distance order (counting sort, ch.4.5);
/// 3. each contour list is processed through its contour arrays, most processed neighbours
///    first. A processed voxel joins the union-find groups of its processed 26-neighbours and
///    records its steepest-ascent neighbour. With no adjacent group it starts a group and is a
///    DMS voxel; with one, it is a true DMS voxel if its exposure meets the threshold, and a
///    bridging path along steepest ascent connects it to its group's DMS; with several, it is a
///    saddle point, a DMS voxel whatever its exposure, bridged into every group before the
///    groups merge (ch.4.3).
/// 4. the labelled voxels are collected into a [`MedialSurface`].
///
/// Each group's DMS voxels stay 26-connected throughout, so the DMS of a 26-connected figure
/// is 26-connected. The time is `O(n lg* n)` in the `n` interior voxels (plus a linear scan of
/// the grid) and the result is the same on any number of threads.
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
/// A degenerate figure is not an error: a one-voxel-thick figure gives a single-voxel DMS
/// (its first voxel) and a warning in [`MedialSurface::warnings`].
pub fn dms(distance: &DistanceMap, options: &MedialOptions) -> Result<MedialSurface, MedialError> {
    options.validate()?;
    let interior = checked_interior_count(distance)?;
    let neighbours = LinearNeighbours::new(&distance.grid);
    let exposure = local_exposure(distance, &neighbours);
    let order = contour_order(&distance.squared, interior);
    let mut extraction = Extraction::new(distance, &exposure, options, neighbours);
    for contour in
        order.chunk_by(|&a, &b| distance.squared[a as usize] == distance.squared[b as usize])
    {
        extraction.process_contour(contour);
    }
    Ok(extraction.finish(interior))
}

/// The per-voxel bookkeeping of ch.4.3 while the contours are processed.
struct Extraction<'a> {
    grid: Grid,
    squared: &'a [u32],
    exposure: &'a [f64],
    options: MedialOptions,
    neighbours: LinearNeighbours,
    /// DMS classification (and processed flag) per voxel.
    labels: Vec<Label>,
    /// Number of processed 26-neighbours per unprocessed voxel.
    processed: Vec<u8>,
    /// Steepest-ascent neighbour per processed voxel ([`NO_VOXEL`] for group founders).
    pointer: Vec<u32>,
    /// Groups of 26-connected processed voxels.
    groups: UnionFind,
    contour: ContourArrays,
    saddles: Vec<usize>,
    /// Group founders whose exposure did not meet the threshold.
    forced_founders: usize,
}

impl<'a> Extraction<'a> {
    fn new(
        distance: &'a DistanceMap,
        exposure: &'a [f64],
        options: &MedialOptions,
        neighbours: LinearNeighbours,
    ) -> Self {
        let len = distance.squared.len();
        Self {
            grid: distance.grid,
            squared: &distance.squared,
            exposure,
            options: *options,
            neighbours,
            labels: vec![Label::Unprocessed; len],
            processed: vec![0; len],
            pointer: vec![NO_VOXEL; len],
            groups: UnionFind::new(len),
            contour: ContourArrays::new(len),
            saddles: Vec::new(),
            forced_founders: 0,
        }
    }

    /// Processes one contour list through its contour arrays.
    fn process_contour(&mut self, contour: &[u32]) {
        self.contour.fill(contour, &self.processed);
        while let Some(voxel) = self.contour.pop() {
            self.process_voxel(voxel as usize);
        }
    }

    /// Whether `voxel`'s exposure makes it a true DMS voxel.
    fn sufficient(&self, voxel: usize) -> bool {
        let ignored = self.options.ignore_distance_one && self.squared[voxel] == 1;
        !ignored && self.exposure[voxel] >= self.options.exposure_threshold
    }

    fn process_voxel(&mut self, voxel: usize) {
        let squared = self.squared[voxel];
        let mut adjacent = AdjacentGroups::new();
        for k in 0..NEIGHBOUR_COUNT {
            let n = self.neighbours.at(voxel, k);
            let n_squared = self.squared[n];
            if n_squared == 0 {
                continue;
            }
            match self.labels[n] {
                Label::Unprocessed => {
                    let before = self.processed[n];
                    self.processed[n] = before + 1;
                    if n_squared == squared {
                        self.contour.promote(n as u32, before);
                    }
                }
                label => {
                    let root = self.groups.find(n);
                    let slope = ascent(squared, n_squared, self.neighbours.lengths[k]);
                    adjacent.offer(root, n, slope, label.is_medial());
                }
            }
        }
        let sufficient = self.sufficient(voxel);
        match adjacent.len() {
            0 => {
                self.labels[voxel] = if sufficient {
                    Label::True
                } else {
                    self.forced_founders += 1;
                    Label::Bridging
                };
            }
            1 => {
                let (root, step) = adjacent.groups().next().expect("one group");
                self.pointer[voxel] = step as u32;
                self.groups.union(voxel, root);
                if sufficient {
                    self.labels[voxel] = Label::True;
                    bridge(step, &mut self.labels, &self.pointer);
                } else {
                    self.labels[voxel] = Label::NonMedial;
                }
            }
            _ => {
                self.labels[voxel] = if sufficient {
                    Label::True
                } else {
                    Label::Bridging
                };
                self.saddles.push(voxel);
                for (root, step) in adjacent.groups() {
                    bridge(step, &mut self.labels, &self.pointer);
                    self.groups.union(voxel, root);
                }
                self.pointer[voxel] = adjacent.steepest().map_or(NO_VOXEL, |v| v as u32);
            }
        }
    }

    /// Collects the labelled voxels into the output.
    fn finish(mut self, interior_voxels: usize) -> MedialSurface {
        let len = self.labels.len();
        let mut voxels = Vec::new();
        let mut kinds = Vec::new();
        let mut slots = vec![NOT_MEDIAL; len];
        for (index, label) in self.labels.iter().enumerate() {
            let kind = match label {
                Label::True => DmsKind::True,
                Label::Bridging => DmsKind::Bridging,
                _ => continue,
            };
            slots[index] = voxels.len() as u32;
            voxels.push(index);
            kinds.push(kind);
        }
        let exposure = voxels.iter().map(|&i| self.exposure[i]).collect();
        let squared = voxels.iter().map(|&i| self.squared[i]).collect();
        // Components numbered by their smallest voxel; `root_id` is indexed by group root.
        let mut root_id = vec![NOT_MEDIAL; len];
        let mut components = 0usize;
        let component = voxels
            .iter()
            .map(|&i| {
                let root = self.groups.find(i);
                if root_id[root] == NOT_MEDIAL {
                    root_id[root] = components as u32;
                    components += 1;
                }
                root_id[root]
            })
            .collect();
        self.saddles.sort_unstable();

        let mut warnings = Vec::new();
        let threshold = self.options.exposure_threshold;
        if !USEFUL_THRESHOLDS.contains(&threshold) {
            warnings.push(format!(
                "exposure threshold {threshold} is outside the useful range {:?} of ch.4.4: expect a DMS that is too detailed (low) or too sparse (high)",
                USEFUL_THRESHOLDS
            ));
        }
        if voxels.len() == 1 {
            warnings.push(format!(
                "the medial surface is a single voxel (the figure has {interior_voxels} interior voxels and is nowhere more than about two voxels thick): use a smaller voxel size"
            ));
        } else if self.forced_founders > 0 {
            warnings.push(format!(
                "{} DMS voxels were kept below the exposure threshold only to start a group: lower the exposure threshold or use a smaller voxel size",
                self.forced_founders
            ));
        }
        if components > 1 {
            warnings.push(format!(
                "the figure has {components} separate 26-connected parts, so the medial surface has {components} components: keep only the largest part when voxelizing"
            ));
        }
        MedialSurface {
            grid: self.grid,
            voxels,
            kinds,
            exposure,
            squared,
            component,
            components,
            saddles: self.saddles,
            slots,
            exposure_threshold: threshold,
            interior_voxels,
            warnings,
        }
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

    #[test]
    fn single_interior_voxel_gives_a_single_voxel_dms_with_a_warning() {
        let distance = box_map([1, 1, 1]);
        let surface = dms(&distance, &MedialOptions::default()).unwrap();
        assert_eq!(surface.voxels, vec![distance.grid.index([1, 1, 1])]);
        assert_eq!(surface.kinds, vec![DmsKind::Bridging]);
        assert!((surface.exposure[0] - 2.0).abs() < 1e-12);
        assert!(surface.warnings.iter().any(|w| w.contains("single voxel")));
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
            .any(|w| w.contains("smaller voxel size")));
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
    fn separate_parts_give_one_component_each_and_a_warning() {
        let distance = distance_map([24, 12, 12], |p| {
            (p - DVec3::new(6.0, 6.0, 6.0)).length() < 4.5
                || (p - DVec3::new(17.0, 6.0, 6.0)).length() < 4.5
        });
        let options = MedialOptions::default();
        let surface = dms(&distance, &options).unwrap();
        assert_invariants(&distance, &surface, &options);
        assert_eq!(surface.components, 2);
        assert!(surface.warnings.iter().any(|w| w.contains("2 separate")));
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
    }
}

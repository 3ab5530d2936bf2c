//! Local exposure of every voxel's inscribed sphere (dissertation ch.4.2).

use super::neighbourhood::{
    checked_interior_count, LinearNeighbours, ADJACENCY_CLASSES, CLASS_LENGTHS,
};
use super::MedialError;
use crate::distance::DistanceMap;
use rayon::prelude::*;

/// Local exposure of every voxel (dissertation ch.4.2), voxel units.
///
/// The relative exposure of voxel `i` with respect to a neighbour `n` is how far the sphere of
/// radius `sqrt(d_i)` about `i` protrudes from the sphere of radius `sqrt(d_n)` about `n`:
/// `e(i : n) = sqrt(d_i) + |i - n| - sqrt(d_n)`. The local exposure is the minimum over the 26
/// neighbours, computed as in ch.4.2 per adjacency class (6 face, 12 edge, 8 corner neighbours)
/// from the class's largest neighbour distance. Exterior neighbours take part with `d_n = 0`.
/// For an exact distance map the values lie in `[0, 2]`.
///
/// `distance`: an exact squared distance map whose grid has at least one exterior layer on
/// every side. Returns one value per grid voxel (linear index), 0 for exterior voxels.
/// Computed in parallel; the result does not depend on the number of threads.
///
/// # Errors
/// [`MedialError::SizeMismatch`], [`MedialError::GridTooLarge`], [`MedialError::EmptyFigure`]
/// or [`MedialError::InteriorOnBorder`] for an unusable distance map.
pub fn exposure(distance: &DistanceMap) -> Result<Vec<f64>, MedialError> {
    checked_interior_count(distance)?;
    Ok(local_exposure(
        distance,
        &LinearNeighbours::new(&distance.grid),
    ))
}

/// [`exposure`] without the checks; `distance` must have passed [`checked_interior_count`].
pub(crate) fn local_exposure(distance: &DistanceMap, neighbours: &LinearNeighbours) -> Vec<f64> {
    let squared = &distance.squared;
    let [nx, ny, _] = distance.grid.dims;
    let plane = (nx * ny).max(1);
    let mut out = vec![0.0; squared.len()];
    out.par_chunks_mut(plane)
        .enumerate()
        .for_each(|(z, slice)| {
            let first = z * plane;
            for (offset, value) in slice.iter_mut().enumerate() {
                let index = first + offset;
                if squared[index] != 0 {
                    *value = voxel_exposure(squared, index, neighbours);
                }
            }
        });
    out
}

/// Local exposure of the interior, non-border voxel `index`.
#[inline]
pub(crate) fn voxel_exposure(squared: &[u32], index: usize, neighbours: &LinearNeighbours) -> f64 {
    let largest = ADJACENCY_CLASSES.map(|class| {
        class
            .map(|k| squared[neighbours.at(index, k)])
            .max()
            .unwrap_or(0)
    });
    exposure_from_largest(squared[index], largest)
}

/// Local exposure of a voxel of squared distance `squared` whose largest neighbour squared
/// distances per adjacency class (faces, edges, corners) are `largest` (ch.4.2: the largest
/// neighbour of a class gives the class's minimum relative exposure).
///
/// The radii are subtracted before the neighbour length is added, so that equal distances
/// give exactly the length (1 for a plateau voxel): a threshold of 1.0, common in ch.4.4 and
/// ch.5, then does not depend on rounding.
#[inline]
pub(crate) fn exposure_from_largest(squared: u32, largest: [u32; 3]) -> f64 {
    let radius = (squared as f64).sqrt();
    (0..3)
        .map(|c| (radius - (largest[c] as f64).sqrt()) + CLASS_LENGTHS[c])
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voxel::Grid;
    use glam::DVec3;

    fn map(dims: [usize; 3], values: &[([usize; 3], u32)]) -> DistanceMap {
        let grid = Grid {
            dims,
            origin: DVec3::ZERO,
            voxel_size: 1.0,
        };
        let mut squared = vec![0; grid.len()];
        for &(c, v) in values {
            squared[grid.index(c)] = v;
        }
        DistanceMap { grid, squared }
    }

    #[test]
    fn figure_4_2_examples_in_a_plane() {
        // The "9" of Figure 4.2: largest face neighbour 9, largest edge neighbour 13. Put the
        // 2D neighbourhood in the z = 1 plane; the planes above and below hold smaller values
        // so that they do not lower the minimum.
        let c = [2, 2, 1];
        let dm = map(
            [5, 5, 3],
            &[
                (c, 9),
                ([1, 2, 1], 9),
                ([3, 2, 1], 4),
                ([2, 1, 1], 5),
                ([2, 3, 1], 8),
                ([1, 1, 1], 13),
                ([3, 3, 1], 2),
            ],
        );
        let e = exposure(&dm).unwrap();
        let expected = (3.0 + 1.0 - 3.0f64).min(3.0 + 2f64.sqrt() - 13f64.sqrt());
        assert!((e[dm.grid.index(c)] - expected).abs() < 1e-12);
        assert!((e[dm.grid.index(c)] - 0.809).abs() < 1e-3);
    }

    #[test]
    fn plateau_voxels_have_exposure_exactly_one() {
        for value in [2, 3, 5, 7, 10, 13, 97, 1234] {
            let largest = [value, value, value];
            assert_eq!(
                exposure_from_largest(value, largest),
                1.0,
                "squared {value}"
            );
        }
    }

    #[test]
    fn isolated_voxel_has_exposure_two() {
        let dm = map([3, 3, 3], &[([1, 1, 1], 1)]);
        let e = exposure(&dm).unwrap();
        assert!((e[13] - 2.0).abs() < 1e-12);
        assert_eq!(e.iter().filter(|&&v| v != 0.0).count(), 1);
    }

    #[test]
    fn unpadded_and_empty_maps_are_rejected() {
        let dm = map([3, 3, 3], &[([0, 1, 1], 1)]);
        assert_eq!(
            exposure(&dm).unwrap_err(),
            MedialError::InteriorOnBorder { coords: [0, 1, 1] }
        );
        let dm = map([3, 3, 3], &[]);
        assert_eq!(exposure(&dm).unwrap_err(), MedialError::EmptyFigure);
    }
}

//! Errors of the medial stage.

use thiserror::Error;

/// Errors from building the discrete medial surface with [`dms`](super::dms).
#[derive(Debug, Clone, Error, PartialEq)]
pub enum MedialError {
    /// The exposure threshold is not a finite number in `[0, 2]`.
    #[error("exposure threshold {value} is out of range: use a finite value in [0, 2] (default 0.5; dissertation ch.4.4 recommends 0.4 to 1.0)")]
    InvalidExposureThreshold {
        /// The threshold given.
        value: f64,
    },
    /// The distance map's value array does not match its grid.
    #[error("the distance map holds {values} values but its grid has {voxels} voxels: build it with distance::edt from the same solid")]
    SizeMismatch {
        /// Length of `DistanceMap::squared`.
        values: usize,
        /// `grid.len()`.
        voxels: usize,
    },
    /// The grid has more voxels than the stage's 32-bit voxel indices can address.
    #[error("the grid has {voxels} voxels, more than the medial stage supports ({max}): use a larger voxel size")]
    GridTooLarge {
        /// `grid.len()`.
        voxels: usize,
        /// The largest supported grid.
        max: usize,
    },
    /// The map has more distinct positive values than the stage's 25-bit distance levels
    /// hold (an exact distance map never has: its values are below `2^20`).
    #[error("the distance map has {distinct} distinct positive values, more than the medial stage supports ({max}): use an exact squared distance map (distance::edt)")]
    TooManyDistances {
        /// Number of distinct positive values.
        distinct: usize,
        /// The largest supported number.
        max: usize,
    },
    /// No voxel has a positive distance: there is no figure.
    #[error("the distance map has no interior voxel: voxelize a closed mesh, or use a smaller voxel size")]
    EmptyFigure,
    /// An interior voxel lies on the outermost layer of the grid.
    #[error("interior voxel {coords:?} lies on the grid border: pad the grid with at least one exterior layer (voxel::voxelize does)")]
    InteriorOnBorder {
        /// Coordinates of the first such voxel (x fastest order).
        coords: [usize; 3],
    },
}

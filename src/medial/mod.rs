//! The discrete medial surface (DMS) of a voxelized figure (dissertation ch.4).
//!
//! [`dms`] turns an exact squared [`DistanceMap`](crate::distance::DistanceMap) into a
//! [`MedialSurface`]: the voxels whose inscribed spheres are (nearly) maximal, found by
//! tracking the ridges of the distance map from the deepest voxels outwards.
//!
//! - [`exposure`]: local exposure of each voxel's sphere against its 6/18/26 neighbours
//!   (ch.4.2); voxels at or above [`MedialOptions::exposure_threshold`] are *true* DMS voxels.
//! - contour lists in decreasing distance order, each processed through contour arrays by
//!   number of processed neighbours (ch.4.3, `contour.rs`);
//! - union-find groups of processed voxels, threaded through the 8-byte per-voxel records
//!   (`union_find.rs`, `record.rs`);
//! - steepest-ascent bridging paths and saddle points that keep each group's DMS connected
//!   (`bridging.rs`), giving *bridging* DMS voxels;
//! - the special handling of the "1" voxels (ch.4.4, [`MedialOptions::ignore_distance_one`]).
//!
//! ch.4.5 bounds the stage by `O(n lg* n)` for `n` interior voxels with union by rank; the
//! union-find here has no ranks (they would not fit the 8-byte voxel record), which is
//! `O(n lg n)` in the worst case and linear in practice.
//!
//! ```
//! use skelfit::distance::DistanceMap;
//! use skelfit::medial::{dms, MedialOptions};
//! use skelfit::voxel::Grid;
//!
//! // A 5 x 3 x 3 bar of interior voxels (squared distances by hand) in a padded 7 x 5 x 5 grid.
//! let grid = Grid { dims: [7, 5, 5], origin: glam::DVec3::ZERO, voxel_size: 1.0 };
//! let mut squared = vec![0; grid.len()];
//! for x in 1..6 {
//!     for y in 1..4 {
//!         for z in 1..4 {
//!             let inner = y == 2 && z == 2 && x > 1 && x < 5;
//!             squared[grid.index([x, y, z])] = if inner { 4 } else { 1 };
//!         }
//!     }
//! }
//! let surface = dms(&DistanceMap { grid, squared }, &MedialOptions::default()).unwrap();
//! // The DMS is the bar's axis: the three deep voxels.
//! assert_eq!(surface.voxels, vec![grid.index([2, 2, 2]), grid.index([3, 2, 2]), grid.index([4, 2, 2])]);
//! assert_eq!(surface.components, 1);
//! ```

mod bridging;
mod contour;
mod dms;
mod error;
mod exposure;
mod neighbourhood;
mod options;
mod record;
mod surface;
mod union_find;
mod warning;

#[cfg(test)]
mod testing;

pub use dms::dms;
pub use error::MedialError;
pub use exposure::exposure;
pub use options::MedialOptions;
pub use surface::{DmsKind, MedialSurface, NOT_MEDIAL};
pub use warning::MedialWarning;

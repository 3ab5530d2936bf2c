//! Exact Euclidean distance transform of a voxel solid.
//!
//! Beyond the seed (dissertation ch.3 propagates approximate distances from contour to
//! contour): we compute the *exact* squared Euclidean distance with the separable linear-time
//! algorithm of Meijster, Roerdink and Hesselink (2000), which is the lower envelope of
//! parabolas of Felzenszwalb and Huttenlocher (2012) in integer arithmetic. Lines are processed
//! in parallel with rayon; the result does not depend on the thread count because every value is
//! an exact integer.

mod edt;
mod map;

pub use edt::edt;
pub use map::DistanceMap;

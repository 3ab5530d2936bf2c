//! Numeric and geometric helpers shared by several stages: one moving average, one median, one principal
//! component analysis, one Douglas-Peucker simplification, one fast hasher for integer keys. Stage modules call these instead of
//! keeping their own copies, so the same input gives the same bits everywhere.

mod douglas_peucker;
mod fast_hash;
mod median;
mod pca;
mod smoothing;

pub use douglas_peucker::{
    closest_on_segment, douglas_peucker, douglas_peucker_closed, point_segment_distance,
};
pub(crate) use fast_hash::{fast_map, FastMap};
pub(crate) use median::upper_median;
pub(crate) use pca::{
    major_axis_by_iteration, point_covariance, principal_axes, principal_axis_2d,
};
pub(crate) use smoothing::{moving_average, Ends};

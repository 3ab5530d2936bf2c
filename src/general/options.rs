//! Parameters of the general control skeleton.

use super::GeneralError;
use glam::DVec3;
use serde::Serialize;

/// Options of [`control_skeleton`](super::control_skeleton) (dissertation ch.5.2.5, Table 5.2).
///
/// The other Table 5.2 parameters belong to earlier stages: voxel-size to
/// [`VoxelOptions`](crate::voxel::VoxelOptions), exposure threshold to
/// [`MedialOptions`](crate::medial::MedialOptions), closeness-of-fit to
/// [`PathOptions`](crate::paths::PathOptions).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GeneralOptions {
    /// Approximation error, **voxel units**: a skeletal edge whose chain section is between the
    /// min- and max-fraction lengths is split while the largest distance from the edge to its
    /// smoothed chain vertices exceeds this. Default 0.4 (Table 5.2, range `[0, inf)`). The
    /// dissertation states no unit; its models are scaled into the unit cube with voxels of
    /// 0.005 to 0.02, where 0.4 unit-cube units would be 20 to 80 voxels, more than the
    /// thickness of most limbs, so no edge would ever be split for error; Figure 5.8 measures
    /// errors of 0.41 to 2.79 "units" on a chain drawn on the voxel lattice. Voxel units it is.
    pub approximation_error: f64,
    /// Min fraction of the heart radius in `[0, 1]`: edges whose chain section is shorter than
    /// `min_fraction * heart_radius` are never split. Default 0.1 (Table 5.2).
    pub min_fraction: f64,
    /// Max fraction of the heart radius in `[0, 1]`, at least `min_fraction`: edges whose chain
    /// section is longer than `max_fraction * heart_radius` are always split. Default 0.3
    /// (Table 5.2).
    pub max_fraction: f64,
    /// Largest number of control segments (skeletal edges); `None` lets the heap empty
    /// (Table 5.2 "number-of-segments", default unspecified). At least 1. Splitting stops at
    /// this count; a path tree with more chains than this keeps all its chains (with a warning).
    pub segments: Option<usize>,
    /// Root the skeleton at the lowest end point of the skeletal graph (along
    /// [`up`](Self::up)) instead of the midpoint of a deep segment: the flag suggested among
    /// the shortcomings of ch.5.3 (e.g. for trees). Default `false` (ch.5.2.5).
    pub root_at_lowest: bool,
    /// The up direction of the mesh frame, used by [`root_at_lowest`](Self::root_at_lowest).
    /// Default +Y (dissertation 7.1.2; the project convention). Finite and non-zero.
    pub up: DVec3,
}

impl Default for GeneralOptions {
    fn default() -> Self {
        Self {
            approximation_error: 0.4,
            min_fraction: 0.1,
            max_fraction: 0.3,
            segments: None,
            root_at_lowest: false,
            up: DVec3::Y,
        }
    }
}

impl GeneralOptions {
    /// Checks every parameter against the ranges of Table 5.2.
    ///
    /// # Errors
    /// The [`GeneralError`] variant naming the first offending parameter and its value.
    pub fn validate(&self) -> Result<(), GeneralError> {
        let e = self.approximation_error;
        if e.is_nan() || e < 0.0 {
            return Err(GeneralError::InvalidApproximationError { value: e });
        }
        if !(0.0..=1.0).contains(&self.min_fraction) {
            return Err(GeneralError::InvalidMinFraction {
                value: self.min_fraction,
            });
        }
        if !(0.0..=1.0).contains(&self.max_fraction) {
            return Err(GeneralError::InvalidMaxFraction {
                value: self.max_fraction,
            });
        }
        if self.min_fraction > self.max_fraction {
            return Err(GeneralError::FractionsOutOfOrder {
                min: self.min_fraction,
                max: self.max_fraction,
            });
        }
        if self.segments == Some(0) {
            return Err(GeneralError::InvalidSegments { value: 0 });
        }
        if !(self.up.is_finite() && self.up.length_squared() > 0.0) {
            return Err(GeneralError::InvalidUp {
                value: self.up.to_array(),
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_valid_and_every_bad_value_is_named() {
        assert!(GeneralOptions::default().validate().is_ok());
        let bad = [
            GeneralOptions {
                approximation_error: -1.0,
                ..Default::default()
            },
            GeneralOptions {
                min_fraction: 1.5,
                ..Default::default()
            },
            GeneralOptions {
                max_fraction: f64::NAN,
                ..Default::default()
            },
            GeneralOptions {
                min_fraction: 0.5,
                max_fraction: 0.2,
                ..Default::default()
            },
            GeneralOptions {
                segments: Some(0),
                ..Default::default()
            },
            GeneralOptions {
                up: DVec3::ZERO,
                ..Default::default()
            },
        ];
        let words = [
            "approximation error",
            "min fraction",
            "max fraction",
            "min fraction",
            "number of segments",
            "up direction",
        ];
        for (options, word) in bad.iter().zip(words) {
            let err = options.validate().unwrap_err().to_string();
            assert!(err.contains(word), "{err}");
        }
        let infinite = GeneralOptions {
            approximation_error: f64::INFINITY,
            ..Default::default()
        };
        assert!(infinite.validate().is_ok());
    }
}

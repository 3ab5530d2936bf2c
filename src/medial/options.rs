//! Parameters of the discrete medial surface.

use super::MedialError;
use serde::Serialize;

/// Options of [`dms`](super::dms).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MedialOptions {
    /// Exposure threshold `T_exp`, voxel units. A voxel whose local exposure (ch.4.2) is at
    /// least this is a *true* DMS voxel. Default 0.5 (dissertation Table 5.2; ch.4.4: 0.4 keeps
    /// finer protrusions, 1.0 gives a lean DMS; values above 1.0 or below ~0.25 are rarely
    /// useful). Valid range `[0, 2]`: local exposures of an exact distance map lie in `[0, 2]`.
    pub exposure_threshold: f64,
    /// Treat the "1" voxels (squared distance exactly 1, i.e. face-adjacent to the outside) as
    /// non-DMS voxels unless they are saddle points (or lie on a bridging path), to suppress
    /// the spurious extensions of ch.4.4. Default `true`, as in every 3D result of the
    /// dissertation (ch.4.4, ch.5.2).
    pub ignore_distance_one: bool,
}

impl Default for MedialOptions {
    fn default() -> Self {
        Self {
            exposure_threshold: 0.5,
            ignore_distance_one: true,
        }
    }
}

impl MedialOptions {
    /// Largest accepted exposure threshold: the largest local exposure of an exact distance
    /// map (a voxel whose face neighbours all lie outside).
    pub const MAX_EXPOSURE_THRESHOLD: f64 = 2.0;

    /// Checks every parameter.
    ///
    /// # Errors
    /// [`MedialError::InvalidExposureThreshold`] when the threshold is not finite or outside
    /// `[0, 2]`.
    pub fn validate(&self) -> Result<(), MedialError> {
        let value = self.exposure_threshold;
        if !(0.0..=Self::MAX_EXPOSURE_THRESHOLD).contains(&value) {
            return Err(MedialError::InvalidExposureThreshold { value });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_valid_and_out_of_range_thresholds_are_rejected() {
        assert!(MedialOptions::default().validate().is_ok());
        for value in [-0.1, 2.5, f64::NAN, f64::INFINITY] {
            let options = MedialOptions {
                exposure_threshold: value,
                ..Default::default()
            };
            let err = options.validate().unwrap_err();
            assert!(matches!(err, MedialError::InvalidExposureThreshold { .. }));
            assert!(err.to_string().contains("use a finite value"));
        }
    }
}

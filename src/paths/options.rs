//! Parameters of the path tree.

use super::PathError;
use serde::Serialize;

/// Options of [`path_tree`](super::path_tree) (dissertation ch.5.2.4, Table 5.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PathOptions {
    /// Closeness of fit, a fraction of the heart radius in `[0, 1]`: a new branch is grown only
    /// when its extreme point lies at least `closeness * heart_radius` (path length over the
    /// DMS) beyond the covered region. Default 0.1 (Table 5.2; ch.5.2.4 recommends 0.05 to 0.1,
    /// smaller values reach fingers but add spurious branches).
    pub closeness: f64,
    /// The heart is exact (a depth labelling from every DMS voxel) when the DMS has at most this
    /// many voxels; larger surfaces use [`heart_samples`](Self::heart_samples) sources.
    /// Default 256: the exact heart costs a quadratic number of steps (ch.5.2.4); measured on
    /// this project's 2-core machine it took 120 ms for a 1 341-voxel DMS and 5.5 s for the
    /// snake's, while 256 voxels take a few milliseconds.
    pub exact_heart_max: usize,
    /// Number of deterministic depth-labelling sources for a sampled heart: positions evenly
    /// spaced through the DMS voxels in grid order, which spreads them over the figure in
    /// proportion to its DMS. Default 64 (ch.5.2.4 suggests "100 or so" random sources; evenly
    /// spaced ones cover the figure better: with 64 the heart lay 0 to 5 voxels (path length)
    /// from the exact heart on the 16 reference models at the default voxel size, with 16 up to
    /// 15 voxels). At least 1.
    pub heart_samples: usize,
    /// Half-width (voxels) of the box in which a local depth maximum must be the deepest DMS
    /// voxel to count as an extreme point. Default 5 ("within five adjacent voxels", ch.5.2.4).
    pub extreme_neighbourhood: usize,
    /// Extreme points closer than this (Euclidean, voxel units) fall into one group; a branch
    /// reaching one member of a group retires the whole group. Default 5.0 voxels, the same
    /// neighbourhood as [`extreme_neighbourhood`](Self::extreme_neighbourhood) (ch.5.2.4 groups
    /// "by proximity ... another application of neighborhood searches"). Finite, `>= 0`.
    pub group_radius: f64,
    /// Box-filter radius of chain smoothing, in chain edges, limited at chain ends
    /// (Figure 5.6). Default 3 ("a filter radius of three edges usually works well", ch.5.2.4).
    /// 0 disables smoothing.
    pub smoothing_radius: usize,
}

impl Default for PathOptions {
    fn default() -> Self {
        Self {
            closeness: 0.1,
            exact_heart_max: 256,
            heart_samples: 64,
            extreme_neighbourhood: 5,
            group_radius: 5.0,
            smoothing_radius: 3,
        }
    }
}

impl PathOptions {
    /// Checks every parameter.
    ///
    /// # Errors
    /// [`PathError::InvalidCloseness`], [`PathError::InvalidHeartSamples`] or
    /// [`PathError::InvalidGroupRadius`] naming the offending value.
    pub fn validate(&self) -> Result<(), PathError> {
        if !(0.0..=1.0).contains(&self.closeness) {
            return Err(PathError::InvalidCloseness {
                value: self.closeness,
            });
        }
        if self.heart_samples == 0 {
            return Err(PathError::InvalidHeartSamples {
                value: self.heart_samples,
            });
        }
        if !(self.group_radius.is_finite() && self.group_radius >= 0.0) {
            return Err(PathError::InvalidGroupRadius {
                value: self.group_radius,
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_valid_and_bad_values_are_rejected() {
        assert!(PathOptions::default().validate().is_ok());
        for value in [-0.1, 1.5, f64::NAN] {
            let options = PathOptions {
                closeness: value,
                ..Default::default()
            };
            let err = options.validate().unwrap_err();
            assert!(err.to_string().contains("[0, 1]"), "{err}");
        }
        let options = PathOptions {
            heart_samples: 0,
            ..Default::default()
        };
        assert!(matches!(
            options.validate(),
            Err(PathError::InvalidHeartSamples { .. })
        ));
        let options = PathOptions {
            group_radius: f64::INFINITY,
            ..Default::default()
        };
        assert!(matches!(
            options.validate(),
            Err(PathError::InvalidGroupRadius { .. })
        ));
    }
}

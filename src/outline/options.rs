//! Parameters of the outline stage, with their defaults and where they come from.

use super::OutlineError;
use crate::lod::LodOptions;

/// Options of [`outline_part`](super::outline_part) and the steps it runs. Lengths are
/// fractions of the outline's bounding-box diagonal unless said otherwise, so the result does not
/// depend on the outline's units.
#[derive(Debug, Clone, PartialEq)]
pub struct OutlineOptions {
    /// A path whose end lies within this many mean edge lengths of its start counts as closed
    /// (a hand-drawn stroke rarely ends exactly where it began). Default 3.
    pub closing_gap: f64,
    /// Lines per SVG Bézier curve when flattening. Default 16.
    pub curve_segments: usize,
    /// Spacing of the uniform resampling of the stroke, as a fraction of its perimeter. Default
    /// 0.005: seed 003 Fig.19 resamples a stroke of perimeter 1972 with step 10.
    pub resample_fraction: f64,
    /// Douglas-Peucker tolerance of the polygon handed to the straight skeleton. Default 0.005
    /// (a measurement: outlines of 2,000 points become polygons of 20-60 corners that keep
    /// every limb).
    pub polygon_tolerance: f64,
    /// Straight-skeleton edges shorter than this multiple of the mean skeleton edge length are
    /// collapsed. Default 0.5 (seed 003, 3.1).
    pub collapse_ratio: f64,
    /// Bones between internal joints shorter than this are collapsed after BoundedDP
    /// ([`collapse_bones`](crate::lod::collapse_bones)). Default 0.03 (seed 003's ε_c = 10 px
    /// on sketches a few hundred pixels across).
    pub collapse_fraction: f64,
    /// Junction-to-terminal branches shorter than this are pruned after BoundedDP
    /// ([`prune_branches`](crate::lod::prune_branches)): spurs that noise in the stroke leaves in
    /// the straight skeleton. Default 0.08 (seed 003 prunes with ε_t = 30 px on sketches a few
    /// hundred pixels across; 0.08 removes the spurs of strokes with 1 % jitter in our tests
    /// and keeps limbs longer than a tenth of the figure).
    pub prune_fraction: f64,
    /// Numerical tolerance of the straight skeleton (event times and positions). Default 1e-9.
    pub tolerance: f64,
    /// BoundedDP joint extraction along each branch.
    pub bounded_dp: BoundedDpOptions,
    /// Inflation of the outline into a closed 3D mesh.
    pub inflate: InflateOptions,
    /// Level-of-detail operations applied to the final skeleton. Default: none.
    pub lod: LodOptions,
}

impl Default for OutlineOptions {
    fn default() -> Self {
        Self {
            closing_gap: 3.0,
            curve_segments: 16,
            resample_fraction: 0.005,
            polygon_tolerance: 0.005,
            collapse_ratio: 0.5,
            collapse_fraction: 0.03,
            prune_fraction: 0.08,
            tolerance: 1e-9,
            bounded_dp: BoundedDpOptions::default(),
            inflate: InflateOptions::default(),
            lod: LodOptions::default(),
        }
    }
}

/// Options of [`bounded_dp`](super::bounded_dp) (seed 003, Algorithms 1 and 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundedDpOptions {
    /// Initial threshold ε0 of the combined axis and shape error, fraction of the diagonal.
    /// Default 0.03 (seed 003 uses ε_s = 5 px for sketches a few hundred pixels across, but
    /// starts Algorithm 2 from "a fairly large value").
    pub epsilon: f64,
    /// Weight α_s of the shape variation term (Eq. 1). Default 1.0 (Algorithm 1 adds the two
    /// terms unweighted).
    pub shape_weight: f64,
    /// Factor the threshold is multiplied by while a simplified edge leaves the general
    /// cylinder. Default 0.8 (seed 003, 3.1).
    pub reduction: f64,
    /// Spacing of the samples and slices along a branch's spline, fraction of the diagonal.
    /// Default 0.01.
    pub sample_spacing: f64,
    /// Branches with fewer samples than this are kept as one bone. Default 3.
    pub min_samples: usize,
    /// Samples closer to a branch end than this multiple of the end node's radius (its
    /// straight-skeleton offset time) lie inside the end joint's ball and are not candidate
    /// joints. Default 1.0 (seed 003 approximates each joint by its inscribed ball).
    pub end_margin: f64,
    /// Slice extents are capped at this multiple of the local axis radius, so a slice near a
    /// junction that runs along a neighbouring limb does not count as shape variation.
    /// Default 2.0 (a measurement on starfish and stick-figure outlines).
    pub extent_cap: f64,
}

impl Default for BoundedDpOptions {
    fn default() -> Self {
        Self {
            epsilon: 0.03,
            shape_weight: 1.0,
            reduction: 0.8,
            sample_spacing: 0.01,
            min_samples: 3,
            end_margin: 1.0,
            extent_cap: 2.0,
        }
    }
}

/// Options of [`inflate`](super::inflate).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InflateOptions {
    /// Height parameter c of the Poisson equation `-Δh = c` (seed 003, 4.1): scales how thick
    /// the inflated part is. The half thickness at a point is `thickness * sqrt(h)` where `h`
    /// solves the equation for `c = 2` on the outline in outline units; 1.0 gives a round
    /// cross-section for a long strip (`h = R² - y²` across a strip of half width `R`). Default 1.0.
    pub thickness: f64,
    /// Spacing of the interior sample grid, as a fraction of the diagonal. Default 0.02.
    pub spacing: f64,
    /// Gauss-Seidel sweeps of the Poisson solve (at most). Default 2000.
    pub max_sweeps: usize,
    /// The solve stops when no height changes by more than this fraction of the largest.
    /// Default 1e-6.
    pub convergence: f64,
}

impl Default for InflateOptions {
    fn default() -> Self {
        Self {
            thickness: 1.0,
            spacing: 0.02,
            max_sweeps: 2000,
            convergence: 1e-6,
        }
    }
}

fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<(), OutlineError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(OutlineError::InvalidOption {
            name,
            value,
            expected,
        })
    }
}

impl InflateOptions {
    /// Checks every field is in range.
    ///
    /// # Errors
    /// [`OutlineError::InvalidOption`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), OutlineError> {
        check(
            "thickness",
            self.thickness,
            self.thickness > 0.0,
            "must be > 0",
        )?;
        check(
            "inflate.spacing",
            self.spacing,
            self.spacing >= 0.002 && self.spacing <= 0.2,
            "must be in [0.002, 0.2]",
        )?;
        check(
            "inflate.convergence",
            self.convergence,
            self.convergence > 0.0 && self.convergence < 1.0,
            "must be in (0, 1)",
        )
    }
}

impl OutlineOptions {
    /// Checks every field is in range.
    ///
    /// # Errors
    /// [`OutlineError::InvalidOption`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), OutlineError> {
        let b = &self.bounded_dp;
        let i = &self.inflate;
        check(
            "closing_gap",
            self.closing_gap,
            self.closing_gap >= 0.0,
            "must be >= 0",
        )?;
        check(
            "resample_fraction",
            self.resample_fraction,
            self.resample_fraction >= 1e-5 && self.resample_fraction <= 0.1,
            "must be in [1e-5, 0.1]",
        )?;
        check(
            "polygon_tolerance",
            self.polygon_tolerance,
            (0.0..=0.2).contains(&self.polygon_tolerance),
            "must be in [0, 0.2]",
        )?;
        check(
            "collapse_ratio",
            self.collapse_ratio,
            (0.0..=10.0).contains(&self.collapse_ratio),
            "must be in [0, 10]",
        )?;
        check(
            "collapse_fraction",
            self.collapse_fraction,
            (0.0..=1.0).contains(&self.collapse_fraction),
            "must be in [0, 1]",
        )?;
        check(
            "prune_fraction",
            self.prune_fraction,
            (0.0..=1.0).contains(&self.prune_fraction),
            "must be in [0, 1]",
        )?;
        check(
            "tolerance",
            self.tolerance,
            self.tolerance > 0.0 && self.tolerance < 1e-3,
            "must be in (0, 1e-3)",
        )?;
        check(
            "bounded_dp.epsilon",
            b.epsilon,
            b.epsilon >= 0.0,
            "must be >= 0",
        )?;
        check(
            "bounded_dp.shape_weight",
            b.shape_weight,
            b.shape_weight >= 0.0,
            "must be >= 0",
        )?;
        check(
            "bounded_dp.reduction",
            b.reduction,
            b.reduction > 0.0 && b.reduction < 1.0,
            "must be in (0, 1)",
        )?;
        check(
            "bounded_dp.sample_spacing",
            b.sample_spacing,
            b.sample_spacing > 1e-4 && b.sample_spacing <= 0.2,
            "must be in (1e-4, 0.2]",
        )?;
        check(
            "bounded_dp.end_margin",
            b.end_margin,
            b.end_margin >= 0.0,
            "must be >= 0",
        )?;
        check(
            "bounded_dp.extent_cap",
            b.extent_cap,
            b.extent_cap > 0.0,
            "must be > 0",
        )?;
        i.validate()?;
        Ok(self.lod.validate()?)
    }
}

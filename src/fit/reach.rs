//! Leg tips out to the skin: the medial surface of a thin foot or hand can stop well short of
//! the sole (a few voxels across, its medial piece breaks off), which left the limb's distal
//! joints hanging above the ground on one side of a symmetric figure; the skin does not move
//! with the voxel grid.

use super::{DorsalProbe, FitInput, FitInputOptions};
use crate::distance::DistanceMap;
use crate::options::{Checks, OptionProblems};
use crate::template::LimbKind;
use glam::DVec3;

/// Options of the leg tips' reach to the skin ([`super::FitInputOptions::reach`]). Angles are
/// degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReachOptions {
    /// A tilted ray replaces the straight end direction only when it reaches this many times
    /// as far, and then the least tilted ray that reaches within this factor of the farthest
    /// is taken. Default 1.1 (a hoof in front of the pastern; the right foot of the symmetric
    /// MakeHuman body, whose straight ray dipped through the sole 5 cm short of the toes).
    pub deeper: f64,
    /// A tip stops where its ray enters a part whose inscribed radius exceeds this multiple of
    /// the limb end's (a foot touching the other leg is one solid with it). Default 2.
    pub thicker: f64,
    /// Largest tilt of a ray from the end direction, degrees. Default 30.
    pub max_tilt: f64,
    /// Cones of tilted rays, evenly spaced up to [`ReachOptions::max_tilt`] (6: every 5
    /// degrees). Default 6.
    pub tilts: usize,
    /// Rays around each cone, evenly spaced in azimuth. Default 16.
    pub azimuths: usize,
    /// Step of the march along the chosen ray that looks for a thicker part, as a fraction of
    /// the path's end extension. Default 0.25.
    pub march_step: f64,
    /// Most steps of that march. Default 4096.
    pub max_march_steps: usize,
}

impl ReachOptions {
    /// Checks every option.
    ///
    /// # Errors
    /// Every option out of range.
    pub fn validate(&self) -> Result<(), OptionProblems> {
        let mut c = Checks::default();
        c.range("deeper", self.deeper, 1.0, 10.0);
        c.range("thicker", self.thicker, 1.0, 1000.0);
        c.range("max_tilt", self.max_tilt, 0.0, 90.0);
        c.at_least("tilts", self.tilts, 1);
        c.at_least("azimuths", self.azimuths, 1);
        c.positive("march_step", self.march_step, 1.0);
        c.at_least("max_march_steps", self.max_march_steps, 1);
        c.finish()
    }
}

impl Default for ReachOptions {
    fn default() -> Self {
        Self {
            deeper: 1.1,
            thicker: 2.0,
            max_tilt: 30.0,
            tilts: 6,
            azimuths: 16,
            march_step: 0.25,
            max_march_steps: 4096,
        }
    }
}

/// Guards the march step against a zero-length extension, mesh units.
const MIN_EXTENSION: f64 = 1e-12;

/// Moves the extended tip of every leg path (and its digit paths) out to the skin: from the
/// path's last medial point along its end direction (as
/// [`FitInputOptions::end_extension`] extends it, over the last
/// [`FitInputOptions::end_direction_points`]) to where `probe` says the figure ends, when that
/// is farther than the extension already reaches ([`FitInputOptions::reach`]).
///
/// When a ray within [`ReachOptions::max_tilt`] of the end direction reaches clearly farther
/// ([`ReachOptions::deeper`]), the tip follows the least tilted ray that reaches nearly as far
/// as the farthest: the limb may bend past its medial piece, or the end direction may dip
/// through a thin sole. A tip never goes on into a part [`ReachOptions::thicker`] than the
/// limb's end (by `distance`, the figure's distance map). Arms and wings keep the extension: on
/// CesiumMan's mitten hands the longer arm path moved the refined wrist onto the fingertips.
/// Returns how many tips moved.
pub(super) fn reach_the_skin(
    input: &mut FitInput,
    options: &FitInputOptions,
    probe: &dyn DorsalProbe,
    distance: &DistanceMap,
) -> usize {
    let mut moved = 0;
    let mut reach = |points: &mut Vec<DVec3>| {
        if options.end_extension > 0.0
            && reach_tip(
                points,
                options.end_direction_points,
                &options.reach,
                probe,
                distance,
            )
        {
            moved += 1;
        }
    };
    for limb in &mut input.limbs {
        if !matches!(
            limb.kind,
            LimbKind::Leg | LimbKind::ForeLeg | LimbKind::HindLeg
        ) {
            continue;
        }
        if limb.digits.is_empty() {
            reach(&mut limb.path);
        }
        for digit in &mut limb.digits {
            reach(&mut digit.path);
        }
    }
    moved
}

/// Moves the last point of `points` (the extension past the medial path's end, the point
/// before it) out to the skin; whether it moved. Paths of fewer than three points, or without
/// an extension, stay.
fn reach_tip(
    points: &mut [DVec3],
    end_points: usize,
    options: &ReachOptions,
    probe: &dyn DorsalProbe,
    distance: &DistanceMap,
) -> bool {
    let n = points.len();
    let k = end_points;
    if n < 3 || k == 0 {
        return false;
    }
    // The last point is the extension; the one before it, the medial path's end.
    let end = points[n - 2];
    let from = points[n.saturating_sub(2 + k)];
    let Some(dir) = (end - from).try_normalize() else {
        return false;
    };
    let Some(depth) = probe.depth(end, dir) else {
        return false;
    };
    let extension = end.distance(points[n - 1]);
    if !(depth.is_finite() && depth > extension) {
        return false;
    }
    let (best_dir, deepest) = deepest_ray(end, dir, depth, options, probe);
    let best = before_thicker(end, best_dir, deepest, extension, options, distance);
    if best > extension {
        points[n - 1] = end + best_dir * best;
        true
    } else {
        false
    }
}

/// The ray from `end` the tip follows, and how far it reaches: the straight `dir` (reaching
/// `depth`), unless a ray within [`ReachOptions::max_tilt`] reaches clearly farther
/// ([`ReachOptions::deeper`]); then the least tilted ray that reaches nearly as far as the
/// farthest (the deepest at that tilt).
fn deepest_ray(
    end: DVec3,
    dir: DVec3,
    depth: f64,
    options: &ReachOptions,
    probe: &dyn DorsalProbe,
) -> (DVec3, f64) {
    let side = dir.any_orthonormal_vector();
    let other = dir.cross(side);
    let rays: Vec<Vec<(DVec3, f64)>> = (1..=options.tilts)
        .map(|i| {
            let tilt = options.max_tilt * i as f64 / options.tilts as f64;
            (0..options.azimuths)
                .filter_map(|k| {
                    let azimuth = std::f64::consts::TAU * k as f64 / options.azimuths as f64;
                    let d = (dir * tilt.to_radians().cos()
                        + (side * azimuth.cos() + other * azimuth.sin()) * tilt.to_radians().sin())
                    .normalize();
                    probe
                        .depth(end, d)
                        .filter(|x| x.is_finite())
                        .map(|x| (d, x))
                })
                .collect()
        })
        .collect();
    let farthest = rays.iter().flatten().map(|r| r.1).fold(depth, f64::max);
    if farthest > options.deeper * depth {
        if let Some(&(d, x)) = rays
            .iter()
            .filter_map(|at_tilt| {
                at_tilt
                    .iter()
                    .filter(|r| r.1 * options.deeper >= farthest)
                    .max_by(|a, b| a.1.total_cmp(&b.1))
            })
            .next()
        {
            return (d, x);
        }
    }
    (dir, depth)
}

/// How far along `dir` from `end` the tip goes: `reach`, or less where the ray enters a part
/// [`ReachOptions::thicker`] than the limb's end (never less than `extension`).
fn before_thicker(
    end: DVec3,
    dir: DVec3,
    reach: f64,
    extension: f64,
    options: &ReachOptions,
    distance: &DistanceMap,
) -> f64 {
    let limit = options.thicker * distance.radius_at(end).max(extension);
    let steps = (reach / (options.march_step * extension.max(MIN_EXTENSION)))
        .ceil()
        .min(options.max_march_steps as f64) as usize;
    for k in 1..=steps {
        let t = reach * k as f64 / steps as f64;
        if distance.radius_at(end + dir * t) > limit {
            return t.max(extension);
        }
    }
    reach
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_reach_options_are_valid_and_bad_ones_are_all_named() {
        assert!(ReachOptions::default().validate().is_ok());
        let bad = ReachOptions {
            deeper: f64::NAN,
            tilts: 0,
            march_step: 0.0,
            ..ReachOptions::default()
        };
        let message = bad.validate().unwrap_err().to_string();
        for name in ["deeper", "tilts", "march_step"] {
            assert!(message.contains(name), "{message}");
        }
    }

    #[test]
    fn the_default_tilts_are_every_five_degrees() {
        let o = ReachOptions::default();
        let tilts: Vec<f64> = (1..=o.tilts)
            .map(|i| o.max_tilt * i as f64 / o.tilts as f64)
            .collect();
        assert_eq!(tilts, [5.0, 10.0, 15.0, 20.0, 25.0, 30.0]);
    }
}

//! Sizing the voxel grid around a mesh: checked dimensions, the voxel budget, the memory check
//! and the smallest voxel size that fits when the asked one does not.

use super::{Grid, VoxelError, VoxelOptions, VoxelSize};
use crate::mesh::Mesh;
use glam::DVec3;

/// Working memory of the voxel and distance stages per voxel, bytes: six `i8` winding votes,
/// the inside, surface and classification flags, the `u32` squared distance map, and as much
/// again for the later stages' per-voxel maps (a 1.3 G-voxel humanoid grid measured 11.5 GB
/// while still voxelizing).
pub(crate) const WORKING_BYTES_PER_VOXEL: u64 = 2 * (6 + 3 + 4);

/// The grid [`voxelize`](super::voxelize) uses for `mesh`: voxels of the asked size, aligned
/// with the bounding box's minimum corner, `padding` (at least one) empty voxels around it.
///
/// # Errors
/// [`VoxelOptions::validate`]'s errors, [`VoxelError::NoTriangles`], [`VoxelError::Flat`],
/// [`VoxelError::TooLarge`] (over budget, or dimensions that overflow) and
/// [`VoxelError::OutOfMemory`] (more working memory than is available), both naming a voxel
/// size that fits.
pub(super) fn grid_of(mesh: &Mesh, options: &VoxelOptions) -> Result<Grid, VoxelError> {
    options.validate()?;
    let (min, max) = mesh.bounding_box().ok_or(VoxelError::NoTriangles)?;
    let extent = max - min;
    let longest = extent.max_element();
    if !extent.is_finite() || extent.min_element() <= 0.0 {
        return Err(VoxelError::Flat {
            extent: extent.to_array(),
        });
    }
    let h = match options.size {
        VoxelSize::Absolute(h) => h,
        VoxelSize::Fraction(f) => f * longest,
    };
    let pad = options.padding.max(1);
    let sizing = Sizing {
        extent,
        longest,
        pad,
    };
    let dims = sizing.dims(h);
    let voxels = count(dims);
    if voxels.is_none_or(|v| v > options.max_voxels) {
        let (fitting_size, fitting_fraction) = sizing.fitting(h, options.max_voxels);
        return Err(VoxelError::TooLarge {
            dims: dims.unwrap_or_else(|| sizing.dims_saturating(h)),
            voxels: voxels.unwrap_or(usize::MAX),
            budget: options.max_voxels,
            fitting_size,
            fitting_fraction,
        });
    }
    let (dims, voxels) = (dims.unwrap_or_default(), voxels.unwrap_or_default());
    if let Some(available_bytes) = available_memory() {
        let needed_bytes = (voxels as u64).saturating_mul(WORKING_BYTES_PER_VOXEL);
        if needed_bytes > available_bytes {
            let budget = usize::try_from(available_bytes / WORKING_BYTES_PER_VOXEL)
                .unwrap_or(usize::MAX)
                .max(options.minimum_voxels());
            let (fitting_size, fitting_fraction) = sizing.fitting(h, budget);
            return Err(VoxelError::OutOfMemory {
                dims,
                voxels,
                needed_bytes,
                available_bytes,
                fitting_size,
                fitting_fraction,
            });
        }
    }
    // Align voxel boundaries with the minimum corner: a flat face there is then sampled exactly,
    // and each axis rounds to the nearest voxel rather than up to a whole extra one.
    Ok(Grid {
        dims,
        origin: min - DVec3::splat(pad as f64 * h),
        voxel_size: h,
    })
}

/// The product of the dimensions, `None` on overflow.
fn count(dims: Option<[usize; 3]>) -> Option<usize> {
    dims?.iter().try_fold(1usize, |acc, &d| acc.checked_mul(d))
}

/// What the grid dimensions depend on.
#[derive(Clone, Copy)]
struct Sizing {
    /// Bounding-box extent, mesh units; every component positive and finite.
    extent: DVec3,
    /// Its largest component.
    longest: f64,
    /// Empty voxels on each side (at least one).
    pad: usize,
}

impl Sizing {
    /// Voxels along each axis for voxel size `h`, `None` when a dimension does not fit a
    /// `usize` (a tiny `h`).
    fn dims(&self, h: f64) -> Option<[usize; 3]> {
        let mut dims = [0usize; 3];
        for (k, d) in dims.iter_mut().enumerate() {
            let cells = (self.extent[k] / h).ceil().max(1.0);
            // Below 2^53 the f64 holds the integer exactly, and fits any 64-bit usize; NaN
            // (never the case for a validated size) fails too.
            if cells.is_nan() || cells >= 9_007_199_254_740_992.0 {
                return None;
            }
            *d = usize::try_from(cells as u64)
                .ok()?
                .checked_add(self.pad.checked_mul(2)?)?;
        }
        Some(dims)
    }

    /// Voxels along each axis for voxel size `h`, `usize::MAX` for an axis that overflows
    /// (for messages).
    fn dims_saturating(&self, h: f64) -> [usize; 3] {
        let mut dims = [usize::MAX; 3];
        for (k, d) in dims.iter_mut().enumerate() {
            let one = Sizing {
                extent: DVec3::splat(self.extent[k]),
                ..*self
            };
            if let Some([n, _, _]) = one.dims(h) {
                *d = n;
            }
        }
        dims
    }

    /// Whether the grid for voxel size `h` has at most `budget` voxels.
    fn fits(&self, h: f64, budget: usize) -> bool {
        count(self.dims(h)).is_some_and(|v| v <= budget)
    }

    /// A voxel size that fits `budget` (which must admit the one-voxel grid), as
    /// `(mesh units, fraction of the longest side)`: the smallest size above `too_small` that
    /// fits, found by bisection (the voxel count never grows with the size), rounded up to four
    /// significant digits so that both numbers, printed, still fit.
    fn fitting(&self, too_small: f64, budget: usize) -> (f64, f64) {
        let (mut lo, mut hi) = (too_small.max(f64::MIN_POSITIVE), self.longest);
        if !self.fits(hi, budget) {
            // Only for a budget below the minimum grid, which validation refuses.
            return (self.longest, 1.0);
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.fits(mid, budget) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let fraction = round_up(hi / self.longest).min(1.0);
        let mut size = round_up(hi);
        let mut fraction_ok = fraction;
        while !self.fits(fraction_ok * self.longest, budget) && fraction_ok < 1.0 {
            fraction_ok = round_up(fraction_ok * 1.0001).min(1.0);
        }
        while !self.fits(size, budget) && size < self.longest {
            size = round_up(size * 1.0001);
        }
        (size, fraction_ok)
    }
}

/// `x > 0` rounded up to four significant digits.
fn round_up(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 || x.is_infinite() {
        return x;
    }
    let scale = 10f64.powi(3 - x.log10().floor() as i32);
    let rounded = (x * scale).ceil() / scale;
    if rounded < x {
        rounded + 1.0 / scale
    } else {
        rounded
    }
}

/// Memory available to new allocations, bytes, where the system tells (Linux): the least of
/// `MemAvailable` (`/proc/meminfo`), the cgroup v2 limit less its usage
/// (`/sys/fs/cgroup/memory.max`, `memory.current`) and the address-space limit (`ulimit -v`,
/// `/proc/self/limits`) less the process's current size. `None` where none can be read, and
/// then no memory check is made.
pub(crate) fn available_memory() -> Option<u64> {
    let read = |path: &str| std::fs::read_to_string(path).ok();
    let field = |text: &str, key: &str| -> Option<u64> {
        let line = text.lines().find(|l| l.starts_with(key))?;
        line[key.len()..].split_whitespace().next()?.parse().ok()
    };
    let meminfo = read("/proc/meminfo").and_then(|t| field(&t, "MemAvailable:"));
    let cgroup = (|| {
        let max: u64 = read("/sys/fs/cgroup/memory.max")?.trim().parse().ok()?;
        let current: u64 = read("/sys/fs/cgroup/memory.current")?.trim().parse().ok()?;
        Some(max.saturating_sub(current))
    })();
    let address_space = (|| {
        let limit = field(&read("/proc/self/limits")?, "Max address space")?;
        let size = field(&read("/proc/self/status")?, "VmSize:")?;
        Some(limit.saturating_sub(size.saturating_mul(1024)))
    })();
    [
        meminfo.and_then(|kib| kib.checked_mul(1024)),
        cgroup,
        address_space,
    ]
    .into_iter()
    .flatten()
    .min()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sizing(extent: [f64; 3]) -> Sizing {
        let extent = DVec3::from_array(extent);
        Sizing {
            extent,
            longest: extent.max_element(),
            pad: 2,
        }
    }

    #[test]
    fn tiny_voxel_sizes_overflow_to_none_not_wrap() {
        let s = sizing([1.4, 0.1, 0.1]);
        assert_eq!(s.dims(1e-19), None);
        assert_eq!(s.dims(1e-20), None);
        assert_eq!(s.dims(f64::MIN_POSITIVE), None);
        assert_eq!(s.dims(1.4), Some([5, 5, 5]));
    }

    #[test]
    fn fitting_size_is_the_smallest_that_fits_and_never_above_the_longest_side() {
        let s = sizing([2.0, 1.0, 0.5]);
        for budget in [125, 130, 1000, 123_456, 10_000_000] {
            let (size, fraction) = s.fitting(1e-6, budget);
            assert!(s.fits(size, budget), "budget {budget}: size {size}");
            assert!(
                s.fits(fraction * 2.0, budget),
                "budget {budget}: {fraction}"
            );
            assert!(fraction <= 1.0 && fraction > 0.0, "{fraction}");
            // Not much larger than needed.
            assert!(!s.fits(size * 0.99, budget) || size * 0.99 < 1e-6);
        }
    }

    #[test]
    fn round_up_keeps_four_digits_and_never_goes_down() {
        assert_eq!(round_up(0.012341), 0.01235);
        assert_eq!(round_up(1.0), 1.0);
        for x in [1e-7, 0.3, 7.77777, 12345.6] {
            assert!(round_up(x) >= x);
        }
    }
}

//! Parameters of the skinning stage.

use super::SkinError;
use crate::voxel::Connectivity;

/// Options of [`skin`](super::skin) and [`skin_from_bones`](super::skin_from_bones).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkinOptions {
    /// Scale applied to every distance-map sphere radius before marking the voxels it covers.
    /// Default 1.0: the sphere of a chain voxel is exactly its maximal inscribed ball, as in
    /// dissertation 5.2.5 and 8.3.
    pub sphere_scale: f64,
    /// Neighbourhood of the breadth-first propagation of influence sets into uncovered voxels.
    /// Default [`Connectivity::TwentySix`]: the interior is 26-connected (the voxelizer keeps the
    /// largest 26-connected component), so a 26-connected flood reaches every interior voxel and
    /// thin diagonal features that a 6-connected flood would miss.
    pub connectivity: Connectivity,
    /// Spacing of the sample points along a bone in [`bone_segments`](super::bone_segments),
    /// in voxels. Default 0.5: every voxel the bone passes through gets at least one sample.
    pub bone_sample_spacing: f64,
    /// How far (voxels, Chebyshev radius) [`bone_segments`](super::bone_segments) looks for
    /// the nearest interior voxel when a bone sample lies outside the figure. Default 3: a bone
    /// that grazes the surface still gets chain voxels; one that is far outside gets none (and a
    /// warning).
    pub bone_search_radius: usize,
    /// Length of the segment of a leaf joint (one without children) in
    /// [`bone_segments`](super::bone_segments), as a fraction of its parent bone's length,
    /// continued along the parent bone's direction and cut where it leaves the figure.
    /// Default 1.0: a head or hand joint at the end of a chain gets a segment reaching towards
    /// the end of the figure instead of no influence at all (beyond the seed, which always ends
    /// chains at end-effector points).
    pub leaf_extension: f64,
}

impl Default for SkinOptions {
    fn default() -> Self {
        Self {
            sphere_scale: 1.0,
            connectivity: Connectivity::TwentySix,
            bone_sample_spacing: 0.5,
            bone_search_radius: 3,
            leaf_extension: 1.0,
        }
    }
}

impl SkinOptions {
    /// Checks every field is in range.
    ///
    /// # Errors
    /// [`SkinError::InvalidOption`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), SkinError> {
        let positive = "give a finite number above zero";
        let non_negative = "give a finite number of zero or more";
        for (name, value, ok, expected) in [
            (
                "sphere_scale",
                self.sphere_scale,
                self.sphere_scale > 0.0,
                positive,
            ),
            (
                "bone_sample_spacing",
                self.bone_sample_spacing,
                self.bone_sample_spacing > 0.0,
                positive,
            ),
            (
                "leaf_extension",
                self.leaf_extension,
                self.leaf_extension >= 0.0,
                non_negative,
            ),
        ] {
            if !(ok && value.is_finite()) {
                return Err(SkinError::InvalidOption {
                    name,
                    value,
                    expected,
                });
            }
        }
        if self.bone_search_radius > 64 {
            return Err(SkinError::InvalidOption {
                name: "bone_search_radius",
                value: self.bone_search_radius as f64,
                expected: "give at most 64 voxels",
            });
        }
        Ok(())
    }
}

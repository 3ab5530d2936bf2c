//! Parameters of the skinning stage.

use super::SkinError;
use crate::voxel::Connectivity;

/// How vertex weights are computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SkinMethod {
    /// Geodesic voxel binding (Dionne & de Lasa 2013): weights fall off with the distance
    /// from each bone through the solid and vary continuously over the surface, at most four
    /// per vertex. The default: it deforms without tearing (`reports/deformation/`).
    #[default]
    Geodesic,
    /// The dissertation's anchor weights (5.2.5, 8.3): equal-share weights over the influence
    /// set of each vertex's voxel. Kept for comparison; they change abruptly between
    /// neighbouring voxels and tear the mesh when a joint turns.
    Anchor,
}

/// Options of [`skin`](super::skin) and [`skin_from_bones`](super::skin_from_bones).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkinOptions {
    /// How weights are computed. Default [`SkinMethod::Geodesic`].
    pub method: SkinMethod,
    /// Exponent of the geodesic falloff, `weight ∝ distance^-falloff` before the fifth
    /// nearest joint's weight is subtracted ([`SkinMethod::Geodesic`] only). Larger values
    /// give narrower blends around the joints. Default 2.
    pub falloff: f64,
    /// How much longer than the nearest joint's path through the solid a joint's may be and
    /// still weigh on a point ([`SkinMethod::Geodesic`] only): a joint's weight fades linearly
    /// from the nearest's path length to zero at this ratio, so blends stay local to the
    /// joints (a forearm does not move the waist beside it). Default 2.
    pub blend_ratio: f64,
    /// Exponent of the depth weighting of the geodesic distance ([`SkinMethod::Geodesic`]
    /// only): a step into a voxel at depth `d` (voxels from the outside) costs its length
    /// times `d^-depth_exponent`, so a bone's distance leaks less through a thin contact of
    /// two body parts than through the core. Default 1 (0 is the plain geodesic distance,
    /// which roughly triples the edges torn at the MakeHuman shoulders).
    pub depth_exponent: f64,
    /// Rounds of diffusion of the geodesic weights through the voxels before the vertices
    /// sample them ([`SkinMethod::Geodesic`] only): each round replaces every voxel's weights
    /// by the mean of its own and its face neighbours' (voxels outside the figure link only
    /// where their nearest interior voxels touch), so the blend between two bones spreads over
    /// about `sqrt(2 rounds / 7)` voxels either side of where they meet, whatever the mesh's
    /// tessellation. Default 75 (about 4.6 voxels, as far as the 128 half-step rounds used
    /// before at 0.59 times the work): with none, the finely tessellated MakeHuman groins and
    /// armpits tear (54 edges past 2× over the sweep on `mh_male_heavy_short`, about 30 with
    /// the default; `reports/deformation/`).
    pub voxel_smoothing_iterations: usize,
    /// Bone radius (voxels) from which the diffusion of
    /// [`Self::voxel_smoothing_iterations`] runs at full rate ([`SkinMethod::Geodesic`] only):
    /// where the nearest joint's bones run through a thinner body part (inscribed radius `r`
    /// along them, median), each round moves a voxel's weights only `(r / blend_radius)²` of
    /// the way to its neighbours' mean (at least 5 %), so the blend across a joint spreads in
    /// proportion to the part's thickness, as bone heat's does: a hoof or a finger blends over
    /// a voxel or two, a thigh or a torso over the full width. Default 3 (the full rate on a
    /// MakeHuman thigh and torso; on the artists' skeletons of `reports/deformation/` the mean
    /// random-pose distance to the artists' weights drops from 0.88 to 0.71 % of the figure's
    /// size, most on the Quaternius animals' feet); 0 diffuses everywhere at the full rate.
    pub blend_radius: f64,
    /// Air the figure encloses ([`SkinMethod::Geodesic`] only): an outside voxel that meets
    /// the figure in all six axis directions within this fraction of the grid's longest side
    /// counts as inside for the weights, which may then cross it. A garment modelled as a thin
    /// shell around a hollow (a jacket over a skinny torso, open at the hem) then follows the
    /// bones of the body inside it rather than the arms it touches at the shoulders
    /// (`quaternius_cyberpunk_character` on its artist's skeleton: 7 edges past 2× over the
    /// sweep → 0, `reports/deformation/`). The gaps between limbs (armpits, the crotch) are
    /// open to the front and back and stay outside. Default 0.15; 0 turns it off.
    pub enclosed_air: f64,
    /// Rounds of Laplacian smoothing of the geodesic weights over the mesh's edges
    /// ([`SkinMethod::Geodesic`] only); an edge's share is scaled by (voxel size / edge
    /// length)², so coarse low-poly meshes are barely smoothed. Meshes much finer than the
    /// voxels (edges under a quarter voxel on average, such as a body subdivided to a million
    /// triangles) get proportionally fewer rounds. Default 32.
    pub smoothing_iterations: usize,
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
    /// Longest extension of the segment of a leaf joint (one without children) in
    /// [`bone_segments`](super::bone_segments), as a multiple of its parent bone's length,
    /// along the leaf's bone axis (where the skeleton's rest frames give one) or its parent
    /// bone's direction. The extension ends earlier where the figure ends (crossing gaps
    /// between shells no wider than [`Self::bone_search_radius`]) or where another bone or
    /// joint comes within the local radius (the extension has entered another body part:
    /// it then ends at that joint's inscribed ball, so that an IK foot joint below a lower leg
    /// keeps the hoof). Default infinite: a leaf bone carries the whole end of the figure it
    /// points into, however short its parent bone (a head beyond a short neck: with one parent
    /// length, the neck shared the head's skin and the head moved apart from the artist's,
    /// CesiumMan 0.74 → 0.26 % random-pose distance, `reports/deformation/`). Beyond the seed,
    /// which ends chains at end-effector points.
    pub leaf_extension: f64,
}

impl Default for SkinOptions {
    fn default() -> Self {
        Self {
            method: SkinMethod::Geodesic,
            falloff: 2.0,
            depth_exponent: 1.0,
            blend_ratio: 2.0,
            voxel_smoothing_iterations: 75,
            blend_radius: 3.0,
            enclosed_air: 0.15,
            smoothing_iterations: 32,
            sphere_scale: 1.0,
            connectivity: Connectivity::TwentySix,
            bone_sample_spacing: 0.5,
            bone_search_radius: 3,
            leaf_extension: f64::INFINITY,
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
                "falloff",
                self.falloff,
                self.falloff > 0.0 && self.falloff <= 16.0,
                "give a finite number above zero and at most 16",
            ),
            (
                "blend_ratio",
                self.blend_ratio,
                self.blend_ratio > 1.0,
                "give a finite number above 1",
            ),
            (
                "depth_exponent",
                self.depth_exponent,
                (0.0..=8.0).contains(&self.depth_exponent),
                "give a number from 0 to 8",
            ),
            (
                "blend_radius",
                self.blend_radius,
                self.blend_radius >= 0.0,
                "give zero or more voxels (0: the full rate everywhere)",
            ),
            (
                "enclosed_air",
                self.enclosed_air,
                (0.0..=1.0).contains(&self.enclosed_air),
                "give a fraction from 0 to 1 of the grid's longest side (0: off)",
            ),
            (
                "leaf_extension",
                self.leaf_extension,
                self.leaf_extension >= 0.0,
                "give zero or more (infinite: to the end of the figure)",
            ),
        ] {
            // The leaf extension may be infinite (to the end of the figure).
            let finite = value.is_finite() || (name == "leaf_extension" && value > 0.0);
            if !(ok && finite) {
                return Err(SkinError::InvalidOption {
                    name,
                    value,
                    expected,
                });
            }
        }
        if self.smoothing_iterations > 1000 {
            return Err(SkinError::InvalidOption {
                name: "smoothing_iterations",
                value: self.smoothing_iterations as f64,
                expected: "give at most 1000 rounds",
            });
        }
        if self.voxel_smoothing_iterations > 10_000 {
            return Err(SkinError::InvalidOption {
                name: "voxel_smoothing_iterations",
                value: self.voxel_smoothing_iterations as f64,
                expected: "give at most 10000 rounds",
            });
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

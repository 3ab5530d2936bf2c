//! Tunable numbers of bone generation, with their sources.

use super::BoneError;

/// Options of [`super::bones`]. Sizes are fractions of measured lengths or distance-map radii
/// (the figure's local thickness), so they hold for any unit and scale.
#[derive(Debug, Clone, PartialEq)]
pub struct BoneOptions {
    /// Vertices around each ring of a swept bone part. Default 16 (smooth enough for a preview;
    /// the tests' closedness checks hold for any value >= 3).
    pub segments: u32,
    /// Rings along a long bone's profile or a swept part. Default 12.
    pub rings: u32,
    /// Vertebra width as a fraction of the diameter of the largest sphere within the trunk.
    /// Default 1/12 (dissertation 9.1).
    pub vertebra_width: f64,
    /// Tail vertebra width ratio between successive vertebrae. Default 0.9: "a decrease of 10 %
    /// between each successive pair" (dissertation 9.1).
    pub tail_taper: f64,
    /// Long-bone shaft radius as a fraction of the median distance-map radius along its segment.
    /// Default 0.3 (measured: human humerus shaft ~11 mm in an upper arm of ~45 mm radius is
    /// 0.25; slightly more reads better in previews).
    pub shaft_fraction: f64,
    /// Largest long-bone shaft radius as a fraction of the bone's length. Default 0.08
    /// (measured ratios: human femur ~0.03, humerus ~0.04, horse cannon bone ~0.08); it keeps
    /// bones whose segment runs through the trunk (animal-like shoulders and hips lie inside
    /// the girdle sphere, 8.2) from taking the trunk's thickness.
    pub max_shaft_ratio: f64,
    /// Epiphysis (bone end) radius as a multiple of the shaft radius. Default 1.7 (human femur:
    /// condyles ~80 mm wide over a ~27 mm shaft give ~1.5-2).
    pub epiphysis_scale: f64,
    /// Cranium half-width as a fraction of the largest distance-map radius in the head.
    /// Default 0.85: "occupy as much interior space in the head as possible" (9.1), with a
    /// margin for soft tissue.
    pub cranium_fraction: f64,
    /// Rib-cage semi-axes as a fraction of its girdle sphere radius. Default 0.85 (9.1: sized
    /// by the girdle sphere; the margin keeps the ribs inside the sphere).
    pub ribcage_fraction: f64,
    /// Rib pairs per rib cage. Default 10 (human: 12 pairs, of which the lowest two are
    /// floating and short; 9.1.1 suggests a count parameter).
    pub rib_pairs: usize,
    /// Rib tube radius as a fraction of the girdle sphere radius. Default 0.04.
    pub rib_thickness: f64,
    /// Scapula width as a fraction of its length. Default 0.5 (dissertation 9.1: "half its
    /// length").
    pub scapula_width: f64,
    /// Scapula length as a fraction of its girdle segment (girdle joint → shoulder). Default 0.9.
    pub scapula_length: f64,
    /// Pelvis height (cranial extent of the iliac blades) as a multiple of the half distance
    /// between the hip sockets. Default 1.3 (human pelvis: ~22 cm tall, sockets ~17 cm apart).
    pub pelvis_height: f64,
    /// Fraction of a bone's vertices that must lie inside the figure (distance map) before the
    /// bone stops shrinking. Default 0.995.
    pub inside_fraction: f64,
    /// A bone vertex counts as inside the figure when the distance map, interpolated
    /// trilinearly between voxel centres, reaches this value there, voxel units. Default 1.0:
    /// as deep as the shallowest interior voxel centres (the surface lies between them and the
    /// first exterior centres, near the 0.5 level).
    pub clearance: f64,
    /// A bone with a smaller fraction of its vertices inside the figure at its best placement
    /// is left out (with a warning): its segment runs outside the figure. Default 0.5.
    pub min_inside_fraction: f64,
    /// Factor by which a bone's size shrinks per fitting step when too many of its vertices
    /// lie outside. Default 0.85.
    pub shrink_step: f64,
    /// Maximum number of shrinking steps; a bone still outside afterwards is kept with a
    /// warning. Default 12 (0.85^12 ≈ 0.14 of the measured size).
    pub max_shrink_steps: usize,
    /// Radius of the articulation sphere round each joint (where bones may meet), as a
    /// fraction of the distance-map radius at the joint. Default 0.6 (the ends of long bones
    /// reach about 0.5 of the local thickness).
    pub articulation: f64,
    /// Caudal shift of a rib cage's centre from its girdle sphere centre, as a fraction of the
    /// sphere radius. Default 0.4 (the thorax extends behind/below the shoulders).
    pub ribcage_shift: f64,
    /// Gap left between neighbouring bones (scapula above the rib cage, ribs beside the
    /// vertebrae), as a fraction of the girdle sphere radius. Default 0.04.
    pub gap: f64,
}

impl Default for BoneOptions {
    fn default() -> Self {
        Self {
            segments: 16,
            rings: 12,
            vertebra_width: 1.0 / 12.0,
            tail_taper: 0.9,
            shaft_fraction: 0.3,
            max_shaft_ratio: 0.08,
            epiphysis_scale: 1.7,
            cranium_fraction: 0.85,
            ribcage_fraction: 0.85,
            rib_pairs: 10,
            rib_thickness: 0.04,
            scapula_width: 0.5,
            scapula_length: 0.9,
            pelvis_height: 1.3,
            inside_fraction: 0.995,
            clearance: 1.0,
            min_inside_fraction: 0.5,
            shrink_step: 0.85,
            max_shrink_steps: 12,
            gap: 0.04,
            articulation: 0.6,
            ribcage_shift: 0.4,
        }
    }
}

impl BoneOptions {
    /// Checks every field's range.
    ///
    /// # Errors
    /// [`BoneError::BadOption`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), BoneError> {
        let bad = |name: &'static str, value: f64, range: &'static str| {
            Err(BoneError::BadOption { name, value, range })
        };
        if !(3..=256).contains(&self.segments) {
            return bad("segments", self.segments as f64, "[3, 256]");
        }
        if !(2..=256).contains(&self.rings) {
            return bad("rings", self.rings as f64, "[2, 256]");
        }
        if self.rib_pairs > 64 {
            return bad("rib_pairs", self.rib_pairs as f64, "[0, 64]");
        }
        if self.max_shrink_steps > 100 {
            return bad("max_shrink_steps", self.max_shrink_steps as f64, "[0, 100]");
        }
        for (name, value) in [
            ("vertebra_width", self.vertebra_width),
            ("shaft_fraction", self.shaft_fraction),
            ("max_shaft_ratio", self.max_shaft_ratio),
            ("cranium_fraction", self.cranium_fraction),
            ("ribcage_fraction", self.ribcage_fraction),
            ("rib_thickness", self.rib_thickness),
            ("scapula_width", self.scapula_width),
            ("scapula_length", self.scapula_length),
            ("tail_taper", self.tail_taper),
            ("inside_fraction", self.inside_fraction),
            ("min_inside_fraction", self.min_inside_fraction),
            ("shrink_step", self.shrink_step),
            ("articulation", self.articulation),
            ("ribcage_shift", self.ribcage_shift),
        ] {
            if !(value > 0.0 && value <= 1.0) {
                return bad(name, value, "(0, 1]");
            }
        }
        for (name, value) in [
            ("epiphysis_scale", self.epiphysis_scale),
            ("pelvis_height", self.pelvis_height),
        ] {
            if !(1.0..=4.0).contains(&value) {
                return bad(name, value, "[1, 4]");
            }
        }
        if !(0.0..=10.0).contains(&self.clearance) {
            return bad("clearance", self.clearance, "[0, 10]");
        }
        if !(0.0..=0.5).contains(&self.gap) {
            return bad("gap", self.gap, "[0, 0.5]");
        }
        Ok(())
    }
}

//! Fit parameters.

use super::FitError;
use crate::template::Preset;

/// Moving limb joints onto the bends of their path (see [`FitOptions::snap_to_bend`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BendSnap {
    /// Search half-window around a joint's Table 8.1 place, as a fraction of the limb's length
    /// outside the girdle.
    pub window: f64,
    /// Half-length of the stencil that measures the path's turning angle, same units.
    pub stencil: f64,
    /// Smallest turning angle that moves a joint, degrees.
    pub min_angle: f64,
}

/// Tunables of the anatomical fit. Ratios, counts and DOFs come from the template; these are the
/// geometric choices the dissertation leaves open.
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// Naming preset of the output joints. Default anatomical (DESIGN.md, Joint names).
    pub preset: Preset,
    /// Points the head-to-tail path is resampled to before offsetting and smoothing.
    /// Default 256 (enough for ~20 vertebrae at 10+ samples each; chosen).
    pub axial_samples: usize,
    /// Smoothing half-window of the adjusted head-to-tail path, in vertebral segment lengths
    /// (moving average, ends fixed; dissertation 8.1 smooths "as in 5.2.4"). Default 0.5.
    pub axial_smoothing: f64,
    /// Length over which the trunk's dorsal offset fades into the neck and tail, in vertebral
    /// segment lengths. Default 1.0 (one vertebra; chosen to avoid a step).
    pub offset_blend: f64,
    /// Half-width of the S-shaped cervical replacement window around the head/neck junction,
    /// as a fraction of the neck section's length. Default 0.5 (the anterior half of the neck,
    /// 8.1 "near the junction of the head and neck sections").
    pub cervical_window: f64,
    /// Dorsal offset of the cervical replacement at the junction, as a fraction of the dorsal
    /// ray's depth (or of the distance-map radius without a probe). Default 0.7 (as the trunk).
    pub cervical_depth: f64,
    /// Lateral displacement of a pectoral girdle joint from the dorsal spine, as a fraction of
    /// the girdle sphere radius. Default 0.25 (chosen: scapulae sit beside the spine).
    pub girdle_lateral: f64,
    /// Anterior (pectoral) or posterior (pelvic) offset of animal-like shoulders/hips inside
    /// the girdle sphere, as a fraction of its radius (8.2, "offset in the anterior direction
    /// for pectoral girdles or in the posterior direction for pelvic girdles"). Default 0.3.
    pub girdle_offset: f64,
    /// Largest distance of an interior shoulder/hip from the sphere centre, as a fraction of the
    /// radius (8.2: "inside the girdle sphere"). Default 0.95.
    pub girdle_inside: f64,
    /// Anterior shift of wing joints towards the leading edge, as a fraction of the local
    /// distance-map radius (8.2 shifts them "to the anterior edge"). Default 0.8.
    pub wing_shift: f64,
    /// Smoothing half-window of limb and digit paths, in points (8.2 smooths the limb paths).
    /// Default 2.
    pub limb_smoothing: usize,
    /// A tail is built when the path extends past the hindmost pair by at least this many
    /// vertebral segment lengths. Default 0.5.
    pub min_tail: f64,
    /// The neck/trunk boundary is moved this many girdle-sphere radii anteriorly from the
    /// foremost pair's midpoint (0 = dissertation 8.1). Beyond the seed: the pectoral girdle
    /// fills its sphere and the cervical vertebrae start at its anterior edge. Default 1.0
    /// (measured with reference-joint paths on the six MakeHuman humanoids: neck error mean
    /// 97 mm at 0, see tests/it/fit.rs `oracle_paths_on_makehuman`).
    pub neck_at_girdle_edge: f64,
    /// Without a pectoral limb pair, the neck/trunk boundary is put at this fraction of the way
    /// from the head tip to the hindmost pair. Default 0.35 (chosen: a human's head and neck
    /// take about a third of the head-to-crotch path).
    pub fallback_trunk_start: f64,
    /// Where the limb's outer segmentation starts (the human-like shoulder/hip, the animal-like
    /// elbow/knee): `true` at the path point nearest [`LimbInput::root`](super::LimbInput)
    /// (where the labelled limb leaves the trunk) when given; `false` at the exit of the girdle
    /// sphere (dissertation 8.2). Beyond the seed: the sphere's radius is the trunk's
    /// front-back half-depth, so its exit lies well inside a human's shoulders. Default true
    /// (measured, see `reports/rig/`).
    pub root_from_labels: bool,
    /// Inner limb joints (elbow/knee, wrist/ankle, ...) move to the sharpest bend of the limb
    /// path near their Table 8.1 place (seed 004: joints are where limbs bend); `None` keeps
    /// Table 8.1 alone (8.2). Default window 0.15, stencil 0.06, 20 degrees (reference
    /// humanoids' 15-joint mean error 34.0 → 30.2 mm).
    pub snap_to_bend: Option<BendSnap>,
    /// Head/neck boundary at the narrowest point of the head-to-tail path between these
    /// fractions of the way from the head tip to the neck/trunk boundary; `None` uses the
    /// template's `[sections]` fractions (8.1). Default `None` (`Some([0.2, 0.8])` helps only
    /// long necks: quadruped CD-J2J 3.98 → 3.88 %, MakeHuman heads 10 mm off).
    pub head_at_narrowing: Option<[f64; 2]>,
    /// Human-like shoulders and hips from labelled roots lie on the axis of the upper arm /
    /// thigh, fitted to this central fraction of that segment, at the point nearest the
    /// labelled root. Default 0.6 (chosen: avoids the bulges at both ends).
    pub root_axis_span: f64,
    /// The root joint lies this many vertebral segments anterior of the hindmost limb pair's
    /// point on the spine (clamped to the trunk). Default 0 ("the root joint at the hindmost
    /// limb pair", 8.1); 0.5 puts it mid-way along the last trunk segment.
    pub root_offset: f64,
    /// How far the root joint follows the trunk's dorsal offset: 0 on the centred
    /// head-to-tail path (the pelvic girdle's centre, where rigs put the pelvis), 1 on the
    /// dorsal spine. Default 0 (measured on the reference rigs, see `reports/rig/`).
    pub root_dorsal: f64,
    /// Animal-like knees and elbows where the limb comes free of the trunk: the first point
    /// down the limb path from which a horizontal ray towards the other limb pair leaves the
    /// figure within this many local path radii (the knee then one radius behind that surface
    /// point, the elbow on the path); only the knee or elbow moves, never towards the trunk.
    /// `None` keeps the labelled root. Needs the fit's ray probe (`fit_with_probe`). Default 3
    /// (Quaternius quadrupeds' worse knee 12.0 → 4.8 % of height from the reference stifle).
    pub limb_fold: Option<f64>,
    /// For templates with the S-shaped neck, the trunk's dorsal offset fades out this many
    /// vertebral segments before the neck/trunk boundary (not behind the foremost girdle), so
    /// the neck leaves the trunk at the chest's front, as the cervical spine does. 0 =
    /// dissertation 8.1. Default 2 (the fox's neck joint 35 → 15 mm from its reference).
    pub neck_base_drop: f64,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            preset: Preset::Anatomical,
            axial_samples: 256,
            axial_smoothing: 0.5,
            offset_blend: 1.0,
            cervical_window: 0.5,
            cervical_depth: 0.7,
            girdle_lateral: 0.25,
            girdle_offset: 0.3,
            girdle_inside: 0.95,
            wing_shift: 0.8,
            limb_smoothing: 2,
            min_tail: 0.5,
            neck_at_girdle_edge: 1.0,
            fallback_trunk_start: 0.35,
            root_from_labels: true,
            snap_to_bend: Some(BendSnap {
                window: 0.15,
                stencil: 0.06,
                min_angle: 20.0,
            }),
            head_at_narrowing: None,
            root_axis_span: 0.6,
            root_offset: 0.0,
            root_dorsal: 0.0,
            limb_fold: Some(3.0),
            neck_base_drop: 2.0,
        }
    }
}

impl FitOptions {
    /// Checks the ranges.
    ///
    /// # Errors
    /// [`FitError::InvalidOption`] naming the first bad field.
    pub fn validate(&self) -> Result<(), FitError> {
        let fraction = |name: &'static str, v: f64, lo: f64, hi: f64| {
            if v.is_finite() && v >= lo && v <= hi {
                Ok(())
            } else {
                Err(FitError::InvalidOption {
                    name,
                    value: v,
                    range: format!("[{lo}, {hi}]"),
                })
            }
        };
        if self.axial_samples < 16 {
            return Err(FitError::InvalidOption {
                name: "axial_samples",
                value: self.axial_samples as f64,
                range: "16 or more".into(),
            });
        }
        fraction("axial_smoothing", self.axial_smoothing, 0.0, 10.0)?;
        fraction("offset_blend", self.offset_blend, 0.0, 10.0)?;
        fraction("cervical_window", self.cervical_window, 0.0, 1.0)?;
        fraction("cervical_depth", self.cervical_depth, 0.0, 1.0)?;
        fraction("girdle_lateral", self.girdle_lateral, 0.0, 1.0)?;
        fraction("girdle_offset", self.girdle_offset, 0.0, 1.0)?;
        fraction("girdle_inside", self.girdle_inside, 0.0, 1.0)?;
        fraction("wing_shift", self.wing_shift, 0.0, 2.0)?;
        fraction("min_tail", self.min_tail, 0.0, 10.0)?;
        fraction("neck_at_girdle_edge", self.neck_at_girdle_edge, 0.0, 3.0)?;
        fraction("root_offset", self.root_offset, 0.0, 10.0)?;
        fraction("root_dorsal", self.root_dorsal, 0.0, 1.0)?;
        fraction("neck_base_drop", self.neck_base_drop, 0.0, 10.0)?;
        if let Some(k) = self.limb_fold {
            fraction("limb_fold", k, 0.5, 20.0)?;
        }
        if let Some([lo, hi]) = self.head_at_narrowing {
            fraction("head_at_narrowing[0]", lo, 0.0, 1.0)?;
            fraction("head_at_narrowing[1]", hi, lo, 1.0)?;
        }
        if let Some(b) = self.snap_to_bend {
            fraction("snap_to_bend.window", b.window, 0.0, 0.5)?;
            fraction("snap_to_bend.stencil", b.stencil, 0.0, 0.5)?;
            fraction("snap_to_bend.min_angle", b.min_angle, 0.0, 180.0)?;
        }
        fraction("root_axis_span", self.root_axis_span, 0.05, 1.0)?;
        fraction(
            "fallback_trunk_start",
            self.fallback_trunk_start,
            0.05,
            0.95,
        )?;
        Ok(())
    }
}

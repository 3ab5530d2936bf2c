//! Tunable numbers of the refinement, with their sources.

use super::full_spine::SpineDetail;
use crate::options::{Checks, OptionProblems};
use serde::{Deserialize, Serialize};

/// Options of [`super::refine`]. Lengths given as fractions of the figure's height (measured
/// along the body's transverse normal) so that one set of defaults serves children and adults
/// in any unit.
#[derive(Debug, Clone, PartialEq)]
pub struct RefineOptions {
    /// Whether [`crate::pipeline::rig`] refines the joints of humanoid fits (`skelfit rig
    /// --refine on|off`); [`super::refine`] itself ignores it. Default true.
    pub in_rig: bool,
    /// Whether [`crate::pipeline::rig`] makes the paired joints of a bilaterally symmetric
    /// figure mirror each other ([`super::symmetrize`]), for every template. Default true.
    pub symmetry: bool,
    /// The spine [`super::refine_fit`] outputs (`skelfit rig --spine coarse|full`). Default
    /// [`SpineDetail::Coarse`]: the template's trunk and neck joints, placed on the spine curve.
    pub spine: SpineDetail,
    /// Taubin smoothing passes of the joined voxel solid's boundary, which
    /// [`crate::pipeline::rig`] slices instead of an input made of several shells or not closed.
    /// Default 10 (rounds the voxel staircase; the volume stays within a few percent).
    pub joined_smoothing: usize,
    /// Canonical keys (e.g. `knee_L`) left at their rough positions even when refinement
    /// finds them. Default empty (refine every joint it can).
    pub keep: Vec<String>,
    /// Spacing of the transverse head slices, fraction of height. Default 0.004 (7 mm on a
    /// 1.75 m figure): fine enough that the chin-throat transfer is seen within a centimetre
    /// (seed 004, 3.1).
    pub head_slice_step: f64,
    /// The head ends where a slice's diameter falls below this fraction of the largest head
    /// slice's diameter ("shrinked significantly", seed 004, 3.1). Default 0.75: the neck is
    /// 55-65 % of the head's length on the MakeHuman bodies (measurement).
    pub head_shrink_ratio: f64,
    /// The head also ends where the major axis has turned by more than this angle (degrees)
    /// from the largest slice's (the 90° head-torso transfer, seed 004, 3.1). Default 60.
    pub head_turn_degrees: f64,
    /// Principal axes only count as turned when both slices are at least this elongated
    /// (major / minor diameter); round slices have no meaningful axis. Default 1.1.
    pub head_min_elongation: f64,
    /// Neither criterion is checked above this depth below the top, fraction of height: the
    /// first slices of the skull are small and round, their axes meaningless. Default 0.05
    /// (9 cm on 1.75 m, about the forehead).
    pub head_min_depth: f64,
    /// The head search stops in any case this far below the top, fraction of height. Default
    /// 0.2 (a head is about 1/8 of an adult's height, 1/5-1/6 of a child's).
    pub head_max_depth: f64,
    /// Part of the nose-level slice used as the back of the head for the occipital circle:
    /// points whose forward coordinate is behind the slice centroid by at least this fraction
    /// of the slice's forward extent. Default 0.1 (seed 004, 3.1, fig. 2).
    pub head_back_fraction: f64,
    /// Where the head joint goes. Default [`HeadLevel::Auto`]: nose level on a head with a
    /// face, else the top of the neck.
    pub head_level: HeadLevel,
    /// Automatic head level: the head's forward-most slice is a nose, and the joint goes to
    /// nose level, when it lies between these fractions of the head's sliced length above its
    /// lowest slice. Defaults 0.1 and 0.45 (a nose tip is about a third of the way up from the
    /// chin; at the bottom the forward-most slice is a chin or collar, higher a visor, brim or
    /// hair).
    pub head_nose_min: f64,
    /// See [`Self::head_nose_min`].
    pub head_nose_max: f64,
    /// Neck top: how much further than `head_max_depth` the neck is searched, fraction of
    /// height. Default 0.1 (the neck below a head that fills the whole head search).
    pub head_neck_search: f64,
    /// Neck top: the head begins at the first slice above the narrowest neck slice whose
    /// diameter is this many times the neck's. Default 1.5 (a head is about twice as wide as
    /// its neck; hair, helmets and stylised heads more).
    pub head_neck_widening: f64,
    /// Step between Plumber sphere centres along a limb, fraction of height. Default 0.008
    /// (14 mm on 1.75 m: about a third of a wrist's diameter).
    pub limb_step: f64,
    /// Sphere radius as a multiple of the local limb radius (perimeter / 2π of the previous
    /// slice): the sphere must be larger than the tube to cut it (Mortara et al. 2004 grow the
    /// radius with the tube). Default 1.5.
    pub sphere_radius_factor: f64,
    /// A slice whose perimeter exceeds the previous one by this factor means the sphere has
    /// reached the torso (or the foot): the limb trace stops. Default 1.6.
    pub merge_ratio: f64,
    /// A slice whose perimeter is below this fraction of the previous one means the limb has
    /// split into digits: the trace stops. Default 0.6.
    pub split_ratio: f64,
    /// Limbs are traced beyond their distal rough joint by this fraction of the distal segment
    /// (into hand and foot, needed by the wrist and ankle criteria). Default 0.7.
    pub distal_overshoot: f64,
    /// Knees and elbows: a smallest angle above this (degrees) counts as a straight limb and the
    /// limb ratio is used instead (seed 004, 3.3). Default 160: the MakeHuman legs (straight)
    /// measure 164-174 degrees at their most bent curve point and the A-pose arms 138-144;
    /// 165 sat inside the legs' range, so moving a hip by a centimetre could flip a child's
    /// knee to the smallest-angle rule and 7 cm up the thigh.
    pub straight_degrees: f64,
    /// Upper leg's share of the hip-ankle height where the knee of a straight leg is searched
    /// (Dellas et al. 2007 via seed 004, 3.3). Default 0.485: the mean of the MakeHuman
    /// reference rigs' (hip - knee) / (hip - ankle) heights, 0.448-0.499 (the heavy body's
    /// 0.448 is the low outlier; 0.49 left its knees 32 mm low, 0.485 leaves 28 mm).
    pub leg_ratio: f64,
    /// When set, the knee of a straight leg is placed in the transverse cross-section at
    /// `leg_ratio` of the way from the hip's height to the ankle's, at its centroid across the
    /// body and at this fraction of its depth from the back (0) to the front (1), instead of on
    /// the sphere slices' centroid curve. Default `Some(0.5)`: the femoral condyles fill the
    /// knee's depth and the MakeHuman knees lie at 0.47-0.60 of it (measurement), while the
    /// sphere slices' centroids, tilted into the calf, were 10-20 mm behind them.
    pub knee_depth: Option<f64>,
    /// Upper arm's share of the shoulder-wrist length for a straight arm. Default 0.54:
    /// humerus / (humerus + ulna) of adult anthropometry (~0.31 m / 0.26 m).
    pub arm_ratio: f64,
    /// When set, the shoulder found from the armpit is moved along the body's forward to this
    /// fraction of the body's depth through it (0 the back, 1 the front; the sagittal slice
    /// through the joint). Default `Some(0.5)`: the humeral head sits mid-way between the front
    /// and back of the shoulder (the MakeHuman shoulders at 0.48-0.54 of it, measurement),
    /// while the arm line's cut was 0-14 mm behind it.
    pub shoulder_depth: Option<f64>,
    /// The shoulder is moved proximally along the upper arm's line from the armpit plane's cut
    /// by this multiple of the upper arm's radius (median slice perimeter / 2π). Default 0.5:
    /// the humeral head's centre lies above the plane through the armpit; without the move the
    /// MakeHuman shoulders came out 3-29 mm too far down the arm, with it 1-34 mm (mean error
    /// 14.5 mm against 18; 1.0 overshoots on slim bodies; measurement with
    /// `skelfit bench --method anatomical`).
    pub shoulder_proximal: f64,
    /// When set, the shoulder's height is taken from the top of the shoulder instead: this
    /// multiple of the upper arm's radius below the first surface crossing straight above the
    /// joint (the acromion's skin). Default `Some(1.4)`: on the MakeHuman bodies the humeral
    /// head's centre lies 1.15-1.73 radii below that surface (mean 1.38), while its height
    /// above the armpit varies from 37 to 84 mm (a heavy body's armpit hangs low), which had
    /// put the heavy body's shoulders 34 mm too low.
    pub shoulder_below_top: Option<f64>,
    /// Half-width of the minimal-perimeter search around the ratio point, fraction of the limb
    /// length. Default 0.02: a wider window pulls the knee to the thin part below the patella,
    /// 3-4 cm under the MakeHuman knees (measurement).
    pub ratio_window: f64,
    /// The ankle is searched on the part of the leg curve below this fraction of the rough
    /// knee-ankle segment. Default 0.6.
    pub ankle_search_from: f64,
    /// When set, the ankle found on the leg's centroid curve is moved along the body's up to
    /// this fraction of height above its sole (the lowest mesh point under it). Default
    /// `Some(0.042)`: the ankle joint (talocrural axis) is at 0.040-0.043 of stature on all six
    /// MakeHuman reference rigs (measurement), close to the classical anthropometric 0.039 of
    /// Drillis and Contini (1966). The seed's curvature maximum alone was 11-24 mm off in
    /// height on those bodies; `None` keeps it.
    pub ankle_height: Option<f64>,
    /// When set, the ankle's depth (along the body's forward) is that of the shin's axis at
    /// the ankle's height: a line fitted through the leg's centroid curve from 0.4 of the way
    /// between the knee and the curvature maximum down to half a curvature window above it.
    /// Default `true`: the foot pulls the sphere slices' centroids forward around the ankle,
    /// which put the curvature maximum 1-14 mm in front of the MakeHuman ankles and 46-49 mm
    /// in front of CesiumMan's (measurement); on the shin's axis they are 0-4 and 22-24 mm off.
    pub ankle_on_shin_axis: bool,
    /// The wrist is searched on the part of the arm curve beyond this fraction of the rough
    /// elbow-wrist segment (at most of the rough shoulder-elbow one: a forearm is shorter than
    /// the upper arm). Default 0.5.
    pub wrist_search_from: f64,
    /// Curvature on the leg's centroid curve is measured over this arc-length window, fraction
    /// of height. Default 0.03 (5 cm).
    pub curvature_window: f64,
    /// Height of the hip slice above the crotch, fraction of the way from the crotch up to the
    /// shoulders (refined, else rough). Default 0.155. The seed (3.3) averages the crotch and
    /// sacroiliac heights; on the MakeHuman bodies the buttocks' flat bulge made the
    /// sacroiliac height unstable (the hip joints lay at 0.7-1.1 of the way from crotch to
    /// sacroiliac point), while the reference hips lay 0.150-0.159 of the way from the crotch
    /// to the shoulders on the five adults and 0.184 on the child (measurement). It was 0.050
    /// of the height (0.048-0.058 on those bodies), which sent a short-legged figure's hips
    /// too high: the pelvis scales with the trunk, not the stature (quaternius_knight 0.163
    /// of its trunk, men_adventurer 0.150, platformer character about 0.10).
    /// The crotch is the top of the gap between the legs (where transverse slices stop cutting
    /// two thighs), or the lowest point of the median-plane silhouette when the legs touch.
    pub hip_above_crotch: f64,
    /// When set, each hip (the centroid of its half of the hip slice) is moved along the
    /// body's forward to this fraction of the body's depth through it (0 the back, 1 the
    /// front; the sagittal slice through the joint). Default `Some(0.45)`: the half-slice
    /// centroid lay 17-21 mm in front of the male MakeHuman hips (the genital bulge) and 0-9
    /// mm on the others; at 0.45 the hips are within 10 mm in depth on all six (measurement
    /// with `skelfit bench --method anatomical`).
    pub hip_depth: Option<f64>,
    /// The pelvis (root) joint lies this fraction of height above the midpoint of the hips.
    /// Default 0.006: the pelvis's centre is above the hip sockets, which sit low on it; the
    /// MakeHuman root joints are 0.003-0.010 of height above the hips' midpoint (mean 0.006,
    /// measurement).
    pub pelvis_above_hips: f64,
    /// The back's neck point and the throat are searched no higher than this fraction of the
    /// way from the shoulders to the head joint. Default 0.6 (0.5 until the refinement report
    /// of 659069c): the back of the neck rises forward up to the skull, so the seed's local
    /// maximum (3.2) is reached only at the window's end; C7/T1 of the MakeHuman rigs lies at
    /// 0.51-0.52 of the way (measurement).
    pub neck_window: f64,
    /// C7/T1 (the `neck` joint) lies this fraction of the way from the back of the neck to the
    /// throat, on the segment between the two silhouette points. Default 0.3: the cervical
    /// vertebral bodies sit in the posterior part of the neck, the larynx and trachea in front
    /// of them; the MakeHuman C7/T1 joints lie 0.18-0.40 of the way (mean 0.29, measurement).
    /// The seed's midpoint (0.5) put the neck 11-25 mm in front of those.
    pub neck_depth: f64,
    /// Resampling step of the median silhouette before its cubic B-spline, fraction of height.
    /// Default 0.004.
    pub silhouette_step: f64,
    /// Depth of the thoracic spine (T6/T7) in front of the back point, fraction of height: the
    /// seed's "heuristical value depending on the body's overall height" (3.2). Default 0.035
    /// (6 cm on 1.75 m: skin, spinous process and lamina to the vertebral body's back). A trunk
    /// deep for its height (a stylised figure) takes a share of its depth there instead when
    /// that is more (a quarter at T6, three tenths at L3 and the sacrum; `refine::spine`).
    pub thoracic_depth: f64,
    /// Depth of the lumbar spine (L3/L4) in front of the lumbar point, fraction of height.
    /// Default 0.04.
    pub lumbar_depth: f64,
    /// Depth of the sacrum centre in front of the sacroiliac point, fraction of height.
    /// Default 0.045.
    pub sacral_depth: f64,
    /// Meshes whose mean edge is longer than this fraction of height are split at edge
    /// midpoints first (up to three times): slices cut triangles by their corners' sides, and a
    /// limb of a 3k-triangle body has triangles longer than the spheres' radius. Default 0.01
    /// (the 27k-triangle MakeHuman bodies are below it, their 3k decimations four times
    /// above; measurement).
    pub max_mean_edge: f64,
    /// A refined joint farther than this from its rough position (fraction of height) is
    /// rejected and the joint keeps its rough position with a warning. Default 0.09: the rough
    /// skeletons to refine are off by up to ~6 cm (issue 6), twice that is a failed analysis.
    pub max_shift: f64,
    /// Whether a round separate piece at a limb joint (a jointed figure's ball between two
    /// rigid limb pieces) places that joint at its centre ([`super::joint_balls`]). Default
    /// true: a figure made of one surface has no such piece and is left alone.
    pub joint_pieces: bool,
}

impl RefineOptions {
    /// Checks every option. Steps and sizes must be above zero (a zero head slice step would
    /// never leave the top); every number must be finite (a NaN `max_shift` would accept any
    /// move).
    ///
    /// # Errors
    /// Every option out of range.
    pub fn validate(&self) -> Result<(), OptionProblems> {
        let mut c = Checks::default();
        c.positive("head_slice_step", self.head_slice_step, 0.1);
        c.range(
            "joined_smoothing",
            self.joined_smoothing as f64,
            0.0,
            1000.0,
        );
        c.positive("head_shrink_ratio", self.head_shrink_ratio, 1.0);
        c.range("head_turn_degrees", self.head_turn_degrees, 0.0, 180.0);
        c.range("head_min_elongation", self.head_min_elongation, 1.0, 100.0);
        c.range("head_min_depth", self.head_min_depth, 0.0, 1.0);
        c.range("head_max_depth", self.head_max_depth, 0.0, 1.0);
        c.range("head_back_fraction", self.head_back_fraction, 0.0, 1.0);
        c.range("head_neck_search", self.head_neck_search, 0.0, 1.0);
        c.range("head_nose_min", self.head_nose_min, 0.0, 1.0);
        c.range("head_nose_max", self.head_nose_max, self.head_nose_min, 1.0);
        c.range("head_neck_widening", self.head_neck_widening, 1.0, 100.0);
        c.positive("limb_step", self.limb_step, 0.1);
        c.positive("sphere_radius_factor", self.sphere_radius_factor, 10.0);
        c.positive("merge_ratio", self.merge_ratio, 100.0);
        c.range("split_ratio", self.split_ratio, 0.0, 100.0);
        c.range("distal_overshoot", self.distal_overshoot, 0.0, 10.0);
        c.range("straight_degrees", self.straight_degrees, 0.0, 180.0);
        c.range("leg_ratio", self.leg_ratio, 0.0, 1.0);
        c.range("arm_ratio", self.arm_ratio, 0.0, 1.0);
        c.range("shoulder_proximal", self.shoulder_proximal, 0.0, 10.0);
        c.range("ratio_window", self.ratio_window, 0.0, 1.0);
        c.range("ankle_search_from", self.ankle_search_from, 0.0, 1.0);
        c.range("wrist_search_from", self.wrist_search_from, 0.0, 1.0);
        c.positive("curvature_window", self.curvature_window, 1.0);
        c.range("hip_above_crotch", self.hip_above_crotch, -1.0, 1.0);
        c.range("pelvis_above_hips", self.pelvis_above_hips, -1.0, 1.0);
        c.range("neck_window", self.neck_window, 0.0, 1.0);
        c.range("neck_depth", self.neck_depth, 0.0, 1.0);
        c.positive("silhouette_step", self.silhouette_step, 0.1);
        c.range("thoracic_depth", self.thoracic_depth, 0.0, 1.0);
        c.range("lumbar_depth", self.lumbar_depth, 0.0, 1.0);
        c.range("sacral_depth", self.sacral_depth, 0.0, 1.0);
        c.positive("max_mean_edge", self.max_mean_edge, 1.0);
        c.range("max_shift", self.max_shift, 0.0, 10.0);
        for (name, value) in [
            ("knee_depth", self.knee_depth),
            ("shoulder_depth", self.shoulder_depth),
            ("ankle_height", self.ankle_height),
            ("hip_depth", self.hip_depth),
        ] {
            if let Some(v) = value {
                c.range(name, v, 0.0, 1.0);
            }
        }
        if let Some(v) = self.shoulder_below_top {
            c.range("shoulder_below_top", v, 0.0, 10.0);
        }
        c.finish()
    }
}

/// Where the head joint sits: two conventions of rigging.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HeadLevel {
    /// At nose level when the head has a face (its forward-most slice is a nose, see
    /// [`RefineOptions::head_nose_min`]), else at the top of the neck.
    #[default]
    Auto,
    /// At the top of the neck, where its section widens into the head: game and engine rigs
    /// (Mixamo, Unreal, Unity humanoids, Quaternius, GDQuest) and the glTF sample characters.
    NeckTop,
    /// At nose level, between the head's centroid and the centre of the back of the skull
    /// (seed 004, 3.1, fig. 2): MakeHuman's rigs.
    NoseLevel,
}

impl Default for RefineOptions {
    fn default() -> Self {
        Self {
            in_rig: true,
            symmetry: true,
            spine: SpineDetail::Coarse,
            joined_smoothing: 10,
            head_slice_step: 0.004,
            head_shrink_ratio: 0.75,
            head_turn_degrees: 60.0,
            head_min_elongation: 1.1,
            head_min_depth: 0.05,
            head_max_depth: 0.2,
            head_level: HeadLevel::Auto,
            head_nose_min: 0.1,
            head_nose_max: 0.45,
            head_neck_search: 0.1,
            head_neck_widening: 1.5,
            head_back_fraction: 0.1,
            limb_step: 0.008,
            sphere_radius_factor: 1.5,
            merge_ratio: 1.6,
            split_ratio: 0.6,
            distal_overshoot: 0.7,
            keep: Vec::new(),
            straight_degrees: 160.0,
            leg_ratio: 0.485,
            knee_depth: Some(0.5),
            arm_ratio: 0.54,
            shoulder_depth: Some(0.5),
            shoulder_proximal: 0.5,
            shoulder_below_top: Some(1.4),
            ratio_window: 0.02,
            ankle_search_from: 0.6,
            ankle_height: Some(0.042),
            ankle_on_shin_axis: true,
            wrist_search_from: 0.5,
            curvature_window: 0.03,
            hip_above_crotch: 0.155,
            hip_depth: Some(0.45),
            pelvis_above_hips: 0.006,
            neck_window: 0.6,
            neck_depth: 0.3,
            silhouette_step: 0.004,
            thoracic_depth: 0.035,
            lumbar_depth: 0.04,
            sacral_depth: 0.045,
            max_mean_edge: 0.01,
            max_shift: 0.09,
            joint_pieces: true,
        }
    }
}

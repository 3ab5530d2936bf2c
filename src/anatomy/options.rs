//! Parameters of the level graph and of body-part labelling.

use super::AnatomyError;
use crate::medial::MedialOptions;
use crate::paths::PathOptions;
use crate::voxel::VoxelOptions;
use glam::DVec3;
use serde::Serialize;

/// How the forward direction is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Forward {
    /// A given direction (need not be axis-aligned; its component along up is ignored).
    Direction(DVec3),
    /// Found from the figure (see `facing`): labelled once facing the file's convention (+Z,
    /// turned with the up found), then again facing the direction its paired limbs, feet or
    /// head and tail show, when that is another one.
    Auto,
}

/// How the up direction is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Up {
    /// A given direction.
    Direction(DVec3),
    /// Found from the figure (see [`find_up`](super::find_up)): +Y (the glTF convention) when
    /// the figure stands on a pair of legs under it, else the axis (±X, ±Y,
    /// ±Z) whose labels make the most complete one; +Y with a warning when none is complete.
    Auto,
}

impl Up {
    /// The given direction, or +Y for [`Up::Auto`] (the first candidate).
    pub fn or_default(self) -> DVec3 {
        match self {
            Up::Direction(d) => d,
            Up::Auto => DVec3::Y,
        }
    }
}

/// Options of the level graph ([`level_graph`](super::level_graph), ch.7.3.1-7.3.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LevelOptions {
    /// Number of heart-value bins (strata) of the level graph. Default 20 ("about twenty sets
    /// works fine for most figures", ch.7.3.1). At least 2.
    pub bins: usize,
    /// A vertex whose distal fraction (its DMS voxels plus those of every vertex distal to it,
    /// over all DMS voxels) is below this is *insignificant*. Default 0.005: ch.7.3.2 names
    /// only "a very small fraction"; 0.5 % keeps ears and fingers out and every limb of the
    /// reference models in (their smallest limb, the fox's fore leg, holds ~3 %).
    pub insignificant_fraction: f64,
    /// A vertex merging at least two previously disconnected regions each holding at least this
    /// distal fraction is a *major junction*. Default 0.02: ch.7.3.2 says "sufficiently large";
    /// 2 % is above ears, fingers and toes and below every limb, head and tail of the reference
    /// models.
    pub junction_fraction: f64,
    /// Fraction of the figure's extent along up (resp. forward) within which a DMS voxel marks
    /// its vertex as extreme up/down (resp. forward/backward). Default 0.1 ("top 10 %",
    /// ch.7.3.2).
    pub extreme_fraction: f64,
    /// A vertex has a *linear* cross-section when a farthest point of its voxel group lies more
    /// than this multiple of the inscribed radius from its centroid. Default 1.5 ("a multiple
    /// of 1.5 seems to work fairly well", ch.7.3.2).
    pub linear_ratio: f64,
    /// How interior voxels (and through them mesh vertices and the marks' reach) are given to
    /// DMS voxels: the one minimising path length through the interior minus this multiple of
    /// its inscribed radius (0: nearest centre; 1: nearest sphere surface), in `[0, 1]`.
    /// Default 0: measured on the reference models, the mean per-vertex agreement of the six
    /// quadrupeds was 91.8 % at 0, 91.5 % at 0.5 and 91.2 % at 1 (MakeHuman bodies 97.2 %,
    /// 97.3 %, 97.5 %): the choice barely matters, the simplest rule is kept.
    pub radius_weight: f64,
}

impl Default for LevelOptions {
    fn default() -> Self {
        Self {
            bins: 20,
            insignificant_fraction: 0.005,
            junction_fraction: 0.02,
            extreme_fraction: 0.1,
            linear_ratio: 1.5,
            radius_weight: 0.0,
        }
    }
}

/// Options of the labelling rules ([`label_graph`](super::label_graph), ch.7.3.3).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RuleOptions {
    /// The trunk is *vertical* (human-like) when its principal axis is within this angle of
    /// up, degrees. Default 35 ("mostly vertical", ch.7.3.3).
    pub vertical_angle: f64,
    /// The trunk is *horizontal* (animal-like) when its principal axis is at least this angle
    /// from up, degrees. Default 55 ("mostly horizontal", ch.7.3.3); in between it is slanted
    /// and the figure class is unknown.
    pub horizontal_angle: f64,
    /// A section is a wing when at least this fraction of its significant vertices have a linear
    /// cross-section. Default 0.4 (ch.7.3.3).
    pub wing_fraction: f64,
    /// Arms (and other paired limbs) must reach at least this far from their attachment, as a
    /// fraction of the heart radius. Default 0.3 ("at least a moderate length", ch.7.3.3).
    pub limb_length: f64,
    /// Two sections pair as arms only when their attachments lie within this fraction of the
    /// heart radius of each other ("join the trunk at approximately the same vertex",
    /// ch.7.3.3). Default 0.5.
    pub pair_distance: f64,
    /// A tail must join the trunk within this fraction of the heart radius of the most
    /// posterior limb pair's attachments ("at roughly the same point", ch.7.2). Default 0.4: keeps the
    /// tail of every reference quadruped and rejects the hair behind CesiumMan's head (a
    /// rearward bump joining 0.54 heart radii from its legs).
    pub tail_distance: f64,
    /// A tail must reach at least this far from where it joins the trunk, as a fraction of the
    /// heart radius. Default 0.1: the closeness of fit of the path tree (Table 5.2), the
    /// shortest protrusion ch.5 grows a branch into; a long neck makes the heart radius large,
    /// and the alpaca's short tail reaches 0.17 of it.
    pub tail_length: f64,
    /// Unlabelled sections shorter than this fraction of the heart radius are merged into the
    /// trunk; longer ones are merged too but named in a warning ("brought to the attention of
    /// the user", ch.7.3.3). Default 0.3.
    pub leftover_length: f64,
    /// A limb has separate digits when a vertex in its distal part merges at least two branches
    /// each holding this fraction of the limb's DMS voxels. Default 0.05 (ch.7.3.3 "notable
    /// branches toward the end").
    pub digit_fraction: f64,
    /// Digits are looked for only beyond this fraction of the limb's length from its
    /// attachment. Default 0.6.
    pub digit_start: f64,
    /// Give the neck to the head in the per-voxel and per-mesh-vertex labels
    /// ([`Labelling::mesh_parts`](super::Labelling::mesh_parts)): the trunk's vertices from the
    /// head's junction down to the nearest pectoral limb's (with the pieces hanging from them).
    /// Parts and the fit keep them in the trunk. Default true (ch.6: the cervical vertebrae
    /// belong to the head region; per-vertex agreement on CesiumMan 74.0 → 95.0 %).
    pub neck_in_head: bool,
    /// In the per-voxel and per-mesh-vertex labels, DMS voxels of arms and fore legs within
    /// this multiple of a trunk DMS voxel's inscribed radius count as trunk (the shoulder
    /// girdle belongs to the trunk, ch.6); parts and the fit are unchanged. In `[0, 1]`; 0
    /// turns it off. Default 0.4 (per-vertex agreement on the quadrupeds +0.1 to +1.3 points,
    /// wolf 91.4 → 92.7 %; larger multiples take the upper arm).
    pub pectoral_root_scale: f64,
}

impl Default for RuleOptions {
    fn default() -> Self {
        Self {
            vertical_angle: 35.0,
            horizontal_angle: 55.0,
            wing_fraction: 0.4,
            limb_length: 0.3,
            pair_distance: 0.5,
            tail_distance: 0.4,
            tail_length: 0.1,
            leftover_length: 0.3,
            digit_fraction: 0.05,
            digit_start: 0.6,
            neck_in_head: true,
            pectoral_root_scale: 0.4,
        }
    }
}

/// Parameters of the labelling itself ([`label_pieces`](super::label_pieces)): the level
/// graph, the rules and the orientation. The voxel stages' options sit beside it
/// ([`LabelPipelineOptions`], `pipeline::RigOptions`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LabelOptions {
    /// Level graph and vertex marks.
    pub level: LevelOptions,
    /// Labelling rules.
    pub rules: RuleOptions,
    /// Up direction. Default [`Up::Auto`] (ch.7.1.2 has the user give it; the figure's labels
    /// find it when not given).
    pub up: Up,
    /// Forward direction. Default [`Forward::Auto`] (ch.7.1.2 has the user give it; the figure's
    /// labels find it when not given, the file's convention kept when they cannot tell).
    pub forward: Forward,
}

impl Default for LabelOptions {
    fn default() -> Self {
        Self {
            level: LevelOptions::default(),
            rules: RuleOptions::default(),
            up: Up::Auto,
            forward: Forward::Auto,
        }
    }
}

/// All parameters of [`label`](super::label), one options struct per stage: the voxel stages
/// and the labelling.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct LabelPipelineOptions {
    /// Voxelization (default voxel size 0.01 of the longest side, Table 5.2).
    pub voxel: VoxelOptions,
    /// Discrete medial surface.
    pub medial: MedialOptions,
    /// Heart sampling (the heart values come from the heart's depth sums, ch.7.3.1).
    pub paths: PathOptions,
    /// Level graph, rules and orientation.
    pub label: LabelOptions,
}

impl LabelPipelineOptions {
    /// Checks the options of every stage (medial surface, paths, labelling).
    ///
    /// # Errors
    /// The stage's error when one stage's options are invalid; [`crate::Error::Options`] with
    /// each stage's error when several are.
    pub fn validate(&self) -> crate::Result<()> {
        let mut errors: Vec<crate::Error> = Vec::new();
        errors.extend(self.medial.validate().err().map(Into::into));
        errors.extend(self.paths.validate().err().map(Into::into));
        errors.extend(self.label.validate().err().map(Into::into));
        match errors.len() {
            0 => Ok(()),
            1 => Err(errors.remove(0)),
            _ => Err(crate::Error::Options(errors)),
        }
    }
}

fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<(), AnatomyError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(AnatomyError::InvalidOption {
            name,
            value,
            expected,
        })
    }
}

impl LabelOptions {
    /// Checks every parameter of the anatomy stage (the voxel, medial and path options beside
    /// it are checked by their stages).
    ///
    /// # Errors
    /// [`AnatomyError::InvalidOption`] naming the first bad field,
    /// [`AnatomyError::InvalidOrientation`] for a zero or non-finite up vector.
    pub fn validate(&self) -> Result<(), AnatomyError> {
        let l = &self.level;
        check("level.bins", l.bins as f64, l.bins >= 2, "at least 2")?;
        let unit = "in [0, 1]";
        for (name, v) in [
            ("level.insignificant_fraction", l.insignificant_fraction),
            ("level.junction_fraction", l.junction_fraction),
            ("level.extreme_fraction", l.extreme_fraction),
            ("level.radius_weight", l.radius_weight),
            ("rules.wing_fraction", self.rules.wing_fraction),
            ("rules.digit_fraction", self.rules.digit_fraction),
            ("rules.digit_start", self.rules.digit_start),
            ("rules.pectoral_root_scale", self.rules.pectoral_root_scale),
        ] {
            check(name, v, (0.0..=1.0).contains(&v), unit)?;
        }
        check(
            "level.linear_ratio",
            l.linear_ratio,
            l.linear_ratio > 0.0,
            "positive",
        )?;
        let r = &self.rules;
        for (name, v) in [
            ("rules.vertical_angle", r.vertical_angle),
            ("rules.horizontal_angle", r.horizontal_angle),
        ] {
            check(name, v, (0.0..=90.0).contains(&v), "in [0, 90] degrees")?;
        }
        check(
            "rules.horizontal_angle",
            r.horizontal_angle,
            r.horizontal_angle >= r.vertical_angle,
            "at least rules.vertical_angle",
        )?;
        for (name, v) in [
            ("rules.limb_length", r.limb_length),
            ("rules.pair_distance", r.pair_distance),
            ("rules.tail_distance", r.tail_distance),
            ("rules.tail_length", r.tail_length),
            ("rules.leftover_length", r.leftover_length),
        ] {
            check(name, v, v >= 0.0, "non-negative")?;
        }
        if let Up::Direction(up) = self.up {
            super::Frame::new(up, up.any_orthonormal_vector())?;
            if let Forward::Direction(f) = self.forward {
                super::Frame::new(up, f)?;
            }
        }
        Ok(())
    }
}

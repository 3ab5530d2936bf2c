//! Options of the digit stage.

use crate::options::{Checks, OptionProblems};

/// How [`fit_hands`](super::fit_hands) finds and places the digits. Lengths are fractions of the
/// forearm (elbow to wrist), so the options do not depend on the mesh's units.
#[derive(Debug, Clone, PartialEq)]
pub struct DigitOptions {
    /// Whether the rig looks at the hands again (default true).
    pub enabled: bool,
    /// Whether the rig places the toe joints of an upright figure's feet from their surface
    /// (default true): the toe at the ball of the foot, the toe end at its tip.
    pub feet: bool,
    /// Spacing of the contour levels, fraction of the forearm. Default 1/80 (3 mm on an adult):
    /// a fifth of a finger's width, so the webs between fingers are seen.
    pub level_step: f64,
    /// How far from the wrist the hand's surface is taken, fraction of the forearm. Default
    /// 1.2 (a hand is about 0.75 forearm long).
    pub reach: f64,
    /// How far behind the wrist the wrist's cross-section (the geodesic sources) reaches,
    /// fraction of the forearm. Default 0.05.
    pub wrist_band: f64,
    /// Fewest contour levels a digit branch spans; shorter branches are noise. Default 3.
    pub min_levels: usize,
    /// Share of each digit's length (base joint to tip, thumb first) that stands free of the
    /// palm beyond the web. Default `[0.44, 0.84, 0.82, 0.77, 0.72]`: the means over the six
    /// MakeHuman hands of ../shared/refdata (thumb from its carpometacarpal joint).
    pub free_share: [f64; 5],
    /// The last two finger joints (end joint, middle joint) as fractions of the finger's length
    /// measured from its tip. Default `[0.33, 0.62]`: distal:middle:proximal segments
    /// 33:29:38 to the skin tip (the means over the MakeHuman reference hands; the
    /// dissertation's 10:15:25 bone ratios stop short of the fingertip pad).
    pub finger_from_tip: [f64; 2],
    /// The thumb's interphalangeal and metacarpophalangeal joints as fractions of its length
    /// from the tip. Default `[0.30, 0.67]` (MakeHuman reference hands).
    pub thumb_from_tip: [f64; 2],
    /// How far from the ankle the foot's surface is taken, fraction of the shank (knee to
    /// ankle). Default 1.0 (a human foot is about 0.6 shank long).
    pub foot_reach: f64,
    /// Depth of the cap at the front of the foot whose mean places the toe end across and
    /// up, fraction of the foot's length. Default 0.03.
    pub toe_cap: f64,
    /// The ball of the foot is the middle of the stretch of cross-sections at least this
    /// share of the widest one wide. Default 0.95: the forefoot is about as wide across all
    /// five metatarsal heads.
    pub ball_plateau: f64,
    /// A horizontal figure's toe must stand free of its hoof or paw for at least this share of
    /// the length its three phalanges have by the template's ratios (Table 8.1, scaled by the
    /// shank); a shorter branch is a scallop of the rim (a low-poly hoof's cleft, a paw's toe
    /// notches) and the foot keeps one digit chain. Default 0.5: half the phalanges.
    pub min_paw_digit: f64,
}

impl Default for DigitOptions {
    fn default() -> Self {
        Self {
            enabled: true,
            level_step: 1.0 / 80.0,
            reach: 1.2,
            wrist_band: 0.05,
            min_levels: 3,
            free_share: [0.44, 0.84, 0.82, 0.77, 0.72],
            finger_from_tip: [0.33, 0.62],
            thumb_from_tip: [0.30, 0.67],
            feet: true,
            foot_reach: 1.0,
            toe_cap: 0.03,
            ball_plateau: 0.95,
            min_paw_digit: 0.5,
        }
    }
}

impl DigitOptions {
    /// Checks every field.
    ///
    /// # Errors
    /// Every out-of-range field, by name.
    pub fn validate(&self) -> Result<(), OptionProblems> {
        let mut c = Checks::default();
        c.range("digits.level_step", self.level_step, 1e-3, 0.2);
        c.range("digits.reach", self.reach, 0.2, 3.0);
        c.range("digits.wrist_band", self.wrist_band, 0.0, 0.5);
        c.at_least("digits.min_levels", self.min_levels, 1);
        c.range("digits.foot_reach", self.foot_reach, 0.2, 3.0);
        c.range("digits.toe_cap", self.toe_cap, 0.0, 0.5);
        c.range("digits.ball_plateau", self.ball_plateau, 0.5, 1.0);
        c.range("digits.min_paw_digit", self.min_paw_digit, 0.0, 1.0);
        for (k, v) in self.free_share.iter().enumerate() {
            c.range(&format!("digits.free_share[{k}]"), *v, 0.05, 1.0);
        }
        for (name, pair) in [
            ("finger_from_tip", self.finger_from_tip),
            ("thumb_from_tip", self.thumb_from_tip),
        ] {
            c.range(&format!("digits.{name}[0]"), pair[0], 0.05, 0.95);
            c.range(&format!("digits.{name}[1]"), pair[1], pair[0], 0.95);
        }
        c.finish()
    }
}

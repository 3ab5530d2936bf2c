//! Canonical anatomical keys: the typed names of the joints every template, metric, naming
//! preset and the refinement agree on (`pelvis`, `elbow_L`, `tail_base`, ...).
//!
//! Strings appear only at the file-format edges (template TOML, naming presets, skeleton
//! JSON): [`Canonical::as_str`] and [`str::parse`] convert, and round-trip.

use super::JointId;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

/// A side of the figure. The figure's left is `up × forward` (+X for +Y up, +Z forward).
///
/// Written `L`/`R` in files (labels.json, label overrides); `Left`/`Right` are read too.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum Side {
    /// The figure's left (`_L`).
    #[serde(rename = "L", alias = "Left")]
    Left,
    /// The figure's right (`_R`).
    #[serde(rename = "R", alias = "Right")]
    Right,
}

impl Side {
    /// Left, then right.
    pub const BOTH: [Side; 2] = [Side::Left, Side::Right];

    /// `_L` or `_R`.
    pub fn suffix(self) -> &'static str {
        match self {
            Self::Left => "_L",
            Self::Right => "_R",
        }
    }

    /// `L` or `R`.
    pub fn letter(self) -> &'static str {
        match self {
            Self::Left => "L",
            Self::Right => "R",
        }
    }

    /// The other side.
    pub fn opposite(self) -> Side {
        match self {
            Self::Left => Self::Right,
            Self::Right => Self::Left,
        }
    }

    /// `+1` for left, `-1` for right.
    pub fn sign(self) -> f64 {
        match self {
            Self::Left => 1.0,
            Self::Right => -1.0,
        }
    }

    /// `left` or `right`.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Left => "left",
            Self::Right => "right",
        }
    }
}

/// A tail key. Keys starting with `tail_` that are none of these are still accepted as tail
/// keys by [`is_canonical_key`] (a reference rig may name more tail joints).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Tail {
    /// `tail_base`: where the tail leaves the trunk.
    Base,
    /// `tail_mid`.
    Mid,
    /// `tail_end`: the tail's tip.
    End,
}

/// A digit of the hand, thumb first (issue 25).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Finger {
    /// The first digit (pollex).
    Thumb,
    /// The second digit.
    Index,
    /// The third digit.
    Middle,
    /// The fourth digit.
    Ring,
    /// The fifth digit.
    Pinky,
}

impl Finger {
    /// Thumb to pinky.
    pub const ALL: [Finger; 5] = [
        Finger::Thumb,
        Finger::Index,
        Finger::Middle,
        Finger::Ring,
        Finger::Pinky,
    ];

    /// `thumb`, `index`, `middle`, `ring`, `pinky`.
    pub const fn as_str(self) -> &'static str {
        match self {
            Self::Thumb => "thumb",
            Self::Index => "index",
            Self::Middle => "middle",
            Self::Ring => "ring",
            Self::Pinky => "pinky",
        }
    }
}

/// The written digit keys, `[side][finger][joint]` (`thumb_01_L` .. `pinky_03_R`).
const DIGIT_KEYS: [[[&str; 3]; 5]; 2] = [
    [
        ["thumb_01_L", "thumb_02_L", "thumb_03_L"],
        ["index_01_L", "index_02_L", "index_03_L"],
        ["middle_01_L", "middle_02_L", "middle_03_L"],
        ["ring_01_L", "ring_02_L", "ring_03_L"],
        ["pinky_01_L", "pinky_02_L", "pinky_03_L"],
    ],
    [
        ["thumb_01_R", "thumb_02_R", "thumb_03_R"],
        ["index_01_R", "index_02_R", "index_03_R"],
        ["middle_01_R", "middle_02_R", "middle_03_R"],
        ["ring_01_R", "ring_02_R", "ring_03_R"],
        ["pinky_01_R", "pinky_02_R", "pinky_03_R"],
    ],
];

/// The 30 digit keys in table order: left hand then right, thumb to pinky, base joint first.
pub const DIGITS: [Canonical; 30] = {
    let mut out = [Canonical::Pelvis; 30];
    let mut i = 0;
    while i < 30 {
        let side = if i < 15 { Side::Left } else { Side::Right };
        let finger = Finger::ALL[(i % 15) / 3];
        out[i] = Canonical::Digit(side, finger, (i % 3) as u8 + 1);
        i += 1;
    }
    out
};

/// A canonical anatomical key. Sided keys carry their [`Side`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Canonical {
    /// `pelvis`: the trunk's root.
    Pelvis,
    /// `spine`: the trunk joint nearest the template's `spine_at` fraction pelvis → neck.
    Spine,
    /// `chest`: the trunk joint nearest `chest_at`.
    Chest,
    /// `neck`: the base of the neck (C7).
    Neck,
    /// `head`: the head's pivot.
    Head,
    /// `clavicle_L`, `clavicle_R`.
    Clavicle(Side),
    /// `shoulder_L`, `shoulder_R`.
    Shoulder(Side),
    /// `elbow_L`, `elbow_R`.
    Elbow(Side),
    /// `wrist_L`, `wrist_R`.
    Wrist(Side),
    /// `hip_L`, `hip_R`.
    Hip(Side),
    /// `knee_L`, `knee_R`.
    Knee(Side),
    /// `ankle_L`, `ankle_R`.
    Ankle(Side),
    /// `toe_L`, `toe_R`.
    Toe(Side),
    /// `tail_base`, `tail_mid`, `tail_end`.
    Tail(Tail),
    /// `C1`..`C7`, `T1`..`T12`, `L1`..`L5`, `sacrum`: the full spine (`skelfit rig --spine
    /// full`).
    Vertebra(Vertebra),
    /// `thumb_01_L` .. `pinky_03_R`: a digit joint, numbered 1 (the base: the thumb's
    /// carpometacarpal joint, a finger's knuckle) to 3 (the last joint). Numbers outside 1..=3
    /// are written as 3.
    Digit(Side, Finger, u8),
}

/// Names of the full spine's joints from the top: the joint below each vertebra (`C1` joins C1
/// and C2, ..., `L5` joins L5 and the sacrum; each rotates its vertebra and everything above),
/// then the sacrum centre (seed 004, 3.2).
pub const VERTEBRA_NAMES: [&str; 25] = [
    "C1", "C2", "C3", "C4", "C5", "C6", "C7", "T1", "T2", "T3", "T4", "T5", "T6", "T7", "T8", "T9",
    "T10", "T11", "T12", "L1", "L2", "L3", "L4", "L5", "sacrum",
];

/// A region of the spine: what a vertebral joint's limits depend on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum SpineRegion {
    /// C1..C7.
    Cervical,
    /// T1..T12.
    Thoracic,
    /// L1..L5.
    Lumbar,
    /// The sacrum (fused, moves with the pelvis).
    Sacral,
}

/// One joint of the full spine, by its index in [`VERTEBRA_NAMES`] (0 = `C1`, 24 = `sacrum`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Vertebra(u8);

impl Vertebra {
    /// The 25 joints from the top: `C1`..`L5`, `sacrum`.
    pub const ALL: [Vertebra; 25] = {
        let mut out = [Vertebra(0); 25];
        let mut i = 0;
        while i < 25 {
            out[i] = Vertebra(i as u8);
            i += 1;
        }
        out
    };

    /// The sacrum centre, the spine's lowest joint.
    pub const SACRUM: Vertebra = Vertebra(24);

    /// The joint at `index` from the top (0 = `C1`), if there is one.
    pub fn new(index: usize) -> Option<Self> {
        (index < VERTEBRA_NAMES.len()).then_some(Self(index as u8))
    }

    /// Its index from the top (0 = `C1`, 24 = `sacrum`).
    pub fn index(self) -> usize {
        usize::from(self.0)
    }

    /// Its name as written in files (`C1`, `T12`, `sacrum`).
    pub const fn as_str(self) -> &'static str {
        VERTEBRA_NAMES[self.0 as usize]
    }

    /// Its region.
    pub fn region(self) -> SpineRegion {
        match self.0 {
            0..=6 => SpineRegion::Cervical,
            7..=18 => SpineRegion::Thoracic,
            19..=23 => SpineRegion::Lumbar,
            _ => SpineRegion::Sacral,
        }
    }
}

use Side::{Left, Right};

/// The canonical keys of the comparison table, in table order (head to toe, left before
/// right); tail keys come after them.
pub const TABLE: [Canonical; 21] = [
    Canonical::Pelvis,
    Canonical::Spine,
    Canonical::Chest,
    Canonical::Neck,
    Canonical::Head,
    Canonical::Clavicle(Left),
    Canonical::Clavicle(Right),
    Canonical::Shoulder(Left),
    Canonical::Shoulder(Right),
    Canonical::Elbow(Left),
    Canonical::Elbow(Right),
    Canonical::Wrist(Left),
    Canonical::Wrist(Right),
    Canonical::Hip(Left),
    Canonical::Hip(Right),
    Canonical::Knee(Left),
    Canonical::Knee(Right),
    Canonical::Ankle(Left),
    Canonical::Ankle(Right),
    Canonical::Toe(Left),
    Canonical::Toe(Right),
];

/// The tail keys.
pub const TAILS: [Canonical; 3] = [
    Canonical::Tail(Tail::Base),
    Canonical::Tail(Tail::Mid),
    Canonical::Tail(Tail::End),
];

const TABLE_KEYS: [&str; TABLE.len()] = {
    let mut out = [""; TABLE.len()];
    let mut i = 0;
    while i < TABLE.len() {
        out[i] = TABLE[i].as_str();
        i += 1;
    }
    out
};

/// The canonical anatomical keys as written in files, in table order ([`TABLE`]). Tail joints
/// use keys starting with `tail_` (e.g. `tail_base`, `tail_mid`, `tail_end`).
pub const CANONICAL_KEYS: &[&str] = &TABLE_KEYS;

/// How every tail key begins.
pub const TAIL_PREFIX: &str = "tail_";

/// Whether `key` is a canonical anatomical key ([`CANONICAL_KEYS`], a digit key of
/// [`DIGITS`], `tail_*` or a [`VERTEBRA_NAMES`] entry).
pub fn is_canonical_key(key: &str) -> bool {
    CANONICAL_KEYS.contains(&key)
        || is_digit_key(key)
        || key.starts_with(TAIL_PREFIX)
        || VERTEBRA_NAMES.contains(&key)
}

/// Whether `key` is one of the 30 digit keys ([`DIGITS`]).
pub fn is_digit_key(key: &str) -> bool {
    DIGITS.iter().any(|d| d.as_str() == key)
}

/// Sort position of a canonical key: [`CANONICAL_KEYS`] order, then the digit keys
/// ([`DIGITS`] order), then the other keys.
pub fn key_rank(key: &str) -> usize {
    CANONICAL_KEYS
        .iter()
        .position(|k| *k == key)
        .or_else(|| {
            DIGITS
                .iter()
                .position(|d| d.as_str() == key)
                .map(|i| CANONICAL_KEYS.len() + i)
        })
        .unwrap_or(CANONICAL_KEYS.len() + DIGITS.len())
}

impl Canonical {
    /// The key as written in files (`pelvis`, `elbow_L`, `tail_base`).
    pub const fn as_str(self) -> &'static str {
        match self {
            Self::Pelvis => "pelvis",
            Self::Spine => "spine",
            Self::Chest => "chest",
            Self::Neck => "neck",
            Self::Head => "head",
            Self::Clavicle(Left) => "clavicle_L",
            Self::Clavicle(Right) => "clavicle_R",
            Self::Shoulder(Left) => "shoulder_L",
            Self::Shoulder(Right) => "shoulder_R",
            Self::Elbow(Left) => "elbow_L",
            Self::Elbow(Right) => "elbow_R",
            Self::Wrist(Left) => "wrist_L",
            Self::Wrist(Right) => "wrist_R",
            Self::Hip(Left) => "hip_L",
            Self::Hip(Right) => "hip_R",
            Self::Knee(Left) => "knee_L",
            Self::Knee(Right) => "knee_R",
            Self::Ankle(Left) => "ankle_L",
            Self::Ankle(Right) => "ankle_R",
            Self::Toe(Left) => "toe_L",
            Self::Toe(Right) => "toe_R",
            Self::Tail(Tail::Base) => "tail_base",
            Self::Tail(Tail::Mid) => "tail_mid",
            Self::Tail(Tail::End) => "tail_end",
            Self::Vertebra(v) => v.as_str(),
            Self::Digit(side, finger, k) => {
                let s = match side {
                    Left => 0,
                    Right => 1,
                };
                let j = match k {
                    0 | 1 => 0,
                    2 => 1,
                    _ => 2,
                };
                DIGIT_KEYS[s][finger as usize][j]
            }
        }
    }

    /// The side of a sided key.
    pub fn side(self) -> Option<Side> {
        match self {
            Self::Clavicle(s)
            | Self::Shoulder(s)
            | Self::Elbow(s)
            | Self::Wrist(s)
            | Self::Hip(s)
            | Self::Knee(s)
            | Self::Ankle(s)
            | Self::Toe(s)
            | Self::Digit(s, ..) => Some(s),
            _ => None,
        }
    }

    /// The same limb joint on the other side (`shoulder_R` for `shoulder_L`); `None` for axial
    /// keys, toes and digits.
    pub fn mirrored(self) -> Option<Canonical> {
        Some(match self {
            Self::Shoulder(s) => Self::Shoulder(s.opposite()),
            Self::Elbow(s) => Self::Elbow(s.opposite()),
            Self::Wrist(s) => Self::Wrist(s.opposite()),
            Self::Hip(s) => Self::Hip(s.opposite()),
            Self::Knee(s) => Self::Knee(s.opposite()),
            Self::Ankle(s) => Self::Ankle(s.opposite()),
            _ => return None,
        })
    }

    /// The key without its side suffix, as a template names the joint it places (`elbow` for
    /// `elbow_L`, `pelvis` for `pelvis`).
    pub fn stem(self) -> &'static str {
        let key = self.as_str();
        match self.side() {
            Some(_) => &key[..key.len() - 2],
            None => key,
        }
    }
}

impl fmt::Display for Canonical {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A string that is not a canonical key.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("`{0}` is not a canonical key (pelvis, spine, chest, neck, head, clavicle/shoulder/elbow/wrist/hip/knee/ankle/toe with _L or _R, tail_base, tail_mid, tail_end, thumb/index/middle/ring/pinky_01..03 with _L or _R, C1..C7, T1..T12, L1..L5, sacrum)")]
pub struct NotCanonical(pub String);

/// A map from canonical keys to joints: the maps of files and fits, keyed by the written key
/// (`BTreeMap<String, JointId>`), and typed ones (`BTreeMap<Canonical, JointId>`).
pub trait CanonicalJoints {
    /// The joint mapped to `key`, if any.
    fn joint_of(&self, key: Canonical) -> Option<JointId>;
}

impl CanonicalJoints for BTreeMap<String, JointId> {
    fn joint_of(&self, key: Canonical) -> Option<JointId> {
        self.get(key.as_str()).copied()
    }
}

impl CanonicalJoints for BTreeMap<Canonical, JointId> {
    fn joint_of(&self, key: Canonical) -> Option<JointId> {
        self.get(&key).copied()
    }
}

impl FromStr for Canonical {
    type Err = NotCanonical;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        TABLE
            .iter()
            .chain(&TAILS)
            .chain(&DIGITS)
            .copied()
            .chain(Vertebra::ALL.map(Canonical::Vertebra))
            .find(|k| k.as_str() == s)
            .ok_or_else(|| NotCanonical(s.to_string()))
    }
}

impl Serialize for Canonical {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.as_str())
    }
}

impl<'de> Deserialize<'de> for Canonical {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let s = String::deserialize(deserializer)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_round_trips_through_its_string() {
        for key in TABLE.iter().chain(&TAILS).chain(&DIGITS) {
            assert_eq!(key.as_str().parse::<Canonical>(), Ok(*key));
            assert!(is_canonical_key(key.as_str()));
        }
        for v in Vertebra::ALL {
            let key = Canonical::Vertebra(v);
            assert_eq!(key.as_str().parse::<Canonical>(), Ok(key));
            assert!(is_canonical_key(key.as_str()));
        }
        assert_eq!(
            Vertebra::new(7).map(Vertebra::region),
            Some(SpineRegion::Thoracic)
        );
        assert_eq!(Vertebra::SACRUM.region(), SpineRegion::Sacral);
        assert!("elbow".parse::<Canonical>().is_err());
        assert!("elbow_X".parse::<Canonical>().is_err());
    }

    #[test]
    fn stems_and_sides() {
        assert_eq!(Canonical::Elbow(Side::Right).stem(), "elbow");
        assert_eq!(Canonical::Elbow(Side::Right).side(), Some(Side::Right));
        assert_eq!(Canonical::Pelvis.stem(), "pelvis");
        assert_eq!(Canonical::Tail(Tail::End).stem(), "tail_end");
        assert_eq!(key_rank("pelvis"), 0);
        assert_eq!(key_rank("tail_base"), CANONICAL_KEYS.len() + DIGITS.len());
        assert_eq!(key_rank("thumb_01_L"), CANONICAL_KEYS.len());
        assert_eq!(DIGITS[29].as_str(), "pinky_03_R");
        assert_eq!(DIGITS[29].side(), Some(Side::Right));
    }

    #[test]
    fn sides_are_written_l_and_r_and_read_either_way() {
        assert_eq!(serde_json::to_string(&Side::Left).unwrap(), "\"L\"");
        let read: Side = serde_json::from_str("\"Right\"").unwrap();
        assert_eq!(read, Side::Right);
        let read: Side = serde_json::from_str("\"R\"").unwrap();
        assert_eq!(read, Side::Right);
    }
}

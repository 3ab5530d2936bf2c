//! Bone kinds.

use crate::skeleton::Canonical;
use serde::Serialize;

/// What a bone is (dissertation 9.1's axial and appendicular components).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum BoneKind {
    /// Human-like cranium (upright figures).
    Cranium,
    /// Generalised animal skull (9.1.1; horizontal figures).
    AnimalCranium,
    /// Lower jaw.
    Mandible,
    /// One vertebra of the neck or trunk.
    Vertebra,
    /// One tail vertebra (tapering 10 % per vertebra).
    TailVertebra,
    /// Ribs and sternum of one pectoral girdle group.
    RibCage,
    /// Shoulder blade of a pectoral limb.
    Scapula,
    /// Upper bone of a pectoral limb.
    Humerus,
    /// Radius and ulna.
    RadiusUlna,
    /// Wrist bones.
    Carpals,
    /// Hand bone of a digit.
    Metacarpal,
    /// Pelvic girdle (both hip bones).
    Pelvis,
    /// Upper bone of a pelvic limb.
    Femur,
    /// Knee cap.
    Patella,
    /// Tibia and fibula.
    TibiaFibula,
    /// Ankle bones.
    Tarsals,
    /// Foot bone of a digit.
    Metatarsal,
    /// A phalanx of a digit (hand or foot).
    Phalanx,
}

impl BoneKind {
    /// Lowercase snake-case name (`tibia_fibula`), used in node and file names.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Cranium => "cranium",
            Self::AnimalCranium => "animal_cranium",
            Self::Mandible => "mandible",
            Self::Vertebra => "vertebra",
            Self::TailVertebra => "tail_vertebra",
            Self::RibCage => "rib_cage",
            Self::Scapula => "scapula",
            Self::Humerus => "humerus",
            Self::RadiusUlna => "radius_ulna",
            Self::Carpals => "carpals",
            Self::Metacarpal => "metacarpal",
            Self::Pelvis => Canonical::Pelvis.as_str(),
            Self::Femur => "femur",
            Self::Patella => "patella",
            Self::TibiaFibula => "tibia_fibula",
            Self::Tarsals => "tarsals",
            Self::Metatarsal => "metatarsal",
            Self::Phalanx => "phalanx",
        }
    }
}

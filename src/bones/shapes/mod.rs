//! Procedural, watertight bone shapes (dissertation 9.1, with the feature-based parameters
//! 9.1.1 recommends). Each builder returns a closed, outward-wound [`crate::mesh::Mesh`] in the
//! bone's own local frame, documented per family; sizes of features (heads, condyles, orbits,
//! processes) follow widths, not lengths, so features keep their shape under stretching.

mod long_bone;
mod pelvis;
mod primitive;
mod ribcage;
mod scapula;
mod skull;
mod small;
mod vertebra;

pub use long_bone::{
    femur, humerus, metapodial, patella, phalanx, radius_ulna, tibia_fibula, LongBone,
};
pub use pelvis::{pelvis, Pelvis};
pub use primitive::{
    dent, ellipsoid, merge, orient_outward, place, profile_z, sweep, tube, Section,
};
pub use ribcage::{rib_cage, RibCage};
pub use scapula::{scapula, Scapula};
pub use skull::{animal_cranium, human_cranium, mandible, Jaw, Skull};
pub use small::{carpals, tarsals, Block};
pub use vertebra::{vertebra, Vertebra};

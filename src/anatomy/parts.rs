//! Body-part vocabulary and the labelling result.

use super::{Frame, LevelGraph, Marks, Reach};
use crate::voxel::Grid;
use crate::warning::Warning;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// A body-part label (dissertation ch.6-7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Label {
    /// The trunk: major junctions and the level-graph pieces between them, girdles included.
    Trunk,
    /// The head (possibly with the neck, ch.7.3.3).
    Head,
    /// The neck (only from a labels override).
    Neck,
    /// The jaw (only from a labels override).
    Jaw,
    /// The tail.
    Tail,
    /// An arm (a fore limb that does not reach the ground).
    Arm,
    /// A leg (a limb that reaches the ground).
    Leg,
    /// A wing (a limb with mostly linear cross-sections).
    Wing,
    /// A digit branching at a limb's end.
    Digit,
}

impl Label {
    /// Lowercase name as written in labels.json.
    pub fn name(self) -> &'static str {
        match self {
            Label::Trunk => "trunk",
            Label::Head => "head",
            Label::Neck => "neck",
            Label::Jaw => "jaw",
            Label::Tail => "tail",
            Label::Arm => "arm",
            Label::Leg => "leg",
            Label::Wing => "wing",
            Label::Digit => "digit",
        }
    }

    /// Whether parts with this label come in left/right pairs.
    pub fn is_limb(self) -> bool {
        matches!(self, Label::Arm | Label::Leg | Label::Wing)
    }
}

pub use crate::skeleton::Side;

/// Which girdle a limb pair belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LimbPair {
    /// Pectoral girdle: arms, a quadruped's front legs.
    Fore,
    /// Pelvic girdle: a biped's legs, a quadruped's back legs.
    Hind,
}

/// The figure class from the trunk's slope (ch.7.3.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum FigureClass {
    /// Mostly vertical trunk.
    #[serde(rename = "human-like")]
    HumanLike,
    /// Mostly horizontal trunk.
    #[serde(rename = "animal-like")]
    AnimalLike,
    /// Slanted trunk or no clear trunk.
    #[serde(rename = "unknown")]
    Unknown,
}

impl FigureClass {
    /// Name as written in labels.json.
    pub fn name(self) -> &'static str {
        match self {
            FigureClass::HumanLike => "human-like",
            FigureClass::AnimalLike => "animal-like",
            FigureClass::Unknown => "unknown",
        }
    }
}

/// A section of the level graph: a subtree hanging off the trunk (a candidate protrusion).
#[derive(Debug, Clone, Serialize)]
pub struct Section {
    /// The section's proximal vertex (its root).
    pub top: usize,
    /// The trunk vertex it joins.
    pub attachment_vertex: usize,
    /// Level-graph vertices of the section (top first).
    pub vertices: Vec<usize>,
    /// Number of DMS voxels.
    pub voxels: usize,
    /// Distal fraction of the top vertex.
    pub weight: f64,
    /// Centroid of the top vertex (where the section leaves the trunk), mesh units.
    pub attachment: DVec3,
    /// The section's DMS voxel of highest heart value (its distal extreme), mesh units.
    pub distal: DVec3,
    /// Distance from the attachment vertex's centroid to `distal`, mesh units.
    pub length: f64,
    /// Mean of the section's DMS voxel centres, mesh units.
    pub mean: DVec3,
    /// How far its vertices' regions reach along up and forward.
    pub reach: Reach,
    /// Which extremes of the figure its vertices reach (OR of their direction marks).
    pub extreme: Extremes,
    /// Fraction of its significant vertices with a linear cross-section.
    pub linear_fraction: f64,
    /// Whether every vertex is insignificant.
    pub insignificant: bool,
}

/// Which extremes of the figure a region reaches: the OR of its vertices' direction
/// [`Marks`]. Serialized as the array `[up, down, forward, backward]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(into = "[bool; 4]")]
pub struct Extremes {
    /// The top of the figure along up.
    pub up: bool,
    /// The bottom along up.
    pub down: bool,
    /// The front along forward.
    pub forward: bool,
    /// The back along forward.
    pub backward: bool,
}

impl Extremes {
    /// These extremes and the direction marks of `marks`.
    pub fn with(self, marks: Marks) -> Extremes {
        Extremes {
            up: self.up | marks.up,
            down: self.down | marks.down,
            forward: self.forward | marks.forward,
            backward: self.backward | marks.backward,
        }
    }
}

impl From<Extremes> for [bool; 4] {
    fn from(e: Extremes) -> Self {
        [e.up, e.down, e.forward, e.backward]
    }
}

/// One labelled body part.
#[derive(Debug, Clone, Serialize)]
pub struct Part {
    /// What it is.
    pub label: Label,
    /// Left or right for paired parts (digits inherit their limb's side).
    pub side: Option<Side>,
    /// Girdle of a limb (arms are `Fore`; a single leg pair is `Hind`).
    pub limb_pair: Option<LimbPair>,
    /// The section it was made from (`None` for the trunk).
    pub section: Option<usize>,
    /// Level-graph vertices.
    pub vertices: Vec<usize>,
    /// DMS positions (indices into the medial surface's voxels), ascending.
    pub voxels: Vec<usize>,
    /// The trunk vertex (or, for a digit, the limb vertex) it joins; `None` for the trunk.
    pub attachment_vertex: Option<usize>,
    /// Where it leaves its parent, mesh units (the trunk: the heart voxel's centre).
    pub attachment: DVec3,
    /// Its distal extreme, mesh units (the trunk: the heart voxel's centre).
    pub distal: DVec3,
    /// Trunk vertices joining it to its pair partner (pelvic/pectoral girdle pieces), empty
    /// when unpaired.
    pub girdle: Vec<usize>,
    /// Parts (indices) of the digits found at its end.
    pub digits: Vec<usize>,
    /// The part it hangs from (digits: their limb; others: the trunk; the trunk: `None`).
    pub parent: Option<usize>,
    /// Number of mesh vertices labelled with this part.
    pub vertex_count: usize,
}

/// The result of [`label`](super::label): the level graph, its sections, the parts and the
/// per-voxel and per-vertex labels.
#[derive(Debug, Clone, Serialize)]
pub struct Labelling {
    /// Figure class from the trunk's slope.
    pub figure: FigureClass,
    /// The body frame used (up, forward, left).
    pub frame: Frame,
    /// How up was found (`Up::Auto`), `None` when it was given.
    pub up_found: Option<super::UpChoice>,
    /// How forward was found (`Forward::Auto`), `None` when it was given.
    pub forward_found: Option<super::ForwardChoice>,
    /// Principal axis of the trunk's DMS voxels (unit).
    pub trunk_axis: DVec3,
    /// Angle between the trunk axis and up, degrees.
    pub trunk_angle: f64,
    /// The parts; the trunk is part 0.
    pub parts: Vec<Part>,
    /// The sections of the level graph.
    pub sections: Vec<Section>,
    /// The level graph.
    pub level_graph: LevelGraph,
    /// Part of each level-graph vertex.
    pub vertex_parts: Vec<u32>,
    /// Grid of the voxel stages.
    pub grid: Grid,
    /// Linear grid index of each DMS position.
    pub dms_voxels: Vec<usize>,
    /// Part of each DMS position (`u32::MAX` for DMS voxels outside the labelled component).
    pub voxel_parts: Vec<u32>,
    /// Part of each mesh vertex, in mesh order.
    pub mesh_parts: Vec<u32>,
    /// Part of each grid voxel (linear index) inside the figure, `u32::MAX` outside: the
    /// interior labels the mesh-vertex labels are taken from (neck in the head, pectoral limb
    /// roots in the trunk). The fit follows a thin part (a tail a few voxels across) past where
    /// its medial surface stops through them. Empty when not computed.
    #[serde(skip)]
    pub interior_parts: Vec<u32>,
    /// What could not be identified, and what earlier stages (voxelization, the medial
    /// surface) warned about, in stage order.
    pub warnings: Vec<Warning>,
}

impl Labelling {
    /// Indices of the parts with `label`.
    pub fn find(&self, label: Label) -> Vec<usize> {
        (0..self.parts.len())
            .filter(|&i| self.parts[i].label == label)
            .collect()
    }

    /// The part with `label` and `side` (the first if several).
    pub fn part(&self, label: Label, side: Option<Side>) -> Option<&Part> {
        self.parts
            .iter()
            .find(|p| p.label == label && p.side == side)
    }

    /// Number of parts with `label`.
    pub fn count(&self, label: Label) -> usize {
        self.parts.iter().filter(|p| p.label == label).count()
    }

    /// The parts in order as `trunk, head, arm L, arm R, leg L fore, ...` (label, side, and
    /// for legs the pair).
    pub fn parts_summary(&self) -> String {
        self.parts
            .iter()
            .map(|p| {
                let mut s = p.label.name().to_string();
                if let Some(side) = p.side {
                    s.push(' ');
                    s.push_str(side.letter());
                }
                if p.label == Label::Leg {
                    match p.limb_pair {
                        Some(LimbPair::Fore) => s.push_str(" fore"),
                        Some(LimbPair::Hind) => s.push_str(" hind"),
                        None => {}
                    }
                }
                s
            })
            .collect::<Vec<_>>()
            .join(", ")
    }
}

//! The validated, in-memory template.

use crate::skeleton::canonical::SpineRegion;
use crate::skeleton::Dof;
use std::collections::BTreeMap;

/// The bundled templates: `(name, TOML text)`, embedded at build time.
pub const BUILTIN_TEMPLATES: &[(&str, &str)] = &[
    ("humanoid", include_str!("../../templates/humanoid.toml")),
    ("quadruped", include_str!("../../templates/quadruped.toml")),
    ("winged", include_str!("../../templates/winged.toml")),
];

/// The axial places a template joint can take (dissertation 8.1): `root` (the root joint at the
/// hindmost limb pair), `trunk`, `neck` and `tail` (repeated vertebral joints, named
/// `<name>_01`, `<name>_02`... away from the root), `head` (joint of the rigid head segment),
/// `head_end`, `jaw`, `jaw_end` (when the input has a jaw branch) and `tail_end`; and the sided
/// head branches `ear` (repeated, one joint per entry of the `ear` ratio list, base first) and
/// `ear_end` (the tip), built when the input has ears.
pub const AXIAL_PLACES: &[&str] = &[
    "root", "trunk", "neck", "head", "head_end", "jaw", "jaw_end", "tail", "tail_end", "ear",
    "ear_end",
];

/// The places whose joints exist once per side.
pub const SIDED_PLACES: &[&str] = &["ear", "ear_end"];

/// Overall posture: decides the dorsal direction and human-like versus animal-like rules
/// (dissertation 8.1: a nearly vertical trunk is human-like).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Posture {
    /// Human-like: trunk vertical, dorsal is backwards (−forward).
    Upright,
    /// Animal-like: trunk horizontal, dorsal is up.
    Horizontal,
}

/// The refinement a template's fits get after the fit (`refine` in the template header).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RefineKind {
    /// Slicing the mesh to place a human body's joints ([`crate::refine::refine_fit`], seed 004):
    /// `refine = "human_slicing"`.
    HumanSlicing,
}

/// A body part a template expects the labels to have (`expects` in the template header);
/// a paired part is expected on both sides. The rig names each one the labels lack
/// ([`crate::pipeline::missing_parts`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExpectedPart {
    /// `head`.
    Head,
    /// `arms`: a left and a right arm.
    Arms,
    /// `legs`: a left and a right leg, of any girdle.
    Legs,
    /// `fore_legs`: a left and a right leg of the fore girdle.
    ForeLegs,
    /// `hind_legs`: a left and a right leg of the hind girdle.
    HindLegs,
    /// `wings`: a left and a right wing.
    Wings,
}

impl ExpectedPart {
    /// Every part, in the order the names are listed in messages.
    pub const ALL: [ExpectedPart; 6] = [
        Self::Head,
        Self::Arms,
        Self::Legs,
        Self::ForeLegs,
        Self::HindLegs,
        Self::Wings,
    ];

    /// The name written in template files.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Head => "head",
            Self::Arms => "arms",
            Self::Legs => "legs",
            Self::ForeLegs => "fore_legs",
            Self::HindLegs => "hind_legs",
            Self::Wings => "wings",
        }
    }

    /// Parses [`ExpectedPart::as_str`] names.
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.as_str() == name)
    }
}

/// How the head-to-tail path in front of the foremost limb pair is split (8.1): fractions of
/// it for the head (anterior) and the neck (posterior); they sum to 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sections {
    /// Fraction for the head.
    pub head: f64,
    /// Fraction for the neck.
    pub neck: f64,
}

/// Rules for the axial skeleton (8.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxialRules {
    /// Dorsal offset of the trunk as a fraction of the distance-map radius (8.1: 0.7).
    pub dorsal_offset: f64,
    /// Vertebral segment length as a fraction of the head segment length (8.1: about 1/3).
    pub vertebra_to_head: f64,
    /// Whether to build the S-shaped cervical replacement (8.1: animal-like figures).
    pub cervical_s_curve: bool,
    /// Whether the trunk's dorsal offset tapers from the full `dorsal_offset` at the pelvic
    /// girdle to none at the pectoral girdle ([`crate::fit`] axial stage). A horizontal
    /// figure's sacrum is fused to the top of the pelvis, so its spine runs dorsally there,
    /// while the thoracic vertebrae at the shoulders lie deep under the withers (tall spinous
    /// processes and the scapulae above them), near the middle of the chest's cross-section.
    /// Optional in the file (default `false`: the offset is the same along the trunk).
    pub dorsal_taper: bool,
    /// Canonical `spine`: the trunk joint nearest this fraction of the joint chain's length
    /// pelvis → neck, where the joints end up ([`crate::fit::assign_trunk_keys`]).
    pub spine_at: f64,
    /// Canonical `chest`: the trunk joint nearest this fraction.
    pub chest_at: f64,
}

/// An inclusive count range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CountRange {
    /// Fewest.
    pub min: usize,
    /// Most.
    pub max: usize,
}

impl CountRange {
    /// `n` clamped into the range.
    pub fn clamp(&self, n: usize) -> usize {
        n.clamp(self.min, self.max)
    }
}

/// Vertebral segment counts per section.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VertebraRules {
    /// Neck segments.
    pub neck: CountRange,
    /// Trunk segments (the root sits in the middle of one of them).
    pub trunk: CountRange,
    /// Tail segments (0..=max; built only when the path has a tail).
    pub tail: CountRange,
}

/// One template joint. Sided joints exist once per side, named `<name>_L` / `<name>_R`.
#[derive(Debug, Clone, PartialEq)]
pub struct TemplateJoint {
    /// Anatomical name (without side suffix).
    pub name: String,
    /// Parent template joint; `None` for the root. A repeated parent (trunk, neck, tail) means
    /// its last instance, or for a girdle joint its instance nearest the girdle.
    pub parent: Option<String>,
    /// Axial place (one of [`AXIAL_PLACES`]); `None` for limb joints (placed by a limb group).
    pub place: Option<String>,
    /// Whether the joint exists per side.
    pub side: bool,
    /// Canonical key (`_L`/`_R` appended for sided joints).
    pub canonical: Option<String>,
    /// Whether the joint deforms the skin (false for end markers).
    pub deform: bool,
    /// Degrees of freedom with limits, radians.
    pub dofs: Vec<Dof>,
    /// 1-based line in the template file.
    pub line: Option<usize>,
}

/// Limb kinds, as labelled (dissertation 7.3.3).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "snake_case")]
pub enum LimbKind {
    /// Human-like fore limb.
    Arm,
    /// A leg of a single leg pair.
    Leg,
    /// A wing.
    Wing,
    /// The foremost leg pair of a figure with several.
    ForeLeg,
    /// A hind leg pair.
    HindLeg,
}

impl LimbKind {
    /// The name used in templates and warnings (`arm`, `leg`, `wing`, `fore_leg`, `hind_leg`).
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Arm => "arm",
            Self::Leg => "leg",
            Self::Wing => "wing",
            Self::ForeLeg => "fore_leg",
            Self::HindLeg => "hind_leg",
        }
    }

    /// Parses [`LimbKind::as_str`] names.
    pub fn parse(s: &str) -> Option<Self> {
        [
            Self::Arm,
            Self::Leg,
            Self::Wing,
            Self::ForeLeg,
            Self::HindLeg,
        ]
        .into_iter()
        .find(|k| k.as_str() == s)
    }

    /// The girdle a limb of this kind normally attaches by (8.2): pectoral for arms, wings and
    /// fore legs, pelvic otherwise.
    pub fn natural_girdle(self) -> Girdle {
        match self {
            Self::Arm | Self::Wing | Self::ForeLeg => Girdle::Pectoral,
            Self::Leg | Self::HindLeg => Girdle::Pelvic,
        }
    }
}

/// Girdle type (8.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Girdle {
    /// Two independent segments (scapulae/clavicles), one per side.
    Pectoral,
    /// A rigid extension of the root's vertebral segment.
    Pelvic,
}

/// Where the limb's joints go relative to the girdle sphere (8.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Placement {
    /// Human-like: the limb root (shoulder/hip) just outside the girdle sphere; Table 8.1 from
    /// its first row.
    Human,
    /// Animal-like: elbow/knee just outside the sphere, shoulder/hip inside; Table 8.1 from its
    /// second row.
    Animal,
}

/// What to build distal to the wrist/ankle when the limb has no separated digits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Manus {
    /// The whole limb path is partitioned by all Table 8.1 rows (a single digit, 8.2).
    Digit,
    /// One segment from the start of `digit_row` to the tip.
    Segment,
}

/// A limb pair's template (8.2).
#[derive(Debug, Clone, PartialEq)]
pub struct LimbGroup {
    /// Group name (`arm`, `leg`, `fore_leg`, `hind_leg`, `wing`).
    pub name: String,
    /// Limb kinds this group takes, preferred first.
    pub kinds: Vec<LimbKind>,
    /// Whether a missing pair is expected (no warning).
    pub optional: bool,
    /// Girdle type.
    pub girdle: Girdle,
    /// Human- or animal-like placement.
    pub placement: Placement,
    /// Name of the ratio list in [`Template::ratios`].
    pub ratios: String,
    /// The pectoral girdle's joint (scapula/clavicle), if any.
    pub girdle_joint: Option<String>,
    /// One joint per Table 8.1 boundary: limb root, start of each later row, tip
    /// (`ratios.len() + 1` names).
    pub chain: Vec<String>,
    /// The Table 8.1 row where separated digits start (metacarpals/metatarsals).
    pub digit_row: usize,
    /// Digit names, first digit (thumb/hallux) first.
    pub digits: Vec<String>,
    /// Single-digit or one-segment manus without separated digits.
    pub manus: Manus,
    /// Whether this is a wing (joints shifted to the anterior edge, 8.2).
    pub wing: bool,
    /// DOFs of the first digit's base joint (8.2: two, no roll).
    pub first_digit_base_dofs: Vec<Dof>,
    /// DOFs of the other digits' base joints (8.2: hinge).
    pub digit_base_dofs: Vec<Dof>,
    /// DOFs of the joints between phalanges (8.2: hinge).
    pub phalanx_dofs: Vec<Dof>,
    /// 1-based line in the template file.
    pub line: Option<usize>,
}

/// A validated template.
#[derive(Debug, Clone, PartialEq)]
pub struct Template {
    /// Template name.
    pub name: String,
    /// What figures it is for.
    pub description: String,
    /// Where it was loaded from (`builtin:<name>` or the path).
    pub file: String,
    /// Upright (human-like) or horizontal (animal-like).
    pub posture: Posture,
    /// The refinement its fits get, if any.
    pub refinement: Option<RefineKind>,
    /// The body parts it expects the labels to have, in file order (empty: none checked).
    pub expects: Vec<ExpectedPart>,
    /// Head/neck split.
    pub sections: Sections,
    /// Axial rules.
    pub axial: AxialRules,
    /// Vertebra counts.
    pub vertebrae: VertebraRules,
    /// Named relative ratio lists (Table 8.1 columns `animal_forelimb`, `animal_hind_limb`,
    /// `human_arm`, `human_leg`; `digit`, `first_digit`).
    pub ratios: BTreeMap<String, Vec<f64>>,
    /// Joints, parents before children.
    pub joints: Vec<TemplateJoint>,
    /// Limb groups, anterior first.
    pub limbs: Vec<LimbGroup>,
    /// DOFs of the vertebral joints per region (`[full_spine]`), for `skelfit rig --spine
    /// full`; `None` when the template declares none (the full spine is then not offered).
    pub full_spine: Option<FullSpineDofs>,
}

/// The rotational limits of one inter-vertebral joint per spine region (`[full_spine]` of a
/// template): local x lateral (flexion positive), y dorsal (lateral bending), z along the
/// spine (axial rotation), as every axial joint's frame. The sacrum is fused and rides on the
/// pelvis: it gets no DOFs.
#[derive(Debug, Clone, PartialEq)]
pub struct FullSpineDofs {
    /// Each of C1..C7.
    pub cervical: Vec<Dof>,
    /// Each of T1..T12.
    pub thoracic: Vec<Dof>,
    /// Each of L1..L5.
    pub lumbar: Vec<Dof>,
}

impl FullSpineDofs {
    /// The DOFs of a joint of `region` (none for the sacrum).
    pub fn of(&self, region: SpineRegion) -> &[Dof] {
        match region {
            SpineRegion::Cervical => &self.cervical,
            SpineRegion::Thoracic => &self.thoracic,
            SpineRegion::Lumbar => &self.lumbar,
            SpineRegion::Sacral => &[],
        }
    }
}

impl Template {
    /// The joint called `name`.
    pub fn joint(&self, name: &str) -> Option<&TemplateJoint> {
        self.joints.iter().find(|j| j.name == name)
    }

    /// The joint at axial place `place`.
    pub fn placed(&self, place: &str) -> Option<&TemplateJoint> {
        self.joints
            .iter()
            .find(|j| j.place.as_deref() == Some(place))
    }

    /// A ratio list normalised to fractions summing to 1.
    pub fn fractions(&self, ratios: &str) -> Option<Vec<f64>> {
        let r = self.ratios.get(ratios)?;
        let total: f64 = r.iter().sum();
        Some(r.iter().map(|v| v / total).collect())
    }
}

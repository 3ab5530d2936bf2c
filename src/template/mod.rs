//! Anatomical templates loaded from `templates/*.toml` (dissertation ch.6 and 8.1-8.2): joint
//! names and hierarchy, sections, Table 8.1 limb ratios, digit ratios, vertebra count rules,
//! degrees of freedom with limits, canonical keys, and the naming presets of
//! `templates/presets/*.json`.
//!
//! A template is data: [`Template::builtin`] parses one of the bundled files (embedded with
//! `include_str!`, so the binary works anywhere) and [`Template::load`] reads one from disk.
//! Loading validates everything and reports every problem with its file, key path and line
//! ([`TemplateProblem`]). The fit stage (`crate::fit`) turns a template plus measured geometry
//! into a [`crate::skeleton::Skeleton`].
//!
//! ```
//! use skelfit::template::Template;
//!
//! let humanoid = Template::builtin("humanoid").unwrap();
//! // Table 8.1, human arm: humerus, radius-ulna, carpals, metacarpals, three phalanges.
//! assert_eq!(humanoid.ratios["human_arm"], [190.0, 150.0, 20.0, 36.0, 25.0, 15.0, 10.0]);
//! assert_eq!(humanoid.joint("elbow").unwrap().dofs.len(), 1); // a hinge
//!
//! // A broken file reports every problem with its location.
//! let broken = "[template]\nname = \"x\"\nposture = \"sideways\"\n[sections]\nhead = 0.7\nneck = 0.7\n\
//!     [axial]\ndorsal_offset = 0.7\nvertebra_to_head = 0.33\ncervical_s_curve = false\n\
//!     spine_at = 0.3\nchest_at = 0.6\n[vertebrae]\nneck = [1, 2]\ntrunk = [3, 6]\ntail = [0, 0]\n\
//!     [ratios]\n";
//! let message = Template::parse(broken, "x.toml").unwrap_err().to_string();
//! assert!(message.contains("x.toml:3: template.posture: unknown posture"));
//! assert!(message.contains("does not sum to 1"));
//! assert!(message.contains("no joint has place \"root\""));
//! ```

mod error;
mod load;
mod model;
mod preset;
mod rest_frames;

pub use error::{TemplateError, TemplateProblem};
pub use model::{
    AxialRules, CountRange, ExpectedPart, FullSpineDofs, Girdle, LimbGroup, LimbKind, Manus,
    Placement, Posture, RefineKind, Sections, Template, TemplateJoint, VertebraRules, AXIAL_PLACES,
    BUILTIN_TEMPLATES, SIDED_PLACES,
};
pub use preset::{apply_preset, EngineJoint, EnginePlacement, EngineSkeleton, Preset, PresetNames};
pub use rest_frames::{apply_rest_frames, RestFrame, RestFrames};

#[cfg(test)]
mod tests;

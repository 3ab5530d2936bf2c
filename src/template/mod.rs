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

mod error;
mod load;
mod model;
mod preset;

pub use error::{TemplateError, TemplateProblem};
pub use model::{
    AxialRules, CountRange, Girdle, LimbGroup, LimbKind, Manus, Placement, Posture, Sections,
    Template, TemplateJoint, VertebraRules, AXIAL_PLACES, BUILTIN_TEMPLATES,
};
pub use preset::{apply_preset, Preset, PresetNames};

#[cfg(test)]
mod tests;

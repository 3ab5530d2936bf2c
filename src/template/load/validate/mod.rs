//! Template validation in phases, in file order: header (with the expected parts), sections, axial rules, vertebra
//! counts, ratios, joints, hierarchy, limbs. Every phase reports every problem it finds.

mod joints;
mod limbs;
mod rules;

use super::{dofs, topological, Problems, RawTemplate};
use crate::template::model::*;

/// The template of a parsed file, with every problem pushed to `p` (the template is only used
/// when there are none).
pub(super) fn validate(raw: RawTemplate, p: &mut Problems) -> Template {
    let header = rules::header(raw.template, p);
    let sections = rules::sections(raw.sections, p);
    let axial = rules::axial(raw.axial.into_inner(), p);
    let vertebrae = rules::vertebrae(raw.vertebrae, p);
    let ratios = rules::ratios(raw.ratios, p);
    let table = joints::joints(&raw.joint, &ratios, p);
    joints::hierarchy(&table, p);
    let (limbs, owner) = limbs::limbs(&raw.limb, &ratios, &table, p);
    let full_spine = raw.full_spine.map(|raw| FullSpineDofs {
        cervical: dofs(p, "full_spine.cervical", &raw.cervical),
        thoracic: dofs(p, "full_spine.thoracic", &raw.thoracic),
        lumbar: dofs(p, "full_spine.lumbar", &raw.lumbar),
    });
    joints::unused(&table, &owner, p);

    // Parents before children.
    let order = topological(&table.joints);
    let joints = order.into_iter().map(|k| table.joints[k].clone()).collect();

    Template {
        name: header.name,
        description: header.description,
        file: p.file.to_string(),
        posture: header.posture,
        refinement: header.refinement,
        expects: header.expects,
        sections,
        axial,
        vertebrae,
        ratios,
        joints,
        limbs,
        full_spine,
    }
}

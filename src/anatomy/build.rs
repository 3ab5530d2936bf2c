//! From labelled sections to parts: trunk, protrusions, digits, girdles.

use super::rules::Draft;
use super::{Label, LevelGraph, Part, RuleOptions};
use crate::medial::MedialSurface;
use glam::DVec3;

/// Builds the parts of a labelled draft: the trunk (part 0: trunk vertices and every section
/// merged into it), one part per labelled section (head, then limbs and tail by label and
/// side), and digit parts split off the ends of arms and legs. Returns the parts and the part
/// of every level-graph vertex.
pub fn build_parts(
    draft: &Draft,
    graph: &LevelGraph,
    surface: &MedialSurface,
    options: &RuleOptions,
) -> (Vec<Part>, Vec<u32>) {
    let n = graph.vertices.len();
    let mut vertex_parts = vec![0u32; n];
    let heart = if graph.vertices.is_empty() {
        DVec3::ZERO
    } else {
        surface.centre(graph.heart)
    };
    let mut parts = vec![Part {
        label: Label::Trunk,
        side: None,
        limb_pair: None,
        section: None,
        vertices: Vec::new(),
        voxels: Vec::new(),
        attachment_vertex: None,
        attachment: heart,
        distal: heart,
        girdle: Vec::new(),
        digits: Vec::new(),
        parent: None,
        vertex_count: 0,
    }];
    let mut order: Vec<usize> = (0..draft.sections.len())
        .filter(|&s| draft.assignments[s].label.is_some())
        .collect();
    order.sort_by_key(|&s| {
        let a = draft.assignments[s];
        (a.label, a.limb_pair, a.side, s)
    });
    let mut part_of_section = vec![None; draft.sections.len()];
    for &s in &order {
        let a = draft.assignments[s];
        let sec = &draft.sections[s];
        let index = parts.len();
        part_of_section[s] = Some(index);
        for &v in &sec.vertices {
            vertex_parts[v] = index as u32;
        }
        parts.push(Part {
            label: a.label.unwrap_or(Label::Trunk),
            side: a.side,
            limb_pair: a.limb_pair,
            section: Some(s),
            vertices: sec.vertices.clone(),
            voxels: Vec::new(),
            attachment_vertex: Some(sec.attachment_vertex),
            attachment: sec.attachment,
            distal: sec.distal,
            girdle: Vec::new(),
            digits: Vec::new(),
            parent: Some(0),
            vertex_count: 0,
        });
    }
    // Girdles: the trunk path between partners' attachment vertices.
    for &s in &order {
        if let (Some(partner), Some(i)) = (draft.assignments[s].partner, part_of_section[s]) {
            let a = draft.sections[s].attachment_vertex;
            let b = draft.sections[partner].attachment_vertex;
            parts[i].girdle = graph.path(a, b);
        }
    }
    split_digits(
        draft,
        graph,
        surface,
        options,
        &mut parts,
        &mut vertex_parts,
    );
    for v in 0..n {
        parts[vertex_parts[v] as usize].vertices.push(v);
    }
    for part in &mut parts {
        part.vertices.sort_unstable();
        part.vertices.dedup();
        part.voxels = part
            .vertices
            .iter()
            .flat_map(|&v| graph.vertices[v].voxels.iter().copied())
            .collect();
        part.voxels.sort_unstable();
    }
    (parts, vertex_parts)
}

/// Digit parts: the notable branches toward the end of arms and legs (a level-graph vertex
/// past `digit_start` of the limb with at least two children holding `digit_fraction` of its
/// voxels), each child's subtree a digit part taken from its limb.
fn split_digits(
    draft: &Draft,
    graph: &LevelGraph,
    surface: &MedialSurface,
    options: &RuleOptions,
    parts: &mut Vec<Part>,
    vertex_parts: &mut [u32],
) {
    let limbs: Vec<usize> = (1..parts.len())
        .filter(|&i| matches!(parts[i].label, Label::Arm | Label::Leg))
        .collect();
    for i in limbs {
        let s = parts[i].section.unwrap_or(0);
        let sec = &draft.sections[s];
        let base = graph.vertices[sec.attachment_vertex].centroid;
        let min_voxels = options.digit_fraction * sec.voxels as f64;
        let branch = sec.vertices.iter().copied().find(|&v| {
            let lv = &graph.vertices[v];
            lv.centroid.distance(base) >= options.digit_start * sec.length
                && lv
                    .children
                    .iter()
                    .filter(|&&c| graph.vertices[c].distal_voxels as f64 >= min_voxels)
                    .count()
                    >= 2
        });
        let Some(branch) = branch else { continue };
        let bv = &graph.vertices[branch];
        for &c in &bv.children {
            if (graph.vertices[c].distal_voxels as f64) < min_voxels {
                continue;
            }
            let sub = graph.subtree(c);
            let index = parts.len();
            let mut distal = graph.vertices[c].centroid;
            let mut best = f64::NEG_INFINITY;
            for &v in &sub {
                vertex_parts[v] = index as u32;
                for &p in &graph.vertices[v].voxels {
                    if graph.heart_values[p] > best {
                        best = graph.heart_values[p];
                        distal = surface.centre(p);
                    }
                }
            }
            parts[i].vertices.retain(|v| !sub.contains(v));
            parts[i].digits.push(index);
            parts.push(Part {
                label: Label::Digit,
                side: parts[i].side,
                limb_pair: parts[i].limb_pair,
                section: parts[i].section,
                vertices: sub,
                voxels: Vec::new(),
                attachment_vertex: Some(branch),
                attachment: graph.vertices[c].centroid,
                distal,
                girdle: Vec::new(),
                digits: Vec::new(),
                parent: Some(i),
                vertex_count: 0,
            });
        }
    }
}

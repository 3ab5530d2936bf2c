//! The sections of the level graph: the subtrees hanging off the trunk, each a candidate
//! protrusion (dissertation ch.7.3.3).

use super::{Extremes, LevelGraph, Reach, Section};
use crate::medial::MedialSurface;
use glam::DVec3;

/// Sections of `graph` given its trunk vertices: every non-trunk child of a trunk vertex roots
/// one section.
pub fn sections(graph: &LevelGraph, surface: &MedialSurface, trunk: &[bool]) -> Vec<Section> {
    let mut out = Vec::new();
    for t in 0..graph.vertices.len() {
        if !trunk[t] {
            continue;
        }
        for &c in &graph.vertices[t].children {
            if !trunk[c] {
                out.push(section(graph, surface, t, c));
            }
        }
    }
    out
}

/// The section rooted at `top`, a child of the trunk vertex `attachment_vertex` (also used
/// for a branch leaving a section's main path, `fore_limbs.rs`).
pub(super) fn section(
    graph: &LevelGraph,
    surface: &MedialSurface,
    attachment_vertex: usize,
    top: usize,
) -> Section {
    let vertices = graph.subtree(top);
    let mut count = 0usize;
    let mut sum = DVec3::ZERO;
    let mut reach = Reach::EMPTY;
    let mut extreme = Extremes::default();
    let (mut best, mut best_h) = (DVec3::ZERO, f64::NEG_INFINITY);
    let (mut significant, mut linear) = (0usize, 0usize);
    for &v in &vertices {
        let lv = &graph.vertices[v];
        extreme = extreme.with(lv.marks);
        if !lv.insignificant {
            significant += 1;
            linear += usize::from(lv.marks.linear);
        }
        reach = reach.union(lv.reach);
        for &p in &lv.voxels {
            let x = surface.centre(p);
            count += 1;
            sum += x;
            let h = graph.heart_values[p];
            if h > best_h {
                (best, best_h) = (x, h);
            }
        }
    }
    let top_vertex = &graph.vertices[top];
    Section {
        top,
        attachment_vertex,
        voxels: count,
        weight: top_vertex.weight,
        attachment: top_vertex.centroid,
        distal: best,
        length: best.distance(graph.vertices[attachment_vertex].centroid),
        mean: sum / count.max(1) as f64,
        reach,
        extreme,
        linear_fraction: if significant > 0 {
            linear as f64 / significant as f64
        } else {
            0.0
        },
        insignificant: top_vertex.insignificant,
        vertices,
    }
}

//! The neck: trunk pieces between the pectoral girdle and the head, given to the head for the
//! per-voxel and per-vertex labels (dissertation ch.6: the neck is the part of the axial body
//! between the pectoral girdle and the skull).

use super::{Label, LevelGraph, LimbPair, Part};

/// The level-graph vertices of the neck: the trunk vertices on the tree path from the head's
/// attachment vertex towards the root, up to (not including) the nearest attachment vertex of a
/// pectoral limb (arm, wing, fore leg), together with the trunk vertices hanging from them
/// (protrusions merged into the trunk, such as hair or ears behind the head's junction).
///
/// Empty when there is no head, no pectoral limb, or no pectoral limb joins the trunk between
/// the head and the root (a figure whose arms join beyond its head's junction has no neck in
/// the trunk). `vertex_parts` is the part of every level-graph vertex (0 = trunk).
pub fn neck_vertices(graph: &LevelGraph, parts: &[Part], vertex_parts: &[u32]) -> Vec<usize> {
    let Some(head) = parts.iter().find(|p| p.label == Label::Head) else {
        return Vec::new();
    };
    let Some(attachment) = head.attachment_vertex else {
        return Vec::new();
    };
    let girdles: Vec<usize> = parts
        .iter()
        .filter(|p| match p.label {
            Label::Arm | Label::Wing => true,
            Label::Leg => p.limb_pair == Some(LimbPair::Fore),
            _ => false,
        })
        .filter_map(|p| p.attachment_vertex)
        .collect();
    let up = graph.ancestors(attachment);
    let Some(end) = up.iter().position(|v| girdles.contains(v)) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for &v in &up[..end] {
        if vertex_parts[v] != 0 {
            continue;
        }
        out.push(v);
        // Trunk vertices hanging from the neck (not the path itself, added above).
        for &c in &graph.vertices[v].children {
            if up[..end].contains(&c) {
                continue;
            }
            out.extend(
                graph
                    .subtree(c)
                    .into_iter()
                    .filter(|&u| vertex_parts[u] == 0),
            );
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

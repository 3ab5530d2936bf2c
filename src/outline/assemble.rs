//! Connecting parts drawn one after another (seed 003, 3.2): the cylinder-ball intersection
//! test and the attachment of a child skeleton to the nearest bone of its parent.

use super::{OutlineError, OutlinePart};
use crate::mesh::Mesh;
use crate::skeleton::{Joint, JointId, Skeleton};
use glam::{DAffine3, DVec3};

/// Where a part goes in the model: the transform from its outline frame (outline at z = 0) to
/// the model frame. Parts are listed in modelling order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartPlacement {
    /// Outline frame → model frame (rotation, translation, uniform scale).
    pub transform: DAffine3,
}

impl Default for PartPlacement {
    fn default() -> Self {
        Self {
            transform: DAffine3::IDENTITY,
        }
    }
}

/// Several parts connected into one skeleton and one mesh.
#[derive(Debug, Clone)]
pub struct Assembly {
    /// The connected skeleton (a forest when some part touches no earlier part). With several
    /// parts, joint names are prefixed `partN_` (N from 1 in modelling order).
    pub skeleton: Skeleton,
    /// The parts' inflated meshes, placed and concatenated (they may overlap).
    pub mesh: Mesh,
    /// For each part, the earlier part it was attached to (`None`: a root part).
    pub parent_part: Vec<Option<usize>>,
}

/// Distance from `point` to the bone from `a` to `b` (seed 003, Eq. 3): the distance to the
/// bone's line when `point` lies between the two planes through `a` and `b` perpendicular to
/// the bone (its influence region), else the distance to the nearer end. Returns the distance
/// and whether the point was inside the influence region.
pub fn bone_distance(point: DVec3, a: DVec3, b: DVec3) -> (f64, bool) {
    let ab = b - a;
    let inside = ab.dot(point - a) >= 0.0 && (a - b).dot(point - b) >= 0.0;
    if inside && ab.length_squared() > 0.0 {
        (ab.cross(point - a).length() / ab.length(), true)
    } else {
        (point.distance(a).min(point.distance(b)), false)
    }
}

/// The foot of `point` on the bone `a b` (clamped to the bone).
pub fn attach_point(point: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2 == 0.0 {
        return a;
    }
    a + ab * ((point - a).dot(ab) / len2).clamp(0.0, 1.0)
}

/// An undirected joint graph being assembled.
struct Graph {
    positions: Vec<DVec3>,
    radii: Vec<f64>,
    names: Vec<String>,
    edges: Vec<[usize; 2]>,
    part: Vec<usize>,
}

/// Connects `parts` placed by `placements` (same length, modelling order). Each part after the
/// first is tested against the earlier parts with the cylinder-ball approximation (a ball of
/// the joint's radius at every joint, a cylinder with linearly interpolated radius along every
/// bone); its terminal and junction joints inside the most recent intersecting part are the
/// candidates, and the candidate closest to a parent bone ([`bone_distance`]) is attached:
/// inside the bone's influence region the bone is split by a new joint at the foot (bone split
/// event), otherwise the candidate connects to the nearer end joint (joint connect event).
/// A part that meets no earlier part becomes another root.
///
/// # Errors
/// [`OutlineError::NoParts`] without parts, [`OutlineError::Mesh`] if the placed meshes are
/// invalid (a non-finite transform).
pub fn assemble(
    parts: &[OutlinePart],
    placements: &[PartPlacement],
) -> Result<Assembly, OutlineError> {
    if parts.is_empty() {
        return Err(OutlineError::NoParts);
    }
    let prefix = parts.len() > 1;
    let mut g = Graph {
        positions: Vec::new(),
        radii: Vec::new(),
        names: Vec::new(),
        edges: Vec::new(),
        part: Vec::new(),
    };
    let mut roots = Vec::new();
    let mut parent_part = Vec::new();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for (k, part) in parts.iter().enumerate() {
        let t = placements.get(k).copied().unwrap_or_default().transform;
        let scale = t.matrix3.determinant().abs().cbrt();
        let s = &part.skeleton.skeleton;
        let base = g.positions.len();
        for (j, joint) in s.joints.iter().enumerate() {
            g.positions.push(t.transform_point3(joint.position));
            g.radii
                .push(part.skeleton.radii.get(j).copied().unwrap_or(0.0) * scale);
            g.names.push(if prefix {
                format!("part{}_{}", k + 1, joint.name)
            } else {
                joint.name.clone()
            });
            g.part.push(k);
            if let Some(p) = joint.parent {
                g.edges.push([base + p.0, base + j]);
            }
        }
        let offset = positions.len() as u32;
        positions.extend(part.mesh.positions.iter().map(|&p| t.transform_point3(p)));
        triangles.extend(
            part.mesh
                .triangles
                .iter()
                .map(|tri| tri.map(|i| i + offset)),
        );
        let attached = if k == 0 {
            None
        } else {
            attach(&mut g, k, base)
        };
        if attached.is_none() {
            roots.push(base);
        }
        parent_part.push(attached);
    }
    let skeleton = build(&g, &roots);
    Ok(Assembly {
        skeleton: super::part::with_frames(skeleton),
        mesh: Mesh::new(positions, triangles)?,
        parent_part,
    })
}

/// Attaches part `k` (joints from `base`) to the most recent earlier part it intersects.
fn attach(g: &mut Graph, k: usize, base: usize) -> Option<usize> {
    let n = g.positions.len();
    let mut degree = vec![0usize; n];
    for e in &g.edges {
        degree[e[0]] += 1;
        degree[e[1]] += 1;
    }
    let candidates: Vec<usize> = (base..n).filter(|&j| degree[j] != 2).collect();
    for parent in (0..k).rev() {
        let bones: Vec<[usize; 2]> = g
            .edges
            .iter()
            .copied()
            .filter(|e| g.part[e[0]] == parent)
            .collect();
        let joints: Vec<usize> = (0..base).filter(|&j| g.part[j] == parent).collect();
        let inside = |p: DVec3| {
            joints
                .iter()
                .any(|&j| p.distance(g.positions[j]) <= g.radii[j])
                || bones.iter().any(|&[a, b]| {
                    let (pa, pb) = (g.positions[a], g.positions[b]);
                    let foot = attach_point(p, pa, pb);
                    let u = if pa == pb {
                        0.0
                    } else {
                        foot.distance(pa) / pa.distance(pb)
                    };
                    p.distance(foot) <= g.radii[a] + (g.radii[b] - g.radii[a]) * u
                })
        };
        let hits: Vec<usize> = candidates
            .iter()
            .copied()
            .filter(|&c| inside(g.positions[c]))
            .collect();
        if hits.is_empty() {
            continue;
        }
        // The closest (candidate, bone) pair; a lone parent joint counts as a point bone.
        let mut best: Option<(f64, usize, [usize; 2], bool)> = None;
        let pairs: Vec<[usize; 2]> = if bones.is_empty() {
            joints.iter().map(|&j| [j, j]).collect()
        } else {
            bones
        };
        for &c in &hits {
            for &[a, b] in &pairs {
                let (d, region) = bone_distance(g.positions[c], g.positions[a], g.positions[b]);
                if best.is_none_or(|(bd, ..)| d < bd) {
                    best = Some((d, c, [a, b], region && a != b));
                }
            }
        }
        let (_, c, [a, b], split) = best?;
        if split {
            let foot = attach_point(g.positions[c], g.positions[a], g.positions[b]);
            let m = g.positions.len();
            g.positions.push(foot);
            let u = foot.distance(g.positions[a]) / g.positions[a].distance(g.positions[b]);
            g.radii.push(g.radii[a] + (g.radii[b] - g.radii[a]) * u);
            let name = format!("{}_attach_{}", g.names[a], k + 1);
            g.names.push(name);
            g.part.push(parent);
            g.edges.retain(|e| *e != [a, b]);
            g.edges.push([a, m]);
            g.edges.push([m, b]);
            g.edges.push([m, c]);
        } else {
            let end = if g.positions[c].distance(g.positions[a])
                <= g.positions[c].distance(g.positions[b])
            {
                a
            } else {
                b
            };
            g.edges.push([end, c]);
        }
        return Some(parent);
    }
    None
}

/// The skeleton of the graph: breadth-first from each root in order.
fn build(g: &Graph, roots: &[usize]) -> Skeleton {
    let n = g.positions.len();
    let mut adj = vec![Vec::new(); n];
    for &[a, b] in &g.edges {
        adj[a].push(b);
        adj[b].push(a);
    }
    let mut new_id = vec![usize::MAX; n];
    let mut joints: Vec<Joint> = Vec::with_capacity(n);
    for &root in roots {
        if new_id[root] != usize::MAX {
            continue;
        }
        let mut queue = std::collections::VecDeque::from([(root, None::<usize>)]);
        new_id[root] = usize::MAX - 1;
        while let Some((at, parent)) = queue.pop_front() {
            new_id[at] = joints.len();
            joints.push(Joint::new(
                g.names[at].clone(),
                parent.map(JointId),
                g.positions[at],
            ));
            for &next in &adj[at] {
                if new_id[next] == usize::MAX {
                    new_id[next] = usize::MAX - 1;
                    queue.push_back((next, Some(new_id[at])));
                }
            }
        }
    }
    Skeleton { joints }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bone_distance_follows_equation_3() {
        let (a, b) = (DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0));
        assert_eq!(bone_distance(DVec3::new(1.0, 1.0, 0.0), a, b), (1.0, true));
        let (d, inside) = bone_distance(DVec3::new(3.0, 1.0, 0.0), a, b);
        assert!(!inside && (d - 2f64.sqrt()).abs() < 1e-12);
    }
}

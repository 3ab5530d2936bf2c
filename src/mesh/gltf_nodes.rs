//! The glTF node hierarchy: parents, rest-pose world transforms, scene traversal.

use glam::{DMat4, DQuat, DVec3};
use gltf::scene::Transform;
use gltf::{Document, Node};

/// Parents and rest-pose world transforms of all nodes of a document.
pub(super) struct NodeTree {
    /// Parent node of every node, `None` for roots.
    pub parent: Vec<Option<usize>>,
    /// Rest-pose world transform of every node (f64, from the file's f32 values).
    pub world: Vec<DMat4>,
}

impl NodeTree {
    /// Builds the tree; a node with two parents or a cycle is an error.
    pub fn new(document: &Document) -> Result<Self, String> {
        let nodes: Vec<Node> = document.nodes().collect();
        let count = nodes.len();
        let mut parent = vec![None; count];
        for node in &nodes {
            for child in node.children() {
                let c = child.index();
                if parent[c].is_some() || c == node.index() {
                    return Err(format!("node {c} has more than one parent"));
                }
                parent[c] = Some(node.index());
            }
        }
        let local: Vec<DMat4> = nodes.iter().map(local_transform).collect();
        let mut world: Vec<Option<DMat4>> = vec![None; count];
        for start in 0..count {
            let mut chain = Vec::new();
            let mut current = Some(start);
            while let Some(c) = current {
                if world[c].is_some() {
                    break;
                }
                chain.push(c);
                if chain.len() > count {
                    return Err("the node hierarchy has a cycle".to_string());
                }
                current = parent[c];
            }
            let mut accumulated = current.and_then(|c| world[c]).unwrap_or(DMat4::IDENTITY);
            for &c in chain.iter().rev() {
                accumulated *= local[c];
                world[c] = Some(accumulated);
            }
        }
        Ok(Self {
            parent,
            world: world
                .into_iter()
                .map(|w| w.unwrap_or(DMat4::IDENTITY))
                .collect(),
        })
    }

    /// Nodes reachable from `roots`, depth first, parents before children, children in file
    /// order; each node once.
    pub fn preorder(&self, document: &Document, roots: &[usize]) -> Vec<usize> {
        let nodes: Vec<Node> = document.nodes().collect();
        let mut seen = vec![false; nodes.len()];
        let mut order = Vec::new();
        let mut stack: Vec<usize> = roots.iter().rev().copied().collect();
        while let Some(n) = stack.pop() {
            if n >= nodes.len() || std::mem::replace(&mut seen[n], true) {
                continue;
            }
            order.push(n);
            let children: Vec<usize> = nodes[n].children().map(|c| c.index()).collect();
            stack.extend(children.into_iter().rev());
        }
        order
    }

    /// Root nodes (without parent), for a document without scenes.
    pub fn roots(&self) -> Vec<usize> {
        (0..self.parent.len())
            .filter(|&n| self.parent[n].is_none())
            .collect()
    }
}

/// The node's local transform in f64.
fn local_transform(node: &Node) -> DMat4 {
    match node.transform() {
        Transform::Matrix { matrix } => {
            DMat4::from_cols_array_2d(&matrix.map(|c| c.map(f64::from)))
        }
        Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => DMat4::from_scale_rotation_translation(
            DVec3::from_array(scale.map(f64::from)),
            DQuat::from_array(rotation.map(f64::from)),
            DVec3::from_array(translation.map(f64::from)),
        ),
    }
}

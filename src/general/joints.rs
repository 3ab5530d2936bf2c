//! Segments and joints of the control skeleton from the skeletal graph (dissertation ch.5.2.5).

use super::{GeneralOptions, SkeletalGraph};
use crate::paths::PathTree;
use crate::skeleton::{Joint, JointId, Skeleton};
use glam::DVec3;
use serde::Serialize;
use std::collections::{BTreeMap, VecDeque};

/// A control segment: one skeletal edge (or, for the edge hosting a midpoint root, one half of
/// it), rotated by its proximal joint.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Segment {
    /// The joint at the segment's proximal end, which rotates it.
    pub joint: JointId,
    /// The joint at its distal end (the first of the coincident joints at a branch, or an end
    /// effector).
    pub child: JointId,
    /// The path-tree chain it approximates (index into [`PathTree::chains`]).
    pub chain: usize,
    /// Linear grid indices of the path-tree voxels of its chain section, proximal to distal.
    /// The union of their distance-map spheres is the segment's region of influence (ch.5.2.5).
    pub voxels: Vec<usize>,
}

/// The skeleton before frames: joints, segments and each joint's proximal (`incoming`) and
/// distal (`outgoing`) segment directions, mesh frame.
pub(crate) struct Assembly {
    pub skeleton: Skeleton,
    pub segments: Vec<Segment>,
    pub incoming: Vec<Option<DVec3>>,
    pub outgoing: Vec<Option<DVec3>>,
}

/// A vertex of the skeletal graph reached through `edge` from `from`, waiting for its joints.
struct Pending {
    vertex: usize,
    position: DVec3,
    edge: usize,
    from: DVec3,
    parent: JointId,
    voxels: Vec<usize>,
}

struct Builder<'a> {
    tree: &'a PathTree,
    graph: &'a SkeletalGraph,
    out: Assembly,
    joints: usize,
    ends: usize,
}

impl Builder<'_> {
    /// `(vertex, position)` of both ends of edge `e`; vertices are path-tree node indices.
    fn ends(&self, e: usize) -> [(usize, DVec3); 2] {
        let edge = &self.graph.edges[e];
        let chain = &self.tree.chains[edge.chain];
        [edge.start, edge.end].map(|i| (chain.nodes[i], chain.smoothed[i]))
    }

    fn voxels(&self, e: usize, from: usize, to: usize) -> Vec<usize> {
        let edge = &self.graph.edges[e];
        self.tree.chains[edge.chain].voxels[from..=to].to_vec()
    }

    fn add(&mut self, joint: Joint, incoming: Option<DVec3>, outgoing: Option<DVec3>) -> JointId {
        self.out.skeleton.joints.push(joint);
        self.out.incoming.push(incoming);
        self.out.outgoing.push(outgoing);
        JointId(self.out.skeleton.joints.len() - 1)
    }
}

/// Builds joints and segments (ch.5.2.5): the root joint at the midpoint of the deep edge (the
/// edge through the path-tree voxel nearest the heart; it does not divide the edge) or, with
/// [`GeneralOptions::root_at_lowest`], at the lowest end vertex; at every vertex reached from a
/// proximal edge, one joint per distal edge (coincident joints at branches, one less than the
/// edges meeting there), children of the proximal edge's joint; an end effector at every
/// vertex with no distal edge. Names: `root`, then `joint_001`, `joint_002`... and `end_001`,
/// `end_002`... in breadth-first order (parents before children). End effectors have
/// `deform = false` and no degrees of freedom: they rotate nothing.
pub(crate) fn assemble(
    tree: &PathTree,
    graph: &SkeletalGraph,
    options: &GeneralOptions,
) -> Assembly {
    let mut b = Builder {
        tree,
        graph,
        out: Assembly {
            skeleton: Skeleton::default(),
            segments: Vec::new(),
            incoming: Vec::new(),
            outgoing: Vec::new(),
        },
        joints: 0,
        ends: 0,
    };
    if graph.edges.is_empty() {
        let root = Joint::new("root", None, tree.centre(0));
        b.add(root, None, None);
        return b.out;
    }
    let mut incident: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for e in 0..graph.edges.len() {
        for (v, _) in b.ends(e) {
            incident.entry(v).or_default().push(e);
        }
    }
    let mut queue = root(&mut b, &incident, options);
    while let Some(p) = queue.pop_front() {
        let incoming = p.position - p.from;
        let distal: Vec<usize> = incident[&p.vertex]
            .iter()
            .copied()
            .filter(|&e| e != p.edge)
            .collect();
        let chain = graph.edges[p.edge].chain;
        if distal.is_empty() {
            b.ends += 1;
            let mut joint = Joint::new(format!("end_{:03}", b.ends), Some(p.parent), p.position);
            joint.deform = false;
            joint.dofs.clear();
            let child = b.add(joint, Some(incoming), None);
            b.out.segments.push(Segment {
                joint: p.parent,
                child,
                chain,
                voxels: p.voxels,
            });
            continue;
        }
        let mut first = None;
        for e in distal {
            let [a, z] = b.ends(e);
            let (there, forward) = if a.0 == p.vertex {
                (z, true)
            } else {
                (a, false)
            };
            b.joints += 1;
            let joint = Joint::new(format!("joint_{:03}", b.joints), Some(p.parent), p.position);
            let id = b.add(joint, Some(incoming), Some(there.1 - p.position));
            first.get_or_insert(id);
            let edge = graph.edges[e];
            let mut voxels = b.voxels(e, 0, edge.end - edge.start);
            if !forward {
                voxels.reverse();
            }
            queue.push_back(Pending {
                vertex: there.0,
                position: there.1,
                edge: e,
                from: p.position,
                parent: id,
                voxels,
            });
        }
        b.out.segments.push(Segment {
            joint: p.parent,
            child: first.unwrap_or(p.parent),
            chain,
            voxels: p.voxels,
        });
    }
    b.out
}

/// Places the root joint (at the lowest end vertex or the middle of the deep edge, see
/// [`assemble`]) and returns the edges to walk from it. `incident`: the edges at each vertex.
fn root(
    b: &mut Builder<'_>,
    incident: &BTreeMap<usize, Vec<usize>>,
    options: &GeneralOptions,
) -> VecDeque<Pending> {
    let (tree, graph) = (b.tree, b.graph);
    let mut queue = VecDeque::new();
    if options.root_at_lowest {
        let lowest = incident
            .iter()
            .filter(|(_, edges)| edges.len() == 1)
            .map(|(&v, edges)| {
                let e = edges[0];
                let [a, z] = b.ends(e);
                let (here, there, forward) = if a.0 == v {
                    (a, z, true)
                } else {
                    (z, a, false)
                };
                (here.1.dot(options.up), v, e, here.1, there, forward)
            })
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        if let Some((_, _, e, at, there, forward)) = lowest {
            let root = b.add(Joint::new("root", None, at), None, Some(there.1 - at));
            let edge = graph.edges[e];
            let len = edge.end - edge.start;
            let mut voxels = b.voxels(e, 0, len);
            if !forward {
                voxels.reverse();
            }
            queue.push_back(Pending {
                vertex: there.0,
                position: there.1,
                edge: e,
                from: at,
                parent: root,
                voxels,
            });
        }
    } else {
        let e = deep_edge(tree, graph);
        let [u, v] = b.ends(e);
        let middle = (u.1 + v.1) / 2.0;
        let root = b.add(Joint::new("root", None, middle), None, Some(v.1 - middle));
        let edge = graph.edges[e];
        let mid = (edge.end - edge.start) / 2;
        let mut towards_u = b.voxels(e, 0, mid);
        towards_u.reverse();
        let towards_v = b.voxels(e, mid, edge.end - edge.start);
        for (end, voxels) in [(u, towards_u), (v, towards_v)] {
            queue.push_back(Pending {
                vertex: end.0,
                position: end.1,
                edge: e,
                from: middle,
                parent: root,
                voxels,
            });
        }
    }
    queue
}

/// The deep edge: the first edge whose chain section contains the path-tree voxel nearest the
/// heart (the deepest voxel among equally near ones, then the first).
fn deep_edge(tree: &PathTree, graph: &SkeletalGraph) -> usize {
    let mut best = (f64::INFINITY, 0u32, 0usize);
    for node in 0..tree.voxels.len() {
        let d = tree.centre(node).distance_squared(tree.heart_centre);
        if d < best.0 || (d == best.0 && tree.squared[node] > best.1) {
            best = (d, tree.squared[node], node);
        }
    }
    let node = best.2;
    graph
        .edges
        .iter()
        .position(|e| tree.chains[e.chain].nodes[e.start..=e.end].contains(&node))
        .unwrap_or(0)
}

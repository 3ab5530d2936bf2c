//! Reading a fitted skeleton's anatomy from its structure and canonical map: the vertebral
//! column, head, jaw, tail, and each limb's girdle, chain and digits. Names are not used (a
//! naming preset may have renamed every joint).

use super::BoneWarning;
use crate::fit::{Fit, Side};
use crate::skeleton::canonical::{Canonical, Tail};
use crate::skeleton::{JointId, Skeleton};
use glam::{DMat3, DVec3};
use std::collections::BTreeMap;

/// Which girdle a limb hangs from (9.1: arms, wings and fore legs are pectoral).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum GirdleKind {
    Pectoral,
    Pelvic,
}

/// One limb: an optional girdle joint, the chain from the shoulder/hip, and digits.
#[derive(Debug, Clone)]
pub(crate) struct Limb {
    pub girdle: GirdleKind,
    pub side: Side,
    /// Joint the limb hangs from (a trunk joint or the root).
    pub parent: JointId,
    /// Clavicle/scapula joint of a pectoral limb.
    pub girdle_joint: Option<JointId>,
    /// Shoulder/hip, elbow/knee, wrist/ankle, ... up to a leaf or a branching joint.
    pub chain: Vec<JointId>,
    /// Separated digits hanging from the chain's last joint, each base → tip.
    pub digits: Vec<Vec<JointId>>,
    /// Where the limb's first bone starts: the first chain joint, or for a pelvic pair whose
    /// hips nearly coincide (closer than half the knees' distance) a socket below the hip at
    /// the knee's lateral offset.
    pub origin: DVec3,
}

/// Body directions and parts.
#[derive(Debug, Clone)]
pub(crate) struct Body {
    pub up: DVec3,
    pub forward: DVec3,
    pub left: DVec3,
    pub root: JointId,
    /// Root → … → the joint before the head (trunk then neck).
    pub spine: Vec<JointId>,
    pub head: Option<JointId>,
    pub head_end: Option<JointId>,
    /// Jaw joint and its end.
    pub jaw: Option<(JointId, JointId)>,
    /// Tail joints from the first to the tip.
    pub tail: Vec<JointId>,
    pub limbs: Vec<Limb>,
    pub upright: bool,
}

fn single_chain(s: &Skeleton, from: JointId) -> (Vec<JointId>, Vec<JointId>) {
    let mut chain = vec![from];
    loop {
        let children = s.children(*chain.last().unwrap_or(&from));
        match children.len() {
            1 => chain.push(children[0]),
            0 => return (chain, Vec::new()),
            _ => return (chain, children),
        }
    }
}

/// The spine: the ancestors of the head down to the root, else (with a warning) the root's
/// longest chain.
fn spine(
    s: &Skeleton,
    root: JointId,
    head: Option<JointId>,
    warnings: &mut Vec<BoneWarning>,
) -> Vec<JointId> {
    let mut spine = Vec::new();
    if let Some(h) = head {
        let mut cur = s.joint(h).parent;
        while let Some(p) = cur {
            spine.push(p);
            if p == root {
                break;
            }
            cur = s.joint(p).parent;
        }
        spine.reverse();
        if spine.first() != Some(&root) {
            spine.clear();
        }
    }
    if spine.is_empty() {
        warnings.push(BoneWarning::NoHeadOnChain);
        spine = longest_chain(s, root);
    }
    spine
}

/// The limb whose chain starts at `first`, a child of spine joint `parent`: pelvic when it
/// hangs from the root, its side by where it lies (`left`), and a girdle joint split off a
/// pectoral chain when `first` is a clavicle (by `key`, its canonical key) or the chain is long.
fn limb(
    s: &Skeleton,
    parent: JointId,
    first: JointId,
    key: Option<Canonical>,
    root: JointId,
    left: DVec3,
) -> Limb {
    let centre = s.joint(root).position;
    let girdle = if parent == root {
        GirdleKind::Pelvic
    } else {
        GirdleKind::Pectoral
    };
    let (mut chain, branch) = single_chain(s, first);
    let side = if (s.joint(first).position - centre).dot(left)
        + (s.joint(*chain.last().unwrap_or(&first)).position - centre).dot(left)
        >= 0.0
    {
        Side::Left
    } else {
        Side::Right
    };
    let girdle_joint = if girdle == GirdleKind::Pectoral
        && chain.len() >= 2
        && (matches!(key, Some(Canonical::Clavicle(_)))
            || (!matches!(key, Some(Canonical::Shoulder(_)))
                && ((branch.is_empty() && chain.len() >= 9)
                    || (!branch.is_empty() && chain.len() >= 4))))
    {
        Some(chain.remove(0))
    } else {
        None
    };
    let digits = branch.into_iter().map(|b| single_chain(s, b).0).collect();
    let origin = s.joint(chain[0]).position;
    Limb {
        girdle,
        side,
        parent,
        girdle_joint,
        chain,
        digits,
        origin,
    }
}

/// Reads the body of `fit`. `warnings` receives what is missing.
pub(crate) fn body(fit: &Fit, warnings: &mut Vec<BoneWarning>) -> Body {
    let s = &fit.skeleton;
    let key_of: BTreeMap<JointId, Option<Canonical>> = fit
        .canonical
        .iter()
        .map(|(k, id)| (*id, k.parse::<Canonical>().ok()))
        .collect();
    // The pelvis when it is the root or hangs only from non-deforming joints (an engine
    // preset's `root` on the ground), else the skeleton's root.
    let below_controls = |id: JointId| {
        let mut at = s.joint(id).parent;
        while let Some(p) = at {
            if s.joint(p).deform {
                return false;
            }
            at = s.joint(p).parent;
        }
        true
    };
    let root = fit
        .canonical
        .get(Canonical::Pelvis.as_str())
        .copied()
        .filter(|id| below_controls(*id))
        .unwrap_or(JointId(0));
    let head = fit.canonical.get(Canonical::Head.as_str()).copied();
    let spine = spine(s, root, head, warnings);
    let (mut head_end, mut jaw) = (None, None);
    if let Some(h) = head {
        for c in s.children(h) {
            let grand = s.children(c);
            if grand.is_empty() && head_end.is_none() {
                head_end = Some(c);
            } else if grand.len() == 1 && s.children(grand[0]).is_empty() && jaw.is_none() {
                // The jaw is a two-joint branch (jaw, jaw_end); longer head branches are ears,
                // cartilage without a bone.
                jaw = Some((c, grand[0]));
            }
        }
    }
    let in_spine = |j: JointId| spine.contains(&j) || Some(j) == head;
    // Tail: from the canonical tail base, else none.
    let tail = fit
        .canonical
        .get(Canonical::Tail(Tail::Base).as_str())
        .map(|&t| single_chain(s, t).0)
        .unwrap_or_default();

    // Body directions: dorsal from the root frame, head direction along the spine.
    let dorsal = DMat3::from_quat(s.joint(root).frame).y_axis;
    let tip = head
        .map(|h| s.joint(h).position)
        .or_else(|| spine.last().map(|j| s.joint(*j).position))
        .unwrap_or(s.joint(root).position);
    let head_dir = (tip - s.joint(root).position)
        .try_normalize()
        .unwrap_or(DVec3::Y);
    // Limbs: every other child subtree of the spine.
    let mut raw: Vec<(JointId, JointId)> = Vec::new();
    for &j in &spine {
        for c in s.children(j) {
            if !in_spine(c) && !tail.contains(&c) {
                raw.push((j, c));
            }
        }
    }
    // Up: against the pelvic limbs (they hang down), else the dorsal direction.
    let mut down = DVec3::ZERO;
    for &(p, c) in &raw {
        if p == root {
            let (chain, _) = single_chain(s, c);
            let end = s.joint(*chain.last().unwrap_or(&c)).position;
            down += (end - s.joint(c).position).normalize_or_zero();
        }
    }
    let up = (-down).try_normalize().unwrap_or(dorsal);
    let forward = perpendicular(head_dir - dorsal, up)
        .or_else(|| perpendicular(head_dir, up))
        .unwrap_or_else(|| up.any_orthonormal_vector());
    let left = up.cross(forward);
    let upright = head_dir.dot(up) > 0.7;
    let mut limbs = Vec::new();
    for (parent, first) in raw {
        let key = key_of.get(&first).copied().flatten();
        limbs.push(limb(s, parent, first, key, root, left));
    }
    separate_hips(s, &mut limbs, left);
    Body {
        up,
        forward,
        left,
        root,
        spine,
        head,
        head_end,
        jaw,
        tail,
        limbs,
        upright,
    }
}

/// Moves the origins of a pelvic pair apart when the hips nearly coincide (a fit on a figure
/// whose legs meet at the crotch): each socket takes its knee's lateral offset from the hips'
/// midpoint.
fn separate_hips(s: &Skeleton, limbs: &mut [Limb], left: DVec3) {
    let find = |limbs: &[Limb], side: Side| {
        limbs
            .iter()
            .position(|l| l.girdle == GirdleKind::Pelvic && l.side == side && l.chain.len() >= 2)
    };
    let (Some(l), Some(r)) = (find(limbs, Side::Left), find(limbs, Side::Right)) else {
        return;
    };
    let pos = |j: JointId| s.joint(j).position;
    let (hl, hr) = (pos(limbs[l].chain[0]), pos(limbs[r].chain[0]));
    let (kl, kr) = (pos(limbs[l].chain[1]), pos(limbs[r].chain[1]));
    if hl.distance(hr) >= 0.5 * kl.distance(kr) {
        return;
    }
    let mid = 0.5 * (hl + hr);
    limbs[l].origin = mid + left * (kl - mid).dot(left);
    limbs[r].origin = mid + left * (kr - mid).dot(left);
}

/// The unit component of `v` perpendicular to `axis`, if not (nearly) zero.
pub(crate) fn perpendicular(v: DVec3, axis: DVec3) -> Option<DVec3> {
    let p = v - axis * v.dot(axis);
    (p.length() > 1e-6 * v.length().max(1e-300)).then(|| p.normalize())
}

fn longest_chain(s: &Skeleton, root: JointId) -> Vec<JointId> {
    // Depth-first over the tree: the root-to-leaf path with most joints (lowest ids on ties).
    let mut best: Vec<JointId> = vec![root];
    let mut stack = vec![vec![root]];
    while let Some(path) = stack.pop() {
        let last = *path.last().unwrap_or(&root);
        let children = s.children(last);
        if children.is_empty() && path.len() > best.len() {
            best = path.clone();
        }
        for c in children.into_iter().rev() {
            let mut next = path.clone();
            next.push(c);
            stack.push(next);
        }
    }
    // The last joint is a leaf marker: the column ends before it.
    if best.len() > 1 {
        best.pop();
    }
    best
}

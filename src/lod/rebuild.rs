//! Rebuilding a skeleton after joints were merged into groups or removed.

use crate::skeleton::{Joint, JointId, Skeleton};
use glam::DVec3;

/// Union-find over joints.
pub(crate) struct Groups {
    parent: Vec<usize>,
}

impl Groups {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            parent: (0..n).collect(),
        }
    }

    pub(crate) fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] != x {
            self.parent[x] = self.parent[self.parent[x]];
            x = self.parent[x];
        }
        x
    }

    /// Joins the groups of `a` and `b`; the lower index becomes the representative.
    pub(crate) fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            let (lo, hi) = (ra.min(rb), ra.max(rb));
            self.parent[hi] = lo;
        }
    }
}

/// The skeleton with each group of joints (connected through bones) made one joint, and the
/// `removed` joints dropped (their descendants must be removed too). A group keeps the name,
/// frame, DOFs and deform flag of its top joint (its lowest index) and takes the position
/// `position(members)`.
pub(crate) fn rebuild(
    skeleton: &Skeleton,
    groups: &mut Groups,
    removed: &[bool],
    position: impl Fn(&[usize]) -> DVec3,
) -> Skeleton {
    let n = skeleton.len();
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (k, &gone) in removed.iter().enumerate().take(n) {
        if !gone {
            let r = groups.find(k);
            members[r].push(k);
        }
    }
    let mut new_id = vec![usize::MAX; n];
    let mut joints: Vec<Joint> = Vec::new();
    for top in 0..n {
        if removed[top] || groups.find(top) != top {
            continue;
        }
        let old = &skeleton.joints[top];
        let parent = old.parent.map(|p| {
            let g = groups.find(p.0);
            JointId(new_id[g])
        });
        new_id[top] = joints.len();
        joints.push(Joint {
            parent,
            position: position(&members[top]),
            ..old.clone()
        });
    }
    Skeleton { joints }
}

/// The mean position of `members`.
pub(crate) fn mean(skeleton: &Skeleton, members: &[usize]) -> DVec3 {
    members
        .iter()
        .map(|&k| skeleton.joints[k].position)
        .sum::<DVec3>()
        / members.len().max(1) as f64
}

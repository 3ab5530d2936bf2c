//! The undirected view of a skeleton: degrees, neighbours, branches and scopes.

use super::{LodError, LodScope};
use crate::skeleton::Skeleton;

/// Number of bones at each joint (children, plus one for the parent).
pub fn degrees(skeleton: &Skeleton) -> Vec<usize> {
    let mut d = vec![0usize; skeleton.len()];
    for (k, j) in skeleton.joints.iter().enumerate() {
        if let Some(p) = j.parent {
            d[k] += 1;
            d[p.0] += 1;
        }
    }
    d
}

/// Neighbour lists (parent first, then children in joint order).
pub(crate) fn neighbours(skeleton: &Skeleton) -> Vec<Vec<usize>> {
    let mut adj = vec![Vec::new(); skeleton.len()];
    for (k, j) in skeleton.joints.iter().enumerate() {
        if let Some(p) = j.parent {
            adj[k].push(p.0);
        }
    }
    for (k, j) in skeleton.joints.iter().enumerate() {
        if let Some(p) = j.parent {
            adj[p.0].push(k);
        }
    }
    adj
}

/// The branches of a skeleton (seed 003, Definition 6): maximal chains of joints whose inner
/// joints are sleeve joints (two bones), from a junction or terminal joint to another, each
/// listed once, starting at its lower-indexed end. A single joint gives no branch.
pub fn branches(skeleton: &Skeleton) -> Vec<Vec<usize>> {
    let adj = neighbours(skeleton);
    let mut out = Vec::new();
    for start in 0..skeleton.len() {
        if adj[start].len() == 2 {
            continue;
        }
        for &first in &adj[start] {
            let mut chain = vec![start, first];
            let mut prev = start;
            let mut at = first;
            while adj[at].len() == 2 {
                let next = if adj[at][0] == prev {
                    adj[at][1]
                } else {
                    adj[at][0]
                };
                prev = at;
                at = next;
                chain.push(at);
            }
            if start < at || (start == at && chain[1] < chain[chain.len() - 2]) {
                out.push(chain);
            }
        }
    }
    out
}

/// Checks the skeleton's invariants.
pub(crate) fn check(skeleton: &Skeleton) -> Result<(), LodError> {
    skeleton
        .validate()
        .map_err(|problems| LodError::InvalidSkeleton {
            message: problems
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; "),
        })
}

/// Which joints the scope lets an operation change.
pub(crate) fn in_scope(skeleton: &Skeleton, scope: &LodScope) -> Result<Vec<bool>, LodError> {
    let n = skeleton.len();
    let find = |name: &str| {
        skeleton.find(name).ok_or_else(|| LodError::UnknownJoint {
            name: name.to_string(),
        })
    };
    Ok(match scope {
        LodScope::Global => vec![true; n],
        LodScope::Part(name) => {
            let top = find(name)?.0;
            let mut mask = vec![false; n];
            mask[top] = true;
            for k in top + 1..n {
                if let Some(p) = skeleton.joints[k].parent {
                    mask[k] = mask[p.0];
                }
            }
            mask
        }
        LodScope::Branch(name) => {
            let mut at = find(name)?;
            let mut mask = vec![false; n];
            mask[at.0] = true;
            loop {
                let children = skeleton.children(at);
                if children.len() != 1 {
                    break;
                }
                at = children[0];
                mask[at.0] = true;
            }
            mask
        }
    })
}

/// Length of the bones along a chain of joints.
pub(crate) fn chain_length(skeleton: &Skeleton, chain: &[usize]) -> f64 {
    chain
        .windows(2)
        .map(|w| {
            skeleton.joints[w[0]]
                .position
                .distance(skeleton.joints[w[1]].position)
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skeleton::{Joint, JointId};
    use glam::DVec3;

    /// root - a - junction - {b - tip1, tip2}
    fn y_shape() -> Skeleton {
        let j = |name: &str, parent: Option<usize>, x: f64| {
            Joint::new(name, parent.map(JointId), DVec3::new(x, 0.0, 0.0))
        };
        Skeleton {
            joints: vec![
                j("root", None, 0.0),
                j("a", Some(0), 1.0),
                j("junction", Some(1), 2.0),
                j("b", Some(2), 3.0),
                j("tip1", Some(3), 4.0),
                j("tip2", Some(2), 5.0),
            ],
        }
    }

    #[test]
    fn branches_run_between_junction_and_terminal_joints() {
        let s = y_shape();
        assert_eq!(degrees(&s), vec![1, 2, 3, 2, 1, 1]);
        let mut b = branches(&s);
        b.sort();
        assert_eq!(b, vec![vec![0, 1, 2], vec![2, 3, 4], vec![2, 5]]);
        assert!((chain_length(&s, &[0, 1, 2]) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn scopes_select_a_subtree_or_a_branch() {
        let s = y_shape();
        let part = in_scope(&s, &LodScope::Part("b".into())).unwrap();
        assert_eq!(part, vec![false, false, false, true, true, false]);
        let branch = in_scope(&s, &LodScope::Branch("a".into())).unwrap();
        assert_eq!(branch, vec![false, true, true, false, false, false]);
        assert!(in_scope(&s, &LodScope::Part("x".into())).is_err());
    }
}

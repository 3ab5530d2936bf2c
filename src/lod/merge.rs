//! Junction merging (seed 003, 3.3, ε_m): clusters of nearby junction joints become one.

use super::graph::{check, degrees, in_scope};
use super::options::check_threshold;
use super::rebuild::{rebuild, Groups};
use super::{LodError, LodScope};
use crate::skeleton::Skeleton;
use glam::DVec3;

/// Merges junction joints (three or more bones) whose connecting bones add up to at most
/// `epsilon` (skeleton units): from each junction the chain to its ancestors is followed while
/// the length stays within `epsilon`, and reaching another junction merges every joint on the
/// way into one, placed at the mean of the junctions merged (a breadth-first clustering as in
/// seed 003). Joints outside `scope` are not merged.
///
/// # Errors
/// [`LodError::InvalidThreshold`], [`LodError::UnknownJoint`], [`LodError::InvalidSkeleton`].
pub fn merge_junctions(
    skeleton: &Skeleton,
    epsilon: f64,
    scope: &LodScope,
) -> Result<Skeleton, LodError> {
    check_threshold("merge", epsilon)?;
    check(skeleton)?;
    let mask = in_scope(skeleton, scope)?;
    let degree = degrees(skeleton);
    let junction: Vec<bool> = degree.iter().map(|&d| d >= 3).collect();
    let mut groups = Groups::new(skeleton.len());
    for k in 0..skeleton.len() {
        if !junction[k] || !mask[k] {
            continue;
        }
        let mut path = vec![k];
        let mut length = 0.0;
        let mut at = k;
        while let Some(p) = skeleton.joints[at].parent {
            length += skeleton.joints[at]
                .position
                .distance(skeleton.joints[p.0].position);
            if length > epsilon || !mask[p.0] {
                break;
            }
            path.push(p.0);
            if junction[p.0] {
                for w in path.windows(2) {
                    groups.union(w[0], w[1]);
                }
                break;
            }
            at = p.0;
        }
    }
    let removed = vec![false; skeleton.len()];
    Ok(rebuild(skeleton, &mut groups, &removed, |members| {
        let js: Vec<DVec3> = members
            .iter()
            .filter(|&&m| junction[m] || members.len() == 1)
            .map(|&m| skeleton.joints[m].position)
            .collect();
        js.iter().sum::<DVec3>() / js.len().max(1) as f64
    }))
}

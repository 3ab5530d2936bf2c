//! Branch pruning (seed 003, 3.3, ε_t): short junction-to-terminal branches are removed.

use super::graph::{branches, chain_length, check, degrees, in_scope};
use super::options::check_threshold;
use super::rebuild::{rebuild, Groups};
use super::{LodError, LodScope};
use crate::skeleton::Skeleton;

/// Removes every JT-branch (from a junction joint to a terminal joint) shorter than `epsilon`
/// (skeleton units): its sleeve joints and its terminal joint go, the junction stays. Branches
/// holding the root, or any joint outside `scope`, stay. All branches are judged on the input
/// skeleton, so a larger `epsilon` removes a superset.
///
/// # Errors
/// [`LodError::InvalidThreshold`], [`LodError::UnknownJoint`], [`LodError::InvalidSkeleton`].
pub fn prune_branches(
    skeleton: &Skeleton,
    epsilon: f64,
    scope: &LodScope,
) -> Result<Skeleton, LodError> {
    check_threshold("prune", epsilon)?;
    check(skeleton)?;
    let mask = in_scope(skeleton, scope)?;
    let degree = degrees(skeleton);
    let mut removed = vec![false; skeleton.len()];
    for chain in branches(skeleton) {
        let (a, b) = (chain[0], chain[chain.len() - 1]);
        // Everything but the junction end.
        let rest = match (degree[a], degree[b]) {
            (da, 1) if da >= 3 => &chain[1..],
            (1, db) if db >= 3 => &chain[..chain.len() - 1],
            _ => continue,
        };
        if rest.iter().any(|&k| k == 0 || !mask[k]) {
            continue;
        }
        if chain_length(skeleton, &chain) < epsilon {
            for &k in rest {
                removed[k] = true;
            }
        }
    }
    let mut groups = Groups::new(skeleton.len());
    Ok(rebuild(skeleton, &mut groups, &removed, |m| {
        skeleton.joints[m[0]].position
    }))
}

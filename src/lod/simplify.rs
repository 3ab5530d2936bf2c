//! Branch simplification (seed 003, 3.3, ε_s): Douglas-Peucker along each branch.

use super::graph::{branches, check, in_scope};
use super::options::check_threshold;
use super::rebuild::{rebuild, Groups};
use super::{LodError, LodScope};
use crate::math::douglas_peucker;
use crate::skeleton::Skeleton;

/// Drops the sleeve joints of each branch that Douglas-Peucker with tolerance `epsilon`
/// (skeleton units) does not keep; a dropped joint's bone is taken over by its child. Branch
/// ends, the root and joints outside `scope` stay. `epsilon = 0` drops only exactly collinear
/// joints... and is treated as off: the skeleton is returned unchanged.
///
/// # Errors
/// [`LodError::InvalidThreshold`], [`LodError::UnknownJoint`], [`LodError::InvalidSkeleton`].
pub fn simplify_branches(
    skeleton: &Skeleton,
    epsilon: f64,
    scope: &LodScope,
) -> Result<Skeleton, LodError> {
    check_threshold("simplify", epsilon)?;
    check(skeleton)?;
    let mask = in_scope(skeleton, scope)?;
    if epsilon == 0.0 {
        return Ok(skeleton.clone());
    }
    let mut groups = Groups::new(skeleton.len());
    for chain in branches(skeleton) {
        let points: Vec<_> = chain.iter().map(|&k| skeleton.joints[k].position).collect();
        let keep = douglas_peucker(&points, epsilon);
        for (i, &k) in chain.iter().enumerate() {
            let Some(parent) = skeleton.joints[k].parent else {
                continue;
            };
            if !keep[i] && mask[k] {
                groups.union(parent.0, k);
            }
        }
    }
    let removed = vec![false; skeleton.len()];
    Ok(rebuild(skeleton, &mut groups, &removed, |m| {
        skeleton.joints[m[0]].position
    }))
}

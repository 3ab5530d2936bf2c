//! Bone collapsing (seed 003, 3.3, ε_c): short bones between internal joints vanish.

use super::graph::{check, degrees, in_scope};
use super::options::check_threshold;
use super::rebuild::{mean, rebuild, Groups};
use super::{LodError, LodScope};
use crate::skeleton::Skeleton;

/// Collapses every bone shorter than `epsilon` (skeleton units) whose two joints are internal
/// (junction or sleeve joints: two or more bones) into one joint at the mean of the joints
/// collapsed together. Bones are judged on the input skeleton, so a larger `epsilon` collapses
/// a superset and never leaves more joints. Both joints must lie in `scope`.
///
/// # Errors
/// [`LodError::InvalidThreshold`], [`LodError::UnknownJoint`], [`LodError::InvalidSkeleton`].
pub fn collapse_bones(
    skeleton: &Skeleton,
    epsilon: f64,
    scope: &LodScope,
) -> Result<Skeleton, LodError> {
    check_threshold("collapse", epsilon)?;
    check(skeleton)?;
    let mask = in_scope(skeleton, scope)?;
    let degree = degrees(skeleton);
    let mut groups = Groups::new(skeleton.len());
    for (k, joint) in skeleton.joints.iter().enumerate() {
        let Some(p) = joint.parent else { continue };
        let internal = degree[k] >= 2 && degree[p.0] >= 2;
        let short = joint.position.distance(skeleton.joints[p.0].position) < epsilon;
        if internal && short && mask[k] && mask[p.0] {
            groups.union(p.0, k);
        }
    }
    let removed = vec![false; skeleton.len()];
    Ok(rebuild(skeleton, &mut groups, &removed, |m| {
        mean(skeleton, m)
    }))
}

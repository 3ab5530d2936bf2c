//! Level-of-detail operations on any skelfit [`Skeleton`] (seed 003,
//! 3.3): the coarse-to-fine controls that let a user choose how detailed a skeleton is.
//!
//! Four operations, each with one threshold in skeleton units (0 turns it off); a larger
//! threshold never gives more joints:
//!
//! - [`simplify_branches`] (ε_s): Douglas-Peucker along each branch drops sleeve joints;
//! - [`merge_junctions`] (ε_m): clusters of junction joints linked through at most ε_m of bone
//!   become one joint at their mean position;
//! - [`prune_branches`] (ε_t): branches from a junction to a terminal joint shorter than ε_t
//!   are removed;
//! - [`collapse_bones`] (ε_c): bones between two internal joints shorter than ε_c are
//!   collapsed into one joint at their midpoint.
//!
//! [`level_of_detail`] runs them in that order. Each works per branch, per part (the subtree of
//! a joint) or globally ([`LodScope`]). The root joint is never removed; surviving joints keep
//! their names, frames and degrees of freedom.

mod collapse;
mod error;
mod graph;
mod merge;
mod options;
mod prune;
mod rebuild;
mod simplify;

pub use collapse::collapse_bones;
pub use error::LodError;
pub use graph::{branches, degrees};
pub use merge::merge_junctions;
pub use options::{LodOptions, LodScope};
pub use prune::prune_branches;
pub use simplify::simplify_branches;

use crate::skeleton::Skeleton;

/// Applies the four operations of `options` in the order simplify, merge, prune, collapse.
///
/// # Errors
/// [`LodError`] for an invalid skeleton, a negative or non-finite threshold, or a scope naming
/// a joint the skeleton does not have.
pub fn level_of_detail(skeleton: &Skeleton, options: &LodOptions) -> Result<Skeleton, LodError> {
    options.validate()?;
    let s = simplify_branches(skeleton, options.simplify, &options.scope)?;
    let s = merge_junctions(&s, options.merge, &options.scope)?;
    let s = prune_branches(&s, options.prune, &options.scope)?;
    collapse_bones(&s, options.collapse, &options.scope)
}

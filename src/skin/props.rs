//! Held props (a sword, a staff: [`Prop`]) move rigidly with the joint that holds them. They
//! are left out of the voxels, so the weight field reaches them only through the air: a blade
//! hanging beside a leg would take the thigh's weights along its length and bend with the hip.
//! Each prop is bound wholly to one joint, as an artist parents a weapon to the hand bone: the
//! joint weighing most at its grip, the vertex nearest the figure's interior.

use crate::mesh::Mesh;
use crate::skeleton::JointId;
use crate::voxel::{Prop, Solid};

/// How far from a prop's vertices the interior is looked for, in voxels: a hand holding a
/// sword wraps its grip, which lies inside or beside the hand's voxels.
const GRIP_REACH: i32 = 4;

/// The squared distance, in voxels, from the voxel of `vertex` to the nearest interior voxel
/// of `solid` within [`GRIP_REACH`]; `None` when there is none.
fn to_interior(solid: &Solid, vertex: glam::DVec3) -> Option<i32> {
    let grid = &solid.grid;
    let v = grid.to_voxel(vertex);
    let at = [v.x.floor() as i64, v.y.floor() as i64, v.z.floor() as i64];
    let mut best: Option<i32> = None;
    for dz in -GRIP_REACH..=GRIP_REACH {
        for dy in -GRIP_REACH..=GRIP_REACH {
            for dx in -GRIP_REACH..=GRIP_REACH {
                let d = dx * dx + dy * dy + dz * dz;
                if best.is_some_and(|b| b <= d) || d > GRIP_REACH * GRIP_REACH {
                    continue;
                }
                let c = [at[0] + dx as i64, at[1] + dy as i64, at[2] + dz as i64];
                let inside = c
                    .iter()
                    .zip(grid.dims)
                    .all(|(&c, n)| c >= 0 && (c as usize) < n)
                    && solid.inside[grid.index(c.map(|c| c as usize))];
                if inside {
                    best = Some(d);
                }
            }
        }
    }
    best
}

/// Binds every vertex of each of `props` wholly to one joint (`weights`, per vertex of
/// `mesh`): the joint weighing most at the prop's grip, its vertex nearest the interior of
/// `solid` (the first such in vertex order). A prop none of whose vertices lies within [`GRIP_REACH`] voxels of the interior
/// keeps its weights. Returns how many props were bound.
pub(crate) fn bind_props(
    mesh: &Mesh,
    solid: &Solid,
    props: &[Prop],
    weights: &mut [Vec<(JointId, f64)>],
) -> usize {
    let mut bound = 0;
    for prop in props {
        let grip = prop
            .vertices
            .iter()
            .filter(|&&v| (v as usize) < mesh.positions.len() && (v as usize) < weights.len())
            .filter_map(|&v| Some((to_interior(solid, mesh.positions[v as usize])?, v)))
            .min();
        let Some((_, grip)) = grip else {
            continue;
        };
        let Some(&(joint, _)) = weights[grip as usize]
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))
        else {
            continue;
        };
        for &v in &prop.vertices {
            if let Some(w) = weights.get_mut(v as usize) {
                *w = vec![(joint, 1.0)];
            }
        }
        bound += 1;
    }
    bound
}

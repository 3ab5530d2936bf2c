//! Arms hanging against the body (the arms-down pose of scans and of idle bind poses).
//!
//! Where an arm touches the trunk the voxels merge them, and below the shoulder the level
//! graph sees one trunk with no arm leaving it. The mesh keeps them apart: a transverse slice
//! below the armpit cuts each arm's skin as a closed loop of its own beside the trunk's, even
//! where the two surfaces press into each other. [`hanging_arms`] finds the two arms as
//! mirrored runs of such loops down from the shoulders, and [`separate_arms`] cuts the voxels
//! between each arm and the body, so that labelling the cut solid again finds two arms hanging
//! from the shoulders (and the skin weights, which spread through the voxels, keep the arm's
//! skin off the flank).

use super::{Label, Labelling};
use crate::math::upper_median;
use crate::mesh::{point_in_polygon as contains, Mesh, PlaneSlicer, SliceLoop};
use crate::skeleton::JointId;
use crate::voxel::Solid;
use glam::DVec3;
use std::f64::consts::TAU;

/// An arm's loop is at most this fraction of the figure's height thick (perimeter over 2π):
/// an adult's upper arm is about 0.03, a cartoon's fat arm 0.08; the trunk's loop is thicker.
const ARM_MAX_RADIUS: f64 = 0.1;

/// ...and at least this fraction (a finger's loop, a strap, a seam's sliver are thinner).
const ARM_MIN_RADIUS: f64 = 0.01;

/// A hanging arm runs down the body for at least this fraction of the figure's height below
/// its armpit (upper arm, forearm and hand are about 0.36 of the height hanging; an arm that
/// lifts off the body after a short stretch is found by the level graph itself).
const ARM_MIN_RUN: f64 = 0.2;

/// Loops of the two sides are mirror images when their offsets from the median plane and
/// their forward offsets agree within this many times the larger loop's radius.
const MIRROR_RADII: f64 = 1.0;

/// Voxels within this many voxels beyond an arm's loop (around its centre) that are not in the
/// loop are cut: the seam between arm and flank, wide enough that no 26-neighbours remain
/// across it.
const CUT_MARGIN_VOXELS: f64 = 2.0;

/// The share of the head's vertices below the base of its skin that [`hanging_arms`] takes
/// for strays (the medial labels of a figure whose arms merge with its trunk give a few of the
/// hands' or the chest's vertices to the head).
const STRAY_SHARE: f64 = 0.05;

/// One transverse level of a hanging arm.
#[derive(Debug, Clone)]
struct ArmLevel {
    /// The arm's loops at this level in the slice plane's coordinates (left, forward): the arm,
    /// or the fingers of its hand.
    loops: Vec<Vec<(f64, f64)>>,
    /// The loops' centre (area-weighted) and the farthest loop point from it.
    centre: (f64, f64),
    reach: f64,
    /// The radius of a disc of the loops' area.
    radius: f64,
}

/// The two arms found hanging against the body ([`hanging_arms`]).
#[derive(Debug, Clone)]
pub struct HangingArms {
    /// Origin of the slice coordinates (the figure's heart) and the frame's up, left and
    /// forward.
    origin: DVec3,
    up: DVec3,
    left: DVec3,
    forward: DVec3,
    /// Height (along up from `origin`) of the first level and the spacing of the levels.
    top: f64,
    step: f64,
    /// Per side (left, right): the arm's levels from `top` down.
    arms: [Vec<ArmLevel>; 2],
}

impl HangingArms {
    /// How many transverse levels each arm was found on (left, right).
    pub fn levels(&self) -> [usize; 2] {
        [self.arms[0].len(), self.arms[1].len()]
    }

    /// The arms' median radius over their levels (of a disc of their loops' area), mesh units.
    pub fn radius(&self) -> f64 {
        upper_median(self.arms.iter().flatten().map(|l| l.radius).collect()).unwrap_or(0.0)
    }
}

/// Which skin a mesh vertex is in where the arms hang against the body
/// ([`HangingArms::skins`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArmSkin {
    /// Above the armpits.
    Apart,
    /// Below the armpits, on the body's skin (the flank, a hip, a skirt or thigh the hand lies
    /// on, the legs).
    Body,
    /// Below the armpits, on the skin of arm 0 (left) or 1 (right): the arm, its sleeve, the
    /// hand.
    Arm(usize),
}

/// A piece of skin in the arms' band is an arm's when at least this share of its vertices
/// lies within the arm's reach on their level.
const ARM_SKIN_SHARE: f64 = 0.5;

impl HangingArms {
    /// The skin each vertex of `mesh` is in: below the arms' first level (the armpits), the
    /// mesh's pieces of surface there (vertices joined by edges below it: the arm's tube and
    /// hand, the flank's, a sleeve's, a skirt's, the legs') are an arm's when at least
    /// `ARM_SKIN_SHARE` of their vertices lie within that arm's reach of its centre on their
    /// level, else the body's (a skirt the hands lay on, below their last level, is body too).
    /// On every level the arm's loop is apart from the trunk's, so no edge below the armpits
    /// joins them.
    pub fn skins(&self, mesh: &Mesh) -> Vec<ArmSkin> {
        let level = |p: DVec3| {
            let q = p - self.origin;
            let k = (self.top - q.dot(self.up)) / self.step;
            (k >= 0.0).then_some((k.round() as usize, (q.dot(self.left), q.dot(self.forward))))
        };
        let placed: Vec<Option<(usize, (f64, f64))>> =
            mesh.positions.iter().map(|&p| level(p)).collect();
        let mut sets = crate::mesh::DisjointSets::new(mesh.positions.len());
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if placed[a as usize].is_some() && placed[b as usize].is_some() {
                    sets.union(a, b);
                }
            }
        }
        let (piece, count) = sets.numbered();
        // Per piece: vertices, and those within each arm's reach.
        let mut tally = vec![(0usize, [0usize; 2]); count];
        for (v, place) in placed.iter().enumerate() {
            let Some((k, q)) = place else { continue };
            let t = &mut tally[piece[v] as usize];
            t.0 += 1;
            for (side, arm) in self.arms.iter().enumerate() {
                if arm.get(*k).is_some_and(|l| dist(*q, l.centre) <= l.reach) {
                    t.1[side] += 1;
                }
            }
        }
        placed
            .iter()
            .enumerate()
            .map(|(v, place)| {
                if place.is_none() {
                    return ArmSkin::Apart;
                }
                let (n, near) = tally[piece[v] as usize];
                let side = if near[0] >= near[1] { 0 } else { 1 };
                if near[side] as f64 >= ARM_SKIN_SHARE * n as f64 {
                    ArmSkin::Arm(side)
                } else {
                    ArmSkin::Body
                }
            })
            .collect()
    }
}

/// Keeps the skins of arms hanging against the body apart in `weights` (per vertex of `mesh`,
/// joint and weight): a vertex of an arm's skin ([`HangingArms::skins`]) keeps only the weights
/// of that arm's joints (`arm_joints[side][joint]`: the shoulder and the joints below it), a
/// vertex of the body's skin in the band only those of other joints; the weights left are
/// scaled to sum to one. A vertex left with none takes the mean of its mesh neighbours'
/// (repeated outwards from the vertices that have some), or keeps its own when none has.
/// The weight field spreads through the voxels, and where an arm presses into the flank the
/// flank's skin lies in the arm's voxels: raising the arm tore it. Returns how many vertices
/// changed.
pub fn keep_arm_skins_apart(
    mesh: &Mesh,
    skins: &[ArmSkin],
    arm_joints: [&[bool]; 2],
    weights: &mut [Vec<(JointId, f64)>],
) -> usize {
    let is_arm = |side: usize, j: JointId| arm_joints[side].get(j.0) == Some(&true);
    let mut changed = 0;
    let mut empty = vec![false; weights.len()];
    let mut before: Vec<(usize, Vec<(JointId, f64)>)> = Vec::new();
    for (v, w) in weights.iter_mut().enumerate() {
        let keep = |j| match skins.get(v) {
            Some(ArmSkin::Arm(side)) => is_arm(*side, j),
            Some(ArmSkin::Body) => !is_arm(0, j) && !is_arm(1, j),
            _ => true,
        };
        if w.iter().all(|&(j, _)| keep(j)) {
            continue;
        }
        changed += 1;
        w.retain(|&(j, _)| keep(j));
        let sum: f64 = w.iter().map(|(_, x)| x).sum();
        if sum > 0.0 {
            w.iter_mut().for_each(|(_, x)| *x /= sum);
        } else {
            before.push((v, std::mem::take(w)));
            empty[v] = true;
        }
    }
    if before.is_empty() {
        return changed;
    }
    // Vertices left without weights take their neighbours', from the filled ones outwards.
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); weights.len()];
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            if a < weights.len() && b < weights.len() {
                neighbours[a].push(b as u32);
                neighbours[b].push(a as u32);
            }
        }
    }
    loop {
        let mut filled = Vec::new();
        for v in (0..weights.len()).filter(|&v| empty[v]) {
            let mut mean: Vec<(JointId, f64)> = Vec::new();
            let mut n = 0;
            for &u in &neighbours[v] {
                if empty[u as usize] {
                    continue;
                }
                n += 1;
                for &(j, x) in &weights[u as usize] {
                    match mean.iter_mut().find(|(k, _)| *k == j) {
                        Some(m) => m.1 += x,
                        None => mean.push((j, x)),
                    }
                }
            }
            if n > 0 {
                mean.iter_mut().for_each(|(_, x)| *x /= n as f64);
                filled.push((v, mean));
            }
        }
        if filled.is_empty() {
            break;
        }
        for (v, mean) in filled {
            weights[v] = mean;
            empty[v] = false;
        }
    }
    for (v, w) in before {
        if empty[v] {
            weights[v] = w;
        }
    }
    changed
}

/// A closed loop's points in the slice coordinates, its area-weighted centre, area and
/// radius (perimeter over 2π).
struct Flat {
    points: Vec<(f64, f64)>,
    centre: (f64, f64),
    area: f64,
    radius: f64,
}

fn flat(l: &SliceLoop, to2d: impl Fn(DVec3) -> (f64, f64)) -> Option<Flat> {
    if !l.closed || l.points.len() < 3 {
        return None;
    }
    let points: Vec<(f64, f64)> = l.points.iter().map(|&p| to2d(p)).collect();
    let (mut a, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for (i, &(x0, y0)) in points.iter().enumerate() {
        let (x1, y1) = points[(i + 1) % points.len()];
        let cross = x0 * y1 - x1 * y0;
        a += cross;
        cx += (x0 + x1) * cross;
        cy += (y0 + y1) * cross;
    }
    if a.abs() < 1e-18 {
        return None;
    }
    let centre = (cx / (3.0 * a), cy / (3.0 * a));
    Some(Flat {
        points,
        centre,
        area: 0.5 * a.abs(),
        radius: l.perimeter() / TAU,
    })
}

fn dist((ax, ay): (f64, f64), (bx, by): (f64, f64)) -> f64 {
    (ax - bx).hypot(ay - by)
}

/// The arms of a human-like figure whose labelling found none but a head and legs, when they
/// hang against its sides: on transverse slices of `mesh` (along the labelling's up, one voxel
/// apart, from the head's base down), closed loops beside the trunk's loop (their centres
/// outside it), `ARM_MIN_RADIUS`–`ARM_MAX_RADIUS` of the height thick, mirrored across the
/// median plane (`MIRROR_RADII`), first met above the figure's heart and followed down level
/// by level (each level's loops within the previous level's reach of its centre: the arm, then
/// the fingers) for at least `ARM_MIN_RUN` of the height on both sides. `None` otherwise.
pub fn hanging_arms(mesh: &Mesh, labelling: &Labelling) -> Option<HangingArms> {
    if labelling.figure != super::FigureClass::HumanLike
        || labelling.count(Label::Arm) > 0
        || labelling.count(Label::Head) == 0
        || labelling.count(Label::Leg) < 2
    {
        return None;
    }
    let frame = labelling.frame;
    let (up, left, forward) = (frame.up, frame.left, frame.forward);
    let grid = &labelling.grid;
    let origin = grid.centre(grid.coords(*labelling.dms_voxels.get(labelling.level_graph.heart)?));
    let (low, high) = mesh
        .positions
        .iter()
        .map(|p| (*p - origin).dot(up))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| {
            (lo.min(h), hi.max(h))
        });
    let height = high - low;
    let step = labelling.grid.voxel_size;
    if height.is_nan() || height <= 0.0 || step.is_nan() || step <= 0.0 {
        return None;
    }
    // Down from the base of the head's skin (the neck's, the neck being the head's part),
    // stray vertices aside (the lowest `STRAY_SHARE` of the head's), or from where the head
    // leaves the trunk when that is higher.
    let head = *labelling.find(Label::Head).first()?;
    let mut heights: Vec<f64> = (labelling.mesh_parts.iter().zip(&mesh.positions))
        .filter(|(&part, _)| part as usize == head)
        .map(|(_, p)| (*p - origin).dot(up))
        .collect();
    heights.sort_by(f64::total_cmp);
    let base = heights
        .get((STRAY_SHARE * heights.len() as f64) as usize)
        .copied()
        .unwrap_or(f64::NEG_INFINITY);
    let top = base
        .max((labelling.parts[head].attachment - origin).dot(up))
        .min(high);
    let levels = ((top - low) / step).floor() as usize;
    let slicer = PlaneSlicer::new(mesh, up);
    let to2d = |p: DVec3| ((p - origin).dot(left), (p - origin).dot(forward));
    let (min_r, max_r) = (ARM_MIN_RADIUS * height, ARM_MAX_RADIUS * height);

    // Every level's closed loops and its trunk loop (the largest around the figure's axis,
    // the heart's vertical).
    let slices: Vec<(Vec<Flat>, Option<usize>)> = (0..levels)
        .map(|k| {
            let loops: Vec<Flat> = slicer
                .slice(origin + up * (top - k as f64 * step))
                .iter()
                .filter_map(|l| flat(l, to2d))
                .collect();
            let trunk = (0..loops.len())
                .filter(|&i| contains(&loops[i].points, (0.0, 0.0)))
                .max_by(|&a, &b| loops[a].area.total_cmp(&loops[b].area));
            (loops, trunk)
        })
        .collect();
    let outside_trunk = |k: usize, f: &Flat| {
        let (loops, trunk) = &slices[k];
        trunk.is_none_or(|t| !contains(&loops[t].points, f.centre))
    };
    // A start: a level above the heart with a mirrored pair of arm-thick loops beside the
    // trunk (the first below the armpits, or hair falling on the shoulders, whose run ends
    // soon: the next start is tried below it).
    for start in 0..levels {
        if top - start as f64 * step < 0.0 {
            break;
        }
        let (loops, trunk) = &slices[start];
        if trunk.is_none() {
            continue;
        }
        let side_of = |f: &Flat, s: f64| {
            f.centre.0 * s > 0.0
                && f.radius >= min_r
                && f.radius <= max_r
                && outside_trunk(start, f)
                && !contains(&f.points, (0.0, 0.0))
        };
        let pair = loops.iter().filter(|f| side_of(f, 1.0)).find_map(|l| {
            loops
                .iter()
                .filter(|f| side_of(f, -1.0))
                .find(|r| {
                    let tol = MIRROR_RADII * l.radius.max(r.radius);
                    (l.centre.0 + r.centre.0).abs() <= tol && (l.centre.1 - r.centre.1).abs() <= tol
                })
                .map(|r| (l, r))
        });
        let Some((l, r)) = pair else { continue };
        let mut arms = [vec![level_of(&[l])], vec![level_of(&[r])]];
        // Each side goes on down while loops lie within its last level's reach of its centre.
        for (k, (loops, _)) in slices.iter().enumerate().skip(start + 1) {
            let mut going = false;
            for arm in arms.iter_mut() {
                if arm.len() + start != k {
                    continue;
                }
                if let Some(next) = follow(loops, &arm[arm.len() - 1], step, max_r) {
                    arm.push(next);
                    going = true;
                }
            }
            if !going {
                break;
            }
        }
        let run = |arm: &Vec<ArmLevel>| arm.len() as f64 * step;
        if run(&arms[0]) < ARM_MIN_RUN * height || run(&arms[1]) < ARM_MIN_RUN * height {
            continue;
        }
        // And up from the start while both sides' loops go on: to the armpits, where the arm's
        // loop joins the trunk's.
        let mut first = top - start as f64 * step;
        loop {
            let h = first + step;
            if h > high {
                break;
            }
            let loops: Vec<Flat> = slicer
                .slice(origin + up * h)
                .iter()
                .filter_map(|l| flat(l, to2d))
                .collect();
            let (Some(l), Some(r)) = (
                follow(&loops, &arms[0][0], step, max_r),
                follow(&loops, &arms[1][0], step, max_r),
            ) else {
                break;
            };
            arms[0].insert(0, l);
            arms[1].insert(0, r);
            first = h;
        }
        return Some(HangingArms {
            origin,
            up,
            left,
            forward,
            top: first,
            step,
            arms,
        });
    }
    None
}

/// The arm's level among `loops` next to its level `last`: the loops within `last`'s reach
/// (at least two `step`s) of its centre, on its side of the median plane, at most `max_r`
/// thick and not around the figure's axis (the trunk's); `None` when there are none (the arm
/// ends, or joins the trunk at the armpit).
fn follow(loops: &[Flat], last: &ArmLevel, step: f64, max_r: f64) -> Option<ArmLevel> {
    let near: Vec<&Flat> = loops
        .iter()
        .filter(|f| {
            dist(f.centre, last.centre) <= last.reach.max(2.0 * step)
                && f.radius <= max_r
                && !contains(&f.points, (0.0, 0.0))
                && f.centre.0 * last.centre.0 > 0.0
        })
        .collect();
    (!near.is_empty()).then(|| level_of(&near))
}

/// One arm level from its loops (`loops`, one or more: the arm, the fingers).
fn level_of(loops: &[&Flat]) -> ArmLevel {
    let area: f64 = loops.iter().map(|f| f.area).sum();
    let centre = if area > 0.0 {
        let x = loops.iter().map(|f| f.centre.0 * f.area).sum::<f64>() / area;
        let y = loops.iter().map(|f| f.centre.1 * f.area).sum::<f64>() / area;
        (x, y)
    } else {
        loops[0].centre
    };
    let reach = loops
        .iter()
        .flat_map(|f| f.points.iter())
        .map(|&p| dist(p, centre))
        .fold(0.0, f64::max);
    ArmLevel {
        loops: loops.iter().map(|f| f.points.clone()).collect(),
        centre,
        reach,
        radius: (area / std::f64::consts::PI).sqrt(),
    }
}

/// `solid` with the voxels between each arm of `arms` and the body cut: on every level of an
/// arm, the inside voxels within `CUT_MARGIN_VOXELS` beyond the arm's reach of its centre
/// that are not inside its loops (or are inside the trunk's loop too, where the surfaces press
/// into each other), then the arm's voxels still touching (26-neighbours) an inside voxel that
/// is not the arm's. Returns the cut solid and how many voxels were cut.
pub fn separate_arms(solid: &Solid, arms: &HangingArms) -> (Solid, usize) {
    let grid = &solid.grid;
    let margin = CUT_MARGIN_VOXELS * grid.voxel_size;
    // 0: untouched, 1/2: the left/right arm, 3: cut.
    let mut mark = vec![0u8; solid.inside.len()];
    for (i, inside) in solid.inside.iter().enumerate() {
        if !inside {
            continue;
        }
        let p = grid.centre(grid.coords(i)) - arms.origin;
        let k = ((arms.top - p.dot(arms.up)) / arms.step).round();
        if k < 0.0 {
            continue;
        }
        let k = k as usize;
        let q = (p.dot(arms.left), p.dot(arms.forward));
        for (side, arm) in arms.arms.iter().enumerate() {
            let Some(level) = arm.get(k) else { continue };
            if dist(q, level.centre) > level.reach + margin {
                continue;
            }
            let in_arm = level.loops.iter().any(|l| contains(l, q));
            mark[i] = if in_arm { side as u8 + 1 } else { 3 };
        }
    }
    // The arm's voxels that still touch the body below its first level (above it, the arm
    // hangs from the shoulder).
    let below_top = |j: usize| {
        let p = grid.centre(grid.coords(j)) - arms.origin;
        (arms.top - p.dot(arms.up)) / arms.step >= 0.5
    };
    let dims = grid.dims;
    let mut seam = Vec::new();
    for (i, &m) in mark.iter().enumerate() {
        if m != 1 && m != 2 {
            continue;
        }
        let [x, y, z] = grid.coords(i);
        let touches = (-1i64..=1).any(|dz| {
            (-1i64..=1).any(|dy| {
                (-1i64..=1).any(|dx| {
                    let (nx, ny, nz) = (x as i64 + dx, y as i64 + dy, z as i64 + dz);
                    if nx < 0
                        || ny < 0
                        || nz < 0
                        || nx >= dims[0] as i64
                        || ny >= dims[1] as i64
                        || nz >= dims[2] as i64
                    {
                        return false;
                    }
                    let j = grid.index([nx as usize, ny as usize, nz as usize]);
                    solid.inside[j] && mark[j] != m && mark[j] != 3 && below_top(j)
                })
            })
        });
        if touches {
            seam.push(i);
        }
    }
    for i in seam {
        mark[i] = 3;
    }
    let mut cut = solid.clone();
    let mut count = 0;
    for (inside, &m) in cut.inside.iter_mut().zip(&mark) {
        if m == 3 && *inside {
            *inside = false;
            count += 1;
        }
    }
    cut.report.interior_voxels = cut.report.interior_voxels.saturating_sub(count);
    (cut, count)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voxel::{Grid, VoxelReport};

    /// A unit-voxel solid: a trunk x 2..=9, an arm x 10..=12 pressed against its side from
    /// y 2 to 17, both joined above y 17 (the shoulder), z 2..=6; and one arm level per voxel
    /// layer y 2..=17 (the arm's square loop around x 9.6..12.9).
    fn scene() -> (Solid, HangingArms) {
        let grid = Grid {
            dims: [16, 24, 9],
            origin: DVec3::ZERO,
            voxel_size: 1.0,
        };
        let mut inside = vec![false; grid.len()];
        for z in 2..=6 {
            for y in 2..=20 {
                for x in 2..=12 {
                    inside[grid.index([x, y, z])] = true;
                }
            }
        }
        let solid = Solid {
            grid,
            inside,
            surface: vec![false; grid.len()],
            report: VoxelReport::default(),
        };
        let square = vec![(9.6, 1.9), (12.9, 1.9), (12.9, 7.1), (9.6, 7.1)];
        let level = ArmLevel {
            loops: vec![square],
            centre: (11.25, 4.5),
            reach: 3.0,
            radius: 2.0,
        };
        // Levels from y = 17.5 (the top layer's centre) down to y = 2.5.
        let arms = HangingArms {
            origin: DVec3::ZERO,
            up: DVec3::Y,
            left: DVec3::X,
            forward: DVec3::Z,
            top: 17.5,
            step: 1.0,
            arms: [vec![level; 16], Vec::new()],
        };
        (solid, arms)
    }

    #[test]
    fn an_arm_pressed_against_the_trunk_is_cut_free_below_its_shoulder_only() {
        let (solid, arms) = scene();
        let (cut, count) = separate_arms(&solid, &arms);
        assert!(count > 0);
        let grid = cut.grid;
        let at = |x: usize, y: usize, z: usize| cut.inside[grid.index([x, y, z])];
        // The arm keeps a core on every level.
        for y in 2..=17 {
            assert!(at(11, y, 4), "arm core cut at y {y}");
        }
        // Below the shoulder no arm voxel (x >= 10) touches a trunk voxel (x <= 9), even
        // diagonally.
        for z in 0..grid.dims[2] {
            for y in 0..=17 {
                for x in 10..=12 {
                    if !at(x, y, z) {
                        continue;
                    }
                    for (dx, dy, dz) in (-1i64..=1).flat_map(|a| {
                        (-1i64..=1).flat_map(move |b| (-1i64..=1).map(move |c| (a, b, c)))
                    }) {
                        let (nx, ny, nz) = (x as i64 + dx, y as i64 + dy, z as i64 + dz);
                        if nx < 0 || ny < 0 || nz < 0 || ny > 17 || nz >= grid.dims[2] as i64 {
                            continue;
                        }
                        let (nx, ny, nz) = (nx as usize, ny as usize, nz as usize);
                        assert!(
                            !(nx <= 9 && at(nx, ny, nz)),
                            "arm voxel ({x}, {y}, {z}) touches trunk voxel ({nx}, {ny}, {nz})"
                        );
                    }
                }
            }
        }
        // Above its first level the arm still joins the body: the shoulder is untouched.
        for y in 18..=20 {
            for x in 2..=12 {
                assert!(at(x, y, 4), "shoulder voxel ({x}, {y}) cut");
            }
        }
        // The trunk's core stays.
        for y in 2..=20 {
            assert!(at(5, y, 4));
        }
    }

    #[test]
    fn an_arms_skin_keeps_its_arms_weights_and_the_body_none_of_them() {
        use crate::skeleton::JointId;
        // Two triangles: 0-1-2 on the arm, 3-4-5 on the body; vertex 6 above the armpit.
        let p = |x: f64| DVec3::new(x, 0.0, 0.0);
        let mesh = Mesh {
            positions: vec![p(0.0), p(1.0), p(2.0), p(3.0), p(4.0), p(5.0), p(6.0)],
            triangles: vec![[0, 1, 2], [3, 4, 5]],
        };
        let skins = [
            ArmSkin::Arm(0),
            ArmSkin::Arm(0),
            ArmSkin::Arm(0),
            ArmSkin::Body,
            ArmSkin::Body,
            ArmSkin::Body,
            ArmSkin::Apart,
        ];
        // Joint 1 is the left arm's, joint 0 the body's.
        let (body, arm) = (JointId(0), JointId(1));
        let left = [false, true];
        let right = [false, false];
        let mut weights = vec![
            vec![(arm, 0.5), (body, 0.5)],
            vec![(arm, 1.0)],
            vec![(arm, 1.0)],
            vec![(arm, 1.0)],
            vec![(body, 1.0)],
            vec![(body, 0.8), (arm, 0.2)],
            vec![(arm, 0.3), (body, 0.7)],
        ];
        let changed = keep_arm_skins_apart(&mesh, &skins, [&left, &right], &mut weights);
        assert_eq!(changed, 3);
        assert_eq!(weights[0], vec![(arm, 1.0)]);
        // The flank's vertex weighted wholly to the arm takes its neighbours' weights.
        assert_eq!(weights[3], vec![(body, 1.0)]);
        assert_eq!(weights[5], vec![(body, 1.0)]);
        assert_eq!(weights[6], vec![(arm, 0.3), (body, 0.7)]);
    }
}

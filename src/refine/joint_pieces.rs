//! Joints of jointed figures: where a limb is built of separate rigid pieces (a robot, an
//! artist's mannequin), the modeller puts a round piece, a ball or a short round cylinder, at
//! each joint for the neighbouring pieces to turn about, and its centre is the joint. The
//! slices of such a limb meet the pieces' overlaps and gaps instead of a tapering body, so the
//! limb phases' narrowings and bends miss; the ball says where the joint is outright.
//!
//! A figure made of one closed surface (a scanned or sculpted body, a MakeHuman mesh) has no
//! such piece: its separate shells are eyes, teeth and trims, which lie nearer other joints or
//! are far smaller than a limb is thick, and this phase leaves it alone.

use super::driver::Found;
use crate::mesh::Mesh;
use crate::skeleton::{Canonical, Side};
use glam::DVec3;
use nalgebra::{Matrix4, Vector4};

/// A separate mesh piece whose vertices lie on a sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointBall {
    /// The fitted sphere's centre, mesh frame.
    pub centre: DVec3,
    /// The fitted sphere's radius, mesh units.
    pub radius: f64,
    /// The root-mean-square distance of the piece's vertices from the sphere, over `radius`
    /// (0 for a UV sphere's vertices).
    pub roundness: f64,
}

/// The most a ball piece's vertices may stray from its fitted sphere (root mean square, as a
/// fraction of its radius). A UV sphere's vertices lie on the sphere (0); a short capped
/// cylinder about as long as wide strays by under a tenth; a cube's corners lie on a sphere
/// too, and a small cube between two limb pieces is a joint piece as well.
const BALL_ROUNDNESS: f64 = 0.1;

/// A ball piece's smallest bounding-box side over its largest, at least: a ring or a flat disc
/// (a wrist's flange, a collar) has coplanar vertices, which many spheres fit.
const BALL_MIN_ASPECT: f64 = 0.5;

/// A joint ball's radius as a fraction of its limb bone's length, from–to. A limb is about a
/// fifth to a third as thick as its bone is long (human wrists to knees), and a joint piece is
/// as thick as the limb, or a little less where the limb pieces overlap it; rivets, buttons
/// and knuckles are far smaller, a torso far larger.
const BALL_RADIUS_PER_BONE: (f64, f64) = (0.08, 0.35);

/// A limb joint's canonical key for a side.
type JointOfSide = fn(Side) -> Canonical;

/// The limb joints this phase places, each with the joint whose distance gives its limb bone
/// (for the middle joints, half the span between their neighbours is used instead).
const LIMB_CHAINS: [[JointOfSide; 3]; 2] = [
    [Canonical::Shoulder, Canonical::Elbow, Canonical::Wrist],
    [Canonical::Hip, Canonical::Knee, Canonical::Ankle],
];

/// The separate pieces of `mesh` (triangles connected through shared vertices) whose vertices
/// lie on a sphere: at least 8 vertices within `BALL_ROUNDNESS` of the least-squares
/// sphere, a bounding box at least `BALL_MIN_ASPECT` as deep as long, and the sphere's
/// centre inside that box: at least about half the sphere shows (a ball half hidden in the
/// torso still does), where a shallow cap (a domed button, a shoulder pad's curve) is part of a
/// much larger sphere centred beyond it. A short round cylinder counts too: its rims lie on
/// one sphere about its centre. The figure's main piece is never round enough (limbs stick out
/// of it).
pub fn joint_balls(mesh: &Mesh) -> Vec<JointBall> {
    let (labels, count) = mesh.triangle_components();
    // Components join triangles through shared vertices, so each used vertex lies in one
    // piece: the piece of any triangle using it. Each piece's vertices, ascending.
    let mut vertex_piece = vec![u32::MAX; mesh.positions.len()];
    for (t, &label) in labels.iter().enumerate() {
        for v in mesh.triangles[t] {
            vertex_piece[v as usize] = label;
        }
    }
    let mut pieces: Vec<Vec<u32>> = vec![Vec::new(); count];
    for (v, &label) in vertex_piece.iter().enumerate() {
        if label != u32::MAX {
            pieces[label as usize].push(v as u32);
        }
    }
    pieces
        .into_iter()
        .filter_map(|indices| {
            let points: Vec<DVec3> = indices
                .iter()
                .map(|&v| mesh.positions[v as usize])
                .collect();
            ball(&points)
        })
        .collect()
}

/// The sphere through `points` when they make a ball piece (see [`joint_balls`]).
fn ball(points: &[DVec3]) -> Option<JointBall> {
    if points.len() < 8 {
        return None;
    }
    let lo = points.iter().fold(DVec3::INFINITY, |a, &p| a.min(p));
    let hi = points.iter().fold(DVec3::NEG_INFINITY, |a, &p| a.max(p));
    let extent = hi - lo;
    let flat = extent.min_element() < BALL_MIN_ASPECT * extent.max_element();
    if flat || !extent.is_finite() {
        return None;
    }
    let (centre, radius) = sphere_fit(points, 0.5 * (lo + hi))?;
    let rms = (points
        .iter()
        .map(|&p| (p.distance(centre) - radius).powi(2))
        .sum::<f64>()
        / points.len() as f64)
        .sqrt();
    let inside = centre.cmpge(lo).all() && centre.cmple(hi).all();
    (rms <= BALL_ROUNDNESS * radius && inside).then_some(JointBall {
        centre,
        radius,
        roundness: rms / radius,
    })
}

/// The least-squares (algebraic) sphere through `points`: |p − c|² = r² is linear in c and
/// r² − |c|² (Pratt 1987). Solved about `origin` (a point near them) so that far-off
/// coordinates do not cost precision. `None` for coplanar or collinear points.
fn sphere_fit(points: &[DVec3], origin: DVec3) -> Option<(DVec3, f64)> {
    let mut normal = Matrix4::<f64>::zeros();
    let mut rhs = Vector4::<f64>::zeros();
    for &p in points {
        let q = p - origin;
        let row = Vector4::new(2.0 * q.x, 2.0 * q.y, 2.0 * q.z, 1.0);
        normal += row * row.transpose();
        rhs += row * q.length_squared();
    }
    let s = normal.lu().solve(&rhs)?;
    let c = DVec3::new(s[0], s[1], s[2]);
    let r2 = s[3] + c.length_squared();
    (r2 > 0.0 && r2.is_finite()).then(|| (origin + c, r2.sqrt()))
}

/// Moves each limb joint of `joints` (current estimates: refined where found, else rough) to
/// the centre of a joint ball that belongs to it, and records it in `found`; returns the keys
/// placed. A ball belongs to joint J when its centre lies nearer J than any other estimate in
/// `joints`, within half of J's limb bone of it, and its radius is a plausible limb thickness
/// for that bone ([`BALL_RADIUS_PER_BONE`]). J's limb bone is the distance from its chain
/// neighbour to J or to the ball, the longer, for the shoulder, wrist, hip and ankle (upper
/// arm, forearm, thigh, shin) and half the span between its neighbours for the elbow and knee. Of several such balls the roundest
/// is taken (the piece the limb turns about is modelled as a sphere; a pad or socket beside it
/// is only roughly round), the nearest among equally round ones.
///
/// A joint placed on its ball is the estimate for its neighbours from then on, and the joints
/// left are tried again until no more are placed: a badly placed elbow makes the upper arm
/// look too short for the shoulder's ball until the elbow is on its own.
pub(super) fn place_on_balls(
    balls: &[JointBall],
    joints: &Found,
    found: &mut Found,
) -> Vec<Canonical> {
    let mut current = joints.clone();
    let mut placed = Vec::new();
    loop {
        let before = placed.len();
        for side in Side::BOTH {
            for chain in LIMB_CHAINS {
                let keys = chain.map(|k| k(side));
                for i in 0..keys.len() {
                    if placed.contains(&keys[i]) {
                        continue;
                    }
                    if let Some(b) = ball_of(balls, &current, keys, i) {
                        current.insert(keys[i], b.centre);
                        found.insert(keys[i], b.centre);
                        placed.push(keys[i]);
                    }
                }
            }
        }
        if placed.len() == before {
            return placed;
        }
    }
}

/// Two balls whose roundness (root-mean-square distance from their spheres over the radius)
/// differs by less than this are equally round.
const ROUNDNESS_TIE: f64 = 0.02;

/// The ball of the `i`th joint of the limb chain `keys` among `balls`, by the estimates
/// `joints` (see [`place_on_balls`]).
fn ball_of<'a>(
    balls: &'a [JointBall],
    joints: &Found,
    keys: [Canonical; 3],
    i: usize,
) -> Option<&'a JointBall> {
    let at = |i: usize| joints.get(&keys[i]).copied();
    let key = keys[i];
    let p = at(i)?;
    // The limb bone by the estimates, and, for a chain end, by the ball itself: a joint
    // estimate that fell short along the limb shortens its bone as much as it misses the ball.
    let (neighbour, estimated) = match i {
        1 => (None, at(0).zip(at(2)).map(|(a, b)| 0.5 * a.distance(b))?),
        0 => (at(1), p.distance(at(1)?)),
        _ => (at(i - 1), p.distance(at(i - 1)?)),
    };
    let bone = |b: &JointBall| neighbour.map_or(estimated, |q| estimated.max(b.centre.distance(q)));
    let nearest_is_key = |c: DVec3| {
        let d = c.distance(p);
        joints.iter().all(|(k, q)| *k == key || q.distance(c) > d)
    };
    let candidates: Vec<&JointBall> = balls
        .iter()
        .filter(|b| {
            let bone = bone(b);
            bone > 0.0
                && b.centre.distance(p) <= 0.5 * bone
                && (BALL_RADIUS_PER_BONE.0 * bone..=BALL_RADIUS_PER_BONE.1 * bone)
                    .contains(&b.radius)
                && nearest_is_key(b.centre)
        })
        .collect();
    let roundest = candidates
        .iter()
        .map(|b| b.roundness)
        .min_by(f64::total_cmp)?;
    candidates
        .into_iter()
        .filter(|b| b.roundness <= roundest + ROUNDNESS_TIE)
        .min_by(|a, b| a.centre.distance(p).total_cmp(&b.centre.distance(p)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with(meshes: &[Mesh]) -> Mesh {
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for m in meshes {
            let base = positions.len() as u32;
            positions.extend_from_slice(&m.positions);
            triangles.extend(m.triangles.iter().map(|t| t.map(|v| v + base)));
        }
        Mesh::new(positions, triangles).unwrap()
    }

    #[test]
    fn a_uv_sphere_piece_is_a_ball_at_its_centre() {
        let c = DVec3::new(0.3, 1.0, -0.1);
        let mesh = with(&[
            Mesh::uv_sphere(c, 0.04, 8, 12),
            Mesh::cuboid(DVec3::new(-0.2, 0.0, -0.1), DVec3::new(0.2, 1.2, 0.1)),
        ]);
        let balls = joint_balls(&mesh);
        assert_eq!(balls.len(), 1, "{balls:?}");
        assert!(balls[0].centre.distance(c) < 1e-9);
        assert!((balls[0].radius - 0.04).abs() < 1e-9);
    }

    #[test]
    fn a_half_hidden_ball_keeps_its_centre_and_rods_discs_and_caps_are_not_balls() {
        // A ball cut by a plane beside its centre (the rest inside the torso), a long rod, a
        // flat disc and a shallow cap of a large sphere (a pad's dome).
        let c = DVec3::new(0.12, 1.0, 0.0);
        let full = Mesh::uv_sphere(c, 0.04, 10, 16);
        let cut = Mesh::new(
            full.positions.clone(),
            full.triangles
                .iter()
                .copied()
                .filter(|t| {
                    t.iter()
                        .all(|&v| full.positions[v as usize].x >= c.x - 0.015)
                })
                .collect(),
        )
        .unwrap()
        .compacted();
        let rod = Mesh::capsule(DVec3::new(0.5, 1.0, 0.0), 0.03, 0.4, 8, 12);
        let disc = Mesh::cuboid(DVec3::new(0.8, 0.96, -0.04), DVec3::new(0.805, 1.04, 0.04));
        let big = Mesh::uv_sphere(DVec3::new(0.0, 0.3, 0.0), 0.3, 24, 24);
        let cap = Mesh::new(
            big.positions.clone(),
            big.triangles
                .iter()
                .copied()
                .filter(|t| t.iter().all(|&v| big.positions[v as usize].y >= 0.45))
                .collect(),
        )
        .unwrap()
        .compacted();
        let balls = joint_balls(&with(&[cut, rod, disc, cap]));
        assert_eq!(balls.len(), 1, "{balls:?}");
        assert!(balls[0].centre.distance(c) < 1e-9);
    }

    #[test]
    fn a_short_round_cylinder_is_a_ball_at_its_middle() {
        // Its rims lie on the sphere of radius √(a² + b²) about its centre.
        let c = DVec3::new(0.36, 1.0, 0.0);
        let cylinder = Mesh::lathe(c, 0.03, &[(0.03, 0.03), (0.03, -0.03)], -0.03, 12);
        let balls = joint_balls(&cylinder);
        assert_eq!(balls.len(), 1, "{balls:?}");
        assert!(balls[0].centre.distance(c) < 1e-6, "{balls:?}");
    }

    #[test]
    fn a_ball_moves_its_own_joint_only() {
        let side = Side::Left;
        let joints: Found = [
            (Canonical::Shoulder(side), DVec3::new(0.07, 1.06, 0.04)),
            (Canonical::Elbow(side), DVec3::new(0.35, 1.0, 0.0)),
            (Canonical::Wrist(side), DVec3::new(0.57, 1.0, 0.0)),
            (Canonical::Neck, DVec3::new(0.0, 1.1, 0.0)),
        ]
        .into_iter()
        .collect();
        let ball = |x: f64, y: f64, radius: f64, roundness: f64| JointBall {
            centre: DVec3::new(x, y, 0.0),
            radius,
            roundness,
        };
        let shoulder_ball = ball(0.12, 1.0, 0.04, 0.0);
        let button = ball(0.34, 1.02, 0.008, 0.0);
        let torso_sized = ball(0.6, 1.0, 0.2, 0.0);
        let mut found = Found::new();
        let placed = place_on_balls(&[shoulder_ball, button, torso_sized], &joints, &mut found);
        assert_eq!(placed, vec![Canonical::Shoulder(side)]);
        assert_eq!(found[&Canonical::Shoulder(side)], shoulder_ball.centre);
    }

    #[test]
    fn the_roundest_ball_wins_and_a_placed_elbow_lets_the_shoulder_find_its_ball() {
        // The elbow's estimate sits a third of the way down the upper arm: the upper arm looks
        // too short for the shoulder's ball until the elbow is on its own ball; beside the hip
        // ball lies a rougher round socket nearer the hip's estimate.
        let side = Side::Right;
        let joints: Found = [
            (Canonical::Shoulder(side), DVec3::new(-0.067, 1.068, 0.063)),
            (Canonical::Elbow(side), DVec3::new(-0.24, 1.0, 0.0)),
            (Canonical::Wrist(side), DVec3::new(-0.6, 1.0, 0.0)),
            (Canonical::Hip(side), DVec3::new(-0.073, 0.714, 0.082)),
            (Canonical::Knee(side), DVec3::new(-0.126, 0.36, 0.1)),
        ]
        .into_iter()
        .collect();
        let ball = |centre: DVec3, radius: f64, roundness: f64| JointBall {
            centre,
            radius,
            roundness,
        };
        let shoulder = ball(DVec3::new(-0.127, 1.006, 0.004), 0.041, 0.0);
        let elbow = ball(DVec3::new(-0.356, 1.0, 0.0), 0.044, 0.0);
        let hip = ball(DVec3::new(-0.118, 0.682, 0.072), 0.038, 0.0);
        let socket = ball(DVec3::new(-0.059, 0.7, 0.083), 0.054, 0.07);
        let mut found = Found::new();
        place_on_balls(&[shoulder, elbow, hip, socket], &joints, &mut found);
        assert_eq!(found.get(&Canonical::Elbow(side)), Some(&elbow.centre));
        assert_eq!(
            found.get(&Canonical::Shoulder(side)),
            Some(&shoulder.centre)
        );
        assert_eq!(found.get(&Canonical::Hip(side)), Some(&hip.centre));
    }
}

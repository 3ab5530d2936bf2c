//! The spine curve and its joints (seed 004, 3.2): control points from the torso's
//! characteristic points, a chordal Catmull-Rom curve through them, and the 24 inter-vertebral
//! joints plus the sacrum centre spaced by minimising the length deviation of adjacent
//! segments (equation 1) with argmin.

use super::frame::BodyFrame;
use super::torso::TorsoPoints;
use super::RefineOptions;
use glam::DVec3;

/// Names of the spine joints from the top: the joint below each vertebra (`C1` joins C1 and
/// C2, ..., `L5` joins L5 and the sacrum), then the sacrum centre.
pub const SPINE_JOINTS: [&str; 25] = crate::skeleton::canonical::VERTEBRA_NAMES;

/// Index in the joint sequence (0 = head joint, then [`SPINE_JOINTS`]) of the joints fixed to
/// control points: head, C7/T1, T6/T7, L3/L4, sacrum centre.
const FIXED: [usize; 5] = [0, 7, 13, 22, 25];

/// The spine: its control points, the curve and the joints.
#[derive(Debug, Clone, PartialEq)]
pub struct Spine {
    /// Control points from the top: head joint, C7/T1, T6/T7, L3/L4, sacrum centre, lower end.
    pub control: Vec<DVec3>,
    /// The joints named by [`SPINE_JOINTS`], top first.
    pub joints: Vec<(String, DVec3)>,
}

impl Spine {
    /// The joint called `name` (a [`SPINE_JOINTS`] entry).
    pub fn joint(&self, name: &str) -> Option<DVec3> {
        self.joints.iter().find(|(n, _)| n == name).map(|(_, p)| *p)
    }
}

/// Builds the spine from the head joint and the torso points. The depth offsets move the back
/// points into the body along `frame.forward`; every point is kept in the median plane through
/// `centre`. `None` when the control points are not ordered top to bottom.
pub fn spine(
    frame: &BodyFrame,
    centre: DVec3,
    head: DVec3,
    torso: &TorsoPoints,
    options: &RefineOptions,
) -> Option<Spine> {
    let height = frame.height();
    let median = |p: DVec3| p - frame.left * (p - centre).dot(frame.left);
    let c7 = torso.neck.lerp(torso.throat, options.neck_depth);
    // Fractions of the height, or of the trunk's depth there when that is more: a stylised
    // figure's trunk is deep for its height (big ears or hats count in the height), and the
    // spine stays inside the trunk in proportion, not at an adult's 6 cm from the back. The
    // back inset from lies no deeper behind the silhouette's front than the trunk is wide
    // (`width`, [`MAX_DEPTH_PER_WIDTH`]): a deeper silhouette carries something on its back.
    let inset = |p: DVec3, width: Option<f64>, of_height: f64, share: f64| {
        let d = trunk_depth(frame, &torso.silhouette, p);
        let deepest = width.map_or(f64::INFINITY, |w| MAX_DEPTH_PER_WIDTH * w);
        let (back, d) = if d.is_finite() && d > deepest {
            (p + frame.forward * (d - deepest), deepest)
        } else {
            (p, d)
        };
        let by_depth = if d.is_finite() { share * d } else { 0.0 };
        back + frame.forward * (of_height * height).max(by_depth)
    };
    let [back, lumbar, sacral] = torso.widths;
    let t6 = inset(torso.back, back, options.thoracic_depth, THORACIC_SHARE);
    let l3 = inset(torso.lumbar, lumbar, options.lumbar_depth, LUMBAR_SHARE);
    let sacrum = inset(torso.sacroiliac, sacral, options.sacral_depth, SACRAL_SHARE);
    let end = frame.at_height(sacrum, frame.h(torso.crotch));
    let control: Vec<DVec3> = [head, c7, t6, l3, sacrum, end]
        .into_iter()
        .map(median)
        .collect();
    // Ordered top to bottom (a NaN from a broken mesh compares as unordered and is refused).
    if control
        .windows(2)
        .any(|w| frame.h(w[0]).partial_cmp(&frame.h(w[1])) != Some(std::cmp::Ordering::Greater))
    {
        return None;
    }
    let curve = CatmullRom::new(&control);
    let fixed: Vec<f64> = (0..FIXED.len()).map(|k| curve.knots[k]).collect();
    let t = spacing(&fixed)?;
    let joints = SPINE_JOINTS
        .iter()
        .zip(t.iter().skip(1))
        .map(|(name, &u)| (name.to_string(), curve.point(u)))
        .collect();
    Some(Spine { control, joints })
}

/// The deepest a trunk is for its width: its median silhouette's depth from front to back at
/// most this many times its width across at the same height. The reference humanoids measure
/// 0.6-0.85 where the spine's control points lie (MakeHuman bodies, the knight's and the
/// platformer character's stylised trunks); the adventurer's backpack made its chest 1.23 times
/// as deep as wide, and its spine bowed back into the pack.
const MAX_DEPTH_PER_WIDTH: f64 = 1.0;

/// The least share of the trunk's front-to-back depth at the back point that T6/T7 lies in
/// front of it: the thoracic vertebral body sits about a quarter to a third of the chest's
/// depth in front of the back (MakeHuman bodies: the height-based default gives 0.24-0.34).
const THORACIC_SHARE: f64 = 0.25;
/// The same for L3/L4 at the lumbar point (MakeHuman: 0.28-0.46 of the abdomen's depth).
const LUMBAR_SHARE: f64 = 0.3;
/// The same for the sacrum at the sacroiliac point (MakeHuman: 0.31-0.43 of the pelvis's).
const SACRAL_SHARE: f64 = 0.3;

/// The trunk's depth (along `frame.forward`) in the median silhouette at the height of the
/// back point `p`: from `p` to the silhouette's front within a hundredth of the height.
fn trunk_depth(frame: &BodyFrame, silhouette: &[DVec3], p: DVec3) -> f64 {
    let band = 0.01 * frame.height();
    let h = frame.h(p);
    let front = silhouette
        .iter()
        .filter(|q| (frame.h(**q) - h).abs() <= band)
        .map(|q| q.dot(frame.forward))
        .fold(f64::NEG_INFINITY, f64::max);
    front - p.dot(frame.forward)
}

/// Chordal Catmull-Rom curve (Barry-Goldman pyramid) through points, ends extended by
/// reflection.
struct CatmullRom {
    points: Vec<DVec3>,
    knots: Vec<f64>,
}

impl CatmullRom {
    fn new(control: &[DVec3]) -> Self {
        let n = control.len();
        let mut points = Vec::with_capacity(n + 2);
        points.push(control[0] * 2.0 - control[1]);
        points.extend_from_slice(control);
        points.push(control[n - 1] * 2.0 - control[n - 2]);
        let mut knots = vec![0.0];
        for w in control.windows(2) {
            let last = knots[knots.len() - 1];
            knots.push(last + w[0].distance(w[1]).max(1e-12));
        }
        Self { points, knots }
    }

    /// The point at chordal parameter `t` (0 at the first control point).
    fn point(&self, t: f64) -> DVec3 {
        let k = &self.knots;
        let n = k.len();
        let t = t.clamp(k[0], k[n - 1]);
        let i = k.partition_point(|&x| x <= t).clamp(1, n - 1) - 1;
        let (t1, t2) = (k[i], k[i + 1]);
        let t0 = if i == 0 { t1 - (t2 - t1) } else { k[i - 1] };
        let t3 = if i + 2 < n { k[i + 2] } else { t2 + (t2 - t1) };
        let [p0, p1, p2, p3] = [
            self.points[i],
            self.points[i + 1],
            self.points[i + 2],
            self.points[i + 3],
        ];
        let lerp = |a: DVec3, b: DVec3, ta: f64, tb: f64| a + (b - a) * ((t - ta) / (tb - ta));
        let a1 = lerp(p0, p1, t0, t1);
        let a2 = lerp(p1, p2, t1, t2);
        let a3 = lerp(p2, p3, t2, t3);
        let b1 = lerp(a1, a2, t0, t2);
        let b2 = lerp(a2, a3, t1, t3);
        lerp(b1, b2, t1, t2)
    }
}

/// Minimises equation (1) of seed 004 for the parameters of the 26 joints (head, 24
/// inter-vertebral joints, sacrum centre) with the `fixed` parameters of [`FIXED`] held. The
/// sum runs over the free joints only (with the fixed joints' terms included the optimum is a
/// smooth sequence that can leave the interval between two control points when they are
/// unevenly spaced, which would reorder vertebrae), so its minimum, zero, is where every free
/// joint's parameter is the mean of its neighbours': each region's vertebrae evenly spaced
/// between its two fixed joints, as the seed intends ("adjacent vertebrae having the same
/// size"). That is the closed form used here; an iterative solver (argmin's L-BFGS, before)
/// reached the same answer and, on a corrupted mesh a thousand times the usual size, never
/// left its line search. `None` for a non-finite parameter (a joint off the curve of a
/// broken mesh).
fn spacing(fixed: &[f64]) -> Option<Vec<f64>> {
    if fixed.len() != FIXED.len() || !fixed.iter().all(|t| t.is_finite()) {
        return None;
    }
    let mut t = vec![0.0; 26];
    for (k, w) in FIXED.windows(2).enumerate() {
        let (i0, i1) = (w[0], w[1]);
        let (t0, t1) = (fixed[k], fixed[k + 1]);
        for (i, v) in t.iter_mut().enumerate().take(i1 + 1).skip(i0) {
            *v = t0 + (t1 - t0) * (i - i0) as f64 / (i1 - i0) as f64;
        }
    }
    Some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spacing_is_even_between_fixed_joints() {
        let t = spacing(&[0.0, 7.0, 20.0, 29.0, 35.0]).unwrap();
        for (i, v) in t.iter().enumerate().take(8) {
            assert!((v - i as f64).abs() < 1e-6, "{t:?}");
        }
        // 7 → 20 over 6 intervals.
        assert!((t[10] - (7.0 + 13.0 * 3.0 / 6.0)).abs() < 1e-6, "{t:?}");
    }

    /// Equation (1) over the free joints is zero, its minimum, at the spacing found, however
    /// large or far from zero the parameters (a corrupted mesh at a thousand times the size,
    /// far off the origin, once held an iterative solver here for ever).
    #[test]
    fn the_spacing_zeroes_equation_one_at_any_scale() {
        for fixed in [
            [0.0, 7.0, 20.0, 29.0, 35.0],
            [
                2.5e5,
                2.5e5 + 3.1e3,
                2.5e5 + 9.9e3,
                2.5e5 + 1.4e4,
                2.5e5 + 1.45e4,
            ],
            [1.0, 1.0, 1.0, 1.0, 1.0],
        ] {
            let t = spacing(&fixed).unwrap();
            let deviation: f64 = (1..25)
                .filter(|i| !FIXED.contains(i))
                .map(|i| (t[i] - (t[i - 1] + t[i + 1]) * 0.5).powi(2))
                .sum();
            let scale = (fixed[4] - fixed[0]).abs().max(1.0);
            assert!(deviation <= 1e-20 * scale * scale, "{deviation} {t:?}");
            for (k, &i) in FIXED.iter().enumerate() {
                assert_eq!(t[i], fixed[k]);
            }
            assert!(t.windows(2).all(|w| w[1] >= w[0]), "{t:?}");
        }
    }

    #[test]
    fn a_non_finite_joint_gives_no_spacing() {
        assert!(spacing(&[0.0, f64::NAN, 20.0, 29.0, 35.0]).is_none());
        assert!(spacing(&[0.0, 7.0, f64::INFINITY, 29.0, 35.0]).is_none());
    }

    /// A frame with +Y up and +Z forward, 2 units tall.
    fn upright() -> BodyFrame {
        BodyFrame {
            up: DVec3::Y,
            forward: DVec3::Z,
            left: DVec3::X,
            top: 2.0,
            bottom: 0.0,
        }
    }

    /// Torso points on a median silhouette that is a rectangle from the back (z = 0) to
    /// z = `depth`, with the trunk's `widths` at the back points.
    fn box_torso(depth: f64, widths: [Option<f64>; 3]) -> TorsoPoints {
        let mut silhouette = Vec::new();
        for k in 0..=100 {
            let y = 0.5 + k as f64 * 0.01;
            silhouette.push(DVec3::new(0.0, y, 0.0));
            silhouette.push(DVec3::new(0.0, y, depth));
        }
        TorsoPoints {
            neck: DVec3::new(0.0, 1.45, 0.1 * depth),
            back: DVec3::new(0.0, 1.3, 0.0),
            lumbar: DVec3::new(0.0, 1.0, 0.0),
            sacroiliac: DVec3::new(0.0, 0.8, 0.0),
            throat: DVec3::new(0.0, 1.45, 0.9 * depth),
            crotch: DVec3::new(0.0, 0.5, 0.5 * depth),
            widths,
            silhouette,
        }
    }

    /// A trunk as deep as a third of the figure's height (a cartoon body): the spine's back
    /// control points move in by their share of that depth, more than the adult's fraction of
    /// the height; a slim trunk keeps the height-based inset.
    #[test]
    fn a_deep_trunk_keeps_its_spine_in_proportion() {
        let frame = upright();
        let options = RefineOptions::default();
        let head = DVec3::new(0.0, 1.7, 0.1);
        let deep = spine(
            &frame,
            DVec3::ZERO,
            head,
            &box_torso(0.66, [None; 3]),
            &options,
        )
        .unwrap();
        // control: head, c7, t6, l3, sacrum, end.
        assert!(
            (deep.control[2].z - THORACIC_SHARE * 0.66).abs() < 1e-9,
            "{:?}",
            deep.control
        );
        assert!((deep.control[3].z - LUMBAR_SHARE * 0.66).abs() < 1e-9);
        assert!((deep.control[4].z - SACRAL_SHARE * 0.66).abs() < 1e-9);
        let slim = spine(
            &frame,
            DVec3::ZERO,
            head,
            &box_torso(0.2, [None; 3]),
            &options,
        )
        .unwrap();
        assert!((slim.control[2].z - options.thoracic_depth * 2.0).abs() < 1e-9);
        assert!((slim.control[3].z - options.lumbar_depth * 2.0).abs() < 1e-9);
    }

    /// A median silhouette deeper than the trunk is wide (a backpack on the back): the spine's
    /// control points are inset from a back one width behind the front, not from the pack's
    /// rear; a trunk as wide as it is deep keeps its own back.
    #[test]
    fn a_backpack_is_not_the_back_the_spine_is_inset_from() {
        let frame = upright();
        let (depth, width) = (0.66, 0.4);
        let options = RefineOptions::default();
        let head = DVec3::new(0.0, 1.7, 0.1);
        let packed = box_torso(depth, [Some(width); 3]);
        let packed = spine(&frame, DVec3::ZERO, head, &packed, &options).unwrap();
        let back = depth - width;
        for (k, share) in [(2, THORACIC_SHARE), (3, LUMBAR_SHARE), (4, SACRAL_SHARE)] {
            let z = packed.control[k].z;
            assert!((z - (back + share * width)).abs() < 1e-9, "{k}: {z}");
        }
        let wide = box_torso(depth, [Some(depth); 3]);
        let wide = spine(&frame, DVec3::ZERO, head, &wide, &options).unwrap();
        assert!((wide.control[2].z - THORACIC_SHARE * depth).abs() < 1e-9);
    }

    #[test]
    fn catmull_rom_passes_through_its_control_points() {
        let c = [
            DVec3::new(0.0, 3.0, 0.0),
            DVec3::new(0.1, 2.0, 0.0),
            DVec3::new(0.0, 1.0, 0.2),
            DVec3::new(0.0, 0.0, 0.0),
        ];
        let curve = CatmullRom::new(&c);
        for (k, p) in c.iter().enumerate() {
            assert!(curve.point(curve.knots[k]).distance(*p) < 1e-9);
        }
    }
}

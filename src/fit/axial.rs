//! The axial skeleton (dissertation 8.1): dorsal offset of the trunk, the S-shaped cervical
//! replacement, smoothing, the rigid head segment, vertebral segments and the root joint.

use super::polyline::Polyline;
use super::{BodyFrame, DorsalProbe, FitOptions, FitWarning};
use crate::math::{moving_average, Ends};
use crate::template::{Posture, Template};
use glam::DVec3;

/// Section boundaries as arc lengths on the original head-to-tail path (head tip = 0).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Bounds {
    /// Head/neck boundary.
    pub head: f64,
    /// Neck/trunk boundary (foremost limb pair).
    pub neck: f64,
    /// Trunk/tail boundary (hindmost limb pair).
    pub trunk: f64,
}

/// The placed axial joints.
pub(crate) struct AxialFit {
    pub root: DVec3,
    /// Trunk joints from the root towards the neck (exclusive), with their fraction of the way
    /// root → neck base.
    pub trunk: Vec<(DVec3, f64)>,
    /// Neck joints from the neck base towards the head (exclusive).
    pub neck: Vec<DVec3>,
    pub head: DVec3,
    pub head_end: DVec3,
    /// Tail joints from the root's posterior side to the tip (exclusive).
    pub tail: Vec<DVec3>,
    pub tail_end: Option<DVec3>,
    /// The adjusted, smoothed path (head tip first).
    pub spine: Polyline,
    /// Original path parameter (arc length) of each spine sample.
    pub samples_t: Vec<f64>,
}

impl AxialFit {
    /// The point of the adjusted spine at original arc length `t`.
    pub fn spine_at(&self, t: f64) -> DVec3 {
        let n = self.samples_t.len();
        let total = self.samples_t.last().copied().unwrap_or(0.0);
        if n < 2 || total <= 0.0 {
            return self.spine.at(0.0);
        }
        let x = (t / total).clamp(0.0, 1.0) * (n - 1) as f64;
        let k = (x.floor() as usize).min(n - 2);
        let f = x - k as f64;
        self.spine.points[k].lerp(self.spine.points[k + 1], f)
    }
}

/// Smallest perpendicular part (relative to `|v|`) that still defines a direction.
const MIN_PERPENDICULAR: f64 = 1e-6;

/// Unit component of `v` perpendicular to unit `t`; zero when (nearly) parallel.
pub(crate) fn perpendicular(v: DVec3, t: DVec3) -> DVec3 {
    let p = v - t * v.dot(t);
    if p.length() > MIN_PERPENDICULAR * v.length() {
        p.normalize()
    } else {
        DVec3::ZERO
    }
}

/// Vertebral segment length: `ratio` times the head's length `head` along a path `length`
/// long, or a twelfth of the path when that is (nearly) zero.
fn vertebra_length(ratio: f64, head: f64, length: f64) -> f64 {
    let seg = ratio * head;
    if seg <= 1e-12 * length.max(1.0) {
        length / 12.0
    } else {
        seg
    }
}

/// The share of `dorsal_offset` at arc length `t` of the head-to-tail path: 1 everywhere,
/// unless the template asks for the taper (`taper`, [`crate::template::Axial::dorsal_taper`])
/// and both girdles are known with the pectoral one (`pectoral_t`) ahead of the root
/// (`root_t`): then it rises linearly from 0 at the pectoral girdle (the thoracic column deep
/// under the withers, mid-chest) to 1 at the pelvic one (the sacrum on top of the pelvis),
/// staying 0 ahead of the shoulders and 1 behind the hips.
fn dorsal_taper(taper: bool, t: f64, pectoral_t: Option<f64>, root_t: f64) -> f64 {
    match pectoral_t {
        Some(p) if taper && root_t > p => ((t - p) / (root_t - p)).clamp(0.0, 1.0),
        _ => 1.0,
    }
}

/// The axial path moved dorsally at `samples_t` (arc lengths on `original`): the trunk by
/// `dorsal_offset` of the sphere radius (times [`dorsal_taper`]), fading out over
/// `offset_blend` segments (`seg` long) beyond it, and an S-shaped neck on animal-like figures.
#[allow(clippy::too_many_arguments)]
fn dorsal_path(
    original: &Polyline,
    radii: &[f64],
    samples_t: &[f64],
    bounds: Bounds,
    pectoral_t: Option<f64>,
    root_t: f64,
    seg: f64,
    template: &Template,
    options: &FitOptions,
    frame: &BodyFrame,
    probe: Option<&dyn DorsalProbe>,
) -> Vec<DVec3> {
    let rules = &template.axial;
    let blend = options.offset_blend * seg;
    let neck_len = (bounds.neck - bounds.head).max(0.0);
    let window = options.cervical_window * neck_len;
    samples_t
        .iter()
        .map(|&t| {
            let o = original.at(t);
            let r = original.value_at(radii, t);
            let dorsal = perpendicular(frame.dorsal, original.tangent(t));
            // Trunk: 70 % of the sphere radius dorsally, fading out over `blend` beyond it.
            // Animal-like necks leave the trunk low: the offset has faded out by the neck
            // boundary, over `neck_base_drop` segments of the trunk in front of the foremost
            // girdle (the scapulae stay on the dorsal spine).
            let drop = if rules.cervical_s_curve {
                let room = pectoral_t.map_or(f64::INFINITY, |p| (p - bounds.neck).max(0.0));
                (options.neck_base_drop * seg).min(room)
            } else {
                0.0
            };
            let outside = (bounds.neck + drop - t).max(t - bounds.trunk).max(0.0);
            let w = if outside <= 0.0 {
                1.0
            } else if blend > 0.0 {
                (1.0 - outside / blend).max(0.0)
            } else {
                0.0
            };
            let taper = dorsal_taper(rules.dorsal_taper, t, pectoral_t, root_t);
            let mut offset = w * taper * rules.dorsal_offset * r;
            // S-shaped neck: offset along a dorsal ray, peaking at the head/neck junction.
            if rules.cervical_s_curve && window > 0.0 {
                let c = (1.0 - (t - bounds.head).abs() / window).max(0.0);
                if c > 0.0 {
                    let depth = probe.and_then(|p| p.depth(o, dorsal)).unwrap_or(r);
                    offset = offset.max(c * options.cervical_depth * depth.max(0.0));
                }
            }
            o + dorsal * offset
        })
        .collect()
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn axial(
    original: &Polyline,
    radii: &[f64],
    bounds: Bounds,
    root_t: f64,
    pectoral_t: Option<f64>,
    template: &Template,
    options: &FitOptions,
    frame: &BodyFrame,
    probe: Option<&dyn DorsalProbe>,
    labelled_tail: bool,
    warnings: &mut Vec<FitWarning>,
) -> AxialFit {
    let length = original.length();
    let n = options.axial_samples;
    let step = length / (n - 1) as f64;
    let rules = &template.axial;
    // Vertebral segment length from the head on the original path (8.1: about a third).
    let head_len = bounds.head.max(0.0);
    let seg = vertebra_length(rules.vertebra_to_head, head_len, length);
    let samples_t: Vec<f64> = (0..n).map(|k| length * k as f64 / (n - 1) as f64).collect();
    let adjusted = dorsal_path(
        original, radii, &samples_t, bounds, pectoral_t, root_t, seg, template, options, frame,
        probe,
    );
    let half = if step > 0.0 {
        (options.axial_smoothing * seg / step).round() as usize
    } else {
        0
    };
    let spine = Polyline::new(moving_average(&adjusted, half, Ends::Shrink));
    let arc = |t: f64| -> f64 {
        if length <= 0.0 {
            return 0.0;
        }
        let x = (t / length).clamp(0.0, 1.0) * (n - 1) as f64;
        let k = (x.floor() as usize).min(n - 2);
        let f = x - k as f64;
        spine.cum[k] * (1.0 - f) + spine.cum[k + 1] * f
    };
    let h = arc(bounds.head);
    let nk = arc(bounds.neck);
    let te = arc(bounds.trunk);
    let end = spine.length();
    let seg_s = vertebra_length(rules.vertebra_to_head, h, end);
    let count = |len: f64| (len / seg_s).round().max(0.0) as usize;

    // Neck: n equal segments between the head joint and the neck base.
    let n_neck = template.vertebrae.neck.clamp(count(nk - h));
    let neck: Vec<DVec3> = (0..n_neck)
        .map(|j| spine.at(nk - j as f64 * (nk - h) / n_neck as f64))
        .collect();

    // Trunk: n equal segments; the root at the hindmost pair (moved `root_offset` segments
    // anteriorly), between the centred path and the dorsal spine by `root_dorsal`.
    let n_trunk = template.vertebrae.trunk.clamp(count(te - nk)).max(1);
    let b = |i: usize| nk + i as f64 * (te - nk) / n_trunk as f64;
    let t_root =
        (root_t - options.root_offset * seg).clamp(bounds.neck.min(bounds.trunk), bounds.trunk);
    let root_arc = arc(t_root);
    let root = original
        .at(t_root)
        .lerp(spine.at(root_arc), options.root_dorsal);
    // Trunk joints closer than a quarter segment to the root are left out (no coincident
    // joints); those behind it continue into the tail chain.
    let gap = 0.25 * (te - nk) / n_trunk as f64;
    let span = (root_arc - nk).max(1e-300);
    let trunk: Vec<(DVec3, f64)> = (1..n_trunk)
        .rev()
        .filter(|&i| b(i) < root_arc - gap)
        .map(|i| (spine.at(b(i)), (root_arc - b(i)) / span))
        .collect();
    let mut tail: Vec<DVec3> = (1..n_trunk)
        .filter(|&i| b(i) > root_arc + gap)
        .map(|i| spine.at(b(i)))
        .collect();
    let tail_len = end - te;
    let mut tail_end = None;
    // An upright figure's tail is one the labels found: its path otherwise ends at the legs,
    // and a path whose hindmost pair the labels misjudged (a gun in a hand) ran on past it.
    let may_tail = labelled_tail || template.posture != Posture::Upright;
    if may_tail && tail_len >= options.min_tail * seg_s && template.vertebrae.tail.max > 0 {
        let n_tail = template.vertebrae.tail.clamp(count(tail_len)).max(1);
        tail.extend(
            (0..n_tail)
                .map(|j| te + j as f64 * tail_len / n_tail as f64)
                .filter(|&s| s > root_arc + gap)
                .map(|s| spine.at(s)),
        );
        tail_end = Some(spine.at(end));
    } else if template.vertebrae.tail.min > 0 {
        warnings.push(FitWarning::MissingTail);
    }
    AxialFit {
        root,
        trunk,
        neck,
        head: spine.at(h),
        head_end: spine.at(0.0),
        tail,
        tail_end,
        spine,
        samples_t,
    }
}

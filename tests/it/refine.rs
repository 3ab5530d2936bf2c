//! Slicing primitives on analytic shapes and the slicing-based humanoid refinement (seed 004)
//! on the bundled MakeHuman body; accuracy and tessellation robustness on refdata when present.

use glam::{DQuat, DVec3};
use skelfit::eval::load_skeleton;
use skelfit::mesh::{slice_plane, slice_sphere, Mesh, SliceLoop};
use skelfit::refine::{
    carry, leg_split_height, refine, RefineError, RefineOptions, Refinement, REFINED_KEYS,
};
use skelfit::skeleton::{JointId, Skeleton};
use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};
use std::path::Path;

fn unit_box() -> Mesh {
    Mesh::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0))
}

#[test]
fn plane_through_a_box_gives_its_square_outline() {
    let loops = slice_plane(&unit_box(), DVec3::new(0.0, 0.3, 0.0), DVec3::Y);
    assert_eq!(loops.len(), 1);
    let l = &loops[0];
    assert!(l.closed);
    assert!((l.perimeter() - 8.0).abs() < 1e-9, "{}", l.perimeter());
    assert!(l.centroid().unwrap().distance(DVec3::new(0.0, 0.3, 0.0)) < 1e-9);
    let axes = l.principal_axes().unwrap();
    assert!((axes.major_diameter - 2.0).abs() < 0.83, "{axes:?}"); // a square: any axis, 2..2.83
    assert!(axes.normal.abs().distance(DVec3::Y) < 1e-9, "{axes:?}");
}

#[test]
fn plane_through_vertices_and_along_edges_still_gives_one_closed_loop() {
    // Through the four top vertices: the top face's outline.
    let top = slice_plane(&unit_box(), DVec3::Y, DVec3::Y);
    assert_eq!(top.len(), 1, "{top:?}");
    assert!(top[0].closed);
    assert!((top[0].perimeter() - 8.0).abs() < 1e-9);
    // Diagonal plane through two opposite vertical edges.
    let diagonal = slice_plane(&unit_box(), DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0));
    assert_eq!(diagonal.len(), 1, "{diagonal:?}");
    assert!(diagonal[0].closed);
    let expected = 4.0 * 2f64.sqrt() + 4.0;
    assert!((diagonal[0].perimeter() - expected).abs() < 1e-9);
}

#[test]
fn plane_missing_the_mesh_or_with_a_zero_normal_gives_nothing() {
    assert!(slice_plane(&unit_box(), DVec3::Y * 5.0, DVec3::Y).is_empty());
    assert!(slice_plane(&unit_box(), DVec3::ZERO, DVec3::ZERO).is_empty());
    assert!(slice_sphere(&unit_box(), DVec3::ZERO, 0.0).is_empty());
}

#[test]
fn open_mesh_gives_an_open_piece() {
    let mut mesh = unit_box();
    mesh.triangles.remove(0); // one triangle of the -z face
    let loops = slice_plane(&mesh, DVec3::ZERO, DVec3::Y);
    assert_eq!(loops.len(), 1, "{loops:?}");
    assert!(!loops[0].closed);
    assert!(loops[0].perimeter() > 6.0 && loops[0].perimeter() < 8.0);
}

#[test]
fn sphere_around_a_capsule_axis_cuts_two_circles_centred_on_the_axis() {
    let (r, rho) = (0.1, 0.3);
    // A tube with a ring every 5 cm (a sphere only cuts triangles with a corner inside).
    let rings: Vec<(f64, f64)> = (0..=40).map(|k| (r, 1.0 - 0.05 * k as f64)).collect();
    let mesh = Mesh::lathe(DVec3::ZERO, 1.0, &rings, -1.0, 64);
    let loops = slice_sphere(&mesh, DVec3::ZERO, rho);
    assert_eq!(loops.len(), 2, "{loops:?}");
    let polygon = 64.0 * 2.0 * r * (PI / 64.0).sin();
    for l in &loops {
        assert!(l.closed);
        assert!((l.perimeter() - polygon).abs() < 1e-3, "{}", l.perimeter());
        let g = l.centroid().unwrap();
        assert!(g.x.abs() < 1e-9 && g.z.abs() < 1e-9, "{g}");
        assert!((g.y.abs() - (rho * rho - r * r).sqrt()).abs() < 1e-3, "{g}");
        for p in &l.points {
            assert!((p.length() - rho).abs() < 1e-12, "points lie on the sphere");
        }
        let axes = l.principal_axes().unwrap();
        assert!((axes.major_diameter - 2.0 * r).abs() < 2e-3, "{axes:?}");
        assert!(axes.normal.abs().distance(DVec3::Y) < 1e-6);
    }
}

#[test]
fn principal_axes_of_an_ellipse() {
    let points = (0..200)
        .map(|k| {
            let t = TAU * k as f64 / 200.0;
            DVec3::new(2.0 * t.cos(), 0.5, t.sin())
        })
        .collect();
    let l = SliceLoop {
        points,
        closed: true,
    };
    let axes = l.principal_axes().unwrap();
    assert!(axes.major.abs().distance(DVec3::X) < 1e-6, "{axes:?}");
    assert!(axes.minor.abs().distance(DVec3::Z) < 1e-6, "{axes:?}");
    assert!((axes.major_diameter - 4.0).abs() < 1e-3);
    assert!((axes.minor_diameter - 2.0).abs() < 1e-3);
}

/// The deterministic start of the report (examples/refine_report.rs): the `k`-th refined key
/// displaced by 3-6 cm.
fn offset(k: usize) -> DVec3 {
    let k = k as f64;
    let dir = DVec3::new(
        (1.7 * k + 0.3).sin(),
        (2.3 * k + 1.1).cos(),
        (0.9 * k + 2.0).sin(),
    )
    .normalize();
    dir * (0.03 + 0.01 * (k % 4.0))
}

struct Case {
    mesh: Mesh,
    truth: Skeleton,
    rough: Skeleton,
    canonical: BTreeMap<String, JointId>,
}

fn case(dir: &Path, rig: &str) -> Case {
    let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).unwrap();
    let rig = load_skeleton(&dir.join(rig)).unwrap();
    let targets = REFINED_KEYS
        .iter()
        .enumerate()
        .filter_map(|(k, key)| {
            let id = *rig.canonical.get(*key)?;
            Some((id, rig.skeleton.joint(id).position + offset(k)))
        })
        .collect();
    Case {
        mesh,
        rough: carry(&rig.skeleton, &targets),
        truth: rig.skeleton.clone(),
        canonical: rig.canonical.clone(),
    }
}

fn bundled() -> Case {
    case(
        &crate::common::data_dir().join("humanoid/mh_neutral_default"),
        "rig_game_engine.json",
    )
}

/// Errors (mm) of the refined keys: (before, after).
fn errors(c: &Case, r: &Refinement) -> (Vec<f64>, Vec<f64>) {
    REFINED_KEYS
        .iter()
        .filter_map(|k| c.canonical.get(*k))
        .map(|id| {
            let truth = c.truth.joint(*id).position;
            (
                c.rough.joint(*id).position.distance(truth) * 1000.0,
                r.skeleton.joint(*id).position.distance(truth) * 1000.0,
            )
        })
        .unzip()
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

#[test]
fn refinement_brings_displaced_joints_back_on_the_bundled_body() {
    let c = bundled();
    let r = refine(
        &c.mesh,
        &c.rough,
        &c.canonical,
        DVec3::Y,
        DVec3::Z,
        &RefineOptions::default(),
    )
    .unwrap();
    let (before, after) = errors(&c, &r);
    let worst = after.iter().copied().fold(0.0, f64::max);
    assert!(mean(&before) > 40.0);
    // Measured 15.6 mm mean, 29.8 mm max (reports/refine/accuracy.md).
    assert!(mean(&after) < 20.0, "{after:?}");
    assert!(worst < 40.0, "{after:?}");
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    assert!(r.skeleton.validate().is_ok());
    // The full spine: 24 inter-vertebral joints and the sacrum, top to bottom.
    assert_eq!(r.spine.len(), 25);
    assert!(
        r.spine.windows(2).all(|w| w[0].1.y > w[1].1.y),
        "{:?}",
        r.spine
    );
    // Spine joints of the skeleton lie between pelvis and neck.
    let y = |n: &str| r.skeleton.joint(r.skeleton.find(n).unwrap()).position.y;
    assert!(y("spine_01") > y("pelvis") && y("spine_03") < y("neck_01"));
    // Fingers keep their places while the wrist moves.
    let (hand, finger) = (
        c.canonical["wrist_L"],
        r.skeleton.find("middle_01_l").unwrap(),
    );
    let moved = |id: JointId| r.skeleton.joint(id).position - c.rough.joint(id).position;
    assert!(moved(hand).length() > 0.01 && moved(finger) == DVec3::ZERO);
}

#[test]
fn refinement_does_not_depend_on_the_mesh_frame() {
    let c = bundled();
    let options = RefineOptions::default();
    let plain = refine(
        &c.mesh,
        &c.rough,
        &c.canonical,
        DVec3::Y,
        DVec3::Z,
        &options,
    )
    .unwrap();
    // Z up, −X forward, shifted.
    let rotation =
        DQuat::from_rotation_arc(DVec3::Y, DVec3::Z) * DQuat::from_axis_angle(DVec3::Y, 0.5 * PI);
    let shift = DVec3::new(3.0, -2.0, 1.0);
    let f = |p: DVec3| rotation * p + shift;
    let mesh = c.mesh.transformed(f);
    let mut rough = c.rough.clone();
    for j in &mut rough.joints {
        j.position = f(j.position);
    }
    let turned = refine(
        &mesh,
        &rough,
        &c.canonical,
        rotation * DVec3::Y,
        rotation * DVec3::Z,
        &options,
    )
    .unwrap();
    for key in REFINED_KEYS {
        let id = c.canonical[key];
        let a = f(plain.skeleton.joint(id).position);
        let b = turned.skeleton.joint(id).position;
        assert!(a.distance(b) < 1e-3, "{key}: {a} vs {b}");
    }
}

#[test]
fn a_missing_head_warns_and_keeps_the_rough_head() {
    let c = bundled();
    let neck = c.truth.joint(c.canonical["neck"]).position.y;
    let mut mesh = c.mesh.clone();
    mesh.triangles.retain(|t| {
        t.iter()
            .all(|&i| mesh.positions[i as usize].y < neck + 0.02)
    });
    let r = refine(
        &mesh,
        &c.rough,
        &c.canonical,
        DVec3::Y,
        DVec3::Z,
        &RefineOptions::default(),
    )
    .unwrap();
    assert!(
        r.warnings.iter().any(|w| w.to_string().starts_with("head")),
        "{:?}",
        r.warnings
    );
    let id = c.canonical["head"];
    assert_eq!(r.skeleton.joint(id).position, c.rough.joint(id).position);
}

#[test]
fn a_lying_body_given_as_upright_never_panics_and_names_the_joints_it_kept() {
    let c = bundled();
    let tilt = DQuat::from_axis_angle(DVec3::X, 0.45 * PI);
    let mesh = c.mesh.transformed(|p| tilt * p);
    let r = refine(
        &mesh,
        &c.rough,
        &c.canonical,
        DVec3::Y,
        DVec3::Z,
        &RefineOptions::default(),
    )
    .unwrap();
    assert!(!r.warnings.is_empty());
    for key in REFINED_KEYS {
        let id = c.canonical[key];
        if !r.moved.contains_key(key) {
            assert_eq!(
                r.skeleton.joint(id).position,
                c.rough.joint(id).position,
                "{key}"
            );
            assert!(
                r.warnings.iter().any(|w| w.to_string().contains(key)),
                "{key}: {:?}",
                r.warnings
            );
        }
    }
}

#[test]
fn a_body_without_free_limbs_keeps_the_limb_joints_with_warnings() {
    // A capsule where the body should be: arms and legs fused into one blob.
    let c = bundled();
    let mesh = Mesh::capsule(DVec3::new(0.0, 0.9, 0.0), 0.2, 0.7, 12, 48);
    let r = refine(
        &mesh,
        &c.rough,
        &c.canonical,
        DVec3::Y,
        DVec3::Z,
        &RefineOptions::default(),
    )
    .unwrap();
    for key in ["elbow_L", "wrist_R", "knee_L", "ankle_R"] {
        let id = c.canonical[key];
        let kept = r.skeleton.joint(id).position == c.rough.joint(id).position;
        assert!(kept, "{key} moved on a blob");
        assert!(
            r.warnings.iter().any(|w| w.to_string().contains(key)),
            "{key}: {:?}",
            r.warnings
        );
    }
}

#[test]
fn bad_input_is_an_error() {
    let c = bundled();
    let o = RefineOptions::default();
    assert_eq!(
        refine(
            &Mesh::default(),
            &c.rough,
            &c.canonical,
            DVec3::Y,
            DVec3::Z,
            &o
        )
        .unwrap_err(),
        RefineError::EmptyMesh
    );
    assert!(matches!(
        refine(
            &c.mesh,
            &c.rough,
            &c.canonical,
            DVec3::Y,
            DVec3::Y * 2.0,
            &o
        ),
        Err(RefineError::BadDirections { .. })
    ));
    let mut canonical = c.canonical.clone();
    canonical.insert("head".into(), JointId(10_000));
    assert!(matches!(
        refine(&c.mesh, &c.rough, &canonical, DVec3::Y, DVec3::Z, &o),
        Err(RefineError::BadJointId { .. })
    ));
}

/// Accuracy on every MakeHuman body of refdata (skips without it): the measured means are
/// 7.3-13.5 mm (reports/refine/accuracy.md); this guards against regressions.
#[test]
fn refinement_accuracy_on_refdata_humanoids() {
    let Some(root) = crate::common::refdata() else {
        return;
    };
    for model in [
        "mh_child_10y",
        "mh_female_thin_short",
        "mh_female_young_average",
        "mh_male_heavy_short",
        "mh_male_young_average",
        "mh_neutral_default",
    ] {
        let c = case(&root.join("humanoid").join(model), "rig_game_engine.json");
        let r = refine(
            &c.mesh,
            &c.rough,
            &c.canonical,
            DVec3::Y,
            DVec3::Z,
            &RefineOptions::default(),
        )
        .unwrap();
        let (before, after) = errors(&c, &r);
        assert!(
            mean(&after) < 28.0 && mean(&after) < mean(&before),
            "{model}: {after:?}"
        );
    }
}

/// Tessellation robustness (seed 004, table 1) on every refdata variant from 3k (including
/// the non-manifold fast simplification) to 107k triangles: mean displacement from the 27k
/// result at most 3 mm (measured 0.4-2.1 mm, reports/refine/robustness.md).
#[test]
fn refinement_is_robust_to_tessellation() {
    let Some(root) = crate::common::refdata() else {
        return;
    };
    let rig = "rig_game_engine.json";
    let base_dir = root.join("humanoid/mh_male_young_average");
    let base = case(&base_dir, rig);
    let o = RefineOptions::default();
    let reference = refine(
        &base.mesh,
        &base.rough,
        &base.canonical,
        DVec3::Y,
        DVec3::Z,
        &o,
    )
    .unwrap();
    for variant in [
        "altdiag",
        "dec12k",
        "dec6k",
        "dec3k",
        "dec3k_fastsimp",
        "isoremesh",
        "subdiv_loop1",
    ] {
        let dir = root.join(format!("robustness/mh_male_young_average_{variant}"));
        let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).unwrap();
        let r = refine(&mesh, &base.rough, &base.canonical, DVec3::Y, DVec3::Z, &o).unwrap();
        let d: Vec<f64> = REFINED_KEYS
            .iter()
            .map(|k| {
                let id = base.canonical[*k];
                r.skeleton
                    .joint(id)
                    .position
                    .distance(reference.skeleton.joint(id).position)
                    * 1000.0
            })
            .collect();
        assert!(mean(&d) <= 3.0, "{variant}: {d:?}");
    }
}

/// `pipeline::rig` refines humanoid fits by default: on the bundled body the 15 refined joints
/// come closer to the reference (measured 28.4 → 17.0 mm mean) than with `in_rig: false`.
#[test]
fn rig_refines_humanoids_by_default() {
    use skelfit::pipeline::{rig, RigOptions};
    let c = bundled();
    let mean_error = |options: &RigOptions| {
        let r = rig(&c.mesh, options).unwrap();
        let e: Vec<f64> = REFINED_KEYS
            .iter()
            .map(|k| {
                let p = r.fit.skeleton.joint(r.fit.canonical[*k]).position;
                p.distance(c.truth.joint(c.canonical[*k]).position)
            })
            .collect();
        (
            mean(&e),
            r.timings.iter().any(|(stage, _)| stage == "refine"),
        )
    };
    let (on, ran) = mean_error(&RigOptions::default());
    let mut off_options = RigOptions::default();
    off_options.refine.in_rig = false;
    let (off, ran_off) = mean_error(&off_options);
    assert!(ran && !ran_off);
    assert!(on < 0.8 * off, "refined {on:.4} m, fitted {off:.4} m");
}

/// The hip slice is split at the middle of the body's own cross-section, not at the rough
/// pelvis it is given: a rough pelvis 4 cm off the middle of a symmetric pelvis block still
/// gives mirror-image hips (splitting at the rough pelvis moved one hip in and the other out).
#[test]
fn hips_split_at_the_cross_sections_own_middle() {
    let mesh = Mesh::cuboid(DVec3::new(-0.2, 0.0, -0.1), DVec3::new(0.2, 1.0, 0.1));
    let frame = skelfit::refine::BodyFrame::new(&mesh, DVec3::Y, DVec3::Z).unwrap();
    let off_centre = DVec3::new(0.04, 0.5, 0.0);
    let (l, r) = skelfit::refine::hips(&mesh, &frame, off_centre, 0.5, 0.5).unwrap();
    assert!((l.x + r.x).abs() < 1e-9, "{l} {r}");
    assert!(l.x > 0.05 && r.x < -0.05, "{l} {r}");
    assert!(
        (l.y - 0.5).abs() < 1e-9 && (r.y - 0.5).abs() < 1e-9,
        "{l} {r}"
    );
}

/// One mesh holding all of `parts` (overlapping or touching pieces are fine for slicing).
fn merged(parts: &[Mesh]) -> Mesh {
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    for m in parts {
        let base = positions.len() as u32;
        positions.extend_from_slice(&m.positions);
        triangles.extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
    }
    Mesh::new(positions, triangles).unwrap()
}

/// The crotch is where the legs stop being cut apart, not the lowest point of the median
/// plane's cut: a 1 cm spike hanging 5 cm below the pelvis between two legs (a pinched
/// simplification vertex) does not lower it.
#[test]
fn the_crotch_is_the_top_of_the_gap_between_the_legs() {
    let b = |lo: [f64; 3], hi: [f64; 3]| Mesh::cuboid(DVec3::from(lo), DVec3::from(hi));
    let mesh = merged(&[
        b([-0.2, 0.5, -0.1], [0.2, 1.0, 0.1]),
        b([-0.18, 0.0, -0.08], [-0.02, 0.5, 0.08]),
        b([0.02, 0.0, -0.08], [0.18, 0.5, 0.08]),
        b([-0.005, 0.45, -0.005], [0.005, 0.5, 0.005]),
    ]);
    let frame = skelfit::refine::BodyFrame::new(&mesh, DVec3::Y, DVec3::Z).unwrap();
    let centre = DVec3::new(0.0, 0.5, 0.0);
    let split = |from: f64| leg_split_height(&mesh, &frame, centre, from, 0.9, 0.01, 0.5);
    let h = split(0.3).unwrap();
    assert!((h - 0.5).abs() < 0.001, "{h}");
    // Legs not apart where the search starts (touching thighs, a skirt): no answer.
    assert_eq!(split(0.6), None);
}

/// The head's principal axis nearer the given forward is forward: a head wider than deep
/// keeps facing +Z instead of turning 90 degrees to its long axis.
#[test]
fn a_head_wider_than_deep_still_faces_forward() {
    let ellipse = |a: f64, c: f64, y: f64| SliceLoop {
        points: (0..64)
            .map(|k| {
                let t = k as f64 / 64.0 * std::f64::consts::TAU;
                DVec3::new(a * t.cos(), y, c * t.sin())
            })
            .collect(),
        closed: true,
    };
    let mesh = Mesh::cuboid(DVec3::new(-0.2, 0.0, -0.2), DVec3::new(0.2, 1.8, 0.2));
    let frame = skelfit::refine::BodyFrame::new(&mesh, DVec3::Y, DVec3::Z).unwrap();
    let turned = (DVec3::Z + DVec3::X * 0.3).normalize();
    for (a, c) in [(0.10, 0.08), (0.08, 0.10)] {
        let head = skelfit::refine::HeadSlices {
            slices: (0..5)
                .map(|k| ellipse(a, c, 1.7 - 0.02 * k as f64))
                .collect(),
            largest: 0,
            ended_by_shrink: true,
        };
        let f = skelfit::refine::frame_from_head(&frame, &head, turned).unwrap();
        assert!(
            f.forward.distance(DVec3::Z) < 1e-6,
            "{a} {c}: {}",
            f.forward
        );
        assert!(f.left.distance(DVec3::X) < 1e-6, "{a} {c}: {}", f.left);
    }
}

/// A limb profile through `points` (arc = length along them), every slice alike.
fn profile(points: &[DVec3]) -> skelfit::refine::LimbProfile {
    let mut arc = 0.0;
    let slices = points
        .iter()
        .enumerate()
        .map(|(i, &centre)| {
            if i > 0 {
                arc += centre.distance(points[i - 1]);
            }
            skelfit::refine::LimbSlice {
                centre,
                perimeter: 0.3,
                major: 0.1,
                minor: 0.08,
                arc,
            }
        })
        .collect();
    skelfit::refine::LimbProfile { slices }
}

/// Points every `step` along the polyline `corners`.
fn along(corners: &[DVec3], step: f64) -> Vec<DVec3> {
    let mut out = vec![corners[0]];
    for w in corners.windows(2) {
        let n = (w[0].distance(w[1]) / step).ceil() as usize;
        out.extend((1..=n).map(|k| w[0].lerp(w[1], k as f64 / n as f64)));
    }
    out
}

/// A leg bent at the knee whose centroid curve runs on into the foot and folds back (as the
/// sphere slices of a low-poly foot do): the knee is the bend of the leg, not the fold next to
/// an ankle misplaced into the foot (CesiumMan's knees went to its ankles that way).
#[test]
fn a_knee_is_not_taken_from_a_foot_that_folds_back() {
    let (hip, knee, ankle) = (
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.0, 0.55, 0.12),
        DVec3::new(0.0, 0.1, 0.0),
    );
    let points = along(
        &[
            hip,
            knee,
            ankle,
            DVec3::new(0.0, 0.03, 0.05),
            DVec3::new(0.0, 0.02, 0.25),
            DVec3::new(0.0, 0.05, 0.06),
        ],
        0.01,
    );
    let p = profile(&points);
    let distal = DVec3::new(0.0, 0.06, 0.05);
    let (found, rule) =
        skelfit::refine::bend(&p, hip, distal, 0.485, 0.005, &RefineOptions::default()).unwrap();
    assert_eq!(rule, skelfit::refine::BendRule::SmallestAngle);
    assert!(found.distance(knee) < 0.02, "{found}");
}

/// The ankle's depth comes from the shin's axis: a straight slanted shin carried down to
/// the ankle's height, whatever the foot does below it.
#[test]
fn the_shin_axis_reaches_down_to_the_ankle_height() {
    let mesh = Mesh::cuboid(DVec3::new(-0.2, 0.0, -0.2), DVec3::new(0.2, 1.8, 0.2));
    let frame = skelfit::refine::BodyFrame::new(&mesh, DVec3::Y, DVec3::Z).unwrap();
    let shin = |y: f64| DVec3::new(0.1 * y, y, 0.2 + 0.05 * y);
    let mut points: Vec<DVec3> = (0..=40).map(|k| shin(0.9 - 0.02 * k as f64)).collect();
    points.extend([DVec3::new(0.01, 0.05, 0.3), DVec3::new(0.01, 0.03, 0.4)]);
    let p = profile(&points);
    let end = p.slices[40].arc;
    let at = skelfit::refine::on_axis(&p, &frame, 0.0, end, 0.005, 0.08).unwrap();
    assert!(at.distance(shin(0.08)) < 1e-3, "{at} vs {}", shin(0.08));
    assert_eq!(
        skelfit::refine::on_axis(&p, &frame, 0.0, 0.005, 0.005, 0.08),
        None
    );
}

/// The median plane (spine, neck) passes through the body's own waist, not through a rough
/// pelvis that sits off the middle: moving the rough pelvis 3 cm sideways moves the refined
/// neck sideways by under 3 mm (it moved about half as far when the plane followed the pelvis).
#[test]
fn an_off_centre_rough_pelvis_does_not_move_the_neck_sideways() {
    let c = bundled();
    let o = RefineOptions::default();
    let neck_x = |rough: &Skeleton| {
        let r = refine(&c.mesh, rough, &c.canonical, DVec3::Y, DVec3::Z, &o).unwrap();
        r.skeleton.joint(c.canonical["neck"]).position.x
    };
    let mut shifted = c.rough.clone();
    shifted.joints[c.canonical["pelvis"].0].position.x += 0.03;
    let (a, b) = (neck_x(&c.rough), neck_x(&shifted));
    assert!((a - b).abs() < 0.003, "neck x {a} vs {b}");
}

/// T-pose (issue 6: "works for A-pose and T-pose bodies"): the bundled A-pose body, rigged,
/// its arms raised to the horizontal through its own skin, and the reference arm joints turned
/// with them; refining the posed fitted skeleton on the posed mesh finds every joint with no
/// fallback and stays close to the turned reference.
#[test]
fn a_t_pose_body_is_refined_like_an_a_pose_one() {
    use skelfit::pipeline::{rig, RigOptions};
    use skelfit::skin::deform;
    let c = bundled();
    let mut options = RigOptions::default();
    options.refine.in_rig = false;
    let r = rig(&c.mesh, &options).unwrap();
    let (skeleton, canonical) = (&r.fit.skeleton, &r.fit.canonical);
    let at = |key: &str| skeleton.joint(canonical[key]).position;
    let mut pose = skeleton.rest_pose();
    let mut turns = Vec::new();
    for (side, sign) in [("L", 1.0), ("R", -1.0)] {
        let shoulder = at(&format!("shoulder_{side}"));
        let arm = at(&format!("wrist_{side}")) - shoulder;
        // The arm's angle below the horizontal, in the frontal plane; turn it up by that much.
        let below = (-arm.y).atan2(arm.x.abs());
        let turn = DQuat::from_rotation_z(sign * below);
        let id = canonical[&format!("shoulder_{side}")];
        let frame = skeleton.world_transforms(&pose)[id.0]
            .to_scale_rotation_translation()
            .1;
        pose[id.0] = frame.inverse() * turn * frame;
        turns.push((side, shoulder, turn));
    }
    let posed_mesh = deform(&c.mesh, skeleton, &r.skin, &pose).unwrap();
    let world = skeleton.world_transforms(&pose);
    let mut posed = skeleton.clone();
    for (j, w) in posed.joints.iter_mut().zip(&world) {
        j.position = w.translation;
    }
    // Both arms now reach out horizontally.
    for (side, _, _) in &turns {
        let s = posed.joint(canonical[&format!("shoulder_{side}")]).position;
        let w = posed.joint(canonical[&format!("wrist_{side}")]).position;
        assert!((w.y - s.y).abs() < 0.02, "{side}: {s} {w}");
    }
    let refined = refine(
        &posed_mesh,
        &posed,
        canonical,
        DVec3::Y,
        DVec3::Z,
        &RefineOptions::default(),
    )
    .unwrap();
    assert!(refined.warnings.is_empty(), "{:?}", refined.warnings);
    // The reference joints, arms turned about our shoulder pivots like the mesh.
    let truth = |key: &str| {
        let p = c.truth.joint(c.canonical[key]).position;
        match turns.iter().find(|(side, _, _)| {
            key.ends_with(side)
                && !key.starts_with("hip")
                && !key.starts_with("knee")
                && !key.starts_with("ankle")
        }) {
            Some((_, pivot, turn)) => *pivot + *turn * (p - *pivot),
            None => p,
        }
    };
    let errors: Vec<f64> = REFINED_KEYS
        .iter()
        .map(|k| {
            refined
                .skeleton
                .joint(canonical[*k])
                .position
                .distance(truth(k))
                * 1000.0
        })
        .collect();
    println!("T-pose errors (mm): {errors:.0?}");
    assert!(mean(&errors) < 15.0, "{errors:?}");
    // Measured 44-54 mm at the shoulders (the skin's blend smears the posed armpit outwards,
    // and the turned reference is only as good as our pivot); 133 mm when the armpit was the
    // highest point of the gap, the far end of a raised arm's underside. 1-11 mm elsewhere.
    for (key, e) in REFINED_KEYS.iter().zip(&errors) {
        let bound = if key.starts_with("shoulder") {
            60.0
        } else {
            20.0
        };
        assert!(*e < bound, "{key}: {e:.0} mm");
    }
}

/// The core mean error (% of height) and warning codes of the bench's anatomical rig of one
/// refdata humanoid, or `None` (skip) without refdata.
use skelfit::skeleton::{Canonical, Side};

fn real_core(model: &str) -> Option<(f64, Vec<String>, skelfit::eval::BenchResult)> {
    use skelfit::eval::{bench_model, find_bench_models, BenchOptions, RigMethod};
    let dir = crate::common::model(&format!("humanoid/{model}"))?;
    let found = find_bench_models(&dir, "game_engine").unwrap();
    let mut options = BenchOptions::default();
    options.rigger.method = RigMethod::Anatomical;
    let result = bench_model(&found[0], &options);
    let core = result.core.as_ref().expect("a core error").mean_percent;
    let codes = result.warnings.iter().map(|w| w.code.clone()).collect();
    Some((core, codes, result))
}

/// A dress hides the crotch: the median silhouette runs below the knees, the refinement says
/// so and places the hips by proportion (quaternius_women_formal: hips at the skirt's hem, 16 %
/// of height low, before; 1.2 % core mean after). MakeHuman bodies show their crotch and keep
/// the slices' hips.
#[test]
fn hips_hidden_by_a_skirt_come_from_the_proportions() {
    let Some((core, codes, result)) = real_core("quaternius_women_formal") else {
        return;
    };
    assert!(codes.iter().any(|c| c == "crotch_hidden"), "{codes:?}");
    let evaluation = result.evaluation.as_ref().unwrap();
    let hip = evaluation
        .joints
        .iter()
        .find(|j| j.key == Canonical::Hip(Side::Left).as_str())
        .expect("hip_L paired");
    assert!(hip.error_percent < 3.0, "hip_L {:.2} %", hip.error_percent);
    assert!(core < 2.0, "core mean {core:.2} %");
    let Some((core, codes, _)) = real_core("mh_neutral_default") else {
        return;
    };
    assert!(!codes.iter().any(|c| c == "crotch_hidden"), "{codes:?}");
    assert!(core < 0.7, "core mean {core:.2} %");
}

/// A dress whose median slice ends on its hem rather than running down between the legs (the
/// dress turned 3° off the file's axes): the hem's flare, with hips there far below where the
/// arms' length puts them, hides the crotch all the same (quaternius_women_formal turned -3°:
/// hips at the hem, 12 % of its height low, core mean 4.65 % before; 1.94 % after). The
/// hips stay within 3 % of the reference's, turned.
#[test]
fn a_dress_turned_off_the_axes_still_hides_the_crotch() {
    use skelfit::pipeline::{rig, RigOptions};
    use skelfit::refine::RefineWarning;
    use skelfit::skeleton::{Canonical, Side};
    use skelfit::warning::Warning;
    let Some(dir) = crate::common::model("humanoid/quaternius_women_formal") else {
        return;
    };
    let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).unwrap();
    let reference = load_skeleton(&dir.join("rig_gltf.json")).unwrap();
    let (map, _) = skelfit::eval::canonical_map(&reference);
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    let height = hi - lo;
    for degrees in [-3.0f64, 3.0] {
        let turn = DQuat::from_rotation_y(degrees.to_radians());
        let turned = crate::common::turned_about_up(&mesh, degrees);
        let r = rig(&turned, &RigOptions::default()).unwrap();
        assert!(
            r.warnings
                .iter()
                .any(|w| matches!(w, Warning::Refine(RefineWarning::CrotchHidden { .. }))),
            "turned {degrees}: the hidden crotch is not reported"
        );
        for side in Side::BOTH {
            let key = Canonical::Hip(side).as_str();
            let at = r.fit.skeleton.joint(r.fit.canonical[key]).position;
            let expected = turn * reference.skeleton.joint(map[key]).position;
            let off = 100.0 * at.distance(expected) / height;
            assert!(
                off < 3.0,
                "turned {degrees}: {key} {off:.2} % of height off"
            );
        }
    }
}

/// A cape: a thin sheet from the shoulder blades down to below the knees, flaring out behind
/// the legs, a piece of its own that pierces the upper back. Where it hangs behind the thighs
/// the legs' labels begin low and the rough hips fall below the crotch; the median
/// silhouette's torso loop is still found (it was refused for not reaching below the rough
/// hips: hips 10 % of the height low, core mean 3.1 % before; 0.6 % after).
#[test]
fn a_cape_behind_the_legs_leaves_the_torso_silhouette_found() {
    use skelfit::pipeline::{rig, RigOptions};
    use skelfit::refine::RefineWarning;
    use skelfit::warning::Warning;
    let dir = crate::common::data_dir().join("humanoid/mh_neutral_default");
    let body = skelfit::mesh::load(&dir.join("mesh.obj")).unwrap();
    // The sheet: top edge 0.36 wide at the upper back, bottom edge 0.52 wide and 0.25 behind
    // the body's middle at 0.5 high, 12 mm thick, closed.
    let (top, bottom, thick) = ((1.42, -0.085, 0.18), (0.5, -0.25, 0.26), 0.012);
    let mut positions = body.positions.clone();
    let base = positions.len() as u32;
    for layer in [0.0, thick] {
        for (y, z, w) in [top, bottom] {
            positions.push(DVec3::new(-w, y, z - layer));
            positions.push(DVec3::new(w, y, z - layer));
        }
    }
    // Corners: layer 0 then 1, each top-left, top-right, bottom-left, bottom-right.
    let quads = [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [1, 5, 7, 3],
        [3, 7, 6, 2],
        [2, 6, 4, 0],
    ];
    let mut triangles = body.triangles.clone();
    for [a, b, c, d] in quads {
        triangles.push([base + a, base + b, base + c]);
        triangles.push([base + a, base + c, base + d]);
    }
    let caped = Mesh::new(positions, triangles).unwrap();
    let r = rig(&caped, &RigOptions::default()).unwrap();
    assert!(
        !r.warnings
            .iter()
            .any(|w| matches!(w, Warning::Refine(RefineWarning::NoTorsoSilhouette))),
        "the torso silhouette is not found"
    );
    let reference = load_skeleton(&dir.join("rig_game_engine.json")).unwrap();
    let (map, _) = skelfit::eval::canonical_map(&reference);
    let height = 1.66;
    let mut errors = Vec::new();
    for key in [
        "pelvis", "hip_L", "hip_R", "knee_L", "knee_R", "neck", "head",
    ] {
        let at = r.fit.skeleton.joint(r.fit.canonical[key]).position;
        let expected = reference.skeleton.joint(map[key]).position;
        errors.push((key, 100.0 * at.distance(expected) / height));
    }
    for (key, e) in &errors {
        assert!(*e < 2.5, "{key} {e:.2} % of height off: {errors:?}");
    }
}

/// A helmet deeper than a human head (quaternius_knight: head and helmet a third of the
/// height) is still sliced down to its neck: the head search reaches the rough shoulders
/// (head joint 13 % of height off before, 6.8 % after; 4.3 % once its visor's edge was no
/// longer taken for a nose).
#[test]
fn a_helmet_deeper_than_a_human_head_is_still_found() {
    let Some((_, codes, result)) = real_core("quaternius_knight") else {
        return;
    };
    assert!(!codes.iter().any(|c| c == "no_head"), "{codes:?}");
    let evaluation = result.evaluation.as_ref().unwrap();
    let head = evaluation
        .joints
        .iter()
        .find(|j| j.key == Canonical::Head.as_str())
        .unwrap();
    assert!(head.error_percent < 5.0, "head {:.2} %", head.error_percent);
}

/// A big head with long ears (quaternius_platformer_character): the ears mirror each other, so
/// neither is the head (the head is the figure's one median part), and they point up, so they
/// are not a second pair of arms beside the sideways T-posed ones. Before: one ear was the
/// head, the other ear and two face bumps were arms; core mean 23 % of height.
#[test]
fn mirrored_ears_are_neither_the_head_nor_arms() {
    let Some((core, _, result)) = real_core("quaternius_platformer_character") else {
        return;
    };
    let parts = &result.anatomy.as_ref().expect("an anatomy").parts;
    let arms = parts.split(", ").filter(|p| p.starts_with("arm")).count();
    assert_eq!(arms, 2, "{parts}");
    assert!(core < 10.0, "core mean {core:.2} %");
}

/// Short thick legs kink where they meet at the crotch: the smallest angle on the thigh then
/// lies at the edge of the window the knee is searched in, which is no knee
/// (quaternius_knight: knees 11 % of height too high before, within 7 % now).
#[test]
fn a_kink_at_the_crotch_is_not_a_knee() {
    let Some((_, _, result)) = real_core("quaternius_knight") else {
        return;
    };
    let evaluation = result.evaluation.as_ref().unwrap();
    for side in Side::BOTH {
        let key = Canonical::Knee(side).as_str();
        let knee = evaluation.joints.iter().find(|j| j.key == key).unwrap();
        assert!(
            knee.error_percent < 7.0,
            "{key} {:.2} %",
            knee.error_percent
        );
    }
}

/// A big cartoon head's shell envelops the top of the trunk, whose back silhouette then runs
/// up the head's back and puts C7 far behind the head joint: the neck comes forward to the
/// cervical column's lean ([`skelfit::refine::NECK_MAX_LEAN_DEGREES`];
/// quaternius_platformer_character: neck 4.60 % of height off, 2.25 % after).
#[test]
fn a_head_shell_around_the_neck_does_not_push_the_neck_back() {
    let Some((_, _, result)) = real_core("quaternius_platformer_character") else {
        return;
    };
    let evaluation = result.evaluation.as_ref().unwrap();
    let neck = evaluation
        .joints
        .iter()
        .find(|j| j.key == Canonical::Neck.as_str())
        .expect("neck paired");
    assert!(neck.error_percent < 3.0, "neck {:.2} %", neck.error_percent);
}

/// A block figure: legs, torso, neck, a head of `head` (its centre and radius) and two ears
/// above the head, one each side of the median plane x = 0.
fn eared_figure(head: Mesh) -> Mesh {
    let b = |lo: [f64; 3], hi: [f64; 3]| Mesh::cuboid(DVec3::from(lo), DVec3::from(hi));
    merged(&[
        b([-0.15, 0.0, -0.06], [-0.03, 0.9, 0.06]),
        b([0.03, 0.0, -0.06], [0.15, 0.9, 0.06]),
        b([-0.18, 0.9, -0.1], [0.18, 1.45, 0.1]),
        b([-0.05, 1.45, -0.05], [0.05, 1.58, 0.05]),
        head,
        b([0.05, 1.7, -0.02], [0.1, 1.95, 0.02]),
        b([-0.1, 1.7, -0.02], [-0.05, 1.95, 0.02]),
    ])
}

/// The head is the figure's one median part: slicing down from the top, the two ears (which
/// mirror each other across the median plane) are skipped and the head's slices begin at the
/// head's own crown (quaternius_platformer_character: the head landed on an ear and was
/// rejected, 21.8 % of height off; 6.1 % now).
#[test]
fn mirrored_ears_above_the_head_are_not_its_slices() {
    let head = Mesh::cuboid(DVec3::new(-0.09, 1.55, -0.1), DVec3::new(0.09, 1.77, 0.1));
    let mesh = eared_figure(head);
    let frame = skelfit::refine::BodyFrame::new(&mesh, DVec3::Y, DVec3::Z).unwrap();
    let options = RefineOptions::default();
    let near = DVec3::new(0.0, 1.66, 0.0);
    let slices = skelfit::refine::head_slices(&mesh, &frame, near, Some(1.45), &options)
        .expect("head slices");
    let first = frame.h(slices.slices[0].points[0]);
    assert!(first < 1.77 && first > 1.75, "first head slice at {first}");
    for s in &slices.slices {
        let xs: Vec<f64> = s.points.iter().map(|p| p.x).collect();
        let (lo, hi) = xs
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(*x), b.max(*x)));
        assert!(
            lo < 0.0 && hi > 0.0,
            "a slice off the median plane: {lo}..{hi}"
        );
    }
}

/// The head joint of `mesh` (a figure whose neck ends at height 1.45) with the head's slices
/// started `near`, at `HeadLevel::Auto`, `NeckTop` and `NoseLevel`.
fn head_joints_by_level(mesh: &Mesh, near: DVec3) -> [DVec3; 3] {
    use skelfit::refine::HeadLevel;
    let frame = skelfit::refine::BodyFrame::new(mesh, DVec3::Y, DVec3::Z).unwrap();
    let slices =
        skelfit::refine::head_slices(mesh, &frame, near, Some(1.45), &RefineOptions::default())
            .expect("head slices");
    [HeadLevel::Auto, HeadLevel::NeckTop, HeadLevel::NoseLevel].map(|level| {
        let options = RefineOptions {
            head_level: level,
            ..RefineOptions::default()
        };
        skelfit::refine::head_joint(mesh, &frame, &slices, Some(1.45), &options)
            .expect("a head joint")
            .joint
    })
}

/// The front of a round head is the cap of a sphere, no nose: the head joint goes at the top of
/// the neck (the game-rig convention), as with `HeadLevel::NeckTop`, not at nose level.
#[test]
fn a_round_head_without_a_nose_has_its_joint_at_the_neck() {
    let head = Mesh::uv_sphere(DVec3::new(0.0, 1.66, 0.0), 0.11, 24, 32);
    let mesh = eared_figure(head);
    let [auto, neck, _] = head_joints_by_level(&mesh, DVec3::new(0.0, 1.66, 0.0));
    assert!(auto.distance(neck) < 1e-9, "auto {auto} vs neck top {neck}");
    assert!(auto.y < 1.62, "head joint at {}", auto.y);
}

/// A figure of blocks (legs, torso) with a neck block 0.12 wide spanning `neck_depth` (back,
/// front) in z from the torso's top at 1.45 up to a head block 0.24 wide and deep centred at
/// (0, 1.72, `head_z`): the head joint at the top of the neck.
fn neck_top_joint(neck_depth: (f64, f64), head_z: f64) -> DVec3 {
    let b = |lo: [f64; 3], hi: [f64; 3]| Mesh::cuboid(DVec3::from(lo), DVec3::from(hi));
    let mesh = merged(&[
        b([-0.15, 0.0, -0.06], [-0.03, 0.9, 0.06]),
        b([0.03, 0.0, -0.06], [0.15, 0.9, 0.06]),
        b([-0.18, 0.9, -0.1], [0.18, 1.45, 0.1]),
        b([-0.06, 1.45, neck_depth.0], [0.06, 1.6, neck_depth.1]),
        b([-0.12, 1.6, head_z - 0.12], [0.12, 1.84, head_z + 0.12]),
    ]);
    let frame = skelfit::refine::BodyFrame::new(&mesh, DVec3::Y, DVec3::Z).unwrap();
    let near = DVec3::new(0.0, 1.7, head_z);
    let options = RefineOptions {
        head_level: skelfit::refine::HeadLevel::NeckTop,
        ..RefineOptions::default()
    };
    let slices = skelfit::refine::head_slices(&mesh, &frame, near, Some(1.45), &options)
        .expect("head slices");
    skelfit::refine::head_joint(&mesh, &frame, &slices, Some(1.45), &options)
        .expect("a head joint")
        .joint
}

/// A hood or helmet hanging down the nape fills the back of the neck's section, whose centroid
/// then lies far behind the skull balanced on it: the joint at the top of the neck comes
/// forward to a tenth of the head's depth behind the skull's centroid
/// ([`skelfit::refine::CONDYLES_BEHIND_CENTROID`]; quaternius_knight: head 4.25 % of height
/// off, 0.24 behind the reference; 2.97 % after). A neck under the skull's centre, or in front
/// of it (a head tilted back), keeps its own axis.
#[test]
fn a_hood_behind_the_neck_does_not_pull_the_head_joint_back() {
    let limit = -skelfit::refine::CONDYLES_BEHIND_CENTROID * 0.24;
    // The neck's block reaches 0.12 behind the head's centre: its centroid is 0.035 behind.
    let hooded = neck_top_joint((-0.12, 0.05), 0.0);
    assert!(
        hooded.z > limit - 0.005 && hooded.z < 0.0,
        "hooded neck's head joint at z {}",
        hooded.z
    );
    let plain = neck_top_joint((-0.06, 0.06), 0.0);
    assert!(
        plain.z.abs() < 0.005,
        "plain neck's head joint at z {}",
        plain.z
    );
    let tilted = neck_top_joint((-0.06, 0.06), -0.04);
    assert!(
        tilted.z.abs() < 0.005,
        "a head behind its neck moved the joint to z {}",
        tilted.z
    );
}

/// Shoulder pads and a chest plate (quaternius_cyberpunk_character: separate shells over the
/// shoulders and a torso box in front of the arms) are not the arm: the shoulder joint is a
/// ball on the upper arm's axis, so the corrections from the surface above it and from the
/// body's depth through it are taken only within an arm's radius of that axis (shoulder_L
/// 7.5 % of height off before, 5.1 % of it forward into the chest box; 6.3 % after).
#[test]
fn shoulder_pads_and_a_chest_plate_do_not_move_the_shoulder_off_the_arm() {
    let Some((_, _, result)) = real_core("quaternius_cyberpunk_character") else {
        return;
    };
    let evaluation = result.evaluation.as_ref().unwrap();
    let shoulder = evaluation
        .joints
        .iter()
        .find(|j| j.key == Canonical::Shoulder(Side::Left).as_str())
        .expect("shoulder_L paired");
    assert!(
        shoulder.error_percent < 7.0,
        "shoulder_L {:.2} %",
        shoulder.error_percent
    );
}

/// The flare of a leg split: two legs as wide and deep together as the trunk they leave run
/// on into it (a short-legged cartoon's crotch, about 1); a skirt standing out around the legs
/// it hides is a hem ([`skelfit::refine::HEM_FLARE`]).
#[test]
fn a_skirt_flares_over_the_legs_and_a_crotch_does_not() {
    use skelfit::refine::{split_flare, HEM_FLARE};
    let b = |lo: [f64; 3], hi: [f64; 3]| Mesh::cuboid(DVec3::from(lo), DVec3::from(hi));
    let legs = [
        b([-0.2, 0.0, -0.1], [-0.02, 0.5, 0.1]),
        b([0.02, 0.0, -0.1], [0.2, 0.5, 0.1]),
    ];
    let crotch = merged(&[
        b([-0.2, 0.5, -0.1], [0.2, 1.5, 0.1]),
        legs[0].clone(),
        legs[1].clone(),
    ]);
    let skirt = merged(&[
        b([-0.3, 0.5, -0.2], [0.3, 1.5, 0.2]),
        legs[0].clone(),
        legs[1].clone(),
    ]);
    let flare = |mesh: &Mesh| {
        let frame = skelfit::refine::BodyFrame::new(mesh, DVec3::Y, DVec3::Z).unwrap();
        split_flare(mesh, &frame, DVec3::new(0.0, 0.5, 0.0), 0.5, 0.015, 0.6).unwrap()
    };
    let (at_crotch, at_hem) = (flare(&crotch), flare(&skirt));
    assert!((at_crotch - 1.0).abs() < 1e-6, "{at_crotch}");
    assert!(at_hem > HEM_FLARE, "{at_hem}");
}

/// A big head (a helmet or a stylised head, sliced down further than `head_max_depth` of the
/// height) with a narrow ridge low on its front: the ridge is no nose, and the head joint goes
/// at the neck's top (quaternius_knight: a visor's edge took the head joint up to nose level,
/// 6.9 % of height too high; 4.3 % off now, in depth only).
#[test]
fn a_ridge_on_a_big_head_is_no_nose() {
    let b = |lo: [f64; 3], hi: [f64; 3]| Mesh::cuboid(DVec3::from(lo), DVec3::from(hi));
    let head = Mesh::uv_sphere(DVec3::ZERO, 1.0, 48, 64).transformed(|p| {
        let (x, y, z) = (0.2 * p.x, 0.3 * p.y, 0.2 * p.z);
        let ridge = (-(x / 0.015).powi(2)).exp() * (-((y + 0.1) / 0.03).powi(2)).exp();
        DVec3::new(x, 1.8 + y, z + if z > 0.0 { 0.05 * ridge } else { 0.0 })
    });
    let mesh = merged(&[
        b([-0.15, 0.0, -0.06], [-0.03, 0.9, 0.06]),
        b([0.03, 0.0, -0.06], [0.15, 0.9, 0.06]),
        b([-0.18, 0.9, -0.1], [0.18, 1.45, 0.1]),
        b([-0.05, 1.45, -0.05], [0.05, 1.55, 0.05]),
        head,
    ]);
    let [auto, neck, nose] = head_joints_by_level(&mesh, DVec3::new(0.0, 1.8, 0.0));
    assert!(nose.y > 1.65, "the ridge's level: {}", nose.y);
    assert!(auto.distance(neck) < 1e-9, "auto {auto} vs neck top {neck}");
    assert!(auto.y < 1.6, "head joint at {}", auto.y);
}

/// Short legs (quaternius_platformer_character, legs 11 % of its height): the rough knees,
/// which the adult leg ratios put above the crotch, made the median silhouette look as if it
/// ran below the knees (a skirt), and the hips stayed where the leg labels begin (hips 9.0 %,
/// pelvis 9.5 % of height off; 4.6 % and 3.9 % now). The legs leave the trunk at the crotch
/// without a hem's flare, so the crotch shows.
#[test]
fn short_legs_show_their_crotch() {
    let Some((core, codes, result)) = real_core("quaternius_platformer_character") else {
        return;
    };
    assert!(!codes.iter().any(|c| c == "crotch_hidden"), "{codes:?}");
    let evaluation = result.evaluation.as_ref().unwrap();
    let error = |key: Canonical| {
        evaluation
            .joints
            .iter()
            .find(|j| j.key == key.as_str())
            .expect("paired")
            .error_percent
    };
    for key in [
        Canonical::Pelvis,
        Canonical::Hip(Side::Left),
        Canonical::Hip(Side::Right),
    ] {
        assert!(error(key) < 6.0, "{} {:.2} %", key.as_str(), error(key));
    }
    assert!(core < 6.5, "core mean {core:.2} %");
}

/// A big head sitting on the trunk with no neck between (quaternius_platformer_character): the
/// neck rises to the junction, the trunk's top, and the head joint goes a neck's length above
/// it (neck 7.6 % and head 6.1 % of height off before, the neck low in the trunk between the
/// arms and the head at the junction; 4.6 % and 2.4 % now).
#[test]
fn a_head_on_its_trunk_keeps_a_neck_below_it() {
    let Some((_, _, result)) = real_core("quaternius_platformer_character") else {
        return;
    };
    let evaluation = result.evaluation.as_ref().unwrap();
    let joint = |key: Canonical| {
        evaluation
            .joints
            .iter()
            .find(|j| j.key == key.as_str())
            .expect("paired")
    };
    let (neck, head) = (joint(Canonical::Neck), joint(Canonical::Head));
    assert!(neck.error_percent < 5.5, "neck {:.2} %", neck.error_percent);
    assert!(head.error_percent < 4.0, "head {:.2} %", head.error_percent);
    assert!(neck.predicted.y < head.predicted.y, "neck above the head");
}

/// Arms modelled as separate pieces sunk into the trunk (quaternius_platformer_character): the
/// slices find no armpit and put the shoulder where the arm leaves the trunk's surface (6.2 %
/// of height off, 0.21 m lateral of the artist's); the arm piece turns about the centre of its
/// buried end (3.8 % now).
#[test]
fn a_buried_arm_piece_puts_its_shoulder_inside_the_trunk() {
    let Some((_, codes, result)) = real_core("quaternius_platformer_character") else {
        return;
    };
    for side in Side::BOTH {
        let error = joint_error(&result, Canonical::Shoulder(side));
        assert!(error < 4.5, "shoulder {side:?} {error:.2} %");
    }
    assert!(!codes.iter().any(|c| c == "no_armpit"), "{codes:?}");
}

/// The error (% of height) of the joint `key` in a bench result.
fn joint_error(result: &skelfit::eval::BenchResult, key: Canonical) -> f64 {
    result
        .evaluation
        .as_ref()
        .unwrap()
        .joints
        .iter()
        .find(|j| j.key == key.as_str())
        .expect("paired")
        .error_percent
}

/// The hips stand above the crotch by a fraction of the trunk (crotch to shoulders), not of the
/// stature: short cartoon legs had their hips and pelvis too high (quaternius_platformer_character
/// pelvis 3.9 % of height off, 2.9 % now) and CesiumMan's pelvis 2.5 % (1.9 % now). Its short,
/// thick legs then give the sphere slices no tube from the lower hips: the knees go by the
/// leg's proportions inside each leg's own section instead of staying at the rough knees in
/// the trunk (7.4 % off, 4.5 % now).
#[test]
fn hips_above_the_crotch_scale_with_the_trunk() {
    let Some((_, codes, result)) = real_core("quaternius_platformer_character") else {
        return;
    };
    assert!(!codes.iter().any(|c| c == "leg_not_sliced"), "{codes:?}");
    let pelvis = joint_error(&result, Canonical::Pelvis);
    assert!(pelvis < 3.4, "platformer pelvis {pelvis:.2} %");
    for side in Side::BOTH {
        let knee = joint_error(&result, Canonical::Knee(side));
        assert!(knee < 5.0, "platformer knee {knee:.2} %");
    }
    let Some((_, _, result)) = real_core("gltf_cesium_man") else {
        return;
    };
    let pelvis = joint_error(&result, Canonical::Pelvis);
    assert!(pelvis < 2.2, "CesiumMan pelvis {pelvis:.2} %");
}

/// A fist (quaternius_platformer_character: round fists, no flat hand) has its wrist at the
/// narrowing before it, not on its cap (3.4 % of height off before, 1.1 % now), and the elbow
/// at the arm ratio along the line from shoulder to wrist (8.6 % off before, 1.9 % now).
#[test]
fn a_fist_has_its_wrist_before_it_and_the_elbow_at_the_arm_ratio() {
    let Some((_, _, result)) = real_core("quaternius_platformer_character") else {
        return;
    };
    for side in Side::BOTH {
        let wrist = joint_error(&result, Canonical::Wrist(side));
        assert!(wrist < 2.0, "wrist {wrist:.2} %");
        let elbow = joint_error(&result, Canonical::Elbow(side));
        assert!(elbow < 3.0, "elbow {elbow:.2} %");
    }
}

/// A head whose long axis turns far from the body's facing (turned on its neck, or made
/// lopsided by hair hanging to one side) leaves the body's frame alone: hair cards turned a
/// bundled body's head frame 30°, every frontal slice of the trunk with it, and the armpits
/// and shoulders were found 9 cm in; a visor turned a game character's by 6° and moved its
/// shoulders 7 cm. A couple of degrees (a figure a little off the file's axes) still set the
/// frame.
#[test]
fn a_head_turned_far_from_the_body_does_not_turn_its_frame() {
    let mesh = Mesh::cuboid(DVec3::new(-0.2, 0.0, -0.2), DVec3::new(0.2, 1.8, 0.2));
    let frame = skelfit::refine::BodyFrame::new(&mesh, DVec3::Y, DVec3::Z).unwrap();
    let head_along = |degrees: f64| {
        let (s, c) = degrees.to_radians().sin_cos();
        let (long, across) = (DVec3::new(s, 0.0, c), DVec3::new(c, 0.0, -s));
        skelfit::refine::HeadSlices {
            slices: (0..5)
                .map(|k| SliceLoop {
                    points: (0..64)
                        .map(|i| {
                            let t = i as f64 / 64.0 * std::f64::consts::TAU;
                            long * (0.10 * t.cos())
                                + across * (0.08 * t.sin())
                                + DVec3::Y * (1.7 - 0.02 * k as f64)
                        })
                        .collect(),
                    closed: true,
                })
                .collect(),
            largest: 0,
            ended_by_shrink: true,
        }
    };
    let f = skelfit::refine::frame_from_head(&frame, &head_along(2.0), DVec3::Z).unwrap();
    assert!(
        f.forward.angle_between(DVec3::Z).to_degrees() > 1.5,
        "{}",
        f.forward
    );
    for degrees in [5.0, -5.0, 30.0, -30.0, 60.0] {
        assert!(
            skelfit::refine::frame_from_head(&frame, &head_along(degrees), DVec3::Z).is_none(),
            "{degrees}"
        );
    }
}

//! General control skeleton (dissertation ch.5.2.4-5.2.5): path trees of analytic shapes,
//! skeletons of the reference models, determinism, bad input.

use crate::common;
use glam::{DQuat, DVec3};
use skelfit::general::{GeneralOptions, GeneralSkeleton};
use skelfit::mesh::{load, Mesh};
use skelfit::paths::PathOptions;
use skelfit::pipeline::{general_skeleton, GeneralSkeletonOptions};
use skelfit::voxel::{voxelize, Solid, VoxelOptions};
use std::time::Instant;

/// Concatenates meshes (overlapping parts are fine: the voxelizer classifies by winding).
fn merge(parts: &[Mesh]) -> Mesh {
    let mut out = Mesh::default();
    for part in parts {
        let base = out.positions.len() as u32;
        out.positions.extend(&part.positions);
        out.triangles
            .extend(part.triangles.iter().map(|t| t.map(|i| i + base)));
    }
    out
}

/// A star of `arms` capsules of radius 0.1 and length 1 from the origin in the XY plane.
fn star(arms: usize) -> Mesh {
    let parts: Vec<Mesh> = (0..arms)
        .map(|k| {
            let angle = std::f64::consts::TAU * k as f64 / arms as f64;
            let rotation = DQuat::from_rotation_z(angle);
            Mesh::capsule(DVec3::ZERO, 0.1, 0.5, 8, 16)
                .transformed(|p| rotation * (p + DVec3::new(0.0, 0.5, 0.0)))
        })
        .collect();
    merge(&parts)
}

/// Whether `p` lies in an interior voxel or within one voxel of one.
fn near_inside(solid: &Solid, p: DVec3) -> bool {
    let grid = &solid.grid;
    let Some(c) = grid.voxel_at(p) else {
        return false;
    };
    (-1..=1).any(|dz| {
        (-1..=1).any(|dy| {
            (-1..=1).any(|dx| {
                grid.offset(c, [dx, dy, dz])
                    .is_some_and(|i| solid.inside[i])
            })
        })
    })
}

fn end_positions(general: &GeneralSkeleton) -> Vec<DVec3> {
    general
        .end_effectors()
        .iter()
        .map(|&j| general.skeleton.joint(j).position)
        .collect()
}

fn nearest(points: &[DVec3], target: DVec3) -> f64 {
    points
        .iter()
        .map(|p| p.distance(target))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn capsule_path_tree_is_one_centred_chain() {
    let mesh = Mesh::capsule(DVec3::ZERO, 0.2, 0.6, 12, 24);
    let general = general_skeleton(&mesh, &GeneralSkeletonOptions::default()).unwrap();
    let tree = &general.path_tree;
    assert_eq!(tree.chains.len(), 1, "{:?}", tree.chains.len());
    let voxel = tree.grid.voxel_size;
    let chain = &tree.chains[0];
    for (i, &v) in chain.voxels.iter().enumerate() {
        let c = tree.grid.centre(tree.grid.coords(v));
        let off_axis = DVec3::new(c.x, 0.0, c.z).length();
        assert!(off_axis <= voxel, "voxel {i} is {off_axis} from the axis");
        let s = chain.smoothed[i];
        assert!(DVec3::new(s.x, 0.0, s.z).length() <= voxel);
    }
    // The chain spans nearly the whole medial axis (|y| <= 0.6).
    let ys: Vec<f64> = chain.smoothed.iter().map(|p| p.y).collect();
    let span =
        ys.iter().cloned().fold(f64::MIN, f64::max) - ys.iter().cloned().fold(f64::MAX, f64::min);
    assert!(span > 1.0, "span {span}");
    assert_eq!(general.end_effectors().len(), 2);
    assert!(general.skeleton.validate().is_ok());
    assert!(general.warnings.is_empty(), "{:?}", general.warnings);
}

#[test]
fn stars_have_one_end_effector_per_arm() {
    for arms in [3, 6] {
        let mesh = star(arms);
        let general = general_skeleton(&mesh, &GeneralSkeletonOptions::default()).unwrap();
        let ends = end_positions(&general);
        assert_eq!(ends.len(), arms, "{arms} arms: ends {ends:?}");
        for k in 0..arms {
            let angle = std::f64::consts::TAU * k as f64 / arms as f64;
            let tip = DQuat::from_rotation_z(angle) * DVec3::new(0.0, 1.0, 0.0);
            assert!(
                nearest(&ends, tip) < 0.15,
                "{arms} arms: arm {k} tip unreached"
            );
        }
        assert!(general.skeleton.validate().is_ok());
    }
}

/// Checks a refdata model's skeleton: joints inside the mesh (asserted), and returns the
/// targets with no end effector within 10% of the figure size (largest bounding-box side).
fn check_model(
    relative: &str,
    options: &GeneralSkeletonOptions,
    targets: impl Fn(&Mesh) -> Vec<(String, DVec3)>,
) -> Vec<String> {
    let Some(dir) = common::model(relative) else {
        return Vec::new();
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let start = Instant::now();
    let general = general_skeleton(&mesh, options).unwrap();
    let elapsed = start.elapsed().as_secs_f64();
    let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
    assert!(general.skeleton.validate().is_ok());
    for joint in &general.skeleton.joints {
        assert!(
            near_inside(&solid, joint.position),
            "{relative}: joint {} at {} is outside the mesh",
            joint.name,
            joint.position
        );
    }
    // Frames (ch.5.2.5): z along each segment from the joint that rotates it (the root's frame
    // follows one of its two halves); proper rotations everywhere.
    let s = &general.skeleton;
    for seg in &general.segments {
        let (joint, child) = (s.joint(seg.joint), s.joint(seg.child));
        let m = s.frame_matrix(seg.joint);
        assert!((m.determinant() - 1.0).abs() < 1e-9);
        let along = (child.position - joint.position).normalize();
        if joint.parent.is_some() {
            assert!(
                m.z_axis.dot(along) > 1.0 - 1e-9,
                "{relative}: {} z axis not along its segment",
                joint.name
            );
        }
        assert!(!seg.voxels.is_empty());
    }
    let (lo, hi) = mesh.bounding_box().unwrap();
    let size = (hi - lo).max_element();
    let ends = end_positions(&general);
    if std::env::var_os("SKELFIT_PRINT_ENDS").is_some() {
        println!(
            "{relative} root {} heart {} ends {ends:?}",
            general.skeleton.joints[0].position, general.path_tree.heart_centre
        );
    }
    let mut report = Vec::new();
    let mut failures = Vec::new();
    // Targets sharing a name are alternatives: the nearest counts.
    let mut best: std::collections::BTreeMap<String, f64> = Default::default();
    for (name, target) in targets(&mesh) {
        let d = nearest(&ends, target) / size;
        let entry = best.entry(name).or_insert(f64::INFINITY);
        *entry = entry.min(d);
    }
    for (name, d) in best {
        report.push(format!("{name} {d:.3}"));
        if d > 0.1 {
            failures.push(format!("{relative}: {name}"));
        }
    }
    println!(
        "{relative}: {:.0} ms ({:?}), {} path-tree voxels, {} joints, {} ends, {} chains; {}",
        elapsed * 1e3,
        general
            .timings
            .iter()
            .map(|(n, t)| format!("{n} {t:.0}"))
            .collect::<Vec<_>>(),
        general.path_tree.voxels.len(),
        general.skeleton.len(),
        ends.len(),
        general.path_tree.chains.len(),
        report.join(", ")
    );
    failures
}

/// Canonical joints of a refdata rig file.
fn canonical(relative: &str, rig: &str, keys: &[&str]) -> Vec<(String, DVec3)> {
    let Some(dir) = common::model(relative) else {
        return Vec::new();
    };
    let rig = skelfit::eval::load_skeleton(&dir.join(rig)).unwrap();
    keys.iter()
        .filter_map(|&k| {
            let id = rig.canonical.get(k)?;
            Some((k.to_string(), rig.skeleton.joint(*id).position))
        })
        .collect()
}

/// Limb ends of a four-legged figure facing +Z with +Y up: the lowest vertex of each
/// quadrant about the bounding-box centre, the most forward vertex (head) and the tail tip:
/// either the last joint of the reference rig whose name contains "tail" (tails may hang down)
/// or the most backward vertex (a rig's last tail joint may sit at the base of the last bone).
fn quadruped_ends(relative: &str, mesh: &Mesh) -> Vec<(String, DVec3)> {
    let (lo, hi) = mesh.bounding_box().unwrap();
    let c = (lo + hi) / 2.0;
    let mut out = Vec::new();
    for (name, sx, sz) in [
        ("foot_FL", 1.0, 1.0),
        ("foot_FR", -1.0, 1.0),
        ("foot_BL", 1.0, -1.0),
        ("foot_BR", -1.0, -1.0),
    ] {
        let foot = mesh
            .positions
            .iter()
            .filter(|p| (p.x - c.x) * sx > 0.0 && (p.z - c.z) * sz > 0.0)
            .min_by(|a, b| a.y.total_cmp(&b.y))
            .copied();
        out.extend(foot.map(|p| (name.to_string(), p)));
    }
    let by_z = |a: &&DVec3, b: &&DVec3| a.z.total_cmp(&b.z);
    out.push(("head".into(), *mesh.positions.iter().max_by(by_z).unwrap()));
    let rig = common::model(relative)
        .and_then(|dir| skelfit::eval::load_skeleton(&dir.join("rig_gltf.json")).ok());
    let tail = rig.and_then(|rig| {
        let joints = rig.skeleton.joints;
        let last = joints.iter().rev();
        last.map(|j| j.position)
            .zip(joints.iter().rev().map(|j| j.name.to_lowercase()))
            .find(|(_, name)| name.contains("tail"))
            .map(|(p, _)| p)
    });
    out.extend(tail.map(|p| ("tail".to_string(), p)));
    out.push(("tail".into(), *mesh.positions.iter().min_by(by_z).unwrap()));
    out
}

const QUADRUPEDS: [&str; 6] = [
    "khronos_fox",
    "quaternius_alpaca",
    "quaternius_deer",
    "quaternius_horse",
    "quaternius_triceratops",
    "quaternius_wolf",
];

const HUMANOIDS: [&str; 6] = [
    "mh_child_10y",
    "mh_female_thin_short",
    "mh_female_young_average",
    "mh_male_heavy_short",
    "mh_male_young_average",
    "mh_neutral_default",
];

/// Humanoid limb ends: the canonical wrists and toes of the reference rig, and the centre of the
/// head, halfway between the rig's `head` joint (at the base of the skull) and the top of the
/// mesh (end effectors lie on the medial surface, about a head radius inside the skull top).
fn humanoid_ends(relative: &str, rig: &str, mesh: &Mesh) -> Vec<(String, DVec3)> {
    let mut targets = canonical(relative, rig, &["wrist_L", "wrist_R", "toe_L", "toe_R"]);
    let top = mesh.positions.iter().max_by(|a, b| a.y.total_cmp(&b.y));
    if let Some((_, head)) = canonical(relative, rig, &["head"]).pop() {
        targets.push(("head".to_string(), (head + *top.unwrap()) / 2.0));
    }
    targets
}

#[test]
fn humanoid_skeletons_reach_hands_feet_and_head() {
    let mut failures = Vec::new();
    let options = GeneralSkeletonOptions::default();
    for model in HUMANOIDS {
        let relative = format!("humanoid/{model}");
        failures.extend(check_model(&relative, &options, |mesh| {
            humanoid_ends(&relative, "rig_game_engine.json", mesh)
        }));
    }
    let relative = "humanoid/gltf_cesium_man";
    failures.extend(check_model(relative, &options, |mesh| {
        humanoid_ends(relative, "rig_gltf.json", mesh)
    }));
    assert!(failures.is_empty(), "no end effector near {failures:?}");
}

#[test]
fn quadruped_skeletons_reach_feet_head_and_tail() {
    let mut failures = Vec::new();
    let options = GeneralSkeletonOptions::default();
    for model in QUADRUPEDS {
        let relative = format!("quadruped/{model}");
        // The alpaca's tail is a stub that protrudes less than 0.1 heart radius beyond the
        // body's coverage: it needs the finer end of the recommended closeness range (0.05).
        let options = GeneralSkeletonOptions {
            paths: PathOptions {
                closeness: if model == "quaternius_alpaca" {
                    0.05
                } else {
                    0.1
                },
                ..Default::default()
            },
            ..options
        };
        failures.extend(check_model(&relative, &options, |mesh| {
            quadruped_ends(&relative, mesh)
        }));
    }
    assert!(failures.is_empty(), "no end effector near {failures:?}");
}

#[test]
fn other_skeletons_lie_inside() {
    let options = GeneralSkeletonOptions::default();
    for model in ["quaternius_snake", "quaternius_spider", "quaternius_trex"] {
        check_model(&format!("other/{model}"), &options, |_| Vec::new());
    }
}

#[test]
fn skeletons_are_identical_on_one_and_two_threads() {
    let Some(dir) = common::model("quadruped/quaternius_horse") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| general_skeleton(&mesh, &GeneralSkeletonOptions::default()).unwrap())
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a.skeleton, b.skeleton);
    assert_eq!(a.segments, b.segments);
    assert_eq!(a.path_tree.voxels, b.path_tree.voxels);
}

#[test]
fn out_of_range_parameters_give_clear_errors() {
    let mesh = Mesh::capsule(DVec3::ZERO, 0.2, 0.6, 8, 16);
    let cases = [
        (
            GeneralSkeletonOptions {
                paths: PathOptions {
                    closeness: 2.0,
                    ..Default::default()
                },
                ..Default::default()
            },
            "closeness of fit 2",
        ),
        (
            GeneralSkeletonOptions {
                general: GeneralOptions {
                    max_fraction: -0.3,
                    ..Default::default()
                },
                ..Default::default()
            },
            "max fraction -0.3",
        ),
        (
            GeneralSkeletonOptions {
                general: GeneralOptions {
                    segments: Some(0),
                    ..Default::default()
                },
                ..Default::default()
            },
            "number of segments 0",
        ),
    ];
    for (options, words) in cases {
        let err = general_skeleton(&mesh, &options).unwrap_err().to_string();
        assert!(err.contains(words), "{err}");
    }
}

#[test]
fn a_tiny_figure_gives_an_error_or_a_warned_one_joint_skeleton() {
    let mesh = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
    for fraction in [0.3, 0.45, 0.9] {
        let options = GeneralSkeletonOptions {
            voxel: VoxelOptions {
                size: skelfit::voxel::VoxelSize::Fraction(fraction),
                ..Default::default()
            },
            ..Default::default()
        };
        match general_skeleton(&mesh, &options) {
            Ok(general) => {
                assert!(general.skeleton.validate().is_ok());
                if general.skeleton.len() == 1 {
                    assert!(!general.warnings.is_empty());
                }
            }
            Err(err) => assert!(!err.to_string().is_empty()),
        }
    }
}

#[test]
fn a_segment_limit_caps_the_skeleton() {
    let mesh = star(3);
    let options = GeneralSkeletonOptions {
        general: GeneralOptions {
            approximation_error: 0.0,
            max_fraction: 0.1,
            segments: Some(5),
            ..Default::default()
        },
        ..Default::default()
    };
    let general = general_skeleton(&mesh, &options).unwrap();
    assert!(
        general.graph.edges.len() <= 5,
        "{}",
        general.graph.edges.len()
    );
    let lowest = GeneralSkeletonOptions {
        general: GeneralOptions {
            root_at_lowest: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let general = general_skeleton(&mesh, &lowest).unwrap();
    let root = general.skeleton.joints[0].position;
    let min_y = general
        .skeleton
        .joints
        .iter()
        .map(|j| j.position.y)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(root.y, min_y);
    assert_eq!(
        general
            .skeleton
            .children(skelfit::skeleton::JointId(0))
            .len(),
        1
    );
}

/// Prints stage timings on a fine grid (about a million interior voxels). Run with
/// `cargo test --release -- --ignored --nocapture general::fine_grid_timings`.
#[test]
#[ignore]
fn fine_grid_timings() {
    let Some(dir) = common::model("humanoid/mh_male_young_average") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    for (fraction, e) in [
        (0.01, 0.4),
        (0.01, 1.0),
        (0.01, 2.0),
        (0.005, 0.4),
        (0.005, 1.0),
        (0.005, 2.0),
    ] {
        let options = GeneralSkeletonOptions {
            voxel: VoxelOptions {
                size: skelfit::voxel::VoxelSize::Fraction(fraction),
                ..Default::default()
            },
            general: GeneralOptions {
                approximation_error: e,
                ..Default::default()
            },
            ..Default::default()
        };
        print!("err {e} ");
        let start = Instant::now();
        let general = general_skeleton(&mesh, &options).unwrap();
        let solid = voxelize(&mesh, &options.voxel).unwrap();
        println!(
            "fraction {fraction}: {} interior voxels, {} path-tree voxels, {} segments, {} joints, {:.0} ms total, {:?}",
            solid.interior_count(),
            general.path_tree.voxels.len(),
            general.segments.len(),
            general.skeleton.len(),
            start.elapsed().as_secs_f64() * 1e3,
            general.timings.iter().map(|(n, t)| format!("{n} {t:.0}")).collect::<Vec<_>>()
        );
    }
}

//! Integration tests of the skin stage.

use crate::common;
use glam::{DQuat, DVec3};
use skelfit::distance::{edt, DistanceMap};
use skelfit::eval::load_skeleton;
use skelfit::mesh::{load, Mesh};
use skelfit::skeleton::{Joint, JointId, Skeleton};
use skelfit::skin::{deform, skin_from_bones, Skin, SkinOptions};
use skelfit::voxel::{voxelize, Solid, VoxelOptions, VoxelSize};

/// A capsule along +Y from -2 to 2 (radius 0.5) with a root-mid-tip chain along its axis;
/// frames point local z along +Y.
pub struct CapsuleRig {
    pub mesh: Mesh,
    pub skeleton: Skeleton,
    pub solid: Solid,
    pub distance: DistanceMap,
}

pub fn capsule_rig() -> CapsuleRig {
    let mesh = Mesh::capsule(DVec3::ZERO, 0.5, 1.5, 8, 24);
    let options = VoxelOptions {
        size: VoxelSize::Fraction(1.0 / 50.0),
        ..Default::default()
    };
    let solid = voxelize(&mesh, &options).unwrap();
    let distance = edt(&solid);
    let frame = DQuat::from_rotation_arc(DVec3::Z, DVec3::Y);
    let joint = |name: &str, parent: Option<usize>, y: f64| Joint {
        frame,
        ..Joint::new(name, parent.map(JointId), DVec3::new(0.0, y, 0.0))
    };
    let skeleton = Skeleton {
        joints: vec![
            joint("root", None, -1.5),
            joint("mid", Some(0), 0.0),
            joint("tip", Some(1), 1.5),
        ],
    };
    CapsuleRig {
        mesh,
        skeleton,
        solid,
        distance,
    }
}

pub fn capsule_skin(rig: &CapsuleRig) -> Skin {
    skin_from_bones(
        &rig.mesh,
        &rig.skeleton,
        &rig.solid,
        &rig.distance,
        &SkinOptions::default(),
    )
    .unwrap()
}

/// Every vertex has positive weights summing to one, sorted by joint, and engine weights
/// summing to one.
fn assert_weights_are_a_partition(skin: &Skin, vertices: usize) {
    assert_eq!(skin.weights.len(), vertices);
    for (v, weights) in skin.weights.iter().enumerate() {
        assert!(!weights.is_empty(), "vertex {v} has no weights");
        assert!(
            weights.iter().all(|&(_, w)| w > 0.0 && w <= 1.0 + 1e-12),
            "vertex {v}: {weights:?}"
        );
        assert!(
            weights.windows(2).all(|p| p[0].0 < p[1].0),
            "vertex {v} unsorted"
        );
        let sum: f64 = weights.iter().map(|(_, w)| w).sum();
        assert!((sum - 1.0).abs() < 1e-12, "vertex {v} sums to {sum}");
        let engine: f32 = skin.engine.weights[v].iter().sum();
        assert!(
            (engine - 1.0).abs() <= 2.0 * f32::EPSILON,
            "vertex {v} engine sum {engine}"
        );
        assert!(skin.engine.weights[v].iter().all(|&w| w >= 0.0));
    }
}

#[test]
fn capsule_weights_are_non_negative_and_sum_to_one() {
    let rig = capsule_rig();
    let skin = capsule_skin(&rig);
    assert_weights_are_a_partition(&skin, rig.mesh.positions.len());
    assert!(skin.warnings.is_empty(), "{:?}", skin.warnings);
    // The ends belong to one joint only.
    for (p, weights) in rig.mesh.positions.iter().zip(&skin.weights) {
        if p.y < -1.2 {
            assert_eq!(weights, &vec![(JointId(0), 1.0)], "at {p}");
        }
        if p.y > 1.0 {
            assert!(
                weights.iter().all(|&(j, _)| j != JointId(0)),
                "at {p}: {weights:?}"
            );
        }
    }
}

#[test]
fn rest_pose_returns_the_input_exactly() {
    let rig = capsule_rig();
    let skin = capsule_skin(&rig);
    let rest = deform(&rig.mesh, &rig.skeleton, &skin, &rig.skeleton.rest_pose()).unwrap();
    assert_eq!(rest, rig.mesh);
}

#[test]
fn bending_the_middle_joint_moves_the_tip_rigidly_and_keeps_the_root() {
    let rig = capsule_rig();
    let skin = capsule_skin(&rig);
    let mut pose = rig.skeleton.rest_pose();
    // Local x is the hinge axis; a quarter turn bends the tip half sideways.
    pose[1] = DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2);
    let bent = deform(&rig.mesh, &rig.skeleton, &skin, &pose).unwrap();
    let world = rig.skeleton.world_transforms(&pose);
    let mid = rig.skeleton.skinning_matrices(&pose)[1];
    // The tip joint swung 90 degrees about the mid joint.
    let tip = world[2].translation;
    assert!(
        (tip.length() - 1.5).abs() < 1e-12 && tip.y.abs() < 1e-12,
        "tip at {tip}"
    );
    let mut moved = 0;
    for (v, (&p, &q)) in rig.mesh.positions.iter().zip(&bent.positions).enumerate() {
        if p.y > 1.0 {
            assert!((q - mid.transform_point3(p)).length() < 1e-12, "vertex {v}");
            moved += 1;
        }
        if p.y < -1.2 {
            assert_eq!(p, q, "vertex {v} at the root moved");
        }
    }
    assert!(moved > 0);
    // Edge lengths of the tip stay the same (rigid motion).
    for t in &rig.mesh.triangles {
        let [a, b] = [t[0] as usize, t[1] as usize];
        if rig.mesh.positions[a].y > 1.0 && rig.mesh.positions[b].y > 1.0 {
            let before = (rig.mesh.positions[a] - rig.mesh.positions[b]).length();
            let after = (bent.positions[a] - bent.positions[b]).length();
            assert!((before - after).abs() < 1e-12);
        }
    }
}

#[test]
fn mismatched_pose_is_an_error_not_a_panic() {
    let rig = capsule_rig();
    let skin = capsule_skin(&rig);
    assert!(deform(&rig.mesh, &rig.skeleton, &skin, &[]).is_err());
    let mut pose = rig.skeleton.rest_pose();
    pose[0].x = f64::NAN;
    assert!(deform(&rig.mesh, &rig.skeleton, &skin, &pose).is_err());
}

#[test]
fn skeleton_outside_the_mesh_is_reported() {
    let rig = capsule_rig();
    let mut skeleton = rig.skeleton.clone();
    for j in &mut skeleton.joints {
        j.position.x += 10.0;
    }
    let err = skin_from_bones(
        &rig.mesh,
        &skeleton,
        &rig.solid,
        &rig.distance,
        &SkinOptions::default(),
    )
    .unwrap_err();
    assert!(err.to_string().contains("inside the mesh"), "{err}");
}

/// The bundled MakeHuman body with its game_engine reference skeleton (deforming joints).
pub fn humanoid() -> (Mesh, Skeleton) {
    let dir = common::data_dir().join("humanoid/mh_neutral_default");
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let rig = load_skeleton(&dir.join("rig_game_engine.json"))
        .unwrap()
        .deforming();
    (mesh, rig.skeleton)
}

#[test]
fn humanoid_weights_are_non_negative_and_sum_to_one() {
    let (mesh, skeleton) = humanoid();
    let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
    let distance = edt(&solid);
    let skin =
        skin_from_bones(&mesh, &skeleton, &solid, &distance, &SkinOptions::default()).unwrap();
    assert_weights_are_a_partition(&skin, mesh.positions.len());
    eprintln!("humanoid skin warnings: {:?}", skin.warnings);
    // The top of the head belongs mostly to the head joint.
    let top = (0..mesh.positions.len())
        .max_by(|&a, &b| mesh.positions[a].y.total_cmp(&mesh.positions[b].y))
        .unwrap();
    let head = skeleton.find("head").unwrap();
    let best = skin.weights[top]
        .iter()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    assert_eq!(best.0, head, "top of head weights {:?}", skin.weights[top]);
    let rest = deform(&mesh, &skeleton, &skin, &skeleton.rest_pose()).unwrap();
    assert_eq!(rest, mesh);
}

#[test]
fn bending_a_humanoid_joint_moves_only_its_own_limb() {
    let (mesh, skeleton) = humanoid();
    let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
    let distance = edt(&solid);
    let skin =
        skin_from_bones(&mesh, &skeleton, &solid, &distance, &SkinOptions::default()).unwrap();
    // (joint, region the moved vertices must lie in: +X is the figure's left, +Y up).
    type Region = fn(DVec3) -> bool;
    let cases: [(&str, Region); 3] = [
        // The left arm from the shoulder joint (x 0.17) out: the elbow's blend, spread over
        // a few voxels (`voxel_smoothing_iterations`), reaches up the short upper arm (a few
        // % halfway), never the torso.
        ("lowerarm_l", |p| p.x > 0.16 && p.y > 0.8),
        // The right leg below mid-thigh: the calf's weight blends into the thigh above the
        // knee (at y 0.48; the hip at 0.9) up to about y 0.7, inner thigh included, never the
        // other leg.
        ("calf_r", |p| p.x < -0.03 && p.y < 0.72),
        ("head", |p| p.y > 1.4 && p.x.abs() < 0.1),
    ];
    for (name, region) in cases {
        let id = skeleton.find(name).unwrap();
        let mut pose = skeleton.rest_pose();
        pose[id.0] = DQuat::from_rotation_x(1.0);
        let bent = deform(&mesh, &skeleton, &skin, &pose).unwrap();
        let moved: Vec<usize> = (0..mesh.positions.len())
            .filter(|&v| bent.positions[v] != mesh.positions[v])
            .collect();
        assert!(
            moved.len() > 500,
            "{name} moved only {} vertices",
            moved.len()
        );
        let outside: Vec<DVec3> = moved
            .iter()
            .map(|&v| mesh.positions[v])
            .filter(|&p| !region(p))
            .collect();
        assert!(
            outside.is_empty(),
            "{name} moved {} vertices outside: {:?}",
            outside.len(),
            &outside[..outside.len().min(20)]
        );
    }
}

#[test]
fn skin_takes_chain_voxels_from_the_skeleton_builder() {
    use skelfit::skin::{skin, SegmentVoxels, SkinError};
    let rig = capsule_rig();
    let grid = rig.solid.grid;
    // Chains as the builder hands them over: the axis voxels below and above the middle joint.
    let axis = |from: f64, to: f64| -> Vec<usize> {
        let mut voxels: Vec<usize> = (0..=40)
            .filter_map(|k| {
                let y = from + (to - from) * k as f64 / 40.0;
                grid.voxel_at(DVec3::new(0.0, y, 0.0))
                    .map(|c| grid.index(c))
            })
            .collect();
        voxels.sort_unstable();
        voxels.dedup();
        voxels
    };
    let segments = vec![
        SegmentVoxels {
            joint: JointId(0),
            child: Some(JointId(1)),
            tip: None,
            voxels: axis(-1.5, 0.0),
        },
        SegmentVoxels {
            joint: JointId(1),
            child: None,
            tip: Some(DVec3::new(0.0, 1.5, 0.0)),
            voxels: axis(0.0, 1.5),
        },
    ];
    let options = SkinOptions::default();
    let bound = skin(
        &rig.mesh,
        &rig.skeleton,
        &rig.solid,
        &rig.distance,
        &segments,
        &options,
    )
    .unwrap();
    assert_weights_are_a_partition(&bound, rig.mesh.positions.len());
    for (p, w) in rig.mesh.positions.iter().zip(&bound.weights) {
        if p.y > 1.0 {
            assert_eq!(w, &vec![(JointId(1), 1.0)]);
        }
    }
    let mut bad = segments.clone();
    bad[1].joint = JointId(7);
    assert!(matches!(
        skin(
            &rig.mesh,
            &rig.skeleton,
            &rig.solid,
            &rig.distance,
            &bad,
            &options
        ),
        Err(SkinError::UnknownJoint {
            segment: 1,
            joint: 7,
            ..
        })
    ));
}

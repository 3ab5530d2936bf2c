//! `skelfit rig --spine full` (issue 25, part 7): the 24 inter-vertebral joints and the sacrum
//! from the pelvis to the head, in order along the back, inside the body, and a 30° forward
//! bend spread over them stretching no mesh edge past 2× (the edge-stretch measure of
//! `skelfit check`, `skin::check`).

use crate::common;
use glam::{DAffine3, DQuat, DVec3};
use skelfit::mesh::{load, load_gltf_scene, winding_number, Mesh};
use skelfit::pipeline::{rig, Rig, RigOptions};
use skelfit::refine::{SpineDetail, GIRDLE_VERTEBRA};
use skelfit::skeleton::canonical::VERTEBRA_NAMES;
use skelfit::skeleton::{JointId, Skeleton};
use skelfit::skin::check::{blend, mesh_edges};
use skelfit::template::Preset;
use std::path::Path;

/// The forward bend of the must-show, degrees, spread evenly over C1..L5 (the sacrum is fused).
const BEND_DEGREES: f64 = 30.0;

fn full_options() -> RigOptions {
    let mut options = RigOptions::default();
    options.refine.spine = SpineDetail::Full;
    options
}

/// World skinning matrices of the forward bend: every vertebral joint but the sacrum turned by
/// its share of `degrees` about the body's left axis through its rest position, composed down
/// the tree (a joint's matrix is its parent's times its own turn).
fn bend_matrices(
    skeleton: &Skeleton,
    vertebrae: &[JointId],
    left: DVec3,
    degrees: f64,
) -> Vec<DAffine3> {
    let moving = &vertebrae[..vertebrae.len() - 1];
    let share = (degrees / moving.len() as f64).to_radians();
    let mut matrices = vec![DAffine3::IDENTITY; skeleton.len()];
    for (k, joint) in skeleton.joints.iter().enumerate() {
        let parent = joint.parent.map_or(DAffine3::IDENTITY, |p| matrices[p.0]);
        matrices[k] = if moving.contains(&JointId(k)) {
            let p = joint.position;
            parent
                * DAffine3::from_translation(p)
                * DAffine3::from_quat(DQuat::from_axis_angle(left, share))
                * DAffine3::from_translation(-p)
        } else {
            parent
        };
    }
    matrices
}

/// The largest posed / rest length of a mesh edge, and the edges past 2×.
fn stretch(mesh: &Mesh, posed: &[DVec3]) -> (f64, usize) {
    let mut worst = 1.0f64;
    let mut over_2 = 0;
    for (a, b) in mesh_edges(mesh) {
        let (a, b) = (a as usize, b as usize);
        let rest = mesh.positions[a].distance(mesh.positions[b]);
        if rest > 0.0 {
            let ratio = posed[a].distance(posed[b]) / rest;
            worst = worst.max(ratio);
            over_2 += usize::from(ratio > 2.0);
        }
    }
    (worst, over_2)
}

/// The engine weights written to the .glb (four per vertex) as `(joint, weight)` lists.
fn written_weights(rig: &Rig) -> Vec<Vec<(JointId, f64)>> {
    let e = &rig.skin.engine;
    e.joints
        .iter()
        .zip(&e.weights)
        .map(|(j, w)| {
            j.iter()
                .zip(w)
                .filter(|(_, w)| **w > 0.0)
                .map(|(j, w)| (JointId(usize::from(*j)), f64::from(*w)))
                .collect()
        })
        .collect()
}

/// Asserts the full spine's invariants on `rig` of `mesh`; returns the bend's worst stretch.
fn check_full_spine(name: &str, mesh: &Mesh, rig: &Rig) -> f64 {
    let s = &rig.fit.skeleton;
    let vertebrae: Vec<JointId> = VERTEBRA_NAMES
        .iter()
        .map(|n| {
            s.find(n)
                .unwrap_or_else(|| panic!("{name}: no joint {n}; warnings {:#?}", rig.warnings))
        })
        .collect();
    let canonical = &rig.fit.canonical;
    let (pelvis, head) = (canonical["pelvis"], canonical["head"]);
    // One chain: head → C1 → ... → L5 → sacrum → pelvis.
    assert_eq!(
        s.joint(head).parent,
        Some(vertebrae[0]),
        "{name}: head on C1"
    );
    for w in vertebrae.windows(2) {
        assert_eq!(
            s.joint(w[0]).parent,
            Some(w[1]),
            "{name}: {}",
            s.joint(w[0]).name
        );
    }
    assert_eq!(
        s.joint(vertebrae[24]).parent,
        Some(pelvis),
        "{name}: sacrum on pelvis"
    );
    assert_eq!(canonical["neck"], vertebrae[6], "{name}: neck is C7");
    for side in ["L", "R"] {
        if let Some(c) = canonical.get(&format!("clavicle_{side}")) {
            assert_eq!(s.joint(*c).parent, s.find(GIRDLE_VERTEBRA), "{name}");
        }
    }
    // In order along the back: each joint below the one above it (head first).
    let up = rig.input.up.normalize();
    let heights: Vec<f64> = std::iter::once(head)
        .chain(vertebrae.iter().copied())
        .map(|j| s.joint(j).position.dot(up))
        .collect();
    for (k, w) in heights.windows(2).enumerate() {
        assert!(
            w[1] < w[0],
            "{name}: {} not below the joint above it ({heights:?})",
            VERTEBRA_NAMES[k]
        );
    }
    // Inside the body: the mesh winds around each joint.
    for (n, &j) in VERTEBRA_NAMES.iter().zip(&vertebrae) {
        let p = s.joint(j).position;
        let w = winding_number(mesh, p);
        assert!(
            w > 0.5,
            "{name}: {n} at {p} is outside the body (winding number {w:.2})"
        );
    }
    // The bend.
    let left = up.cross(rig.input.forward).normalize();
    let matrices = bend_matrices(s, &vertebrae, left, BEND_DEGREES);
    let posed = blend(&mesh.positions, &written_weights(rig), &matrices);
    let (worst, over_2) = stretch(mesh, &posed);
    // The bend moved the head forward: the chain really turned.
    let head_moved =
        matrices[head.0].transform_point3(s.joint(head).position) - s.joint(head).position;
    assert!(
        head_moved.dot(rig.input.forward) > 0.0,
        "{name}: the bend moved the head {head_moved}"
    );
    eprintln!("{name}: full spine ok, {BEND_DEGREES}° forward bend worst edge stretch {worst:.3}, {over_2} edges past 2x");
    assert_eq!(
        over_2, 0,
        "{name}: {over_2} edges past 2x (worst {worst:.2})"
    );
    worst
}

/// Rigs `dir/mesh.obj` with the full spine and checks it.
fn check_model(dir: &Path) -> f64 {
    let name = dir.file_name().unwrap().to_string_lossy().into_owned();
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let rig = rig(&mesh, &full_options()).unwrap();
    check_full_spine(&name, &mesh, &rig)
}

#[test]
fn the_bundled_body_gets_the_full_spine() {
    check_model(&common::data_dir().join("humanoid/mh_neutral_default"));
}

#[test]
fn every_makehuman_body_gets_the_full_spine() {
    let Some(refdata) = common::refdata() else {
        return;
    };
    let mut bodies: Vec<_> = std::fs::read_dir(refdata.join("humanoid"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("mh_"))
        })
        .collect();
    bodies.sort();
    assert!(!bodies.is_empty());
    for dir in bodies {
        check_model(&dir);
    }
}

#[test]
fn the_real_humanoids_get_the_full_spine() {
    let Some(refdata) = common::refdata() else {
        return;
    };
    let mut models: Vec<_> = std::fs::read_dir(refdata.join("humanoid"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            !p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("mh_"))
        })
        .filter(|p| p.join("mesh.obj").is_file())
        .collect();
    models.sort();
    assert!(!models.is_empty());
    for dir in models {
        check_model(&dir);
    }
}

/// `--spine full` writes the vertebrae into the .glb, the skeleton JSON (names and canonical
/// keys) and the BVH; `--spine coarse` is today's output, byte for byte.
#[test]
fn cli_writes_the_full_spine_and_coarse_is_the_default() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = common::data_dir().join("humanoid/mh_neutral_default/mesh.obj");
    let mesh = mesh.to_str().unwrap();
    let path = |f: &str| dir.path().join(f).to_str().unwrap().to_string();
    let run = |stem: &str, extra: &[&str]| {
        let (glb, json, bvh) = (
            path(&format!("{stem}.glb")),
            path(&format!("{stem}.json")),
            path(&format!("{stem}.bvh")),
        );
        let args: Vec<&str> = [
            &[
                "rig",
                mesh,
                "-o",
                &glb,
                "--skeleton-json",
                &json,
                "--bvh",
                &bvh,
            ][..],
            extra,
        ]
        .concat();
        let out = common::skelfit(&args);
        assert!(out.status.success(), "{}", common::stderr(&out));
        [glb, json, bvh].map(|f| std::fs::read(f).unwrap())
    };
    let default = run("default", &[]);
    let coarse = run("coarse", &["--spine", "coarse"]);
    let without_timings = |json: &[u8]| {
        let mut v: serde_json::Value = serde_json::from_slice(json).unwrap();
        v["run"]["timings_ms"] = serde_json::Value::Null;
        v
    };
    assert!(
        default[0] == coarse[0],
        "--spine coarse is the default (.glb)"
    );
    assert!(
        default[2] == coarse[2],
        "--spine coarse is the default (.bvh)"
    );
    assert_eq!(without_timings(&default[1]), without_timings(&coarse[1]));
    let full = run("full", &["--spine", "full"]);

    let json: serde_json::Value = serde_json::from_slice(&full[1]).unwrap();
    let names: Vec<&str> = json["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["name"].as_str().unwrap())
        .collect();
    for v in VERTEBRA_NAMES {
        assert!(names.contains(&v), "{v} in {names:?}");
        assert_eq!(json["canonical"][v], v, "canonical key {v}");
    }
    assert!(
        !names.contains(&"spine_01") && !names.contains(&"neck_01"),
        "{names:?}"
    );
    let t6 = json["joints"]
        .as_array()
        .unwrap()
        .iter()
        .find(|j| j["name"] == "T6")
        .unwrap();
    assert_eq!(t6["dofs"].as_array().unwrap().len(), 3, "{t6}");
    let bvh = String::from_utf8(full[2].clone()).unwrap();
    assert!(
        bvh.contains("JOINT C1") && bvh.contains("JOINT sacrum"),
        "{bvh}"
    );
    let scene = load_gltf_scene(Path::new(&path("full.glb"))).unwrap();
    let skeleton = scene.skeleton.expect("a skeleton in the .glb");
    for v in VERTEBRA_NAMES {
        assert!(skeleton.find(v).is_some(), "{v} in the .glb");
    }
    let coarse_json: serde_json::Value = serde_json::from_slice(&coarse[1]).unwrap();
    assert!(coarse_json["canonical"].get("C1").is_none());
}

/// An engine preset has a fixed skeleton without vertebrae, and the full spine is the
/// refinement's: both combinations are usage errors (exit 2) naming the way out.
#[test]
fn cli_refuses_the_full_spine_with_an_engine_preset_or_without_refinement() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = common::data_dir().join("humanoid/mh_neutral_default/mesh.obj");
    let glb = dir.path().join("out.glb");
    let (mesh, glb) = (mesh.to_str().unwrap(), glb.to_str().unwrap());
    for extra in [&["--preset", "mixamo"][..], &["--refine", "off"]] {
        let args = [&["rig", mesh, "-o", glb, "--spine", "full"][..], extra].concat();
        let out = common::skelfit(&args);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{extra:?}: {}",
            common::stderr(&out)
        );
        assert!(
            common::stderr(&out).contains("--spine full needs"),
            "{}",
            common::stderr(&out)
        );
    }
    assert!(!Path::new(glb).exists());
    let mut options = full_options();
    options.fit.preset = Preset::Unreal;
    assert!(options.validate().is_err());
}

/// A figure that is not a humanoid keeps its coarse spine, with a warning saying why.
#[test]
fn a_quadruped_keeps_its_spine_with_a_warning() {
    let mesh = load(&common::data_dir().join("quadruped/quaternius_horse/mesh.obj")).unwrap();
    let rig = rig(&mesh, &full_options()).unwrap();
    assert!(rig.fit.skeleton.find("T1").is_none());
    assert!(
        rig.warnings.iter().any(|w| w.code() == "coarse_spine_kept"),
        "{:?}",
        rig.warnings
    );
}

//! Integration tests of the exporters: round trips through the `gltf` crate and
//! `skelfit::eval::load_skeleton`, determinism, and the Khronos validator when installed.

use crate::skin::{capsule_rig, capsule_skin, humanoid};
use skelfit::distance::edt;
use skelfit::eval::load_skeleton;
use skelfit::export::{
    bvh_text, glb_bytes, obj_text, skeleton_json, write_bvh, write_glb, write_obj,
    write_skeleton_json, BvhOptions, ExportError, GltfOptions, JsonOptions,
};
use skelfit::mesh::{load, Mesh};
use skelfit::skeleton::Skeleton;
use skelfit::skin::{skin_from_bones, Skin, SkinOptions};
use skelfit::voxel::{voxelize, VoxelOptions};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Reads a GLB back with the `gltf` crate and checks joints, positions and weights.
fn assert_glb_round_trips(bytes: &[u8], mesh: &Mesh, skeleton: &Skeleton, skin: &Skin) {
    let (document, buffers, _) = gltf::import_slice(bytes).unwrap();
    assert_eq!(document.skins().count(), 1);
    let gltf_skin = document.skins().next().unwrap();
    let names: Vec<String> = gltf_skin
        .joints()
        .map(|n| n.name().unwrap().to_owned())
        .collect();
    let expected: Vec<String> = skeleton.joints.iter().map(|j| j.name.clone()).collect();
    assert_eq!(names, expected);
    let node = document.nodes().find(|n| n.mesh().is_some()).unwrap();
    assert!(node.skin().is_some());
    let scene = document.default_scene().unwrap();
    assert!(
        scene.nodes().any(|n| n.index() == node.index()),
        "mesh node at the root"
    );
    let primitive = node.mesh().unwrap().primitives().next().unwrap();
    let reader = primitive.reader(|b| Some(&buffers[b.index()]));
    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    assert_eq!(positions.len(), mesh.positions.len());
    for (p, q) in positions.iter().zip(&mesh.positions) {
        let p = glam::Vec3::from_array(*p).as_dvec3();
        assert!((p - *q).length() < 1e-6 * (1.0 + q.length()));
    }
    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    assert_eq!(
        indices,
        mesh.triangles.iter().flatten().copied().collect::<Vec<_>>()
    );
    let joints: Vec<[u16; 4]> = reader.read_joints(0).unwrap().into_u16().collect();
    let weights: Vec<[f32; 4]> = reader.read_weights(0).unwrap().into_f32().collect();
    assert_eq!(joints, skin.engine.joints);
    for (w, e) in weights.iter().zip(&skin.engine.weights) {
        for k in 0..4 {
            assert!((w[k] - e[k]).abs() < 1e-6);
        }
    }
    // The bind pose read back by the eval loader puts every joint where it was.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rig.glb");
    std::fs::write(&path, bytes).unwrap();
    let rig = load_skeleton(&path).unwrap();
    assert_eq!(rig.skeleton.len(), skeleton.len());
    for (a, b) in rig.skeleton.joints.iter().zip(&skeleton.joints) {
        assert_eq!(a.name, b.name);
        assert_eq!(a.parent, b.parent, "{}", a.name);
        assert!((a.position - b.position).length() < 1e-5, "{}", a.name);
    }
}

#[test]
fn capsule_glb_round_trips_through_the_gltf_crate() {
    let rig = capsule_rig();
    let skin = capsule_skin(&rig);
    let bytes = glb_bytes(&rig.mesh, &rig.skeleton, &skin, &GltfOptions::default()).unwrap();
    assert_glb_round_trips(&bytes, &rig.mesh, &rig.skeleton, &skin);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("capsule.glb");
    write_glb(
        &path,
        &rig.mesh,
        &rig.skeleton,
        &skin,
        &GltfOptions::default(),
    )
    .unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), bytes);
}

/// The whole chain voxelize → skin → GLB, run on a pool of `threads` threads.
fn humanoid_glb(threads: usize) -> (Vec<u8>, Mesh, Skeleton, Skin) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let (mesh, skeleton) = humanoid();
        let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
        let distance = edt(&solid);
        let skin =
            skin_from_bones(&mesh, &skeleton, &solid, &distance, &SkinOptions::default()).unwrap();
        let bytes = glb_bytes(&mesh, &skeleton, &skin, &GltfOptions::default()).unwrap();
        (bytes, mesh, skeleton, skin)
    })
}

#[test]
fn humanoid_glb_round_trips_and_is_identical_on_one_and_two_threads() {
    let (one, mesh, skeleton, skin) = humanoid_glb(1);
    let (two, ..) = humanoid_glb(2);
    assert!(one == two, "GLB bytes differ between 1 and 2 threads");
    assert_glb_round_trips(&one, &mesh, &skeleton, &skin);
}

/// The validator script, run on `files`; `None` (skip) when node or the validator is missing.
pub(crate) fn validate(files: &[PathBuf]) -> Option<String> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/validate_gltf.mjs");
    let output = match Command::new("node").arg(&script).args(files).output() {
        Ok(output) => output,
        Err(e) => {
            eprintln!(
                "SKIPPED: node not available ({e}); install Node.js to run the glTF validator"
            );
            return None;
        }
    };
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    match output.status.code() {
        Some(0) => Some(stdout),
        Some(2) => {
            eprintln!("SKIPPED: glTF validator not run: {stderr}");
            None
        }
        _ => panic!("glTF validator reported errors:\n{stdout}\n{stderr}"),
    }
}

#[test]
fn glb_files_pass_the_khronos_validator() {
    let dir = tempfile::tempdir().unwrap();
    let rig = capsule_rig();
    let skin = capsule_skin(&rig);
    let capsule = dir.path().join("capsule.glb");
    write_glb(
        &capsule,
        &rig.mesh,
        &rig.skeleton,
        &skin,
        &GltfOptions::default(),
    )
    .unwrap();
    let (bytes, ..) = humanoid_glb(2);
    let human = dir.path().join("humanoid.glb");
    std::fs::write(&human, bytes).unwrap();
    // Two roots: the capsule chain plus a free-standing control joint that deforms nothing.
    let mut forest = rig.skeleton.clone();
    forest.joints.push(skelfit::skeleton::Joint {
        deform: false,
        ..skelfit::skeleton::Joint::new("ik_target", None, glam::DVec3::new(1.0, 0.0, 0.0))
    });
    let two_roots = dir.path().join("two_roots.glb");
    write_glb(
        &two_roots,
        &rig.mesh,
        &forest,
        &skin,
        &GltfOptions::default(),
    )
    .unwrap();
    // Keep the files for inspection (e.g. a Blender import) when asked to.
    if let Some(keep) = std::env::var_os("SKELFIT_KEEP_EXPORTS") {
        for file in [&capsule, &human, &two_roots] {
            std::fs::copy(file, Path::new(&keep).join(file.file_name().unwrap())).unwrap();
        }
    }
    if let Some(report) = validate(&[capsule, human, two_roots]) {
        eprintln!("{report}");
        assert_eq!(report.matches("numErrors=0 ").count(), 3, "{report}");
    }
}

#[test]
fn skeleton_json_round_trips_through_load_skeleton() {
    let (_, skeleton) = humanoid();
    let mut canonical = BTreeMap::new();
    canonical.insert("pelvis".to_owned(), "pelvis".to_owned());
    canonical.insert("head".to_owned(), "head".to_owned());
    let options = JsonOptions {
        model: Some("mh".into()),
        units: Some("m".into()),
        canonical,
        ..Default::default()
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("skeleton.json");
    write_skeleton_json(&path, &skeleton, &options).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text, skeleton_json(&skeleton, &options).unwrap());
    assert!(text.contains("\"format\": \"skelfit-skeleton-v1\""));
    let rig = load_skeleton(&path).unwrap();
    assert_eq!(rig.units.as_deref(), Some("m"));
    assert_eq!(rig.model, "mh");
    assert_eq!(rig.canonical["head"], skeleton.find("head").unwrap());
    assert_eq!(rig.skeleton.len(), skeleton.len());
    for (a, b) in rig.skeleton.joints.iter().zip(&skeleton.joints) {
        assert_eq!(a.name, b.name);
        assert_eq!(a.parent, b.parent);
        assert_eq!(a.position, b.position, "positions read back bit for bit");
        assert_eq!(a.deform, b.deform);
    }
    // Frames and DOFs are in the file too.
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["joints"][0]["frame"].as_array().unwrap().len(), 4);
    assert!(json["joints"][0]["dofs"].is_array());
    // Unknown canonical joints are an error.
    let bad = JsonOptions {
        canonical: [("pelvis".to_owned(), "nope".to_owned())].into(),
        ..Default::default()
    };
    assert!(skeleton_json(&skeleton, &bad).is_err());
}

#[test]
fn bvh_round_trips_through_load_skeleton() {
    let (_, skeleton) = humanoid();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("skeleton.bvh");
    write_bvh(&path, &skeleton, &BvhOptions::default()).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text, bvh_text(&skeleton, &BvhOptions::default()).unwrap());
    assert!(text.contains("MOTION\nFrames: 1\n"));
    // One motion value per channel.
    let channels: usize = text
        .lines()
        .filter_map(|l| l.trim().strip_prefix("CHANNELS "))
        .map(|l| {
            l.split_whitespace()
                .next()
                .unwrap()
                .parse::<usize>()
                .unwrap()
        })
        .sum();
    assert_eq!(
        text.lines().last().unwrap().split_whitespace().count(),
        channels
    );
    let rig = load_skeleton(&path).unwrap();
    for joint in &skeleton.joints {
        let id = rig.skeleton.find(&joint.name).expect(&joint.name);
        let read = rig.skeleton.joint(id);
        assert!(
            (read.position - joint.position).length() < 1e-5,
            "{}",
            joint.name
        );
        let parent = |s: &Skeleton, p: Option<skelfit::skeleton::JointId>| {
            p.map(|p| s.joint(p).name.clone())
        };
        assert_eq!(
            parent(&rig.skeleton, read.parent),
            parent(&skeleton, joint.parent)
        );
        assert!(read.deform);
    }
    // Only the leaves' end sites were added, as non-deforming joints.
    let extra: Vec<_> = rig
        .skeleton
        .joints
        .iter()
        .filter(|j| skeleton.find(&j.name).is_none())
        .collect();
    assert!(extra.iter().all(|j| !j.deform && j.name.ends_with("_end")));
    // A BVH read back and written again keeps its end sites as end sites.
    let again = bvh_text(&rig.skeleton, &BvhOptions::default()).unwrap();
    assert_eq!(
        again.matches("End Site").count(),
        text.matches("End Site").count()
    );
}

#[test]
fn obj_round_trips_through_the_mesh_loader() {
    let rig = capsule_rig();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("capsule.obj");
    write_obj(&path, &rig.mesh).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), obj_text(&rig.mesh));
    let back = load(&path).unwrap();
    assert_eq!(back.triangles.len(), rig.mesh.triangles.len());
}

#[test]
fn exporters_report_bad_input_and_leave_no_file() {
    let rig = capsule_rig();
    let skin = capsule_skin(&rig);
    let options = GltfOptions::default();
    let mut fewer = rig.mesh.clone();
    fewer.positions.pop();
    assert!(matches!(
        glb_bytes(&fewer, &rig.skeleton, &skin, &options),
        Err(ExportError::SizeMismatch { .. })
    ));
    let empty = Skeleton::default();
    assert!(matches!(
        glb_bytes(&rig.mesh, &empty, &skin, &options),
        Err(ExportError::EmptySkeleton)
    ));
    let mut renamed = rig.skeleton.clone();
    renamed.joints[1].name = "bad\nname".into();
    assert!(matches!(
        bvh_text(&renamed, &BvhOptions::default()),
        Err(ExportError::InvalidName { .. })
    ));
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no/such/folder/out.glb");
    let err = write_glb(&missing, &rig.mesh, &rig.skeleton, &skin, &options).unwrap_err();
    assert!(matches!(err, ExportError::Io { .. }), "{err}");
    assert!(err.to_string().starts_with("cannot write"));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// Every refdata model with a mesh and a reference rig: skin it to its own deforming joints
/// with the bone fallback, check the weights, and validate the GLB.
#[test]
fn refdata_models_skin_and_export_valid_glb() {
    let Some(refdata) = crate::common::refdata() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    for kind in ["humanoid", "quadruped", "other"] {
        let Ok(entries) = std::fs::read_dir(refdata.join(kind)) else {
            continue;
        };
        let mut models: Vec<PathBuf> = entries.map(|e| e.unwrap().path()).collect();
        models.sort();
        for model in models {
            let Some(rig_path) = std::fs::read_dir(&model)
                .unwrap()
                .map(|e| e.unwrap().path())
                .filter(|p| {
                    let name = p.file_name().unwrap().to_string_lossy();
                    name.starts_with("rig_") && name.ends_with(".json")
                })
                .min()
            else {
                continue;
            };
            let mesh_path = model.join("mesh.obj");
            if !mesh_path.is_file() {
                continue;
            }
            let mesh = load(&mesh_path).unwrap();
            let skeleton = load_skeleton(&rig_path).unwrap().deforming().skeleton;
            let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
            let distance = edt(&solid);
            let skin =
                skin_from_bones(&mesh, &skeleton, &solid, &distance, &SkinOptions::default())
                    .unwrap_or_else(|e| panic!("{}: {e}", model.display()));
            for (v, w) in skin.weights.iter().enumerate() {
                let sum: f64 = w.iter().map(|(_, x)| x).sum();
                assert!(
                    !w.is_empty() && (sum - 1.0).abs() < 1e-12,
                    "{} vertex {v}",
                    model.display()
                );
            }
            let name = model.file_name().unwrap().to_string_lossy().into_owned();
            eprintln!(
                "{name}: {} vertices, {} joints, warnings {:?}",
                mesh.positions.len(),
                skeleton.len(),
                skin.warnings
            );
            let path = dir.path().join(format!("{name}.glb"));
            write_glb(&path, &mesh, &skeleton, &skin, &GltfOptions::default()).unwrap();
            if let Some(keep) = std::env::var_os("SKELFIT_KEEP_EXPORTS") {
                std::fs::copy(&path, Path::new(&keep).join(path.file_name().unwrap())).unwrap();
            }
            files.push(path);
        }
    }
    if let Some(report) = validate(&files) {
        assert_eq!(
            report.matches("numErrors=0 ").count(),
            files.len(),
            "{report}"
        );
    }
}

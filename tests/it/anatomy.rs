//! Body-part labelling (dissertation ch.7): the reference humanoids and quadrupeds, rotation,
//! determinism across thread counts, bad input.
//!
//! Per-vertex agreement: each mesh vertex's reference region is the region of the nearest bone
//! of the model's reference rig (`rig_game_engine.json` for MakeHuman, else `rig_gltf.json`);
//! the joint → region rule (canonical keys first, then words of the joint name, then the
//! parent's region; a bone carries its parent joint's region) is documented and unit-tested in
//! `src/anatomy/reference.rs`. Arms and front legs are both *fore limbs*.

use crate::common;
use glam::{DQuat, DVec3};
use skelfit::anatomy::{
    agreement, label, labels_json, AnatomyWarning, FigureClass, Forward, Label, LabelOptions,
    LabelPipelineOptions, Labelling, LimbPair, Side,
};
use skelfit::eval::{load_skeleton, reference_regions};
use skelfit::mesh::{load, Mesh};
use skelfit::warning::Warning;
use std::path::Path;

/// The labelling stages with `label` and every voxel stage's defaults.
fn stages(label: LabelOptions) -> LabelPipelineOptions {
    LabelPipelineOptions {
        label,
        ..Default::default()
    }
}

fn labelled(dir: &Path, options: &LabelOptions) -> (Mesh, Labelling) {
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let labels = label(&mesh, &stages(*options)).unwrap();
    (mesh, labels)
}

fn agreement_percent(dir: &Path, mesh: &Mesh, labels: &Labelling) -> f64 {
    let rig = ["rig_game_engine.json", "rig_gltf.json"]
        .iter()
        .map(|n| dir.join(n))
        .find(|p| p.is_file())
        .unwrap();
    let rig = load_skeleton(&rig).unwrap();
    agreement(labels, &reference_regions(&rig, mesh)).percent
}

/// The one part with `label` and `side` (and `pair` when given); panics with the parts listed.
fn one(labels: &Labelling, label_: Label, side: Option<Side>, pair: Option<LimbPair>) -> usize {
    let found: Vec<usize> = (0..labels.parts.len())
        .filter(|&i| {
            let p = &labels.parts[i];
            p.label == label_ && p.side == side && (pair.is_none() || p.limb_pair == pair)
        })
        .collect();
    assert_eq!(
        found.len(),
        1,
        "{label_:?} {side:?} {pair:?}: {:?}",
        labels
            .parts
            .iter()
            .map(|p| (p.label, p.side, p.limb_pair))
            .collect::<Vec<_>>()
    );
    found[0]
}

/// Minimum per-vertex agreement (%) asserted per humanoid: 95 as the issue asks, except where
/// we measured less (see reports/labels/labels.md). CesiumMan measures 95.47 % (74.0 % before
/// the neck went to the head, `RuleOptions::neck_in_head`, 94.95 % before the arms' roots inside
/// the chest went to the trunk, `RuleOptions::pectoral_root_scale`).
const HUMANOIDS: &[(&str, f64)] = &[
    ("gltf_cesium_man", 95.0),
    ("mh_child_10y", 95.0),
    ("mh_female_thin_short", 95.0),
    ("mh_female_young_average", 95.0),
    ("mh_male_heavy_short", 95.0),
    ("mh_male_young_average", 95.0),
    ("mh_neutral_default", 95.0),
];

#[test]
fn humanoids_have_a_head_a_trunk_two_arms_and_two_legs() {
    for &(name, minimum) in HUMANOIDS {
        let Some(dir) = common::model(&format!("humanoid/{name}")) else {
            return;
        };
        let (mesh, labels) = labelled(&dir, &LabelOptions::default());
        assert_eq!(labels.figure, FigureClass::HumanLike, "{name}");
        assert_eq!(labels.count(Label::Trunk), 1, "{name}");
        assert_eq!(labels.count(Label::Head), 1, "{name}");
        assert_eq!(labels.count(Label::Arm), 2, "{name}");
        assert_eq!(labels.count(Label::Leg), 2, "{name}");
        assert_eq!(labels.count(Label::Tail), 0, "{name}");
        // Left is +X: the left limbs end on the +X side.
        for label_ in [Label::Arm, Label::Leg] {
            let l = one(&labels, label_, Some(Side::Left), None);
            let r = one(&labels, label_, Some(Side::Right), None);
            assert!(labels.parts[l].distal.x > 0.0, "{name} {label_:?} L");
            assert!(labels.parts[r].distal.x < 0.0, "{name} {label_:?} R");
        }
        let head = one(&labels, Label::Head, None, None);
        let trunk = &labels.parts[0];
        assert!(labels.parts[head].distal.y > trunk.attachment.y, "{name}");
        let percent = agreement_percent(&dir, &mesh, &labels);
        println!("{name}: {percent:.1} % of vertices agree");
        assert!(percent >= minimum, "{name}: {percent:.1} % < {minimum} %");
    }
}

/// Minimum per-vertex agreement (%) per quadruped, as measured (reports/labels/labels.md):
/// below the 95 % on these low-poly models, where a few vertices at each limb's root
/// are a large share (the Quaternius rigs start the legs inside the body, e.g. the horse's
/// hind leg bone begins at the top of the haunch; the triceratops' `FrontLeg.*`/`BackLeg.*`
/// bones run from the body's midline to the shoulders and hips, so its chest and belly count
/// as legs). The triceratops measured 88.1 % before the neck went to the head (91.1 % after).
const QUADRUPEDS: &[(&str, f64)] = &[
    ("khronos_fox", 89.0),
    ("quaternius_alpaca", 92.0),
    ("quaternius_deer", 91.0),
    ("quaternius_horse", 93.0),
    ("quaternius_triceratops", 90.0),
    ("quaternius_wolf", 90.0),
];

#[test]
fn quadrupeds_have_a_head_a_trunk_four_legs_and_a_tail() {
    for &(name, minimum) in QUADRUPEDS {
        let Some(dir) = common::model(&format!("quadruped/{name}")) else {
            return;
        };
        let (mesh, labels) = labelled(&dir, &LabelOptions::default());
        assert_eq!(labels.figure, FigureClass::AnimalLike, "{name}");
        assert_eq!(labels.count(Label::Trunk), 1, "{name}");
        assert_eq!(labels.count(Label::Head), 1, "{name}");
        assert_eq!(labels.count(Label::Leg), 4, "{name}");
        assert_eq!(labels.count(Label::Arm), 0, "{name}");
        // Every reference quadruped has tail joints.
        assert_eq!(labels.count(Label::Tail), 1, "{name}");
        let mut z = std::collections::BTreeMap::new();
        for pair in [LimbPair::Fore, LimbPair::Hind] {
            let l = one(&labels, Label::Leg, Some(Side::Left), Some(pair));
            let r = one(&labels, Label::Leg, Some(Side::Right), Some(pair));
            assert!(labels.parts[l].distal.x > 0.0, "{name} {pair:?} L");
            assert!(labels.parts[r].distal.x < 0.0, "{name} {pair:?} R");
            z.insert(pair, labels.parts[l].distal.z + labels.parts[r].distal.z);
        }
        assert!(
            z[&LimbPair::Fore] > z[&LimbPair::Hind],
            "{name}: fore legs in front"
        );
        let head = &labels.parts[one(&labels, Label::Head, None, None)];
        let tail = &labels.parts[one(&labels, Label::Tail, None, None)];
        assert!(
            head.distal.z > tail.distal.z,
            "{name}: head in front of tail"
        );
        let percent = agreement_percent(&dir, &mesh, &labels);
        println!("{name}: {percent:.1} % of vertices agree");
        assert!(percent >= minimum, "{name}: {percent:.1} % < {minimum} %");
    }
}

/// A tail resting on the ground reaches the bottom of the figure like a leg but lies on the
/// median plane, where no leg has a mirror partner: the rat's was paired with a hind leg
/// (five legs, one unpaired) until legs on that plane stayed single for the tail rule.
#[test]
fn a_tail_lying_on_the_ground_is_a_tail_not_a_fifth_leg() {
    let Some(dir) = common::model("quadruped/quaternius_rat") else {
        return;
    };
    let (_, labels) = labelled(&dir, &LabelOptions::default());
    assert_eq!(labels.count(Label::Tail), 1, "{:?}", parts(&labels));
    let tail = &labels.parts[one(&labels, Label::Tail, None, None)];
    assert!(
        tail.distal.x.abs() < 0.05 * labels_extent(&labels),
        "tail off the median plane"
    );
    for p in labels.parts.iter().filter(|p| p.label == Label::Leg) {
        assert!(
            p.side.is_some() && p.limb_pair.is_some(),
            "an unpaired leg: {:?}",
            parts(&labels)
        );
    }
}

/// The largest distance between two parts' distal ends: a size for tolerances.
fn labels_extent(labels: &Labelling) -> f64 {
    let ends: Vec<DVec3> = labels.parts.iter().map(|p| p.distal).collect();
    ends.iter()
        .flat_map(|a| ends.iter().map(move |b| a.distance(*b)))
        .fold(0.0, f64::max)
}

/// Regression: CesiumMan's hair (protrusions behind the head, merged into the trunk beyond the
/// arms' junction) and neck were labelled trunk, 512 of its 1388 head vertices.
#[test]
fn cesium_man_neck_and_back_of_head_are_labelled_head() {
    let Some(dir) = common::model("humanoid/gltf_cesium_man") else {
        return;
    };
    let (mesh, labels) = labelled(&dir, &LabelOptions::default());
    let rig = load_skeleton(&dir.join("rig_gltf.json")).unwrap();
    let a = agreement(&labels, &reference_regions(&rig, &mesh));
    let (_, n, k) = a.per_region.iter().find(|r| r.0 == "head").unwrap().clone();
    println!("cesium_man head: {k}/{n}");
    assert!(k as f64 >= 0.99 * n as f64, "head {k}/{n}");
    // The parts (which the anatomical fit reads) keep the neck in the trunk.
    let mut options = LabelOptions::default();
    options.rules.neck_in_head = false;
    let kept = label(&mesh, &stages(options)).unwrap();
    assert_eq!(kept.voxel_parts, labels.voxel_parts);
    let a = agreement(&kept, &reference_regions(&rig, &mesh));
    let (_, _, k_kept) = a.per_region.iter().find(|r| r.0 == "head").unwrap().clone();
    assert!(
        k_kept < k,
        "head {k_kept} without the neck rule, {k} with it"
    );
}

/// Labels as comparable tuples.
fn parts(labels: &Labelling) -> Vec<(Label, Option<Side>, Option<LimbPair>)> {
    let mut v: Vec<_> = labels
        .parts
        .iter()
        .map(|p| (p.label, p.side, p.limb_pair))
        .collect();
    v.sort();
    v
}

#[test]
fn a_figure_rotated_to_z_up_gets_the_same_labels() {
    for model in [
        "humanoid/mh_male_young_average",
        "quadruped/quaternius_horse",
    ] {
        let Some(dir) = common::model(model) else {
            return;
        };
        let (mesh, labels) = labelled(&dir, &LabelOptions::default());
        // +Y up → +Z up: a quarter turn about +X sends +Y to +Z and +Z (forward) to −Y.
        let turn = DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2);
        let rotated = mesh.transformed(|p| turn * p);
        let options = LabelOptions {
            up: skelfit::anatomy::Up::Direction(DVec3::Z),
            forward: Forward::Direction(DVec3::NEG_Y),
            ..Default::default()
        };
        let turned = label(&rotated, &stages(options)).unwrap();
        assert_eq!(turned.figure, labels.figure, "{model}");
        assert_eq!(parts(&turned), parts(&labels), "{model}");
        // Same region per vertex (part indices may be ordered alike; compare by label/side).
        let key = |l: &Labelling, i: usize| {
            let p = &l.parts[l.mesh_parts[i] as usize];
            (p.label, p.side, p.limb_pair)
        };
        let same = (0..mesh.positions.len())
            .filter(|&i| key(&labels, i) == key(&turned, i))
            .count();
        let percent = 100.0 * same as f64 / mesh.positions.len() as f64;
        println!("{model}: {percent:.2} % of vertices keep their label");
        // The rotated mesh voxelizes on a grid shifted by a fraction of a voxel, so a few
        // vertices at part boundaries change; measured 98.6 % (humanoid) and 97.3 % (horse),
        // 99.6 % and 97.9 % with the bone-following labels below.
        assert!(percent >= 96.0, "{model}: {percent:.2} %");
        // The default, bone-following labels (`skelfit label`) too.
        let rig_options = |label: LabelOptions| skelfit::pipeline::RigOptions {
            label,
            ..Default::default()
        };
        let bones = skelfit::pipeline::label_by_bones(&mesh, &rig_options(LabelOptions::default()))
            .unwrap();
        let turned_bones =
            skelfit::pipeline::label_by_bones(&rotated, &rig_options(options)).unwrap();
        assert_eq!(parts(&turned_bones), parts(&bones), "{model}");
        let same = (0..mesh.positions.len())
            .filter(|&i| key(&bones, i) == key(&turned_bones, i))
            .count();
        let percent = 100.0 * same as f64 / mesh.positions.len() as f64;
        println!("{model}: {percent:.2} % of vertices keep their bone-following label");
        assert!(percent >= 96.0, "{model}: {percent:.2} %");
    }
}

#[test]
fn labels_are_identical_on_one_and_two_threads() {
    let Some(dir) = common::model("quadruped/khronos_fox") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let medial = labels_json(
                &label(&mesh, &LabelPipelineOptions::default()).unwrap(),
                None,
            );
            let bones = skelfit::pipeline::label_by_bones(&mesh, &Default::default()).unwrap();
            (medial.to_string(), labels_json(&bones, None).to_string())
        })
    };
    let one_thread = run(1);
    assert_eq!(one_thread, run(2));
    assert_eq!(one_thread, run(2));
}

/// Concatenates meshes (overlaps are fine: the voxelizer classifies by winding).
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

#[test]
fn a_sphere_has_no_trunk_and_says_so() {
    let mesh = Mesh::uv_sphere(DVec3::ZERO, 1.0, 24, 48);
    let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
    assert_eq!(labels.figure, FigureClass::Unknown);
    assert_eq!(labels.parts[0].label, Label::Trunk);
    assert_eq!(labels.mesh_parts.len(), mesh.positions.len());
    assert!(
        labels
            .warnings
            .iter()
            .any(|w| matches!(w, Warning::Anatomy(AnatomyWarning::NoMajorJunction))),
        "{:?}",
        labels.warnings
    );
}

#[test]
fn three_legs_are_labelled_with_an_odd_leg_warning() {
    // A horizontal body along Z with three vertical legs (two at the front, one at the back)
    // and a head on it (a head apart from the body would be joined to it across the gap).
    let body = Mesh::capsule(DVec3::ZERO, 0.25, 0.6, 8, 16).transformed(|p| {
        DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2) * p + DVec3::new(0.0, 1.0, 0.0)
    });
    let leg = |x: f64, z: f64| Mesh::capsule(DVec3::new(x, 0.55, z), 0.08, 0.45, 8, 16);
    let head = Mesh::uv_sphere(DVec3::new(0.0, 1.2, 0.85), 0.22, 12, 24);
    let mesh = merge(&[body, leg(0.15, 0.5), leg(-0.15, 0.5), leg(0.0, -0.5), head]);
    let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
    assert_eq!(labels.count(Label::Leg), 3, "{:?}", parts(&labels));
    assert!(
        labels
            .warnings
            .iter()
            .any(|w| w.to_string().contains("odd number of legs")),
        "{:?}",
        labels.warnings
    );
}

#[test]
fn the_spider_gets_a_best_effort_with_a_warning() {
    let Some(dir) = common::model("other/quaternius_spider") else {
        return;
    };
    let (mesh, labels) = labelled(&dir, &LabelOptions::default());
    assert_eq!(labels.mesh_parts.len(), mesh.positions.len());
    assert!(labels.count(Label::Leg) > 4, "{:?}", parts(&labels));
    assert!(
        labels
            .warnings
            .iter()
            .any(|w| w.to_string().contains("not vertebrate-like")),
        "{:?}",
        labels.warnings
    );
}

/// An open mouth's lower jaw, a median section leaving the trunk beside the head and reaching
/// forward below it, is the jaw (head region), not a leftover merged into the trunk: the
/// snake's mandible and tongue scored as trunk against the artist's `LowerMouth`/`Tongue`.
#[test]
fn an_open_mouths_lower_jaw_is_the_jaw() {
    for model in ["other/quaternius_snake", "other/quaternius_trex"] {
        let Some(dir) = common::model(model) else {
            return;
        };
        let (_, labels) = labelled(&dir, &LabelOptions::default());
        assert_eq!(labels.count(Label::Jaw), 1, "{model}: {:?}", parts(&labels));
        assert_eq!(
            labels.count(Label::Head),
            1,
            "{model}: {:?}",
            parts(&labels)
        );
    }
}

/// Paired legs mirror each other across the median plane: a spider's eight legs pair left
/// with right, not with their neighbours along one side (which leave the trunk closer to each
/// other than to their partners: the nearest-attachment pairing put `FrontLeg.R` with
/// `MidFrontLeg.R` and gave both sides one label, weight share 24.2 %). Every leg part's
/// vertices lie on its side, and the anterior half of the four pairs are fore legs, as the
/// artist's `FrontLeg`/`MidFrontLeg` against `MidBackLeg`/`BackLeg`.
#[test]
fn a_spiders_legs_pair_across_the_median_plane() {
    let Some(dir) = common::model("other/quaternius_spider") else {
        return;
    };
    let (mesh, labels) = labelled(&dir, &LabelOptions::default());
    let left = labels.frame.left;
    let centre = mesh.positions.iter().sum::<DVec3>() / mesh.positions.len() as f64;
    let mut legs = 0;
    for (i, part) in labels.parts.iter().enumerate() {
        if part.label != Label::Leg {
            continue;
        }
        legs += 1;
        let sign = match part.side {
            Some(Side::Left) => 1.0,
            Some(Side::Right) => -1.0,
            None => panic!("leg {i} without a side: {:?}", parts(&labels)),
        };
        let (on_side, all) = mesh
            .positions
            .iter()
            .zip(&labels.mesh_parts)
            .filter(|(_, &p)| p as usize == i)
            .fold((0, 0), |(k, n), (x, _)| {
                (k + usize::from(sign * (*x - centre).dot(left) > 0.0), n + 1)
            });
        assert!(
            all > 0 && on_side == all,
            "leg {i} ({:?}): {on_side} of {all} vertices on its side",
            part.side
        );
    }
    assert_eq!(legs, 8, "{:?}", parts(&labels));
    for side in [Side::Left, Side::Right] {
        for pair in [LimbPair::Fore, LimbPair::Hind] {
            let n = labels
                .parts
                .iter()
                .filter(|p| {
                    p.label == Label::Leg && p.side == Some(side) && p.limb_pair == Some(pair)
                })
                .count();
            assert_eq!(n, 2, "{side:?} {pair:?}: {:?}", parts(&labels));
        }
    }
}

/// Runs `skelfit label MESH -o JSON ARGS...`, asserts success and returns the JSON.
fn run_label(mesh: &Path, json: &Path, args: &[&str]) -> serde_json::Value {
    let (mesh, json_path) = (mesh.to_str().unwrap(), json.to_str().unwrap());
    let out = common::skelfit(&[&["label", mesh, "-o", json_path], args].concat());
    assert!(out.status.success(), "{}", common::stderr(&out));
    serde_json::from_slice(&std::fs::read(json).unwrap()).unwrap()
}

/// `vertex_labels` line up with the file's own `v` statements, whatever order the faces use
/// them in: `tobj` numbers an OBJ's vertices by first use, and the labels once came out in
/// that order. The file here lists its faces backwards (so first use is far from file order),
/// splits one vertex into two `v` statements and adds one no face uses.
#[test]
fn cli_vertex_labels_follow_the_files_vertex_order() {
    let source =
        std::fs::read_to_string(common::data_dir().join("quadruped/quaternius_horse/mesh.obj"))
            .unwrap();
    let vertices: Vec<&str> = source.lines().filter(|l| l.starts_with("v ")).collect();
    let faces: Vec<&str> = source.lines().filter(|l| l.starts_with("f ")).collect();
    let mut text: String = vertices.iter().map(|v| format!("{v}\n")).collect();
    // A copy of vertex 1 (file index len) used by the first face listed; then an unused one.
    let split = vertices.len();
    text.push_str(&format!("{}\n", vertices[0]));
    text.push_str("v 1000 1000 1000\n");
    for (k, f) in faces.iter().rev().enumerate() {
        if k == 0 {
            let words: Vec<String> = f
                .split_whitespace()
                .skip(1)
                .map(|w| match w.split('/').next() {
                    Some("1") => (split + 1).to_string(),
                    Some(i) => i.to_string(),
                    None => String::new(),
                })
                .collect();
            text.push_str(&format!("f {}\n", words.join(" ")));
        } else {
            text.push_str(&format!("{f}\n"));
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("reordered.obj");
    std::fs::write(&mesh, text).unwrap();
    let json = dir.path().join("labels.json");
    let doc = run_label(&mesh, &json, &[]);
    let labels = doc["vertex_labels"].as_array().unwrap();
    assert_eq!(
        labels.len(),
        vertices.len() + 2,
        "one label per v statement"
    );
    assert!(labels[split + 1].is_null(), "the unused vertex has no part");
    assert_eq!(labels[split], labels[0], "a split vertex keeps its part");
    let parts = doc["parts"].as_array().unwrap();
    let label_of = |i: usize| {
        let p = &parts[labels[i].as_u64().unwrap() as usize];
        (
            p["label"].as_str().unwrap().to_string(),
            p["limb_pair"].as_str().map(str::to_string),
        )
    };
    let position = |i: usize| -> Vec<f64> {
        vertices[i]
            .split_whitespace()
            .skip(1)
            .map(|w| w.parse().unwrap())
            .collect()
    };
    let extreme = |axis: usize, sign: f64| {
        (0..vertices.len())
            .max_by(|&a, &b| (sign * position(a)[axis]).total_cmp(&(sign * position(b)[axis])))
            .unwrap()
    };
    // The horse faces +Z with its tail at -Z and its hooves on the ground.
    assert_eq!(label_of(extreme(2, 1.0)).0, "head");
    assert_eq!(label_of(extreme(1, -1.0)).0, "leg");
    let hindmost = label_of(extreme(2, -1.0)).0;
    assert!(hindmost == "tail" || hindmost == "leg", "{hindmost}");
    assert_eq!(
        label_of(extreme(1, 1.0)).0,
        "head",
        "the ears are the highest point"
    );
}

#[test]
fn cli_label_writes_json_ply_and_svg_and_guesses_forward() {
    let mesh = common::data_dir().join("humanoid/mh_neutral_default/mesh.obj");
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("labels.json");
    let ply = dir.path().join("labels.ply");
    let svg = dir.path().join("labels.svg");
    let doc = run_label(
        &mesh,
        &json,
        &[
            "--ply",
            ply.to_str().unwrap(),
            "--svg",
            svg.to_str().unwrap(),
            "--up",
            "+Y",
            "--forward",
            "auto",
        ],
    );
    assert_eq!(doc["figure"], "human-like");
    let parts = doc["parts"].as_array().unwrap();
    let count = |label: &str| parts.iter().filter(|p| p["label"] == label).count();
    assert_eq!((count("head"), count("arm"), count("leg")), (1, 2, 2));
    let vertices = load(&mesh).unwrap().positions.len();
    assert_eq!(doc["vertex_labels"].as_array().unwrap().len(), vertices);
    // Forward is found from the feet: +Z, the file's convention, so no warning, but the
    // choice and its confidence are in the JSON.
    let forward = doc["forward"].as_array().unwrap();
    assert!(forward[2].as_f64().unwrap() > 0.9, "{forward:?}");
    let found = &doc["forward_found"];
    assert!(found["confidence"].as_f64().unwrap() > 0.3, "{found}");
    assert!(found["note"].as_str().unwrap().contains("feet"), "{found}");
    assert!(!doc["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|w| w["code"] == "forward_guessed"));
    let ply = std::fs::read_to_string(&ply).unwrap();
    assert!(ply.starts_with("ply\n") && ply.contains("property uchar red"));
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("<circle"));
    // A bad direction is a usage error with a message.
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_skelfit"))
        .args([
            "label",
            mesh.to_str().unwrap(),
            "-o",
            json.to_str().unwrap(),
            "--up",
            "sideways",
        ])
        .output()
        .unwrap();
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("sideways"));
}

#[test]
fn an_override_relabels_a_section() {
    let Some(dir) = common::model("quadruped/quaternius_horse") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
    let tail = one(&labels, Label::Tail, None, None);
    let point = labels.parts[tail].distal.to_array();
    let overrides: skelfit::anatomy::Overrides = serde_json::from_value(serde_json::json!({
        "sections": [{"point": point, "label": "trunk"}]
    }))
    .unwrap();
    let fixed = skelfit::anatomy::label_with_overrides(
        &mesh,
        &LabelPipelineOptions::default(),
        Some(&overrides),
    )
    .unwrap();
    assert_eq!(fixed.count(Label::Tail), 0);
    assert_eq!(fixed.count(Label::Leg), 4);
    assert!(fixed.parts[0].vertex_count > labels.parts[0].vertex_count);
}

#[test]
fn flat_paired_protrusions_are_wings() {
    // A horizontal body along Z, two legs, a head in front and two flat plates sideways.
    let body = Mesh::capsule(DVec3::ZERO, 0.25, 0.5, 8, 16).transformed(|p| {
        DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2) * p + DVec3::new(0.0, 1.0, 0.0)
    });
    let leg = |x: f64| Mesh::capsule(DVec3::new(x, 0.5, -0.2), 0.08, 0.4, 8, 16);
    let head = Mesh::uv_sphere(DVec3::new(0.0, 1.3, 0.9), 0.22, 12, 24);
    let left = Mesh::cuboid(DVec3::new(0.1, 0.96, -0.2), DVec3::new(1.1, 1.04, 0.3));
    let right = Mesh::cuboid(DVec3::new(-1.1, 0.96, -0.2), DVec3::new(-0.1, 1.04, 0.3));
    let mesh = merge(&[body, leg(0.12), leg(-0.12), head, left, right]);
    let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
    assert_eq!(
        labels.count(Label::Wing),
        2,
        "{:?} {:?}",
        parts(&labels),
        labels.warnings
    );
    let l = one(&labels, Label::Wing, Some(Side::Left), None);
    assert!(labels.parts[l].distal.x > 0.5);
    assert_eq!(labels.count(Label::Leg), 2, "{:?}", parts(&labels));
    assert_eq!(labels.count(Label::Head), 1, "{:?}", parts(&labels));
}

/// Per-vertex labels that follow the fitted skeleton (`pipeline::label_by_bones`, the CLI's
/// default): the same parts as the medial labels, every vertex counted once, and on the
/// bundled bodies (no refdata needed) closer to the reference rig than the medial labels
/// (measured: MakeHuman neutral 99.3 % against 96.1 %, horse 93.9 % against 94.6 %, where the
/// Quaternius rig starts its fore legs at the armpit; reports/labels/labels.md).
#[test]
fn bone_following_labels_on_the_bundled_bodies() {
    use skelfit::pipeline::{label_by_bones, RigOptions};
    for (model, floor) in [
        ("humanoid/mh_neutral_default", 98.5),
        ("quadruped/quaternius_horse", 93.0),
    ] {
        let dir = common::data_dir().join(model);
        let (mesh, medial) = labelled(&dir, &LabelOptions::default());
        let bones = label_by_bones(&mesh, &RigOptions::default()).unwrap();
        assert_eq!(parts(&bones), parts(&medial), "{model}");
        assert_eq!(bones.voxel_parts, medial.voxel_parts, "{model}");
        let counted: usize = bones.parts.iter().map(|p| p.vertex_count).sum();
        assert_eq!(counted, mesh.positions.len(), "{model}");
        for (i, p) in bones.parts.iter().enumerate() {
            let n = bones
                .mesh_parts
                .iter()
                .filter(|&&q| q as usize == i)
                .count();
            assert_eq!(p.vertex_count, n, "{model} part {i}");
        }
        let b = agreement_percent(&dir, &mesh, &bones);
        let m = agreement_percent(&dir, &mesh, &medial);
        println!("{model}: bones {b:.1} %, medial {m:.1} %");
        assert!(b >= floor, "{model}: {b:.1} % < {floor} %");
    }
}

/// Bone-following labels on every humanoid, quadruped and tessellation variant of refdata,
/// as measured in reports/labels/labels.md (skips without refdata). The fox and the
/// triceratops gain most (95.9 and 93.5 % against 90.7 % medial; the fox's spine and head on
/// the median plane cost it 0.3 points); the Quaternius quadrupeds
/// stay below 95 % (90.9-93.9 %), see the table's notes.
#[test]
fn bone_following_labels_on_refdata() {
    use skelfit::pipeline::{label_by_bones, RigOptions};
    let floors: &[(&str, f64)] = &[
        // 93.1 since the head joint sits at the top of the neck (head error 2.9 -> 0.8 % of
        // height); why the better joint agrees less with the artist's weights is not analysed.
        ("humanoid/gltf_cesium_man", 93.0),
        ("humanoid/mh_child_10y", 98.0),
        ("humanoid/mh_female_thin_short", 98.0),
        ("humanoid/mh_female_young_average", 98.0),
        ("humanoid/mh_male_heavy_short", 98.0),
        ("humanoid/mh_male_young_average", 98.0),
        ("quadruped/khronos_fox", 95.5),
        ("quadruped/quaternius_alpaca", 90.0),
        ("quadruped/quaternius_deer", 90.5),
        ("quadruped/quaternius_horse", 93.0),
        // 91.3 since the quadruped spine sinks from the hips to the middle of the chest
        // (`axial.dorsal_taper`; CD-J2J 3.31 -> 3.29 %): the triceratops' reference legs run
        // horizontally from the body's midline, so its nearest-bone rule counts the chest as
        // legs, and a lower chest spine moves that boundary.
        ("quadruped/quaternius_triceratops", 91.0),
        ("quadruped/quaternius_wolf", 90.5),
        ("robustness/mh_male_young_average_altdiag", 97.5),
        ("robustness/mh_male_young_average_dec12k", 97.5),
        ("robustness/mh_male_young_average_dec6k", 97.5),
        ("robustness/mh_male_young_average_dec3k", 97.5),
        ("robustness/mh_male_young_average_dec3k_fastsimp", 97.5),
        ("robustness/mh_male_young_average_isoremesh", 97.5),
        ("robustness/mh_male_young_average_subdiv_loop1", 97.5),
    ];
    for &(model, floor) in floors {
        let Some(dir) = common::model(model) else {
            return;
        };
        let mesh = load(&dir.join("mesh.obj")).unwrap();
        let bones = label_by_bones(&mesh, &RigOptions::default()).unwrap();
        let b = agreement_percent(&dir, &mesh, &bones);
        println!("{model}: {b:.1} %");
        assert!(b >= floor, "{model}: {b:.1} % < {floor} %");
    }
}

/// The artist's skin weights of a glTF reference (read with the mesh, `GltfScene::weights`)
/// give nearly the same body regions as the nearest-bone rule on CesiumMan (measured 97.8 %),
/// and the weights of every skinned vertex sum to one. A wrong joint numbering (skin order vs
/// skeleton order) or a wrong vertex order would break both.
#[test]
fn skin_weight_regions_agree_with_the_nearest_bone_on_cesium_man() {
    use skelfit::anatomy::{weight_regions, Region};
    let Some(dir) = common::model("humanoid/gltf_cesium_man") else {
        return;
    };
    let scene = skelfit::mesh::load_gltf_scene(&dir.join("source.glb")).unwrap();
    let skeleton = scene.skeleton.unwrap();
    let weights = scene.weights.unwrap();
    assert_eq!(weights.len(), scene.mesh.positions.len());
    for w in &weights {
        let sum: f64 = w.iter().map(|(_, x)| x).sum();
        assert!((sum - 1.0).abs() < 1e-9, "{w:?}");
    }
    let reference = load_skeleton(&dir.join("rig_gltf.json")).unwrap();
    let canonical = reference
        .canonical
        .iter()
        .filter_map(|(k, id)| {
            Some((
                k.clone(),
                skeleton.find(&reference.skeleton.joints[id.0].name)?,
            ))
        })
        .collect();
    let by_weight = weight_regions(&skeleton, &canonical, &weights);
    let nearest = reference_regions(&reference, &scene.mesh);
    let both: Vec<(Region, Region)> = nearest
        .iter()
        .zip(&by_weight)
        .filter_map(|(a, b)| Some(((*a)?, (*b)?)))
        .collect();
    assert!(both.len() > scene.mesh.positions.len() * 9 / 10);
    let same = both.iter().filter(|(a, b)| a == b).count() as f64 / both.len() as f64;
    println!("nearest bone vs skin weights: {:.1} %", 100.0 * same);
    assert!(same > 0.95, "{same}");
    // The top of the head moves with a head joint.
    let top = (0..scene.mesh.positions.len())
        .max_by(|&a, &b| {
            scene.mesh.positions[a]
                .y
                .total_cmp(&scene.mesh.positions[b].y)
        })
        .unwrap();
    assert_eq!(by_weight[top], Some(Region::Head));
}

/// A sphere (no limbs, no head) gets a trunk-only rig, and every vertex the trunk.
#[test]
fn bone_following_labels_of_a_sphere_are_all_trunk() {
    use skelfit::pipeline::{label_by_bones, RigOptions};
    let mesh = Mesh::uv_sphere(DVec3::ZERO, 1.0, 16, 32);
    let labels = label_by_bones(&mesh, &RigOptions::default()).unwrap();
    assert_eq!(labels.mesh_parts.len(), mesh.positions.len());
    assert!(labels.mesh_parts.iter().all(|&p| p == 0));
    assert_eq!(labels.parts[0].label, Label::Trunk);
    assert_eq!(labels.parts[0].vertex_count, mesh.positions.len());
}

/// A sauropod's fore legs hold under 2 % of its medial voxels beside the long neck and tail,
/// too few for a major junction by size alone: the trunk stopped at the hind legs and the neck
/// with both fore legs became one "leg". Regions reaching the ground make a junction.
#[test]
fn small_fore_legs_beside_a_long_neck_are_legs_and_the_neck_carries_the_head() {
    let Some(dir) = common::model("quadruped/quaternius_apatosaurus") else {
        return;
    };
    let (_, labels) = labelled(&dir, &LabelOptions::default());
    for pair in [LimbPair::Fore, LimbPair::Hind] {
        for side in [Side::Left, Side::Right] {
            let leg = &labels.parts[one(&labels, Label::Leg, Some(side), Some(pair))];
            assert!(
                leg.distal.y < 0.2 * labels_extent(&labels),
                "{pair:?} {side:?} leg does not reach the ground: {:?}",
                leg.distal
            );
        }
    }
    let head = &labels.parts[one(&labels, Label::Head, None, None)];
    let tail = &labels.parts[one(&labels, Label::Tail, None, None)];
    assert!(
        head.distal.z > 0.0 && tail.distal.z < 0.0,
        "{:?}",
        parts(&labels)
    );
}

/// An animal standing on two leg pairs has no arms: the rat's thigh bulges and the stag's
/// antlers were paired as arms (six limbs on a four-legged body).
#[test]
fn a_four_legged_animal_has_no_arms() {
    for model in ["quadruped/quaternius_rat", "quadruped/quaternius_stag"] {
        let Some(dir) = common::model(model) else {
            return;
        };
        let (_, labels) = labelled(&dir, &LabelOptions::default());
        assert_eq!(labels.count(Label::Arm), 0, "{model}: {:?}", parts(&labels));
        assert_eq!(labels.count(Label::Leg), 4, "{model}: {:?}", parts(&labels));
    }
}

/// The default per-vertex labels (`label_by_skin`: each vertex the part of the bones carrying
/// most of its skin weight) score against the artists' own weights (issue 21, item 6) at least
/// as well as the nearest-bone labels of the same rig wherever the nearest bone is not the one
/// that moves the vertex: a big head over short limbs (platformer: 80.1 → 90.6 % measured),
/// a fox's legs against its belly (87.7 → 93.4 %). A figure no template fits keeps its medial
/// labels instead of one part for every vertex (snake: 4.4 → 84.3 %; 91.7 % once its open
/// mouth's mandible is the jaw, not trunk; spider: 24.2 → 45.7 % once its legs pair across the
/// median plane and its four pairs divide into two fore and two hind).
#[test]
fn skin_following_labels_score_on_the_artists_weights() {
    use skelfit::eval::label_score;
    use skelfit::pipeline::{label_by_bones, label_by_skin, RigOptions};
    let floors: &[(&str, f64)] = &[
        ("humanoid/quaternius_platformer_character", 87.0),
        ("humanoid/gltf_cesium_man", 93.5),
        ("quadruped/khronos_fox", 92.0),
        ("other/quaternius_snake", 90.0),
        ("other/quaternius_spider", 44.0),
    ];
    for &(model, floor) in floors {
        let Some(dir) = common::model(model) else {
            return;
        };
        let mesh = load(&dir.join("mesh.obj")).unwrap();
        let share = |labels| {
            label_score(&dir, &mesh, &labels, None)
                .unwrap()
                .and_then(|s| s.weight_share)
                .map(|w| w.percent)
                .expect("artist weights")
        };
        let skin = share(label_by_skin(&mesh, &RigOptions::default()).unwrap());
        let nearest = share(label_by_bones(&mesh, &RigOptions::default()).unwrap());
        println!("{model}: skin {skin:.1} %, nearest bone {nearest:.1} %");
        assert!(skin >= floor, "{model}: {skin:.1} % < {floor} %");
        assert!(
            skin + 0.5 >= nearest,
            "{model}: {skin:.1} % < {nearest:.1} %"
        );
    }
}

/// A capsule of `radius` from `from` to `to`.
fn limb(from: DVec3, to: DVec3, radius: f64) -> Mesh {
    let axis = to - from;
    let turn = DQuat::from_rotation_arc(DVec3::Y, axis.normalize());
    let centre = 0.5 * (from + to);
    Mesh::capsule(DVec3::ZERO, radius, 0.5 * axis.length(), 8, 16)
        .transformed(|p| turn * p + centre)
}

/// A raptor-like biped facing +Z: a horizontal body on two hind legs, a long tail, a neck and
/// head rising in front, and `extras` (short arms, a single bump, ears) added to it.
fn biped_with(extras: &[Mesh]) -> Mesh {
    let mut parts = vec![
        limb(
            DVec3::new(0.0, 1.0, -0.45),
            DVec3::new(0.0, 1.0, 0.45),
            0.25,
        ),
        limb(
            DVec3::new(0.0, 1.05, -0.5),
            DVec3::new(0.0, 1.15, -1.8),
            0.12,
        ),
        limb(DVec3::new(0.0, 1.1, 0.5), DVec3::new(0.0, 1.45, 0.95), 0.12),
        Mesh::uv_sphere(DVec3::new(0.0, 1.5, 1.1), 0.18, 12, 24),
    ];
    for x in [0.18, -0.18] {
        parts.push(limb(
            DVec3::new(x, 0.95, -0.15),
            DVec3::new(x * 1.1, 0.08, -0.1),
            0.09,
        ));
    }
    parts.extend(extras.iter().cloned());
    merge(&parts)
}

/// A biped whose heart lies at its hips: a short body on two hind legs, a long heavy tail, and
/// in front one long piece rising from the hips to the head (chest and neck), carrying the
/// `extras`. Its short arms branch off the head's section, not off the trunk.
fn long_necked_biped_with(extras: &[Mesh]) -> Mesh {
    let mut parts = vec![
        limb(DVec3::new(0.0, 1.0, -0.45), DVec3::new(0.0, 1.0, 0.0), 0.25),
        limb(
            DVec3::new(0.0, 1.05, -0.5),
            DVec3::new(0.0, 1.15, -2.2),
            0.14,
        ),
        limb(DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, 1.5, 1.1), 0.17),
        limb(DVec3::new(0.0, 1.5, 1.0), DVec3::new(0.0, 1.45, 1.35), 0.14),
    ];
    for x in [0.18, -0.18] {
        parts.push(limb(
            DVec3::new(x, 0.95, -0.2),
            DVec3::new(x * 1.1, 0.08, -0.1),
            0.09,
        ));
    }
    parts.extend(extras.iter().cloned());
    merge(&parts)
}

/// A short arm hanging from the chest on the side of `x` (its sign).
fn short_arm(x: f64) -> Mesh {
    limb(
        DVec3::new(0.2 * x, 0.95, 0.45),
        DVec3::new(0.3 * x, 0.68, 0.62),
        0.05,
    )
}

/// The raptor-like biped of [`biped_with`] with both short arms (shared with `rig.rs`).
pub(crate) fn short_armed_biped() -> Mesh {
    biped_with(&[short_arm(1.0), short_arm(-1.0)])
}

/// Issue 21: a raptor's short arms were merged into the trunk ("no front limb pair"), being
/// shorter than the arm rule's length. A mirror-symmetric pair ahead of the hind legs is the
/// fore-limb pair however short; a single bump or a pair rising from the head (ears) is not.
/// Fails when any part of `labels` is a fore limb.
fn assert_no_fore_pair(labels: &Labelling) {
    assert!(
        labels
            .parts
            .iter()
            .all(|p| p.limb_pair != Some(LimbPair::Fore)),
        "{:?}",
        parts(labels)
    );
}

#[test]
fn a_bipeds_short_arm_pair_is_its_fore_limb_pair() {
    let mesh = short_armed_biped();
    let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
    assert_eq!(labels.figure, FigureClass::AnimalLike);
    for side in [Side::Left, Side::Right] {
        let fore = &labels.parts[one(&labels, Label::Leg, Some(side), Some(LimbPair::Fore))];
        let hind = &labels.parts[one(&labels, Label::Leg, Some(side), Some(LimbPair::Hind))];
        let sign = if side == Side::Left { 1.0 } else { -1.0 };
        assert!(
            fore.distal.x * sign > 0.1,
            "{side:?} fore {:?}",
            fore.distal
        );
        assert!(
            fore.distal.z > 0.3 && fore.distal.y > 0.5,
            "{:?}",
            fore.distal
        );
        assert!(hind.distal.y < 0.3, "{side:?} hind {:?}", hind.distal);
    }
    assert_eq!(labels.count(Label::Head), 1, "{:?}", parts(&labels));
    assert_eq!(labels.count(Label::Tail), 1, "{:?}", parts(&labels));

    // The heart at the hips: the arms branch off the head's section (the raptor's case), and
    // the trunk is carried on to where they leave it.
    let arm = |x: f64| {
        limb(
            DVec3::new(0.12 * x, 1.1, 0.4),
            DVec3::new(0.25 * x, 0.85, 0.55),
            0.05,
        )
    };
    let mesh = long_necked_biped_with(&[arm(1.0), arm(-1.0)]);
    let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
    for side in [Side::Left, Side::Right] {
        let fore = &labels.parts[one(&labels, Label::Leg, Some(side), Some(LimbPair::Fore))];
        let sign = if side == Side::Left { 1.0 } else { -1.0 };
        assert!(
            fore.distal.x * sign > 0.1,
            "{side:?} fore {:?}",
            fore.distal
        );
        assert!((0.3..0.7).contains(&fore.distal.z), "{:?}", fore.distal);
    }
    let head = &labels.parts[one(&labels, Label::Head, None, None)];
    assert!(head.distal.z > 1.2, "{:?}", head.distal);
    let mesh = long_necked_biped_with(&[arm(-1.0)]);
    let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
    assert_no_fore_pair(&labels);

    // One arm only: a bump, not a limb pair.
    let mesh = biped_with(&[short_arm(1.0)]);
    let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
    assert_eq!(labels.count(Label::Leg), 2, "{:?}", parts(&labels));
    assert_no_fore_pair(&labels);

    // A winged biped's fore limbs are its wings: no third limb pair.
    let wing = |x: f64| {
        Mesh::cuboid(
            DVec3::new(if x > 0.0 { 0.1 } else { -1.1 }, 0.96, -0.2),
            DVec3::new(if x > 0.0 { 1.1 } else { -0.1 }, 1.04, 0.3),
        )
    };
    let mesh = biped_with(&[wing(1.0), wing(-1.0), short_arm(1.0), short_arm(-1.0)]);
    let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
    assert_eq!(labels.count(Label::Wing), 2, "{:?}", parts(&labels));
    assert_eq!(labels.count(Label::Leg), 2, "{:?}", parts(&labels));

    // Ears rising from the head mirror each other too, but they are not limbs.
    let ear = |x: f64| {
        limb(
            DVec3::new(0.1 * x, 1.6, 1.05),
            DVec3::new(0.2 * x, 1.9, 1.0),
            0.05,
        )
    };
    let mesh = biped_with(&[ear(1.0), ear(-1.0)]);
    let labels = label(&mesh, &LabelPipelineOptions::default()).unwrap();
    assert_eq!(labels.count(Label::Leg), 2, "{:?}", parts(&labels));
    assert_no_fore_pair(&labels);
}

/// Issue 21 on the reference dinosaurs: the velociraptor's short arms branch off the head's
/// section (its heart lies at the hips), the T-rex's leave the trunk as sections too short for
/// the arm rule; both are now the fore leg pair, held above the ground ahead of the hind legs.
/// Before: trunk, head, tail and two hind legs only (label weight share 70.0 % and 78.3 %).
#[test]
fn the_dinosaurs_short_arms_are_their_fore_legs() {
    for model in ["other/quaternius_velociraptor", "other/quaternius_trex"] {
        let Some(dir) = common::model(model) else {
            return;
        };
        let (_, labels) = labelled(&dir, &LabelOptions::default());
        for side in [Side::Left, Side::Right] {
            let fore = &labels.parts[one(&labels, Label::Leg, Some(side), Some(LimbPair::Fore))];
            let hind = &labels.parts[one(&labels, Label::Leg, Some(side), Some(LimbPair::Hind))];
            assert!(
                fore.distal.z > hind.distal.z && fore.distal.y > 0.5 * hind.attachment.y,
                "{model} {side:?}: fore {:?} hind {:?}",
                fore.distal,
                hind.distal
            );
        }
    }
}

/// The adventurer's backpack is no tail whichever way the figure faces. Turned to face -X, the
/// backpack and the legs joined the trunk at one level-graph vertex spanning the lower back,
/// so the backpack passed as rooted at the pelvic end and was labelled a tail (the pelvis then
/// lost its hip slice). Where each section leaves the trunk tells them apart: the backpack
/// between the shoulder blades, nearer the arms' roots than the legs'.
#[test]
fn a_backpack_is_no_tail_whichever_way_the_figure_faces() {
    let Some(dir) = common::model("humanoid/quaternius_men_adventurer") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    for degrees in [0.0f64, 90.0, 180.0, 270.0] {
        let turned = common::turned_about_up(&mesh, degrees);
        let labels = label(&turned, &stages(LabelOptions::default())).unwrap();
        assert_eq!(
            labels.count(Label::Tail),
            0,
            "turned {degrees}: {}",
            labels.parts_summary()
        );
        assert_eq!(
            (labels.count(Label::Arm), labels.count(Label::Leg)),
            (2, 2),
            "turned {degrees}: {}",
            labels.parts_summary()
        );
    }
}

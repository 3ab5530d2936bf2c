//! The anatomical rig (`pipeline::rig`, dissertation ch.7-8) on the reference humanoids and
//! quadrupeds: every canonical joint, joints inside the figure, left/right, skin weights, bad
//! input (a wrong template, a one-armed figure).

use crate::common;
use glam::DVec3;
use skelfit::mesh::{load, Mesh};
use skelfit::pipeline::{rig, Rig, RigOptions, TemplateChoice};
use skelfit::skeleton::canonical::DIGITS;
use skelfit::skeleton::JointId;
use std::path::Path;

/// A humanoid rig has every canonical key (`CANONICAL_KEYS`: pelvis to toes, no tail).
const HUMANOID_KEYS: &[&str] = skelfit::eval::CANONICAL_KEYS;

const QUADRUPED_KEYS: &[&str] = &[
    "pelvis",
    "spine",
    "chest",
    "neck",
    "head",
    "shoulder_L",
    "shoulder_R",
    "elbow_L",
    "elbow_R",
    "wrist_L",
    "wrist_R",
    "hip_L",
    "hip_R",
    "knee_L",
    "knee_R",
    "ankle_L",
    "ankle_R",
    "tail_base",
    "tail_end",
];

fn rigged(dir: &Path, options: &RigOptions) -> (Mesh, Rig) {
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let r = rig(&mesh, options).unwrap();
    (mesh, r)
}

fn models(kind: &str) -> Vec<std::path::PathBuf> {
    let Some(root) = common::refdata() else {
        return Vec::new();
    };
    let mut dirs: Vec<_> = std::fs::read_dir(root.join(kind))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("mesh.obj").is_file())
        .collect();
    dirs.sort();
    dirs
}

/// Generalised winding number of `mesh` at `p` (1 inside a closed outward mesh, 0 outside):
/// the solid angles of the triangles over 4π (Van Oosterom and Strackee 1983).
fn winding(mesh: &Mesh, p: DVec3) -> f64 {
    let mut total = 0.0;
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|v| mesh.positions[v as usize] - p);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let det = a.dot(b.cross(c));
        let div = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        total += 2.0 * det.atan2(div);
    }
    total / (4.0 * std::f64::consts::PI)
}

/// Every deforming joint lies in an interior voxel or within one voxel of one (joints on the
/// skin's inner side at a coarse grid). Digit joints, in fingers thinner than the body's
/// voxels, lie inside the mesh itself (winding number above one half).
fn assert_inside(name: &str, mesh: &Mesh, r: &Rig) {
    let grid = &r.solid.grid;
    let digits: std::collections::HashSet<JointId> = DIGITS
        .iter()
        .filter_map(|k| r.fit.canonical.get(k.as_str()).copied())
        .collect();
    for (id, j) in r.fit.skeleton.joints.iter().enumerate() {
        if !j.deform {
            continue;
        }
        if digits.contains(&JointId(id)) {
            let w = winding(mesh, j.position);
            assert!(
                w > 0.5,
                "{name}: digit joint {} at {:?} is outside the mesh (winding {w:.2})",
                j.name,
                j.position
            );
            continue;
        }
        let c = grid.to_voxel(j.position);
        let inside = (-1i64..=1).any(|dx| {
            (-1i64..=1).any(|dy| {
                (-1i64..=1).any(|dz| {
                    let v = [
                        c.x.floor() as i64 + dx,
                        c.y.floor() as i64 + dy,
                        c.z.floor() as i64 + dz,
                    ];
                    v.iter()
                        .zip(grid.dims)
                        .all(|(&a, d)| a >= 0 && (a as usize) < d)
                        && r.solid.inside[grid.index([v[0] as usize, v[1] as usize, v[2] as usize])]
                })
            })
        });
        assert!(
            inside,
            "{name}: joint {} at {:?} is outside the figure",
            j.name, j.position
        );
    }
}

/// `_L` joints lie on the figure's left (+X here) of their `_R` twins.
fn assert_left_right(name: &str, r: &Rig) {
    let left = r.labelling.frame.left;
    for (key, &id) in &r.fit.canonical {
        let Some(base) = key.strip_suffix("_L") else {
            continue;
        };
        let Some(&twin) = r.fit.canonical.get(&format!("{base}_R")) else {
            continue;
        };
        let (l, rr) = (
            r.fit.skeleton.joint(id).position,
            r.fit.skeleton.joint(twin).position,
        );
        assert!(
            (l - rr).dot(left) > 0.0,
            "{name}: {key} {l:?} is not left of {base}_R {rr:?}"
        );
    }
}

fn assert_keys(name: &str, r: &Rig, keys: &[&str]) {
    let missing: Vec<&&str> = keys
        .iter()
        .filter(|k| !r.fit.canonical.contains_key(**k))
        .collect();
    assert!(
        missing.is_empty(),
        "{name}: missing canonical joints {missing:?}; warnings {:?}",
        r.warnings
    );
}

fn assert_skin(name: &str, mesh: &Mesh, r: &Rig) {
    assert_eq!(r.skin.engine.joints.len(), mesh.positions.len(), "{name}");
    for (v, w) in r.skin.engine.weights.iter().enumerate() {
        let sum: f32 = w.iter().sum();
        assert!(
            (sum - 1.0).abs() < 1e-3,
            "{name}: vertex {v} weights sum {sum}"
        );
        assert!(w.iter().all(|x| *x >= 0.0), "{name}: vertex {v}");
    }
}

#[test]
fn every_humanoid_gets_every_canonical_joint_inside_and_sided() {
    // The real game characters too (issue 21): stylised, clothed, many-piece figures.
    for dir in models("humanoid") {
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        let (mesh, r) = rigged(&dir, &RigOptions::default());
        assert_eq!(r.fit.template, "humanoid", "{name}");
        assert_keys(&name, &r, HUMANOID_KEYS);
        assert_inside(&name, &mesh, &r);
        assert_left_right(&name, &r);
        assert_skin(&name, &mesh, &r);
        assert!(r.fit.skeleton.validate().is_ok(), "{name}");
    }
}

#[test]
fn every_humanoid_source_glb_rigs_as_a_whole_humanoid() {
    // Users hand over the artist's file, not refdata's cleaned mesh.obj: the glTF as exported,
    // with its doubled faces, its node transforms and its many pieces.
    for dir in models("humanoid") {
        let path = dir.join("source.glb");
        if !path.is_file() {
            continue;
        }
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        let mesh = load(&path).unwrap();
        let r = rig(&mesh, &RigOptions::default()).unwrap();
        assert_eq!(r.fit.template, "humanoid", "{name}: source.glb");
        assert_keys(&name, &r, HUMANOID_KEYS);
        assert_inside(&name, &mesh, &r);
        assert_left_right(&name, &r);
    }
}

#[test]
fn every_quadruped_gets_every_canonical_joint_inside_and_sided() {
    for dir in models("quadruped") {
        if common::awaits_real_character_work(&dir, "every_quadruped_gets_every_canonical_joint") {
            continue;
        }
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        let (mesh, r) = rigged(&dir, &RigOptions::default());
        assert_eq!(r.fit.template, "quadruped", "{name}");
        assert_keys(&name, &r, QUADRUPED_KEYS);
        assert_inside(&name, &mesh, &r);
        assert_left_right(&name, &r);
        assert_skin(&name, &mesh, &r);
        // Fore limbs ahead of hind limbs, head ahead of the tail.
        let at = |k: &str| r.fit.skeleton.joint(r.fit.canonical[k]).position;
        let fwd = r.labelling.frame.forward;
        assert!((at("shoulder_L") - at("hip_L")).dot(fwd) > 0.0, "{name}");
        assert!((at("head") - at("tail_end")).dot(fwd) > 0.0, "{name}");
    }
}

/// Mean error (mesh units) over pelvis, neck, head, shoulders, elbows, wrists, hips, knees and
/// ankles of the MakeHuman bodies (those with `rig_game_engine.json`), printing each model's
/// mean; `None` without reference data.
/// Mean joint error over all models, the largest per-model mean and the largest single error
/// (metres), or `None` without the reference data.
fn makehuman_mean_error(options: &RigOptions) -> Option<(f64, f64, f64)> {
    // The 15-joint set, which is also the set refinement places.
    const SET: [&str; 15] = skelfit::refine::REFINED_KEYS;
    let mut errors = Vec::new();
    let (mut worst_mean, mut worst) = (0.0_f64, 0.0_f64);
    for dir in models("humanoid") {
        let reference = dir.join("rig_game_engine.json");
        if !reference.is_file() {
            continue;
        }
        let reference = skelfit::eval::load_skeleton(&reference).unwrap();
        let (_, r) = rigged(&dir, options);
        let model: Vec<f64> = SET
            .iter()
            .map(|key| {
                let p = r.fit.skeleton.joint(r.fit.canonical[*key]).position;
                p.distance(reference.canonical_joint(key).unwrap().position)
            })
            .collect();
        let mean = model.iter().sum::<f64>() / model.len() as f64;
        let max = model.iter().copied().fold(0.0, f64::max);
        println!(
            "{}: mean {:.1} mm, max {:.1} mm",
            dir.file_name().unwrap().to_string_lossy(),
            mean * 1e3,
            max * 1e3
        );
        errors.extend(model);
        worst_mean = worst_mean.max(mean);
        worst = worst.max(max);
    }
    (!errors.is_empty()).then(|| {
        let mean = errors.iter().sum::<f64>() / errors.len() as f64;
        (mean, worst_mean, worst)
    })
}

/// The humanoid rig without refinement (issue 5's target is 30 mm; measured 29.7 mm on the six
/// MakeHuman bodies when written, 33.5 mm since the leg paths run on to the toe tips; the rough
/// hips and knees sit 2-8 cm low, which refinement corrects) and with it (the default; measured 8.1 mm, per model 6.0-9.8
/// mm, the largest single joint error 27.2 mm, the heavy body's knees). With refinement the
/// bounds are issue 6's targets: mean <= 14 mm and max <= 29 mm on every model (and the overall
/// mean below 9.5 mm, a regression guard).
/// Per-model numbers: `cargo test --release --test it makehuman_joint_error -- --nocapture`.
#[test]
fn makehuman_joint_error_stays_within_the_measured_bounds() {
    let mut off = RigOptions::default();
    off.refine.in_rig = false;
    if let Some((mean, _, _)) = makehuman_mean_error(&off) {
        println!("without refinement: mean {:.1} mm", mean * 1e3);
        assert!(mean < 0.034, "mean joint error {:.1} mm", mean * 1e3);
    }
    if let Some((mean, worst_mean, worst)) = makehuman_mean_error(&RigOptions::default()) {
        println!("with refinement: mean {:.1} mm", mean * 1e3);
        assert!(mean < 0.0095, "mean joint error {:.1} mm", mean * 1e3);
        assert!(
            worst_mean <= 0.014,
            "a model's mean error is {:.1} mm",
            worst_mean * 1e3
        );
        assert!(worst <= 0.029, "a joint's error is {:.1} mm", worst * 1e3);
    }
}

/// The canonical `spine` and `chest` are the trunk joints nearest the template's fractions
/// (25 % and 45 % of the way pelvis -> neck) where the joints end up: the refinement moves
/// the trunk joints onto the spine curve, and the keys used to stay with the joints chosen
/// before it (the bundled MakeHuman body's `chest` then sat at 57 %, 96 mm from the
/// reference's `spine_03`; now 45 %, 38 mm).
#[test]
fn trunk_keys_follow_the_refined_spine() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default");
    let (_, r) = rigged(&dir, &RigOptions::default());
    let skeleton = &r.fit.skeleton;
    let key = |k: &str| r.fit.canonical[k];
    let mut chain = vec![key("neck")];
    while *chain.last().unwrap() != key("pelvis") {
        let parent = skeleton.joint(*chain.last().unwrap()).parent.unwrap();
        chain.push(parent);
    }
    chain.reverse();
    let mut along = vec![0.0];
    for w in chain.windows(2) {
        let step = skeleton
            .joint(w[0])
            .position
            .distance(skeleton.joint(w[1]).position);
        along.push(along.last().unwrap() + step);
    }
    let total = *along.last().unwrap();
    let fraction = |id| along[chain.iter().position(|&c| c == id).unwrap()] / total;
    for (k, at) in [("spine", 0.25), ("chest", 0.45)] {
        let ours = (fraction(key(k)) - at).abs();
        for &other in &chain[1..chain.len() - 1] {
            assert!(
                ours <= (fraction(other) - at).abs() + 1e-9,
                "{k} is {} at {:.2} of the chain; {} at {:.2} is nearer {at}",
                skeleton.joint(key(k)).name,
                fraction(key(k)),
                skeleton.joint(other).name,
                fraction(other)
            );
        }
    }
    let reference = skelfit::eval::load_skeleton(&dir.join("rig_game_engine.json")).unwrap();
    let error = skeleton
        .joint(key("chest"))
        .position
        .distance(reference.canonical_joint("chest").unwrap().position);
    println!("chest: {:.1} mm from the reference", error * 1e3);
    assert!(
        error < 0.06,
        "chest {:.1} mm from the reference",
        error * 1e3
    );
}

/// A tessellation study pairs the anatomical rig with the reference through the rig's own
/// canonical map, as `skelfit bench` does (it used to read the joint names by the naming
/// preset, which ties `chest` to `spine_03` whatever the fit chose).
#[test]
fn a_study_evaluates_the_rig_by_its_own_canonical_map() {
    use skelfit::eval::{tessellation_study, RigMethod, StudyOptions};
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default");
    let (mesh, r) = rigged(&dir, &RigOptions::default());
    let reference = skelfit::eval::load_skeleton(&dir.join("rig_game_engine.json")).unwrap();
    let mut options = StudyOptions::default();
    options.rigger.method = RigMethod::Anatomical;
    let study = tessellation_study(&mesh, "mh", Some(&reference), &[], &options).unwrap();
    let evaluation = study.base().unwrap().to_reference.as_ref().unwrap();
    for key in ["spine", "chest", "neck", "shoulder_L"] {
        let joint = evaluation.joints.iter().find(|j| j.key == key).unwrap();
        assert_eq!(
            joint.predicted_joint,
            r.fit.skeleton.joint(r.fit.canonical[key]).name,
            "{key}"
        );
    }
    // The study page opens with its verdict: the variants' moves from the base rig.
    assert_eq!(
        skelfit::report::study_verdict(&study),
        "no variant was compared with the base rig"
    );
    let halved = tessellation_study(&mesh, "mh", None, &[0.5], &options).unwrap();
    let verdict = skelfit::report::study_verdict(&halved);
    assert!(
        verdict.contains(" of 1 variants; largest move: x0.5 "),
        "{verdict}"
    );
    let page = skelfit::report::study_html(&halved, "study", "", None);
    assert!(page.contains("<p class=\"verdict\">"), "no verdict line");
}

/// Engine presets name each canonical joint by its key, also after the refinement has moved
/// `spine`/`chest` to other joints (the names used to be given before it, so Mixamo's
/// `Spine2` was no longer the `chest`).
#[test]
fn preset_names_follow_the_final_canonical_keys() {
    use skelfit::template::Preset;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default");
    for preset in [Preset::Mixamo, Preset::Unity, Preset::MakeHuman] {
        let mut options = RigOptions::default();
        options.fit.preset = preset;
        let (_, r) = rigged(&dir, &options);
        let table = preset.names().unwrap();
        for (key, id) in &r.fit.canonical {
            let Some(names) = table.joints.get(key) else {
                continue;
            };
            assert_eq!(
                &r.fit.skeleton.joint(*id).name,
                &names[0],
                "{preset:?}: canonical {key}"
            );
        }
    }
}

/// Runs `error` (a fraction of height, `None` where the model's rig lacks the joints) on every
/// refdata quadruped with the default options and with `off`, prints each, and returns the two
/// means; `None` without refdata or a model that has the joints.
fn refdata_means(
    what: &str,
    error: &dyn Fn(&Path, &RigOptions) -> Option<f64>,
    off: &RigOptions,
) -> Option<(f64, f64)> {
    let (mut with, mut without, mut n) = (0.0, 0.0, 0);
    for dir in models("quadruped") {
        if common::awaits_real_character_work(&dir, what) {
            continue;
        }
        let (Some(a), Some(b)) = (error(&dir, &RigOptions::default()), error(&dir, off)) else {
            continue;
        };
        println!(
            "{}: {what} {:.1} % with, {:.1} % without",
            dir.display(),
            100.0 * a,
            100.0 * b
        );
        with += a;
        without += b;
        n += 1;
    }
    (n > 0).then(|| {
        let (with, without) = (with / n as f64, without / n as f64);
        println!(
            "mean of {n}: {:.1} % with, {:.1} % without",
            100.0 * with,
            100.0 * without
        );
        (with, without)
    })
}

/// The knees (stifles) of an animal sit at the flank fold, low on the front of the hind leg
/// (`FitOptions::limb_fold`), not where the leg's medial piece leaves the trunk on the haunch.
/// Measured against the `BackUpperLeg.*` joints (the stifles) of the Quaternius rigs: the
/// bundled horse, the worse side: 3.7 % of height with the fold, 12.3 % without; with
/// `../shared/refdata`, every quadruped whose rig has such joints is measured too and printed
/// (`cargo test --release --test it quadruped_knees -- --nocapture`).
#[test]
fn quadruped_knees_sit_at_the_flank_fold() {
    let error = |dir: &Path, options: &RigOptions| -> Option<f64> {
        let reference = skelfit::eval::load_skeleton(&dir.join("rig_gltf.json")).ok()?;
        let (mesh, r) = rigged(dir, options);
        let (lo, hi) = mesh.bounding_box().unwrap();
        let sk = &r.fit.skeleton;
        let mut worst: f64 = 0.0;
        for s in ["L", "R"] {
            let ours = sk.joints[sk.find(&format!("knee_{s}"))?.0].position;
            let id = reference.skeleton.find(&format!("BackUpperLeg.{s}"))?;
            worst =
                worst.max(ours.distance(reference.skeleton.joints[id.0].position) / (hi.y - lo.y));
        }
        Some(worst)
    };
    let mut off = RigOptions::default();
    off.fit.limb_fold = None;
    let horse = common::data_dir().join("quadruped/quaternius_horse");
    let (with, without) = (
        error(&horse, &RigOptions::default()).unwrap(),
        error(&horse, &off).unwrap(),
    );
    println!(
        "bundled horse: knee error {:.1} % with the fold, {:.1} % without",
        100.0 * with,
        100.0 * without
    );
    assert!(with < 0.05, "{with}");
    assert!(without > 2.0 * with, "{without} vs {with}");
    if let Some((with, without)) = refdata_means("knees", &error, &off) {
        assert!(with < 0.5 * without, "{with} vs {without}");
    }
}

/// An animal's tarsometatarsal joint (`foot`) lies one tarsal row below its hock, not far
/// down the cannon bone: when the bend snapping takes the ankle up to the hock, the row stays
/// the template's share of the shank (tarsals over tibia, 35/174) instead of its share of the
/// path left below. Before, the deer's, the stag's and the apatosaurus's foot joints lay a
/// quarter of the hip-to-ankle distance below the ankle (0.25, 0.27, 0.25; CD-J2J deer 3.10,
/// stag 3.06, apatosaurus 2.26 %), now 0.15–0.17 (3.06, 2.99, 2.24 %); the other quadrupeds,
/// whose ankles stay at their Table 8.1 places, 0.08–0.19. Bound: twice the template's share
/// of femur and tibia together (35/349) and some slack.
#[test]
fn quadruped_foot_joints_sit_one_tarsal_row_below_the_hock() {
    // Every quadruped, the new ones (cow, husky, rat, apatosaurus, stag) among them.
    for dir in models("quadruped") {
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        let (_, r) = rigged(&dir, &RigOptions::default());
        let sk = &r.fit.skeleton;
        for s in ["L", "R"] {
            let at = |j: &str| sk.find(&format!("{j}_{s}")).map(|id| sk.joint(id).position);
            let (Some(hip), Some(ankle), Some(foot)) = (at("hip"), at("ankle"), at("foot")) else {
                continue;
            };
            let row = ankle.distance(foot) / hip.distance(ankle);
            println!("{name} {s}: ankle to foot {row:.2} of hip to ankle");
            assert!(
                row < 0.22,
                "{name} {s}: foot joint {row:.2} of the leg below the ankle"
            );
        }
    }
}

/// An animal's elbows sit where the fore leg comes free of the chest floor
/// (`FitOptions::limb_fold`), not where its medial piece leaves the trunk's. Measured with
/// `../shared/refdata` against the fox's canonical elbows and the Quaternius rigs'
/// `FrontUpperLeg.*` joints (their elbows), mean of both sides in % of height
/// (`cargo test --release --test it quadruped_elbows -- --nocapture`).
#[test]
fn quadruped_elbows_sit_below_the_chest_floor() {
    let error = |dir: &Path, options: &RigOptions| -> Option<f64> {
        let reference = skelfit::eval::load_skeleton(&dir.join("rig_gltf.json")).ok()?;
        let (mesh, r) = rigged(dir, options);
        let (lo, hi) = mesh.bounding_box().unwrap();
        let sk = &r.fit.skeleton;
        let mut sum = 0.0;
        for s in ["L", "R"] {
            let ours = sk.joints[sk.find(&format!("elbow_{s}"))?.0].position;
            let id = reference
                .canonical
                .get(&format!("elbow_{s}"))
                .copied()
                .or_else(|| reference.skeleton.find(&format!("FrontUpperLeg.{s}")))?;
            sum += ours.distance(reference.skeleton.joints[id.0].position) / (hi.y - lo.y) / 2.0;
        }
        Some(sum)
    };
    let mut off = RigOptions::default();
    off.fit.limb_fold = None;
    if let Some((with, without)) = refdata_means("elbows", &error, &off) {
        assert!(with < 0.85 * without, "{with} vs {without}");
    }
}

/// An animal's neck leaves the trunk at the middle of the chest's front, not along the top of
/// the back (the quadruped template's `axial.dorsal_taper`, which has faded the dorsal offset
/// out by the shoulders, and `FitOptions::neck_base_drop` for templates without it): measured
/// on the bundled horse against its rig's `Neck1` (7.3 % of height with the defaults, 9.3 %
/// with neither) and, with `../shared/refdata`, on the fox against its canonical neck (14 mm
/// with, 35 mm with neither).
#[test]
fn quadruped_necks_leave_the_trunk_at_the_chest_front() {
    let error = |dir: &Path, reference_joint: &str, options: &RigOptions| -> f64 {
        let reference = skelfit::eval::load_skeleton(&dir.join("rig_gltf.json")).unwrap();
        let (_, r) = rigged(dir, options);
        let sk = &r.fit.skeleton;
        let ours = sk.joints[sk.find("neck_01").unwrap().0].position;
        let id = reference.skeleton.find(reference_joint).unwrap();
        ours.distance(reference.skeleton.joints[id.0].position)
    };
    let mut off = RigOptions::default();
    off.fit.neck_base_drop = 0.0;
    let mut even = skelfit::template::Template::builtin("quadruped").unwrap();
    even.axial.dorsal_taper = false;
    off.template = TemplateChoice::Custom(Box::new(even));
    let horse = common::data_dir().join("quadruped/quaternius_horse");
    let (with, without) = (
        error(&horse, "Neck1", &RigOptions::default()),
        error(&horse, "Neck1", &off),
    );
    println!("bundled horse: neck {with:.3} with, {without:.3} without (units)");
    assert!(with < 0.85 * without, "{with} vs {without}");
    if let Some(fox) = common::model("quadruped/khronos_fox") {
        let (with, without) = (
            error(&fox, "b_Neck_04", &RigOptions::default()),
            error(&fox, "b_Neck_04", &off),
        );
        println!("fox: neck {with:.3} m with, {without:.3} m without");
        assert!(with < 0.6 * without, "{with} vs {without}");
    }
}

/// The bundled MakeHuman body is left-right symmetric, and so are its feet: the right leg's
/// medial path used to end a voxel lower, its end direction dipped through the thin sole, and
/// the right toe chain stopped 5 cm short of the toes (toe_R 68 mm from the reference, toe_L
/// 29 mm). The fit input's reach to the skin (`fit/reach.rs`) now takes a clearly deeper ray within 30 degrees.
#[test]
fn a_symmetric_body_gets_mirrored_feet() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default");
    let (_, r) = rigged(&dir, &RigOptions::default());
    let at = |name: &str| {
        let id = r.fit.skeleton.find(name).unwrap();
        r.fit.skeleton.joint(id).position
    };
    for joint in ["ankle", "toe", "toe_end"] {
        let (l, rr) = (at(&format!("{joint}_L")), at(&format!("{joint}_R")));
        let mirrored = DVec3::new(-rr.x, rr.y, rr.z);
        println!("{joint}: left {l:.3}, right mirrored {mirrored:.3}");
        assert!(
            l.distance(mirrored) < 0.015,
            "{joint}_L {l:.3} and {joint}_R mirrored {mirrored:.3} differ by {:.1} mm",
            l.distance(mirrored) * 1e3
        );
    }
}

/// A loose piece far from the figure (a helper object left in the file) used to size the voxel
/// grid: one tetrahedron two horse-lengths away coarsened the voxels from 0.057 to 0.125 and
/// the rig changed (66 joints instead of 58). It is left out of the voxels with a warning, and
/// the horse gets the rig it gets alone.
#[test]
fn a_loose_piece_far_away_leaves_the_rig_unchanged_and_is_named() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/quadruped/quaternius_horse");
    let (horse, alone) = rigged(&dir, &RigOptions::default());
    let (_, hi) = horse.bounding_box().unwrap();
    let base = horse.positions.len() as u32;
    let mut positions = horse.positions.clone();
    let at = hi + DVec3::splat(10.0);
    positions.extend([at, at + DVec3::X, at + DVec3::Y, at + DVec3::Z]);
    let mut triangles = horse.triangles.clone();
    triangles.extend([
        [base, base + 2, base + 1],
        [base, base + 1, base + 3],
        [base, base + 3, base + 2],
        [base + 1, base + 2, base + 3],
    ]);
    let messy = Mesh::new(positions, triangles).unwrap();
    let r = rig(&messy, &RigOptions::default()).unwrap();
    assert_eq!(r.solid.grid, alone.solid.grid);
    assert_eq!(r.fit.skeleton.joints.len(), alone.fit.skeleton.joints.len());
    for (a, b) in r.fit.skeleton.joints.iter().zip(&alone.fit.skeleton.joints) {
        assert!(a.position.distance(b.position) < 1e-9, "{} moved", a.name);
    }
    assert!(
        r.warnings.iter().any(|w| w
            .to_string()
            .starts_with("1 loose piece of the mesh (4 triangles")),
        "{:?}",
        r.warnings
    );
    assert!(r.skin.weights[base as usize..]
        .iter()
        .all(|w| !w.is_empty()));
}

/// Legs reach the ground on both sides even where the medial surface of a thin foot broke
/// off on one side (the alpaca's left fore foot: its limb path stopped 0.46 units above the
/// ground, and its digit joints hung 0.38 above it): the fit input's reach to the skin (`fit/reach.rs`) takes the path tip
/// to the skin along the end direction.
#[test]
fn every_foot_reaches_the_ground() {
    for dir in models("quadruped") {
        if common::awaits_real_character_work(&dir, "every_foot_reaches_the_ground") {
            continue;
        }
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        let (mesh, r) = rigged(&dir, &RigOptions::default());
        let (lo, hi) = mesh.bounding_box().unwrap();
        let h = hi.y - lo.y;
        let sk = &r.fit.skeleton;
        let mut lowest = Vec::new();
        // The fit's single digit chain per foot, or the digits a hoof's or paw's surface shows.
        for (chain, digits) in [("finger", "fore_digit"), ("toe", "hind_digit")] {
            for side in ["L", "R"] {
                let low = sk
                    .joints
                    .iter()
                    .filter(|j| {
                        (j.name.starts_with(chain) || j.name.starts_with(digits))
                            && j.name.ends_with(side)
                    })
                    .map(|j| (j.position.y - lo.y) / h)
                    .fold(f64::INFINITY, f64::min);
                lowest.push(low);
                assert!(
                    low < 0.03,
                    "{name}: {chain} {side} ends {:.1} % of height above the ground",
                    100.0 * low
                );
            }
        }
        println!("{name}: lowest digit joints {lowest:.3?} of height");
    }
}

#[test]
fn a_humanoid_template_on_a_quadruped_warns_and_does_not_panic() {
    let Some(dir) = common::model("quadruped/quaternius_horse") else {
        return;
    };
    let options = RigOptions {
        template: TemplateChoice::Builtin("humanoid".into()),
        ..Default::default()
    };
    let (_, r) = rigged(&dir, &options);
    assert_eq!(r.fit.template, "humanoid");
    assert!(!r.warnings.is_empty());
    assert!(r.fit.skeleton.validate().is_ok());
    let Some(dir) = common::model("humanoid/mh_neutral_default") else {
        return;
    };
    let options = RigOptions {
        template: TemplateChoice::Builtin("quadruped".into()),
        ..Default::default()
    };
    let (_, r) = rigged(&dir, &options);
    // The arms are no fore legs. (A quadruped's tail is optional, `[vertebrae] tail = [0, 8]`:
    // a body without one is not warned about it, as a frog is not.)
    assert!(
        r.warnings
            .iter()
            .any(|w| w.to_string().contains("arm") && w.to_string().contains("fore_leg")),
        "{:?}",
        r.warnings
    );
}

#[test]
fn a_one_armed_figure_gets_a_rig_whose_warning_names_the_missing_arm() {
    let Some(dir) = common::model("humanoid/mh_neutral_default") else {
        return;
    };
    let mut mesh = load(&dir.join("mesh.obj")).unwrap();
    // Cut the right arm off (the figure's right is -X): an open mesh with a hole at the
    // shoulder, which the voxelizer closes.
    let keep: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .copied()
        .filter(|t| {
            t.iter().all(|&i| {
                let p = mesh.positions[i as usize];
                !(p.x < -0.2 && p.y > 0.9)
            })
        })
        .collect();
    mesh.triangles = keep;
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    assert!(r.fit.canonical.contains_key("shoulder_L"));
    assert!(!r.fit.canonical.contains_key("shoulder_R"));
    assert!(
        r.warnings
            .iter()
            .any(|w| w.to_string().contains("arm") && w.to_string().contains("right")),
        "{:?}",
        r.warnings
    );
    // Never silent: the rig lists the part it lacks.
    assert_eq!(r.missing, vec!["arm R".to_string()]);
    assert!(r.fit.skeleton.validate().is_ok());
}

#[test]
fn a_sphere_gets_a_best_effort_rig_with_warnings() {
    let mesh = Mesh::uv_sphere(DVec3::ZERO, 1.0, 24, 48);
    // No limbs: no vertebrate template fits, and the rig says so and gets the general skeleton.
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    assert_eq!(r.fit.template, skelfit::pipeline::GENERAL);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.to_string().contains("no template fits")
                && w.to_string().contains("no limbs")),
        "{:?}",
        r.warnings
    );
    assert!(r.fit.canonical.is_empty());
    assert!(r.fit.skeleton.validate().is_ok());
    assert_eq!(r.skin.engine.weights.len(), mesh.positions.len());
    // A template the user forces is fitted, and not mistaken for a full figure: the parts it
    // lacks are listed.
    let forced = RigOptions {
        template: skelfit::pipeline::TemplateChoice::Builtin("quadruped".into()),
        ..RigOptions::default()
    };
    let r = rig(&mesh, &forced).unwrap();
    assert_eq!(r.fit.template, "quadruped");
    assert!(r.missing.len() >= 4, "{:?}", r.missing);
    assert!(r.fit.skeleton.validate().is_ok());
}

#[test]
fn a_figure_with_eight_legs_gets_the_general_skeleton_not_a_quadruped() {
    // A spider-like toy: a flat body with four legs a side, each bent down to the ground.
    let mut parts = vec![capsule_between(
        DVec3::new(0.0, 0.6, -0.5),
        DVec3::new(0.0, 0.6, 0.5),
        0.22,
    )];
    for k in 0..4 {
        let z = -0.36 + 0.24 * k as f64;
        for side in [-1.0, 1.0] {
            let knee = DVec3::new(side * 0.75, 0.85, z * 1.6);
            parts.push(capsule_between(DVec3::new(side * 0.1, 0.6, z), knee, 0.05));
            parts.push(capsule_between(
                knee,
                DVec3::new(side * 1.1, 0.05, z * 2.0),
                0.05,
            ));
        }
    }
    let mesh = merged(&parts);
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let legs = r.labelling.count(skelfit::anatomy::Label::Leg);
    assert!(legs >= 6, "{legs} legs: {:?}", r.labelling.warnings);
    assert_eq!(
        r.fit.template,
        skelfit::pipeline::GENERAL,
        "{:?}",
        r.warnings
    );
    assert!(r
        .warnings
        .iter()
        .any(|w| w.to_string().contains("no template fits")));
    // The general skeleton reaches every leg: an end effector near each foot.
    let feet = r
        .fit
        .skeleton
        .joints
        .iter()
        .filter(|j| j.name.starts_with("end_") && j.position.y < 0.3)
        .count();
    assert!(feet >= 6, "{feet} end effectors near the ground");
    assert!(r.fit.skeleton.validate().is_ok());
}

#[test]
fn rigs_are_identical_on_one_and_two_threads() {
    let dir = common::data_dir().join("quadruped/quaternius_horse");
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let r = rig(&mesh, &RigOptions::default()).unwrap();
            (r.fit.skeleton, r.skin.engine)
        })
    };
    assert_eq!(run(1), run(2));
}

#[test]
fn a_box_gets_stub_warnings_instead_of_a_silent_quadruped() {
    // The medial surface of a box reaches its eight corners, which labelling takes for limbs,
    // head and tail; the rig says that those "limbs" are stubs.
    let mesh = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    assert!(
        r.warnings
            .iter()
            .any(|w| w.to_string().contains("a stub rather than a limb")),
        "{:?}",
        r.warnings
    );
    assert!(r.fit.skeleton.validate().is_ok());
}

fn merged(parts: &[Mesh]) -> Mesh {
    let mut out = Mesh::default();
    for part in parts {
        let base = out.positions.len() as u32;
        out.positions.extend_from_slice(&part.positions);
        out.triangles.extend(
            part.triangles
                .iter()
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
    }
    out
}

/// A capsule of radius `r` from `a` to `b`.
fn capsule_between(a: DVec3, b: DVec3, r: f64) -> Mesh {
    let d = b - a;
    let c = Mesh::capsule(DVec3::ZERO, r, 0.5 * d.length(), 8, 16);
    let q = glam::DQuat::from_rotation_arc(DVec3::Y, d.normalize());
    c.transformed(|p| q * p + 0.5 * (a + b))
}

/// A toy quadruped of capsules (+Y up, +Z forward): body, four legs, neck, a round head with a
/// snout and,
/// with `ears`, two thin ears rising from the back of the head and leaning outwards.
fn toy_quadruped(ears: bool) -> Mesh {
    let mut parts = vec![
        capsule_between(DVec3::new(0.0, 1.0, -0.6), DVec3::new(0.0, 1.0, 0.6), 0.25),
        capsule_between(
            DVec3::new(0.0, 1.05, 0.6),
            DVec3::new(0.0, 1.45, 0.95),
            0.15,
        ),
        Mesh::uv_sphere(DVec3::new(0.0, 1.5, 1.05), 0.2, 16, 32),
        capsule_between(DVec3::new(0.0, 1.45, 1.1), DVec3::new(0.0, 1.4, 1.4), 0.1),
    ];
    for (x, z) in [(0.15, 0.5), (-0.15, 0.5), (0.15, -0.5), (-0.15, -0.5)] {
        parts.push(capsule_between(
            DVec3::new(x, 1.0, z),
            DVec3::new(x, 0.1, z),
            0.08,
        ));
    }
    if ears {
        for x in [0.08, -0.08] {
            parts.push(capsule_between(
                DVec3::new(x, 1.62, 0.98),
                DVec3::new(1.75 * x, 1.88, 0.95),
                0.03,
            ));
        }
    }
    merged(&parts)
}

#[test]
fn a_quadruped_with_ears_gets_an_ear_chain_per_side_inside_and_one_without_gets_none() {
    let (with, without) = (toy_quadruped(true), toy_quadruped(false));
    let r = rig(&with, &RigOptions::default()).unwrap();
    assert_eq!(r.fit.template, "quadruped", "{:?}", r.warnings);
    assert_eq!(r.input.ears.len(), 2, "{:?}", r.warnings);
    assert_inside("toy with ears", &with, &r);
    let position = |name: &str| {
        r.fit
            .skeleton
            .joints
            .iter()
            .find(|j| j.name == name)
            .unwrap_or_else(|| panic!("no joint {name}"))
            .position
    };
    for side in ["_L", "_R"] {
        let (base, tip) = (
            position(&format!("ear_01{side}")),
            position(&format!("ear_end{side}")),
        );
        // The chain rises from the top of the head towards the modelled tip.
        assert!(base.y > 1.55 && tip.y > 1.8, "{side}: {base:?} {tip:?}");
        assert!(position(&format!("ear_03{side}")).y > base.y, "{side}");
        let head = r.fit.skeleton.joint(r.fit.canonical["head"]);
        let ear = r
            .fit
            .skeleton
            .joints
            .iter()
            .position(|j| j.name == format!("ear_01{side}"));
        assert_eq!(
            r.fit.skeleton.joints[ear.unwrap()]
                .parent
                .map(|p| &r.fit.skeleton.joint(p).name),
            Some(&head.name)
        );
    }
    assert!(position("ear_end_L").x > 0.1 && position("ear_end_R").x < -0.1);

    let r = rig(&without, &RigOptions::default()).unwrap();
    assert!(r.input.ears.is_empty(), "{:?}", r.input.ears);
    assert!(!r
        .fit
        .skeleton
        .joints
        .iter()
        .any(|j| j.name.starts_with("ear")));
}

/// Every reference quadruped whose rig has ear joints (`Ear*`) gets an ear chain per side, with
/// the tips near the reference ear joints (within 8 % of the figure's longest side: the reference chains stop short of the tips).
#[test]
fn quadrupeds_with_reference_ears_get_ears() {
    for dir in models("quadruped") {
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        let Ok(reference) = skelfit::eval::load_skeleton(&dir.join("rig_gltf.json")) else {
            continue;
        };
        let ears: Vec<DVec3> = reference
            .skeleton
            .joints
            .iter()
            .filter(|j| j.name.starts_with("Ear"))
            .map(|j| j.position)
            .collect();
        if ears.is_empty() {
            continue;
        }
        let (mesh, r) = rigged(&dir, &RigOptions::default());
        assert_eq!(r.input.ears.len(), 2, "{name}");
        let bbox = mesh.bounding_box().unwrap();
        let size = (bbox.1 - bbox.0).max_element();
        for ear in &r.input.ears {
            let tip = *ear.path.last().unwrap();
            let nearest = ears
                .iter()
                .map(|e| e.distance(tip))
                .fold(f64::MAX, f64::min);
            assert!(
                nearest < 0.08 * size,
                "{name}: ear tip {tip:?} is {nearest} from the reference ears"
            );
        }
    }
}

/// Blender's turn of a Y-up figure to Z-up (+Y to +Z, +Z forward to -Y).
fn z_up_turn() -> glam::DQuat {
    glam::DQuat::from_rotation_arc(DVec3::Y, DVec3::Z)
}

/// `mesh` turned Z-up by [`z_up_turn`].
fn turned_z_up(mesh: &Mesh) -> Mesh {
    let turn = z_up_turn();
    let mut z_up = mesh.clone();
    for p in &mut z_up.positions {
        *p = turn * *p;
    }
    z_up
}

/// Asserts that each of `keys` in the rig of `y_up` turned Z-up (default options) lies within
/// `bound` of the height of its place in the Y-up rig ([`z_up_offsets`]).
fn assert_z_up_within(y_up: &Mesh, keys: &[&str], bound: f64) {
    for (key, off) in z_up_offsets(y_up, &RigOptions::default(), keys) {
        assert!(
            off < bound,
            "{key} differs by {:.1} % of the height",
            100.0 * off
        );
    }
}

/// Per key, how far (fraction of the height) the joint of `y_up`'s rig (default options) lies
/// from the same joint of its Z-up turn rigged with `options`, turned back; panics naming a key
/// either rig lacks.
fn z_up_offsets(y_up: &Mesh, options: &RigOptions, keys: &[&str]) -> Vec<(String, f64)> {
    let reference = rig(y_up, &RigOptions::default()).unwrap();
    let found = rig(&turned_z_up(y_up), options).unwrap();
    let (lo, hi) = y_up.bounding_box().unwrap();
    let height = hi.y - lo.y;
    let at = |r: &Rig, key: &str| {
        r.fit
            .canonical
            .get(key)
            .map(|id| r.fit.skeleton.joints[id.0].position)
    };
    keys.iter()
        .map(|&key| {
            let (Some(p), Some(q)) = (at(&reference, key), at(&found, key)) else {
                panic!("{key} missing");
            };
            (
                key.to_string(),
                p.distance(z_up_turn().inverse() * q) / height,
            )
        })
        .collect()
}

/// The bundled body and horse turned Z-up (as Blender and CAD tools write them) rig with no
/// orientation given: up is found (+Z), forward follows Blender's convention (-Y), and the
/// joints match the Y-up rig's turned the same way.
#[test]
fn z_up_copies_rig_without_orientation_flags_like_the_y_up_files() {
    let turn = z_up_turn();
    for dir in [
        "data/humanoid/mh_neutral_default",
        "data/quadruped/quaternius_horse",
    ] {
        let y_up = load(
            &Path::new(env!("CARGO_MANIFEST_DIR"))
                .join(dir)
                .join("mesh.obj"),
        )
        .unwrap();
        let z_up = turned_z_up(&y_up);
        let explicit = RigOptions {
            label: skelfit::anatomy::LabelOptions {
                up: skelfit::anatomy::Up::Direction(DVec3::Y),
                ..Default::default()
            },
            ..Default::default()
        };
        let reference = rig(&y_up, &explicit).unwrap();
        let found = rig(&z_up, &RigOptions::default()).unwrap();
        let choice = found.labelling.up_found.as_ref().expect("up was found");
        assert!(choice.up.distance(DVec3::Z) < 1e-9, "{dir}: {choice:?}");
        assert!(choice.confidence > 0.5, "{dir}: {choice:?}");
        assert!(
            found
                .warnings
                .iter()
                .any(|w| w.to_string().starts_with("up is +Z")),
            "{dir}: {:?}",
            found.warnings
        );
        let (lo, hi) = y_up.bounding_box().unwrap();
        let size = (hi - lo).max_element();
        let mut worst: f64 = 0.0;
        for (key, id) in &reference.fit.canonical {
            let other = found
                .fit
                .canonical
                .get(key)
                .unwrap_or_else(|| panic!("{dir}: {key}"));
            let p = reference.fit.skeleton.joints[id.0].position;
            let q = turn.inverse() * found.fit.skeleton.joints[other.0].position;
            let off = if key.starts_with("tail_") && key != "tail_end" {
                // The tail's joints are equally spaced vertebrae behind the root whose count
                // rounds (the root itself moves with the hind pair by a voxel or two): the
                // tail base may move along the spine. It must lie on the other axial chain.
                distance_to_tail(&reference.fit, q)
            } else {
                p.distance(q)
            };
            worst = worst.max(off / size);
        }
        assert!(
            worst < 0.03,
            "{dir}: a joint differs by {:.1} % of the size",
            100.0 * worst
        );
    }
}

/// Distance from `q` to the root-to-tail chain of `fit` (its root joint, then its `tail*`
/// joints in order; segments between them).
fn distance_to_tail(fit: &skelfit::fit::Fit, q: DVec3) -> f64 {
    let tail: Vec<DVec3> = fit
        .skeleton
        .joints
        .iter()
        .filter(|j| j.parent.is_none() || j.name.starts_with("tail"))
        .map(|j| j.position)
        .collect();
    tail.windows(2)
        .map(|w| skelfit::eval::point_segment_distance(q, w[0], w[1]))
        .chain(tail.iter().map(|t| t.distance(q)))
        .fold(f64::INFINITY, f64::min)
}

/// Y-up files keep +Y at once (one labelling of the level graph), and a figure standing either
/// way up cannot be oriented: +Y with confidence 0.
#[test]
fn y_up_figures_keep_up_at_once() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default");
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let labels = skelfit::anatomy::label(&mesh, &Default::default()).unwrap();
    let choice = labels.up_found.unwrap();
    assert_eq!(choice.up, DVec3::Y);
    assert_eq!(choice.scores.len(), 1, "{choice:?}");
    assert!(choice.scores[0].complete && choice.confidence == 1.0);
    // A capsule (no legs): nothing stands; +Y is kept with confidence 0.
    let capsule = Mesh::capsule(DVec3::ZERO, 0.3, 1.0, 8, 16);
    let labels = skelfit::anatomy::label(&capsule, &Default::default()).unwrap();
    let choice = labels.up_found.unwrap();
    assert_eq!((choice.up, choice.confidence), (DVec3::Y, 0.0));
}

/// The wasp as its artist shipped it (source.glb, Y-up, facing +X): under +Y its one labelled
/// leg hangs straight down; under +X (lying on its side) the labels make a "complete" humanoid
/// whose legs slant 40 degrees. +Y stays, and the insect gets the general skeleton as its
/// mesh.obj does, not a humanoid rig lying on its side.
#[test]
fn plumb_legs_under_y_outweigh_a_complete_figure_with_slanting_legs() {
    let Some(dir) = common::model("other/quaternius_wasp") else {
        return;
    };
    let mesh = load(&dir.join("source.glb")).unwrap();
    let labels = skelfit::anatomy::label(&mesh, &Default::default()).unwrap();
    let choice = labels.up_found.unwrap();
    assert_eq!(choice.up, DVec3::Y, "{choice:?}");
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    assert_ne!(r.fit.template, "humanoid");
}

/// A figure labelled with more limbs than the template places (the wasp: one leg and four
/// arms for a quadruped's two leg pairs) is not forced into it: the general skeleton, with
/// the reason.
#[test]
fn more_limbs_than_the_template_places_gets_the_general_skeleton() {
    let Some(dir) = common::model("other/quaternius_wasp") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let limbs = [
        skelfit::anatomy::Label::Leg,
        skelfit::anatomy::Label::Arm,
        skelfit::anatomy::Label::Wing,
    ]
    .iter()
    .map(|&l| r.labelling.count(l))
    .sum::<usize>();
    assert!(limbs > 4, "{limbs} limbs");
    assert_eq!(r.fit.template, skelfit::pipeline::GENERAL);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.to_string().contains("no template fits") && w.to_string().contains("limbs")),
        "{:?}",
        r.warnings
    );
}

/// A tail a few voxels across has no medial voxels over its last stretch, so its medial path
/// stopped far short of the tip (a rat's tail: half its length). The fit follows the tail's
/// interior voxels on to the tip, and the tail's last joint reaches it.
#[test]
fn a_thin_tail_is_followed_past_its_medial_surface_to_its_tip() {
    let tip = DVec3::new(0.0, 0.95, -2.2);
    let radius = 0.04;
    let mut parts = vec![toy_quadruped(false)];
    parts.push(capsule_between(DVec3::new(0.0, 1.0, -0.7), tip, radius));
    let mesh = merged(&parts);
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    assert_eq!(r.fit.template, "quadruped", "{:?}", r.warnings);
    let grid = r.labelling.grid;
    let medial_end = r
        .labelling
        .dms_voxels
        .iter()
        .map(|&i| grid.centre(grid.coords(i)).z)
        .fold(f64::INFINITY, f64::min);
    let tail_end = r.fit.skeleton.joint(r.fit.canonical["tail_end"]).position;
    // The medial surface stops well short of the tip: the case this is about.
    assert!(
        medial_end > tip.z + 0.3,
        "medial end {medial_end}, voxel {}",
        grid.voxel_size
    );
    // The tail's last joint reaches the tip (within a few voxels) and stays on the tail.
    let reach = tail_end.z - (tip.z - radius);
    assert!(
        reach.abs() < 3.0 * grid.voxel_size,
        "tail end {tail_end:?}, medial end {medial_end}, voxel {}",
        grid.voxel_size
    );
    assert!(tail_end.x.abs() < 2.0 * grid.voxel_size, "{tail_end:?}");
}

/// Issue 21: a biped's short arms, once labelled as its fore-limb pair, get the quadruped
/// template's fore-leg chain (scapula, shoulder, elbow, wrist on each side) and the skin of the
/// hands moves with it. Before, the arms were trunk: no fore-leg joints, the hands weighted to
/// the spine.
#[test]
fn a_bipeds_short_arms_get_a_fore_leg_chain_with_weights() {
    let mesh = crate::anatomy::short_armed_biped();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let keys = [
        "shoulder_L",
        "elbow_L",
        "wrist_L",
        "shoulder_R",
        "elbow_R",
        "wrist_R",
    ];
    assert_keys("short-armed biped", &r, &keys);
    assert_skin("short-armed biped", &mesh, &r);
    let skeleton = &r.fit.skeleton;
    for (side, sign) in [("L", 1.0), ("R", -1.0)] {
        let shoulder = r.fit.canonical[format!("shoulder_{side}").as_str()];
        let wrist = skeleton
            .joint(r.fit.canonical[format!("wrist_{side}").as_str()])
            .position;
        assert!(
            wrist.x * sign > 0.1 && wrist.z > 0.35 && wrist.y > 0.55,
            "wrist_{side} {wrist:?}"
        );
        // The shoulder's chain: every joint below it.
        let mut chain = vec![shoulder];
        let mut k = 0;
        while k < chain.len() {
            chain.extend(skeleton.children(chain[k]));
            k += 1;
        }
        // The hand's skin (the arm's last quarter) mostly follows the chain.
        let hand: Vec<usize> = (0..mesh.positions.len())
            .filter(|&v| {
                let p = mesh.positions[v];
                p.x * sign > 0.22 && p.z > 0.52 && p.y < 0.8
            })
            .collect();
        assert!(!hand.is_empty());
        let on_chain: f64 = hand
            .iter()
            .map(|&v| {
                r.skin.weights[v]
                    .iter()
                    .filter(|(j, _)| chain.contains(j))
                    .map(|(_, w)| w)
                    .sum::<f64>()
            })
            .sum::<f64>()
            / hand.len() as f64;
        assert!(
            on_chain > 0.8,
            "{side}: hand weight on the fore leg {on_chain}"
        );
    }
}

/// A jointed figure's arms (quaternius_cyberpunk_character: rigid pieces with a ball at each
/// joint) turned Z-up: a sub-voxel change of the grid had a straight arm's voxel path jog snap
/// the rough wrist a fifth of the arm inward, and the sphere trace, stopped at a seam between
/// pieces near the shoulder, gave elbow and wrist points that took the wrong balls (wrists
/// 10 %, elbows 8 % of the height off the Y-up rig). Elbows and wrists now match the Y-up
/// rig's within 5 % of the height.
#[test]
fn a_jointed_figures_arms_turned_z_up_match_the_y_up_rig() {
    let Some(dir) = common::model("humanoid/quaternius_cyberpunk_character") else {
        return;
    };
    let y_up = load(&dir.join("mesh.obj")).unwrap();
    let keys = ["elbow_L", "elbow_R", "wrist_L", "wrist_R"];
    assert_z_up_within(&y_up, &keys, 0.05);
}

/// The head's end joint (the head bone's tip) of MakeHuman bodies turned Z-up: the fit leaves
/// it at the end of the head's medial path, which wandered over the skull's dome with the voxel
/// grid (5.3 % of the height from the Y-up rig's on mh_male_heavy_short, 6.3 % on the 3k-triangle
/// body). The refinement puts it straight above the refined head joint at the head's top slice:
/// within 1 % of the Y-up rig's, and above the head joint in both.
#[test]
fn the_head_end_tops_the_head_joint_whatever_the_voxel_grid() {
    for model in [
        "humanoid/mh_male_heavy_short",
        "robustness/mh_male_young_average_dec3k",
    ] {
        let Some(dir) = common::model(model) else {
            return;
        };
        let y_up = load(&dir.join("mesh.obj")).unwrap();
        let found = rig(&y_up, &RigOptions::default()).unwrap();
        let skeleton = &found.fit.skeleton;
        let head = found.fit.canonical["head"];
        let end = skeleton.find("head_end").expect("head_end");
        let (p, q) = (
            skeleton.joints[head.0].position,
            skeleton.joints[end.0].position,
        );
        assert!(
            (q - p).normalize().y > 0.99,
            "{model}: head {p} head_end {q}"
        );
        let z_up = rig(&turned_z_up(&y_up), &RigOptions::default()).unwrap();
        let other = z_up.fit.skeleton.find("head_end").expect("head_end");
        let (lo, hi) = y_up.bounding_box().unwrap();
        let off = q.distance(z_up_turn().inverse() * z_up.fit.skeleton.joints[other.0].position)
            / (hi.y - lo.y);
        assert!(
            off < 0.01,
            "{model}: head_end differs by {:.1} %",
            100.0 * off
        );
    }
}

/// The MakeHuman body (mh_male_young_average) turned Z-up: its wrists 0.8 mm from the Y-up
/// rig's, the levels of the hand's contour tree fell so that ring and little finger did not
/// part (4 digits a hand, 5 Y-up). A hand read with fewer than five digits is read again on
/// levels half a step shifted: five digits, each joint within 1 % of the height of the Y-up
/// rig's.
#[test]
fn a_shallow_web_parts_the_fingers_of_a_z_up_hand_too() {
    let Some(dir) = common::model("humanoid/mh_male_young_average") else {
        return;
    };
    let y_up = load(&dir.join("mesh.obj")).unwrap();
    let keys: Vec<String> = ["L", "R"]
        .iter()
        .flat_map(|side| {
            ["ring", "pinky"]
                .iter()
                .flat_map(move |f| (1..=3).map(move |k| format!("{f}_0{k}_{side}")))
        })
        .collect();
    let keys: Vec<&str> = keys.iter().map(String::as_str).collect();
    assert_z_up_within(&y_up, &keys, 0.01);
}

/// The jointed figure (quaternius_cyberpunk_character) turned Z-up: the fit put the left
/// elbow a third of the arm inward and the left shoulder high and forward, and the refined left
/// shoulder, 0.127 m from that rough one, was refused as too far; symmetry then averaged the
/// rough left with the refined right (shoulders 4.5 % of the height from the Y-up rig's, core
/// error 2.1 %). A refined joint whose mirror image lies at its partner's accepted refined place
/// is accepted however far it moved: the shoulders match the Y-up rig's within 1 %.
#[test]
fn a_refined_shoulder_that_mirrors_its_partner_is_kept_far_from_a_wrong_rough_one() {
    let Some(dir) = common::model("humanoid/quaternius_cyberpunk_character") else {
        return;
    };
    let y_up = load(&dir.join("mesh.obj")).unwrap();
    let keys = ["shoulder_L", "shoulder_R"];
    assert_z_up_within(&y_up, &keys, 0.01);
}

/// A figure in a skirt (quaternius_women_formal) turned Z-up: on the turned grid a fold of the
/// skirt at the hip reaches down beside the legs and, attached where the left leg is, was
/// paired with it; the right leg stayed single, three legs made five limbs and the figure got
/// the general skeleton with no canonical joints. Legs pair with a partner of comparable
/// length first and a stub beside a biped's leg pair is no leg: it rigs as a humanoid.
#[test]
fn a_skirt_fold_beside_the_legs_is_no_leg_of_a_z_up_figure() {
    let Some(dir) = common::model("humanoid/quaternius_women_formal") else {
        return;
    };
    let mesh = turned_z_up(&load(&dir.join("mesh.obj")).unwrap());
    let found = rig(&mesh, &RigOptions::default()).unwrap();
    for key in [
        "pelvis", "knee_L", "knee_R", "ankle_L", "ankle_R", "wrist_L", "wrist_R",
    ] {
        assert!(
            found.fit.canonical.contains_key(key),
            "no {key}: {:?}",
            found.warnings
        );
    }
}

/// A figure in a long skirt (quaternius_women_formal) turned Z-up: the median silhouette's
/// lower back and buttocks were folds of the skirt, in order from top to bottom on the turned
/// grid (out of order Y-up), and the spine curve through them put `spine` 0.14 m below the
/// pelvis (9 % of the height from the Y-up rig's). A spine whose lumbar point lies below the
/// pelvis is refused: the trunk joints are carried along as Y-up, above the pelvis and within
/// 5 % of the height of the Y-up rig's.
#[test]
fn a_skirts_folds_make_no_spine_below_the_pelvis_of_a_z_up_figure() {
    let Some(dir) = common::model("humanoid/quaternius_women_formal") else {
        return;
    };
    let y_up = load(&dir.join("mesh.obj")).unwrap();
    assert_z_up_within(&y_up, &["spine", "chest"], 0.05);
    let found = rig(&turned_z_up(&y_up), &RigOptions::default()).unwrap();
    let at = |key: &str| found.fit.skeleton.joints[found.fit.canonical[key].0].position;
    assert!(
        at("spine").z > at("pelvis").z,
        "{} {}",
        at("spine"),
        at("pelvis")
    );
}

/// A cartoon figure with big fists (quaternius_platformer_character) turned Z-up: the fit's
/// rough wrist fell far out in the fist, and the wrist search, starting half that rough
/// forearm beyond the elbow, began past the wrist's narrowing (wrists 10 % of the height off
/// the Y-up rig). The search starts at most half an upper arm beyond the elbow: the wrists
/// match the Y-up rig's within 3 % of the height, with the up found automatically.
#[test]
fn a_big_fists_rough_wrist_does_not_start_the_wrist_search_past_the_wrist() {
    let Some(dir) = common::model("humanoid/quaternius_platformer_character") else {
        return;
    };
    let y_up = load(&dir.join("mesh.obj")).unwrap();
    assert_z_up_within(&y_up, &["wrist_L", "wrist_R"], 0.03);
}

/// A big-headed bunny (quaternius_platformer_character) turned Z-up labels as a whole standing
/// humanoid under -Z too: upside down its long ears hang like legs and a bump on the face is
/// the "head", below the arms. With both ends of Z complete the automatic up kept +Y (the
/// figure then rigged lying down). A humanoid's head tops its arm roots: -Z is no whole
/// humanoid and +Z is found. The spider, Y-up, whole either way along Z under those labels
/// (its head above its arms both ways), still keeps +Y.
#[test]
fn a_figure_whose_ears_hang_like_legs_upside_down_is_found_z_up() {
    let Some(dir) = common::model("humanoid/quaternius_platformer_character") else {
        return;
    };
    let found = rig(
        &turned_z_up(&load(&dir.join("mesh.obj")).unwrap()),
        &RigOptions::default(),
    )
    .unwrap();
    let choice = found.labelling.up_found.as_ref().expect("up was found");
    assert!(choice.up.distance(DVec3::Z) < 1e-9, "{choice:?}");
    assert!(choice.confidence > 0.5, "{choice:?}");
    let minus_z = choice.scores.iter().find(|s| s.name == "-Z").unwrap();
    assert!(!minus_z.complete, "{choice:?}");
    let Some(spider) = common::model("other/quaternius_spider") else {
        return;
    };
    let found = rig(
        &load(&spider.join("mesh.obj")).unwrap(),
        &RigOptions::default(),
    )
    .unwrap();
    let choice = found
        .labelling
        .up_found
        .as_ref()
        .expect("up was looked for");
    assert!(choice.up.distance(DVec3::Y) < 1e-9, "{choice:?}");
}

/// A figure that does not face the file's +Z (glTF's convention; some files face -Z or ±X) is
/// rigged facing where it does with the default options (`--forward auto`): its feet show the
/// way, its left arm's joints get the `_L` keys, the choice is reported, and the joints are
/// where the unturned rig puts them, turned. A mirror mix-up would put `shoulder_L` a
/// shoulder width off.
#[test]
fn a_body_facing_away_from_plus_z_is_rigged_facing_where_its_feet_point() {
    use skelfit::anatomy::AnatomyWarning;
    use skelfit::warning::Warning;
    let dir = common::data_dir().join("humanoid/mh_neutral_default");
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let base = rig(&mesh, &RigOptions::default()).unwrap();
    let height = 1.7;
    for (degrees, facing) in [(180.0f64, DVec3::NEG_Z), (90.0, DVec3::X)] {
        let turn = glam::DQuat::from_rotation_y(degrees.to_radians());
        let turned = common::turned_about_up(&mesh, degrees);
        let r = rig(&turned, &RigOptions::default()).unwrap();
        assert!(
            r.labelling.frame.forward.distance(facing) < 1e-9,
            "turned {degrees}: forward {}",
            r.labelling.frame.forward
        );
        assert!(
            r.warnings.iter().any(|w| matches!(
                w,
                Warning::Anatomy(AnatomyWarning::ForwardGuessed { confidence, .. }) if *confidence > 0.3
            )),
            "turned {degrees}: the choice is not reported"
        );
        for key in ["shoulder_L", "wrist_L", "hip_L", "ankle_R"] {
            let at = |r: &Rig| r.fit.skeleton.joints[r.fit.canonical[key].0].position;
            let off = at(&r).distance(turn * at(&base));
            assert!(
                off < 0.02 * height,
                "turned {degrees}: {key} {off:.3} m from the unturned rig's, turned"
            );
        }
    }
}

/// The core joints (pelvis, neck, head, shoulders, elbows, wrists, hips, knees, ankles) of
/// `r` lie within `fraction` of the height of `body` from where `alone` (the rig of `body`
/// without what was added) has them.
fn assert_core_unmoved(body: &Mesh, alone: &Rig, r: &Rig, fraction: f64) {
    let (lo, hi) = body.bounding_box().unwrap();
    let height = hi.y - lo.y;
    let at = |r: &Rig, k: &str| r.fit.skeleton.joint(r.fit.canonical[k]).position;
    for key in skelfit::eval::CORE_KEYS {
        let moved = at(r, key).distance(at(alone, key));
        assert!(moved < fraction * height, "{key} moved {moved}");
    }
}

/// A sword hanging from the right hand down beside the leg (a separate thin box: a blade 1.2 cm
/// thick, 5 cm wide, reaching to 8 cm above the ground) was labelled a third leg and the right
/// arm was lost (core error 7.9 % of the height). It is a held prop: left out of the skeleton
/// fit and of the slicing with a warning, the rig that of the body alone, and the blade bound
/// wholly to the right hand's joint so that it moves rigidly with the hand.
#[test]
fn a_sword_held_down_beside_the_leg_is_a_prop_bound_to_the_hand_not_a_leg() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default");
    let (body, alone) = rigged(&dir, &RigOptions::default());
    let at = |r: &Rig, k: &str| r.fit.skeleton.joint(r.fit.canonical[k]).position;
    let wrist = at(&alone, "wrist_R");
    let blade = Mesh::cuboid(
        DVec3::new(wrist.x - 0.025, 0.08, wrist.z - 0.006),
        DVec3::new(wrist.x + 0.025, wrist.y - 0.02, wrist.z + 0.006),
    );
    let first = body.positions.len();
    let armed = merged(&[body.clone(), blade]);
    let r = rig(&armed, &RigOptions::default()).unwrap();
    assert!(
        r.missing.is_empty(),
        "missing {:?}: {:?}",
        r.missing,
        r.warnings
    );
    assert!(
        r.warnings.iter().any(|w| w
            .to_string()
            .starts_with("1 thin rigid piece held by the figure")),
        "{:?}",
        r.warnings
    );
    assert_core_unmoved(&body, &alone, &r, 0.002);
    let hand = r.fit.canonical["wrist_R"];
    for (v, w) in r.skin.weights.iter().enumerate().skip(first) {
        assert_eq!(w, &vec![(hand, 1.0)], "blade vertex {v}");
    }
}

/// A humanoid with a tail (a lizardfolk, a cat person): a tail leaving the sacrum backwards
/// and curving down. In the median plane it continues the torso's outline down past the
/// crotch, and the hips followed it 9 % of the height low, with no warning, and the tail got
/// no bones. The refinement slices the body without the tail (its interior voxels taken out
/// of the joined solid): the core joints stay where the tailless body has them; and the
/// humanoid template builds a tail chain along it, as the quadruped's does.
#[test]
fn a_humanoids_tail_does_not_pull_its_hips_down() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default");
    let (body, alone) = rigged(&dir, &RigOptions::default());
    let at = |r: &Rig, k: &str| r.fit.skeleton.joint(r.fit.canonical[k]).position;
    let pelvis = at(&alone, "pelvis");
    let points: Vec<DVec3> = (0..=8)
        .map(|i| {
            let t = i as f64 / 8.0;
            DVec3::new(
                0.0,
                pelvis.y + 0.02 - 0.45 * t.powf(1.3),
                pelvis.z - 0.08 - 0.7 * t,
            )
        })
        .collect();
    let mut parts = vec![body.clone()];
    for (i, w) in points.windows(2).enumerate() {
        parts.push(capsule_between(w[0], w[1], 0.055 - 0.004 * i as f64));
    }
    let tailed = merged(&parts);
    let r = rig(&tailed, &RigOptions::default()).unwrap();
    assert!(r.missing.is_empty(), "missing {:?}", r.missing);
    assert!(
        r.labelling
            .parts
            .iter()
            .any(|p| p.label == skelfit::anatomy::Label::Tail),
        "no tail labelled"
    );
    assert_core_unmoved(&body, &alone, &r, 0.015);
    let height = {
        let (lo, hi) = body.bounding_box().unwrap();
        hi.y - lo.y
    };
    // The tail gets its own chain, from its root to its tip.
    let (root, tip) = (points[0], points[points.len() - 1]);
    let base = at(&r, "tail_base");
    let end = at(&r, "tail_end");
    assert!(
        base.distance(root) < 0.1 * height,
        "tail base at {base}, root {root}"
    );
    assert!(
        end.distance(tip) < 0.05 * height,
        "tail end at {end}, tip {tip}"
    );
    assert!(
        !alone.fit.canonical.contains_key("tail_base"),
        "a tailless body got a tail"
    );
}

/// Hair made of cards, as game characters' is: 150 small open quads over the scalp, those at
/// the back hanging down to the shoulders. A ray through several cards wound the same way
/// counted one per card and outvoted the other five directions of the inside/outside vote:
/// bars of "inside" voxels grew across the grid, and the body was rigged as no humanoid at all
/// (five legs, one arm, the general skeleton). Each direction now votes once, and the cards,
/// small open sheets that enclose nothing, are left out of the voxels and of the slicing: the
/// rig is the bald body's.
#[test]
fn hair_cards_on_the_head_leave_the_rig_of_the_bald_body() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default");
    let (body, alone) = rigged(&dir, &RigOptions::default());
    let head = alone
        .fit
        .skeleton
        .joint(alone.fit.canonical["head"])
        .position;
    let top = body.bounding_box().unwrap().1.y;
    let mut hair = Mesh::default();
    let (radius, width) = (0.11, 0.03);
    for k in 0..150 {
        // A golden-angle spiral over the cap up to 1.2 rad from the crown.
        let theta = k as f64 * 2.399_963;
        let phi = (1.0 - (k as f64 + 0.5) / 150.0 * (1.0 - 1.2_f64.cos())).acos();
        let (s, c) = theta.sin_cos();
        let root = DVec3::new(
            head.x + radius * phi.sin() * c,
            top - 0.02 - radius * (1.0 - phi.cos()),
            head.z - 0.01 + radius * phi.sin() * s,
        );
        let length = if s < 0.0 {
            0.1 + 0.2 * ((k * 7) % 10) as f64 / 10.0
        } else {
            0.05
        };
        let across = DVec3::new(-s, 0.0, c) * width;
        let down = DVec3::new(0.02 * c, -length, 0.02 * s);
        let first = hair.positions.len() as u32;
        hair.positions.extend([
            root + across,
            root - across,
            root + across + down,
            root - across + down,
        ]);
        hair.triangles
            .extend([[0, 2, 1], [1, 2, 3]].map(|t: [u32; 3]| t.map(|i| i + first)));
    }
    let haired = merged(&[body.clone(), hair]);
    let r = rig(&haired, &RigOptions::default()).unwrap();
    assert!(
        r.missing.is_empty(),
        "missing {:?}: {:?}",
        r.missing,
        r.warnings
    );
    assert_eq!(
        r.solid.report.sheets, 150,
        "every card left out of the voxels"
    );
    assert_core_unmoved(&body, &alone, &r, 0.002);
}

/// A robe: an open bell (wound outwards, as single-sided clothing is) hanging from the waist
/// to mid-shin over the legs. The winding vote fills it, so the labels see legs only below its
/// hem, and the rig came out with the pelvis 31 % of the height low and no warning at all.
/// Four things went wrong, each now checked against the figure's proportions:
/// - the rough legs (shins below the hem) leaned 21° and tilted every slice with them: legs
///   leaning more than 15° no longer set the body's up;
/// - the crotch the silhouette gave (where the shins part below the hem) put the hips 0.29 of
///   the height below where the arms put them: that is no crotch, and clothing hides it;
/// - the hips and pelvis so placed were rejected as too far from the rough ones: a pelvis
///   between accepted hips is accepted;
/// - the knees, which the leg's trace cannot reach, stayed at the rough knees: they go on the
///   line from hip to ankle.
#[test]
fn a_robe_over_the_legs_keeps_the_hips_where_the_arms_put_them() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default");
    let (body, alone) = rigged(&dir, &RigOptions::default());
    let (lo, hi) = body.bounding_box().unwrap();
    let height = hi.y - lo.y;
    let at = |r: &Rig, k: &str| r.fit.skeleton.joint(r.fit.canonical[k]).position;
    let pelvis = at(&alone, "pelvis");
    let (top, hem) = (
        pelvis.y + 0.05,
        0.5 * (at(&alone, "knee_L").y + at(&alone, "ankle_L").y),
    );
    let mut coat = Mesh::default();
    let (rows, segments) = (10_u32, 32_u32);
    for r in 0..=rows {
        let t = r as f64 / rows as f64;
        let radius = 0.19 * (1.0 + 0.6 * t);
        for k in 0..segments {
            let a = k as f64 / segments as f64 * std::f64::consts::TAU;
            coat.positions.push(DVec3::new(
                pelvis.x + 1.15 * radius * a.cos(),
                top + (hem - top) * t,
                pelvis.z + 0.9 * radius * a.sin(),
            ));
        }
    }
    for r in 0..rows {
        for k in 0..segments {
            let (a, b) = (r * segments + k, r * segments + (k + 1) % segments);
            coat.triangles
                .extend([[a, b, a + segments], [b, b + segments, a + segments]]);
        }
    }
    let coated = merged(&[body.clone(), coat]);
    let r = rig(&coated, &RigOptions::default()).unwrap();
    assert!(r.missing.is_empty(), "missing {:?}", r.missing);
    for (key, limit) in [
        ("pelvis", 0.05),
        ("hip_L", 0.05),
        ("hip_R", 0.05),
        ("knee_L", 0.04),
        ("knee_R", 0.04),
    ] {
        let off = at(&r, key).distance(at(&alone, key));
        assert!(off < limit * height, "{key} {off} off: {:?}", r.warnings);
    }
}

/// Rigs `mesh` and its copies turned about up by each of `turns` (degrees) with the default
/// options, asserts that each of `keys` of every turned rig lies within `bound` of the height
/// of the unturned rig's joint, turned, and returns the turned rigs with their turns.
fn assert_turned_within(mesh: &Mesh, turns: &[f64], keys: &[&str], bound: f64) -> Vec<(f64, Rig)> {
    let (lo, hi) = mesh.bounding_box().unwrap();
    let height = hi.y - lo.y;
    let base = rig(mesh, &RigOptions::default()).unwrap();
    let at = |r: &Rig, key: &str| r.fit.skeleton.joint(r.fit.canonical[key]).position;
    turns
        .iter()
        .map(|&degrees| {
            let turn = glam::DQuat::from_rotation_y(degrees.to_radians());
            let r = rig(
                &common::turned_about_up(mesh, degrees),
                &RigOptions::default(),
            )
            .unwrap();
            for key in keys {
                let off = at(&r, key).distance(turn * at(&base, key));
                assert!(
                    off < bound * height,
                    "turned {degrees}: {key} {off:.3} from the unturned rig's"
                );
            }
            (degrees, r)
        })
        .collect()
}

/// Paired limbs mirror each other. A figure turned a few degrees off the file's axes falls
/// differently on the voxels, and the medial path of one hand broke off at the palm
/// (quaternius_women_formal turned 3°: the left arm's path ended at the wrist, 0.44 out from
/// the median plane against the right arm's 0.64): the fit spread the left arm's joints over
/// the shorter path, the refinement's trace stopped short of the hand and the wrists were
/// found 4 cm in (gdquest_mannequiny turned -3°: 9 cm). The shorter path is carried on through
/// its part's voxels as far as its partner's reaches, and the wrists stay where the unturned
/// rig has them.
#[test]
fn a_hand_whose_medial_path_breaks_off_reaches_as_far_as_its_partner() {
    use skelfit::template::LimbKind;
    for model in [
        "humanoid/quaternius_women_formal",
        "humanoid/gdquest_mannequiny",
    ] {
        let Some(dir) = common::model(model) else {
            return;
        };
        let mesh = load(&dir.join("mesh.obj")).unwrap();
        let turned = assert_turned_within(&mesh, &[-3.0, 3.0], &["wrist_L", "wrist_R"], 0.015);
        for (degrees, r) in turned {
            // How far out each arm's path reaches from the median plane between the roots.
            let arms: Vec<_> = (r.input.limbs.iter())
                .filter(|l| l.kind == LimbKind::Arm)
                .collect();
            assert_eq!(arms.len(), 2, "{model} turned {degrees}");
            let centre = 0.5 * (arms[0].root.unwrap() + arms[1].root.unwrap());
            let left = r.labelling.frame.left;
            let reach: Vec<f64> = (arms.iter())
                .map(|l| (*l.path.last().unwrap() - centre).dot(left).abs())
                .collect();
            let ratio = reach[0].min(reach[1]) / reach[0].max(reach[1]);
            assert!(
                ratio > 0.9,
                "{model} turned {degrees}: the arms' paths reach {reach:.3?}"
            );
        }
    }
}

/// The head's long axis corrects the body's facing by a few degrees at most. Turned 1° about
/// up, quaternius_cyberpunk_character's visored head gave an axis 6° off the figure's facing;
/// the frame turned with it moved the armpits' frontal slices, the refined shoulder landed
/// where the rough one was rejected and both shoulders were left 7 cm (5 % of the height) in
/// and up. The head now turns the frame by at most 3°, and the shoulders stay where the
/// unturned rig has them.
#[test]
fn a_head_axis_a_few_degrees_off_the_facing_leaves_the_shoulders_alone() {
    let Some(dir) = common::model("humanoid/quaternius_cyberpunk_character") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    assert_turned_within(&mesh, &[-1.0, 1.0], &["shoulder_L", "shoulder_R"], 0.015);
}

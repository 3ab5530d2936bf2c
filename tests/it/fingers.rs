//! Digits of the hands (issue 25): the 30 finger joints of the MakeHuman bodies against their
//! game_engine rigs, thumbs on their side of the palm, hands in T-pose, finger curls, mittens.

use glam::{DQuat, DVec3};
use skelfit::digits::DigitWarning;
use skelfit::eval::load_skeleton;
use skelfit::mesh::{load, Mesh};
use skelfit::pipeline::{rig, Rig, RigOptions};
use skelfit::skeleton::canonical::{Finger, DIGITS};
use skelfit::skeleton::{Canonical, Side};
use skelfit::skin::deform;
use skelfit::warning::Warning;

fn digit_warnings(r: &Rig) -> Vec<DigitWarning> {
    r.warnings
        .iter()
        .filter_map(|w| match w {
            Warning::Digits(d) => Some(d.clone()),
            _ => None,
        })
        .collect()
}

fn bundled() -> Mesh {
    load(&crate::common::data_dir().join("humanoid/mh_neutral_default/mesh.obj")).unwrap()
}

/// Every MakeHuman body: mean error over the 30 finger joints ≤ 8 mm against rig_game_engine
/// (reference names through the MakeHuman preset), and each thumb nearer the reference thumb
/// than the reference pinky (the thumb on the correct side of the palm).
#[test]
fn makehuman_fingers_are_within_8_mm_with_thumbs_on_their_side() {
    let Some(dirs) = crate::common::makehuman_bodies() else {
        return;
    };
    for dir in dirs {
        let mesh = load(&dir.join("mesh.obj")).unwrap();
        let r = rig(&mesh, &RigOptions::default()).unwrap();
        assert!(
            digit_warnings(&r).is_empty(),
            "{dir:?}: {:?}",
            digit_warnings(&r)
        );
        let reference = load_skeleton(&dir.join("rig_game_engine.json")).unwrap();
        let (ref_map, _) = skelfit::eval::canonical_map(&reference);
        let at = |key: &str| r.fit.skeleton.joint(r.fit.canonical[key]).position;
        let truth = |key: &str| reference.skeleton.joint(ref_map[key]).position;
        let errors: Vec<f64> = DIGITS
            .iter()
            .map(|k| at(k.as_str()).distance(truth(k.as_str())) * 1000.0)
            .collect();
        let mean = errors.iter().sum::<f64>() / errors.len() as f64;
        println!("{}: finger joints mean {mean:.1} mm", dir.display());
        assert!(mean <= 8.0, "{dir:?}: mean {mean:.1} mm {errors:?}");
        for side in Side::BOTH {
            let thumb = at(Canonical::Digit(side, Finger::Thumb, 2).as_str());
            let t = truth(Canonical::Digit(side, Finger::Thumb, 2).as_str());
            let p = truth(Canonical::Digit(side, Finger::Pinky, 2).as_str());
            assert!(thumb.distance(t) < thumb.distance(p), "{dir:?} {side:?}");
        }
    }
}

/// The bundled body with its arms turned about the shoulders (`angle` radians up from the rest
/// A-pose in the frontal plane) through its own rig.
fn posed(mesh: &Mesh, r: &Rig, angle: impl Fn(DVec3) -> f64) -> Mesh {
    let (skeleton, canonical) = (&r.fit.skeleton, &r.fit.canonical);
    let mut pose = skeleton.rest_pose();
    for (side, sign) in [("L", 1.0), ("R", -1.0)] {
        let id = canonical[&format!("shoulder_{side}")];
        let arm = skeleton.joint(canonical[&format!("wrist_{side}")]).position
            - skeleton.joint(id).position;
        let turn = DQuat::from_rotation_z(sign * angle(arm));
        let frame = skeleton.world_transforms(&pose)[id.0]
            .to_scale_rotation_translation()
            .1;
        pose[id.0] = frame.inverse() * turn * frame;
    }
    deform(mesh, skeleton, &r.skin, &pose).unwrap()
}

/// Hands in T-pose (arms horizontal) and hanging (arms turned down by 30°) keep five digits
/// each, thumbs first.
#[test]
fn t_pose_and_hanging_hands_keep_five_digits() {
    let mesh = bundled();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    assert!(digit_warnings(&r).is_empty(), "{:?}", digit_warnings(&r));
    let t_pose = posed(&mesh, &r, |arm| (-arm.y).atan2(arm.x.abs()));
    let hanging = posed(&mesh, &r, |_| -0.5);
    for (name, m) in [("t-pose", t_pose), ("hanging", hanging)] {
        let p = rig(&m, &RigOptions::default()).unwrap();
        assert!(
            digit_warnings(&p).is_empty(),
            "{name}: {:?}",
            digit_warnings(&p)
        );
        for key in DIGITS {
            assert!(p.fit.canonical.contains_key(key.as_str()), "{name}: {key}");
        }
    }
}

/// Curling every finger 90° (base joint about its x axis) stretches no hand edge past 2× (was
/// 2.78× at the index/middle web before the web's vertices blended both neighbouring digits).
#[test]
fn curling_every_finger_90_degrees_stretches_no_edge_past_twice() {
    let mesh = bundled();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let (skeleton, canonical) = (&r.fit.skeleton, &r.fit.canonical);
    let mut pose = skeleton.rest_pose();
    for key in DIGITS
        .iter()
        .filter(|k| matches!(k, Canonical::Digit(_, f, 1) if *f != Finger::Thumb))
    {
        pose[canonical[key.as_str()].0] = DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2);
    }
    let curled = deform(&mesh, skeleton, &r.skin, &pose).unwrap();
    let mut worst: f64 = 1.0;
    let mut at = (0, 0);
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            let rest = mesh.positions[a].distance(mesh.positions[b]);
            if rest > 0.0 {
                let stretch = curled.positions[a].distance(curled.positions[b]) / rest;
                if stretch > worst {
                    (worst, at) = (stretch, (a, b));
                }
            }
        }
    }
    let names = |v: usize| -> Vec<(String, f64)> {
        r.skin.weights[v]
            .iter()
            .map(|(j, w)| (skeleton.joint(*j).name.clone(), *w))
            .collect()
    };
    println!(
        "curl: worst edge stretch {worst:.2} between {:?} {:?} and {:?} {:?}",
        mesh.positions[at.0],
        names(at.0),
        mesh.positions[at.1],
        names(at.1)
    );
    assert!(worst <= 2.0, "worst edge stretch {worst:.2}");
}

/// A mitten-handed game character gets the fused-fingers warning naming the hand (no panic),
/// and a hand without a mesh beyond the wrist is a warning, not a failure.
#[test]
fn mitten_hands_warn_that_the_fingers_are_fused() {
    let Some(dir) = crate::common::model("humanoid/quaternius_knight") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let w = digit_warnings(&r);
    assert!(
        w.iter()
            .any(|w| matches!(w, DigitWarning::FingersFused { .. })),
        "{w:?}"
    );
    assert!(
        w.iter().any(|w| w.to_string().contains("left hand")),
        "{w:?}"
    );
}

/// Hands modelled as separate mesh pieces beyond the wrist (the Quaternius cyberpunk and
/// platformer characters) are found: no hand is reported missing (regression: `no_hand`
/// when the surface distance started only behind the wrist plane).
#[test]
fn hands_that_are_separate_mesh_pieces_are_found() {
    for name in [
        "quaternius_cyberpunk_character",
        "quaternius_platformer_character",
    ] {
        let Some(dir) = crate::common::model(&format!("humanoid/{name}")) else {
            continue;
        };
        let mesh = load(&dir.join("mesh.obj")).unwrap();
        let r = rig(&mesh, &RigOptions::default()).unwrap();
        let w = digit_warnings(&r);
        println!("{name}: {w:?}");
        assert!(
            !w.iter().any(|w| matches!(w, DigitWarning::NoHand { .. })),
            "{name}: {w:?}"
        );
    }
}

/// `skelfit bones` keeps the digits' bones: sized on the surface (fingers are thinner than the
/// voxels), every finger of the bundled body gets its three bones, each inside the figure,
/// where the voxel figure alone left them out.
#[test]
fn finger_bones_are_sized_on_the_surface() {
    use skelfit::bones::{bones, bones_with_surface, BoneOptions};
    let mesh = bundled();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let digit_joints: Vec<_> = DIGITS.iter().map(|k| r.fit.canonical[k.as_str()]).collect();
    let voxel = bones(&r.fit, &r.distance, &BoneOptions::default()).unwrap();
    let fine = bones_with_surface(&r.fit, &r.distance, &mesh, &BoneOptions::default()).unwrap();
    let on_digit = |b: &&skelfit::bones::Bone| digit_joints.contains(&b.joint);
    let before = voxel.bones.iter().filter(on_digit).count();
    let after: Vec<&skelfit::bones::Bone> = fine.bones.iter().filter(on_digit).collect();
    println!(
        "digit bones: {before} on the voxels, {} on the surface",
        after.len()
    );
    assert_eq!(after.len(), DIGITS.len(), "{:?}", fine.warnings);
    for b in after {
        let n = b.mesh.positions.len() as f64;
        let centre = b.mesh.positions.iter().sum::<DVec3>() / n;
        assert!(
            skelfit::mesh::winding_number(&mesh, centre) > 0.5,
            "{} at {centre}",
            b.name
        );
    }
}

/// Per vertex of `r`'s mesh, whether its largest skin weight is on a joint of the left hand's
/// digit `digit` (`index`, `pinky`...).
fn left_digit_vertices(r: &Rig, digit: &str) -> Vec<bool> {
    let sk = &r.fit.skeleton;
    r.skin
        .weights
        .iter()
        .map(|w| {
            w.iter()
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .is_some_and(|&(j, _)| {
                    let name = &sk.joint(j).name;
                    name.starts_with(digit)
                        && name[digit.len()..].starts_with('_')
                        && name.ends_with("_L")
                })
        })
        .collect()
}

/// Asserts that `warnings` name the left hand with `found` separated digits and that the rig
/// `p` still has the left thumb.
fn assert_left_hand_counted(p: &Rig, warnings: &[DigitWarning], found: usize) {
    assert!(
        warnings.iter().any(|w| matches!(
            w,
            DigitWarning::DigitCount {
                side: Side::Left,
                found: f
            } if *f == found
        )),
        "{warnings:?}"
    );
    assert!(
        p.fit
            .canonical
            .contains_key(Canonical::Digit(Side::Left, Finger::Thumb, 1).as_str()),
        "the left thumb"
    );
}

/// The bundled body without its left index finger (the triangles of the vertices its joints
/// move most removed, leaving an open hole at the knuckle): the left hand gets the four digits
/// it shows with a warning naming that hand (issue 25, bad input), never a panic.
#[test]
fn a_missing_finger_is_named_in_a_warning() {
    let mesh = bundled();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let cut = left_digit_vertices(&r, "index");
    assert!(cut.iter().filter(|&&c| c).count() > 20, "no finger to cut");
    assert!(
        (0..cut.len()).all(|v| !cut[v] || mesh.positions[v].x > 0.0),
        "the left hand is at +x"
    );
    let triangles: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .copied()
        .filter(|t| t.iter().all(|&v| !cut[v as usize]))
        .collect();
    let maimed = Mesh::new(mesh.positions.clone(), triangles).unwrap();
    let p = rig(&maimed, &RigOptions::default()).unwrap();
    let warnings = digit_warnings(&p);
    println!("{warnings:?}");
    for k in DIGITS {
        if !p.fit.canonical.contains_key(k.as_str()) {
            println!("missing {}", k.as_str());
        }
    }
    assert_left_hand_counted(&p, &warnings, 4);
}

/// Hands hanging against the thighs (the arms turned down until the fingertips lie on the
/// thighs' surface) still rig without a panic: each hand keeps its five digits or the rig
/// names that hand in a warning (issue 25, bad input).
#[test]
fn hands_touching_the_thighs_keep_their_digits_or_are_named() {
    let mesh = bundled();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let pressed = posed(&mesh, &r, |_| -0.75);
    let p = rig(&pressed, &RigOptions::default()).unwrap();
    let warnings = digit_warnings(&p);
    println!("{warnings:?}");
    for side in Side::BOTH {
        let complete = DIGITS
            .iter()
            .filter(|k| k.as_str().ends_with(side.suffix()))
            .all(|k| p.fit.canonical.contains_key(k.as_str()));
        let named = warnings
            .iter()
            .any(|w| w.to_string().contains(side.as_str()));
        assert!(complete || named, "{side:?}: {warnings:?}");
    }
}

/// The bundled body with a sixth digit on its left hand: a copy of the pinky that shares the
/// pinky's base ring (the corners where the pinky's triangles meet the palm's) and splays away
/// from the ring finger, by one finger spacing at the tip. The rig does not panic, the right
/// hand keeps its five digits without a warning, and the left hand is named in a warning that
/// says six digits separate, its thumb still found (issue 25, bad input: six fingers).
#[test]
fn a_sixth_finger_is_named_in_a_warning() {
    let mesh = bundled();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let sk = &r.fit.skeleton;
    let joint = |k: &str| sk.joint(r.fit.canonical[k]).position;
    let pinky = left_digit_vertices(&r, "pinky");
    assert!(
        pinky.iter().filter(|&&c| c).count() > 20,
        "no pinky to copy"
    );
    // The base ring: pinky corners that also belong to a triangle with a non-pinky corner.
    let mut ring = vec![false; pinky.len()];
    for t in &mesh.triangles {
        if t.iter().any(|&v| !pinky[v as usize]) {
            for &v in t {
                ring[v as usize] |= pinky[v as usize];
            }
        }
    }
    let spacing = joint("pinky_01_L") - joint("ring_01_L");
    let (base, tip) = (joint("pinky_01_L"), joint("pinky_03_L"));
    let reach = base.distance(tip);
    assert!(spacing.length() > 0.005 && reach > 0.01, "a pinky to copy");
    let mut positions = mesh.positions.clone();
    let mut copy: Vec<u32> = (0..positions.len() as u32).collect();
    for v in (0..pinky.len()).filter(|&v| pinky[v] && !ring[v]) {
        let p = mesh.positions[v];
        copy[v] = positions.len() as u32;
        positions.push(p + spacing * (p.distance(base) / reach).min(1.0));
    }
    let mut triangles = mesh.triangles.clone();
    triangles.extend(
        mesh.triangles
            .iter()
            .filter(|t| t.iter().all(|&v| pinky[v as usize]))
            .map(|t| t.map(|v| copy[v as usize])),
    );
    let six = Mesh::new(positions, triangles).unwrap();
    let p = rig(&six, &RigOptions::default()).unwrap();
    let warnings = digit_warnings(&p);
    println!("{warnings:?}");
    let complete = DIGITS
        .iter()
        .filter(|k| k.as_str().ends_with(Side::Right.suffix()))
        .all(|k| p.fit.canonical.contains_key(k.as_str()));
    assert!(complete, "the right hand keeps five digits");
    assert!(
        warnings
            .iter()
            .all(|w| !w.to_string().contains(Side::Right.as_str())),
        "{warnings:?}"
    );
    assert_left_hand_counted(&p, &warnings, 6);
}

//! Feet (issue 25): the toe joint at the ball of the foot and the toe end at its tip on the
//! MakeHuman bodies against their reference rigs, the real humanoids' toes, toe bends, and the
//! single digit chain of an animal's feet.

use glam::{DQuat, DVec3};
use skelfit::digits::DigitWarning;
use skelfit::eval::load_skeleton;
use skelfit::mesh::{load, winding_number, Mesh};
use skelfit::pipeline::{rig, Rig, RigOptions};
use skelfit::skeleton::{Canonical, Side};
use skelfit::skin::deform;
use skelfit::warning::Warning;

fn foot_warnings(r: &Rig) -> Vec<DigitWarning> {
    r.warnings
        .iter()
        .filter_map(|w| match w {
            Warning::Digits(d @ DigitWarning::NoFoot { .. }) => Some(d.clone()),
            _ => None,
        })
        .collect()
}

/// The `tail` of joint `name` in a refdata rig file (MakeHuman bones have tails).
fn tail(path: &std::path::Path, name: &str) -> DVec3 {
    let rig: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let joint = rig["joints"]
        .as_array()
        .unwrap()
        .iter()
        .find(|j| j["name"] == name)
        .unwrap();
    let t: Vec<f64> = serde_json::from_value(joint["tail"].clone()).unwrap();
    DVec3::new(t[0], t[1], t[2])
}

fn height(mesh: &Mesh) -> f64 {
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    hi - lo
}

/// The joint at the end of the chain below `id` (each joint's only child, to the leaf).
fn chain_end(r: &Rig, id: skelfit::skeleton::JointId) -> skelfit::skeleton::JointId {
    let mut at = id;
    while let [only] = r.fit.skeleton.children(at).as_slice() {
        at = *only;
    }
    at
}

/// Every MakeHuman body: the toe joint within 1.2 % of the height of the reference's ball of
/// the foot (`ball_l`, rig_game_engine) and the toe end within 1.2 % of the reference's toe
/// tip (the tail of `ball_l`); the Mixamo rig's `ToeBase` (1.7 cm further forward and up) is
/// printed beside it.
#[test]
fn makehuman_toes_sit_at_the_ball_and_the_tip_of_the_foot() {
    let Some(dirs) = crate::common::makehuman_bodies() else {
        return;
    };
    for dir in dirs {
        let mesh = load(&dir.join("mesh.obj")).unwrap();
        let h = height(&mesh);
        let r = rig(&mesh, &RigOptions::default()).unwrap();
        assert!(
            foot_warnings(&r).is_empty(),
            "{dir:?}: {:?}",
            foot_warnings(&r)
        );
        let game = load_skeleton(&dir.join("rig_game_engine.json")).unwrap();
        let mixamo = load_skeleton(&dir.join("rig_mixamo.json")).unwrap();
        let (game_map, _) = skelfit::eval::canonical_map(&game);
        let (mixamo_map, _) = skelfit::eval::canonical_map(&mixamo);
        for side in Side::BOTH {
            let key = Canonical::Toe(side).as_str();
            let toe = r.fit.canonical[key];
            let at = r.fit.skeleton.joint(toe).position;
            let end = r.fit.skeleton.joint(chain_end(&r, toe)).position;
            let ball = game.skeleton.joint(game_map[key]).position;
            let tip = tail(
                &dir.join("rig_game_engine.json"),
                &game.skeleton.joint(game_map[key]).name,
            );
            let base = mixamo.skeleton.joint(mixamo_map[key]).position;
            let (e_ball, e_tip) = (at.distance(ball), end.distance(tip));
            println!(
                "{} {side:?}: toe {:.1} mm ({:.2} %), toe end {:.1} mm ({:.2} %); Mixamo ToeBase {:.1} mm",
                dir.file_name().unwrap().to_string_lossy(),
                e_ball * 1000.0,
                100.0 * e_ball / h,
                e_tip * 1000.0,
                100.0 * e_tip / h,
                at.distance(base) * 1000.0
            );
            assert!(
                e_ball <= 0.012 * h,
                "{dir:?} {side:?}: toe at {at} vs {ball}"
            );
            assert!(
                e_tip <= 0.012 * h,
                "{dir:?} {side:?}: end at {end} vs {tip}"
            );
        }
    }
}

/// The real humanoids whose reference maps a toe: the toe joint lies inside the foot, ahead of
/// the ankle and behind the toe end, and its error is printed (artists put the ball anywhere
/// from the middle of a shoe to the toes).
#[test]
fn real_humanoid_toes_lie_in_the_forefoot() {
    for name in ["gdquest_mannequiny", "gltf_cesium_man"] {
        let Some(dir) = crate::common::model(&format!("humanoid/{name}")) else {
            continue;
        };
        let mesh = load(&dir.join("mesh.obj")).unwrap();
        let h = height(&mesh);
        let r = rig(&mesh, &RigOptions::default()).unwrap();
        assert!(
            foot_warnings(&r).is_empty(),
            "{name}: {:?}",
            foot_warnings(&r)
        );
        let reference = load_skeleton(&dir.join("rig_gltf.json")).unwrap();
        let (map, _) = skelfit::eval::canonical_map(&reference);
        for side in Side::BOTH {
            let key = Canonical::Toe(side).as_str();
            let toe = r.fit.canonical[key];
            let at = r.fit.skeleton.joint(toe).position;
            let ankle = r
                .fit
                .skeleton
                .joint(r.fit.canonical[Canonical::Ankle(side).as_str()]);
            let end = r.fit.skeleton.joint(chain_end(&r, toe)).position;
            let e = at.distance(reference.skeleton.joint(map[key]).position);
            println!(
                "{name} {side:?}: toe {:.1} mm ({:.2} % of height)",
                e * 1000.0,
                100.0 * e / h
            );
            assert!(winding_number(&mesh, at) > 0.5, "{name} {side:?}: {at}");
            let forward = (end - ankle.position) * DVec3::new(1.0, 0.0, 1.0);
            assert!((at - ankle.position).dot(forward) > 0.0, "{name} {side:?}");
            assert!((end - at).dot(forward) > 0.0, "{name} {side:?}");
        }
    }
}

/// Every humanoid in the reference data, whatever its feet (shoes, a knight's boxy boots whose
/// shaft a coarse mesh's triangles carry far above the ankle, a cartoon's round stubs): each
/// joint of the toe chain lies no higher than the ankle and no nearer the heel, along the
/// figure's forward, and the chain's end lies ahead of the ankle unless the leg has no foot
/// (a peg leg, with its warning). The knight's toes once ran up
/// the back of its boot, its end 6 % of the height above the ankle.
#[test]
fn toes_lie_below_the_ankle_and_point_where_the_figure_faces() {
    let Some(root) = crate::common::refdata() else {
        return;
    };
    let mut seen = 0;
    for entry in std::fs::read_dir(root.join("humanoid")).unwrap() {
        let dir = entry.unwrap().path();
        let Ok(mesh) = load(&dir.join("mesh.obj")) else {
            continue;
        };
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        let r = rig(&mesh, &RigOptions::default()).unwrap();
        let (up, forward) = (r.input.up, r.input.forward);
        let h = height(&mesh);
        for side in Side::BOTH {
            let (Some(&ankle), Some(&toe)) = (
                r.fit.canonical.get(Canonical::Ankle(side).as_str()),
                r.fit.canonical.get(Canonical::Toe(side).as_str()),
            ) else {
                continue;
            };
            let a = r.fit.skeleton.joint(ankle).position;
            let mut at = toe;
            loop {
                let p = r.fit.skeleton.joint(at).position;
                let name_at = &r.fit.skeleton.joint(at).name;
                assert!(
                    (p - a).dot(up) <= 0.01 * h,
                    "{name} {side:?}: {name_at} at {p} above the ankle {a}"
                );
                assert!(
                    (p - a).dot(forward) >= -0.01 * h,
                    "{name} {side:?}: {name_at} at {p} behind the ankle {a}"
                );
                match r.fit.skeleton.children(at).as_slice() {
                    [only] => at = *only,
                    _ => break,
                }
            }
            let end = r.fit.skeleton.joint(at).position;
            // A peg leg has no foot (and says so): its chain keeps the fit's, straight down.
            let no_foot = foot_warnings(&r)
                .iter()
                .any(|w| matches!(w, DigitWarning::NoFoot { side: s } if *s == side));
            assert!(
                no_foot || (end - a).dot(forward) > 0.03 * h,
                "{name} {side:?}: toe end {end} not ahead of the ankle {a}"
            );
        }
        seen += 1;
    }
    println!("{seen} humanoids checked");
}

/// Bending the toes 40° up and 40° down at the ball of the foot (about the toe joint's x axis)
/// stretches no edge of the bundled body past 2×.
#[test]
fn bending_the_toes_stretches_no_edge_past_twice() {
    let mesh =
        load(&crate::common::data_dir().join("humanoid/mh_neutral_default/mesh.obj")).unwrap();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let (skeleton, canonical) = (&r.fit.skeleton, &r.fit.canonical);
    for angle in [40f64, -40.0] {
        let mut pose = skeleton.rest_pose();
        for side in Side::BOTH {
            let toe = canonical[Canonical::Toe(side).as_str()];
            pose[toe.0] = DQuat::from_rotation_x(angle.to_radians());
        }
        let bent = deform(&mesh, skeleton, &r.skin, &pose).unwrap();
        let mut worst: f64 = 1.0;
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
                let rest = mesh.positions[a].distance(mesh.positions[b]);
                if rest > 0.0 {
                    worst = worst.max(bent.positions[a].distance(bent.positions[b]) / rest);
                }
            }
        }
        println!("toes bent {angle}°: worst edge stretch {worst:.2}");
        assert!(
            worst <= 2.0,
            "toes bent {angle}°: worst edge stretch {worst:.2}"
        );
        // The toe tips moved: the bend reaches the toes.
        let tip = r
            .fit
            .skeleton
            .joint(chain_end(&r, canonical["toe_L"]))
            .position;
        let near = (0..mesh.positions.len())
            .min_by(|&a, &b| {
                mesh.positions[a]
                    .distance(tip)
                    .total_cmp(&mesh.positions[b].distance(tip))
            })
            .unwrap();
        assert!(bent.positions[near].distance(mesh.positions[near]) > 0.01);
    }
}

/// A four-legged animal's paws (the Khronos fox) keep one digit chain per foot: the toe key
/// mapped, a chain of single joints below it to its end, no foot warning.
#[test]
fn animal_paws_keep_a_single_digit_chain() {
    let Some(dir) = crate::common::model("quadruped/khronos_fox") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    assert!(foot_warnings(&r).is_empty(), "{:?}", foot_warnings(&r));
    for side in Side::BOTH {
        let toe = r.fit.canonical[Canonical::Toe(side).as_str()];
        let end = chain_end(&r, toe);
        assert_ne!(end, toe, "{side:?}: no digit below the toe");
        assert!(r.fit.skeleton.children(end).is_empty());
    }
}

/// A hoof's dewclaw is not a digit (issue 21): the cow's and the deer's fore hooves show a
/// second branch, a dewclaw high behind the hoof standing free for less than half the length
/// the template gives a digit's phalanges, so they keep one digit chain per foot as the
/// horse's hoof does (before, the dewclaw was taken for the fourth digit of a cloven hoof).
/// Hooves never get a thumb or a hand warning.
#[test]
fn hooves_with_a_dewclaw_keep_one_digit_chain_and_no_hand_warnings() {
    for model in [
        "quadruped/quaternius_cow",
        "quadruped/quaternius_deer",
        "quadruped/quaternius_horse",
    ] {
        let Some(dir) = crate::common::model(model) else {
            return;
        };
        let mesh = load(&dir.join("mesh.obj")).unwrap();
        let r = rig(&mesh, &RigOptions::default()).unwrap();
        let hand_warnings: Vec<String> = r
            .warnings
            .iter()
            .filter(|w| matches!(w, Warning::Digits(_)))
            .map(|w| w.to_string())
            .collect();
        assert!(hand_warnings.is_empty(), "{model}: {hand_warnings:?}");
        let sk = &r.fit.skeleton;
        assert!(
            !r.fit.canonical.contains_key("thumb_01_L"),
            "{model}: an animal has no thumb"
        );
        for side in Side::BOTH {
            let s = side.suffix();
            let named = |n: &str| sk.joints.iter().position(|j| j.name == format!("{n}{s}"));
            assert!(
                named("fore_digit_3_01").is_none() && named("fore_digit_4_01").is_none(),
                "{model}: {side:?} a dewclaw taken for a digit"
            );
            let finger = named("finger_01").unwrap_or_else(|| panic!("{model}: {side:?}"));
            let parent = sk.joints[finger].parent.map(|p| sk.joint(p).name.clone());
            assert_eq!(
                parent,
                Some(format!("hand{s}")),
                "{model}: {side:?} single chain"
            );
        }
    }
}

/// A paw whose toes are only notches of its front rim (the rat's hind paws: four toes, each
/// standing free for a few hundredths of the shank) bends as one: one digit chain from the
/// ankle to the middle of the toes' tips, not four three-joint digits packed into the notches
/// (rat CD-J2J 3.91 -> 3.35 %). The chain follows the foot's centre line down the shank and
/// round the heel along the sole, every joint inside the foot: the straight line from the
/// ankle to the toes cut through the air in front of the heel (hind_digit_3_01 and _02 outside
/// the mesh; rat CD-J2J 3.35 -> 3.20 %).
#[test]
fn a_paw_with_notched_toes_gets_one_digit_chain_to_the_toe_tips() {
    let Some(dir) = crate::common::model("quadruped/quaternius_rat") else {
        return;
    };
    let mesh = load(&dir.join("mesh.obj")).unwrap();
    let r = rig(&mesh, &RigOptions::default()).unwrap();
    let sk = &r.fit.skeleton;
    for side in Side::BOTH {
        let s = side.suffix();
        let ankle = r.fit.canonical[Canonical::Ankle(side).as_str()];
        let children = sk.children(ankle);
        let names: Vec<&str> = children
            .iter()
            .map(|&c| sk.joint(c).name.as_str())
            .collect();
        assert_eq!(names, [format!("hind_digit_3_01{s}")], "{side:?}");
        // The chain runs forward and down from the ankle to the toes on the ground.
        let (a, end) = (
            sk.joint(ankle).position,
            sk.joint(chain_end(&r, ankle)).position,
        );
        assert!(
            end.z > a.z + 0.3 && end.y < 0.2,
            "{side:?}: {a:?} -> {end:?}"
        );
        for k in ["01", "02", "03"] {
            assert!(
                sk.joints
                    .iter()
                    .all(|j| j.name != format!("hind_digit_2_{k}{s}")),
                "{side:?}: a notch taken for a toe"
            );
            let id = sk.find(&format!("hind_digit_3_{k}{s}")).unwrap();
            let at = sk.joint(id).position;
            let w = winding_number(&mesh, at);
            assert!(
                w > 0.5,
                "{side:?}: hind_digit_3_{k} at {at} outside the foot ({w:.2})"
            );
        }
    }
}

//! Real characters re-posed by their artists' own skin weights (arms lowered into A-poses, as
//! `examples/pose_study.rs` does for every humanoid) still rig as whole humanoids with their
//! core joints in place. Skips when ../shared/refdata is missing.

#[path = "../../examples/common/refdata.rs"]
mod refdata;

use super::common::model;
use glam::DVec3;
use skelfit::pipeline::{rig, Rig, RigOptions};
use skelfit::skin::check::{check_deformation, sweep, SweepKind};
use std::collections::BTreeMap;

/// The model re-posed with both upper arms `degrees` below the horizontal, rigged with the
/// defaults; with the artist's joints in that pose by canonical key, and the figure's height.
fn reposed(relative: &str, degrees: f64) -> Option<(Rig, BTreeMap<String, DVec3>, f64)> {
    let dir = model(relative)?;
    let artist = refdata::artist_rig(&dir)?.expect("artist rig");
    let (mesh, reference) = artist.with_arms_at(degrees).expect("posed mesh");
    let (low, high) = mesh.bounding_box().expect("bounds");
    let fitted = rig(&mesh, &RigOptions::default()).expect("rig");
    Some((fitted, reference, high.y - low.y))
}

/// Error of canonical joint `key`, % of height.
fn error(rig: &Rig, reference: &BTreeMap<String, DVec3>, height: f64, key: &str) -> f64 {
    let id = rig.fit.canonical[key];
    100.0 * rig.fit.skeleton.joint(id).position.distance(reference[key]) / height
}

#[test]
fn a_short_legged_figure_with_arms_hanging_into_the_ground_band_keeps_them_as_arms() {
    // The platformer's hands, arms 45 degrees down, reach the lowest tenth of its height: they
    // had paired as a second leg pair (each with its own side's leg) and the figure got the
    // general skeleton. (Its shoulders still land at the elbows: the upper arm is fused with
    // the costume's side down to there, so the arm's section starts at the elbow.)
    let Some((rig, reference, height)) = reposed("humanoid/quaternius_platformer_character", 45.0)
    else {
        return;
    };
    assert_eq!(rig.fit.template, "humanoid", "{:?}", rig.warnings);
    for key in ["pelvis", "wrist_L", "wrist_R", "hip_R", "knee_L"] {
        let e = error(&rig, &reference, height, key);
        assert!(e < 8.0, "{key} {e:.2} % of height off");
    }
}

#[test]
fn a_backpack_is_no_tail_in_an_a_pose() {
    // Arms 45 degrees down: the backpack was labelled a tail and the pelvis sat at its base,
    // 22.7 % of the height off.
    let Some((rig, reference, height)) = reposed("humanoid/quaternius_men_adventurer", 45.0) else {
        return;
    };
    let e = error(&rig, &reference, height, "pelvis");
    assert!(e < 8.0, "pelvis {e:.2} % of height off");
}

#[test]
fn feet_side_by_side_keep_their_ankles_apart_and_the_head_joint_stays_at_the_neck() {
    // Arms 30 degrees down: the sphere trace took in both shins and symmetry put both ankles
    // on the median plane; the head slices ended at the fringe and a face was read there, which
    // put the head joint 9.6 % of the height too high.
    let Some((rig, reference, height)) = reposed("humanoid/quaternius_women_formal", 30.0) else {
        return;
    };
    let e = error(&rig, &reference, height, "head");
    assert!(e < 3.0, "head {e:.2} % of height off");
    let hips = |key: &str| rig.fit.skeleton.joint(rig.fit.canonical[key]).position;
    let apart = hips("ankle_L").distance(hips("ankle_R"));
    let hip_width = hips("hip_L").distance(hips("hip_R"));
    assert!(
        apart > 0.5 * hip_width,
        "ankles {apart:.3} apart, hips {hip_width:.3}"
    );
}

#[test]
fn a_straight_arm_lowered_keeps_its_elbow_in_the_middle_of_the_arm() {
    // Arms 30 and 60 degrees down, elbows straight: at 30 the elbow's window reached the slope
    // of the shoulder's bend and the fit snapped the elbow there (8.3 % of the height off); at
    // 60 a seam of the jointed arm's pieces took it (9.0 %), and the refinement's elbow, at the
    // crease, was refused as too far from that rough one.
    for degrees in [30.0, 60.0] {
        let Some((rig, reference, height)) =
            reposed("humanoid/quaternius_cyberpunk_character", degrees)
        else {
            return;
        };
        for key in ["elbow_L", "elbow_R"] {
            let e = error(&rig, &reference, height, key);
            assert!(e < 3.0, "{degrees} degrees: {key} {e:.2} % of height off");
        }
    }
}

#[test]
fn a_big_heads_ear_is_not_its_head() {
    // Arms 45 degrees down: one ear merged into the big head, the other stood alone and was
    // taken for the head (the head joint 20 % of the height off, in the ear); the head of an
    // upright figure lies on its median plane.
    let Some((rig, reference, height)) = reposed("humanoid/quaternius_platformer_character", 45.0)
    else {
        return;
    };
    let e = error(&rig, &reference, height, "head");
    assert!(e < 8.0, "head {e:.2} % of height off");
}

#[test]
fn arms_hanging_against_the_body_are_found_and_cut_apart_from_it() {
    // Arms 85 degrees down, against the sides: the voxels merged them with the trunk and the
    // rig had no arms (women_formal 11.1 % on the 7 joints left, CesiumMan 3.9 %). On
    // transverse slices of the mesh each arm is its own loop beside the trunk's: they are cut
    // apart in the voxels and the figure labelled again.
    for (relative, bound) in [
        ("humanoid/quaternius_women_formal", 2.0),
        ("humanoid/gltf_cesium_man", 3.0),
    ] {
        let Some(dir) = model(relative) else {
            return;
        };
        let artist = refdata::artist_rig(&dir)
            .expect("source.glb")
            .expect("artist rig");
        let (mesh, reference) = artist.with_arms_at(85.0).expect("posed mesh");
        let (low, high) = mesh.bounding_box().expect("bounds");
        let height = high.y - low.y;
        let rig = rig(&mesh, &RigOptions::default()).expect("rig");
        assert!(
            rig.missing.is_empty(),
            "{relative}: missing {:?}",
            rig.missing
        );
        assert!(
            rig.warnings.iter().any(|w| w.code() == "arms_separated"),
            "{relative}: {:?}",
            rig.warnings
        );
        let keys: Vec<&str> = skelfit::eval::CORE_KEYS
            .iter()
            .copied()
            .filter(|k| reference.contains_key(*k))
            .collect();
        let mean = keys
            .iter()
            .map(|k| error(&rig, &reference, height, k))
            .sum::<f64>()
            / keys.len() as f64;
        assert!(mean < bound, "{relative}: core mean {mean:.2} % of height");
        for key in ["shoulder_L", "elbow_R", "wrist_L"] {
            let e = error(&rig, &reference, height, key);
            assert!(e < 6.0, "{relative}: {key} {e:.2} % of height off");
        }
        // Raising an arm does not tear the flank it lay against, nor drag the skirt its hand
        // lay on: the arm's skin and the body's keep apart in the weights (women_formal had
        // 959 edges past 2x over the sweep, stretched up to 70 times).
        let (poses, missing) = sweep(
            &rig.fit.skeleton,
            &rig.fit.canonical,
            SweepKind::Humanoid,
            glam::DVec3::Y,
            glam::DVec3::Z,
        );
        let check = check_deformation(
            &mesh,
            &rig.fit.skeleton,
            &rig.skin.weights,
            SweepKind::Humanoid,
            &poses,
            missing,
        )
        .expect("sweep");
        assert!(
            check.worst() < 5.0 && check.total_over_2() < mesh.positions.len() / 40,
            "{relative}: {} edges past 2x, worst {:.1}",
            check.total_over_2(),
            check.worst()
        );
    }
}

//! Refinement (seed 004) started from the anatomical fit (dissertation ch.8) of "oracle" paths:
//! the axial and limb paths run through the MakeHuman reference joints with radii from the
//! mesh's distance map, as in the ignored test `oracle_paths_on_makehuman`
//! (tests/it/fit.rs). Prints and writes `reports/refine/oracle_fit.{md,csv}`: errors of the
//! fit before and after refinement over the 15 refined joints.
//!
//! Run: `cargo run --release --example refine_oracle_fit [-- REFDATA_DIR [OUT_DIR]]`.

use glam::DVec3;
use skelfit::distance::edt;
use skelfit::fit::{fit, AxialPath, FitInput, FitOptions, LimbInput, Side};
use skelfit::refine::{refine, RefineOptions, REFINED_KEYS};
use skelfit::template::{LimbKind, Template};
use skelfit::voxel::{voxelize, VoxelOptions};
use std::fmt::Write as _;
use std::path::PathBuf;

/// Points every `step` along the polyline through `corners`.
fn dense(corners: &[DVec3], step: f64) -> Vec<DVec3> {
    let mut out = vec![corners[0]];
    for w in corners.windows(2) {
        let n = ((w[1] - w[0]).length() / step).ceil().max(1.0) as usize;
        out.extend((1..=n).map(|k| w[0].lerp(w[1], k as f64 / n as f64)));
    }
    out
}

fn main() {
    if let Err(message) = run() {
        eprintln!("refine_oracle_fit: error: {message}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = PathBuf::from(args.first().map_or("../shared/refdata", String::as_str));
    let out_dir = PathBuf::from(args.get(1).map_or("reports/refine", String::as_str));
    std::fs::create_dir_all(&out_dir).map_err(|e| e.to_string())?;
    let template = Template::builtin("humanoid").map_err(|e| e.to_string())?;
    let mut md = String::from("# Refinement from the oracle-path fit (seed 004)\n\nRegenerate: `cargo run --release --example refine_oracle_fit`\n\nStart: `fit::fit` (humanoid template) on paths through the reference joints with distance-map radii. Errors in mm over the 15 refined joints.\n\n| model | fit mean | fit max | refined mean | refined max | warnings |\n|---|---|---|---|---|---|\n");
    let mut csv = String::from("model,joint,fit_mm,refined_mm\n");
    for model in [
        "mh_child_10y",
        "mh_female_thin_short",
        "mh_female_young_average",
        "mh_male_heavy_short",
        "mh_male_young_average",
        "mh_neutral_default",
    ] {
        let dir = root.join("humanoid").join(model);
        let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).map_err(|e| e.to_string())?;
        let solid = voxelize(&mesh, &VoxelOptions::default()).map_err(|e| e.to_string())?;
        let dist = edt(&solid);
        let radius = |p: DVec3| {
            dist.grid.voxel_at(p).map_or(0.0, |c| {
                dist.distance(dist.grid.index(c)) * dist.grid.voxel_size
            })
        };
        let rig = skelfit::eval::load_skeleton(&dir.join("rig_game_engine.json"))
            .map_err(|e| e.to_string())?;
        let j = |n: &str| {
            rig.skeleton
                .find(n)
                .map(|id| rig.skeleton.joint(id).position)
                .ok_or_else(|| format!("{model}: no joint {n}"))
        };
        let top = mesh
            .positions
            .iter()
            .copied()
            .fold(DVec3::splat(f64::MIN), |a, b| if b.y > a.y { b } else { a });
        let crotch = (j("thigh_l")? + j("thigh_r")?) * 0.5;
        let axial = dense(
            &[
                DVec3::new(0.0, top.y, j("head")?.z),
                j("head")?,
                j("neck_01")?,
                j("spine_03")?,
                j("spine_02")?,
                j("spine_01")?,
                j("pelvis")?,
                crotch,
            ],
            0.005,
        );
        let radii = axial.iter().map(|p| radius(*p)).collect();
        let mut limbs = Vec::new();
        for (side, s) in [(Side::Left, "l"), (Side::Right, "r")] {
            let attach = (j("upperarm_l")? + j("upperarm_r")?) * 0.5;
            let m3 = j(&format!("middle_03_{s}"))?;
            let tip = m3 + (m3 - j(&format!("middle_02_{s}"))?);
            let path = dense(
                &[
                    attach,
                    j(&format!("upperarm_{s}"))?,
                    j(&format!("lowerarm_{s}"))?,
                    j(&format!("hand_{s}"))?,
                    j(&format!("middle_01_{s}"))?,
                    j(&format!("middle_02_{s}"))?,
                    m3,
                    tip,
                ],
                0.005,
            );
            let r = path.iter().map(|p| radius(*p)).collect();
            limbs.push(LimbInput {
                kind: LimbKind::Arm,
                side,
                pair: 0,
                attach,
                path,
                radii: r,
                digits: Vec::new(),
                root: None,
            });
            let ball = j(&format!("ball_{s}"))?;
            let toe = mesh
                .positions
                .iter()
                .copied()
                .filter(|v| (v.x - ball.x).abs() < 0.05 && v.y < 0.04)
                .fold(ball, |a, b| if b.z > a.z { b } else { a });
            let path = dense(
                &[
                    crotch,
                    j(&format!("thigh_{s}"))?,
                    j(&format!("calf_{s}"))?,
                    j(&format!("foot_{s}"))?,
                    ball,
                    toe,
                ],
                0.005,
            );
            let r = path.iter().map(|p| radius(*p)).collect();
            limbs.push(LimbInput {
                kind: LimbKind::Leg,
                side,
                pair: 0,
                attach: crotch,
                path,
                radii: r,
                digits: Vec::new(),
                root: None,
            });
        }
        let input = FitInput {
            up: DVec3::Y,
            forward: DVec3::Z,
            axial: AxialPath {
                points: axial,
                radii,
                sections: None,
                tail: false,
            },
            limbs,
            jaw: None,
            ears: Vec::new(),
        };
        let f = fit(&input, &template, &FitOptions::default()).map_err(|e| e.to_string())?;
        let r = refine(
            &mesh,
            &f.skeleton,
            &f.canonical,
            DVec3::Y,
            DVec3::Z,
            &RefineOptions::default(),
        )
        .map_err(|e| e.to_string())?;
        let (mut before, mut after) = (Vec::new(), Vec::new());
        for key in REFINED_KEYS {
            let (Some(id), Some(truth)) = (f.canonical.get(key), rig.canonical.get(key)) else {
                continue;
            };
            let truth = rig.skeleton.joint(*truth).position;
            let b = f.skeleton.joint(*id).position.distance(truth) * 1000.0;
            let a = r.skeleton.joint(*id).position.distance(truth) * 1000.0;
            let _ = writeln!(csv, "{model},{key},{b:.2},{a:.2}");
            before.push(b);
            after.push(a);
        }
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
        let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
        let _ = writeln!(
            md,
            "| {model} | {:.1} | {:.1} | {:.1} | {:.1} | {} |",
            mean(&before),
            max(&before),
            mean(&after),
            max(&after),
            r.warnings
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; ")
        );
        eprintln!(
            "{model}: fit {:.1}/{:.1} refined {:.1}/{:.1} mm {:?}",
            mean(&before),
            max(&before),
            mean(&after),
            max(&after),
            r.warnings
        );
    }
    std::fs::write(out_dir.join("oracle_fit.md"), md).map_err(|e| e.to_string())?;
    std::fs::write(out_dir.join("oracle_fit.csv"), csv).map_err(|e| e.to_string())?;
    Ok(())
}

//! A quick probe of the skin options against the reference data, for choosing the method:
//! per model the sweep's edges past 2x (skelfit's rig; skelfit's weights on the artist's
//! skeleton; the artist's) and the random-pose distance to the artist's weights (skelfit's and
//! Blender's bone heat, measured as `examples/deformation.rs` does), plus how sharp each
//! weighting is: the share of vertices with one dominant joint (≥ 0.95) and the width of the
//! blend across each joint relative to the local limb radius. With `PROBE_DIAG=1`, where
//! skelfit's weights differ from the artist's on each model (`diag`).
//!
//! Run: `cargo run --release --example deformation_probe -- [key=value ...]` with keys
//! `falloff`, `blend_ratio`, `depth_exponent`, `voxel_smoothing`, `blend_radius`,
//! `enclosed_air`, `smoothing`, `leaf`, `rig=0` (skip skelfit's own rigs), `only=SUBSTRING`.

#[path = "common/refdata.rs"]
mod refdata;

use refdata::{
    artist_rig, blender_file, blender_weights, check, distance_with_unweighted, exported, models,
    ArtistRig, Model, Weights,
};
use skelfit::mesh::{load, Mesh};
use skelfit::pipeline::{rig, RigOptions};
use skelfit::skeleton::{JointId, Skeleton};
use skelfit::skin::check::SweepKind;
use skelfit::skin::compare::{pose_distance, RandomPoseOptions};
use skelfit::skin::{skin_skeleton, SkeletonSkinOptions, SkinOptions};
use std::collections::BTreeMap;
use std::path::Path;

/// Edges past 2x over the sweep, `None` where the canonical map names no joint to pose.
fn over2(
    mesh: &Mesh,
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    weights: &[Vec<(JointId, f64)>],
    kind: SweepKind,
) -> Option<usize> {
    check(mesh, skeleton, canonical, weights, kind)
        .ok()
        .filter(|c| !c.poses.is_empty())
        .map(|c| c.total_over_2())
}

/// Share of vertices whose largest weight is at least 0.95.
fn rigid_share(weights: &Weights) -> f64 {
    let n = weights.iter().filter(|w| !w.is_empty()).count().max(1);
    weights
        .iter()
        .filter(|w| w.iter().any(|x| x.1 >= 0.95))
        .count() as f64
        / n as f64
}

/// Median over joints (with a deforming parent and a single child) of the half width of the
/// blend between parent and joint along the bone, over the local limb radius.
fn blend_width(mesh: &Mesh, skeleton: &Skeleton, weights: &Weights) -> f64 {
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); skeleton.len()];
    for (k, j) in skeleton.joints.iter().enumerate() {
        if let Some(p) = j.parent {
            children[p.0].push(k);
        }
    }
    let mut ratios = Vec::new();
    for (c, joint) in skeleton.joints.iter().enumerate() {
        let Some(p) = joint.parent else { continue };
        if !joint.deform || !skeleton.joint(p).deform || children[c].len() != 1 {
            continue;
        }
        let a = skeleton.joint(p).position;
        let b = joint.position;
        let e = skeleton.joint(JointId(children[c][0])).position;
        let dir = (e - a).normalize_or_zero();
        if dir == glam::DVec3::ZERO {
            continue;
        }
        let (mut band, mut radius) = (Vec::new(), Vec::new());
        for (v, w) in weights.iter().enumerate() {
            let wp = w.iter().find(|x| x.0 == p).map_or(0.0, |x| x.1);
            let wc = w.iter().find(|x| x.0 .0 == c).map_or(0.0, |x| x.1);
            if wp + wc < 0.8 {
                continue;
            }
            let x = mesh.positions[v] - b;
            let axial = x.dot(dir);
            let radial = (x - dir * axial).length();
            if axial.abs() < (e - b).length().min((b - a).length()) {
                radius.push(radial);
            }
            let f = wc / (wp + wc);
            if f > 0.1 && f < 0.9 {
                band.push(axial.abs());
            }
        }
        if band.len() < 4 || radius.len() < 4 {
            continue;
        }
        band.sort_by(f64::total_cmp);
        radius.sort_by(f64::total_cmp);
        let r = radius[radius.len() / 2];
        if r > 0.0 {
            ratios.push(band[band.len() * 9 / 10] / r);
        }
    }
    if ratios.is_empty() {
        return f64::NAN;
    }
    ratios.sort_by(f64::total_cmp);
    ratios[ratios.len() / 2]
}

fn main() {
    let mut skin = SkinOptions::default();
    let mut do_rig = true;
    let mut only = String::new();
    for arg in std::env::args().skip(1) {
        let (k, v) = arg.split_once('=').expect("key=value");
        match k {
            "falloff" => skin.falloff = v.parse().unwrap(),
            "blend_ratio" => skin.blend_ratio = v.parse().unwrap(),
            "depth_exponent" => skin.depth_exponent = v.parse().unwrap(),
            "voxel_smoothing" => skin.voxel_smoothing_iterations = v.parse().unwrap(),
            "smoothing" => skin.smoothing_iterations = v.parse().unwrap(),
            "leaf" => skin.leaf_extension = v.parse().unwrap(),
            "blend_radius" => skin.blend_radius = v.parse().unwrap(),
            "enclosed_air" => skin.enclosed_air = v.parse().unwrap(),
            "rig" => do_rig = v != "0",
            "only" => only = v.into(),
            _ => panic!("unknown key {k}"),
        }
    }
    let (mut ours, mut blender, mut lower) = (Vec::new(), Vec::new(), 0);
    println!("model | rig>2x | on-artist>2x | artist>2x | mean% | blender% | rigid ours/artist | width ours/artist");
    for model in models(Path::new("../shared/refdata")) {
        if !model.name.contains(&only) {
            continue;
        }
        let rig_over = if do_rig {
            let mesh = load(&model.dir.join("mesh.obj")).unwrap();
            let options = RigOptions {
                skin,
                ..Default::default()
            };
            match rig(&mesh, &options) {
                Ok(r) => {
                    let weights = exported(&r.skin.engine);
                    let over = over2(
                        &mesh,
                        &r.fit.skeleton,
                        &r.fit.canonical,
                        &weights,
                        model.kind,
                    );
                    over.map_or("-".into(), |o| o.to_string())
                }
                Err(e) => format!("err {e}"),
            }
        } else {
            "-".into()
        };
        let Some(Ok(artist)) = artist_rig(&model.dir) else {
            println!("{} | {rig_over}", model.name);
            continue;
        };
        let Some((text, mean, b)) = artist_line(&model, &artist, &skin) else {
            println!("{} | {rig_over} | failed", model.name);
            continue;
        };
        ours.push(mean);
        if let Some(b) = b {
            blender.push(b);
            lower += usize::from(mean < b);
        }
        println!("{} | {rig_over} | {text}", model.name);
    }
    let average = |x: &[f64]| x.iter().sum::<f64>() / x.len().max(1) as f64;
    println!(
        "mean on artist {:.3} % over {} (Blender {:.3} % over {}); lower than Blender on {lower}",
        average(&ours),
        ours.len(),
        average(&blender),
        blender.len(),
    );
}

/// The columns from `on-artist>2x` on, skelfit's and Blender's random-pose distance (% of the
/// figure's size).
fn artist_line(
    model: &Model,
    artist: &ArtistRig,
    skin: &SkinOptions,
) -> Option<(String, f64, Option<f64>)> {
    let (mesh, skeleton) = (&artist.mesh, &artist.skeleton);
    let options = SkeletonSkinOptions {
        skin: *skin,
        ..Default::default()
    };
    let skinned = skin_skeleton(mesh, skeleton, &options).ok()?;
    let ours = exported(&skinned.skin.engine);
    let size = artist.size();
    let d = pose_distance(
        mesh,
        skeleton,
        &ours,
        &artist.weights,
        &RandomPoseOptions::default(),
    )
    .ok()?;
    let mean = 100.0 * d.mean / size;
    let blender = blender_weights(
        &blender_file(Path::new("reports/deformation"), model),
        artist,
    )
    .ok()
    .map(|(weights, _)| 100.0 * distance_with_unweighted(artist, &weights).mean / size);
    if std::env::var("PROBE_DIAG").is_ok() {
        diag(mesh, skeleton, &ours, &artist.weights);
    }
    let on = over2(mesh, skeleton, &artist.canonical, &ours, model.kind);
    let art = over2(
        mesh,
        skeleton,
        &artist.canonical,
        &artist.weights,
        model.kind,
    );
    let fmt = |x: Option<usize>| x.map_or("-".to_string(), |x| x.to_string());
    Some((
        format!(
            "{} | {} | {mean:.2} | {} | {:.2}/{:.2} | {:.2}/{:.2}",
            fmt(on),
            fmt(art),
            blender.map_or("?".into(), |b| format!("{b:.2}")),
            rigid_share(&ours),
            rigid_share(&artist.weights),
            blend_width(mesh, skeleton, &ours),
            blend_width(mesh, skeleton, &artist.weights),
        ),
        mean,
        blender,
    ))
}

/// Where our weights differ from the artist's: total weight moved, by (artist's dominant joint,
/// joint that holds the weight in ours instead), with how the two are related.
fn diag(mesh: &Mesh, skeleton: &Skeleton, ours: &Weights, artist: &Weights) {
    let _ = mesh;
    let mut moved: BTreeMap<(usize, usize), (f64, usize)> = BTreeMap::new();
    let mut hist = [0usize; 11];
    for (o, a) in ours.iter().zip(artist) {
        let Some(&(dom, wd)) = a.iter().max_by(|x, y| x.1.total_cmp(&y.1)) else {
            continue;
        };
        if wd < 0.95 {
            continue;
        }
        let mine = o.iter().find(|x| x.0 == dom).map_or(0.0, |x| x.1);
        hist[(mine * 10.0) as usize] += 1;
        for &(j, w) in o {
            if j != dom {
                let e = moved.entry((dom.0, j.0)).or_default();
                e.0 += w;
                e.1 += 1;
            }
        }
    }
    println!("  ours' weight on the artist's rigid joint (deciles): {hist:?}");
    // Error per vertex over the random poses, summed per the artist's dominant joint.
    let mut random = skelfit::skin::compare::SplitMix64(20);
    let mut err = vec![0.0f64; mesh.positions.len()];
    for _ in 0..20 {
        let pose = skelfit::skin::compare::random_pose(skeleton, 30.0, &mut random);
        let m = skeleton.skinning_matrices(&pose);
        let a = skelfit::skin::check::blend(&mesh.positions, ours, &m);
        let b = skelfit::skin::check::blend(&mesh.positions, artist, &m);
        for v in 0..err.len() {
            if !ours[v].is_empty() && !artist[v].is_empty() {
                err[v] += a[v].distance(b[v]) / 20.0;
            }
        }
    }
    let total: f64 = err.iter().sum();
    let mut per: BTreeMap<usize, f64> = BTreeMap::new();
    for (v, a) in artist.iter().enumerate() {
        if let Some(&(dom, _)) = a.iter().max_by(|x, y| x.1.total_cmp(&y.1)) {
            *per.entry(dom.0).or_default() += err[v];
        }
    }
    let mut per: Vec<_> = per.into_iter().collect();
    per.sort_by(|a, b| b.1.total_cmp(&a.1));
    let listed: Vec<String> = per
        .iter()
        .take(10)
        .map(|(j, e)| {
            format!(
                "{} {:.0}%",
                skeleton.joint(JointId(*j)).name,
                100.0 * e / total
            )
        })
        .collect();
    println!(
        "  error share by the artist's dominant joint: {}",
        listed.join(", ")
    );
    let mut list: Vec<_> = moved.into_iter().collect();
    list.sort_by(|a, b| b.1 .0.total_cmp(&a.1 .0));
    for ((d, j), (w, n)) in list.into_iter().take(12) {
        let rel = if skeleton.joint(JointId(j)).parent == Some(JointId(d)) {
            "child"
        } else if skeleton.joint(JointId(d)).parent == Some(JointId(j)) {
            "parent"
        } else if skeleton.joint(JointId(d)).parent.is_some()
            && skeleton.joint(JointId(d)).parent == skeleton.joint(JointId(j)).parent
        {
            "sibling"
        } else {
            "other"
        };
        println!(
            "  {} -> {} ({rel}): {w:.1} over {n}",
            skeleton.joint(JointId(d)).name,
            skeleton.joint(JointId(j)).name
        );
    }
}

//! A quick probe of the skin options against the reference data, for choosing the method:
//! per model the sweep's edges past 2x (skelfit's rig; skelfit's weights on the artist's
//! skeleton; the artist's) and the random-pose distance to the artist's weights, plus how
//! sharp each weighting is: the share of vertices with one dominant joint (≥ 0.95) and the
//! width of the blend across each joint relative to the local limb radius.
//!
//! Run: `cargo run --release --example deformation_probe -- [key=value ...]` with keys
//! `falloff`, `blend_ratio`, `depth_exponent`, `voxel_smoothing`, `smoothing`, `rig=0` (skip
//! skelfit's own rigs), `only=SUBSTRING`.

use skelfit::mesh::{load, load_gltf_scene, Mesh};
use skelfit::pipeline::{rig, RigOptions};
use skelfit::skeleton::{JointId, Skeleton};
use skelfit::skin::check::{check_deformation, sweep, SweepKind};
use skelfit::skin::compare::{pose_distance, RandomPoseOptions};
use skelfit::skin::{skin_skeleton, EngineWeights, SkeletonSkinOptions, SkinOptions};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

type Weights = Vec<Vec<(JointId, f64)>>;

fn exported(engine: &EngineWeights) -> Weights {
    engine
        .joints
        .iter()
        .zip(&engine.weights)
        .map(|(j, w)| {
            j.iter()
                .zip(w)
                .filter(|(_, &w)| w > 0.0)
                .map(|(&j, &w)| (JointId(usize::from(j)), f64::from(w)))
                .collect()
        })
        .collect()
}

fn over2(
    mesh: &Mesh,
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    weights: &[Vec<(JointId, f64)>],
    kind: SweepKind,
) -> usize {
    let (poses, missing) = sweep(skeleton, canonical, kind, glam::DVec3::Y, glam::DVec3::Z);
    if poses.is_empty() {
        return usize::MAX;
    }
    check_deformation(mesh, skeleton, weights, kind, &poses, missing)
        .map(|c| c.total_over_2())
        .unwrap_or(usize::MAX)
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
            "rig" => do_rig = v != "0",
            "only" => only = v.into(),
            _ => panic!("unknown key {k}"),
        }
    }
    let root = PathBuf::from("../shared/refdata");
    let (mut sum_ours, mut n_artist, mut lower) = (0.0, 0, 0);
    println!("model | rig>2x | on-artist>2x | artist>2x | mean% | blender% | rigid ours/artist | width ours/artist");
    for (folder, kind) in [
        ("humanoid", SweepKind::Humanoid),
        ("quadruped", SweepKind::Animal),
    ] {
        let mut dirs: Vec<PathBuf> = std::fs::read_dir(root.join(folder))
            .unwrap()
            .filter_map(Result::ok)
            .map(|e| e.path())
            .collect();
        dirs.sort();
        for dir in dirs {
            let name = dir.file_name().unwrap().to_string_lossy().to_string();
            if !name.contains(&only) {
                continue;
            }
            let rig_over = if do_rig {
                let mesh = load(&dir.join("mesh.obj")).unwrap();
                let options = RigOptions {
                    skin,
                    ..Default::default()
                };
                match rig(&mesh, &options) {
                    Ok(r) => over2(
                        &mesh,
                        &r.fit.skeleton,
                        &r.fit.canonical,
                        &exported(&r.skin.engine),
                        kind,
                    )
                    .to_string(),
                    Err(e) => format!("err {e}"),
                }
            } else {
                "-".into()
            };
            let source = dir.join("source.glb");
            if !source.is_file() {
                println!("{name} | {rig_over}");
                continue;
            }
            let line = artist_line(&dir, &source, folder, &name, kind, &skin);
            if let Some((text, ours, blender)) = line {
                sum_ours += ours;
                n_artist += 1;
                lower += usize::from(blender.is_some_and(|b| ours < b));
                println!("{name} | {rig_over} | {text}");
            }
        }
    }
    println!(
        "mean on artist {:.3} % over {n_artist}; lower than Blender on {lower}",
        sum_ours / n_artist.max(1) as f64
    );
}

fn artist_line(
    dir: &Path,
    source: &Path,
    folder: &str,
    name: &str,
    kind: SweepKind,
    skin: &SkinOptions,
) -> Option<(String, f64, Option<f64>)> {
    let scene = load_gltf_scene(source).ok()?;
    let skeleton = scene.skeleton?;
    let artist = scene.weights?;
    let mesh = scene.mesh;
    let reference = std::fs::read_dir(dir)
        .ok()?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .find(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("rig_") && n.ends_with(".json"))
        })?;
    let reference = skelfit::eval::load_skeleton(&reference).ok()?;
    let canonical: BTreeMap<String, JointId> = reference
        .canonical
        .iter()
        .filter_map(|(key, &id)| {
            Some((
                key.clone(),
                skeleton.find(&reference.skeleton.joint(id).name)?,
            ))
        })
        .collect();
    let options = SkeletonSkinOptions {
        skin: *skin,
        ..Default::default()
    };
    let skinned = skin_skeleton(&mesh, &skeleton, &options).ok()?;
    let ours = exported(&skinned.skin.engine);
    let (low, high) = mesh.bounding_box()?;
    let size = (high - low).max_element();
    let d = pose_distance(
        &mesh,
        &skeleton,
        &ours,
        &artist,
        &RandomPoseOptions::default(),
    )
    .ok()?;
    let mean = 100.0 * d.mean / size;
    let blender: Option<f64> =
        std::fs::read_to_string(Path::new("reports/deformation/deformation.json"))
            .ok()
            .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
            .and_then(|j| {
                let model = format!("{folder}/{name}");
                j.as_array()
                    .or_else(|| j.get("models").and_then(|m| m.as_array()))?
                    .iter()
                    .find(|m| m.get("model").and_then(|x| x.as_str()) == Some(model.as_str()))
                    .and_then(|m| {
                        m.pointer("/blender_bone_heat_on_artist_skeleton/random_pose_distance/mean")
                    })
                    .and_then(|x| x.as_f64())
                    .map(|x| 100.0 * x / size)
            });
    if std::env::var("PROBE_DIAG").is_ok() {
        diag(&mesh, &skeleton, &ours, &artist);
    }
    let on = over2(&mesh, &skeleton, &canonical, &ours, kind);
    let art = over2(&mesh, &skeleton, &canonical, &artist, kind);
    let fmt = |x: usize| {
        if x == usize::MAX {
            "-".to_string()
        } else {
            x.to_string()
        }
    };
    Some((
        format!(
            "{} | {} | {mean:.2} | {} | {:.2}/{:.2} | {:.2}/{:.2}",
            fmt(on),
            fmt(art),
            blender.map_or("?".into(), |b| format!("{b:.2}")),
            rigid_share(&ours),
            rigid_share(&artist),
            blend_width(&mesh, &skeleton, &ours),
            blend_width(&mesh, &skeleton, &artist),
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

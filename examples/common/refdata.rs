//! The reference data as the deformation examples read it: the models of a refdata folder,
//! the artist's rig of a model's `source.glb`, Blender's bone heat weights on it (written by
//! `tools/blender_autoweights.py`), and the sweep and distance measures on them. Included by
//! `examples/deformation.rs` and `examples/deformation_probe.rs` (`#[path]` module), so that
//! both measure the same way.

#![allow(dead_code)]

use glam::DVec3;
use skelfit::eval::{arms_below_horizontal, load_skeleton};
use skelfit::mesh::{load_gltf_scene, Mesh};
use skelfit::skeleton::{JointId, Skeleton};
use skelfit::skin::check::{blend, check_deformation, sweep, DeformationCheck, SweepKind};
use skelfit::skin::compare::{random_pose, PoseDistance, RandomPoseOptions, SplitMix64};
use skelfit::skin::EngineWeights;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Per-vertex `(joint, weight)` lists.
pub type Weights = Vec<Vec<(JointId, f64)>>;

/// One model of the reference data.
pub struct Model {
    /// `humanoid` or `quadruped`.
    pub folder: &'static str,
    /// The model's folder name.
    pub name: String,
    /// Its folder.
    pub dir: PathBuf,
    /// The sweep it is posed through.
    pub kind: SweepKind,
}

impl Model {
    /// `folder/name`, as the reports name models.
    pub fn id(&self) -> String {
        format!("{}/{}", self.folder, self.name)
    }
}

/// The humanoids, then the quadrupeds of `root`, each in name order.
pub fn models(root: &Path) -> Vec<Model> {
    let mut out = Vec::new();
    for (folder, kind) in [
        ("humanoid", SweepKind::Humanoid),
        ("quadruped", SweepKind::Animal),
    ] {
        let Ok(entries) = std::fs::read_dir(root.join(folder)) else {
            continue;
        };
        let mut dirs: Vec<PathBuf> = entries.filter_map(Result::ok).map(|e| e.path()).collect();
        dirs.sort();
        out.extend(dirs.into_iter().map(|dir| {
            Model {
                folder,
                name: dir
                    .file_name()
                    .unwrap_or_default()
                    .to_string_lossy()
                    .into_owned(),
                dir,
                kind,
            }
        }));
    }
    out
}

/// Engine weights (at most four per vertex, as exported) as `(joint, weight)` lists.
pub fn exported(engine: &EngineWeights) -> Weights {
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

/// The standard sweep of `kind` on `skeleton` (its joints named by `canonical`) with
/// `weights`.
pub fn check(
    mesh: &Mesh,
    skeleton: &Skeleton,
    canonical: &BTreeMap<String, JointId>,
    weights: &[Vec<(JointId, f64)>],
    kind: SweepKind,
) -> Result<DeformationCheck, String> {
    let (poses, missing) = sweep(skeleton, canonical, kind, glam::DVec3::Y, glam::DVec3::Z);
    check_deformation(mesh, skeleton, weights, kind, &poses, missing).map_err(|e| e.to_string())
}

/// The artist's rig from `source.glb`: mesh, skeleton, weights and the canonical map of the
/// model's `rig_*.json` (names looked up in the skin).
pub struct ArtistRig {
    pub mesh: Mesh,
    pub skeleton: Skeleton,
    pub weights: Weights,
    pub canonical: BTreeMap<String, JointId>,
}

impl ArtistRig {
    /// The longest side of the mesh's bounding box, which distances are given in % of.
    pub fn size(&self) -> f64 {
        self.mesh
            .bounding_box()
            .map_or(0.0, |(low, high)| (high - low).max_element())
    }

    /// The figure with both upper arms `degrees` below the horizontal (+Y up, +Z forward;
    /// [`arms_below_horizontal`]), posed by linear blend skinning with the artist's weights:
    /// the posed mesh and the artist's canonical joints in that pose.
    pub fn with_arms_at(&self, degrees: f64) -> Result<(Mesh, BTreeMap<String, DVec3>), String> {
        let matrices =
            arms_below_horizontal(&self.skeleton, &self.canonical, degrees, DVec3::Y, DVec3::Z);
        let positions = blend(&self.mesh.positions, &self.weights, &matrices);
        let mesh = Mesh::new(positions, self.mesh.triangles.clone()).map_err(|e| e.to_string())?;
        let joints = self
            .canonical
            .iter()
            .map(|(key, &id)| {
                let p = matrices[id.0].transform_point3(self.skeleton.joint(id).position);
                (key.clone(), p)
            })
            .collect();
        Ok((mesh, joints))
    }
}

/// The artist's rig of the model in `dir`; `None` without `source.glb`.
pub fn artist_rig(dir: &Path) -> Option<Result<ArtistRig, String>> {
    let source = dir.join("source.glb");
    if !source.is_file() {
        return None;
    }
    Some((|| {
        let scene = load_gltf_scene(&source).map_err(|e| e.to_string())?;
        let skeleton = scene.skeleton.ok_or("no skin")?;
        let weights = scene.weights.ok_or("no weights")?;
        let reference = std::fs::read_dir(dir)
            .map_err(|e| e.to_string())?
            .filter_map(Result::ok)
            .map(|e| e.path())
            .find(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("rig_") && n.ends_with(".json"))
            })
            .ok_or("no rig_*.json")?;
        let reference = load_skeleton(&reference).map_err(|e| e.to_string())?;
        let canonical: BTreeMap<String, JointId> = reference
            .canonical
            .iter()
            .filter_map(|(key, &id)| {
                let name = &reference.skeleton.joint(id).name;
                Some((key.clone(), skeleton.find(name)?))
            })
            .collect();
        Ok(ArtistRig {
            mesh: scene.mesh,
            skeleton,
            weights,
            canonical,
        })
    })())
}

/// The file `tools/blender_autoweights.py` writes for `model` under `out` (the report folder).
pub fn blender_file(out: &Path, model: &Model) -> PathBuf {
    out.join("blender")
        .join(model.folder)
        .join(format!("{}.json", model.name))
}

/// Blender's bone heat weights for `rig` from `file` (written by
/// `tools/blender_autoweights.py`): each vertex of the artist's mesh takes the weights of the
/// vertex of Blender's export at the same rest position (within about 1e-4 of the figure's
/// size, after mapping Blender's bone heads onto the joints), bone names looked up in the
/// artist's skeleton. Also returns the vertices left without weight.
pub fn blender_weights(file: &Path, rig: &ArtistRig) -> Result<(Weights, usize), String> {
    let text = std::fs::read_to_string(file).map_err(|e| format!("{}: {e}", file.display()))?;
    let json: serde_json::Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    let bones: Vec<Option<JointId>> = json["bones"]
        .as_array()
        .ok_or("no bones")?
        .iter()
        .map(|b| b.as_str().and_then(|name| rig.skeleton.find(name)))
        .collect();
    // Blender's rest frame → the frame of the mesh skelfit loads: the affine map that takes
    // the bones' rest heads onto the joints (least squares).
    let point = |v: &serde_json::Value| -> Option<glam::DVec3> {
        let c = v.as_array()?;
        Some(glam::DVec3::new(
            c.first()?.as_f64()?,
            c.get(1)?.as_f64()?,
            c.get(2)?.as_f64()?,
        ))
    };
    let (mut ata, mut atb) = (glam::DMat4::ZERO, [glam::DVec4::ZERO; 3]);
    for (name, head) in json["heads"].as_object().ok_or("no heads")? {
        let (Some(joint), Some(h)) = (rig.skeleton.find(name), point(head)) else {
            continue;
        };
        let a = h.extend(1.0);
        let target = rig.skeleton.joint(joint).position;
        for r in 0..4 {
            *ata.col_mut(r) += a * a[r];
        }
        for (c, t) in atb.iter_mut().zip(target.to_array()) {
            *c += a * t;
        }
    }
    let inverse = ata.inverse();
    if !inverse.is_finite() {
        return Err("too few bones to match Blender's frame".into());
    }
    let rows = atb.map(|b| inverse * b);
    let to_mesh = |p: glam::DVec3| {
        let a = p.extend(1.0);
        glam::DVec3::new(rows[0].dot(a), rows[1].dot(a), rows[2].dot(a))
    };
    let positions = json["positions"].as_array().ok_or("no positions")?;
    let weights = json["weights"].as_array().ok_or("no weights")?;
    let (low, high) = rig.mesh.bounding_box().ok_or("empty mesh")?;
    let quantum = 1e-4 * (high - low).max_element();
    let key = |p: glam::DVec3| (p / quantum).round().as_i64vec3();
    let mut at: std::collections::HashMap<glam::I64Vec3, usize> = Default::default();
    for (k, p) in positions.iter().enumerate() {
        let c: Vec<f64> = p
            .as_array()
            .ok_or("bad position")?
            .iter()
            .filter_map(serde_json::Value::as_f64)
            .collect();
        if c.len() == 3 {
            at.entry(key(to_mesh(glam::DVec3::new(c[0], c[1], c[2]))))
                .or_insert(k);
        }
    }
    let mut out = Vec::with_capacity(rig.mesh.positions.len());
    let mut unweighted = 0;
    for &p in &rig.mesh.positions {
        let base = key(p);
        let found = (-1..=1)
            .flat_map(|x| {
                (-1..=1).flat_map(move |y| (-1..=1).map(move |z| glam::I64Vec3::new(x, y, z)))
            })
            .find_map(|d| at.get(&(base + d)).copied());
        let mut w: Vec<(JointId, f64)> = found
            .and_then(|k| weights[k].as_array())
            .map(|list| {
                list.iter()
                    .filter_map(|e| {
                        let joint = bones.get(e[0].as_u64()? as usize).copied().flatten()?;
                        let x = e[1].as_f64()?;
                        (x > 0.0).then_some((joint, x))
                    })
                    .collect()
            })
            .unwrap_or_default();
        let sum: f64 = w.iter().map(|e| e.1).sum();
        if sum > 0.0 {
            w.iter_mut().for_each(|e| e.1 /= sum);
        } else {
            unweighted += 1;
        }
        out.push(w);
    }
    Ok((out, unweighted))
}

/// The mean distance between the mesh skinned with `weights` and with the artist's, over the
/// default random poses ([`RandomPoseOptions`]), over every vertex the artist skinned; a
/// vertex without weights in `weights` stays at rest (as under Blender's armature modifier)
/// instead of being left out.
pub fn distance_with_unweighted(rig: &ArtistRig, weights: &[Vec<(JointId, f64)>]) -> PoseDistance {
    let options = RandomPoseOptions::default();
    let mut random = SplitMix64(options.seed);
    let (mut sum, mut max, mut count) = (0.0, 0.0f64, 0usize);
    for _ in 0..options.poses {
        let pose = random_pose(&rig.skeleton, options.max_degrees, &mut random);
        let matrices = rig.skeleton.skinning_matrices(&pose);
        let posed = blend(&rig.mesh.positions, weights, &matrices);
        let artist = blend(&rig.mesh.positions, &rig.weights, &matrices);
        for ((p, q), w) in posed.iter().zip(&artist).zip(&rig.weights) {
            if !w.is_empty() {
                let d = p.distance(*q);
                sum += d;
                max = max.max(d);
                count += 1;
            }
        }
    }
    PoseDistance {
        mean: if count > 0 { sum / count as f64 } else { 0.0 },
        max,
        poses: options.poses,
        vertices: rig.weights.iter().filter(|w| !w.is_empty()).count(),
    }
}

/// How far `weights` lie from the artist's: per vertex the artist skinned, half the sum over
/// joints of the absolute weight differences (0: the same weights, 1: no joint in common),
/// averaged over those vertices.
pub fn weight_difference(rig: &ArtistRig, weights: &[Vec<(JointId, f64)>]) -> f64 {
    let (mut sum, mut count) = (0.0, 0usize);
    for (artist, other) in rig.weights.iter().zip(weights) {
        if artist.is_empty() {
            continue;
        }
        let mut joints: Vec<JointId> = artist.iter().chain(other).map(|e| e.0).collect();
        joints.sort_unstable();
        joints.dedup();
        let of =
            |w: &[(JointId, f64)], j: JointId| w.iter().find(|e| e.0 == j).map_or(0.0, |e| e.1);
        sum += joints
            .iter()
            .map(|&j| (of(artist, j) - of(other, j)).abs())
            .sum::<f64>()
            / 2.0;
        count += 1;
    }
    if count > 0 {
        sum / count as f64
    } else {
        0.0
    }
}

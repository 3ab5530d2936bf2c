//! Bone meshes (dissertation 9.1) on realistic fits of every refdata humanoid and quadruped
//! (FitInput from paths through the reference joints, as the fit oracle tests do), on a
//! snake-like figure and on skeletons with missing parts.

use glam::{DQuat, DVec3};
use skelfit::bones::{bones, BoneKind, BoneOptions, Bones};
use skelfit::distance::{edt, DistanceMap};
use skelfit::fit::{fit, AxialPath, Fit, FitInput, FitOptions, LimbInput, Side};
use skelfit::mesh::Mesh;
use skelfit::skeleton::{JointId, Skeleton};
use skelfit::template::{LimbKind, Template};
use skelfit::voxel::{voxelize, VoxelOptions};
use std::collections::BTreeMap;
use std::path::Path;

/// Points every `step` along the polyline through `corners`.
fn dense(corners: &[DVec3], step: f64) -> Vec<DVec3> {
    let mut out = vec![corners[0]];
    for w in corners.windows(2) {
        let n = ((w[1] - w[0]).length() / step).ceil().max(1.0) as usize;
        out.extend((1..=n).map(|k| w[0].lerp(w[1], k as f64 / n as f64)));
    }
    out
}

fn radius(map: &DistanceMap, p: DVec3) -> f64 {
    map.grid.voxel_at(p).map_or(0.0, |c| {
        map.distance(map.grid.index(c)) * map.grid.voxel_size
    })
}

/// From `from` along `dir` to 85 % of the way to the figure's surface (a path tip).
fn tip(map: &DistanceMap, from: DVec3, dir: DVec3) -> DVec3 {
    let dir = dir.normalize();
    let h = map.grid.voxel_size * 0.5;
    let mut t = 0.0;
    while radius(map, from + dir * (t + h)) > 0.0 && t < 1e3 * h {
        t += h;
    }
    from + dir * (0.85 * t)
}

/// Reference joints of a refdata model as (axial head → tail, fore limbs L/R, hind limbs L/R),
/// each a list of joint positions.
struct Oracle {
    axial: Vec<DVec3>,
    fore: Vec<(Side, Vec<DVec3>)>,
    hind: Vec<(Side, Vec<DVec3>)>,
    upright: bool,
}

fn oracle(dir: &Path, upright: bool) -> Oracle {
    let rig_file = ["rig_game_engine.json", "rig_gltf.json"]
        .iter()
        .map(|f| dir.join(f))
        .find(|p| p.is_file())
        .unwrap();
    let rig = skelfit::eval::load_skeleton(&rig_file).unwrap();
    let by_name = |n: &str| {
        rig.skeleton
            .find(n)
            .map(|id| rig.skeleton.joint(id).position)
    };
    let key = |k: &str| {
        rig.canonical
            .get(k)
            .map(|id| rig.skeleton.joint(*id).position)
    };
    let names = |list: &[&str], s: &str| -> Vec<DVec3> {
        list.iter()
            .filter_map(|n| by_name(&n.replace("{s}", s)))
            .collect()
    };
    if key("head").is_some() {
        let mut axial: Vec<DVec3> = ["head", "neck", "chest", "spine", "pelvis"]
            .iter()
            .filter_map(|k| key(k))
            .collect();
        let mut tails: Vec<(&String, DVec3)> = rig
            .canonical
            .iter()
            .filter(|(k, _)| k.starts_with("tail_"))
            .map(|(k, id)| (k, rig.skeleton.joint(*id).position))
            .collect();
        let rank = |k: &str| {
            ["tail_base", "tail_mid", "tail_end"]
                .iter()
                .position(|x| *x == k)
        };
        tails.sort_by_key(|(k, _)| rank(k));
        axial.extend(tails.iter().map(|t| t.1));
        let side = |s: &str, keys: &[&str]| -> Vec<DVec3> {
            keys.iter()
                .filter_map(|k| key(&format!("{k}_{s}")))
                .collect()
        };
        let fore = vec![
            (Side::Left, side("L", &["shoulder", "elbow", "wrist"])),
            (Side::Right, side("R", &["shoulder", "elbow", "wrist"])),
        ];
        let hind = vec![
            (Side::Left, side("L", &["hip", "knee", "ankle", "toe"])),
            (Side::Right, side("R", &["hip", "knee", "ankle", "toe"])),
        ];
        return Oracle {
            axial,
            fore,
            hind,
            upright,
        };
    }
    if by_name("Torso3").is_some() {
        // Quaternius animals.
        let axial = names(
            &[
                "Head", "Neck3", "Neck2", "Neck1", "Torso3", "Torso2", "Torso", "Back", "Tail2",
                "Tail3", "Tail4", "Tail5", "Tail6", "Tail7", "Tail8",
            ],
            "",
        );
        let fore = [
            "FrontUpperLeg.{s}",
            "FrontLowerLeg.{s}",
            "IKFrontLeg.{s}",
            "FF.{s}",
        ];
        let hind = [
            "BackLeg.{s}",
            "BackUpperLeg.{s}",
            "BackLowerLeg.{s}",
            "IKBackLeg.{s}",
            "FFB.{s}",
        ];
        return Oracle {
            axial,
            fore: vec![
                (Side::Left, names(&fore, "L")),
                (Side::Right, names(&fore, "R")),
            ],
            hind: vec![
                (Side::Left, names(&hind, "L")),
                (Side::Right, names(&hind, "R")),
            ],
            upright,
        };
    }
    // Quaternius dinosaurs (triceratops).
    let axial = names(
        &[
            "Head",
            "Neck",
            "Shoulders",
            "Torso",
            "Hips",
            "Tail1",
            "Tail2",
            "Tail3",
            "Tail4",
            "Tail5",
        ],
        "",
    );
    let fore = ["FrontUpLeg.{s}", "FrontLowLeg.{s}", "FrontFoot.{s}"];
    let hind = ["BackUpLeg.{s}", "BackLowLeg.{s}", "BackFoot.{s}"];
    Oracle {
        axial,
        fore: vec![
            (Side::Left, names(&fore, "L")),
            (Side::Right, names(&fore, "R")),
        ],
        hind: vec![
            (Side::Left, names(&hind, "L")),
            (Side::Right, names(&hind, "R")),
        ],
        upright,
    }
}

fn limb_input(
    map: &DistanceMap,
    kind: LimbKind,
    side: Side,
    attach: DVec3,
    joints: &[DVec3],
    down: bool,
) -> LimbInput {
    let mut corners = vec![attach];
    corners.extend_from_slice(joints);
    let n = joints.len();
    let last = joints[n - 1];
    let dir = if down {
        -DVec3::Y
    } else {
        last - joints[n - 2]
    };
    corners.push(tip(map, last, dir));
    let path = dense(&corners, map.grid.voxel_size);
    let radii = path.iter().map(|p| radius(map, *p)).collect();
    LimbInput {
        kind,
        side,
        pair: 0,
        attach,
        path,
        radii,
        digits: Vec::new(),
        root: None,
    }
}

/// A realistic fit of a refdata model and its distance map.
fn refdata_fit(dir: &Path, upright: bool) -> (Mesh, DistanceMap, Fit) {
    let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).unwrap();
    let solid = voxelize(&mesh, &VoxelOptions::default()).unwrap();
    let map = edt(&solid);
    let o = oracle(dir, upright);
    let mid = |l: &[(Side, Vec<DVec3>)]| (l[0].1[0] + l[1].1[0]) * 0.5;
    let (fore_mid, hind_mid) = (mid(&o.fore), mid(&o.hind));
    let mut corners = vec![tip(map_ref(&map), o.axial[0], o.axial[0] - o.axial[1])];
    corners.extend(o.axial.iter().copied());
    if upright {
        corners.push(hind_mid);
    } else {
        let n = corners.len();
        let last = corners[n - 1];
        corners.push(tip(&map, last, last - corners[n - 2]));
    }
    let points = dense(&corners, map.grid.voxel_size);
    let radii = points.iter().map(|p| radius(&map, *p)).collect();
    let mut limbs = Vec::new();
    let (fore_kind, hind_kind) = if upright {
        (LimbKind::Arm, LimbKind::Leg)
    } else {
        (LimbKind::ForeLeg, LimbKind::HindLeg)
    };
    for (side, joints) in &o.fore {
        limbs.push(limb_input(
            &map, fore_kind, *side, fore_mid, joints, !upright,
        ));
    }
    for (side, joints) in &o.hind {
        limbs.push(limb_input(&map, hind_kind, *side, hind_mid, joints, false));
    }
    let input = FitInput {
        up: DVec3::Y,
        forward: DVec3::Z,
        axial: AxialPath {
            points,
            radii,
            sections: None,
            tail: false,
        },
        limbs,
        jaw: None,
        ears: Vec::new(),
    };
    let template = Template::builtin(if o.upright { "humanoid" } else { "quadruped" }).unwrap();
    let f = fit(&input, &template, &FitOptions::default()).unwrap();
    (mesh, map, f)
}

fn map_ref(m: &DistanceMap) -> &DistanceMap {
    m
}

/// Winding number of `p` with respect to a mesh of closed outward parts, by signed crossings
/// of the ray towards +x (a slightly tilted ray avoids edges).
struct Winding {
    triangles: Vec<[DVec3; 3]>,
}

impl Winding {
    fn new(mesh: &Mesh) -> Self {
        Self {
            triangles: (0..mesh.triangles.len()).map(|t| mesh.corners(t)).collect(),
        }
    }

    fn winding(&self, p: DVec3) -> i32 {
        let d = DVec3::new(1.0, 1.3e-4, 2.9e-4).normalize();
        let mut w = 0;
        for [a, b, c] in &self.triangles {
            // Möller–Trumbore.
            let (e1, e2) = (*b - *a, *c - *a);
            let h = d.cross(e2);
            let det = e1.dot(h);
            if det.abs() < 1e-300 {
                continue;
            }
            let s = p - *a;
            let u = s.dot(h) / det;
            if !(0.0..=1.0).contains(&u) {
                continue;
            }
            let q = s.cross(e1);
            let v = d.dot(q) / det;
            if v < 0.0 || u + v > 1.0 {
                continue;
            }
            if e2.dot(q) / det > 0.0 {
                w += if e1.cross(e2).dot(d) > 0.0 { 1 } else { -1 };
            }
        }
        w
    }
}

/// A 2-D bucket grid (y, z) over the skin's triangles for fast ray tests along +x.
struct Skin {
    cells: Vec<Vec<[DVec3; 3]>>,
    lo: DVec3,
    size: f64,
    n: usize,
}

impl Skin {
    fn new(mesh: &Mesh) -> Self {
        let (lo, hi) = mesh.bounding_box().unwrap();
        let n = 64;
        let size = (hi.y - lo.y).max(hi.z - lo.z) / n as f64 * 1.0001;
        let mut cells = vec![Vec::new(); n * n];
        for t in 0..mesh.triangles.len() {
            let c = mesh.corners(t);
            let (mut a, mut b) = (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN));
            for p in c {
                a = a.min(p);
                b = b.max(p);
            }
            let cell = |v: f64, o: f64| (((v - o) / size).floor().max(0.0) as usize).min(n - 1);
            for i in cell(a.y, lo.y)..=cell(b.y, lo.y) {
                for j in cell(a.z, lo.z)..=cell(b.z, lo.z) {
                    cells[i * n + j].push(c);
                }
            }
        }
        Self { cells, lo, size, n }
    }

    fn inside(&self, p: DVec3) -> bool {
        let i = ((p.y - self.lo.y) / self.size).floor();
        let j = ((p.z - self.lo.z) / self.size).floor();
        if i < 0.0 || j < 0.0 || i >= self.n as f64 || j >= self.n as f64 {
            return false;
        }
        let w = Winding {
            triangles: self.cells[i as usize * self.n + j as usize].clone(),
        };
        // Ray along +x exactly (cells are in y, z).
        let mut count = 0;
        for [a, b, c] in &w.triangles {
            // Point in triangle in the (y, z) projection, then the crossing's x.
            let area = |p: DVec3, q: DVec3, r: DVec3| {
                (q.y - p.y) * (r.z - p.z) - (q.z - p.z) * (r.y - p.y)
            };
            let (w0, w1, w2) = (area(*b, *c, p), area(*c, *a, p), area(*a, *b, p));
            let total = w0 + w1 + w2;
            if total == 0.0 {
                continue;
            }
            let inside_tri =
                (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0) || (w0 <= 0.0 && w1 <= 0.0 && w2 <= 0.0);
            if !inside_tri {
                continue;
            }
            let x = (w0 * a.x + w1 * b.x + w2 * c.x) / total;
            if x > p.x {
                // Signed: leaving through an outward face counts +1 (a winding number, so
                // overlapping closed parts stay inside).
                count += if (*b - *a).cross(*c - *a).x > 0.0 {
                    1
                } else {
                    -1
                };
            }
        }
        count != 0
    }
}

/// Checks of one figure's bones; returns (inside fraction, intersecting vertex fraction).
fn check(name: &str, skin: &Mesh, skeleton: &Skeleton, b: &Bones) -> (f64, f64) {
    // Closed, consistently oriented, outward.
    for bone in &b.bones {
        let s = bone.mesh.stats();
        assert!(
            s.closed && s.boundary_edges == 0 && s.non_manifold_edges == 0,
            "{name}: {} not closed: {s:?}",
            bone.name
        );
        assert!(
            s.signed_volume.unwrap() > 0.0,
            "{name}: {} inward",
            bone.name
        );
        assert!(bone.joint.0 < skeleton.len());
    }
    // Inside the skin (ray parity against the input mesh, independent of the voxels).
    let test = Skin::new(skin);
    let (mut inside, mut total) = (0usize, 0usize);
    for bone in &b.bones {
        for p in &bone.mesh.positions {
            total += 1;
            inside += usize::from(test.inside(*p));
        }
    }
    let inside_fraction = inside as f64 / total as f64;
    if inside_fraction < 0.99 {
        for bone in &b.bones {
            let out = bone
                .mesh
                .positions
                .iter()
                .filter(|p| !test.inside(**p))
                .count();
            if out > 0 {
                println!(
                    "    {name}: {} has {out} of {} vertices outside",
                    bone.name,
                    bone.mesh.positions.len()
                );
            }
        }
    }
    // No bone vertex inside another bone outside articulations.
    let boxes: Vec<(DVec3, DVec3)> = b
        .bones
        .iter()
        .map(|x| x.mesh.bounding_box().unwrap())
        .collect();
    let mut hits = 0usize;
    let mut worst: BTreeMap<(String, String), usize> = BTreeMap::new();
    for (i, a) in b.bones.iter().enumerate() {
        for (j, c) in b.bones.iter().enumerate() {
            if i == j {
                continue;
            }
            let (lo, hi) = boxes[j];
            let candidates: Vec<DVec3> = a
                .mesh
                .positions
                .iter()
                .copied()
                .filter(|p| p.cmpge(lo).all() && p.cmple(hi).all())
                .filter(|p| {
                    !b.articulations
                        .iter()
                        .any(|r| r.centre.distance(*p) < r.radius)
                })
                .collect();
            if candidates.is_empty() {
                continue;
            }
            let w = Winding::new(&c.mesh);
            let n = candidates.iter().filter(|p| w.winding(**p) > 0).count();
            if n > 0 {
                hits += n;
                *worst.entry((a.name.clone(), c.name.clone())).or_default() += n;
            }
        }
    }
    let intersecting = hits as f64 / total as f64;
    println!(
        "{name:32} bones {:3} vertices {total:6} inside {:6.2} % intersecting {:5.2} % warnings {}",
        b.bones.len(),
        100.0 * inside_fraction,
        100.0 * intersecting,
        b.warnings.len()
    );
    for w in &b.warnings {
        println!("    warning: {w}");
    }
    for ((a, c), n) in worst.iter().filter(|x| *x.1 > 0) {
        println!("    {a} in {c}: {n} vertices");
    }
    (inside_fraction, intersecting)
}

fn models(category: &str) -> Vec<std::path::PathBuf> {
    let Some(root) = crate::common::refdata() else {
        return Vec::new();
    };
    let mut dirs: Vec<_> = std::fs::read_dir(root.join(category))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("mesh.obj").is_file())
        .collect();
    dirs.sort();
    dirs
}

/// `cargo test --release --test it bones_on_refdata -- --nocapture` prints the table.
#[test]
fn bones_on_refdata_lie_inside_the_skin_closed_and_apart() {
    for (category, upright) in [("humanoid", true), ("quadruped", false)] {
        for dir in models(category) {
            if crate::common::awaits_real_character_work(&dir, "bones_on_refdata") {
                continue;
            }
            let name = dir.file_name().unwrap().to_string_lossy().to_string();
            let (mesh, map, f) = refdata_fit(&dir, upright);
            let b = bones(&f, &map, &BoneOptions::default()).unwrap();
            if std::env::var("BONES_DEBUG").is_ok_and(|v| v == name) {
                for j in &f.skeleton.joints {
                    println!(
                        "{:16} {:?} {:.3} {:.3}",
                        j.name,
                        j.parent,
                        j.position,
                        glam::DMat3::from_quat(j.frame).y_axis
                    );
                }
            }
            for kind in [
                BoneKind::Mandible,
                BoneKind::Vertebra,
                BoneKind::RibCage,
                BoneKind::Scapula,
                BoneKind::Pelvis,
                BoneKind::Femur,
                BoneKind::Humerus,
                BoneKind::RadiusUlna,
                BoneKind::TibiaFibula,
                BoneKind::Patella,
            ] {
                assert!(b.count(kind) > 0, "{name}: no {kind:?}: {:?}", b.warnings);
            }
            let skull = if upright {
                BoneKind::Cranium
            } else {
                BoneKind::AnimalCranium
            };
            assert_eq!(b.count(skull), 1, "{name}");
            assert_eq!(b.count(BoneKind::Scapula), 2, "{name}: {:?}", b.warnings);
            let (inside, intersecting) = check(&name, &mesh, &f.skeleton, &b);
            assert!(inside >= 0.98, "{name}: {:.2} % inside", 100.0 * inside);
            assert!(
                intersecting == 0.0,
                "{name}: {:.2} % of bone vertices inside other bones",
                100.0 * intersecting
            );
        }
    }
}

/// A closed capsule of radius `r` from `a` to `b`.
fn limb_capsule(a: DVec3, b: DVec3, r: f64) -> Mesh {
    let d = b - a;
    let c = Mesh::capsule(DVec3::ZERO, r, 0.5 * d.length(), 6, 16);
    let q = DQuat::from_rotation_arc(DVec3::Y, d.normalize());
    let mid = 0.5 * (a + b);
    c.transformed(|p| mid + q * p)
}

fn merged(parts: Vec<Mesh>) -> Mesh {
    skelfit::bones::shapes::merge(parts)
}

/// A toy quadruped of capsules (+Y up, +Z forward, ~2.5 units long) with its distance map and
/// a FitInput along the capsules' axes; `hind_right` and `fore` choose which limbs the input
/// has (the mesh always has all four legs).
fn toy_quadruped(fore: bool, hind_right: bool) -> (Mesh, DistanceMap, FitInput) {
    let v = DVec3::new;
    let mut parts = vec![
        limb_capsule(v(0.0, 1.0, -0.6), v(0.0, 1.0, 0.6), 0.25),
        limb_capsule(v(0.0, 1.05, 0.55), v(0.0, 1.45, 0.9), 0.11),
        limb_capsule(v(0.0, 1.45, 0.8), v(0.0, 1.4, 1.3), 0.13),
        limb_capsule(v(0.0, 1.05, -0.6), v(0.0, 0.7, -1.2), 0.06),
    ];
    for x in [0.15, -0.15] {
        for z in [0.45, -0.45] {
            parts.push(limb_capsule(v(x, 0.95, z), v(x, 0.05, z), 0.07));
        }
    }
    let mesh = merged(parts);
    let options = VoxelOptions {
        size: skelfit::voxel::VoxelSize::Fraction(0.01),
        ..Default::default()
    };
    let map = edt(&voxelize(&mesh, &options).unwrap());
    let axial_corners = [
        v(0.0, 1.4, 1.38),
        v(0.0, 1.43, 0.95),
        v(0.0, 1.2, 0.68),
        v(0.0, 1.0, 0.45),
        v(0.0, 1.0, -0.45),
        v(0.0, 1.02, -0.65),
        v(0.0, 0.73, -1.18),
    ];
    let points = dense(&axial_corners, 0.01);
    let radii = points.iter().map(|p| radius(&map, *p)).collect();
    let mut limbs = Vec::new();
    let leg = |kind, side: Side, z: f64| {
        let x = 0.15 * side.sign();
        let attach = v(0.0, 1.0, z);
        let path = dense(&[attach, v(x, 0.9, z), v(x, 0.06, z)], 0.01);
        LimbInput {
            kind,
            side,
            pair: 0,
            attach,
            radii: path.iter().map(|p| radius(&map, *p)).collect(),
            path,
            digits: Vec::new(),
            root: None,
        }
    };
    if fore {
        limbs.push(leg(LimbKind::ForeLeg, Side::Left, 0.45));
        limbs.push(leg(LimbKind::ForeLeg, Side::Right, 0.45));
    }
    limbs.push(leg(LimbKind::HindLeg, Side::Left, -0.45));
    if hind_right {
        limbs.push(leg(LimbKind::HindLeg, Side::Right, -0.45));
    }
    let input = FitInput {
        up: DVec3::Y,
        forward: DVec3::Z,
        axial: AxialPath {
            points,
            radii,
            sections: None,
            tail: false,
        },
        limbs,
        jaw: None,
        ears: Vec::new(),
    };
    (mesh, map, input)
}

fn quadruped_fit(input: &FitInput) -> Fit {
    fit(
        input,
        &Template::builtin("quadruped").unwrap(),
        &FitOptions::default(),
    )
    .unwrap()
}

#[test]
fn toy_quadruped_has_every_bone_family_inside_and_apart() {
    let (mesh, map, input) = toy_quadruped(true, true);
    let f = quadruped_fit(&input);
    let b = bones(&f, &map, &BoneOptions::default()).unwrap();
    for kind in [
        BoneKind::AnimalCranium,
        BoneKind::Mandible,
        BoneKind::Vertebra,
        BoneKind::TailVertebra,
        BoneKind::RibCage,
        BoneKind::Scapula,
        BoneKind::Humerus,
        BoneKind::RadiusUlna,
        BoneKind::Pelvis,
        BoneKind::Femur,
        BoneKind::Patella,
        BoneKind::TibiaFibula,
    ] {
        assert!(b.count(kind) > 0, "no {kind:?}: {:?}", b.warnings);
    }
    let (inside, intersecting) = check("toy quadruped", &mesh, &f.skeleton, &b);
    assert!(inside >= 0.98, "{inside}");
    assert!(intersecting == 0.0, "{intersecting}");
    // Deterministic.
    assert_eq!(b, bones(&f, &map, &BoneOptions::default()).unwrap());
}

/// Distances of every bone vertex to its joint and to the far end of its segment are kept by
/// any pose: the bone moves rigidly with the segment (forward kinematics).
#[test]
fn posing_moves_each_bone_rigidly_with_its_segment() {
    let (_, map, input) = toy_quadruped(true, true);
    let f = quadruped_fit(&input);
    let b = bones(&f, &map, &BoneOptions::default()).unwrap();
    let s = &f.skeleton;
    let pose: Vec<DQuat> = (0..s.len())
        .map(|k| {
            let a = 0.1 + 0.05 * (k % 7) as f64;
            DQuat::from_euler(glam::EulerRot::XYZ, a, -0.5 * a, 0.3 * a)
        })
        .collect();
    let posed = b.posed_mesh(s, &pose);
    let world = s.world_transforms(&pose);
    let mut offset = 0;
    let mut moved = 0.0f64;
    for bone in &b.bones {
        let n = bone.mesh.positions.len();
        let after = &posed.positions[offset..offset + n];
        offset += n;
        let j = bone.joint;
        let centroid = bone.mesh.positions.iter().sum::<DVec3>() / n as f64;
        let far = s
            .children(j)
            .into_iter()
            .min_by(|a, c| {
                s.joint(*a)
                    .position
                    .distance(centroid)
                    .total_cmp(&s.joint(*c).position.distance(centroid))
            })
            .unwrap_or(j);
        for (rest, now) in bone.mesh.positions.iter().zip(after) {
            for end in [j, far] {
                let before = rest.distance(s.joint(end).position);
                let posed = now.distance(world[end.0].translation);
                assert!(
                    (before - posed).abs() < 1e-9,
                    "{}: {before} -> {posed}",
                    bone.name
                );
            }
            moved = moved.max(rest.distance(*now));
        }
    }
    assert_eq!(offset, posed.positions.len());
    assert!(moved > 0.1, "the pose should move bones: {moved}");
    // The rest pose gives the rest meshes.
    let rest = b.posed_mesh(s, &s.rest_pose());
    let world_mesh = b.world_mesh();
    for (a, c) in rest.positions.iter().zip(&world_mesh.positions) {
        assert!(a.distance(*c) < 1e-9);
    }
}

/// The bones GLB: every bone is a child node of its joint's node and its vertices, carried
/// through the node transforms, land on the rest-pose bone mesh.
#[test]
fn bones_glb_nests_bones_under_their_joints() {
    let (_, map, input) = toy_quadruped(true, true);
    let f = quadruped_fit(&input);
    let b = bones(&f, &map, &BoneOptions::default()).unwrap();
    let bytes = skelfit::bones::bones_glb_bytes(
        &f.skeleton,
        &b,
        None,
        &skelfit::export::GltfOptions::default(),
    )
    .unwrap();
    let (doc, buffers, _) = gltf::import_slice(&bytes).unwrap();
    let nodes: Vec<gltf::Node> = doc.nodes().collect();
    let mut parent = vec![None; nodes.len()];
    for n in &nodes {
        for c in n.children() {
            parent[c.index()] = Some(n.index());
        }
    }
    let world = |mut k: usize| {
        let mut m = glam::Mat4::from_cols_array_2d(&nodes[k].transform().matrix());
        while let Some(p) = parent[k] {
            m = glam::Mat4::from_cols_array_2d(&nodes[p].transform().matrix()) * m;
            k = p;
        }
        m
    };
    let size = f
        .skeleton
        .joints
        .iter()
        .map(|j| j.position.length())
        .fold(0.0, f64::max);
    for bone in &b.bones {
        let node = nodes
            .iter()
            .find(|n| n.mesh().is_some() && n.name() == Some(bone.name.as_str()))
            .unwrap();
        let p = parent[node.index()].expect("bone nodes hang from joints");
        assert_eq!(
            nodes[p].name(),
            Some(f.skeleton.joint(bone.joint).name.as_str()),
            "{}",
            bone.name
        );
        let m = world(node.index());
        let prim = node.mesh().unwrap().primitives().next().unwrap();
        let reader = prim.reader(|buf| Some(&buffers[buf.index()]));
        let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        assert_eq!(positions.len(), bone.mesh.positions.len());
        for (p, expected) in positions.iter().zip(&bone.mesh.positions) {
            let got = m.transform_point3(glam::Vec3::from_array(*p)).as_dvec3();
            assert!(
                got.distance(*expected) < 1e-5 * size.max(1.0),
                "{}",
                bone.name
            );
        }
    }
    // OBJ and SVG of the bones alone.
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("bones.obj");
    skelfit::bones::write_bones_obj(&obj, &b).unwrap();
    let back = skelfit::mesh::load(&obj).unwrap();
    assert_eq!(back.triangles.len(), b.world_mesh().triangles.len());
    let svg = skelfit::bones::bones_svg(&b, None, 300.0);
    // Three views; in each, a titled group per bone that shows, filled and outlined.
    assert!(svg.starts_with("<svg"));
    let groups = svg.matches("<g><title>").count();
    assert!(
        groups > 3 + b.bones.len() && groups <= 3 + 3 * b.bones.len(),
        "{groups}"
    );
    assert_eq!(svg.matches("<path").count(), 2 * (groups - 3));
}

/// Removes the joints below `name` (keeping it), re-indexing parents and the canonical map.
fn cut_below(f: &Fit, name: &str) -> Fit {
    let s = &f.skeleton;
    let cut = s.find(name).unwrap();
    let mut drop = vec![false; s.len()];
    for (k, j) in s.joints.iter().enumerate() {
        if let Some(p) = j.parent {
            drop[k] = drop[p.0] || p == cut;
        }
    }
    let mut map = vec![None; s.len()];
    let mut joints = Vec::new();
    for (k, j) in s.joints.iter().enumerate() {
        if drop[k] {
            continue;
        }
        map[k] = Some(JointId(joints.len()));
        let mut j = j.clone();
        j.parent = j.parent.and_then(|p| map[p.0]);
        joints.push(j);
    }
    Fit {
        skeleton: Skeleton { joints },
        canonical: f
            .canonical
            .iter()
            .filter_map(|(k, id)| map[id.0].map(|n| (k.clone(), n)))
            .collect(),
        warnings: f.warnings.clone(),
        template: f.template.clone(),
    }
}

#[test]
fn missing_parts_give_warnings_and_the_bones_that_can_be_made() {
    // A missing hind leg: one femur, the pelvis mirrors the other socket.
    let (_, map, input) = toy_quadruped(true, false);
    let f = quadruped_fit(&input);
    let b = bones(&f, &map, &BoneOptions::default()).unwrap();
    assert_eq!(b.count(BoneKind::Femur), 1);
    assert_eq!(b.count(BoneKind::Pelvis), 1);
    assert!(
        b.warnings.iter().any(|w| w.to_string().contains("mirrors")),
        "{:?}",
        b.warnings
    );
    // No fore legs: no rib cage, no scapulae, with a warning.
    let (_, map, input) = toy_quadruped(false, true);
    let f = quadruped_fit(&input);
    let b = bones(&f, &map, &BoneOptions::default()).unwrap();
    assert_eq!(b.count(BoneKind::RibCage) + b.count(BoneKind::Scapula), 0);
    assert!(b.count(BoneKind::Femur) == 2 && b.count(BoneKind::Vertebra) > 0);
    assert!(
        b.warnings
            .iter()
            .any(|w| w.to_string().contains("no rib cage")),
        "{:?}",
        b.warnings
    );
    // Digit-less fore legs: cut below the wrists.
    let (_, map, input) = toy_quadruped(true, true);
    let full = quadruped_fit(&input);
    let wrist_l = full.skeleton.joint(full.canonical["wrist_L"]).name.clone();
    let wrist_r = full.skeleton.joint(full.canonical["wrist_R"]).name.clone();
    let cut = cut_below(&cut_below(&full, &wrist_l), &wrist_r);
    let all = bones(&full, &map, &BoneOptions::default()).unwrap();
    let b = bones(&cut, &map, &BoneOptions::default()).unwrap();
    assert_eq!(b.count(BoneKind::Humerus), 2);
    assert_eq!(b.count(BoneKind::RadiusUlna), 2);
    assert_eq!(b.count(BoneKind::Carpals), 0);
    assert!(all.count(BoneKind::Carpals) == 2);
    assert!(
        b.warnings
            .iter()
            .filter(|w| w.to_string().contains("digit-less"))
            .count()
            == 2,
        "{:?}",
        b.warnings
    );
}

#[test]
fn a_snake_gets_a_skull_and_vertebrae_but_no_girdles() {
    let v = DVec3::new;
    let mesh = limb_capsule(v(0.0, 0.1, -2.0), v(0.0, 0.1, 2.0), 0.1);
    let map = edt(&voxelize(&mesh, &VoxelOptions::default()).unwrap());
    let points = dense(&[v(0.0, 0.1, 2.05), v(0.0, 0.1, -2.05)], 0.01);
    let radii = points.iter().map(|p| radius(&map, *p)).collect();
    let input = FitInput {
        up: DVec3::Y,
        forward: DVec3::Z,
        axial: AxialPath {
            points,
            radii,
            sections: None,
            tail: false,
        },
        limbs: Vec::new(),
        jaw: None,
        ears: Vec::new(),
    };
    let f = quadruped_fit(&input);
    let b = bones(&f, &map, &BoneOptions::default()).unwrap();
    assert_eq!(b.count(BoneKind::AnimalCranium), 1, "{:?}", b.warnings);
    assert!(b.count(BoneKind::Vertebra) >= 3, "{:?}", b.warnings);
    for kind in [
        BoneKind::RibCage,
        BoneKind::Pelvis,
        BoneKind::Femur,
        BoneKind::Humerus,
    ] {
        assert_eq!(b.count(kind), 0);
    }
    assert!(b
        .warnings
        .iter()
        .any(|w| w.to_string().contains("no rib cage")));
    assert!(b
        .warnings
        .iter()
        .any(|w| w.to_string().contains("no pelvis")));
    // Bad input is an error, not a panic.
    let empty = Fit {
        skeleton: Skeleton::default(),
        canonical: BTreeMap::new(),
        warnings: Vec::new(),
        template: "x".into(),
    };
    assert!(bones(&empty, &map, &BoneOptions::default()).is_err());
    let bad = BoneOptions {
        tail_taper: 1.5,
        ..Default::default()
    };
    assert!(bones(&f, &map, &bad).is_err());
}

/// `skelfit bones` end to end on the bundled data: a validator-clean armature with bones,
/// OBJ and SVG.
#[test]
fn cli_bones_writes_glb_obj_and_svg() {
    let Some(dir) = crate::common::model("quadruped/khronos_fox") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    let glb = out.path().join("fox_bones.glb");
    let obj = out.path().join("fox_bones.obj");
    let svg = out.path().join("fox_bones.svg");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_skelfit"))
        .arg("bones")
        .arg(dir.join("mesh.obj"))
        .arg("-o")
        .arg(&glb)
        .arg("--obj")
        .arg(&obj)
        .arg("--svg")
        .arg(&svg)
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let stdout = String::from_utf8_lossy(&status.stdout);
    assert!(
        stdout.contains("rib_cage 1") && stdout.contains("pelvis 1"),
        "{stdout}"
    );
    let (doc, ..) = gltf::import(&glb).unwrap();
    assert!(doc.meshes().count() > 20);
    assert!(doc.skins().next().is_none());
    let bones = skelfit::mesh::load(&obj).unwrap();
    assert!(bones.triangles.len() > 1000);
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
}

/// The same properties with the whole pipeline (`pipeline::rig`: labelling → paths → fit)
/// instead of reference-joint paths; prints the table with
/// `cargo test --release --test it bones_on_rigged -- --nocapture`.
#[test]
fn bones_on_rigged_refdata() {
    use skelfit::pipeline::{rig, RigOptions};
    for category in ["humanoid", "quadruped"] {
        for dir in models(category) {
            if crate::common::awaits_real_character_work(&dir, "bones_on_rigged_refdata") {
                continue;
            }
            let name = dir.file_name().unwrap().to_string_lossy().to_string();
            let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).unwrap();
            let rigged = match rig(&mesh, &RigOptions::default()) {
                Ok(r) => r,
                Err(e) => {
                    println!("{name}: rig failed: {e}");
                    continue;
                }
            };
            let b = bones(&rigged.fit, &rigged.distance, &BoneOptions::default()).unwrap();
            let (inside, intersecting) = check(&name, &mesh, &rigged.fit.skeleton, &b);
            assert!(inside >= 0.98, "{name}: {inside}");
            assert!(intersecting == 0.0, "{name}: {intersecting}");
        }
    }
}

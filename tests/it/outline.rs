//! Outline skeletons (seed 003): straight skeletons against known answers and invariants, the
//! outline pipeline, assembly of parts, level-of-detail monotonicity, bad input, the CLI.

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use skelfit::lod::{
    collapse_bones, level_of_detail, merge_junctions, prune_branches, simplify_branches,
    LodOptions, LodScope,
};
use skelfit::outline::{
    assemble, outline_part, outline_skeleton, read_outline, straight_skeleton, Outline,
    OutlineError, OutlineOptions, PartPlacement, StraightSkeleton,
};
use skelfit::skeleton::{Joint, JointId, Skeleton};
use std::process::Command;

fn node_at(s: &StraightSkeleton, p: DVec2) -> usize {
    s.nodes
        .iter()
        .position(|n| n.position.distance(p) < 1e-9)
        .unwrap_or_else(|| panic!("no node at {p}: {s:#?}"))
}

fn degree(s: &StraightSkeleton, node: usize) -> usize {
    s.arcs.iter().filter(|a| a.contains(&node)).count()
}

/// Distance from `p` to the line through polygon edge `e`.
fn line_distance(polygon: &[DVec2], e: usize, p: DVec2) -> f64 {
    let (a, b) = (polygon[e], polygon[(e + 1) % polygon.len()]);
    (b - a).normalize().perp_dot(p - a)
}

/// The invariants every straight skeleton of a simple polygon keeps.
fn check_invariants(polygon: &[DVec2], s: &StraightSkeleton, tolerance: f64) {
    let n = polygon.len();
    assert_eq!(s.corners, n);
    let outline = Outline {
        points: polygon.to_vec(),
    };
    for (k, node) in s.nodes.iter().enumerate().skip(n) {
        assert!(
            node.edges.len() >= 3,
            "node {k} has {} defining edges",
            node.edges.len()
        );
        // Equidistant from every defining edge's line, at the node's offset time, on the inner side.
        for &e in &node.edges {
            let d = line_distance(polygon, e, node.position);
            assert!(
                (d - node.time).abs() <= tolerance,
                "node {k} at {} time {} is {d} from edge {e}",
                node.position,
                node.time
            );
        }
        // No polygon edge line is nearer than the offset time where the edge itself is near.
        assert!(outline.contains(node.position), "node {k} lies outside");
    }
    // A tree with one arc from each corner.
    assert_eq!(s.arcs.len(), s.nodes.len() - 1, "{s:#?}");
    for corner in 0..n {
        assert_eq!(degree(s, corner), 1, "corner {corner}");
    }
    let mut reached = vec![false; s.nodes.len()];
    let mut stack = vec![0usize];
    reached[0] = true;
    while let Some(at) = stack.pop() {
        for a in &s.arcs {
            let other = if a[0] == at {
                a[1]
            } else if a[1] == at {
                a[0]
            } else {
                continue;
            };
            if !reached[other] {
                reached[other] = true;
                stack.push(other);
            }
        }
    }
    assert!(reached.iter().all(|&r| r), "the skeleton is not connected");
    // Planar: arcs meet only at shared nodes.
    for (i, a) in s.arcs.iter().enumerate() {
        for b in &s.arcs[i + 1..] {
            if a.iter().any(|x| b.contains(x)) {
                continue;
            }
            let (p, q) = (s.nodes[a[0]].position, s.nodes[a[1]].position);
            let (r, t) = (s.nodes[b[0]].position, s.nodes[b[1]].position);
            let side = |u: DVec2, v: DVec2, w: DVec2| (v - u).perp_dot(w - u);
            let crosses = side(p, q, r) * side(p, q, t) < -tolerance
                && side(r, t, p) * side(r, t, q) < -tolerance;
            assert!(!crosses, "arcs {a:?} and {b:?} cross");
        }
    }
}

#[test]
fn rectangle_skeleton_is_a_ridge_with_four_diagonals() {
    let rect = [
        DVec2::ZERO,
        DVec2::new(4.0, 0.0),
        DVec2::new(4.0, 2.0),
        DVec2::new(0.0, 2.0),
    ];
    let s = straight_skeleton(&rect, 1e-9).unwrap();
    check_invariants(&rect, &s, 1e-9);
    assert_eq!(s.nodes.len(), 6);
    let (a, b) = (
        node_at(&s, DVec2::new(1.0, 1.0)),
        node_at(&s, DVec2::new(3.0, 1.0)),
    );
    assert!(s.arcs.contains(&[a.min(b), a.max(b)]));
    assert_eq!(s.nodes[a].time, 1.0);
    assert_eq!(s.nodes[b].edges, vec![0, 1, 2]);
}

#[test]
fn l_shape_skeleton_meets_at_the_inner_corner_bisector() {
    // Two arms of width 2; the reflex corner (2,2) runs to (1,1) where both arm axes meet.
    let l = [
        DVec2::new(0.0, 0.0),
        DVec2::new(4.0, 0.0),
        DVec2::new(4.0, 2.0),
        DVec2::new(2.0, 2.0),
        DVec2::new(2.0, 4.0),
        DVec2::new(0.0, 4.0),
    ];
    let s = straight_skeleton(&l, 1e-9).unwrap();
    check_invariants(&l, &s, 1e-9);
    assert_eq!(s.nodes.len(), 9, "{s:#?}");
    let centre = node_at(&s, DVec2::new(1.0, 1.0));
    let right = node_at(&s, DVec2::new(3.0, 1.0));
    let top = node_at(&s, DVec2::new(1.0, 3.0));
    assert_eq!(degree(&s, centre), 4);
    assert_eq!(degree(&s, right), 3);
    assert_eq!(degree(&s, top), 3);
    assert!(s.arcs.contains(&[3, centre]), "the reflex corner's arc");
    assert!(s.arcs.contains(&[0, centre]));
}

#[test]
fn regular_polygons_collapse_to_their_centre() {
    for sides in [3usize, 4, 5, 6, 7, 12] {
        let polygon: Vec<DVec2> = (0..sides)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / sides as f64;
                DVec2::new(5.0 + 2.0 * a.cos(), -1.0 + 2.0 * a.sin())
            })
            .collect();
        let s = straight_skeleton(&polygon, 1e-9).unwrap();
        check_invariants(&polygon, &s, 1e-9);
        assert_eq!(s.nodes.len(), sides + 1, "{sides} sides: {s:#?}");
        let centre = &s.nodes[sides];
        assert!(centre.position.distance(DVec2::new(5.0, -1.0)) < 1e-9);
        let inradius = 2.0 * (std::f64::consts::PI / sides as f64).cos();
        assert!((centre.time - inradius).abs() < 1e-9);
        assert_eq!(centre.edges.len(), sides);
    }
}

/// A star-shaped simple polygon with random radii (seeded).
fn random_polygon(seed: u64, n: usize) -> Vec<DVec2> {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * (k as f64 + 0.8 * next()) / n as f64;
            let r = 0.4 + 1.6 * next();
            DVec2::new(r * a.cos(), r * a.sin())
        })
        .collect()
}

#[test]
fn random_simple_polygons_keep_every_invariant() {
    for seed in 0..500u64 {
        let n = 5 + (seed as usize % 60);
        let polygon = random_polygon(seed, n);
        let s = straight_skeleton(&polygon, 1e-9).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        check_invariants(&polygon, &s, 1e-7);
    }
}

proptest! {
    #![proptest_config(crate::common::proptest_config(64))]
    #[test]
    fn straight_skeleton_invariants_hold_for_random_stars(seed in 1000u64..100_000, n in 4usize..40) {
        let polygon = random_polygon(seed, n);
        let s = straight_skeleton(&polygon, 1e-9).unwrap();
        check_invariants(&polygon, &s, 1e-7);
    }
}

/// A starfish outline: `arms` lobes, `points` samples.
fn starfish(arms: usize, points: usize) -> Vec<DVec2> {
    (0..points)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / points as f64;
            let r = 100.0 * (0.45 + 0.55 * (0.5 + 0.5 * (arms as f64 * a).cos()).powi(3));
            DVec2::new(r * a.cos(), r * a.sin())
        })
        .collect()
}

#[test]
fn a_starfish_outline_gets_one_terminal_joint_per_arm_inside_the_outline() {
    let options = OutlineOptions::default();
    for arms in [3usize, 5] {
        let outline = Outline::new(starfish(arms, 2000), &options).unwrap();
        let part = outline_skeleton(&outline, &options).unwrap();
        let s = &part.skeleton;
        assert!(s.validate().is_ok());
        let degrees = skelfit::lod::degrees(s);
        let terminals = degrees.iter().filter(|&&d| d == 1).count();
        assert_eq!(terminals, arms, "{arms} arms: {:#?}", s.joints);
        for j in &s.joints {
            assert!(
                outline.contains(j.position.truncate()),
                "{} outside",
                j.name
            );
            assert_eq!(j.position.z, 0.0);
        }
        assert!(s.len() < 40, "{} joints", s.len());
        // The root is the thickest joint: near the centre.
        assert!(s.joints[0].position.length() < 30.0);
        let svg = skelfit::outline::outline_svg(&part);
        assert!(svg.starts_with("<svg") && svg.matches("<circle").count() == s.len());
    }
}

#[test]
fn a_noisy_stroke_gives_the_same_topology_as_a_clean_one() {
    let options = OutlineOptions::default();
    let clean = starfish(4, 2000);
    // Radial jitter of up to ±1 (1 % of the size) at every sample: an unsteady hand, but the
    // stroke stays simple (its angle about the centre still increases monotonically).
    let noisy: Vec<DVec2> = clean
        .iter()
        .enumerate()
        .map(|(k, p)| *p * (1.0 + (((k * 7919) % 13) as f64 / 12.0 - 0.5) * 2.0 / p.length()))
        .collect();
    let count = |points: Vec<DVec2>| {
        let outline = Outline::new(points, &options).unwrap();
        let part = outline_skeleton(&outline, &options).unwrap();
        skelfit::lod::degrees(&part.skeleton)
            .iter()
            .filter(|&&d| d == 1)
            .count()
    };
    assert_eq!(count(clean), 4);
    assert_eq!(count(noisy), 4);
}

fn rectangle(min: DVec2, max: DVec2, per_side: usize) -> Vec<DVec2> {
    let corners = [min, DVec2::new(max.x, min.y), max, DVec2::new(min.x, max.y)];
    (0..4)
        .flat_map(|c| {
            let (a, b) = (corners[c], corners[(c + 1) % 4]);
            (0..per_side).map(move |k| a.lerp(b, k as f64 / per_side as f64))
        })
        .collect()
}

#[test]
fn a_crossing_part_attaches_to_the_nearest_bone_of_the_earlier_part() {
    let options = OutlineOptions::default();
    // A horizontal body, then a vertical leg overlapping its middle from below.
    let body = Outline::new(
        rectangle(DVec2::new(0.0, 0.0), DVec2::new(100.0, 20.0), 50),
        &options,
    )
    .unwrap();
    let leg = Outline::new(
        rectangle(DVec2::new(45.0, -60.0), DVec2::new(55.0, 15.0), 50),
        &options,
    )
    .unwrap();
    let far = Outline::new(
        rectangle(DVec2::new(300.0, 0.0), DVec2::new(320.0, 40.0), 50),
        &options,
    )
    .unwrap();
    let parts: Vec<_> = [&body, &leg, &far]
        .iter()
        .map(|o| outline_part(o, &options).unwrap())
        .collect();
    let placements = vec![PartPlacement::default(); 3];
    let assembly = assemble(&parts, &placements).unwrap();
    assert_eq!(assembly.parent_part, vec![None, Some(0), None]);
    let s = &assembly.skeleton;
    assert!(s.validate().is_ok());
    let roots: Vec<_> = s.joints.iter().filter(|j| j.parent.is_none()).collect();
    assert_eq!(roots.len(), 2, "body+leg connected, far part separate");
    // The leg's upper end lies inside the body's bone region: a bone split joint on the body axis.
    let split = s
        .joints
        .iter()
        .find(|j| j.name.contains("_attach_2"))
        .expect("a split joint");
    assert!(
        (split.position.y - 10.0).abs() < 1.0 && (split.position.x - 50.0).abs() < 3.0,
        "{}",
        split.position
    );
    let stats = assembly.mesh.stats();
    assert_eq!(stats.boundary_edges, 0);
}

/// A random tree skeleton from proptest values: parent of joint k is `parents[k] % k`.
fn random_skeleton(parents: &[usize], coords: &[(f64, f64, f64)]) -> Skeleton {
    let joints = coords
        .iter()
        .enumerate()
        .map(|(k, &(x, y, z))| {
            let parent = (k > 0).then(|| JointId(parents[k] % k));
            Joint::new(format!("j{k}"), parent, DVec3::new(x, y, z))
        })
        .collect();
    Skeleton { joints }
}

fn arb_skeleton() -> impl Strategy<Value = Skeleton> {
    (2usize..40).prop_flat_map(|n| {
        (
            proptest::collection::vec(0usize..1000, n),
            proptest::collection::vec((-10.0f64..10.0, -10.0f64..10.0, -10.0f64..10.0), n),
        )
            .prop_map(|(p, c)| random_skeleton(&p, &c))
    })
}

proptest! {
    #![proptest_config(crate::common::proptest_config(200))]
    #[test]
    fn raising_a_threshold_never_adds_joints(
        skeleton in arb_skeleton(),
        a in 0.0f64..12.0,
        b in 0.0f64..12.0,
    ) {
        let (lo, hi) = (a.min(b), a.max(b));
        let g = LodScope::Global;
        type Op = fn(&Skeleton, f64, &LodScope) -> Result<Skeleton, skelfit::lod::LodError>;
        let ops: [(&str, Op); 4] = [
            ("simplify", simplify_branches),
            ("merge", merge_junctions),
            ("prune", prune_branches),
            ("collapse", collapse_bones),
        ];
        for (name, op) in ops {
            let fine = op(&skeleton, lo, &g).unwrap();
            let coarse = op(&skeleton, hi, &g).unwrap();
            prop_assert!(fine.validate().is_ok() && coarse.validate().is_ok());
            prop_assert!(coarse.len() <= fine.len(), "{name}: {} joints at {hi} > {} at {lo}", coarse.len(), fine.len());
            prop_assert!(fine.len() <= skeleton.len());
            prop_assert_eq!(&coarse.joints[0].name, &skeleton.joints[0].name);
        }
    }
}

#[test]
fn each_operation_does_what_the_seed_describes() {
    // A T: root at the left end of a bar with a short stem and a sleeve joint.
    let j = |name: &str, parent: Option<usize>, x: f64, y: f64| {
        Joint::new(name, parent.map(JointId), DVec3::new(x, y, 0.0))
    };
    let s = Skeleton {
        joints: vec![
            j("root", None, 0.0, 0.0),
            j("mid", Some(0), 5.0, 0.1),
            j("junction", Some(1), 10.0, 0.0),
            j("junction2", Some(2), 11.0, 0.0),
            j("end", Some(3), 20.0, 0.0),
            j("stem", Some(2), 10.0, 2.0),
            j("stem2", Some(3), 11.0, 8.0),
        ],
    };
    let g = LodScope::Global;
    // ε_s: "mid" is 0.1 off the chord root-junction.
    assert_eq!(simplify_branches(&s, 0.05, &g).unwrap().len(), 7);
    let simple = simplify_branches(&s, 0.5, &g).unwrap();
    assert!(simple.find("mid").is_none() && simple.len() == 6);
    // ε_m: the two junctions 1 apart merge at their mean.
    let merged = merge_junctions(&s, 1.5, &g).unwrap();
    assert_eq!(merged.len(), 6);
    let m = merged.find("junction").unwrap();
    assert_eq!(merged.joint(m).position, DVec3::new(10.5, 0.0, 0.0));
    // ε_t: the 2-long stem goes, the 8-long one stays.
    let pruned = prune_branches(&s, 5.0, &g).unwrap();
    assert!(pruned.find("stem").is_none() && pruned.find("stem2").is_some());
    // ε_c: the 1-long bone between the two internal junctions collapses.
    let collapsed = collapse_bones(&s, 1.5, &g).unwrap();
    assert_eq!(collapsed.len(), 6);
    // Scopes: a part that excludes the junctions changes nothing there.
    let scoped = collapse_bones(&s, 1.5, &LodScope::Part("stem2".into())).unwrap();
    assert_eq!(scoped.len(), 7);
    let branch = simplify_branches(&s, 0.5, &LodScope::Branch("mid".into())).unwrap();
    assert_eq!(branch.len(), 6);
    assert!(simplify_branches(&s, 0.5, &LodScope::Branch("nope".into())).is_err());
    assert!(level_of_detail(
        &s,
        &LodOptions {
            merge: -1.0,
            ..Default::default()
        }
    )
    .is_err());
}

fn write(dir: &std::path::Path, name: &str, text: &str) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn bad_outlines_are_named_errors_not_panics() {
    let dir = tempfile::tempdir().unwrap();
    let options = OutlineOptions::default();
    let read = |name: &str, text: &str| read_outline(&write(dir.path(), name, text), &options);
    assert!(matches!(
        read("two.csv", "0,0\n1,0\n"),
        Err(OutlineError::TooFewPoints { count: 2 })
    ));
    assert!(matches!(
        read("dup.csv", "0,0\n1,0\n1,0\n1,1\n0,1\n"),
        Err(OutlineError::DuplicatePoint { .. })
    ));
    assert!(matches!(
        read("bow.csv", "0,0\n1,1\n1,0\n0,1\n"),
        Err(OutlineError::SelfIntersecting { .. })
    ));
    let open: String = (0..30)
        .map(|k| format!("{},{}\n", k, (k as f64 * 0.3).sin()))
        .collect();
    assert!(matches!(
        read("open.csv", &open),
        Err(OutlineError::OpenPath { .. })
    ));
    assert!(matches!(
        read(
            "open.svg",
            r#"<svg><path d="M0 0 L 10 0 L 10 10 L 20 10 L 20 20 L 30 20"/></svg>"#
        ),
        Err(OutlineError::OpenPath { .. })
    ));
    assert!(matches!(
        read("x.dxf", "0,0"),
        Err(OutlineError::UnknownFormat { .. })
    ));
    let err = read("bow.csv", "0,0\n1,1\n1,0\n0,1\n")
        .unwrap_err()
        .to_string();
    assert!(
        err.starts_with("the outline intersects itself") && err.contains("draw a simple outline"),
        "{err}"
    );
}

fn skelfit(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_skelfit"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn cli_outline_writes_a_skinned_glb_svg_and_json() {
    let dir = tempfile::tempdir().unwrap();
    let csv: String = starfish(5, 800)
        .iter()
        .map(|p| format!("{},{}\n", p.x, p.y))
        .collect();
    let input = write(dir.path(), "star.csv", &csv);
    let glb = dir.path().join("star.glb");
    let svg = dir.path().join("star.svg");
    let json = dir.path().join("star.json");
    let out = skelfit(&[
        "outline",
        input.to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
        "--skeleton-json",
        json.to_str().unwrap(),
        "--thickness",
        "0.8",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(&glb).unwrap();
    assert_eq!(&bytes[0..4], b"glTF");
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    let rig = skelfit::eval::load_skeleton(&json).unwrap();
    assert!(rig.skeleton.len() >= 6);

    // skelfit simplify: coarser with every threshold raised.
    let coarse = dir.path().join("coarse.json");
    let out = skelfit(&[
        "simplify",
        json.to_str().unwrap(),
        "-o",
        coarse.to_str().unwrap(),
        "--prune",
        "1000",
        "--collapse",
        "1000",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let simpler = skelfit::eval::load_skeleton(&coarse).unwrap();
    assert!(simpler.skeleton.len() < rig.skeleton.len());

    // Bad input: an error message and exit code 1, no panic.
    let bad = write(dir.path(), "bad.csv", "0,0\n1,1\n1,0\n0,1\n");
    let out = skelfit(&[
        "outline",
        bad.to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("skelfit: error:") && err.contains("intersects itself"),
        "{err}"
    );
}

/// Axis-aligned polygons make many events coincide (equal arm widths, collinear reflex
/// corners): a plus sign, a comb and a staircase.
#[test]
fn orthogonal_polygons_with_simultaneous_events_keep_every_invariant() {
    let pts = |v: &[(f64, f64)]| v.iter().map(|&(x, y)| DVec2::new(x, y)).collect::<Vec<_>>();
    let plus = pts(&[
        (1.0, 0.0),
        (2.0, 0.0),
        (2.0, 1.0),
        (3.0, 1.0),
        (3.0, 2.0),
        (2.0, 2.0),
        (2.0, 3.0),
        (1.0, 3.0),
        (1.0, 2.0),
        (0.0, 2.0),
        (0.0, 1.0),
        (1.0, 1.0),
    ]);
    let mut comb = vec![DVec2::new(0.0, 0.0), DVec2::new(9.0, 0.0)];
    for k in (0..5).rev() {
        let x = 2.0 * k as f64;
        comb.push(DVec2::new(x + 1.0, 4.0));
        comb.push(DVec2::new(x, 4.0));
        if k > 0 {
            comb.push(DVec2::new(x, 1.0));
            comb.push(DVec2::new(x - 1.0, 1.0));
        }
    }
    comb[2] = DVec2::new(9.0, 4.0);
    comb[3] = DVec2::new(8.0, 4.0);
    // A corner list whose closing edge is long: closed explicitly by repeating the start.
    let mut stairs = vec![DVec2::new(0.0, 0.0), DVec2::new(6.0, 0.0)];
    for k in (0..6).rev() {
        stairs.push(DVec2::new(k as f64 + 1.0, 6.0 - k as f64));
        stairs.push(DVec2::new(k as f64, 6.0 - k as f64));
    }
    stairs.push(DVec2::ZERO);
    for (name, polygon) in [("plus", plus), ("comb", comb), ("stairs", stairs)] {
        let outline = Outline::new(polygon.clone(), &OutlineOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let s = straight_skeleton(&outline.points, 1e-9).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_invariants(&outline.points, &s, 1e-7);
    }
}

proptest! {
    #![proptest_config(crate::common::proptest_config(48))]
    /// Random smooth blobs of 2,000 points: the whole pipeline gives a valid skeleton whose
    /// joints all lie inside the outline.
    #[test]
    fn random_blobs_give_valid_skeletons_inside_the_outline(
        amplitudes in proptest::collection::vec(0.0f64..0.35, 5),
        phases in proptest::collection::vec(0.0f64..6.3, 5),
        scale in 0.01f64..1000.0,
    ) {
        let points: Vec<DVec2> = (0..2000)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 2000.0;
                let r = 1.0 + amplitudes
                    .iter()
                    .zip(&phases)
                    .enumerate()
                    .map(|(i, (c, p))| c * ((i + 2) as f64 * a + p).cos())
                    .sum::<f64>()
                    .max(-0.9);
                DVec2::new(a.cos(), a.sin()) * r * scale
            })
            .collect();
        let options = OutlineOptions::default();
        let outline = Outline::new(points, &options).unwrap();
        let part = outline_skeleton(&outline, &options).unwrap();
        prop_assert!(part.skeleton.validate().is_ok());
        prop_assert!(!part.skeleton.is_empty());
        for j in &part.skeleton.joints {
            prop_assert!(outline.contains(j.position.truncate()), "{} at {} outside", j.name, j.position);
        }
        prop_assert_eq!(part.radii.len(), part.skeleton.len());
    }
}

#[test]
fn cli_outline_reads_svg_and_applies_level_of_detail() {
    let dir = tempfile::tempdir().unwrap();
    // A plus-shaped figure drawn with curves at the arm ends, in SVG (y down).
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M 40 0 L 60 0 L 60 40 L 100 40
        C 110 40 110 60 100 60 L 60 60 L 60 100 L 40 100 L 40 60 L 0 60 C -10 60 -10 40 0 40
        L 40 40 Z"/></svg>"#;
    let input = write(dir.path(), "plus.svg", svg);
    let glb = dir.path().join("plus.glb");
    let fine = dir.path().join("fine.json");
    let coarse = dir.path().join("coarse.json");
    let run = |json: &std::path::Path, extra: &[&str]| {
        let mut args = vec![
            "outline",
            input.to_str().unwrap(),
            "-o",
            glb.to_str().unwrap(),
            "--skeleton-json",
            json.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let out = skelfit(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        skelfit::eval::load_skeleton(json).unwrap().skeleton
    };
    let fine = run(&fine, &[]);
    let coarse = run(&coarse, &["--lod-prune", "45"]);
    // Four arms meet at the centre; pruning the arms shorter than 45 leaves fewer terminals.
    assert_eq!(
        skelfit::lod::degrees(&fine)
            .iter()
            .filter(|&&d| d == 1)
            .count(),
        4
    );
    assert!(
        coarse.len() < fine.len(),
        "{} vs {}",
        coarse.len(),
        fine.len()
    );
}

#[test]
fn cli_skeleton_level_of_detail_gives_fewer_joints_and_a_valid_rig() {
    let dir = tempfile::tempdir().unwrap();
    // Three capsule arms from the origin.
    let mut mesh = skelfit::mesh::Mesh::default();
    for k in 0..3 {
        let rotation = glam::DQuat::from_rotation_z(std::f64::consts::TAU * k as f64 / 3.0);
        let arm = skelfit::mesh::Mesh::capsule(DVec3::ZERO, 0.1, 0.5, 8, 16)
            .transformed(|p| rotation * (p + DVec3::new(0.0, 0.5, 0.0)));
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(&arm.positions);
        mesh.triangles
            .extend(arm.triangles.iter().map(|t| t.map(|i| i + base)));
    }
    let obj = dir.path().join("tri.obj");
    skelfit::export::write_obj(&obj, &mesh).unwrap();
    let glb = dir.path().join("tri.glb");
    let count = |extra: &[&str]| {
        let json = dir.path().join("tri.json");
        let mut args = vec![
            "skeleton",
            obj.to_str().unwrap(),
            "-o",
            glb.to_str().unwrap(),
            "--skeleton-json",
            json.to_str().unwrap(),
            "--approx-error",
            "0",
            "--segments",
            "12",
        ];
        args.extend_from_slice(extra);
        let out = skelfit(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert_eq!(&std::fs::read(&glb).unwrap()[0..4], b"glTF");
        skelfit::eval::load_skeleton(&json).unwrap().skeleton.len()
    };
    let full = count(&[]);
    let simplified = count(&["--lod-simplify", "0.2", "--lod-collapse", "0.2"]);
    assert!(simplified < full, "{simplified} vs {full}");
}

proptest! {
    #![proptest_config(crate::common::proptest_config(256))]
    /// Arbitrary point lists, valid or not, give a result or an error, never a panic or a hang.
    #[test]
    fn arbitrary_points_never_panic(
        raw in proptest::collection::vec((-10i32..10, -10i32..10), 0..25),
    ) {
        let points: Vec<DVec2> = raw.iter().map(|&(x, y)| DVec2::new(x as f64, y as f64)).collect();
        let options = OutlineOptions::default();
        if let Ok(outline) = Outline::new(points.clone(), &options) {
            let part = outline_skeleton(&outline, &options);
            prop_assert!(part.is_ok(), "{:?}", part.err());
        }
        // Unvalidated input straight into the algorithms.
        let _ = straight_skeleton(&points, 1e-9);
        let _ = outline_skeleton(&Outline { points }, &options);
    }
}

#[test]
fn a_part_placed_in_a_crossing_plane_attaches_in_3d() {
    let options = OutlineOptions::default();
    let body = Outline::new(
        rectangle(DVec2::new(0.0, 0.0), DVec2::new(100.0, 20.0), 50),
        &options,
    )
    .unwrap();
    // A wing drawn in its own XY plane, turned 90° about +Y so it spans the z direction, and
    // moved so its root end overlaps the body's middle.
    let wing = Outline::new(
        rectangle(DVec2::new(-5.0, 5.0), DVec2::new(60.0, 15.0), 50),
        &options,
    )
    .unwrap();
    let parts = vec![
        outline_part(&body, &options).unwrap(),
        outline_part(&wing, &options).unwrap(),
    ];
    let turn = glam::DAffine3::from_rotation_translation(
        glam::DQuat::from_rotation_y(-std::f64::consts::FRAC_PI_2),
        DVec3::new(50.0, 0.0, 0.0),
    );
    let placements = vec![PartPlacement::default(), PartPlacement { transform: turn }];
    let assembly = assemble(&parts, &placements).unwrap();
    assert_eq!(assembly.parent_part, vec![None, Some(0)]);
    let s = &assembly.skeleton;
    assert_eq!(s.joints.iter().filter(|j| j.parent.is_none()).count(), 1);
    // The wing's far end sticks out along +z.
    let far = s
        .joints
        .iter()
        .map(|j| j.position.z)
        .fold(f64::MIN, f64::max);
    assert!(far > 40.0, "{far}");
    assert!(s.validate().is_ok());
}

#[test]
fn cli_outline_places_parts_and_rejects_bad_placements() {
    let dir = tempfile::tempdir().unwrap();
    let csv = |points: Vec<DVec2>| {
        points
            .iter()
            .map(|p| format!("{},{}\n", p.x, p.y))
            .collect::<String>()
    };
    let body = write(
        dir.path(),
        "body.csv",
        &csv(rectangle(DVec2::ZERO, DVec2::new(100.0, 20.0), 50)),
    );
    let wing = write(
        dir.path(),
        "wing.csv",
        &csv(rectangle(DVec2::new(-5.0, 5.0), DVec2::new(60.0, 15.0), 50)),
    );
    let glb = dir.path().join("bird.glb");
    let json = dir.path().join("bird.json");
    let base = [
        "outline",
        body.to_str().unwrap(),
        wing.to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
        "--skeleton-json",
        json.to_str().unwrap(),
        "--json",
    ];
    let mut args = base.to_vec();
    args.extend(["--place", "2:50,0,0,-90"]);
    let out = skelfit(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(summary["parent_part"], serde_json::json!([null, 0]));
    let rig = skelfit::eval::load_skeleton(&json).unwrap();
    assert!(rig.skeleton.joints.iter().any(|j| j.position.z > 40.0));
    let mut args = base.to_vec();
    args.extend(["--place", "3:0,0,0"]);
    let out = skelfit(&args);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--place"));
}

#[test]
fn the_bundled_starfish_svg_gets_five_arms_named_in_order() {
    let path = crate::common::data_dir().join("outlines/starfish.svg");
    let options = OutlineOptions::default();
    let outline = read_outline(&path, &options).unwrap();
    let part = outline_skeleton(&outline, &options).unwrap();
    let s = &part.skeleton;
    let degrees = skelfit::lod::degrees(s);
    assert_eq!(degrees[0], 5, "the root is the centre junction");
    assert_eq!(degrees.iter().filter(|&&d| d == 1).count(), 5);
    for (k, joint) in s.joints.iter().enumerate().skip(1) {
        assert_eq!(joint.name, format!("joint_{k:03}"));
    }
}

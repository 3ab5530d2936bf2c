//! Integration tests of the voxel stage: volumes, robustness to holes, bad input.

use glam::DVec3;
use skelfit::mesh::Mesh;
use skelfit::voxel::{voxelize, Solid, VoxelError, VoxelOptions, VoxelSize};

fn options(fraction: f64) -> VoxelOptions {
    VoxelOptions {
        size: VoxelSize::Fraction(fraction),
        ..Default::default()
    }
}

fn relative_error(measured: f64, expected: f64) -> f64 {
    (measured - expected).abs() / expected
}

/// Fraction of voxels on which two solids on the same grid disagree, relative to `a`'s interior.
fn disagreement(a: &Solid, b: &Solid) -> f64 {
    assert_eq!(a.grid, b.grid);
    let differ = a
        .inside
        .iter()
        .zip(&b.inside)
        .filter(|(x, y)| x != y)
        .count();
    differ as f64 / a.interior_count() as f64
}

#[test]
fn sphere_and_box_volumes_within_three_percent_at_128() {
    let sphere = Mesh::uv_sphere(DVec3::new(0.3, -1.0, 2.0), 1.5, 64, 128);
    let solid = voxelize(&sphere, &options(1.0 / 128.0)).unwrap();
    let exact = sphere.signed_volume();
    assert!(relative_error(solid.interior_volume(), exact) < 0.03);
    assert_eq!(solid.report.components, 1);
    assert_eq!(solid.report.ambiguous_voxels, 0);

    let cuboid = Mesh::cuboid(DVec3::new(-1.0, 0.0, 0.0), DVec3::new(2.0, 0.5, 1.25));
    let solid = voxelize(&cuboid, &options(1.0 / 128.0)).unwrap();
    assert!(relative_error(solid.interior_volume(), 3.0 * 0.5 * 1.25) < 0.03);
}

#[test]
fn inward_wound_mesh_gives_the_same_solid() {
    let sphere = Mesh::uv_sphere(DVec3::ZERO, 1.0, 32, 64);
    let mut inverted = sphere.clone();
    for t in &mut inverted.triangles {
        t.swap(1, 2);
    }
    let a = voxelize(&sphere, &options(1.0 / 48.0)).unwrap();
    let b = voxelize(&inverted, &options(1.0 / 48.0)).unwrap();
    assert_eq!(a.inside, b.inside);
}

#[test]
fn sphere_with_a_punched_hole_gives_nearly_the_closed_solid() {
    let sphere = Mesh::uv_sphere(DVec3::ZERO, 1.0, 48, 96);
    let mut holed = sphere.clone();
    // Remove every triangle near the north pole: a hole of ~30 degrees half-angle.
    holed
        .triangles
        .retain(|t| t.iter().all(|&i| holed.positions[i as usize].y < 0.85));
    assert!(holed.triangles.len() < sphere.triangles.len());
    let closed = voxelize(&sphere, &options(1.0 / 64.0)).unwrap();
    let open = voxelize(&holed, &options(1.0 / 64.0)).unwrap();
    // Same bounding box up to the cap, so compare by volume and by overlap of the kept part.
    assert!(relative_error(open.interior_volume(), closed.interior_volume()) < 0.03);
    let parity_free = open.report.ambiguous_voxels;
    assert!(parity_free > 0, "the hole should make some votes disagree");
}

#[test]
fn doubled_faces_and_double_sided_shells_give_the_single_solid() {
    let sphere = Mesh::uv_sphere(DVec3::ZERO, 1.0, 32, 64);
    let single = voxelize(&sphere, &options(1.0 / 48.0)).unwrap();
    assert_eq!(single.report.duplicate_triangles, 0);
    // A band of faces around the equator written twice with the same winding (a modelling
    // leftover): counted twice it makes every column through the band see winding 2 on one
    // side and carves the solid.
    let mut doubled = sphere.clone();
    let band: Vec<[u32; 3]> = doubled
        .triangles
        .iter()
        .filter(|t| {
            t.iter()
                .all(|&i| doubled.positions[i as usize].y.abs() < 0.3)
        })
        .copied()
        .collect();
    assert!(!band.is_empty());
    doubled
        .triangles
        .extend(band.iter().map(|&[a, b, c]| [b, c, a]));
    let solid = voxelize(&doubled, &options(1.0 / 48.0)).unwrap();
    assert_eq!(solid.report.duplicate_triangles, band.len());
    assert_eq!(solid.inside, single.inside);
    // The whole sphere drawn from both sides (every face also reversed): the twins would
    // cancel it to nothing.
    let mut two_sided = sphere.clone();
    two_sided
        .triangles
        .extend(sphere.triangles.iter().map(|&[a, b, c]| [a, c, b]));
    let solid = voxelize(&two_sided, &options(1.0 / 48.0)).unwrap();
    assert_eq!(solid.report.duplicate_triangles, sphere.triangles.len());
    assert_eq!(solid.inside, single.inside);
    assert!(solid
        .report
        .warnings()
        .iter()
        .any(|w| w.to_string().contains("repeat another one")));
}

#[test]
fn overlapping_parts_are_one_solid() {
    // Two overlapping boxes as separate, intersecting closed parts (winding 2 in the overlap).
    let mut mesh = Mesh::cuboid(DVec3::ZERO, DVec3::new(2.0, 1.0, 1.0));
    let other = Mesh::cuboid(DVec3::new(1.0, 0.0, 0.0), DVec3::new(3.0, 1.0, 1.0));
    let offset = mesh.positions.len() as u32;
    mesh.positions.extend(other.positions);
    mesh.triangles
        .extend(other.triangles.iter().map(|t| t.map(|i| i + offset)));
    let solid = voxelize(&mesh, &options(1.0 / 96.0)).unwrap();
    assert!(relative_error(solid.interior_volume(), 3.0) < 0.03);
    assert_eq!(solid.report.components, 1);
}

#[test]
fn a_stack_of_open_sheets_beside_a_body_adds_no_volume() {
    // A unit box and, just beside it along +x, five open squares wound the same way (hair
    // cards lying over one another). A ray along x through the stack crosses five sheets;
    // summed unclamped, that one direction outvoted the five that see nothing, and the
    // columns through the stack became a second piece joined to the box (7 % more volume).
    let mut mesh = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
    for k in 0..5 {
        let x = 1.02 + 0.02 * k as f64;
        let first = mesh.positions.len() as u32;
        mesh.positions.extend([
            DVec3::new(x, 0.1, 0.1),
            DVec3::new(x, 0.9, 0.1),
            DVec3::new(x, 0.9, 0.9),
            DVec3::new(x, 0.1, 0.9),
        ]);
        mesh.triangles
            .extend([[0, 1, 2], [0, 2, 3]].map(|t: [u32; 3]| t.map(|i| i + first)));
    }
    let solid = voxelize(&mesh, &options(1.0 / 96.0)).unwrap();
    assert!(
        relative_error(solid.interior_volume(), 1.0) < 0.03,
        "interior volume {} for a unit box",
        solid.interior_volume()
    );
    assert_eq!(solid.report.components, 1, "{:?}", solid.report);
}

#[test]
fn largest_component_is_kept_and_the_rest_reported() {
    let with_cube_at = |lo: f64, hi: f64| {
        let mut mesh = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        let small = Mesh::cuboid(DVec3::splat(lo), DVec3::splat(hi));
        let offset = mesh.positions.len() as u32;
        mesh.positions.extend(small.positions);
        mesh.triangles
            .extend(small.triangles.iter().map(|t| t.map(|i| i + offset)));
        mesh
    };
    // Beside the figure (within a tenth of its size): voxelized and joined to it across the
    // gap (a head or a hand modelled as its own shell).
    let beside = |gap: f64| {
        let mut mesh = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
        let small = Mesh::cuboid(
            DVec3::new(1.0 + gap, 0.35, 0.35),
            DVec3::new(1.3 + gap, 0.65, 0.65),
        );
        let offset = mesh.positions.len() as u32;
        mesh.positions.extend(small.positions);
        mesh.triangles
            .extend(small.triangles.iter().map(|t| t.map(|i| i + offset)));
        mesh
    };
    let solid = voxelize(&beside(0.05), &options(1.0 / 128.0)).unwrap();
    assert_eq!(solid.report.components, 2);
    assert_eq!(solid.report.left_out_pieces, 0);
    assert_eq!(
        (solid.report.joined_pieces, solid.report.dropped_voxels),
        (1, 0)
    );
    assert!(solid.report.bridge_voxels > 0 && solid.report.widest_gap > 0.0);
    assert!(relative_error(solid.interior_volume(), 1.027) < 0.05);
    assert!(solid.report.warnings().is_empty());
    // With joining limited to gaps of 2 % of the grid's side it is dropped, and named.
    let narrow = VoxelOptions {
        join_gap: 0.02,
        ..options(1.0 / 128.0)
    };
    let solid = voxelize(&beside(0.05), &narrow).unwrap();
    assert_eq!(solid.report.components, 2);
    assert!(solid.report.dropped_voxels > 0);
    assert_eq!(solid.report.dropped_pieces.len(), 1);
    assert!(relative_error(solid.interior_volume(), 1.0) < 0.05);
    let warning = &solid.report.warnings()[0];
    assert!(
        warning.to_string().contains("1 piece of the interior")
            && warning.to_string().contains("around (1.2"),
        "{warning}"
    );
    // Diagonally beside (a gap of 0.087 counted in face steps: 15 voxels): dropped too.
    let solid = voxelize(&with_cube_at(1.05, 1.35), &options(1.0 / 128.0)).unwrap();
    assert_eq!(
        (
            solid.report.joined_pieces,
            solid.report.dropped_pieces.len()
        ),
        (0, 1)
    );
    // Far away: left out before voxelizing, so the grid fits the unit cube alone.
    let solid = voxelize(&with_cube_at(3.0, 3.3), &options(1.0 / 128.0)).unwrap();
    assert_eq!(solid.report.left_out_pieces, 1);
    assert_eq!(solid.report.left_out_triangles, 12);
    assert_eq!(solid.report.components, 1);
    assert!((solid.grid.voxel_size - 1.0 / 128.0).abs() < 1e-12);
    assert!(relative_error(solid.interior_volume(), 1.0) < 0.05);
    assert!(solid.report.warnings()[0]
        .to_string()
        .starts_with("1 loose piece"));
}

#[test]
fn voxelization_is_deterministic_across_thread_counts() {
    let mesh = Mesh::capsule(DVec3::ZERO, 0.5, 1.0, 16, 32);
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| voxelize(&mesh, &options(1.0 / 50.0)).unwrap())
    };
    let (a, b) = (run(1), run(3));
    assert_eq!(a.inside, b.inside);
    assert_eq!(a.surface, b.surface);
    let _ = disagreement(&a, &b);
}

#[test]
fn surface_voxels_enclose_the_interior() {
    let mesh = Mesh::uv_sphere(DVec3::ZERO, 1.0, 24, 48);
    let solid = voxelize(&mesh, &options(1.0 / 40.0)).unwrap();
    // Every interior voxel next to an exterior voxel is on the surface shell.
    let grid = solid.grid;
    for i in 0..grid.len() {
        if !solid.inside[i] {
            continue;
        }
        let c = grid.coords(i);
        let boundary = skelfit::voxel::Connectivity::Six
            .neighbours()
            .iter()
            .any(|n| grid.offset(c, n.offset).is_some_and(|j| !solid.inside[j]));
        if boundary {
            // the surface passes between the two centres, so one of them is touched
            let touched = solid.surface[i]
                || skelfit::voxel::Connectivity::Six
                    .neighbours()
                    .iter()
                    .any(|n| grid.offset(c, n.offset).is_some_and(|j| solid.surface[j]));
            assert!(touched, "voxel {c:?}");
        }
    }
}

#[test]
fn bad_input_gives_clear_errors() {
    // No triangles.
    let empty = Mesh::default();
    assert_eq!(
        voxelize(&empty, &VoxelOptions::default()).unwrap_err(),
        VoxelError::NoTriangles
    );
    // A single triangle: flat along z.
    let tri = Mesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
    assert!(matches!(
        voxelize(&tri, &VoxelOptions::default()),
        Err(VoxelError::Flat { .. })
    ));
    // A single tilted triangle has a 3-D bounding box but encloses nothing.
    let tilted = Mesh::new(
        vec![
            DVec3::ZERO,
            DVec3::new(1.0, 0.2, 0.1),
            DVec3::new(0.1, 1.0, 0.3),
        ],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let err = voxelize(&tilted, &options(0.05)).unwrap_err();
    assert!(matches!(err, VoxelError::EmptyInterior { .. }), "{err}");
    // Zero-area triangles only (collinear corners, spread in 3-D).
    let degenerate = Mesh::new(
        vec![
            DVec3::ZERO,
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(2.0, 2.0, 2.0),
        ],
        vec![[0, 1, 2], [2, 1, 0]],
    )
    .unwrap();
    assert!(matches!(
        voxelize(&degenerate, &options(0.05)),
        Err(VoxelError::EmptyInterior { .. })
    ));
    // Invalid sizes.
    let cube = Mesh::cuboid(DVec3::ZERO, DVec3::ONE);
    for size in [
        VoxelSize::Fraction(0.0),
        VoxelSize::Fraction(1.5),
        VoxelSize::Absolute(-1.0),
        VoxelSize::Absolute(f64::NAN),
    ] {
        let err = voxelize(
            &cube,
            &VoxelOptions {
                size,
                ..Default::default()
            },
        )
        .unwrap_err();
        assert!(matches!(err, VoxelError::InvalidSize { .. }));
    }
    // Budget exceeded: the error names a size that fits, and that size does fit.
    let err = voxelize(
        &cube,
        &VoxelOptions {
            size: VoxelSize::Fraction(1.0 / 500.0),
            max_voxels: 1_000_000,
            ..Default::default()
        },
    )
    .unwrap_err();
    let VoxelError::TooLarge { fitting_size, .. } = err else {
        panic!("expected TooLarge, got {err}");
    };
    assert!(err.to_string().contains("exceeds the budget"));
    let fitted = voxelize(
        &cube,
        &VoxelOptions {
            size: VoxelSize::Absolute(fitting_size),
            max_voxels: 1_000_000,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(fitted.grid.len() <= 1_000_000);
    assert!(
        fitted.grid.len() > 900_000,
        "the suggested size should be close to the budget"
    );
}

fn load_model(relative: &str) -> Option<Mesh> {
    let dir = crate::common::model(relative)?;
    Some(skelfit::mesh::load(&dir.join("mesh.obj")).expect("refdata mesh loads"))
}

#[test]
fn makehuman_volume_within_three_percent_at_128() {
    let Some(mesh) = load_model("humanoid/mh_male_young_average") else {
        return;
    };
    let solid = voxelize(&mesh, &options(1.0 / 128.0)).unwrap();
    let exact = mesh.signed_volume();
    let error = relative_error(solid.interior_volume(), exact);
    assert!(error < 0.03, "volume error {error}");
    assert_eq!(
        solid.report.ambiguous_voxels, 0,
        "closed mesh: all votes agree"
    );
}

#[test]
fn open_and_non_manifold_refdata_meshes_voxelize_to_one_solid() {
    // The dirty decimation (2 non-manifold edges, 3 parts) against its watertight twin.
    let (Some(dirty), Some(clean)) = (
        load_model("robustness/mh_male_young_average_dec3k_fastsimp"),
        load_model("humanoid/mh_male_young_average"),
    ) else {
        return;
    };
    assert!(!dirty.stats().closed);
    let solid = voxelize(&dirty, &options(1.0 / 128.0)).unwrap();
    let twin = clean.signed_volume();
    let error = relative_error(solid.interior_volume(), twin);
    assert!(
        error < 0.05,
        "fastsimp volume error {error} vs watertight twin"
    );
    assert!(
        solid.report.dropped_voxels * 100 < solid.report.interior_voxels,
        "one solid figure: dropped {} of {}",
        solid.report.dropped_voxels,
        solid.report.interior_voxels
    );

    // The deer has 6 boundary edges (small open seams): compare with the divergence-theorem
    // volume, which small holes barely change.
    let Some(deer) = load_model("quadruped/quaternius_deer") else {
        return;
    };
    let stats = deer.stats();
    assert!(stats.boundary_edges > 0);
    let solid = voxelize(&deer, &options(1.0 / 128.0)).unwrap();
    let estimate = deer.signed_volume().abs();
    let error = relative_error(solid.interior_volume(), estimate);
    assert!(error < 0.05, "deer volume error {error}");
    assert!(solid.report.dropped_voxels * 100 < solid.report.interior_voxels);
}

#[test]
fn makehuman_with_a_punched_hole_gives_nearly_the_closed_solid() {
    let Some(mesh) = load_model("humanoid/mh_male_young_average") else {
        return;
    };
    // Punch a hole in the top of the head: drop every triangle above 97 % of the height.
    let (min, max) = mesh.bounding_box().unwrap();
    let cut = min.y + 0.97 * (max.y - min.y);
    let mut holed = mesh.clone();
    holed
        .triangles
        .retain(|t| t.iter().any(|&i| mesh.positions[i as usize].y < cut));
    assert!(holed.stats().boundary_edges > 0, "the hole is open");
    // Same grid for both: the hole leaves the bounding box unchanged except for the cap top,
    // so voxelize with an absolute size and compare volumes and voxel sets in world space.
    let opts = VoxelOptions {
        size: VoxelSize::Absolute((max.y - min.y) / 128.0),
        ..Default::default()
    };
    let closed = voxelize(&mesh, &opts).unwrap();
    let open = voxelize(&holed, &opts).unwrap();
    let error = relative_error(open.interior_volume(), closed.interior_volume());
    assert!(error < 0.01, "volume changed by {error}");
    let world = |s: &Solid| -> std::collections::BTreeSet<[i64; 3]> {
        s.interior_indices()
            .into_iter()
            .map(|i| {
                let c = s.grid.centre(s.grid.coords(i));
                let h = s.grid.voxel_size;
                [
                    (c.x / h).floor() as i64,
                    (c.y / h).floor() as i64,
                    (c.z / h).floor() as i64,
                ]
            })
            .collect()
    };
    let (a, b) = (world(&closed), world(&open));
    let differ = a.symmetric_difference(&b).count();
    assert!(
        (differ as f64) < 0.01 * a.len() as f64,
        "{differ} of {} voxels differ",
        a.len()
    );
}

/// A long thin figure (a capsule ten times as long as it is thick) holds about two thousand
/// interior voxels at 1 % of its length: `voxelize_figure` refines the grid until it holds
/// about `min_interior`; a needle (80 times) is refined at most to half the voxel edge; the
/// bundled human body already holds more and keeps the first grid.
#[test]
fn thin_figures_get_a_finer_grid_and_bodies_keep_theirs() {
    use skelfit::voxel::voxelize_figure;
    let thin = Mesh::capsule(DVec3::ZERO, 0.2, 4.0, 16, 32);
    let options = VoxelOptions::default();
    let first = voxelize(&thin, &options).unwrap();
    let refined = voxelize_figure(&thin, &options).unwrap();
    assert!(first.report.interior_voxels < options.min_interior / 2);
    let (fraction, held) = refined.report.refined_from.expect("refined");
    assert_eq!((fraction, held), (0.01, first.report.interior_voxels));
    let n = refined.report.interior_voxels;
    assert!(
        n >= options.min_interior * 3 / 4 && n <= options.min_interior * 2,
        "{n} interior voxels"
    );
    assert!(refined.grid.voxel_size < first.grid.voxel_size);
    let needle = Mesh::capsule(DVec3::ZERO, 0.05, 8.0, 16, 32);
    let coarse = voxelize(&needle, &options).unwrap();
    let finer = voxelize_figure(&needle, &options).unwrap();
    let ratio = finer.grid.voxel_size / coarse.grid.voxel_size;
    assert!((ratio - 0.5).abs() < 1e-9, "{ratio}");
    assert!(finer.report.interior_voxels > coarse.report.interior_voxels);
    let body = skelfit::mesh::load(
        &crate::common::data_dir().join("humanoid/mh_neutral_default/mesh.obj"),
    )
    .unwrap();
    let kept = voxelize_figure(&body, &options).unwrap();
    assert_eq!(kept.report.refined_from, None);
    assert_eq!(kept.inside, voxelize(&body, &options).unwrap().inside);
    // Off, or with an absolute size, the first grid stands.
    let off = VoxelOptions {
        min_interior: 0,
        ..Default::default()
    };
    assert_eq!(
        voxelize_figure(&thin, &off).unwrap().report.refined_from,
        None
    );
    let absolute = VoxelOptions {
        size: VoxelSize::Absolute(0.04),
        ..Default::default()
    };
    assert_eq!(
        voxelize_figure(&thin, &absolute)
            .unwrap()
            .report
            .refined_from,
        None
    );
}

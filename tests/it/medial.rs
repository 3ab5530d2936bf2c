//! Integration tests of the medial stage: the discrete medial surface of analytic shapes and
//! of the reference models, through the real voxelization and distance transform.

use glam::{DMat3, DVec3};
use skelfit::distance::{edt, DistanceMap};
use skelfit::medial::{dms, DmsKind, MedialError, MedialOptions, MedialSurface};
use skelfit::mesh::Mesh;
use skelfit::voxel::{voxelize, Grid, Solid, VoxelOptions, VoxelReport, VoxelSize};

fn distance_of(mesh: &Mesh, fraction: f64) -> DistanceMap {
    let options = VoxelOptions {
        size: VoxelSize::Fraction(fraction),
        ..Default::default()
    };
    edt(&voxelize(mesh, &options).expect("voxelize"))
}

fn surface_of(distance: &DistanceMap) -> MedialSurface {
    dms(distance, &MedialOptions::default()).expect("dms")
}

/// World position of the centre of the DMS voxel at `position`.
fn centre(surface: &MedialSurface, position: usize) -> DVec3 {
    surface.grid.centre(surface.coords(position))
}

fn assert_connected(surface: &MedialSurface) {
    let sizes = surface.connected_component_sizes();
    assert_eq!(sizes.len(), 1, "DMS components of sizes {sizes:?}");
    assert_eq!(surface.components, 1);
    assert!(surface.component.iter().all(|&c| c == 0));
}

#[test]
fn box_dms_is_one_connected_surface_through_the_centre_plane() {
    // The 2 x 1 x 3 box of Figure 4.10(a).
    let mesh = Mesh::cuboid(DVec3::ZERO, DVec3::new(2.0, 1.0, 3.0));
    let distance = distance_of(&mesh, 1.0 / 48.0);
    let surface = surface_of(&distance);
    assert_connected(&surface);
    assert!(surface.warnings.is_empty(), "{:?}", surface.warnings);
    let h = distance.grid.voxel_size;
    // Every voxel whose centre lies within half a voxel of the plane y = 0.5 and well inside the
    // box's extent along x and z belongs to the DMS.
    let mut plane = 0;
    for i in 0..distance.grid.len() {
        let p = distance.grid.centre(distance.grid.coords(i));
        let central = (p.y - 0.5).abs() <= 0.5 * h + 1e-9
            && (0.6..=1.4).contains(&p.x)
            && (0.6..=2.4).contains(&p.z);
        if central && distance.squared[i] > 0 {
            plane += 1;
            assert!(surface.contains(i), "centre-plane voxel at {p} missing");
        }
    }
    assert!(plane > 100, "only {plane} centre-plane voxels");
    // A surface, not a volume: far fewer voxels than the interior.
    assert!(
        surface.len() * 4 < surface.interior_voxels,
        "{}",
        surface.len()
    );
    assert!(surface.true_count() > surface.bridging_count());
}

#[test]
fn rotated_box_dms_is_connected() {
    // Figure 4.10(b): rotated by 25 degrees about z, then 20 degrees about x.
    let rotation =
        DMat3::from_rotation_x(20f64.to_radians()) * DMat3::from_rotation_z(25f64.to_radians());
    let mesh = Mesh::cuboid(DVec3::ZERO, DVec3::new(2.0, 1.0, 3.0)).transformed(|p| rotation * p);
    let distance = distance_of(&mesh, 1.0 / 48.0);
    let surface = surface_of(&distance);
    assert_connected(&surface);
    assert!(surface.len() * 4 < surface.interior_voxels);
}

#[test]
fn capsule_dms_lies_near_its_axis() {
    let (radius, half_length) = (0.5, 1.5);
    let mesh = Mesh::capsule(DVec3::ZERO, radius, half_length, 24, 64);
    let distance = distance_of(&mesh, 1.0 / 64.0);
    let surface = surface_of(&distance);
    assert_connected(&surface);
    let h = distance.grid.voxel_size;
    let off_axis: Vec<f64> = (0..surface.len())
        .map(|p| {
            let c = centre(&surface, p);
            let on_axis = DVec3::new(0.0, c.y.clamp(-half_length, half_length), 0.0);
            (c - on_axis).length() / h
        })
        .collect();
    let near = off_axis.iter().filter(|&&d| d <= 2.0).count();
    let worst = off_axis.iter().copied().fold(0.0, f64::max);
    eprintln!(
        "capsule: {} DMS voxels, {near} within 2 voxels of the axis, worst {worst:.2} voxels, radius {:.1} voxels",
        surface.len(),
        radius / h
    );
    assert!(near as f64 >= 0.9 * surface.len() as f64);
    assert!(
        worst <= 0.5 * radius / h,
        "a DMS voxel {worst} voxels from the axis"
    );
    // The axis is covered from cap to cap.
    let (low, high) = (0..surface.len())
        .map(|p| centre(&surface, p).y)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
            (a.min(y), b.max(y))
        });
    assert!(low < -half_length + 2.0 * h && high > half_length - 2.0 * h);
}

#[test]
fn sphere_dms_is_compact_around_the_centre() {
    let radius = 1.0;
    let centre_point = DVec3::new(0.2, -0.4, 0.1);
    let mesh = Mesh::uv_sphere(centre_point, radius, 48, 96);
    let distance = distance_of(&mesh, 1.0 / 48.0);
    let surface = surface_of(&distance);
    assert_connected(&surface);
    let h = distance.grid.voxel_size;
    let off: Vec<f64> = (0..surface.len())
        .map(|p| (centre(&surface, p) - centre_point).length() / h)
        .collect();
    let worst = off.iter().copied().fold(0.0, f64::max);
    let near = off.iter().filter(|&&d| d <= 3.0).count();
    eprintln!(
        "sphere: {} DMS voxels, {near} within 3 voxels of the centre, worst {worst:.2}, radius {:.1} voxels",
        surface.len(),
        radius / h
    );
    assert!(near as f64 >= 0.9 * surface.len() as f64);
    assert!(worst <= 0.5 * radius / h);
}

fn single_voxel_solid() -> Solid {
    let grid = Grid {
        dims: [3, 3, 3],
        origin: DVec3::ZERO,
        voxel_size: 0.1,
    };
    let mut inside = vec![false; grid.len()];
    inside[grid.index([1, 1, 1])] = true;
    Solid {
        grid,
        surface: vec![false; grid.len()],
        inside,
        report: VoxelReport {
            interior_voxels: 1,
            components: 1,
            ..Default::default()
        },
    }
}

#[test]
fn single_interior_voxel_gives_a_single_voxel_dms_and_a_warning() {
    let solid = single_voxel_solid();
    let surface = surface_of(&edt(&solid));
    assert_eq!(surface.voxels, vec![solid.grid.index([1, 1, 1])]);
    assert_eq!(surface.kinds, vec![DmsKind::Bridging]);
    assert_eq!(surface.warnings.len(), 1);
    assert!(surface.warnings[0].to_string().contains("single voxel"));
}

#[test]
fn thin_sheet_gives_a_single_voxel_dms_and_a_warning() {
    // A sheet one voxel thick: every interior voxel is a "1" voxel.
    let mesh = Mesh::cuboid(DVec3::ZERO, DVec3::new(1.0, 0.03, 1.0));
    let distance = distance_of(&mesh, 1.0 / 32.0);
    assert_eq!(distance.max_distance(), 1.0);
    let surface = surface_of(&distance);
    assert_eq!(surface.len(), 1);
    assert!(surface
        .warnings
        .iter()
        .any(|w| w.to_string().contains("smaller voxel size")));
}

#[test]
fn out_of_range_options_and_bad_maps_are_clear_errors() {
    let distance = edt(&single_voxel_solid());
    for value in [-0.5, 2.01, f64::NAN] {
        let options = MedialOptions {
            exposure_threshold: value,
            ..Default::default()
        };
        let err = dms(&distance, &options).unwrap_err();
        assert!(matches!(err, MedialError::InvalidExposureThreshold { .. }));
        assert!(err.to_string().starts_with("exposure threshold"));
    }
    let empty = DistanceMap {
        grid: distance.grid,
        squared: vec![0; distance.grid.len()],
    };
    let err = dms(&empty, &MedialOptions::default()).unwrap_err();
    assert_eq!(err, MedialError::EmptyFigure);
    let mut unpadded = empty.clone();
    unpadded.squared[0] = 1;
    let err = dms(&unpadded, &MedialOptions::default()).unwrap_err();
    assert_eq!(err, MedialError::InteriorOnBorder { coords: [0, 0, 0] });
    // The crate error wraps the stage error.
    let wrapped: skelfit::Error = err.into();
    assert!(wrapped.to_string().contains("pad the grid"));
}

/// Checks that the DMS of a refdata model at 1/128 of its longest side is 26-connected at the
/// default threshold and at 1.0 (ch.4.4, ch.5), and that it reaches along the figure.
fn assert_model_dms_connected(relative: &str) {
    let Some(dir) = crate::common::model(relative) else {
        return;
    };
    let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).expect("load mesh.obj");
    let distance = distance_of(&mesh, 1.0 / 128.0);
    let figure = extent(
        &distance,
        (0..distance.grid.len()).filter(|&i| distance.squared[i] > 0),
    );
    let longest = (0..3).max_by_key(|&a| figure[a]).unwrap();
    for threshold in [0.5, 1.0] {
        let options = MedialOptions {
            exposure_threshold: threshold,
            ..Default::default()
        };
        let start = std::time::Instant::now();
        let surface = dms(&distance, &options).expect("dms");
        eprintln!(
            "{relative} T={threshold}: {} interior voxels, {} DMS voxels ({} true, {} saddles) in {:.0} ms",
            surface.interior_voxels,
            surface.len(),
            surface.true_count(),
            surface.saddles.len(),
            start.elapsed().as_secs_f64() * 1e3
        );
        assert_connected(&surface);
        assert!(surface.warnings.is_empty(), "{:?}", surface.warnings);
        let reach = extent(&distance, surface.voxels.iter().copied());
        assert!(
            reach[longest] as f64 >= 0.85 * figure[longest] as f64,
            "DMS spans {reach:?} voxels of the figure's {figure:?}"
        );
    }
}

/// Number of voxel layers spanned along x, y and z by the voxels `indices`.
fn extent(distance: &DistanceMap, indices: impl Iterator<Item = usize>) -> [usize; 3] {
    let (mut low, mut high) = ([usize::MAX; 3], [0; 3]);
    for i in indices {
        let c = distance.grid.coords(i);
        for a in 0..3 {
            low[a] = low[a].min(c[a]);
            high[a] = high[a].max(c[a]);
        }
    }
    [0, 1, 2].map(|a| high[a] + 1 - low[a])
}

#[test]
fn dms_is_connected_on_a_humanoid_a_quadruped_and_a_spider() {
    for model in [
        "humanoid/mh_male_young_average",
        "quadruped/quaternius_horse",
        "other/quaternius_spider",
    ] {
        assert_model_dms_connected(model);
    }
}

/// Every refdata model (about 2 s in release; CI runs release tests).
#[test]
fn dms_is_connected_on_every_refdata_model() {
    let Some(root) = crate::common::refdata() else {
        return;
    };
    for family in ["humanoid", "quadruped", "other", "robustness"] {
        let Ok(entries) = std::fs::read_dir(root.join(family)) else {
            continue;
        };
        let mut models: Vec<String> = entries
            .filter_map(|e| e.ok())
            .filter(|e| e.path().join("mesh.obj").is_file())
            .filter(|e| !crate::common::awaits_real_character_work(&e.path(), "dms_is_connected"))
            .map(|e| format!("{family}/{}", e.file_name().to_string_lossy()))
            .collect();
        models.sort();
        for model in models {
            assert_model_dms_connected(&model);
        }
    }
}

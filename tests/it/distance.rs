//! Integration tests of the distance stage: the EDT against brute force.

use glam::DVec3;
use proptest::prelude::*;
use skelfit::distance::edt;
use skelfit::voxel::{Grid, Solid, VoxelReport};

fn solid_from_mask(dims: [usize; 3], inside: Vec<bool>) -> Solid {
    let grid = Grid {
        dims,
        origin: DVec3::ZERO,
        voxel_size: 1.0,
    };
    let report = VoxelReport {
        interior_voxels: inside.iter().filter(|&&b| b).count(),
        ..Default::default()
    };
    Solid {
        grid,
        surface: vec![false; inside.len()],
        inside,
        report,
    }
}

fn brute_force(solid: &Solid) -> Vec<u32> {
    let grid = solid.grid;
    let exterior: Vec<[usize; 3]> = (0..grid.len())
        .filter(|&i| !solid.inside[i])
        .map(|i| grid.coords(i))
        .collect();
    (0..grid.len())
        .map(|i| {
            if !solid.inside[i] {
                return 0;
            }
            let c = grid.coords(i);
            exterior
                .iter()
                .map(|e| {
                    (0..3)
                        .map(|k| (c[k] as i64 - e[k] as i64).pow(2))
                        .sum::<i64>() as u32
                })
                .min()
                .unwrap()
        })
        .collect()
}

proptest! {
    #![proptest_config(crate::common::proptest_config(200))]
    #[test]
    fn edt_equals_brute_force_on_random_grids(
        dims in [1usize..14, 1usize..14, 1usize..14],
        density in 0.3f64..0.999,
        seed in any::<u64>(),
    ) {
        let len = dims[0] * dims[1] * dims[2];
        // A deterministic pseudo-random mask from the seed (splitmix64).
        let mut state = seed;
        let mut inside: Vec<bool> = (0..len).map(|_| {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) as f64 / u64::MAX as f64) < density
        }).collect();
        inside[(seed as usize) % len] = false; // at least one exterior voxel
        let solid = solid_from_mask(dims, inside);
        prop_assert_eq!(edt(&solid).squared, brute_force(&solid));
    }
}

#[test]
fn edt_of_single_interior_voxel_is_one() {
    let dims = [3, 3, 3];
    let mut inside = vec![false; 27];
    inside[13] = true;
    let map = edt(&solid_from_mask(dims, inside));
    assert_eq!(map.squared[13], 1);
    assert_eq!(map.squared.iter().filter(|&&d| d != 0).count(), 1);
}

#[test]
fn edt_of_anisotropic_slab_and_rod_equals_brute_force() {
    // A 1-voxel-thick slab, a long rod and a flat box: extreme aspect ratios.
    for (dims, lo, hi) in [
        ([40, 3, 20], [1, 1, 1], [39, 2, 19]),
        ([3, 3, 60], [1, 1, 1], [2, 2, 59]),
        ([30, 9, 5], [1, 1, 1], [29, 8, 4]),
    ] {
        let grid = Grid {
            dims,
            origin: DVec3::ZERO,
            voxel_size: 1.0,
        };
        let inside: Vec<bool> = (0..grid.len())
            .map(|i| {
                let c = grid.coords(i);
                (0..3).all(|k| c[k] >= lo[k] && c[k] < hi[k])
            })
            .collect();
        let solid = solid_from_mask(dims, inside);
        assert_eq!(edt(&solid).squared, brute_force(&solid), "dims {dims:?}");
    }
}

#[test]
fn edt_is_identical_on_one_and_many_threads() {
    let mesh = skelfit::mesh::Mesh::uv_sphere(DVec3::ZERO, 1.0, 24, 48);
    let options = skelfit::voxel::VoxelOptions {
        size: skelfit::voxel::VoxelSize::Fraction(1.0 / 40.0),
        ..Default::default()
    };
    let solid = skelfit::voxel::voxelize(&mesh, &options).unwrap();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| {
            (
                skelfit::voxel::voxelize(&mesh, &options).unwrap(),
                edt(&solid),
            )
        });
    let many = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap()
        .install(|| edt(&solid));
    assert_eq!(one.0.inside, solid.inside);
    assert_eq!(one.1.squared, many.squared);
}

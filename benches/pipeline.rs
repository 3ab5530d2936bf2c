//! Mesh to skinned general control skeleton (voxelize, EDT, medial surface, path tree,
//! skeletal graph, skin weights) on the bundled MakeHuman body and horse at the default voxel
//! size (1 % of the longest side) and at 0.5 %. Throughput is in interior voxels per second;
//! the target is 1 M interior voxels in at most 1 s end to end (see also
//! `cargo run --release --example scaling`, which writes the table in reports/scaling/).
//!
//! Run: `cargo bench --bench pipeline`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use skelfit::pipeline::{general_rig, GeneralRigOptions, GeneralSkeletonOptions};
use skelfit::voxel::{VoxelOptions, VoxelSize};
use std::path::PathBuf;

fn bundled(relative: &str) -> skelfit::mesh::Mesh {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(relative);
    skelfit::mesh::load(&path).expect("bundled mesh")
}

fn options(fraction: f64) -> GeneralRigOptions {
    GeneralRigOptions {
        skeleton: GeneralSkeletonOptions {
            voxel: VoxelOptions {
                size: VoxelSize::Fraction(fraction),
                ..Default::default()
            },
            ..Default::default()
        },
        ..Default::default()
    }
}

fn bench_pipeline(c: &mut Criterion) {
    let models = [
        (
            "humanoid",
            bundled("data/humanoid/mh_neutral_default/mesh.obj"),
        ),
        ("horse", bundled("data/quadruped/quaternius_horse/mesh.obj")),
    ];
    let mut group = c.benchmark_group("general_rig");
    group.sample_size(10);
    for (name, mesh) in &models {
        for fraction in [0.01, 0.005] {
            let options = options(fraction);
            let rig = general_rig(mesh, &options).expect("bundled mesh rigs");
            group.throughput(Throughput::Elements(rig.voxels.interior_voxels as u64));
            group.bench_with_input(BenchmarkId::new(*name, fraction), &options, |b, o| {
                b.iter(|| general_rig(mesh, o).unwrap())
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench_pipeline);
criterion_main!(benches);

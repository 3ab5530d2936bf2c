//! Voxelization and exact EDT on the bundled MakeHuman body at 64, 128 and 256 voxels along its
//! height. Throughput is reported in grid voxels per second.
//!
//! Run: `cargo bench --bench voxel`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use skelfit::distance::edt;
use skelfit::voxel::{voxelize, VoxelOptions, VoxelSize};
use std::path::PathBuf;

fn humanoid() -> skelfit::mesh::Mesh {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default/mesh.obj");
    skelfit::mesh::load(&path).expect("bundled humanoid mesh")
}

fn bench_voxel(c: &mut Criterion) {
    let mesh = humanoid();
    let (min, max) = mesh.bounding_box().unwrap();
    let height = max.y - min.y;
    let mut group = c.benchmark_group("voxelize");
    group.sample_size(20);
    for n in [64u32, 128, 256] {
        let options = VoxelOptions {
            size: VoxelSize::Absolute(height / n as f64),
            ..Default::default()
        };
        let solid = voxelize(&mesh, &options).unwrap();
        group.throughput(Throughput::Elements(solid.grid.len() as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &options, |b, o| {
            b.iter(|| voxelize(&mesh, o).unwrap())
        });
    }
    group.finish();

    let mut group = c.benchmark_group("edt");
    group.sample_size(30);
    for n in [64u32, 128, 256] {
        let options = VoxelOptions {
            size: VoxelSize::Absolute(height / n as f64),
            ..Default::default()
        };
        let solid = voxelize(&mesh, &options).unwrap();
        group.throughput(Throughput::Elements(solid.grid.len() as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &solid, |b, s| {
            b.iter(|| edt(s))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_voxel);
criterion_main!(benches);

//! Skinning: the anatomical `rig` of the bundled MakeHuman body end to end (the target:
//! under 0.15 s), and the skin stage alone on its fitted skeleton with the geodesic weights
//! (default) and the dissertation's anchor weights, on the body (27k triangles) and on the
//! body subdivided to 1.7 M triangles, and the geodesic weights on the body re-tessellated to
//! 1 M triangles (the target: a 1 M-triangle mesh under 1 s). Compare ratios within
//! one run: the machine is shared.
//!
//! Run: `cargo bench --bench skin`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use skelfit::pipeline::{rig, RigOptions};
use skelfit::skin::{skin_from_bones, SkinMethod, SkinOptions};
use std::path::PathBuf;

fn bench_skin(c: &mut Criterion) {
    let path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default/mesh.obj");
    let mesh = skelfit::mesh::load(&path).expect("bundled mesh");
    let options = RigOptions::default();
    let mut group = c.benchmark_group("rig");
    group.sample_size(10);
    group.bench_function("mh_neutral_default", |b| {
        b.iter(|| rig(&mesh, &options).unwrap())
    });
    group.finish();

    let rigged = rig(&mesh, &options).expect("bundled body rigs");
    let fine = mesh.subdivided().subdivided().subdivided();
    let million = mesh.retessellated(1.0e6 / mesh.triangles.len() as f64);
    let mut group = c.benchmark_group("skin");
    group.sample_size(10);
    for (name, method, sizes) in [
        (
            "geodesic",
            SkinMethod::Geodesic,
            &[("27k", &mesh), ("1M", &million), ("1.7M", &fine)][..],
        ),
        (
            "anchor",
            SkinMethod::Anchor,
            &[("27k", &mesh), ("1.7M", &fine)],
        ),
    ] {
        let skin_options = SkinOptions {
            method,
            ..Default::default()
        };
        for &(size, m) in sizes {
            group.bench_with_input(BenchmarkId::new(name, size), &skin_options, |b, o| {
                b.iter(|| {
                    skin_from_bones(m, &rigged.fit.skeleton, &rigged.solid, &rigged.distance, o)
                        .unwrap()
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, bench_skin);
criterion_main!(benches);

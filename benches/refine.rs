//! Slicing-based humanoid refinement (seed 004) on the bundled MakeHuman body (27k triangles)
//! and on its 4x and 16x coarser decimations, from the reference joints displaced by 3-6 cm.
//! The target is at most 50 ms per body; the seed reports under 0.5 s on a 3 GHz
//! Pentium 4 for up to 81k triangles.
//!
//! Run: `cargo bench --bench refine`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use glam::DVec3;
use skelfit::refine::{carry, refine, RefineOptions, REFINED_KEYS};
use std::path::PathBuf;

fn bench_refine(c: &mut Criterion) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("data/humanoid/mh_neutral_default");
    let mesh = skelfit::mesh::load(&dir.join("mesh.obj")).expect("bundled mesh");
    let rig = skelfit::eval::load_skeleton(&dir.join("rig_game_engine.json")).expect("bundled rig");
    // Seeded start: the same deterministic offsets as examples/refine_report.rs.
    let targets = REFINED_KEYS
        .iter()
        .enumerate()
        .filter_map(|(k, key)| {
            let id = *rig.canonical.get(*key)?;
            let kf = k as f64;
            let dir = DVec3::new(
                (1.7 * kf + 0.3).sin(),
                (2.3 * kf + 1.1).cos(),
                (0.9 * kf + 2.0).sin(),
            )
            .normalize();
            Some((
                id,
                rig.skeleton.joint(id).position + dir * (0.03 + 0.01 * (kf % 4.0)),
            ))
        })
        .collect();
    let rough = carry(&rig.skeleton, &targets);
    let options = RefineOptions::default();
    let mut group = c.benchmark_group("refine");
    group.sample_size(20);
    for ratio in [1.0, 0.25, 0.0625] {
        let m = if ratio < 1.0 {
            mesh.decimated(ratio)
        } else {
            mesh.clone()
        };
        group.bench_with_input(
            BenchmarkId::from_parameter(m.triangles.len()),
            &m,
            |b, m| {
                b.iter(|| {
                    refine(m, &rough, &rig.canonical, DVec3::Y, DVec3::Z, &options).expect("refine")
                })
            },
        );
    }
    group.finish();
}

criterion_group!(benches, bench_refine);
criterion_main!(benches);

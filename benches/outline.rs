//! Outline skeletons (seed 003): a noisy five-armed outline of 500, 2,000 and 8,000 points to
//! a simplified skeleton (validation, resampling, Douglas-Peucker polygon, straight skeleton,
//! axis graph, BoundedDP joints). Seed 003 reports 4-14 ms per part; the target is <= 15 ms
//! for 2,000 points. Inflation of the 2,000-point outline is measured separately.
//!
//! Run: `cargo bench --bench outline`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::DVec2;
use skelfit::outline::{inflate, outline_skeleton, Outline, OutlineOptions};

/// A five-armed starfish with a seeded wobble, `n` points.
fn starfish(n: usize) -> Vec<DVec2> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    (0..n)
        .map(|k| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let noise = (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            let r = 100.0 * (0.45 + 0.55 * (0.5 + 0.5 * (5.0 * a).cos()).powi(3)) + 0.3 * noise;
            DVec2::new(r * a.cos(), r * a.sin())
        })
        .collect()
}

fn bench_outline(c: &mut Criterion) {
    let options = OutlineOptions::default();
    let mut group = c.benchmark_group("outline_skeleton");
    group.sample_size(50);
    for n in [500usize, 2000, 8000] {
        let points = starfish(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &points, |b, p| {
            b.iter(|| {
                let outline = Outline::new(p.clone(), &options).unwrap();
                outline_skeleton(&outline, &options).unwrap()
            })
        });
    }
    group.finish();

    let mut group = c.benchmark_group("outline_inflate");
    group.sample_size(10);
    let outline = Outline::new(starfish(2000), &options).unwrap();
    group.bench_function("2000", |b| {
        b.iter(|| inflate(&outline, &options.inflate).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench_outline);
criterion_main!(benches);

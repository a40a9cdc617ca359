//! Criterion benches of convex hulls (issue 13): `hull_pile`, 1,000 random hulls of 12–24
//! points (`scenes::hull_pile`) falling into a 20 m × 20 m box container, single thread,
//! dt = 1/60, sleep on; each iteration runs the first STEPS steps (the fall, the landing and
//! the settling), so the reported time divided by STEPS is the mean ms per step (criterion
//! also prints it as a throughput of steps/s). `hull_build_*` time quickhull alone on random
//! clouds of 24 and 1,000 points.
//!
//! `cargo bench --bench hull_pile` runs all; `cargo bench --bench hull_pile -- hull_pile` one.

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use hearth::collision::hull::builder::{build, HullSettings};
use hearth::math::Vec3;
use hearth::World;

const STEPS: u64 = 300;
const DT: f32 = 1.0 / 60.0;
const HULLS: usize = 1000;

fn scene() -> World {
    let mut w = scenes::world(true);
    scenes::hull_pile(&mut w, HULLS, 1);
    w
}

fn bench_pile(c: &mut Criterion) {
    let mut group = c.benchmark_group("hull");
    group.sample_size(10);
    group.throughput(Throughput::Elements(STEPS));
    group.bench_function("hull_pile", |b| {
        b.iter_batched(
            scene,
            |mut w| {
                for _ in 0..STEPS {
                    w.step(DT).unwrap();
                }
                w
            },
            BatchSize::PerIteration,
        )
    });
    group.finish();
}

fn bench_build(c: &mut Criterion) {
    let mut group = c.benchmark_group("hull");
    for n in [24usize, 1000] {
        let mut rng = scenes::Rng(7);
        let cloud: Vec<Vec3> = scenes::random_cloud(&mut rng, n, Vec3::new(0.5, 0.4, 0.3));
        group.bench_function(format!("hull_build_{n}"), |b| {
            b.iter(|| build(&cloud, &HullSettings::default()).unwrap())
        });
    }
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_pile(c);
    bench_build(c);
}

criterion_group!(group, benches);
criterion_main!(group);

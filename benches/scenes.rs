//! Criterion benches of the standard scenes (issue 3): single-threaded, dt = 1/60, 600
//! steps per iteration; the reported time divided by 600 is ms per step (criterion also
//! prints it as a throughput of steps/s). Scenes come from `hearth::scenes`.
//!
//! `cargo bench --bench scenes` runs all; `cargo bench --bench scenes -- pyramid` one.
//!
//! The `threads` group steps `pile`, `pyramid_large` and `spheres_grid` at 1, 2 and 4 workers
//! (the world's own threads, `WorldSettings::worker_count`): `cargo bench --bench scenes --
//! threads`. Results are bit for bit the same at every count (tests/threads.rs).

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion, Throughput};
use hearth::{World, WorldSettings};

const STEPS: u64 = 600;
const DT: f32 = 1.0 / 60.0;

fn bench_scene(c: &mut Criterion, name: &str, sleep: bool, build: fn(&mut World)) {
    let mut group = c.benchmark_group("scenes");
    group.sample_size(10);
    group.throughput(Throughput::Elements(STEPS));
    let id = if sleep {
        name.to_string()
    } else {
        format!("{name}_sleep_off")
    };
    group.bench_function(id, |b| {
        b.iter_batched(
            || {
                let mut w = scenes::world(sleep);
                build(&mut w);
                w
            },
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

fn bench_workers(c: &mut Criterion, name: &str, sleep: bool, build: fn(&mut World)) {
    let mut group = c.benchmark_group("threads");
    group.sample_size(10);
    group.throughput(Throughput::Elements(STEPS));
    for workers in [1u32, 2, 4] {
        group.bench_with_input(BenchmarkId::new(name, workers), &workers, |b, &workers| {
            b.iter_batched(
                || {
                    let mut w = World::new(WorldSettings {
                        enable_sleep: sleep,
                        worker_count: workers,
                        ..WorldSettings::default()
                    })
                    .unwrap();
                    build(&mut w);
                    w
                },
                |mut w| {
                    for _ in 0..STEPS {
                        w.step(DT).unwrap();
                    }
                    w
                },
                BatchSize::PerIteration,
            )
        });
    }
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_scene(c, "pyramid", false, |w| {
        scenes::pyramid(w, 10);
    });
    bench_scene(c, "pyramid", true, |w| {
        scenes::pyramid(w, 10);
    });
    bench_scene(c, "pyramid_large", false, |w| {
        scenes::pyramid(w, 20);
    });
    bench_scene(c, "pile", true, |w| {
        scenes::pile(w, 4000);
    });
    // Issue 14: the pile with every event kind on (contact begin/end, hit, sensor events on
    // every shape, move events on every body) against none; at most 5 % apart.
    bench_scene(c, "pile_no_events", true, |w| {
        scenes::pile(w, 4000);
        scenes::set_events(w, false);
    });
    bench_scene(c, "pile_all_events", true, |w| {
        scenes::pile(w, 4000);
        scenes::set_events(w, true);
    });
    bench_scene(c, "spheres_grid", false, |w| {
        scenes::spheres_grid(w, 100);
    });
    bench_scene(c, "spheres_grid", true, |w| {
        scenes::spheres_grid(w, 100);
    });
    bench_workers(c, "pile", true, |w| {
        scenes::pile(w, 4000);
    });
    bench_workers(c, "pyramid_large", false, |w| {
        scenes::pyramid(w, 20);
    });
    bench_workers(c, "spheres_grid", false, |w| {
        scenes::spheres_grid(w, 100);
    });
}

criterion_group!(scene_benches, benches);
criterion_main!(scene_benches);

//! Criterion benches of snapshots (issue 15) on the `pile` scene (4,000 bodies,
//! `scenes::pile`): mid-fall (step 60) `save_restore`, and after 600 steps (10 s: settled,
//! mostly asleep) `size` (a save into a scratch buffer: the compressed size depends on every
//! byte), `save` (into a reused buffer), `restore` (into the same world) and `save_restore`
//! (both, the cost of one rollback besides the re-simulated steps).
//!
//! `cargo bench --bench snapshot`.

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use criterion::{criterion_group, criterion_main, Criterion};
use hearth::World;

const SETTLE: usize = 600;
const DT: f32 = 1.0 / 60.0;

/// The pile after `steps` steps.
fn scene(steps: usize) -> World {
    let mut w = scenes::world(true);
    scenes::pile(&mut w, 4000);
    for _ in 0..steps {
        w.step(DT).unwrap();
    }
    w
}

/// Mid-fall (step 60: every body awake, contacts changing).
const FALLING: usize = 60;

fn bench_snapshot(c: &mut Criterion) {
    let mut falling = scene(FALLING);
    let mut buf = Vec::new();
    falling.save_snapshot(&mut buf);
    println!(
        "pile snapshot mid-fall: {} bytes, {:.1} bytes per body",
        buf.len(),
        buf.len() as f64 / 4000.0
    );
    let mut group = c.benchmark_group("snapshot_pile_falling");
    group.sample_size(20);
    group.bench_function("save_restore", |b| {
        b.iter(|| {
            falling.save_snapshot(&mut buf);
            falling.restore_snapshot(&buf).unwrap();
        })
    });
    group.finish();
    let mut w = scene(SETTLE);
    w.save_snapshot(&mut buf);
    println!(
        "pile snapshot settled: {} bytes for 4000 bodies, {:.1} bytes per body, {} contacts",
        buf.len(),
        buf.len() as f64 / 4000.0,
        w.contact_count()
    );
    let mut group = c.benchmark_group("snapshot_pile");
    group.sample_size(20);
    group.bench_function("size", |b| b.iter(|| w.snapshot_size()));
    group.bench_function("save", |b| b.iter(|| w.save_snapshot(&mut buf)));
    let snap = buf.clone();
    group.bench_function("restore", |b| b.iter(|| w.restore_snapshot(&snap).unwrap()));
    group.bench_function("save_restore", |b| {
        b.iter(|| {
            w.save_snapshot(&mut buf);
            w.restore_snapshot(&buf).unwrap();
        })
    });
    group.finish();
}

criterion_group!(benches, bench_snapshot);
criterion_main!(benches);

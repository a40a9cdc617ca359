//! Criterion bench of soft bodies (issue 6), single-threaded at dt = 1/60, sleep off:
//!
//! * `ball_642`: the pressurised icosphere of the tests (642 vertices, 1,920 stretch and
//!   1,920 bending springs, radius 0.5 m, 5 kg, nRT = 500 J, default settings: 20 sub-steps
//!   of 2 stretch passes) resting on a ground plane after a 1.5 m drop.
//! * `cloth_64x64`: a 64×64-cell cloth (4,225 vertices, 2 × 2 m, 1 kg, default settings:
//!   inextensible edges, 20 sub-steps of 2 stretch passes, tethers to the two pins) pinned
//!   at two corners, hanging: the test `a_64x64_cloth_pinned_at_two_corners_hangs_without_
//!   stretching` measures it within 0.4 % of its rest lengths.
//!
//! Each iteration steps a warmed-up scene STEPS times; the reported time divided by STEPS
//! is ms per step (criterion also prints it as a throughput of steps/s).
//!
//! `cargo bench --bench soft`; `cargo bench --bench soft -- cloth` for one.

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use hearth::math::{Quat, Transform, Vec3};
use hearth::soft::{mesh, SoftBodyDef};
use hearth::World;

const STEPS: u64 = 60;
const WARM_UP: usize = 120;
const DT: f32 = 1.0 / 60.0;

fn ball() -> World {
    let mut w = scenes::world(false);
    scenes::ground_plane(&mut w);
    let def = SoftBodyDef {
        transform: Transform::new(Vec3::new(0.0, 1.5, 0.0), Quat::IDENTITY),
        mass: 5.0,
        pressure: 500.0,
        ..Default::default()
    };
    w.create_soft_body(&def, &mesh::icosphere(0.5, 3), None).unwrap();
    for _ in 0..WARM_UP {
        w.step(DT).unwrap();
    }
    w
}

fn cloth() -> World {
    let mut w = scenes::world(false);
    scenes::ground_plane(&mut w);
    let n = 64;
    let def = SoftBodyDef {
        transform: Transform::new(Vec3::new(0.0, 3.0, 0.0), Quat::IDENTITY),
        mass: 1.0,
        ..Default::default()
    };
    let h = w.create_soft_body(&def, &mesh::cloth(2.0, 2.0, n, n), None).unwrap();
    w.pin_soft_vertex(h, 0, None).unwrap();
    w.pin_soft_vertex(h, n, None).unwrap();
    for _ in 0..WARM_UP {
        w.step(DT).unwrap();
    }
    w
}

fn benches(c: &mut Criterion) {
    let mut group = c.benchmark_group("soft");
    group.sample_size(10);
    group.throughput(Throughput::Elements(STEPS));
    for (name, scene) in [("ball_642", ball as fn() -> World), ("cloth_64x64", cloth)] {
        group.bench_function(name, |b| {
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
    }
    group.finish();
}

criterion_group!(soft_benches, benches);
criterion_main!(soft_benches);

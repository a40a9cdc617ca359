//! Criterion bench of joints: Box3D's joint_grid scene, a 100×100 grid of spheres each joined
//! to its left and upper neighbour by a ball joint (19,794 joints), the middle of the top row
//! static, sleep off, dt = 1/60. Each iteration steps a warmed-up grid STEPS times; the
//! reported time divided by STEPS is ms per step (also printed as steps/s throughput).
//!
//! `ragdolls`: 100 of the 11-body ragdolls of `tests/scenes` (`scenes::ragdoll`: ball joints
//! with cone and twist limits, limited hinges) standing 2 m apart in a 10 × 10 grid on a
//! plane, each part given the spin of `tests/joints.rs`'s ragdoll test so they fall in
//! heaps, sleep on; each iteration steps a new scene through its first 120 steps (the fall
//! and the landing).
//!
//! `cargo bench --bench joints`.

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use hearth::joints::BallParams;
use hearth::math::{Quat, Transform, Vec3};
use hearth::{BodyDef, BodyType, Geometry, JointDef, JointKind, ShapeDef, World, WorldSettings};

const STEPS: u64 = 60;
const DT: f32 = 1.0 / 60.0;

/// The joint grid: `n`×`n` spheres of radius 0.4 one metre apart; the seven in the middle of
/// the top row are static.
pub fn joint_grid(n: usize) -> World {
    let mut w = World::new(WorldSettings {
        enable_sleep: false,
        ..Default::default()
    })
    .unwrap();
    let shape = ShapeDef {
        density: 1000.0,
        ..Default::default()
    };
    let mut ids = Vec::with_capacity(n * n);
    for k in 0..n {
        for i in 0..n {
            let fixed = i == 0 && k + 3 >= n / 2 && k <= n / 2 + 3;
            let b = w
                .create_body(&BodyDef {
                    body_type: if fixed { BodyType::Static } else { BodyType::Dynamic },
                    transform: Transform::new(Vec3::new(k as f32, -(i as f32), 0.0), Quat::IDENTITY),
                    ..Default::default()
                })
                .unwrap();
            w.create_shape(
                b,
                &shape,
                &Geometry::Sphere {
                    center: Vec3::ZERO,
                    radius: 0.4,
                },
            )
            .unwrap();
            let mut join = |other, offset: Vec3| {
                if fixed && w.body(other).unwrap().is_static() {
                    return; // two static bodies need no joint
                }
                let mut def = JointDef::new(JointKind::Ball(BallParams::default()));
                def.body_a = b;
                def.body_b = other;
                def.frame_a.p = offset;
                def.frame_b.p = -offset;
                w.create_joint(&def).unwrap();
            };
            if i > 0 {
                join(ids[k * n + i - 1], Vec3::new(0.0, 0.5, 0.0));
            }
            if k > 0 {
                join(ids[(k - 1) * n + i], Vec3::new(-0.5, 0.0, 0.0));
            }
            ids.push(b);
        }
    }
    w
}

/// Steps of the ragdoll scene per iteration.
const RAGDOLL_STEPS: u64 = 120;

/// The ragdoll scene (see the module doc).
fn ragdolls() -> World {
    let mut w = scenes::world(true);
    scenes::ground_plane(&mut w);
    for i in 0..10 {
        for k in 0..10 {
            for b in scenes::ragdoll(&mut w, Vec3::new(2.0 * i as f32, 2.0, 2.0 * k as f32)) {
                w.set_angular_velocity(b, Vec3::new(0.5, 0.0, 2.0)).unwrap();
            }
        }
    }
    w
}

fn benches(c: &mut Criterion) {
    let mut group = c.benchmark_group("joints");
    group.sample_size(10);
    group.throughput(Throughput::Elements(STEPS));
    group.bench_function("joint_grid_100_sleep_off", |b| {
        b.iter_batched(
            || {
                let mut w = joint_grid(100);
                for _ in 0..10 {
                    w.step(DT).unwrap();
                }
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
    group.throughput(Throughput::Elements(RAGDOLL_STEPS));
    group.bench_function("ragdolls_100", |b| {
        b.iter_batched(
            ragdolls,
            |mut w| {
                for _ in 0..RAGDOLL_STEPS {
                    w.step(DT).unwrap();
                }
                w
            },
            BatchSize::PerIteration,
        )
    });
    group.finish();
}

criterion_group!(joint_benches, benches);
criterion_main!(joint_benches);

//! Criterion bench of the particle world (issue 4): 100,000 particles with world gravity, a
//! drag generator attached to all of them and a ground plane, single-threaded at dt = 1/60.
//! Each iteration steps 60 times after a warm-up in which the particles (dropped from at
//! most 1 m) have landed; the reported time divided by 60 is ms per step (criterion also
//! prints it as a throughput of steps/s).
//!
//! `cargo bench --bench particles`; `cargo bench --bench particles -- sleep_off` for one.

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use hearth::generators::GeneratorDef;
use hearth::math::Vec3;
use hearth::particles::ParticleDef;
use hearth::World;

const PARTICLES: usize = 100_000;
const STEPS: u64 = 60;
const WARM_UP: usize = 60;
const DT: f32 = 1.0 / 60.0;

/// 100,000 particles on a 317 × 316 grid 0.2 m apart, at heights from 0.05 to 1 m, moving
/// sideways a little, with drag; a ground plane.
fn scene(sleep: bool) -> World {
    let mut w = scenes::world(sleep);
    scenes::ground_plane(&mut w);
    let drag = w.create_generator(&GeneratorDef::Drag { k1: 0.05, k2: 0.01 }).unwrap();
    let side = (PARTICLES as f32).sqrt().ceil() as usize;
    let mut ids = Vec::with_capacity(PARTICLES);
    for k in 0..PARTICLES {
        let (i, j) = (k % side, k / side);
        let h = 0.05 + 0.95 * ((k * 7919) % 1000) as f32 / 1000.0;
        let def = ParticleDef {
            position: Vec3::new(0.2 * i as f32, h, 0.2 * j as f32),
            velocity: Vec3::new(((k % 13) as f32 - 6.0) * 0.05, 0.0, ((k % 7) as f32 - 3.0) * 0.05),
            radius: 0.05,
            ..Default::default()
        };
        ids.push(w.create_particle(&def).unwrap());
    }
    w.attach_particles(drag, &ids).unwrap();
    for _ in 0..WARM_UP {
        w.step(DT).unwrap();
    }
    w
}

fn benches(c: &mut Criterion) {
    let mut group = c.benchmark_group("particles");
    group.sample_size(10);
    group.throughput(Throughput::Elements(STEPS));
    for (name, sleep) in [
        ("100k_gravity_drag_ground_sleep_off", false),
        ("100k_gravity_drag_ground", true),
    ] {
        group.bench_function(name, |b| {
            b.iter_batched(
                || scene(sleep),
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

criterion_group!(particle_benches, benches);
criterion_main!(particle_benches);

//! Criterion benches of the queries (issue 14) in the settled `pile` scene (4,000 spheres and
//! boxes in a 30 m × 30 m container, `scenes::pile`), stepped until every body sleeps (at
//! most 1,200 steps) before timing, single thread:
//!
//! * `rays_100k`: 100,000 closest-hit rays (`World::cast_ray_closest`), origins uniform in
//!   the container up to 25 m high, random directions, 40 m long;
//! * `sphere_overlaps_10k`: 10,000 sphere overlaps (`World::overlap_shape`), radius 0.5 to
//!   1.5 m, centres uniform in the lower 10 m of the container.
//!
//! Criterion reports the time per batch; divided by the batch size it is the time per query.
//! `cargo bench --bench queries`.

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use hearth::collision::filter::QueryFilter;
use hearth::math::{Quat, Transform, Vec3};
use hearth::{Geometry, World};

const BODIES: usize = 4000;
const RAYS: usize = 100_000;
const OVERLAPS: usize = 10_000;

fn settled_pile() -> World {
    let mut w = scenes::world(true);
    scenes::pile(&mut w, BODIES);
    for _ in 0..1200 {
        w.step(1.0 / 60.0).unwrap();
        if w.awake_body_count() == 0 {
            break;
        }
    }
    w
}

fn benches(c: &mut Criterion) {
    let w = settled_pile();
    let mut rng = scenes::Rng(42);
    let rays: Vec<(Vec3, Vec3)> = (0..RAYS)
        .map(|_| {
            let o = Vec3::new(rng.range(-14.0, 14.0), rng.range(0.5, 25.0), rng.range(-14.0, 14.0));
            let d = rng.vec(1.0).normalize_or(Vec3::NEG_Y) * 40.0;
            (o, d)
        })
        .collect();
    let spheres: Vec<(Geometry, Transform)> = (0..OVERLAPS)
        .map(|_| {
            let p = Vec3::new(rng.range(-14.0, 14.0), rng.range(0.0, 10.0), rng.range(-14.0, 14.0));
            let g = Geometry::Sphere {
                center: Vec3::ZERO,
                radius: rng.range(0.5, 1.5),
            };
            (g, Transform::new(p, Quat::IDENTITY))
        })
        .collect();
    let filter = QueryFilter::DEFAULT;
    let mut group = c.benchmark_group("queries");
    group.sample_size(10);
    group.throughput(Throughput::Elements(RAYS as u64));
    group.bench_function("rays_100k", |b| {
        b.iter(|| {
            let mut hits = 0usize;
            for (o, d) in &rays {
                hits += w.cast_ray_closest(*o, *d, &filter).unwrap().is_some() as usize;
            }
            hits
        })
    });
    group.throughput(Throughput::Elements(OVERLAPS as u64));
    group.bench_function("sphere_overlaps_10k", |b| {
        b.iter(|| {
            let mut found = 0usize;
            for (g, xf) in &spheres {
                w.overlap_shape(g, xf, &filter, |_| {
                    found += 1;
                    true
                })
                .unwrap();
            }
            found
        })
    });
    group.finish();
}

criterion_group!(queries, benches);
criterion_main!(queries);

//! Criterion benches of level geometry (issue 13): 1,000 mixed bodies — spheres, boxes,
//! capsules and convex hulls in turn — dropped from 8 m onto hilly terrain of 256 × 256
//! one-metre cells, as a triangle mesh (131,072 triangles, `terrain_mesh`) and as a
//! heightfield (257 × 257 samples, `terrain_heightfield`). Single thread, dt = 1/60, sleep
//! on; each iteration runs the first STEPS steps (the fall, the landing and the settling),
//! so the reported time divided by STEPS is the mean ms per step (criterion also prints it
//! as a throughput of steps/s). `terrain_*_build` time building the geometry alone.
//!
//! `cargo bench --bench terrain` runs all; `cargo bench --bench terrain -- terrain_mesh` one.

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use hearth::World;

const STEPS: u64 = 300;
const DT: f32 = 1.0 / 60.0;
const CELLS: u32 = 256;
const BODIES: usize = 1000;

fn scene(heightfield: bool) -> World {
    let mut w = scenes::world(true);
    if heightfield {
        scenes::terrain_heightfield(&mut w, CELLS, false, 1);
    } else {
        scenes::terrain_mesh(&mut w, CELLS, false, 1);
    }
    scenes::terrain_drop(&mut w, BODIES, 8.0, 1);
    w
}

fn bench_terrain(c: &mut Criterion, name: &str, heightfield: bool) {
    let mut group = c.benchmark_group("terrain");
    group.sample_size(10);
    group.throughput(Throughput::Elements(STEPS));
    group.bench_function(name, |b| {
        b.iter_batched(
            || scene(heightfield),
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
    let mut group = c.benchmark_group("terrain");
    group.sample_size(10);
    let n = CELLS + 1;
    let heights = scenes::terrain_heights(CELLS, 1);
    let (v, t) = scenes::grid_mesh(CELLS, 1.0, &heights);
    group.bench_function("terrain_mesh_build", |b| {
        b.iter(|| hearth::collision::mesh::TriangleMesh::new(&v, &t).unwrap())
    });
    group.bench_function("terrain_heightfield_build", |b| {
        b.iter(|| hearth::collision::heightfield::Heightfield::new(n, n, &heights, None).unwrap())
    });
    let mesh = hearth::collision::mesh::TriangleMesh::new(&v, &t).unwrap();
    let hf = hearth::collision::heightfield::Heightfield::new(n, n, &heights, None).unwrap();
    eprintln!(
        "terrain memory: mesh {} bytes ({} triangles), heightfield {} bytes",
        mesh.memory_bytes(),
        mesh.triangle_count(),
        hf.memory_bytes()
    );
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_terrain(c, "terrain_mesh", false);
    bench_terrain(c, "terrain_heightfield", true);
    bench_build(c);
}

criterion_group!(terrain, benches);
criterion_main!(terrain);

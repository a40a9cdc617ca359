//! Criterion benches of the queries (issue 14) in the settled `pile` scene (4,000 spheres and
//! boxes in a 30 m × 30 m container, `scenes::pile`), stepped until every body sleeps (at
//! most 1,200 steps) before timing, single thread:
//!
//! * `rays_100k`: 100,000 closest-hit rays (`World::cast_ray_closest`, which the C batch
//!   call `hearth_world_cast_rays` runs per ray), origins uniform in the container up to
//!   25 m high, random directions, 40 m long;
//! * `sphere_overlaps_10k`: 10,000 sphere overlaps (`World::overlap_shape`), radius 0.5 to
//!   1.5 m, centres uniform in the lower 10 m of the container;
//! * `aabb_overlaps_10k`: 10,000 box overlaps (`World::overlap_aabb`), the spheres' bounds;
//! * `rebuilt/*`: the same three after `World::rebuild_broadphase` (the tree rebuilt with a
//!   binned SAH, as a host does after loading a level).
//!
//! Criterion reports the time per batch; divided by the batch size it is the time per query.
//! `cargo bench --bench queries`.
//!
//! Instruction counts (repeatable on a loaded machine): `HEARTH_QUERY_PROFILE=<kind>` runs
//! the batch of one kind (`rays`, `spheres` or `aabbs`) once, prints a checksum and
//! exits (`stats` prints the tree boxes a closest ray tests on average), without criterion
//! (with `HEARTH_QUERY_REBUILD=1`, after rebuilding the tree); `HEARTH_QUERY_SNAPSHOT=<file>` keeps the settled pile in a
//! snapshot file (written when missing), so a run under
//! `valgrind --tool=callgrind` does not settle the pile under emulation. Run once with the
//! kind `none` to only count the setup, and subtract. The kind `digest` prints a hash of
//! every answer (each ray's hit shape, body, point, normal and fraction bits; each overlap's
//! sorted shape ids), to check that a change to the queries keeps them bit for bit.

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use criterion::{criterion_group, Criterion, Throughput};
use hearth::collision::aabb::Aabb;
use hearth::collision::filter::QueryFilter;
use hearth::math::{Quat, Transform, Vec3};
use hearth::{Geometry, World};

const BODIES: usize = 4000;
const RAYS: usize = 100_000;
const OVERLAPS: usize = 10_000;

fn settle() -> World {
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

fn settled_pile() -> World {
    let Ok(path) = std::env::var("HEARTH_QUERY_SNAPSHOT") else {
        return settle();
    };
    if let Ok(bytes) = std::fs::read(&path) {
        let mut w = scenes::world(true);
        w.restore_snapshot(&bytes).expect("snapshot of the settled pile");
        return w;
    }
    let w = settle();
    let mut bytes = Vec::new();
    w.save_snapshot(&mut bytes);
    std::fs::write(&path, &bytes).expect("writable snapshot path");
    w
}

struct Inputs {
    rays: Vec<(Vec3, Vec3)>,
    spheres: Vec<(Geometry, Transform)>,
    boxes: Vec<Aabb>,
}

fn inputs() -> Inputs {
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
    let boxes = spheres
        .iter()
        .map(|(g, xf)| {
            let Geometry::Sphere { radius, .. } = *g else {
                unreachable!()
            };
            Aabb::new(xf.p - Vec3::splat(radius), xf.p + Vec3::splat(radius))
        })
        .collect();
    Inputs { rays, spheres, boxes }
}

fn rays(w: &World, q: &Inputs) -> usize {
    let filter = QueryFilter::DEFAULT;
    let mut hits = 0usize;
    for (o, d) in &q.rays {
        hits += w.cast_ray_closest(*o, *d, &filter).unwrap().is_some() as usize;
    }
    hits
}

fn sphere_overlaps(w: &World, q: &Inputs) -> usize {
    let filter = QueryFilter::DEFAULT;
    let mut found = 0usize;
    for (g, xf) in &q.spheres {
        w.overlap_shape(g, xf, &filter, |_| {
            found += 1;
            true
        })
        .unwrap();
    }
    found
}

fn aabb_overlaps(w: &World, q: &Inputs) -> usize {
    let filter = QueryFilter::DEFAULT;
    let mut found = 0usize;
    for bb in &q.boxes {
        w.overlap_aabb(bb, &filter, |_| {
            found += 1;
            true
        })
        .unwrap();
    }
    found
}

fn benches(c: &mut Criterion) {
    let mut w = settled_pile();
    let q = inputs();
    for prefix in ["", "rebuilt/"] {
        if !prefix.is_empty() {
            w.rebuild_broadphase();
        }
        let mut group = c.benchmark_group("queries");
        group.sample_size(10);
        group.throughput(Throughput::Elements(RAYS as u64));
        group.bench_function(format!("{prefix}rays_100k"), |b| b.iter(|| rays(&w, &q)));
        group.throughput(Throughput::Elements(OVERLAPS as u64));
        group.bench_function(format!("{prefix}sphere_overlaps_10k"), |b| {
            b.iter(|| sphere_overlaps(&w, &q))
        });
        group.bench_function(format!("{prefix}aabb_overlaps_10k"), |b| {
            b.iter(|| aabb_overlaps(&w, &q))
        });
        group.finish();
    }
}

/// FNV-1a over 32-bit words.
struct Fnv(u64);

impl Fnv {
    fn word(&mut self, x: u32) {
        for b in x.to_le_bytes() {
            self.0 = (self.0 ^ b as u64).wrapping_mul(0x100_0000_01b3);
        }
    }
    fn vec(&mut self, v: Vec3) {
        for c in v.to_array() {
            self.word(c.to_bits());
        }
    }
}

/// Prints a hash of every ray hit (bits) and every overlap's sorted id list, per kind.
fn digest(w: &World, q: &Inputs) {
    let filter = QueryFilter::DEFAULT;
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    for (o, d) in &q.rays {
        match w.cast_ray_closest(*o, *d, &filter).unwrap() {
            Some(hit) => {
                h.word(hit.shape.index);
                h.word(hit.shape.generation);
                h.word(hit.body.index);
                h.vec(hit.point);
                h.vec(hit.normal);
                h.word(hit.fraction.to_bits());
            }
            None => h.word(u32::MAX),
        }
    }
    println!("rays digest {:016x}", h.0);
    let mut ids = Vec::new();
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    for (g, xf) in &q.spheres {
        ids.clear();
        w.overlap_shape(g, xf, &filter, |s| {
            ids.push((s.index, s.generation));
            true
        })
        .unwrap();
        ids.sort_unstable();
        h.word(ids.len() as u32);
        ids.iter().for_each(|&(i, g)| {
            h.word(i);
            h.word(g)
        });
    }
    println!("spheres digest {:016x}", h.0);
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    for bb in &q.boxes {
        ids.clear();
        w.overlap_aabb(bb, &filter, |s| {
            ids.push((s.index, s.generation));
            true
        })
        .unwrap();
        ids.sort_unstable();
        h.word(ids.len() as u32);
        ids.iter().for_each(|&(i, g)| {
            h.word(i);
            h.word(g)
        });
    }
    println!("aabbs digest {:016x}", h.0);
}

criterion_group!(queries, benches);

fn main() {
    if let Ok(kind) = std::env::var("HEARTH_QUERY_PROFILE") {
        let mut w = settled_pile();
        if std::env::var_os("HEARTH_QUERY_REBUILD").is_some() {
            w.rebuild_broadphase();
        }
        let q = inputs();
        let n = match kind.as_str() {
            "rays" => rays(&w, &q),
            "spheres" => sphere_overlaps(&w, &q),
            "aabbs" => aabb_overlaps(&w, &q),
            "none" => 0,
            "digest" => {
                digest(&w, &q);
                0
            }
            "stats" => {
                let f = QueryFilter::DEFAULT;
                let tested: u64 = q
                    .rays
                    .iter()
                    .map(|(o, d)| w.cast_ray_closest_counted(*o, *d, &f).unwrap().1 as u64)
                    .sum();
                println!(
                    "tree height {}, boxes tested per closest ray {:.2}",
                    w.tree_height(),
                    tested as f64 / RAYS as f64
                );
                0
            }
            other => panic!("HEARTH_QUERY_PROFILE: unknown kind {other}"),
        };
        println!("{kind}: {n}");
        return;
    }
    queries();
    criterion::Criterion::default().configure_from_args().final_summary();
}

//! Sleep on terrain: bodies dropped on triangle meshes and heightfields come to rest and
//! sleep, and a body at rest on one sleeps when the same body on a plane does.
//!
//! The cause these guard (`collision/narrow_phase/mesh.rs`, `reduce_in_place`): a shape's
//! contacts with triangles less than 5° apart share one manifold, reduced to four points. On
//! curved terrain a box face touches a ridge line or a few triangle vertices and hangs
//! millimetres to centimetres above the rest; choosing the four by area alone kept corners in
//! the air and dropped real supports, and the body rocked on what was left, awake for ever.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;

use hearth::math::{Quat, Transform, Vec3};
use hearth::world::World;
use hearth::{BodyDef, BodyHandle, Geometry, ShapeDef};

const DT: f32 = 1.0 / 60.0;

fn awake(w: &World, bodies: &[BodyHandle]) -> Vec<usize> {
    (0..bodies.len()).filter(|&k| w.is_awake(bodies[k]).unwrap()).collect()
}

/// 200 mixed bodies (spheres, boxes, capsules, hulls in turn) dropped from 8 m on hilly
/// terrain of 64 × 64 one-metre cells, two seeds, as a mesh and as a heightfield. Measured
/// (default rolling resistance 0.05, sleep threshold 0.05 m/s, 0.5 s): all asleep by step
/// 1,201 / 1,186 (seed 1), step 2,836 (heightfield, seed 0: a ball rolling into a hollow);
/// seed 0 on the mesh keeps one hull awake, twitching on a crease (1 mm in 2 s) — the
/// stated exception. Before the fix (area-only reduction) 12 of the 200 were still awake
/// at step 1,500 on the mesh, seed 0, boxes and hulls rocking in place.
#[test]
fn mixed_drop_on_mesh_and_heightfield_ends_asleep() {
    for heightfield in [false, true] {
        for seed in 0..2u32 {
            let mut w = scenes::world(true);
            if heightfield {
                scenes::terrain_heightfield(&mut w, 64, false, seed);
            } else {
                scenes::terrain_mesh(&mut w, 64, false, seed);
            }
            let bodies = scenes::terrain_drop(&mut w, 200, 8.0, seed);
            for _ in 0..1500 {
                w.step(DT).unwrap();
            }
            let left = awake(&w, &bodies);
            assert!(
                left.len() <= 1,
                "hf {heightfield} seed {seed}: awake at step 1500: {left:?}"
            );
            for &k in &left {
                // The exception: a box or hull twitching in place, not a ball or capsule
                // rolling (these come to rest in the hollows of the bowl).
                assert!(k % 4 == 1 || k % 4 == 3, "hf {heightfield} seed {seed}: body {k} awake");
                let p0 = w.transform(bodies[k]).unwrap().p;
                for _ in 0..120 {
                    w.step(DT).unwrap();
                }
                let moved = (w.transform(bodies[k]).unwrap().p - p0).length();
                assert!(
                    moved < 0.005,
                    "hf {heightfield} seed {seed}: body {k} moved {moved} m in 2 s"
                );
            }
        }
    }
}

/// Ground kinds for the rest tests.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Ground {
    Plane,
    Mesh,
    Heightfield,
}

/// A static ground of 16 × 16 one-metre cells centred on the origin, heights `f(x)` at the
/// sample columns (the plane variant needs `f` linear).
fn ground(w: &mut World, kind: Ground, f: &dyn Fn(f32) -> f32) {
    let cells = 16u32;
    let n = cells + 1;
    let heights: Vec<f32> = (0..n * n).map(|i| f((i % n) as f32 - 0.5 * cells as f32)).collect();
    let g = w.create_body(&BodyDef::default()).unwrap();
    let def = ShapeDef::default();
    let geometry = match kind {
        Ground::Plane => {
            let slope = f(1.0) - f(0.0);
            Geometry::Plane {
                normal: Vec3::new(-slope, 1.0, 0.0).normalize(),
                offset: f(0.0) / Vec3::new(-slope, 1.0, 0.0).length(),
            }
        }
        Ground::Mesh => {
            let (v, t) = scenes::grid_mesh(cells, 1.0, &heights);
            Geometry::Mesh {
                mesh: w.create_mesh(&v, &t).unwrap(),
                local: Transform::IDENTITY,
                scale: Vec3::ONE,
            }
        }
        Ground::Heightfield => {
            let half = 0.5 * cells as f32;
            Geometry::Heightfield {
                heightfield: w.create_heightfield(n, n, &heights, None).unwrap(),
                local: Transform::new(Vec3::new(-half, 0.0, -half), Quat::IDENTITY),
                scale: Vec3::ONE,
            }
        }
    };
    w.create_shape(g, &def, &geometry).unwrap();
}

/// The four shape kinds with their half height when lying as placed.
fn shapes(w: &mut World) -> Vec<(Geometry, f32)> {
    let hull = w
        .create_convex_hull(
            &[
                Vec3::new(-0.3, -0.2, -0.25),
                Vec3::new(0.3, -0.2, -0.25),
                Vec3::new(0.3, -0.2, 0.25),
                Vec3::new(-0.3, -0.2, 0.25),
                Vec3::new(0.0, 0.25, 0.0),
            ],
            &Default::default(),
        )
        .unwrap();
    vec![
        (
            Geometry::Sphere {
                center: Vec3::ZERO,
                radius: 0.3,
            },
            0.3,
        ),
        (
            Geometry::Box {
                center: Vec3::ZERO,
                rotation: Quat::IDENTITY,
                half_extents: Vec3::new(0.4, 0.28, 0.34),
            },
            0.28,
        ),
        (
            Geometry::Capsule {
                a: Vec3::new(0.0, 0.0, -0.4),
                b: Vec3::new(0.0, 0.0, 0.4),
                radius: 0.2,
            },
            0.2,
        ),
        (
            Geometry::Hull {
                hull,
                local: Transform::IDENTITY,
                scale: 1.0,
            },
            0.2,
        ),
    ]
}

/// Step at which one body, placed 2 mm above the ground at `x` tilted with the surface
/// slope `angle` (radians), falls asleep (None within 20 s).
fn sleep_step(kind: Ground, shape: usize, x: f32, angle: f32, f: &dyn Fn(f32) -> f32) -> Option<usize> {
    let mut w = scenes::world(true);
    ground(&mut w, kind, f);
    let (g, up) = shapes(&mut w)[shape];
    let n = Vec3::new(-angle.sin(), angle.cos(), 0.0);
    // z = 0.3: inside a cell, off the diagonals.
    let p = Vec3::new(x, f(x), 0.3) + n * (up + 0.002);
    let b = scenes::dynamic_body(
        &mut w,
        Transform::new(p, Quat::from_rotation_z(angle)),
        &ShapeDef::default(),
        &g,
    );
    (1..=1200).find(|_| {
        w.step(DT).unwrap();
        !w.is_awake(b).unwrap()
    })
}

/// Each kind at rest on a flat mesh and heightfield, and on a slope of triangles (boxes and
/// hulls 10°, balls and capsules 2.5°), sleeps within 0.2 s (12 steps) of the same body on a
/// plane. Measured: the same
/// step (95, that is 1.58 s: the motion measure starts above the threshold, see
/// `dynamics/island.rs`).
#[test]
fn resting_on_triangles_sleeps_like_on_a_plane() {
    let flat = |_: f32| 0.0;
    for shape in 0..4 {
        let on_plane = sleep_step(Ground::Plane, shape, 0.0, 0.0, &flat).expect("plane: asleep");
        for kind in [Ground::Mesh, Ground::Heightfield] {
            let s = sleep_step(kind, shape, 0.0, 0.0, &flat).unwrap_or(usize::MAX);
            assert!(
                s.abs_diff(on_plane) <= 12,
                "{kind:?} shape {shape}: {s} vs plane {on_plane}"
            );
        }
        // Boxes and hulls on 10°; balls and capsules roll down that (the default rolling
        // resistance, 0.05, holds them on up to atan 0.05 = 2.9°): 2.5° for them, which
        // also checks that triangle contacts apply rolling resistance as a plane does.
        {
            let deg: f32 = if shape == 1 || shape == 3 { 10.0 } else { 2.5 };
            let slope = move |x: f32| x * deg.to_radians().tan();
            let a = deg.to_radians();
            let on_plane = sleep_step(Ground::Plane, shape, 0.0, a, &slope).expect("slope: asleep");
            for kind in [Ground::Mesh, Ground::Heightfield] {
                let s = sleep_step(kind, shape, 0.0, a, &slope).unwrap_or(usize::MAX);
                assert!(
                    s.abs_diff(on_plane) <= 12,
                    "{kind:?} slope shape {shape}: {s} vs {on_plane}"
                );
            }
        }
    }
}

/// A box across a ridge or on a hump of triangles (creases of 1° to 4°, under the 5° that
/// share one manifold) tips onto one side and sleeps. Measured: within 4.2 s (step 247); before
/// the fix it rocked on the ridge for ever (1° and 2°, centred and 0.3 m off).
#[test]
fn box_across_a_gentle_ridge_or_hump_sleeps() {
    for kind in [Ground::Mesh, Ground::Heightfield] {
        for deg in [1.0f32, 2.0, 4.0] {
            let t = deg.to_radians().tan();
            let ridge = move |x: f32| -x.abs() * t;
            let hump = move |x: f32| -0.5 * x * x * t;
            for x in [0.0, 0.3] {
                let tilt = if x == 0.0 { 0.0 } else { -deg.to_radians() };
                let s = sleep_step(kind, 1, x, tilt, &ridge);
                assert!(s.is_some_and(|s| s <= 300), "{kind:?} ridge {deg}° at {x}: {s:?}");
                let s = sleep_step(kind, 1, x, 0.0, &hump);
                assert!(s.is_some_and(|s| s <= 300), "{kind:?} hump {deg}° at {x}: {s:?}");
            }
        }
    }
}

/// Seeded random single bodies (kind, size 0.1–0.7 m, density 100–5,000 kg/m³, drop height
/// 0.3–3 m, any orientation) on the hilly terrain, as mesh and heightfield: finite state,
/// speed under the free-fall speed from the highest point (drop plus the terrain's relief,
/// under 12 m: 15.4 m/s; asserted 16), and a body that fell asleep is not woken again (it is
/// alone: nothing may wake it). Boxes and hulls sleep within 15 s; balls and capsules, which
/// roll down into a hollow and back and forth in it, within 30 s or are still rolling then
/// (faster than the sleep threshold, not twitching in place).
#[test]
fn random_bodies_on_sloped_terrain_rest_and_stay_asleep() {
    let mut rng = scenes::Rng(0x5EED_7E22);
    for trial in 0..48 {
        let heightfield = trial % 2 == 1;
        let mut w = scenes::world(true);
        if heightfield {
            scenes::terrain_heightfield(&mut w, 32, false, trial);
        } else {
            scenes::terrain_mesh(&mut w, 32, false, trial);
        }
        let kind = (trial / 2) % 4;
        let size = rng.range(0.1, 0.7);
        let hull = w
            .create_convex_hull(
                &[
                    Vec3::new(0.5, 0.0, 0.0),
                    Vec3::new(-0.5, 0.0, 0.1),
                    Vec3::new(0.0, 0.4, 0.0),
                    Vec3::new(0.0, -0.4, -0.1),
                    Vec3::new(0.1, 0.1, 0.5),
                    Vec3::new(-0.1, -0.1, -0.5),
                ],
                &Default::default(),
            )
            .unwrap();
        let g = match kind {
            0 => Geometry::Sphere {
                center: Vec3::ZERO,
                radius: size,
            },
            1 => Geometry::Box {
                center: Vec3::ZERO,
                rotation: Quat::IDENTITY,
                half_extents: Vec3::new(size, rng.range(0.3, 1.0) * size, rng.range(0.3, 1.0) * size),
            },
            2 => Geometry::Capsule {
                a: Vec3::new(-size, 0.0, 0.0),
                b: Vec3::new(size, 0.0, 0.0),
                radius: rng.range(0.2, 0.6) * size,
            },
            _ => Geometry::Hull {
                hull,
                local: Transform::IDENTITY,
                scale: 2.0 * size,
            },
        };
        let (x, z) = (rng.range(-10.0, 10.0), rng.range(-10.0, 10.0));
        let q = Quat::from_euler(
            glam::EulerRot::XYZ,
            rng.range(-3.2, 3.2),
            rng.range(-3.2, 3.2),
            rng.range(-3.2, 3.2),
        );
        let p = Vec3::new(x, 6.0 + rng.range(0.3, 3.0), z);
        let def = ShapeDef {
            density: rng.range(100.0, 5000.0),
            ..ShapeDef::default()
        };
        let b = scenes::dynamic_body(&mut w, Transform::new(p, q), &def, &g);
        let mut slept = None;
        for step in 0..1800 {
            w.step(DT).unwrap();
            let (xf, v, om) = (
                w.transform(b).unwrap(),
                w.linear_velocity(b).unwrap(),
                w.angular_velocity(b).unwrap(),
            );
            assert!(
                xf.p.is_finite() && xf.q.is_finite() && v.is_finite() && om.is_finite(),
                "trial {trial} step {step}"
            );
            assert!(v.length() < 16.0, "trial {trial} step {step}: speed {v}");
            assert!(xf.p.y > -8.0, "trial {trial}: fell through at {}", xf.p);
            let asleep = !w.is_awake(b).unwrap();
            if asleep && slept.is_none() {
                slept = Some(step);
            }
            assert!(
                slept.is_none() || asleep,
                "trial {trial}: asleep at {slept:?}, awake again at {step}"
            );
        }
        let v = w.linear_velocity(b).unwrap().length();
        if kind == 1 || kind == 3 {
            assert!(
                slept.is_some_and(|s| s < 900),
                "trial {trial} kind {kind}: asleep at {slept:?}"
            );
        } else {
            assert!(
                slept.is_some() || v > 0.05,
                "trial {trial} kind {kind}: awake after 30 s, still ({v} m/s)"
            );
        }
    }
}

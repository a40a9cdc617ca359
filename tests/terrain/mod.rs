//! What the mesh and heightfield tests share: a world, materials, bodies, energy, and seeded
//! drops on random terrain.

use super::scenes;
use hearth::math::{Quat, Transform, Vec3};
use hearth::world::{World, WorldSettings};
use hearth::{BodyDef, BodyHandle, BodyType, Geometry, ShapeDef};

const DT: f32 = 1.0 / 60.0;

/// Kinetic plus potential energy of the bodies.
pub fn energy(w: &World, bodies: &[BodyHandle]) -> f32 {
    bodies
        .iter()
        .map(|&b| {
            let body = w.body(b).unwrap();
            let m = body.mass;
            let v = w.linear_velocity(b).unwrap();
            let om = w.angular_velocity(b).unwrap();
            let rot = hearth::math::Mat3::from_quat(body.xf.q);
            let i_world = rot * body.inertia_local * rot.transpose();
            0.5 * m * v.length_squared() + 0.5 * om.dot(i_world * om) + m * 9.81 * body.center.y
        })
        .sum()
}

/// Seeded drops of mixed bodies on random hills: finite, bounded, no energy growth, rest.
/// Balls and capsules roll down slopes steeper than their rolling resistance holds (the
/// default 0.05 holds them up to atan 0.05 = 2.9°; these hills are steeper), even with the
/// damping the bodies get here (linear 0.05, angular 0.5 per second): the boxes and hulls
/// must come to rest, the rolling ones stay slow (terminal speed on these slopes is under
/// 1.5 m/s).
pub fn random_drops(heightfield: bool) {
    for seed in 0..3u32 {
        let mut w = World::new(WorldSettings::default()).unwrap();
        if heightfield {
            scenes::terrain_heightfield(&mut w, 48, false, seed);
        } else {
            scenes::terrain_mesh(&mut w, 48, false, seed);
        }
        let bodies = scenes::terrain_drop(&mut w, 36, 5.0, seed);
        for &b in &bodies {
            w.set_damping(b, 0.05, 0.5).unwrap();
        }
        let e0 = energy(&w, &bodies);
        let mut e_max = e0;
        for step in 0..900 {
            w.step(DT).unwrap();
            let e = energy(&w, &bodies);
            e_max = e_max.max(e);
            for &b in &bodies {
                let p = w.transform(b).unwrap().p;
                let v = w.linear_velocity(b).unwrap();
                assert!(p.is_finite() && v.is_finite(), "seed {seed} step {step}");
                assert!(v.length() < 30.0, "seed {seed} step {step}: {v}");
                assert!(
                    p.x.abs() < 23.0 && p.z.abs() < 23.0,
                    "seed {seed}: left the terrain at {p}"
                );
                assert!(p.y > -4.0, "seed {seed}: fell through at {p}");
            }
        }
        assert!(
            e_max <= e0 + 1.0e-3 * e0.abs().max(1.0),
            "seed {seed}: energy grew {e0} -> {e_max}"
        );
        for (k, &b) in bodies.iter().enumerate() {
            let v = w.linear_velocity(b).unwrap().length();
            // terrain_drop makes spheres, boxes, capsules and hulls in turn.
            let rolls = k % 4 == 0 || k % 4 == 2;
            let limit = if rolls { 1.5 } else { 0.05 };
            assert!(v < limit, "seed {seed}: body {k} (kind {}) still at {v} m/s", k % 4);
        }
    }
}

pub fn world() -> World {
    World::new(WorldSettings {
        enable_sleep: false,
        ..WorldSettings::default()
    })
    .unwrap()
}

pub fn material(friction: f32) -> ShapeDef {
    ShapeDef {
        static_friction: friction,
        dynamic_friction: friction,
        ..ShapeDef::default()
    }
}

pub fn body(w: &mut World, p: Vec3, q: Quat, g: Geometry, friction: f32) -> BodyHandle {
    let b = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(p, q),
            ..Default::default()
        })
        .unwrap();
    w.create_shape(b, &material(friction), &g).unwrap();
    b
}

pub fn cube(h: f32) -> Geometry {
    Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::splat(h),
    }
}

pub fn ball(r: f32) -> Geometry {
    Geometry::Sphere {
        center: Vec3::ZERO,
        radius: r,
    }
}

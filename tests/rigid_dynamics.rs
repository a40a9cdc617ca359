//! Rigid-body physics against analytic answers: free fall, bounce heights from restitution,
//! friction thresholds and sliding distances, conservation laws, gyroscopic motion.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use hearth::math::{Quat, Transform, Vec3};
use hearth::{BodyDef, BodyType, Geometry, Integrator, ShapeDef, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;

fn run(world: &mut World, seconds: f32) {
    for _ in 0..(seconds / DT).round() as usize {
        world.step(DT).unwrap();
    }
}

fn body_at(world: &mut World, t: BodyType, p: Vec3, q: Quat) -> hearth::BodyHandle {
    world
        .create_body(&BodyDef {
            body_type: t,
            transform: Transform::new(p, q),
            allow_sleep: false,
            ..Default::default()
        })
        .unwrap()
}

#[test]
fn free_fall_follows_kinematics() {
    let mut w = scenes::world(true);
    let b = scenes::dynamic_sphere(&mut w, Vec3::new(0.0, 100.0, 0.0), 0.5, &ShapeDef::default());
    run(&mut w, 2.0);
    let y = w.transform(b).unwrap().p.y;
    let v = w.linear_velocity(b).unwrap().y;
    // Semi-implicit Euler with 4 sub-steps: position error g·t·h/2 ≈ 0.02 m.
    assert!((y - (100.0 - 0.5 * G * 4.0)).abs() < 0.05, "y = {y}");
    assert!((v + G * 2.0).abs() < 1e-3, "v = {v}");
}

/// Drops a sphere with restitution `e` from `h` (bottom above the ground) and returns the
/// height of the first rebound peak.
fn bounce_peak(e: f32, h: f32) -> f32 {
    let mut w = scenes::world(false);
    let g = w.create_body(&BodyDef::default()).unwrap();
    let mat = ShapeDef {
        restitution: e,
        ..ShapeDef::default()
    };
    w.create_shape(
        g,
        &mat,
        &Geometry::Plane {
            normal: Vec3::Y,
            offset: 0.0,
        },
    )
    .unwrap();
    let r = 0.25;
    let b = scenes::dynamic_sphere(&mut w, Vec3::new(0.0, h + r, 0.0), r, &mat);
    let mut bounced = false;
    let mut peak = 0.0f32;
    for _ in 0..600 {
        w.step(DT).unwrap();
        let v = w.linear_velocity(b).unwrap().y;
        let y = w.transform(b).unwrap().p.y - r;
        if !bounced && v > 0.0 {
            bounced = true;
        }
        if bounced {
            peak = peak.max(y);
            if v < 0.0 {
                break;
            }
        }
    }
    peak
}

#[test]
fn bounce_height_is_restitution_squared() {
    for (e, tol) in [(0.5f32, 0.05f32), (0.8, 0.05), (1.0, 0.05)] {
        let h = 2.0;
        let peak = bounce_peak(e, h);
        let expected = e * e * h;
        assert!(
            (peak - expected).abs() < tol * expected,
            "e = {e}: peak {peak:.4} vs {expected:.4}"
        );
    }
}

#[test]
fn no_bounce_below_restitution_threshold() {
    // Dropped from 2 cm the impact speed (0.63 m/s) is below the 1 m/s threshold: with
    // restitution 0.9 a bounce would rise e²h = 16 mm; the ball must land, stay down and
    // rest on the plane (not in it, not through it).
    let peak = bounce_peak(0.9, 0.02);
    assert!(peak < 1e-3, "rose {peak} m after landing");
    let mut w = scenes::world(false);
    let g = w.create_body(&BodyDef::default()).unwrap();
    let mat = ShapeDef {
        restitution: 0.9,
        ..ShapeDef::default()
    };
    w.create_shape(
        g,
        &mat,
        &Geometry::Plane {
            normal: Vec3::Y,
            offset: 0.0,
        },
    )
    .unwrap();
    let r = 0.25;
    let b = scenes::dynamic_sphere(&mut w, Vec3::new(0.0, 0.02 + r, 0.0), r, &mat);
    let mut lowest = f32::MAX;
    for _ in 0..60 {
        w.step(DT).unwrap();
        lowest = lowest.min(w.transform(b).unwrap().p.y - r);
    }
    let rest = w.transform(b).unwrap().p.y - r;
    let v = w.linear_velocity(b).unwrap().length();
    println!("no bounce: rose {peak:e} m, lowest {lowest:e} m, rest height {rest:e} m, speed {v:e} m/s");
    assert!(rest.abs() < 1e-3, "rest height above the plane {rest} m");
    assert!(lowest > -5e-3, "sank {lowest} m into the plane");
    assert!(v < 1e-3, "still moving at {v} m/s");
}

/// A box on a plane inclined by `theta`; returns its displacement along the slope after `t`.
fn slide(theta: f32, mu_s: f32, mu_d: f32, t: f32) -> f32 {
    let mut w = scenes::world(false);
    let q = Quat::from_rotation_z(theta);
    let n = q * Vec3::Y;
    let g = w.create_body(&BodyDef::default()).unwrap();
    let mat = ShapeDef {
        static_friction: mu_s,
        dynamic_friction: mu_d,
        ..ShapeDef::default()
    };
    w.create_shape(g, &mat, &Geometry::Plane { normal: n, offset: 0.0 })
        .unwrap();
    let b = body_at(&mut w, BodyType::Dynamic, n * 0.5, q);
    w.create_shape(
        b,
        &mat,
        &Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::splat(0.5),
        },
    )
    .unwrap();
    let down_slope = q * Vec3::NEG_X; // rotating +Y about +Z tilts the surface down towards -X
    let start = w.transform(b).unwrap().p;
    run(&mut w, t);
    let p = w.transform(b).unwrap().p;
    assert!(((p - start).dot(n)).abs() < 0.01, "left the surface");
    (p - start).dot(down_slope)
}

#[test]
fn static_friction_holds_below_the_friction_angle() {
    // tan(25°) = 0.466 < μs = 0.6: holds, even though μd = 0.4 would not.
    let d = slide(25f32.to_radians(), 0.6, 0.4, 2.0);
    assert!(d.abs() < 0.01, "slid {d} m");
}

#[test]
fn sliding_distance_uses_dynamic_friction() {
    // tan(35°) = 0.70 > μs = 0.6: slides with a = g(sinθ − μd cosθ).
    let theta = 35f32.to_radians();
    let (mu_s, mu_d, t) = (0.6, 0.4, 2.0);
    let d = slide(theta, mu_s, mu_d, t);
    let expected = 0.5 * G * (theta.sin() - mu_d * theta.cos()) * t * t;
    assert!(
        (d - expected).abs() < 0.03 * expected,
        "slid {d:.4} m, expected {expected:.4}"
    );
    // Frictionless check of the same set-up.
    let d0 = slide(theta, 0.0, 0.0, t);
    let e0 = 0.5 * G * theta.sin() * t * t;
    assert!((d0 - e0).abs() < 0.02 * e0, "frictionless {d0:.4} vs {e0:.4}");
}

fn zero_g() -> World {
    World::new(WorldSettings {
        gravity: Vec3::ZERO,
        enable_sleep: false,
        ..Default::default()
    })
    .unwrap()
}

#[test]
fn collisions_conserve_linear_and_angular_momentum() {
    let mut w = zero_g();
    let mat = ShapeDef {
        restitution: 0.5,
        static_friction: 0.5,
        dynamic_friction: 0.3,
        ..ShapeDef::default()
    };
    let a = scenes::dynamic_box(&mut w, Vec3::new(-3.0, 0.2, 0.0), Vec3::new(0.5, 0.3, 0.4), &mat);
    let b = scenes::dynamic_sphere(&mut w, Vec3::new(3.0, -0.1, 0.15), 0.4, &mat);
    let c = scenes::dynamic_box(&mut w, Vec3::new(0.0, 3.0, 0.1), Vec3::new(0.3, 0.3, 0.3), &mat);
    w.set_linear_velocity(a, Vec3::new(4.0, 0.0, 0.0)).unwrap();
    w.set_angular_velocity(a, Vec3::new(0.0, 1.0, 2.0)).unwrap();
    w.set_linear_velocity(b, Vec3::new(-3.0, 0.5, 0.0)).unwrap();
    w.set_linear_velocity(c, Vec3::new(0.0, -3.5, 0.0)).unwrap();
    let ids = [a, b, c];
    let totals = |w: &World| {
        let mut p = Vec3::ZERO;
        let mut l = Vec3::ZERO;
        for &h in &ids {
            let body = w.body(h).unwrap();
            p += body.mass * body.v;
            l += body.center.cross(body.mass * body.v) + body.angular_momentum();
        }
        (p, l)
    };
    let (p0, l0) = totals(&w);
    let mut touched = 0;
    for _ in 0..120 {
        w.step(DT).unwrap();
        touched += w.counters.touching_contacts;
    }
    assert!(touched > 0, "the bodies never collided");
    let (p1, l1) = totals(&w);
    assert!((p1 - p0).length() < 1e-3 * p0.length(), "momentum {p0} -> {p1}");
    assert!((l1 - l0).length() < 2e-2 * l0.length(), "angular momentum {l0} -> {l1}");
}

/// An asymmetric box (inertia 1 : 2 : 3) spun about one principal axis with a tiny
/// perturbation; returns the angular-velocity history (body frame) and |L|, E over time.
fn spin(axis: usize, integrator: Integrator, seconds: f32) -> (Vec<Vec3>, Vec<f32>, Vec<f32>) {
    let mut w = World::new(WorldSettings {
        gravity: Vec3::ZERO,
        enable_sleep: false,
        integrator,
        ..Default::default()
    })
    .unwrap();
    let b = body_at(&mut w, BodyType::Dynamic, Vec3::ZERO, Quat::IDENTITY);
    // Half extents chosen so Ix < Iy < Iz.
    let h = Vec3::new(0.9, 0.6, 0.2);
    w.create_shape(
        b,
        &ShapeDef::default(),
        &Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: h,
        },
    )
    .unwrap();
    let mut omega = Vec3::splat(0.01);
    omega[axis] = 4.0;
    w.set_angular_velocity(b, omega).unwrap();
    let (mut ws, mut ls, mut es) = (vec![], vec![], vec![]);
    for _ in 0..(seconds / DT) as usize {
        w.step(DT).unwrap();
        let body = w.body(b).unwrap();
        ws.push(body.xf.q.conjugate() * body.w);
        ls.push(body.angular_momentum().length());
        es.push(body.kinetic_energy());
    }
    (ws, ls, es)
}

#[test]
fn intermediate_axis_spin_tumbles_and_conserves_momentum() {
    for integrator in [Integrator::SemiImplicitEuler, Integrator::Rk4] {
        let (ws, ls, es) = spin(1, integrator, 20.0);
        // Dzhanibekov: the spin about the intermediate axis flips sign.
        assert!(
            ws.iter().any(|w| w.y < -3.0),
            "{integrator:?}: intermediate-axis spin did not tumble"
        );
        let (l0, e0) = (ls[0], es[0]);
        for (l, e) in ls.iter().zip(&es) {
            assert!((l - l0).abs() < 0.02 * l0, "{integrator:?}: |L| drifted {l0} -> {l}");
            assert!(*e <= e0 * 1.001, "{integrator:?}: energy grew {e0} -> {e}");
        }
    }
}

#[test]
fn major_and_minor_axis_spins_are_stable() {
    for axis in [0usize, 2] {
        let (ws, _, _) = spin(axis, Integrator::SemiImplicitEuler, 10.0);
        assert!(ws.iter().all(|w| w[axis] > 3.8), "axis {axis}: spin wandered");
    }
}

#[test]
fn free_spin_keeps_its_energy_with_either_integrator() {
    // The default path turns anisotropic bodies by a symplectic splitting of the free
    // rotation (measured drift 3e-6 over 5 s); RK4 (f64) drifts 3e-4.
    let (_, _, euler) = spin(0, Integrator::SemiImplicitEuler, 5.0);
    let (_, _, rk4) = spin(0, Integrator::Rk4, 5.0);
    let drift = |e: &[f32]| (e[e.len() - 1] - e[0]).abs() / e[0];
    println!(
        "free spin energy drift: euler {:e}, rk4 {:e}",
        drift(&euler),
        drift(&rk4)
    );
    assert!(drift(&euler) < 2e-5, "euler {}", drift(&euler));
    assert!(drift(&rk4) < 1e-3, "rk4 {}", drift(&rk4));
}

/// Relative error of a damped body's speed after 1 s against e^(−c·t), stepped at `dt` with
/// one sub-step: dv/dt = −c·v with c = 4/s, so c·h is 0.4, 0.2, 0.1 for the three steps.
fn damped_speed_error(integrator: Integrator, dt: f32) -> f64 {
    let mut w = World::new(WorldSettings {
        gravity: Vec3::ZERO,
        enable_sleep: false,
        substeps: 1,
        integrator,
        ..Default::default()
    })
    .unwrap();
    let b = scenes::dynamic_sphere(&mut w, Vec3::ZERO, 0.5, &ShapeDef::default());
    let c = 4.0f32;
    w.set_damping(b, c, 0.0).unwrap();
    w.set_linear_velocity(b, Vec3::new(1.0, 0.0, 0.0)).unwrap();
    let n = (1.0 / dt).round() as usize;
    for _ in 0..n {
        w.step(dt).unwrap();
    }
    let v = w.linear_velocity(b).unwrap().x as f64;
    let exact = (-(c as f64) * (n as f64 * dt as f64)).exp();
    (v - exact).abs() / exact
}

/// RK4 is fourth order and semi-implicit Euler first order: halving the step divides RK4's
/// error by about 2⁴ = 16 and Euler's by about 2. (Measured: RK4 errors 1.2e-3, 6.3e-5,
/// 3.8e-6, ratios 19.0 and 16.4; Euler 0.89, 0.42, 0.21, ratios 2.09 and 2.06. At c·h = 0.4
/// the higher terms still show; the bounds also leave room for the f32 rounding of the stored
/// velocity.)
#[test]
fn rk4_error_falls_sixteen_fold_when_the_step_halves_and_euler_twofold() {
    let steps = [0.1f32, 0.05, 0.025];
    let ratios = |integrator| {
        let e = steps.map(|dt| damped_speed_error(integrator, dt));
        println!(
            "{integrator:?}: errors {e:?}, ratios {:.2} {:.2}",
            e[0] / e[1],
            e[1] / e[2]
        );
        [e[0] / e[1], e[1] / e[2]]
    };
    for r in ratios(Integrator::Rk4) {
        assert!((12.0..26.0).contains(&r), "RK4 error ratio {r} (fourth order: 16)");
    }
    for r in ratios(Integrator::SemiImplicitEuler) {
        assert!((1.6..2.4).contains(&r), "Euler error ratio {r} (first order: 2)");
    }
}

#[test]
fn damping_decays_velocity_exponentially() {
    let mut w = zero_g();
    let b = scenes::dynamic_sphere(&mut w, Vec3::ZERO, 0.5, &ShapeDef::default());
    w.set_damping(b, 0.5, 0.0).unwrap();
    w.set_linear_velocity(b, Vec3::new(10.0, 0.0, 0.0)).unwrap();
    run(&mut w, 2.0);
    let v = w.linear_velocity(b).unwrap().x;
    let expected = 10.0 * (-0.5f32 * 2.0).exp();
    assert!((v - expected).abs() < 0.01 * expected, "{v} vs {expected}");
}

#[test]
fn force_at_point_produces_torque() {
    let mut w = zero_g();
    let b = scenes::dynamic_box(&mut w, Vec3::ZERO, Vec3::splat(0.5), &ShapeDef::default());
    // 1000 kg unit cube: I = m/6 = 166.7 kg·m². A force of 100 N at x = 0.5 along +Y gives a
    // torque of 50 N·m about +Z for one step.
    w.apply_force_at_point(b, Vec3::new(0.0, 100.0, 0.0), Vec3::new(0.5, 0.0, 0.0), true)
        .unwrap();
    w.step(DT).unwrap();
    let wz = w.angular_velocity(b).unwrap().z;
    let v = w.linear_velocity(b).unwrap().y;
    assert!((wz - 50.0 / (1000.0 / 6.0) * DT).abs() < 1e-5, "wz = {wz}");
    assert!((v - 100.0 / 1000.0 * DT).abs() < 1e-6);
    // Forces last one step only.
    w.step(DT).unwrap();
    assert!((w.linear_velocity(b).unwrap().y - v).abs() < 1e-7);
}

#[test]
fn kinematic_platform_carries_a_box() {
    let mut w = scenes::world(true);
    let p = w
        .create_body(&BodyDef {
            body_type: BodyType::Kinematic,
            linear_velocity: Vec3::new(1.0, 0.0, 0.0),
            ..Default::default()
        })
        .unwrap();
    w.create_shape(
        p,
        &ShapeDef::default(),
        &Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::new(3.0, 0.25, 3.0),
        },
    )
    .unwrap();
    let b = scenes::dynamic_box(
        &mut w,
        Vec3::new(0.0, 0.75, 0.0),
        Vec3::splat(0.5),
        &ShapeDef::default(),
    );
    // Riding along from the start: static friction keeps it there.
    w.set_linear_velocity(b, Vec3::new(1.0, 0.0, 0.0)).unwrap();
    run(&mut w, 2.0);
    let pb = w.transform(b).unwrap().p;
    let pp = w.transform(p).unwrap().p;
    assert!((pp.x - 2.0).abs() < 1e-3, "platform at {}", pp.x);
    assert!(
        (pb.x - pp.x).abs() < 0.005,
        "box {} left behind by platform {}",
        pb.x,
        pp.x
    );
    assert!((pb.y - 0.75).abs() < 0.01);
    // A target transform drives the kinematic body there in one step.
    let target = Transform::new(Vec3::new(5.0, 0.0, 0.0), Quat::from_rotation_y(0.3));
    w.set_kinematic_target(p, target).unwrap();
    w.step(DT).unwrap();
    let t = w.transform(p).unwrap();
    assert!((t.p - target.p).length() < 1e-3 && t.q.angle_between(target.q) < 1e-3);
}

#[test]
fn rolling_sphere_and_capsule_keep_their_height_and_do_not_gain_energy() {
    for capsule in [false, true] {
        let mut w = scenes::world(false);
        // Neither surface resists rolling (tests/rolling.rs covers rolling resistance).
        let free = ShapeDef {
            rolling_resistance: 0.0,
            torsional_friction: 0.0,
            ..ShapeDef::default()
        };
        let ground = body_at(&mut w, BodyType::Static, Vec3::ZERO, Quat::IDENTITY);
        let plane = Geometry::Plane {
            normal: Vec3::Y,
            offset: 0.0,
        };
        w.create_shape(ground, &free, &plane).unwrap();
        let r = 0.4;
        let b = body_at(&mut w, BodyType::Dynamic, Vec3::new(0.0, r, 0.0), Quat::IDENTITY);
        let g = if capsule {
            // Axis along z: it rolls along x like a log.
            Geometry::Capsule {
                a: Vec3::new(0.0, 0.0, -0.5),
                b: Vec3::new(0.0, 0.0, 0.5),
                radius: r,
            }
        } else {
            Geometry::Sphere {
                center: Vec3::ZERO,
                radius: r,
            }
        };
        w.create_shape(b, &free, &g).unwrap();
        w.set_linear_velocity(b, Vec3::new(2.7, 0.0, 0.0)).unwrap();
        w.set_angular_velocity(b, Vec3::new(0.0, 0.0, -2.7 / r)).unwrap();
        let e0 = w.body(b).unwrap().kinetic_energy();
        let mut worst = 0.0f32;
        for _ in 0..300 {
            w.step(DT).unwrap();
            worst = worst.max((w.transform(b).unwrap().p.y - r).abs());
            assert!(
                w.body(b).unwrap().kinetic_energy() <= e0 * 1.001,
                "capsule {capsule}: rolling gained energy"
            );
        }
        assert!(worst < 1e-3, "capsule {capsule}: height error {worst}");
        assert!(w.linear_velocity(b).unwrap().y.abs() < 1e-3);
        // Rolling without slipping and without rolling resistance keeps its speed.
        assert!((w.linear_velocity(b).unwrap().x - 2.7).abs() < 0.02 * 2.7);
    }
}

// ------------------------------------------------------------------------------------ sleep

/// Drops a body from `h` (its lowest point) onto a plane; returns the time it last moved
/// faster than twice the sleep threshold (the landing and its settling) and the time it fell
/// asleep (None within 10 s).
fn landing_and_sleep(geom: &Geometry, h: f32, bottom: f32, q: Quat) -> (f32, Option<f32>) {
    let mut w = scenes::world(true);
    scenes::ground_plane(&mut w);
    let b = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(Vec3::new(0.0, h + bottom, 0.0), q),
            ..Default::default()
        })
        .unwrap();
    w.create_shape(b, &ShapeDef::default(), geom).unwrap();
    let t = w.settings.sleep_threshold;
    let mut moving = 0.0;
    for step in 1..=600 {
        w.step(DT).unwrap();
        let body = w.body(b).unwrap();
        if !body.awake {
            return (moving, Some(step as f32 * DT));
        }
        if (body.v.length_squared() + body.w.length_squared()).sqrt() > 2.0 * t {
            moving = step as f32 * DT;
        }
    }
    (moving, None)
}

/// The sleep lag: a box dropped from 1 m lands after sqrt(2h/g) = 0.45 s and falls asleep
/// `time_to_sleep` (0.5 s) plus at most 0.33 s (the motion average's decay from its cap,
/// log2(10) half-lives of 0.1 s) after it last moved faster than twice the sleep threshold;
/// asserted within 0.5 s to 0.85 s (measured 0.817 s: it stops within the landing step).
/// The seed's one-second half-life slept 3.8 s after the landing.
#[test]
fn a_landed_box_sleeps_time_to_sleep_after_it_stopped() {
    let s = WorldSettings::default();
    let geom = Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::splat(0.5),
    };
    let (moved, slept) = landing_and_sleep(&geom, 1.0, 0.5, Quat::IDENTITY);
    let slept = slept.expect("asleep within 10 s");
    println!(
        "box from 1 m: last moved at {moved:.3} s, asleep at {slept:.3} s, lag {:.3} s",
        slept - moved
    );
    assert!((moved - (2.0f32 / G).sqrt()).abs() < 0.1, "landed at {moved} s");
    assert!(slept - moved >= s.time_to_sleep && slept - moved <= s.time_to_sleep + 0.35);
}

/// Seeded random drops (spheres, boxes, capsules, 0.05 to 0.5 m, from 0 to 3 m, turned at
/// random): each falls asleep, no sooner than `time_to_sleep` and no later than
/// `time_to_sleep` + 0.35 s after it last moved faster than twice the sleep threshold
/// (0.85 s at the defaults; measured 0.817 s in every case).
#[test]
fn random_drops_sleep_time_to_sleep_after_they_stop() {
    let s = WorldSettings::default();
    let mut seed = 0x51ee_9a11u32;
    let mut rnd = move || {
        seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
        (seed >> 8) as f32 / (1u32 << 24) as f32
    };
    let mut worst = 0.0f32;
    for case in 0..24 {
        let r = 0.05 + 0.45 * rnd();
        let h = 3.0 * rnd();
        let (geom, bottom) = match case % 3 {
            0 => (
                Geometry::Sphere {
                    center: Vec3::ZERO,
                    radius: r,
                },
                r,
            ),
            1 => (
                Geometry::Box {
                    center: Vec3::ZERO,
                    rotation: Quat::IDENTITY,
                    half_extents: Vec3::splat(r),
                },
                r,
            ),
            _ => (
                Geometry::Capsule {
                    a: Vec3::new(-r, 0.0, 0.0),
                    b: Vec3::new(r, 0.0, 0.0),
                    radius: r,
                },
                r,
            ),
        };
        let q = Quat::from_rotation_y(6.0 * rnd());
        let (moved, slept) = landing_and_sleep(&geom, h, bottom, q);
        let slept = slept.unwrap_or_else(|| panic!("case {case}: awake after 10 s"));
        let lag = slept - moved;
        println!(
            "case {case}: shape {}, size {r:.3} m, from {h:.2} m: lag {lag:.3} s",
            case % 3
        );
        assert!(
            lag >= s.time_to_sleep && lag <= s.time_to_sleep + 0.35,
            "case {case}: asleep {lag} s after it stopped"
        );
        worst = worst.max(lag);
    }
    println!("worst lag {worst:.3} s");
}

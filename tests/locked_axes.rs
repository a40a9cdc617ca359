//! Locked linear and angular axes (issue 14 item 7): a locked axis keeps exactly zero velocity
//! through contacts, joints, forces, impulses and gravity. A 2.5D pile stays in its plane and
//! sleeps; an upright character keeps its rotation; a body locked in y floats; joints to
//! locked bodies stay bounded; a seeded random test over masks, poses, masses, shapes and
//! impulses; four and eight lanes agree bit for bit.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use hearth::dynamics::body::{
    LOCK_ANGULAR_X, LOCK_ANGULAR_Y, LOCK_ANGULAR_Z, LOCK_LINEAR_X, LOCK_LINEAR_Y, LOCK_LINEAR_Z,
};
use hearth::joints::{BallParams, HingeParams};
use hearth::math::{Quat, Transform, Vec3};
use hearth::{BodyDef, BodyHandle, BodyType, Geometry, JointDef, JointKind, LaneWidth, ShapeDef, World, WorldSettings};
use scenes::{assert_locked, energy};

const DT: f32 = 1.0 / 60.0;
const ANGULAR: u8 = LOCK_ANGULAR_X | LOCK_ANGULAR_Y | LOCK_ANGULAR_Z;
/// The 2.5D lock: the XY plane, turning only about Z.
const PLANAR: u8 = LOCK_LINEAR_Z | LOCK_ANGULAR_X | LOCK_ANGULAR_Y;

fn body(w: &mut World, p: Vec3, q: Quat, locks: u8, g: &Geometry, density: f32) -> BodyHandle {
    let b = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(p, q),
            locked_axes: locks,
            ..Default::default()
        })
        .unwrap();
    let def = ShapeDef {
        density,
        ..Default::default()
    };
    w.create_shape(b, &def, g).unwrap();
    b
}

fn cube(h: Vec3) -> Geometry {
    Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: h,
    }
}

fn planar_pile(w: &mut World) -> Vec<BodyHandle> {
    scenes::ground_box(w, 20.0);
    let mut v = Vec::new();
    for i in 0..24 {
        let (col, row) = ((i % 6) as f32, (i / 6) as f32);
        let p = Vec3::new(-2.5 + col * 0.9 + 0.1 * row, 0.5 + row * 0.9, 1.25);
        let q = Quat::from_rotation_z(0.1 * i as f32);
        v.push(body(w, p, q, PLANAR, &cube(Vec3::new(0.4, 0.4, 0.4)), 1000.0));
    }
    v
}

#[test]
fn planar_pile_pushed_and_hit_off_centre_stays_in_its_plane_and_sleeps() {
    let mut w = scenes::world(true);
    let pile = planar_pile(&mut w);
    let z0: Vec<f32> = pile.iter().map(|&b| w.body(b).unwrap().center.z).collect();
    for step in 0..1000 {
        if step == 100 {
            // Hit off-centre, with an impulse out of the plane and a push along it.
            for (k, &b) in pile.iter().enumerate() {
                let c = w.body(b).unwrap().center;
                let j = Vec3::new(3.0, 2.0, 5.0 - k as f32 * 0.4) * 100.0;
                w.apply_impulse_at_point(b, j, c + Vec3::new(0.2, 0.3, 0.4), true)
                    .unwrap();
            }
        }
        if (150..250).contains(&step) {
            w.apply_force_at_point(pile[0], Vec3::new(-3000.0, 0.0, 4000.0), Vec3::new(0.0, 0.0, 2.0), true)
                .unwrap();
        }
        w.step(DT).unwrap();
        for (k, &b) in pile.iter().enumerate() {
            assert_locked(&w, b, PLANAR, "planar pile");
            assert_eq!(w.body(b).unwrap().center.z.to_bits(), z0[k].to_bits(), "z moved");
        }
    }
    let sleeping = pile.iter().filter(|&&b| !w.is_awake(b).unwrap()).count();
    assert_eq!(sleeping, pile.len(), "the pile sleeps after 1000 steps");
}

#[test]
fn upright_character_keeps_its_rotation_pushing_a_box_and_walking_down_a_slope() {
    let capsule = Geometry::Capsule {
        a: Vec3::new(0.0, -0.5, 0.0),
        b: Vec3::new(0.0, 0.5, 0.0),
        radius: 0.3,
    };
    // Pushing a box along the ground.
    let mut w = scenes::world(false);
    scenes::ground_box(&mut w, 30.0);
    let crate_box = body(
        &mut w,
        Vec3::new(-3.0, 0.5, 0.0),
        Quat::IDENTITY,
        0,
        &cube(Vec3::splat(0.5)),
        200.0,
    );
    let c = body(
        &mut w,
        Vec3::new(-1.0, 0.85, 0.1),
        Quat::from_rotation_y(0.3),
        ANGULAR,
        &capsule,
        1000.0,
    );
    let q0 = w.transform(c).unwrap().q;
    for step in 0..300 {
        w.apply_force(c, Vec3::new(-6000.0, 0.0, 300.0), true).unwrap();
        w.step(DT).unwrap();
        assert_locked(&w, c, ANGULAR, "character pushing");
        assert_eq!(w.transform(c).unwrap().q, q0, "rotation changed at step {step}");
    }
    assert!(
        w.body(crate_box).unwrap().center.x < -4.0,
        "the character pushed the box"
    );
    // Walking down a 20° slope.
    let mut w = scenes::world(false);
    let slope = w
        .create_body(&BodyDef {
            transform: Transform::new(Vec3::ZERO, Quat::from_rotation_z(0.35)),
            ..Default::default()
        })
        .unwrap();
    w.create_shape(slope, &ShapeDef::default(), &cube(Vec3::new(20.0, 0.5, 3.0)))
        .unwrap();
    let top = Quat::from_rotation_z(0.35) * Vec3::new(8.0, 1.4, 0.0);
    let c = body(&mut w, top, Quat::IDENTITY, ANGULAR, &capsule, 1000.0);
    let q0 = w.transform(c).unwrap().q;
    for step in 0..300 {
        w.apply_force(c, Vec3::new(-1000.0, 0.0, 0.0), true).unwrap();
        w.step(DT).unwrap();
        assert_locked(&w, c, ANGULAR, "character walking down");
        assert_eq!(w.transform(c).unwrap().q, q0, "rotation changed at step {step}");
    }
    let end = w.body(c).unwrap().center;
    assert!(
        end.x < top.x - 4.0 && end.y < top.y - 1.0,
        "walked down the slope: {top} -> {end}"
    );
}

#[test]
fn a_body_locked_in_y_rests_on_nothing_and_still_slides() {
    let mut w = scenes::world(false);
    let b = body(
        &mut w,
        Vec3::new(0.0, 5.0, 0.0),
        Quat::IDENTITY,
        LOCK_LINEAR_Y,
        &cube(Vec3::splat(0.5)),
        1000.0,
    );
    w.apply_linear_impulse(b, Vec3::new(1000.0, 5000.0, 0.0), true).unwrap();
    for _ in 0..600 {
        w.step(DT).unwrap();
        assert_locked(&w, b, LOCK_LINEAR_Y, "floating");
    }
    assert_eq!(w.body(b).unwrap().center.y, 5.0);
    // 1000 N·s on 1000 kg: 1 m/s for 10 s, to f32 rounding.
    assert!((w.body(b).unwrap().center.x - 10.0).abs() < 1e-3);
}

#[test]
fn setter_zeroes_locked_velocities_at_once_and_unknown_bits_change_nothing() {
    let mut w = scenes::world(true);
    let b = body(
        &mut w,
        Vec3::new(0.0, 5.0, 0.0),
        Quat::IDENTITY,
        0,
        &cube(Vec3::splat(0.5)),
        1000.0,
    );
    w.set_linear_velocity(b, Vec3::new(1.0, 2.0, 3.0)).unwrap();
    w.set_angular_velocity(b, Vec3::new(4.0, 5.0, 6.0)).unwrap();
    w.set_locked_axes(b, (LOCK_LINEAR_X | LOCK_ANGULAR_Z) as u32).unwrap();
    assert_eq!(w.linear_velocity(b).unwrap(), Vec3::new(0.0, 2.0, 3.0));
    assert_eq!(w.angular_velocity(b).unwrap(), Vec3::new(4.0, 5.0, 0.0));
    assert_eq!(w.locked_axes(b).unwrap(), 33);
    assert!(w.set_locked_axes(b, 64).is_err());
    assert!(w.set_locked_axes(b, 0x100).is_err());
    assert_eq!(w.locked_axes(b).unwrap(), 33);
    let bad = BodyDef {
        body_type: BodyType::Dynamic,
        locked_axes: 0x40,
        ..Default::default()
    };
    assert!(w.create_body(&bad).is_err());
    // Velocity setters respect the locks; unlocking frees the axes again.
    w.set_linear_velocity(b, Vec3::new(7.0, 0.0, 0.0)).unwrap();
    assert_eq!(w.linear_velocity(b).unwrap(), Vec3::ZERO);
    w.set_locked_axes(b, 0).unwrap();
    w.set_linear_velocity(b, Vec3::new(7.0, 0.0, 0.0)).unwrap();
    assert_eq!(w.linear_velocity(b).unwrap(), Vec3::new(7.0, 0.0, 0.0));
    // A sleeping body is woken.
    let mut w = scenes::world(true);
    scenes::ground_box(&mut w, 5.0);
    let b = body(
        &mut w,
        Vec3::new(0.0, 0.5, 0.0),
        Quat::IDENTITY,
        0,
        &cube(Vec3::splat(0.5)),
        1000.0,
    );
    for _ in 0..300 {
        w.step(DT).unwrap();
    }
    assert!(!w.is_awake(b).unwrap());
    w.set_locked_axes(b, LOCK_LINEAR_Z as u32).unwrap();
    assert!(w.is_awake(b).unwrap());
}

#[test]
fn hinge_and_ball_joints_to_locked_bodies_stay_bounded() {
    for (kind, locks) in [
        (JointKind::Hinge(HingeParams::default()), PLANAR),
        (JointKind::Ball(BallParams::default()), PLANAR),
        (JointKind::Ball(BallParams::default()), ANGULAR),
        (JointKind::Ball(BallParams::default()), LOCK_LINEAR_Y),
    ] {
        let mut w = scenes::world(false);
        // A chain of three: the first hangs from the world, each locked.
        let mut bodies = Vec::new();
        let mut prev: Option<BodyHandle> = None;
        for k in 0..3 {
            let p = Vec3::new(0.8 * (k + 1) as f32, 10.0, 0.0);
            let b = body(&mut w, p, Quat::IDENTITY, locks, &cube(Vec3::new(0.3, 0.1, 0.1)), 500.0);
            let anchor = p - Vec3::new(0.4, 0.0, 0.0);
            let frame = Transform::new(anchor, Quat::IDENTITY);
            let mut def = JointDef::new(kind);
            def.body_a = b;
            def.frame_a = w.transform(b).unwrap().inv_mul(&frame);
            match prev {
                Some(a) => {
                    def.body_b = a;
                    def.frame_b = w.transform(a).unwrap().inv_mul(&frame);
                }
                None => def.frame_b = frame,
            }
            w.create_joint(&def).unwrap();
            bodies.push(b);
            prev = Some(b);
        }
        w.apply_linear_impulse(bodies[2], Vec3::new(0.0, 50.0, 80.0), true)
            .unwrap();
        let e0 = energy(&w, &bodies);
        let mut e_max = e0;
        for _ in 0..1200 {
            w.step(DT).unwrap();
            for &b in &bodies {
                assert_locked(&w, b, locks, "jointed");
                let c = w.body(b).unwrap().center;
                assert!(
                    c.is_finite() && (c - Vec3::new(0.0, 10.0, 0.0)).length() < 3.0,
                    "{c} {locks:#x} {kind:?}"
                );
            }
            e_max = e_max.max(energy(&w, &bodies));
        }
        // The joints' error correction may add a little: 1 % of the mass times g times 1 m.
        let m: f64 = bodies.iter().map(|&b| w.body(b).unwrap().mass as f64).sum();
        assert!(
            e_max <= e0 + 0.01 * m * 9.81,
            "energy grew: {e0} -> {e_max} (locks {locks:#x})"
        );
    }
}

#[test]
fn four_and_eight_lanes_agree_bit_for_bit_with_locks() {
    let run = |lanes: LaneWidth| {
        let mut w = World::new(WorldSettings {
            lane_width: lanes,
            ..WorldSettings::default()
        })
        .unwrap();
        let pile = planar_pile(&mut w);
        for _ in 0..200 {
            w.step(DT).unwrap();
        }
        pile.iter()
            .map(|&b| {
                let x = w.transform(b).unwrap();
                (x.p.to_array(), x.q.to_array())
            })
            .collect::<Vec<_>>()
    };
    let four = run(LaneWidth::Four);
    let auto = run(LaneWidth::Auto);
    assert_eq!(four.len(), auto.len());
    for (a, b) in four.iter().zip(&auto) {
        assert_eq!(a.0.map(f32::to_bits), b.0.map(f32::to_bits));
        assert_eq!(a.1.map(f32::to_bits), b.1.map(f32::to_bits));
    }
}

#[test]
fn seeded_random_locks_poses_masses_shapes_and_impulses() {
    let mut rng = scenes::Rng(0x10c4ed);
    for round in 0..6 {
        let mut w = scenes::world(true);
        // Wide enough that nothing leaves it.
        scenes::ground_box(&mut w, 200.0);
        let mut bodies = Vec::new();
        let mut locks = Vec::new();
        for k in 0..30 {
            let mask = (rng.next_u32() % 64) as u8;
            // On a grid wide enough that no two start overlapping (nothing pushes them apart).
            let p = Vec3::new(
                (k % 6) as f32 * 1.8 - 4.5,
                rng.range(1.0, 3.0),
                (k / 6) as f32 * 1.8 - 3.6,
            );
            let g = match rng.next_u32() % 3 {
                0 => cube(Vec3::new(rng.range(0.1, 0.5), rng.range(0.1, 0.5), rng.range(0.1, 0.5))),
                1 => Geometry::Sphere {
                    center: Vec3::ZERO,
                    radius: rng.range(0.1, 0.5),
                },
                _ => Geometry::Capsule {
                    a: Vec3::new(0.0, -0.3, 0.0),
                    b: Vec3::new(0.0, 0.3, 0.0),
                    radius: rng.range(0.1, 0.4),
                },
            };
            let density = 10f32.powf(rng.range(1.0, 4.0));
            bodies.push(body(&mut w, p, rng.quat(), mask, &g, density));
            locks.push(mask);
        }
        let mut e_ref = f64::NAN;
        for step in 0..600 {
            if step % 100 == 0 {
                for &b in &bodies {
                    let c = w.body(b).unwrap().center;
                    let m = w.body(b).unwrap().mass;
                    let j = rng.vec(3.0) * m;
                    w.apply_impulse_at_point(b, j, c + rng.vec(0.05), true).unwrap();
                    w.apply_torque(b, rng.vec(1.0) * m, true).unwrap();
                }
                w.step(DT).unwrap();
                e_ref = energy(&w, &bodies);
                continue;
            }
            w.step(DT).unwrap();
            for (&b, &m) in bodies.iter().zip(&locks) {
                assert_locked(&w, b, m, "random");
                let body = w.body(b).unwrap();
                assert!(body.center.is_finite() && body.xf.q.is_finite());
                assert!(
                    body.v.length() < 30.0 && body.w.length() < 200.0,
                    "round {round}: {} {}",
                    body.v,
                    body.w
                );
            }
            // Nothing drives the bodies between the kicks: the energy does not grow (a margin of
            // 1 % of the total weight times 0.1 m for the contacts' overlap push).
            let e = energy(&w, &bodies);
            let weight: f64 = bodies.iter().map(|&b| w.body(b).unwrap().mass as f64 * 9.81).sum();
            assert!(
                e <= e_ref + 0.01 * weight * 0.1,
                "round {round} step {step}: energy {e_ref} -> {e}"
            );
        }
    }
}

/// A world without gravity (the bodies float until they meet) that bounces from 5 cm/s.
fn weightless() -> World {
    World::new(WorldSettings {
        gravity: Vec3::ZERO,
        enable_sleep: false,
        restitution_threshold: 0.05,
        ..WorldSettings::default()
    })
    .unwrap()
}

/// Frictionless and perfectly elastic.
fn elastic(density: f32) -> ShapeDef {
    ShapeDef {
        density,
        static_friction: 0.0,
        dynamic_friction: 0.0,
        restitution: 1.0,
        ..Default::default()
    }
}

fn elastic_body(w: &mut World, p: Vec3, locks: u8, g: &Geometry, density: f32, v: Vec3) -> BodyHandle {
    let b = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(p, Quat::IDENTITY),
            locked_axes: locks,
            linear_velocity: v,
            ..Default::default()
        })
        .unwrap();
    w.create_shape(b, &elastic(density), g).unwrap();
    b
}

fn ball(r: f32) -> Geometry {
    Geometry::Sphere {
        center: Vec3::ZERO,
        radius: r,
    }
}

/// A frictionless elastic collision of A (free, moving at `u`) with B (at rest, linear locks
/// `locks_b`) along the unit normal `n` from A to B, in f64. A reduced-DOF body's inverse mass
/// is `diag(free)/m`: the impulse is `j = (1 + e)·(u·n) / (1/m_A + n·diag(free_B)·n/m_B)`, and
/// `v_A = u − n·j/m_A`, `v_B = diag(free_B)·n·j/m_B`.
fn reduced_collision(u: Vec3, n: Vec3, ma: f64, mb: f64, locks_b: u8) -> (glam::DVec3, glam::DVec3) {
    let (u, n) = (u.as_dvec3(), n.as_dvec3());
    let free = glam::DVec3::new(
        f64::from(locks_b & 1 == 0),
        f64::from(locks_b & 2 == 0),
        f64::from(locks_b & 4 == 0),
    );
    let j = 2.0 * u.dot(n) / (1.0 / ma + n.dot(free * n) / mb);
    (u - n * (j / ma), free * n * (j / mb))
}

#[test]
fn box_locked_in_y_and_rotation_bounces_off_a_tilted_wall_as_in_one_dimension() {
    // The box moves along x into a wall tilted 30° about z. Locked in y and in every rotation,
    // its inverse mass along the wall's normal n = (cos θ, sin θ, 0) is n·diag(1,0,1)·n/m =
    // cos²θ/m, so an elastic frictionless bounce (j = 2m·v cos θ / cos²θ) gives Δv_x = −2v:
    // it comes straight back at −v, as in one dimension (within 1e-4·v; measured 2.5e-7·v).
    // The scalar inverse mass with the y component projected away afterwards bounced it with
    // Δv_x = −2v·cos²θ (at 30°, back at only 0.5·v).
    for (theta, v) in [(std::f32::consts::FRAC_PI_6, 4.0f32), (0.3, 2.5), (0.8, 6.0)] {
        let mut w = weightless();
        let wall = w
            .create_body(&BodyDef {
                transform: Transform::new(Vec3::new(3.5, 0.0, 0.0), Quat::from_rotation_z(theta)),
                ..Default::default()
            })
            .unwrap();
        w.create_shape(wall, &elastic(1000.0), &cube(Vec3::new(0.5, 5.0, 5.0)))
            .unwrap();
        let locks = LOCK_LINEAR_Y | ANGULAR;
        let b = elastic_body(
            &mut w,
            Vec3::ZERO,
            locks,
            &cube(Vec3::splat(0.5)),
            700.0,
            Vec3::new(v, 0.0, 0.0),
        );
        for _ in 0..120 {
            w.step(DT).unwrap();
            assert_locked(&w, b, locks, "box into the wall");
        }
        let after = w.linear_velocity(b).unwrap();
        println!("theta {theta} v {v}: after {after}");
        assert!(
            (after.x + v).abs() <= 1e-4 * v,
            "θ {theta}: {after} (expected −{v} along x)"
        );
        assert_eq!(after.z, 0.0, "no motion along z: {after}");
    }
}

#[test]
fn box_locked_in_y_and_rotation_hit_off_centre_takes_the_one_dimensional_momentum() {
    // A ball hits the box's face 0.3 m above and 0.2 m beside its centre. Without rotation the
    // box answers as a point mass: the one-dimensional elastic collision, v_ball = u(m1 −
    // m2)/(m1 + m2), v_box = 2u·m1/(m1 + m2), whatever the lever (within 1e-4·u; measured
    // 1e-7·u).
    let mut w = weightless();
    let locks = LOCK_LINEAR_Y | ANGULAR;
    let boxb = elastic_body(
        &mut w,
        Vec3::new(2.0, 0.0, 0.0),
        locks,
        &cube(Vec3::splat(0.5)),
        200.0,
        Vec3::ZERO,
    );
    let u = 4.0;
    let s = elastic_body(
        &mut w,
        Vec3::new(0.0, 0.3, 0.2),
        0,
        &ball(0.3),
        1000.0,
        Vec3::new(u, 0.0, 0.0),
    );
    let (m1, m2) = (w.body(s).unwrap().mass as f64, w.body(boxb).unwrap().mass as f64);
    for _ in 0..60 {
        w.step(DT).unwrap();
        assert_locked(&w, boxb, locks, "box hit off-centre");
    }
    let (vs, vb) = (w.linear_velocity(s).unwrap(), w.linear_velocity(boxb).unwrap());
    let (es, eb) = (u as f64 * (m1 - m2) / (m1 + m2), 2.0 * u as f64 * m1 / (m1 + m2));
    println!("off-centre: ball {vs} box {vb}; expected {es} {eb}");
    assert!((vs.x as f64 - es).abs() <= 1e-4 * u as f64, "ball {vs}, expected {es}");
    assert!((vb.x as f64 - eb).abs() <= 1e-4 * u as f64, "box {vb}, expected {eb}");
    assert!(
        vs.y.abs() <= 1e-4 && vs.z.abs() <= 1e-4 && vb.z.abs() <= 1e-4,
        "{vs} {vb}"
    );
}

#[test]
fn sphere_locked_in_x_hit_diagonally_moves_only_in_z_with_the_reduced_momentum() {
    // A (free, 1000 kg/m³) moves along x and meets B (locked in x, twice as dense) with the
    // normal n = (1, 0, 1)/√2. B's inverse mass along n is n_z²/m_B = 1/(2m_B): with m_B = 2m_A
    // the impulse is j = 2u·n_x/(1.25/m_A), so B leaves along z at 0.4u and A at (0.2u, 0,
    // −0.8u) (the scalar mass with x projected away gave B u/3). Slowly: the contact's two
    // arms meet at the midpoint of the surfaces, which A's motion within a step moves off the
    // line of centres (at 4 m/s that spins A and moves the result by 1 %, locks or not).
    let r = 0.5;
    let u = 0.5;
    let n = Vec3::new(1.0, 0.0, 1.0).normalize();
    let mut w = weightless();
    // Touching and at rest for a first step, which makes the contact with normal n (a contact
    // found while the balls approach takes its normal from the centres then); then A moves.
    let a = elastic_body(&mut w, Vec3::ZERO, 0, &ball(r), 1000.0, Vec3::ZERO);
    let b = elastic_body(&mut w, n * (2.0 * r), LOCK_LINEAR_X, &ball(r), 2000.0, Vec3::ZERO);
    w.step(DT).unwrap();
    w.set_linear_velocity(a, Vec3::new(u, 0.0, 0.0)).unwrap();
    for _ in 0..60 {
        w.step(DT).unwrap();
        assert_locked(&w, b, LOCK_LINEAR_X, "diagonal hit");
    }
    let (va, vb) = (w.linear_velocity(a).unwrap(), w.linear_velocity(b).unwrap());
    let (ea, eb) = reduced_collision(Vec3::new(u, 0.0, 0.0), n, 1.0, 2.0, LOCK_LINEAR_X);
    println!("diagonal: A {va} B {vb}; expected {ea} {eb}");
    // Within 2e-4·u (measured 8.5e-5·u, the arms' midpoint again).
    assert!(
        (va.as_dvec3() - ea).length() <= 2e-4 * u as f64,
        "A {va}, expected {ea}"
    );
    assert!(
        (vb.as_dvec3() - eb).length() <= 2e-4 * u as f64,
        "B {vb}, expected {eb}"
    );
    assert!((eb.z - 0.4 * u as f64).abs() < 1e-6 && (ea - glam::DVec3::new(0.2, 0.0, -0.8) * u as f64).length() < 1e-6);
    assert_eq!((vb.x, vb.y), (0.0, 0.0), "B moves only along z");
}

#[test]
fn seeded_random_reduced_collisions_match_the_reduced_mass_formula() {
    // Random linear lock masks on B (never all three: it must be able to move along n),
    // densities over two decades, radii, speeds and normals at most 53° off the motion. Within
    // 0.5 % of the speed (measured 0.34 %: the contact's arms meet at the surfaces' midpoint,
    // which moves with A within a step); the scalar inverse mass with the locked components
    // projected away afterwards was off by tens of per cent.
    let mut rng = scenes::Rng(0x5eed_10c5);
    let mut worst = 0.0f64;
    for round in 0..40 {
        let locks = 1 + (rng.next_u32() % 6) as u8;
        let (ra, rb) = (rng.range(0.2, 0.6), rng.range(0.2, 0.6));
        let (da, db) = (10f32.powf(rng.range(2.0, 4.0)), 10f32.powf(rng.range(2.0, 4.0)));
        let dir = rng.vec(1.0).normalize();
        let speed = rng.range(0.2, 1.0);
        let free = Vec3::new(
            (locks & 1 == 0) as u8 as f32,
            (locks & 2 == 0) as u8 as f32,
            (locks & 4 == 0) as u8 as f32,
        );
        // A normal with n·dir ≥ 0.6 and n·free·n ≥ 0.1 (B can take the push).
        let n = loop {
            let n = (dir + rng.vec(0.8)).normalize();
            if n.dot(dir) >= 0.6 && n.dot(free * n) >= 0.1 {
                break n;
            }
        };
        let mut w = weightless();
        // Touching and at rest for a step (the contact's normal is then n), then A moves.
        let a = elastic_body(&mut w, Vec3::ZERO, 0, &ball(ra), da, Vec3::ZERO);
        let b = elastic_body(&mut w, n * (ra + rb), locks, &ball(rb), db, Vec3::ZERO);
        w.step(DT).unwrap();
        w.set_linear_velocity(a, dir * speed).unwrap();
        let (ma, mb) = (w.body(a).unwrap().mass as f64, w.body(b).unwrap().mass as f64);
        let e0 = 0.5 * ma * (speed as f64).powi(2);
        for _ in 0..45 {
            w.step(DT).unwrap();
            assert_locked(&w, b, locks, "random reduced collision");
            let (va, vb) = (w.linear_velocity(a).unwrap(), w.linear_velocity(b).unwrap());
            assert!(va.is_finite() && vb.is_finite(), "round {round}: {va} {vb}");
            let e = 0.5 * ma * va.as_dvec3().length_squared() + 0.5 * mb * vb.as_dvec3().length_squared();
            assert!(e <= e0 * (1.0 + 1e-4), "round {round}: energy {e0} -> {e}");
        }
        let (va, vb) = (w.linear_velocity(a).unwrap(), w.linear_velocity(b).unwrap());
        let (ea, eb) = reduced_collision(dir * speed, n, ma, mb, locks);
        let err = (va.as_dvec3() - ea).length().max((vb.as_dvec3() - eb).length()) / speed as f64;
        worst = worst.max(err);
        assert!(
            err <= 5e-3,
            "round {round} locks {locks}: A {va} vs {ea}, B {vb} vs {eb}"
        );
    }
    println!("worst relative velocity error {worst:e}");
}

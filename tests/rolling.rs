//! Round bodies come to rest (issue 12): rolling resistance and torsional friction against
//! their analytic answers, a seeded randomized run over radii, masses, speeds, resistances
//! and slopes, rolling without resistance that neither gains nor loses speed, and the demo
//! scene and a ragdoll that end asleep.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use hearth::math::{Quat, Transform, Vec3};
use hearth::{BodyDef, BodyHandle, BodyType, Geometry, ShapeDef, World};

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;

/// A material with the given rolling resistance and torsional friction (defaults otherwise).
fn material(rolling: f32, torsional: f32) -> ShapeDef {
    ShapeDef {
        rolling_resistance: rolling,
        torsional_friction: torsional,
        ..ShapeDef::default()
    }
}

/// A static plane through the origin with normal `n`.
fn plane(w: &mut World, n: Vec3, def: &ShapeDef) -> BodyHandle {
    let g = w.create_body(&BodyDef::default()).unwrap();
    let geom = Geometry::Plane { normal: n, offset: 0.0 };
    w.create_shape(g, def, &geom).unwrap();
    g
}

/// A static box whose top face is the plane y = 0.
fn floor_box(w: &mut World, def: &ShapeDef) -> BodyHandle {
    let g = w
        .create_body(&BodyDef {
            transform: Transform::new(Vec3::new(0.0, -1.0, 0.0), Quat::IDENTITY),
            ..Default::default()
        })
        .unwrap();
    let geom = Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::new(100.0, 1.0, 100.0),
    };
    w.create_shape(g, def, &geom).unwrap();
    g
}

fn dynamic(w: &mut World, xf: Transform, geom: Geometry, def: &ShapeDef) -> BodyHandle {
    let b = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: xf,
            ..Default::default()
        })
        .unwrap();
    w.create_shape(b, def, &geom).unwrap();
    b
}

fn sphere(r: f32) -> Geometry {
    Geometry::Sphere {
        center: Vec3::ZERO,
        radius: r,
    }
}

/// A capsule of radius `r` whose segment (length `2·half`) runs along the body's z axis.
fn capsule(half: f32, r: f32) -> Geometry {
    Geometry::Capsule {
        a: Vec3::new(0.0, 0.0, -half),
        b: Vec3::new(0.0, 0.0, half),
        radius: r,
    }
}

/// Moment of inertia of body `b` about its local axis `axis` (kg·m²).
fn inertia_about(w: &World, b: BodyHandle, axis: Vec3) -> f32 {
    axis.dot(w.body(b).unwrap().inertia_local * axis)
}

/// Sets `b` rolling without slipping at `speed` along +x on a level floor (axis z).
fn roll(w: &mut World, b: BodyHandle, speed: f32, r: f32) {
    w.set_linear_velocity(b, Vec3::new(speed, 0.0, 0.0)).unwrap();
    w.set_angular_velocity(b, Vec3::new(0.0, 0.0, -speed / r)).unwrap();
}

/// The deceleration along a slope `θ` (0: a level floor) of a body of mass `m` and moment of
/// inertia `i` about its rolling axis, rolling downhill against rolling resistance `c` with
/// radius `r`. Rolling: the resistance torque c·N·r with N = m·g·cos θ, friction f (uphill)
/// keeping it rolling: m·a = f − m·g·sin θ, i·α = c·N·r − f·r, a = α·r give
/// a = (c·cos θ − sin θ)·g·m·r² / (i + m·r²) — 5/7·c·g for a solid ball on a level floor —
/// and f = m·(a + g·sin θ). That holds while friction can supply f (f ≤ μs·N; at μ = 0.6 on a
/// level floor, c up to 1.4·μ = 0.84 for a ball); beyond it the body slides and slows at
/// (μd·cos θ − sin θ)·g, its spin stopping first (the resistance torque beats friction's).
fn deceleration(c: f32, m: f32, i: f32, r: f32, slope: f32) -> f32 {
    let friction = ShapeDef::default();
    let (sin, cos) = slope.sin_cos();
    let rolling = (c * cos - sin) * G * m * r * r / (i + m * r * r);
    if rolling + G * sin <= friction.static_friction * G * cos {
        rolling
    } else {
        (friction.dynamic_friction * cos - sin) * G
    }
}

/// Steps until `done` holds or `limit` seconds pass; returns the time it first held.
fn time_until(w: &mut World, limit: f32, mut done: impl FnMut(&World) -> bool) -> Option<f32> {
    for k in 1..=(limit / DT) as usize {
        w.step(DT).unwrap();
        if done(w) {
            return Some(k as f32 * DT);
        }
    }
    None
}

/// Balls and capsules rolling on a level floor stop after v²/2a with the deceleration of
/// `deceleration`, within 1.5 % (measured: within 1.1 %); the time to stop within 5 %
/// plus a step. Both a plane and a box floor; the pair uses the larger coefficient. Above
/// c = 1.4·μ (0.9 and 1) the ball slides and stops after v²/(2·μ·g), within the same 1.5 %.
#[test]
fn rolling_bodies_stop_after_the_analytic_distance() {
    let cases = [
        // (capsule?, radius, speed, rolling resistance, box floor?)
        (false, 0.4f32, 2.0f32, 0.05f32, false),
        (false, 0.1, 5.0, 0.1, false),
        (false, 1.0, 1.0, 0.02, true),
        (false, 0.4, 2.0, 0.3, true),
        (false, 0.02, 0.5, 0.05, false),
        (true, 0.2, 2.0, 0.05, false),
        (true, 0.3, 1.5, 0.2, true),
        // Above 1.4·μ = 0.84 friction cannot keep the ball rolling: it slides, slowing at
        // μ·g. Just below (0.8) it rolls; just above (0.9) and at 1 it slides. The two
        // models differ by 5 % there, so the 1.5 % tolerance tells them apart.
        (false, 0.4, 2.0, 0.8, false),
        (false, 0.4, 2.0, 0.9, false),
        (false, 0.4, 2.0, 1.0, false),
    ];
    for (is_capsule, r, v, c, box_floor) in cases {
        let mut w = scenes::world(true);
        // The floor resists less: the pair takes the ball's value.
        let floor = material(0.0, 0.0);
        if box_floor {
            floor_box(&mut w, &floor);
        } else {
            plane(&mut w, Vec3::Y, &floor);
        }
        let geom = if is_capsule { capsule(0.5, r) } else { sphere(r) };
        let xf = Transform::new(Vec3::new(0.0, r, 0.0), Quat::IDENTITY);
        let b = dynamic(&mut w, xf, geom, &material(c, 0.0));
        let (m, i) = (w.body(b).unwrap().mass, inertia_about(&w, b, Vec3::Z));
        roll(&mut w, b, v, r);
        let a = deceleration(c, m, i, r, 0.0);
        let (distance, time) = (v * v / (2.0 * a), v / a);
        let stopped = time_until(&mut w, 2.0 * time + 1.0, |w| w.linear_velocity(b).unwrap().x <= 1e-3).unwrap();
        for _ in 0..(SETTLE / DT) as usize {
            w.step(DT).unwrap();
        }
        let x = w.transform(b).unwrap().p.x;
        println!(
            "capsule {is_capsule} r {r} v {v} c {c} box {box_floor}: distance {x:.4} m (analytic {distance:.4}), \
             stopped at {stopped:.3} s (analytic {time:.3})"
        );
        assert!((x - distance).abs() <= 0.015 * distance, "distance {x} vs {distance}");
        assert!((stopped - time).abs() <= 0.05 * time + DT, "time {stopped} vs {time}");
        assert!(!w.is_awake(b).unwrap(), "it came to rest and sleeps");
        if !is_capsule && (r, v) == (0.4, 2.0) && c == ShapeDef::default().rolling_resistance {
            // README and header: at the default, a ball at 2 m/s stops after 5.7 m.
            assert!((x - 5.7).abs() < 0.05, "default: {x} m from 2 m/s");
        }
    }
}

/// Spinning in place about the vertical, a ball stops after i·ω/(t·r·m·g) (torsional friction
/// t); a capsule lying on the floor after i·ω/((μ·L/2 + t·r)·m·g), its two end points adding
/// the patch's own twist friction μ·N·L/2. Within 2 % plus a step (measured: within a step).
#[test]
fn spinning_ball_and_capsule_stop_in_the_analytic_time() {
    let mu = ShapeDef::default().static_friction;
    for (is_capsule, r, t, omega) in [
        (false, 0.4f32, 0.05f32, 10.0f32),
        (false, 0.1, 0.2, 30.0),
        (false, 0.4, 0.5, 20.0),
        (true, 0.2, 0.05, 30.0),
        (true, 0.1, 0.0, 30.0),
    ] {
        let mut w = scenes::world(true);
        plane(&mut w, Vec3::Y, &material(0.0, 0.0));
        let half = 0.5;
        // The capsule lies along x.
        let q = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
        let (geom, xf) = if is_capsule {
            (capsule(half, r), Transform::new(Vec3::new(0.0, r, 0.0), q))
        } else {
            (sphere(r), Transform::new(Vec3::new(0.0, r, 0.0), Quat::IDENTITY))
        };
        let b = dynamic(&mut w, xf, geom, &material(0.0, t));
        for _ in 0..30 {
            w.step(DT).unwrap();
        }
        w.set_angular_velocity(b, Vec3::new(0.0, omega, 0.0)).unwrap();
        let body = w.body(b).unwrap();
        let m = body.mass;
        let i = inertia_about(&w, b, w.transform(b).unwrap().q.conjugate() * Vec3::Y);
        let lever = if is_capsule { mu * half + t * r } else { t * r };
        let time = i * omega / (lever * m * G);
        let stopped = time_until(&mut w, 2.0 * time + 1.0, |w| w.angular_velocity(b).unwrap().y <= 1e-3).unwrap();
        println!("capsule {is_capsule} r {r} t {t}: stopped at {stopped:.4} s (analytic {time:.4})");
        assert!((stopped - time).abs() <= 0.02 * time + DT, "time {stopped} vs {time}");
        for _ in 0..(SETTLE / DT) as usize {
            w.step(DT).unwrap();
        }
        assert!(!w.is_awake(b).unwrap(), "it came to rest and sleeps");
    }
}

/// Without rolling resistance a rolling ball or capsule keeps its speed on a plane and on a
/// box, however slowly it rolls (no drift, no gain: 0.5 % over 10 s), and one at rest stays at
/// rest. (Before the body-pair cache kept rounded shapes' cores, a resting ball with
/// 1e-4 rad/s of roll on a plane sped up to 0.5 rad/s by itself.)
#[test]
fn rolling_without_resistance_neither_gains_nor_loses() {
    let free = material(0.0, 0.0);
    for box_floor in [false, true] {
        for is_capsule in [false, true] {
            for speed in [0.0f32, 1.0e-4, 1.0] {
                let mut w = scenes::world(false);
                if box_floor {
                    floor_box(&mut w, &free);
                } else {
                    plane(&mut w, Vec3::Y, &free);
                }
                let r = 0.2;
                let geom = if is_capsule { capsule(0.5, r) } else { sphere(r) };
                let b = dynamic(
                    &mut w,
                    Transform::new(Vec3::new(0.0, r, 0.0), Quat::IDENTITY),
                    geom,
                    &free,
                );
                for _ in 0..30 {
                    w.step(DT).unwrap();
                }
                roll(&mut w, b, speed * r, r);
                for _ in 0..600 {
                    w.step(DT).unwrap();
                }
                let omega = w.angular_velocity(b).unwrap().length();
                let label = format!("box {box_floor} capsule {is_capsule} speed {speed}");
                assert!(
                    (omega - speed).abs() <= 0.005 * speed + 1.0e-7,
                    "{label}: {omega} rad/s"
                );
            }
        }
    }
}

/// Tiny deterministic generator (xorshift) for the randomized tests.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }
}

/// Random balls and capsules (radius 2 cm – 1 m, density 100 – 10,000 kg/m³: masses from
/// 3 g to 105 t; 0.1 – 5 m/s, rolling resistance 0.01 – 1, torsional friction 0.02 – 1, a
/// spin of up to ±5 rad/s about the slope's normal) rolling down slopes gentler than their
/// resistance and friction hold (0 – 80 % of atan(min(c, μ))): the state stays finite, a
/// ball's speed and angular speed never exceed their starting values (by 0.1 %), a capsule's
/// never exceed what its energy allows, the energy (kinetic plus potential) never grows,
/// on a level floor kinetic energy falls monotonically until the body stops (1e-6 of the
/// start's; f32 jitter at the stop reaches 1.3e-7) and stays below that, and every body comes to rest and
/// sleeps within 1.2× the longer of its analytic stopping time (v/a, `deceleration`) and
/// spin-down time (i·ω/(t·r·m·g), the ball's; a capsule's patch adds twist friction of its
/// own) plus `SETTLE`. A capsule rolls or spins, not both: rolling fast about its axis while
/// turning about the normal it precesses against the floor, and a thin one (3.4 cm radius,
/// 1.7 m long, 108 rad/s of roll, 4.8 rad/s of turn) lifts 5 mm off the floor and gains up to
/// 4 % of its energy in a step. That is not these rows: with rolling resistance and torsional
/// friction 0 it does the same, and without friction it gains more (a lift of 18 cm); with 24
/// sub-steps instead of 6 it gains nothing. At 0.3 rad of roll per sub-step the gyroscopic
/// precession tips the rod against its contacts faster than the sub-steps resolve; a limit of
/// the sub-step rate, not covered here.
/// README: all sleep by 1.2× their analytic stopping time plus 4.5 s (`SETTLE`).
#[test]
fn random_rolling_bodies_lose_energy_and_come_to_rest() {
    let mut rng = Rng(0x5eed_1234_abcd_0042);
    for case in 0..24 {
        let is_capsule = case % 3 == 2;
        let r = rng.range(0.02, 1.0);
        let density = rng.range(100.0, 10_000.0);
        let v = rng.range(0.1, 5.0);
        let c = rng.range(0.01, 1.0);
        let t = rng.range(0.02, 1.0);
        let spin = rng.range(-5.0, 5.0);
        // A capsule either rolls or spins (see the doc comment); a ball does both.
        let (v, spin) = match (is_capsule, case % 2) {
            (true, 0) => (v, 0.0),
            (true, _) => (0.0, spin),
            _ => (v, spin),
        };
        let level = case % 4 == 0;
        // Friction must hold it too: tan θ below μ as well as below c.
        let steepest = c.min(ShapeDef::default().dynamic_friction).atan();
        let slope = if level { 0.0 } else { rng.range(0.0, 0.8) * steepest };
        let mut w = scenes::world(true);
        // Downhill is +x: the plane's normal leans towards +x.
        let n = Vec3::new(slope.sin(), slope.cos(), 0.0);
        plane(&mut w, n, &material(0.0, 0.0));
        let tilt = Quat::from_rotation_z(-slope);
        let geom = if is_capsule {
            capsule(rng.range(0.05, 1.0), r)
        } else {
            sphere(r)
        };
        let def = ShapeDef {
            density,
            ..material(c, t)
        };
        let b = dynamic(&mut w, Transform::new(n * r, tilt), geom, &def);
        let downhill = Vec3::new(slope.cos(), -slope.sin(), 0.0);
        w.set_linear_velocity(b, downhill * v).unwrap();
        let omega0 = n.cross(downhill) * (v / r) + n * spin;
        w.set_angular_velocity(b, omega0).unwrap();
        let (m, i) = (w.body(b).unwrap().mass, inertia_about(&w, b, Vec3::Z));
        let a = deceleration(c, m, i, r, slope);
        // Spin about the normal: i_n·ω / (t·r·N), N = m·g·cos θ.
        let i_n = inertia_about(&w, b, tilt.conjugate() * n);
        let spin_time = i_n * spin.abs() / (t * r * m * G * slope.cos());
        let limit = 1.2 * (v / a).max(spin_time) + SETTLE;
        let energy = |w: &World| {
            let body = w.body(b).unwrap();
            body.kinetic_energy() + m * G * w.transform(b).unwrap().p.y
        };
        let (mut last_e, mut last_ke) = (energy(&w), w.body(b).unwrap().kinetic_energy());
        let (start_e, start_ke, omega0) = (last_e, last_ke, omega0.length());
        let i_min = [Vec3::X, Vec3::Y, Vec3::Z]
            .map(|axis| inertia_about(&w, b, axis))
            .into_iter()
            .fold(f32::MAX, f32::min);
        let e_scale = last_e.abs().max(m * G * r);
        let slept = time_until(&mut w, limit, |w| {
            let body = w.body(b).unwrap();
            let xf = w.transform(b).unwrap();
            assert!(
                xf.p.is_finite() && body.v.is_finite() && body.w.is_finite(),
                "case {case}: not finite"
            );
            // A ball's roll and spin are independent and both slow down; a capsule's spin can
            // turn into speed (friction at its two ends), so its bounds are what its energy
            // allows: the start's plus the potential energy released, all in one motion.
            let (v_max, w_max) = if is_capsule {
                let free = 2.0 * (start_e - m * G * xf.p.y).max(0.0);
                ((free / m).sqrt(), (free / i_min).sqrt())
            } else {
                (v, omega0)
            };
            let (speed, angular) = (body.v.length(), body.w.length());
            assert!(
                speed <= v_max * 1.001 + 1e-6,
                "case {case}: speed {speed} m/s, bound {v_max}"
            );
            assert!(
                angular <= w_max * 1.001 + 1e-6,
                "case {case}: angular speed {angular} rad/s, bound {w_max}"
            );
            let (e, ke) = (energy(w), body.kinetic_energy());
            assert!(e <= last_e + 1e-5 * e_scale, "case {case}: energy grew {last_e} -> {e}");
            let at_rest = 1e-6 * start_ke;
            if level && last_ke > at_rest {
                assert!(
                    ke <= last_ke * (1.0 + 1e-5),
                    "case {case}: kinetic energy grew {last_ke} -> {ke} (start {start_ke})"
                );
            } else if level {
                assert!(
                    ke <= at_rest,
                    "case {case}: stopped, then moved again: {ke} J (start {start_ke})"
                );
            }
            (last_e, last_ke) = (e, ke);
            !w.is_awake(b).unwrap()
        });
        println!(
            "case {case}: capsule {is_capsule} r {r:.3} mass {m:.3} v {v:.2} c {c:.3} t {t:.3} spin {spin:.2} \
             slope {:.2}°: asleep at {slept:?} s (limit {limit:.2})",
            slope.to_degrees()
        );
        assert!(slept.is_some(), "case {case}: still awake after {limit} s");
    }
}

/// Seconds from stopping to sleeping, at most: the recency-weighted motion (half-life 1 s)
/// falls from its cap of 10× the threshold to the threshold in 3.3 s, then the body must stay
/// still for `time_to_sleep` (0.5 s).
const SETTLE: f32 = 4.5; // README: "plus 4.5 s"

/// The demo (`examples/demo.rs`): a 91-box pyramid hit by four balls and four boxes dropped
/// from 9–16.5 m. The balls roll off across the ground box and stop; every body sleeps by
/// 16 s (measured: all asleep from 14.3 s) and the pyramid's apex moved less than 5 cm.
#[test]
fn demo_scene_ends_asleep() {
    let mut w = scenes::world(true);
    let (pyramid, dropped) = scenes::demo(&mut w, 6);
    let apex = *pyramid.last().unwrap();
    let start = w.transform(apex).unwrap().p;
    for _ in 0..(16.0 / DT) as usize {
        w.step(DT).unwrap();
    }
    let awake = pyramid
        .iter()
        .chain(&dropped)
        .filter(|&&b| w.is_awake(b).unwrap())
        .count();
    let moved = (w.transform(apex).unwrap().p - start).length();
    println!("demo: {awake} awake at 16 s, apex moved {moved:.4} m");
    assert_eq!(awake, 0, "bodies still awake");
    assert!(moved < 0.05, "apex moved {moved} m");
}

/// The ragdoll of `tests/joints.rs`, tipped over with its spin, lands in a heap and sleeps —
/// before rolling resistance and spin friction its sphere head kept rolling in place and held
/// the island awake. Every part asleep by 8 s (measured: 5.55 s).
#[test]
fn ragdoll_comes_to_rest_and_sleeps() {
    let mut w = scenes::world(true);
    plane(&mut w, Vec3::Y, &ShapeDef::default());
    let parts = scenes::ragdoll(&mut w, Vec3::new(0.0, 2.0, 0.0));
    for &b in &parts {
        w.set_angular_velocity(b, Vec3::new(0.5, 0.0, 2.0)).unwrap();
    }
    let slept = time_until(&mut w, 8.0, |w| parts.iter().all(|&b| !w.is_awake(b).unwrap()));
    println!("ragdoll: all asleep at {slept:?} s");
    assert!(slept.is_some(), "still awake after 8 s");
}

/// Mechanical energy (kinetic plus potential, J) of bodies.
fn mechanical_energy(w: &World, bodies: &[BodyHandle]) -> f32 {
    bodies
        .iter()
        .map(|&b| {
            let body = w.body(b).unwrap();
            body.kinetic_energy() + body.mass * G * body.center.y
        })
        .sum()
}

/// Ragdolls tipped over with seeded random spins (up to 3 rad/s about each axis): the state
/// stays finite and the mechanical energy never rises above its start (by more than 0.1 % of
/// the fall's potential energy), in 30 runs of 10 s. Whether each sleeps by then is printed,
/// not asserted (measured: 20 of 30): in the others a limb or the head ends up off the ground,
/// resting against a joint limit, and keeps circling along the frictionless limit (no contact
/// is involved; the joints have no friction to stop it).
#[test]
fn random_ragdolls_never_gain_energy() {
    let mut rng = Rng(0x00da_7a5e_ed00_0001);
    let mut asleep = 0;
    for case in 0..30 {
        let mut w = scenes::world(true);
        plane(&mut w, Vec3::Y, &ShapeDef::default());
        let parts = scenes::ragdoll(&mut w, Vec3::new(0.0, 2.0, 0.0));
        let spin = Vec3::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
        for &b in &parts {
            w.set_angular_velocity(b, spin).unwrap();
        }
        let start = mechanical_energy(&w, &parts);
        let fall: f32 = parts.iter().map(|&b| w.body(b).unwrap().mass * G * 2.0).sum();
        let mut peak = start;
        let slept = time_until(&mut w, 10.0, |w| {
            for &b in &parts {
                let body = w.body(b).unwrap();
                assert!(
                    body.center.is_finite() && body.v.is_finite() && body.w.is_finite(),
                    "case {case}"
                );
            }
            peak = peak.max(mechanical_energy(w, &parts));
            parts.iter().all(|&b| !w.is_awake(b).unwrap())
        });
        asleep += usize::from(slept.is_some());
        println!("case {case} spin {spin}: energy {start:.1} J, peak {peak:.1} J, asleep at {slept:?} s");
        assert!(
            peak <= start + 1e-3 * fall,
            "case {case}: energy rose from {start} to {peak} J"
        );
    }
    println!("{asleep} of 30 ragdolls asleep within 10 s");
}

/// A ball at rest on a slope stays there while tan θ ≤ c (friction must turn it, and the
/// resistance torque c·N·r holds up to m·g·sin θ·r with N = m·g·cos θ), and rolls away above:
/// at 95 % of atan(c) it has moved less than 1 mm after 5 s, at 105 % it has rolled off at
/// the closed-form acceleration (g·(sin θ − c·cos θ)·5/7, within 5 %).
#[test]
fn ball_holds_on_slopes_up_to_atan_c() {
    for c in [0.05f32, 0.2, 0.5] {
        for factor in [0.95f32, 1.05] {
            let slope = factor * c.atan();
            let mut w = scenes::world(false);
            let n = Vec3::new(slope.sin(), slope.cos(), 0.0);
            plane(&mut w, n, &material(0.0, 0.0));
            let r = 0.3;
            let start = n * r;
            let b = dynamic(
                &mut w,
                Transform::new(start, Quat::IDENTITY),
                sphere(r),
                &material(c, 0.0),
            );
            let seconds = 5.0;
            for _ in 0..(seconds / DT) as usize {
                w.step(DT).unwrap();
            }
            let moved = (w.transform(b).unwrap().p - start).length();
            let a = G * (slope.sin() - c * slope.cos()) * 5.0 / 7.0;
            println!(
                "c {c} slope {:.2}°: moved {moved:.5} m (rolling: {:.4} m)",
                slope.to_degrees(),
                0.5 * a * seconds * seconds
            );
            if factor < 1.0 {
                assert!(moved < 1e-3, "c {c}: slid or rolled {moved} m below atan(c)");
            } else {
                let expected = 0.5 * a * seconds * seconds;
                assert!(
                    (moved - expected).abs() <= 0.05 * expected,
                    "c {c}: {moved} vs {expected}"
                );
            }
        }
    }
}

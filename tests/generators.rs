//! Force and contact generators against analytic answers: spring period, stiff-spring
//! frequency and decay, bungee slack, buoyancy equilibrium (Archimedes), drag terminal
//! velocity, rods and cables between bodies, explosions, attachment rules.

use hearth::generators::{End, GeneratorDef, Spring};
use hearth::math::{Quat, Transform, Vec3};
use hearth::particles::ParticleDef;
use hearth::{BodyDef, BodyType, Error, Geometry, ShapeDef, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;

fn world(gravity: Vec3) -> World {
    World::new(WorldSettings {
        gravity,
        enable_sleep: false,
        ..Default::default()
    })
    .unwrap()
}

fn particle(w: &mut World, p: Vec3, inverse_mass: f32) -> hearth::pool::Handle {
    w.create_particle(&ParticleDef {
        position: p,
        inverse_mass,
        collide: false,
        ..Default::default()
    })
    .unwrap()
}

/// A dynamic sphere body of mass `m` (no collisions matter: nothing else is there).
fn ball(w: &mut World, p: Vec3, m: f32) -> hearth::BodyHandle {
    let b = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(p, Quat::IDENTITY),
            allow_sleep: false,
            ..Default::default()
        })
        .unwrap();
    let r = 0.1f32;
    let density = m / (4.0 / 3.0 * std::f32::consts::PI * r * r * r);
    w.create_shape(
        b,
        &ShapeDef {
            density,
            ..Default::default()
        },
        &Geometry::Sphere {
            center: Vec3::ZERO,
            radius: r,
        },
    )
    .unwrap();
    b
}

/// Times of upward zero crossings of `f(t)` sampled every step (linear interpolation).
fn upward_crossings(samples: &[(f32, f32)]) -> Vec<f32> {
    let mut out = Vec::new();
    for w in samples.windows(2) {
        let ((t0, y0), (t1, y1)) = (w[0], w[1]);
        if y0 < 0.0 && y1 >= 0.0 {
            out.push(t0 + (t1 - t0) * (-y0 / (y1 - y0)));
        }
    }
    out
}

fn mean_period(crossings: &[f32]) -> f32 {
    (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f32
}

fn spring(other: End, rest_length: f32, stiffness: f32, damping: f32) -> Spring {
    Spring {
        other,
        local_point: Vec3::ZERO,
        rest_length,
        stiffness,
        damping,
    }
}

#[test]
fn spring_period_matches_two_pi_sqrt_m_over_k() {
    let (m, k) = (2.0f32, 50.0f32);
    let expected = 2.0 * std::f32::consts::PI * (m / k).sqrt();
    // A particle and a body, each on an anchored spring (rest length 1, anchor at the
    // origin), displaced 0.2 m along x with no gravity.
    let mut w = world(Vec3::ZERO);
    let p = particle(&mut w, Vec3::new(1.2, 0.0, 0.0), 1.0 / m);
    let b = ball(&mut w, Vec3::new(0.0, 0.0, 1.2), m);
    let g = w
        .create_generator(&GeneratorDef::Spring(spring(End::World(Vec3::ZERO), 1.0, k, 0.0)))
        .unwrap();
    w.attach_particle(g, p).unwrap();
    w.attach_body(g, b).unwrap();
    let (mut sp, mut sb) = (Vec::new(), Vec::new());
    for i in 0..1200 {
        w.step(DT).unwrap();
        let t = (i + 1) as f32 * DT;
        sp.push((t, w.particle_position(p).unwrap().x - 1.0));
        sb.push((t, w.transform(b).unwrap().p.z - 1.0));
    }
    for (name, s) in [("particle", &sp), ("body", &sb)] {
        let c = upward_crossings(s);
        assert!(c.len() >= 8, "{name}: {} crossings", c.len());
        let period = mean_period(&c);
        let err = (period - expected).abs() / expected;
        println!(
            "spring period ({name}): {period:.5} s, expected {expected:.5} s, error {:.4}%",
            100.0 * err
        );
        // Measured 0.029 % (particle, look-ahead spring) and 0.0008 % (body).
        assert!(err < 5e-4, "{name}: period {period}, expected {expected}");
    }
}

#[test]
fn spring_between_two_particles_keeps_momentum_and_oscillates() {
    // Two 1 kg particles on a spring: the relative motion has the reduced mass m/2.
    let k = 40.0f32;
    let mut w = world(Vec3::ZERO);
    let a = particle(&mut w, Vec3::new(-0.7, 0.0, 0.0), 1.0);
    let b = particle(&mut w, Vec3::new(0.7, 0.0, 0.0), 1.0);
    let g = w
        .create_generator(&GeneratorDef::Spring(spring(End::Particle(b), 1.0, k, 0.0)))
        .unwrap();
    w.attach_particle(g, a).unwrap();
    let mut s = Vec::new();
    for i in 0..900 {
        w.step(DT).unwrap();
        let (pa, pb) = (w.particle_position(a).unwrap(), w.particle_position(b).unwrap());
        s.push(((i + 1) as f32 * DT, (pb - pa).length() - 1.0));
        let momentum = w.particle_velocity(a).unwrap() + w.particle_velocity(b).unwrap();
        assert!(momentum.length() < 1e-4, "momentum {momentum}");
        assert!((pa + pb).length() < 1e-3, "centre moved");
    }
    let expected = 2.0 * std::f32::consts::PI * (0.5 / k).sqrt();
    let period = mean_period(&upward_crossings(&s));
    assert!(
        (period - expected).abs() / expected < 0.01,
        "period {period}, expected {expected}"
    );
}

/// Runs a particle on a stiff spring with `dt` chosen so one damped period is exactly `steps`
/// steps; returns (measured ratio of displacements one period apart, expected ratio,
/// measured period, expected period).
fn stiff_spring_run(k: f32, c: f32, m: f32, substeps: u32, body: bool) -> (f32, f32, f32, f32) {
    let omega_d = (k / m - 0.25 * (c / m) * (c / m)).sqrt();
    let period = 2.0 * std::f32::consts::PI / omega_d;
    let steps = 40usize;
    let dt = period / steps as f32;
    let mut w = World::new(WorldSettings {
        gravity: Vec3::ZERO,
        enable_sleep: false,
        substeps,
        ..Default::default()
    })
    .unwrap();
    let g = w
        .create_generator(&GeneratorDef::StiffSpring {
            anchor: End::World(Vec3::ZERO),
            local_point: Vec3::ZERO,
            stiffness: k,
            damping: c,
        })
        .unwrap();
    let (p, b) = if body {
        let b = ball(&mut w, Vec3::new(1.0, 0.0, 0.0), m);
        w.attach_body(g, b).unwrap();
        (None, Some(b))
    } else {
        let p = particle(&mut w, Vec3::new(1.0, 0.0, 0.0), 1.0 / m);
        w.attach_particle(g, p).unwrap();
        (Some(p), None)
    };
    let mut xs = vec![1.0f32];
    let mut samples = vec![(0.0f32, 1.0f32)];
    for i in 0..steps * 4 {
        w.step(dt).unwrap();
        let x = match (p, b) {
            (Some(p), _) => w.particle_position(p).unwrap().x,
            (_, Some(b)) => w.transform(b).unwrap().p.x,
            _ => unreachable!(),
        };
        xs.push(x);
        samples.push(((i + 1) as f32 * dt, x));
    }
    // The sampled motion is exactly A e^{-ct/2m} cos(ω t + φ): displacements one damped
    // period apart have the ratio e^{-c T / 2m}.
    let (x1, x3) = (xs[steps + 3], xs[3 * steps + 3]);
    let measured = (x3 / x1).sqrt();
    let expected = (-0.5 * c / m * period).exp();
    let crossings = upward_crossings(&samples);
    (measured, expected, mean_period(&crossings), period)
}

#[test]
fn stiff_spring_decay_and_frequency_are_exact() {
    // Soft and very stiff springs (k/m · dt² up to 2.5: an explicit spring explodes there),
    // on particles and on rigid bodies.
    for body in [false, true] {
        for &(k, c, m, n) in &[
            (100.0f32, 2.0f32, 1.0f32, 4u32),
            (4.0e4, 40.0, 2.0, 1),
            (900.0, 30.0, 1.0, 8),
        ] {
            let (measured, expected, period, expected_period) = stiff_spring_run(k, c, m, n, body);
            let err = (measured - expected).abs() / expected;
            let perr = (period - expected_period).abs() / expected_period;
            println!(
                "stiff spring ({}) k={k} c={c} m={m} substeps={n}: decay per period {measured:.6} (exact {expected:.6}, error {:.4}%), period error {:.4}%",
                if body { "body" } else { "particle" },
                100.0 * err,
                100.0 * perr
            );
            // "Exact": measured 0.0000 % for both (f32 rounding); 1e-5 bounds it.
            assert!(err < 1e-5, "decay {measured}, expected {expected}");
            assert!(perr < 1e-5, "period {period}, expected {expected_period}");
        }
    }
}

#[test]
fn stiff_spring_is_stable_where_an_explicit_spring_explodes() {
    // k/m = 1e6 at 60 Hz: ω·dt ≈ 17. The stiff spring stays bounded and settles.
    let mut w = world(Vec3::ZERO);
    let p = particle(&mut w, Vec3::new(0.5, 0.0, 0.0), 1.0);
    let g = w
        .create_generator(&GeneratorDef::StiffSpring {
            anchor: End::World(Vec3::ZERO),
            local_point: Vec3::ZERO,
            stiffness: 1.0e6,
            damping: 10.0,
        })
        .unwrap();
    w.attach_particle(g, p).unwrap();
    // The exact damped oscillator from rest at 0.5 m: ζ = c/(2√(k·m)) = 0.005, so
    // |x(t)| ≤ 0.5·e^(−ζωt)/√(1−ζ²) with ζω = c/2m = 5/s. The stiff spring's step has the
    // exact eigenvalues (so the exact decay per step), not the exact eigenvectors: sampled at
    // ω·dt ≈ 17 its amplitude stays within 3 % of that envelope (measured at most 2.7 %
    // above it, over all 10 s), so it decays at the exact rate, to 1e-22 m after 10 s.
    let mut worst = 0.0f32;
    for k in 1..=600 {
        w.step(DT).unwrap();
        let t = k as f32 * DT;
        let envelope = 0.5 * (-5.0 * t).exp() / (1.0f32 - 0.005 * 0.005).sqrt();
        let x = w.particle_position(p).unwrap().length();
        worst = worst.max(x / envelope);
        assert!(x <= 1.03 * envelope, "at {t} s: {x} m, envelope {envelope} m");
    }
    println!("stiff spring: largest amplitude over the exact envelope {worst}");
    assert!(w.particle_position(p).unwrap().length() < 1e-20);
}

#[test]
fn bungee_slack_has_no_force() {
    let mut w = world(Vec3::ZERO);
    // Closer than the rest length, moving slowly: no force, so the velocity stays exact.
    let p = particle(&mut w, Vec3::new(0.5, 0.0, 0.0), 1.0);
    w.set_particle_velocity(p, Vec3::new(0.3, 0.0, 0.0)).unwrap();
    let g = w
        .create_generator(&GeneratorDef::Bungee(spring(End::World(Vec3::ZERO), 2.0, 100.0, 1.0)))
        .unwrap();
    w.attach_particle(g, p).unwrap();
    for _ in 0..60 {
        w.step(DT).unwrap();
        let x = w.particle_position(p).unwrap().x;
        if x < 2.0 {
            assert_eq!(w.particle_velocity(p).unwrap(), Vec3::new(0.3, 0.0, 0.0));
        }
    }
    // Stretched past the rest length it pulls back: at 0.3 m/s against k = 100 N/m it
    // turns within 0.3/10 m and comes back at (nearly) the same speed.
    while w.particle_position(p).unwrap().x < 2.0 {
        w.step(DT).unwrap();
    }
    let mut max_x = 0.0f32;
    for _ in 0..60 {
        w.step(DT).unwrap();
        max_x = max_x.max(w.particle_position(p).unwrap().x);
    }
    let v = w.particle_velocity(p).unwrap().x;
    assert!(max_x < 2.035 && (-0.3..-0.25).contains(&v), "max x {max_x}, v {v}");
    // A body in slack: the same.
    let mut w = world(Vec3::ZERO);
    let b = ball(&mut w, Vec3::new(0.0, 0.0, 1.0), 1.0);
    w.set_linear_velocity(b, Vec3::new(0.0, 0.0, -0.1)).unwrap();
    let g = w
        .create_generator(&GeneratorDef::Bungee(spring(End::World(Vec3::ZERO), 3.0, 100.0, 0.0)))
        .unwrap();
    w.attach_body(g, b).unwrap();
    for _ in 0..60 {
        w.step(DT).unwrap();
    }
    let v = w.linear_velocity(b).unwrap();
    assert!((v - Vec3::new(0.0, 0.0, -0.1)).length() < 1e-6, "{v}");
}

#[test]
fn buoyancy_equilibrium_depth_follows_archimedes() {
    // Fraction submerged at rest f = m / (ρ V); with the linear model the centre of
    // buoyancy sits at depth (2f - 1)·max_depth below the surface.
    let g = 9.81f32;
    let (rho, volume, max_depth, surface) = (1000.0f32, 0.002f32, 0.25f32, 1.0f32);
    for &m in &[0.6f32, 1.0, 1.6] {
        let f = m / (rho * volume);
        let depth = (2.0 * f - 1.0) * max_depth;
        let expected_y = surface - depth;
        let mut w = world(Vec3::new(0.0, -g, 0.0));
        let p = particle(&mut w, Vec3::new(0.0, surface + 0.5, 0.0), 1.0 / m);
        let b = ball(&mut w, Vec3::new(3.0, surface + 0.5, 0.0), m);
        let buoy = w
            .create_generator(&GeneratorDef::Buoyancy {
                normal: Vec3::Y,
                surface,
                max_depth,
                volume,
                liquid_density: rho,
                local_point: Vec3::ZERO,
            })
            .unwrap();
        // Drag settles the bobbing.
        let drag = w.create_generator(&GeneratorDef::Drag { k1: 2.0, k2: 0.0 }).unwrap();
        for gen in [buoy, drag] {
            w.attach_particle(gen, p).unwrap();
            w.attach_body(gen, b).unwrap();
        }
        for _ in 0..1800 {
            w.step(DT).unwrap();
        }
        let yp = w.particle_position(p).unwrap().y;
        let yb = w.transform(b).unwrap().p.y;
        for (name, y) in [("particle", yp), ("body", yb)] {
            let err = ((surface - y) - depth).abs() / (2.0 * max_depth * f);
            println!(
                "buoyancy m={m}: {name} rests at depth {:.5} m, Archimedes {depth:.5} m (error {:.3}% of the submerged height)",
                surface - y,
                100.0 * err
            );
            // Measured at most 0.001 % of the submerged height.
            assert!(err < 1e-4, "{name}: y {y}, expected {expected_y}");
        }
    }
}

#[test]
fn drag_terminal_velocity_matches_analytic() {
    let g = 9.81f32;
    let (k1, k2) = (0.5f32, 0.2f32);
    for &m in &[0.5f32, 2.0] {
        // m g = k1 v + k2 v²
        let vt = (-k1 + (k1 * k1 + 4.0 * k2 * m * g).sqrt()) / (2.0 * k2);
        let mut w = world(Vec3::new(0.0, -g, 0.0));
        let p = particle(&mut w, Vec3::new(0.0, 1000.0, 0.0), 1.0 / m);
        let b = ball(&mut w, Vec3::new(5.0, 1000.0, 0.0), m);
        let drag = w.create_generator(&GeneratorDef::Drag { k1, k2 }).unwrap();
        w.attach_particle(drag, p).unwrap();
        w.attach_body(drag, b).unwrap();
        for _ in 0..1200 {
            w.step(DT).unwrap();
        }
        for (name, v) in [
            ("particle", -w.particle_velocity(p).unwrap().y),
            ("body", -w.linear_velocity(b).unwrap().y),
        ] {
            let err = (v - vt).abs() / vt;
            println!(
                "drag m={m}: {name} terminal velocity {v:.5} m/s, analytic {vt:.5} m/s, error {:.4}%",
                100.0 * err
            );
            // Measured at most 0.0009 %.
            assert!(err < 2e-5, "{name}: {v}, expected {vt}");
        }
    }
}

#[test]
fn extra_gravity_adds_to_world_gravity() {
    let mut w = world(Vec3::new(0.0, -9.81, 0.0));
    let p = particle(&mut w, Vec3::ZERO, 0.5);
    let b = ball(&mut w, Vec3::new(4.0, 0.0, 0.0), 3.0);
    let q = particle(&mut w, Vec3::new(8.0, 0.0, 0.0), 1.0);
    let g = w
        .create_generator(&GeneratorDef::Gravity {
            acceleration: Vec3::new(2.0, 0.0, 0.0),
        })
        .unwrap();
    w.attach_particle(g, p).unwrap();
    w.attach_body(g, b).unwrap();
    for _ in 0..60 {
        w.step(DT).unwrap();
    }
    let vp = w.particle_velocity(p).unwrap();
    let vb = w.linear_velocity(b).unwrap();
    let vq = w.particle_velocity(q).unwrap();
    assert!((vp - Vec3::new(2.0, -9.81, 0.0)).length() < 1e-3, "{vp}");
    assert!((vb - Vec3::new(2.0, -9.81, 0.0)).length() < 1e-3, "{vb}");
    assert!(
        (vq - Vec3::new(0.0, -9.81, 0.0)).length() < 1e-3,
        "unattached particle: {vq}"
    );
}

#[test]
fn explosion_pushes_outwards_and_falls_off() {
    let mut w = world(Vec3::ZERO);
    let near = particle(&mut w, Vec3::new(1.0, 0.0, 0.0), 1.0);
    let far = particle(&mut w, Vec3::new(0.0, 0.0, -3.0), 1.0);
    let out = particle(&mut w, Vec3::new(0.0, 50.0, 0.0), 1.0);
    let b = ball(&mut w, Vec3::new(0.0, 2.0, 0.0), 1.0);
    w.create_generator(&GeneratorDef::Explosion {
        center: Vec3::ZERO,
        blast_radius: 4.0,
        blast_impulse: 8.0,
        shock_speed: 0.0,
        shock_thickness: 0.0,
        shock_force: 0.0,
        max_radius: 0.0,
        affect_all: true,
    })
    .unwrap();
    w.step(DT).unwrap();
    // Impulse 8 (1 - d/4) on 1 kg.
    let vn = w.particle_velocity(near).unwrap();
    let vf = w.particle_velocity(far).unwrap();
    let vb = w.linear_velocity(b).unwrap();
    assert!((vn - Vec3::new(6.0, 0.0, 0.0)).length() < 1e-3, "{vn}");
    assert!((vf - Vec3::new(0.0, 0.0, -2.0)).length() < 1e-3, "{vf}");
    assert!((vb - Vec3::new(0.0, 4.0, 0.0)).length() < 1e-2, "{vb}");
    assert_eq!(w.particle_velocity(out).unwrap(), Vec3::ZERO);
    // The blast happens once.
    w.step(DT).unwrap();
    assert!((w.particle_velocity(near).unwrap() - vn).length() < 1e-6);

    // A shock wave: it reaches a particle at 5 m after ~0.5 s at 10 m/s and pushes it out.
    let mut w = world(Vec3::ZERO);
    let p = particle(&mut w, Vec3::new(0.0, 0.0, 5.0), 1.0);
    let q = particle(&mut w, Vec3::new(0.0, 0.0, 15.0), 1.0);
    let e = w
        .create_generator(&GeneratorDef::Explosion {
            center: Vec3::ZERO,
            blast_radius: 0.0,
            blast_impulse: 0.0,
            shock_speed: 10.0,
            shock_thickness: 1.0,
            shock_force: 50.0,
            max_radius: 10.0,
            affect_all: false,
        })
        .unwrap();
    w.attach_particle(e, p).unwrap();
    w.attach_particle(e, q).unwrap();
    let mut first_push = None;
    for i in 0..120 {
        w.step(DT).unwrap();
        if first_push.is_none() && w.particle_velocity(p).unwrap().z > 0.0 {
            first_push = Some(i as f32 * DT);
        }
    }
    let t = first_push.expect("the shock wave reached the particle");
    assert!((t - 0.45).abs() < 0.05, "shock arrived at {t}");
    assert!(w.particle_velocity(p).unwrap().z > 1.0);
    assert_eq!(w.particle_velocity(q).unwrap(), Vec3::ZERO, "beyond max_radius");
}

#[test]
fn rod_between_bodies_holds_length_and_cable_goes_slack() {
    // A body hangs from a world anchor by a rod and swings; another hangs by a cable and is
    // thrown upwards: the cable goes slack (no pull) and then catches it.
    let mut w = world(Vec3::new(0.0, -9.81, 0.0));
    let b = ball(&mut w, Vec3::new(1.0, 5.0, 0.0), 2.0);
    let rod = w
        .create_generator(&GeneratorDef::Rod {
            a: End::World(Vec3::new(0.0, 6.0, 0.0)),
            b: End::Body {
                body: b,
                local: Vec3::ZERO,
            },
            length: 2.0f32.sqrt(),
        })
        .unwrap();
    let mut worst = 0.0f32;
    for _ in 0..600 {
        w.step(DT).unwrap();
        let d = (w.transform(b).unwrap().p - Vec3::new(0.0, 6.0, 0.0)).length();
        worst = worst.max((d - 2.0f32.sqrt()).abs());
    }
    println!("rigid rod: worst length error {worst:.5} m");
    // A generated contact keeps one normal per step, so a swinging rod stretches by about
    // (v·dt)²/2L between steps (1.3 mm here); distance joints re-aim every sub-step.
    assert!(worst < 1.5e-3, "rod length error {worst}"); // measured 1.32 mm
    assert!(w.generator(rod).is_ok());

    let c = ball(&mut w, Vec3::new(10.0, 4.0, 0.0), 1.0);
    w.create_generator(&GeneratorDef::Cable {
        a: End::World(Vec3::new(10.0, 6.0, 0.0)),
        b: End::Body {
            body: c,
            local: Vec3::ZERO,
        },
        max_length: 2.0,
        restitution: 0.0,
    })
    .unwrap();
    w.set_linear_velocity(c, Vec3::new(0.0, 3.0, 0.0)).unwrap();
    // Slack while it flies up: free flight, v = 3 - g t.
    for i in 0..20 {
        w.step(DT).unwrap();
        let v = w.linear_velocity(c).unwrap().y;
        let expected = 3.0 - 9.81 * (i + 1) as f32 * DT;
        assert!(
            (v - expected).abs() < 1e-3,
            "slack cable pulled: v {v}, free flight {expected}"
        );
    }
    for _ in 0..300 {
        w.step(DT).unwrap();
    }
    let d = (w.transform(c).unwrap().p - Vec3::new(10.0, 6.0, 0.0)).length();
    assert!(d < 2.0 + 0.01, "the cable caught the body: {d}");
}

#[test]
fn destroying_a_body_detaches_it_everywhere() {
    let mut w = world(Vec3::ZERO);
    let b = ball(&mut w, Vec3::ZERO, 1.0);
    let b2 = ball(&mut w, Vec3::new(3.0, 0.0, 0.0), 1.0);
    let drag = w.create_generator(&GeneratorDef::Drag { k1: 1.0, k2: 0.0 }).unwrap();
    let sp = w
        .create_generator(&GeneratorDef::Spring(spring(
            End::Body {
                body: b,
                local: Vec3::ZERO,
            },
            1.0,
            10.0,
            0.0,
        )))
        .unwrap();
    w.attach_body(drag, b).unwrap();
    w.attach_body(drag, b2).unwrap();
    w.attach_body(sp, b2).unwrap();
    assert!(
        matches!(w.attach_body(drag, b), Err(Error::InvalidArgument(_))),
        "attached twice"
    );
    assert_eq!(w.generator_attachment_counts(drag).unwrap(), (2, 0));
    w.destroy_body(b).unwrap();
    assert_eq!(w.generator_attachment_counts(drag).unwrap(), (1, 0));
    assert!(w.generator(sp).unwrap().broken, "a spring whose end is gone stops");
    // The spring no longer pulls b2.
    for _ in 0..10 {
        w.step(DT).unwrap();
    }
    assert_eq!(w.linear_velocity(b2).unwrap(), Vec3::ZERO);
    // Stale ids.
    w.destroy_generator(drag).unwrap();
    assert_eq!(w.destroy_generator(drag), Err(Error::InvalidId("generator")));
    assert!(w.attach_body(drag, b2).is_err());
    // Rods take no attachments.
    let rod = w
        .create_generator(&GeneratorDef::Rod {
            a: End::World(Vec3::ZERO),
            b: End::Body {
                body: b2,
                local: Vec3::ZERO,
            },
            length: 3.0,
        })
        .unwrap();
    assert!(matches!(w.attach_body(rod, b2), Err(Error::InvalidArgument(_))));
    // A rod to a destroyed body cannot be created.
    assert!(w
        .create_generator(&GeneratorDef::Rod {
            a: End::World(Vec3::ZERO),
            b: End::Body {
                body: b,
                local: Vec3::ZERO,
            },
            length: 1.0,
        })
        .is_err());
}

//! Issue 12: the supported ranges (README "Supported ranges", the header's preamble). Every
//! documented limit equals the library's; time steps at both ends of their range in every
//! subsystem, against free fall; random steps inside the range; each accepted extreme leaves
//! the world finite and within the speed limit; each value outside is refused with a message
//! naming the parameter and changes nothing. The C side is `tests/c/test_ranges.c` and the
//! fuzzer `tests/c/fuzz_api.c`.

use hearth::error::*;
use hearth::generators::{End, GeneratorDef};
use hearth::joints::HingeParams;
use hearth::math::{Quat, Transform, Vec3};
use hearth::particles::emitter::BurstDef;
use hearth::particles::ParticleDef;
use hearth::soft::{mesh, SoftBodyDef, SoftBodyHandle};
use hearth::{
    BodyDef, BodyHandle, BodyType, Geometry, Integrator, JointDef, JointKind, ShapeDef, World, WorldSettings,
};

const G: f32 = 9.81;

fn world(settings: WorldSettings) -> World {
    World::new(WorldSettings {
        enable_sleep: false,
        ..settings
    })
    .unwrap()
}

fn ground(w: &mut World) {
    let g = w.create_body(&BodyDef::default()).unwrap();
    w.create_shape(
        g,
        &ShapeDef::default(),
        &Geometry::Plane {
            normal: Vec3::Y,
            offset: 0.0,
        },
    )
    .unwrap();
}

fn dynamic(w: &mut World, p: Vec3) -> BodyHandle {
    w.create_body(&BodyDef {
        body_type: BodyType::Dynamic,
        transform: Transform::new(p, Quat::IDENTITY),
        ..Default::default()
    })
    .unwrap()
}

fn sphere(w: &mut World, p: Vec3, radius: f32, density: f32) -> BodyHandle {
    let b = dynamic(w, p);
    w.create_shape(
        b,
        &ShapeDef {
            density,
            ..Default::default()
        },
        &Geometry::Sphere {
            center: Vec3::ZERO,
            radius,
        },
    )
    .unwrap();
    b
}

fn cube(w: &mut World, p: Vec3, half: f32) -> BodyHandle {
    let b = dynamic(w, p);
    w.create_shape(
        b,
        &ShapeDef::default(),
        &Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::splat(half),
        },
    )
    .unwrap();
    b
}

fn particle(w: &mut World, p: Vec3) -> hearth::pool::Handle {
    w.create_particle(&ParticleDef {
        position: p,
        collide: false,
        allow_sleep: false,
        ..Default::default()
    })
    .unwrap()
}

fn soft_ball(w: &mut World, p: Vec3) -> SoftBodyHandle {
    let def = SoftBodyDef {
        transform: Transform::new(p, Quat::IDENTITY),
        pressure: 200.0,
        damping: 0.0,
        ..Default::default()
    };
    w.create_soft_body(&def, &mesh::icosphere(0.5, 2), None).unwrap()
}

/// Everything in the world (and the soft bodies `soft`) is finite and no faster than
/// `max_linear_speed`.
fn assert_sane(w: &World, soft: &[SoftBodyHandle], when: &str) {
    let max = w.settings.max_linear_speed * 1.0001;
    for (h, b) in w.bodies.iter() {
        assert!(
            b.xf.p.is_finite() && b.xf.q.is_finite() && b.v.is_finite() && b.w.is_finite(),
            "{when}: body {} is not finite: {:?} v {} w {}",
            h.index,
            b.xf,
            b.v,
            b.w
        );
        if b.is_dynamic() {
            assert!(b.v.length() <= max, "{when}: body {} at {} m/s", h.index, b.v.length());
        }
    }
    for (i, (p, v)) in w.particles.pos.iter().zip(&w.particles.vel).enumerate() {
        assert!(p.is_finite() && v.is_finite(), "{when}: particle {i} is not finite");
        assert!(v.length() <= max, "{when}: particle {i} at {} m/s", v.length());
    }
    for &h in soft {
        let s = w.soft_body(h).unwrap();
        assert!(
            s.pos.iter().chain(&s.vel).all(|v| v.is_finite()),
            "{when}: soft body {} is not finite",
            h.index
        );
        let fastest = s.vel.iter().map(|v| v.length()).fold(0.0f32, f32::max);
        assert!(
            fastest <= max,
            "{when}: soft body {} has a vertex at {fastest} m/s",
            h.index
        );
    }
}

// ----------------------------------------------------------------- the documented limits

/// The numbers README's "Supported ranges" table and the header's preamble state are the
/// library's limits.
#[test]
fn documented_ranges_are_the_enforced_ones() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let header = std::fs::read_to_string(root.join("include/hearth.h")).unwrap();
    let table = &readme[readme.find("## Supported ranges").expect("README section")..];
    let preamble = &header[..header.find("*/").unwrap()];
    // README: f32 resolves 8 mm at 100 km.
    let ulp = f32::from_bits(MAX_COORDINATE.to_bits() + 1) - MAX_COORDINATE;
    assert!(ulp <= 0.008, "{ulp}");
    // Numbers as the documents write them: 0.001, 10000, 1e12.
    let n = |x: f32| if x >= 1.0e6 { format!("{x:e}") } else { format!("{x}") };
    let expected = [
        (
            "time step",
            format!("0, or {} to {} s", n(MIN_TIME_STEP), n(MAX_TIME_STEP)),
        ),
        ("size", format!("{} to {} m", n(MIN_LENGTH), n(MAX_LENGTH))),
        ("position", format!("±{} m", n(MAX_COORDINATE))),
        ("max_linear_speed", format!("up to {} m/s", n(MAX_SPEED))),
        ("angular velocity", "up to the world's max_angular_speed".to_string()),
        ("acceleration", format!("up to {} m/s²", n(MAX_ACCELERATION))),
        ("gravity scale", format!("±{}", n(MAX_GRAVITY_SCALE))),
        ("force", format!("up to {} N", n(MAX_FORCE))),
        ("impulse", format!("up to {} N·s", n(MAX_IMPULSE))),
        (
            "density",
            format!("0, or {} to {} kg/m³", n(MIN_DENSITY), n(MAX_DENSITY)),
        ),
        ("inverse mass", format!("up to {} 1/kg", n(MAX_INVERSE_MASS))),
        ("damping", format!("up to {} 1/s", n(MAX_DAMPING))),
    ];
    // A README table row is `| input | range | why |`; a preamble line `*   input: range`.
    let readme_rows = table.lines().filter_map(|l| {
        let cells: Vec<&str> = l.split('|').collect();
        (cells.len() > 3).then(|| (cells[1].to_string(), cells[2].to_string()))
    });
    let header_rows = preamble.lines().filter_map(|l| {
        let l = l.strip_prefix(" *   ")?;
        let (input, range) = l.split_once(':')?;
        Some((input.to_string(), range.to_string()))
    });
    let readme_rows: Vec<(String, String)> = readme_rows.collect();
    let header_rows: Vec<(String, String)> = header_rows.collect();
    for (what, text) in &expected {
        for (rows, name) in [(&readme_rows, "README"), (&header_rows, "include/hearth.h")] {
            let (_, line) = rows
                .iter()
                .find(|(input, _)| input.contains(what))
                .unwrap_or_else(|| panic!("{name}: no row about {what}"));
            assert!(line.contains(text.as_str()), "{name}: \"{line}\" should say \"{text}\"");
        }
    }
    // The angular speed limit's default and its largest setting, as README words them.
    let (_, angular) = readme_rows
        .iter()
        .find(|(i, _)| i.contains("angular velocity"))
        .unwrap();
    let default = hearth::world::DEFAULT_MAX_ANGULAR_SPEED;
    assert!((default - 100.0 * std::f32::consts::PI).abs() < 1e-3);
    for text in [
        format!("default 100π ≈ {default:.2} rad/s"),
        format!("settable up to {} rad/s", n(MAX_ANGULAR_SPEED)),
    ] {
        assert!(angular.contains(&text), "README: \"{angular}\" should say \"{text}\"");
    }
}

// ----------------------------------------------------------------------------- time steps

/// A step outside [MIN_TIME_STEP, MAX_TIME_STEP] (other than 0) is refused and changes
/// nothing; 0 does nothing; both ends are accepted.
#[test]
fn time_steps_outside_the_range_are_refused() {
    let mut w = world(WorldSettings::default());
    ground(&mut w);
    let b = cube(&mut w, Vec3::new(0.0, 2.0, 0.0), 0.5);
    let p = particle(&mut w, Vec3::new(1.0, 2.0, 0.0));
    let s = soft_ball(&mut w, Vec3::new(-2.0, 2.0, 0.0));
    w.step(1.0 / 60.0).unwrap();
    let state = |w: &World| {
        (
            w.transform(b).unwrap(),
            w.linear_velocity(b).unwrap(),
            w.particle_position(p).unwrap(),
            w.soft_body(s).unwrap().pos.clone(),
        )
    };
    let before = state(&w);
    for dt in [
        1e-20,
        1e-40, // a denormal
        MIN_TIME_STEP * 0.99,
        MAX_TIME_STEP * 1.01,
        1e6,
        -1.0 / 60.0,
        -MIN_TIME_STEP,
        f32::NAN,
        f32::INFINITY,
    ] {
        match w.step(dt) {
            Err(Error::InvalidArgument(m)) => assert!(m.starts_with("dt must be"), "{m}"),
            r => panic!("dt {dt}: {r:?}"),
        }
        assert!(before == state(&w), "a refused step (dt {dt}) changed the world");
    }
    w.step(0.0).unwrap();
    assert!(before == state(&w), "a step of 0 changed the world");
    w.step(MIN_TIME_STEP).unwrap();
    w.step(MAX_TIME_STEP).unwrap();
}

/// Free fall, the analytic answer of every integrator here: semi-implicit Euler over `m`
/// sub-steps of `h` gives v = −g·m·h exactly and a drop of g·h²·m(m + 1)/2. Checked at both
/// ends of the range for bodies and particles (1,000 steps of 1 ms; one step of 0.1 s),
/// and for a soft body's mean vertex velocity in the longest step. (In 1 ms steps a soft
/// body's vertices move less per sub-step than f32 resolves: its velocities come from
/// position differences, so it falls with a visible error there — reported, not asserted.)
#[test]
fn free_fall_is_exact_at_the_shortest_and_the_longest_step() {
    for (dt, steps) in [(MIN_TIME_STEP, 1000usize), (MAX_TIME_STEP, 1)] {
        let mut w = world(WorldSettings::default());
        let b = sphere(&mut w, Vec3::new(0.0, 10.0, 0.0), 0.5, 1000.0);
        let p = particle(&mut w, Vec3::new(5.0, 10.0, 0.0));
        let s = soft_ball(&mut w, Vec3::new(-5.0, 10.0, 0.0));
        for _ in 0..steps {
            w.step(dt).unwrap();
        }
        let m = 6.0 * steps as f32;
        let h = dt / 6.0;
        let (v, drop) = (-G * m * h, G * h * h * m * (m + 1.0) / 2.0);
        let body = (w.linear_velocity(b).unwrap().y, 10.0 - w.transform(b).unwrap().p.y);
        let part = (
            w.particle_velocity(p).unwrap().y,
            10.0 - w.particle_position(p).unwrap().y,
        );
        for (what, (got_v, got_drop)) in [("body", body), ("particle", part)] {
            assert!(
                (got_v - v).abs() < 1e-4 * v.abs(),
                "dt {dt}: {what} v {got_v}, expected {v}"
            );
            assert!(
                (got_drop - drop).abs() < 1e-3,
                "dt {dt}: {what} fell {got_drop} m, expected {drop}"
            );
        }
        let sb = w.soft_body(s).unwrap();
        let sv = sb.vel.iter().map(|v| v.y).sum::<f32>() / sb.vel.len() as f32;
        println!("dt {dt}: soft body mean vertex velocity {sv}, free fall {v}");
        if dt == MAX_TIME_STEP {
            assert!((sv - v).abs() < 1e-3 * v.abs(), "dt {dt}: soft v {sv}, expected {v}");
        }
        assert_sane(&w, &[s], "free fall");
    }
}

/// A world with every subsystem: a box on the ground, a sphere pyramid, a hinge pendulum, a
/// ball-joint chain, particles on a rod and in a burst, a soft ball and a pinned cloth.
struct Scene {
    w: World,
    pendulum: BodyHandle,
    rod_particle: hearth::pool::Handle,
    soft: Vec<SoftBodyHandle>,
}

fn scene(integrator: Integrator) -> Scene {
    let mut w = world(WorldSettings {
        integrator,
        ..Default::default()
    });
    ground(&mut w);
    cube(&mut w, Vec3::new(0.0, 0.5, 0.0), 0.5);
    for i in 0..3 {
        sphere(&mut w, Vec3::new(2.0 + i as f32 * 0.5, 0.25, 0.0), 0.25, 1000.0);
    }
    sphere(&mut w, Vec3::new(2.25, 0.7, 0.0), 0.25, 1000.0);
    // A hinge pendulum 1 m from its pivot at (5, 4, 0), swinging.
    let pendulum = sphere(&mut w, Vec3::new(6.0, 4.0, 0.0), 0.1, 1000.0);
    let mut hinge = JointDef::new(JointKind::Hinge(HingeParams::default()));
    hinge.body_a = pendulum;
    hinge.frame_a = Transform::new(Vec3::new(-1.0, 0.0, 0.0), Quat::IDENTITY);
    hinge.frame_b = Transform::new(Vec3::new(5.0, 4.0, 0.0), Quat::IDENTITY);
    w.create_joint(&hinge).unwrap();
    // A chain of five balls hanging from (-5, 6, 0).
    let mut prev = None;
    for i in 0..5 {
        let b = sphere(&mut w, Vec3::new(-5.0, 5.5 - 0.5 * i as f32, 0.0), 0.1, 1000.0);
        let mut j = JointDef::new(JointKind::Ball(Default::default()));
        j.body_a = b;
        j.frame_a = Transform::new(Vec3::new(0.0, 0.5, 0.0), Quat::IDENTITY);
        match prev {
            None => j.frame_b = Transform::new(Vec3::new(-5.0, 6.0, 0.0), Quat::IDENTITY),
            Some(p) => j.body_b = p,
        }
        w.create_joint(&j).unwrap();
        prev = Some(b);
    }
    let rod_particle = particle(&mut w, Vec3::new(0.0, 5.0, 3.0));
    w.create_generator(&GeneratorDef::Rod {
        a: End::Particle(rod_particle),
        b: End::World(Vec3::new(0.0, 6.0, 3.0)),
        length: 1.0,
    })
    .unwrap();
    w.emit_burst(
        &BurstDef {
            position: Vec3::new(3.0, 1.0, 3.0),
            lifetime_max: f32::INFINITY,
            ..Default::default()
        },
        &mut Vec::new(),
    )
    .unwrap();
    let ball = soft_ball(&mut w, Vec3::new(-3.0, 1.0, -3.0));
    let cloth = w
        .create_soft_body(
            &SoftBodyDef {
                transform: Transform::new(Vec3::new(3.0, 3.0, -3.0), Quat::IDENTITY),
                ..Default::default()
            },
            &mesh::cloth(1.0, 1.0, 8, 8),
            None,
        )
        .unwrap();
    w.pin_soft_vertex(cloth, 0, None).unwrap();
    w.pin_soft_vertex(cloth, 8, None).unwrap();
    Scene {
        w,
        pendulum,
        rod_particle,
        soft: vec![ball, cloth],
    }
}

/// Every subsystem at both ends of the range: rigid contacts, joints (a hinge keeps its
/// pendulum on its circle), particles (a rod keeps its length), soft bodies; finite and
/// within the speed limit throughout, for both integrators.
#[test]
fn every_subsystem_runs_at_the_shortest_and_the_longest_step() {
    for integrator in [Integrator::SemiImplicitEuler, Integrator::Rk4] {
        for (dt, steps) in [(MIN_TIME_STEP, 300usize), (MAX_TIME_STEP, 60)] {
            let mut s = scene(integrator);
            let mut worst_hinge = 0.0f32;
            let mut worst_rod = 0.0f32;
            for i in 0..steps {
                s.w.step(dt).unwrap();
                assert_sane(&s.w, &s.soft, &format!("{integrator:?}, dt {dt}, step {i}"));
                let c = s.w.body(s.pendulum).unwrap().center;
                worst_hinge = worst_hinge.max(((c - Vec3::new(5.0, 4.0, 0.0)).length() - 1.0).abs());
                let p = s.w.particle_position(s.rod_particle).unwrap();
                worst_rod = worst_rod.max(((p - Vec3::new(0.0, 6.0, 3.0)).length() - 1.0).abs());
            }
            println!("{integrator:?} dt {dt}: hinge radius error {worst_hinge} m, rod length error {worst_rod} m");
            assert!(
                worst_hinge < 0.02,
                "{integrator:?} dt {dt}: the pendulum left its circle by {worst_hinge} m"
            );
            assert!(
                worst_rod < 1e-3,
                "{integrator:?} dt {dt}: the rod stretched by {worst_rod} m"
            );
        }
    }
}

/// Seeded random steps anywhere in the range (log-uniform from 10 µs to 1 s) over the whole
/// scene: finite and within the speed limit after every step.
#[test]
fn random_steps_inside_the_range_keep_every_subsystem_sane() {
    let mut s = scene(Integrator::SemiImplicitEuler);
    let mut rng = hearth::particles::emitter::Rng::new(12);
    let (lo, hi) = (MIN_TIME_STEP.ln(), MAX_TIME_STEP.ln());
    for i in 0..150 {
        let dt = (lo + (hi - lo) * rng.next_f32())
            .exp()
            .clamp(MIN_TIME_STEP, MAX_TIME_STEP);
        s.w.step(dt).unwrap();
        assert_sane(&s.w, &s.soft, &format!("step {i} of {dt} s"));
    }
}

// ------------------------------------------------------------------ item 10's extremes

/// Steps `w` and checks it after every step.
fn run_sane(w: &mut World, steps: usize, when: &str) {
    for i in 0..steps {
        w.step(1.0 / 60.0).unwrap();
        assert_sane(w, &[], &format!("{when}, step {i}"));
    }
}

/// The largest values every input accepts leave the world finite and within the speed
/// limit: gravity, the largest and smallest spheres and boxes at the extreme densities,
/// bodies at the edge of the coordinate range, the largest force, impulses at a 100 km lever
/// arm on the lightest body, the strongest explosion, the lightest particle hit by the
/// largest impulse, the largest damping (also with RK4), the largest gravity scale. (Some of
/// these spin bodies up: finite only once the solver caps angular speed, issue 12's
/// `max_angular_speed`.)
#[test]
fn the_largest_accepted_values_leave_the_world_finite() {
    for integrator in [Integrator::SemiImplicitEuler, Integrator::Rk4] {
        let mut w = world(WorldSettings {
            gravity: Vec3::new(0.0, -MAX_ACCELERATION, 0.0),
            integrator,
            ..Default::default()
        });
        ground(&mut w);
        let big = sphere(&mut w, Vec3::new(3.0e4, MAX_LENGTH + 1.0, 0.0), MAX_LENGTH, MAX_DENSITY);
        let tiny = sphere(&mut w, Vec3::new(0.0, 1.0, 0.0), MIN_LENGTH, MIN_DENSITY);
        let light = sphere(&mut w, Vec3::new(1.0, 1.0, 0.0), MIN_LENGTH, MIN_DENSITY);
        // A 20 km plank falling onto the ground from 5 km (placed into the ground it would
        // start 3 km deep: a contact-solver case of its own).
        let heavy_box = dynamic(&mut w, Vec3::new(-3.0e4, 5000.0, 0.0));
        w.create_shape(
            heavy_box,
            &ShapeDef {
                density: MAX_DENSITY,
                ..Default::default()
            },
            &Geometry::Box {
                center: Vec3::ZERO,
                rotation: Quat::from_rotation_z(0.3),
                half_extents: Vec3::new(MAX_LENGTH, MIN_LENGTH, 1.0),
            },
        )
        .unwrap();
        let far = cube(&mut w, Vec3::splat(MAX_COORDINATE), 0.5);
        let damped = cube(&mut w, Vec3::new(5.0, 3.0, 0.0), 0.5);
        w.set_damping(damped, MAX_DAMPING, MAX_DAMPING).unwrap();
        w.set_linear_velocity(damped, Vec3::new(0.0, 0.0, w.settings.max_linear_speed))
            .unwrap();
        w.set_angular_velocity(damped, Vec3::new(w.settings.max_angular_speed, 0.0, 0.0))
            .unwrap();
        let scaled = dynamic(&mut w, Vec3::new(-5.0, 3.0, 0.0));
        w.create_shape(
            scaled,
            &ShapeDef::default(),
            &Geometry::Capsule {
                a: Vec3::ZERO,
                b: Vec3::new(MAX_LENGTH, 0.0, 0.0),
                radius: MIN_LENGTH,
            },
        )
        .unwrap();

        // README: the lightest body, 1 mm of the lightest material, has an inertia of
        // 1.7e-18 kg·m² and an inverse mass of 2.4e11 1/kg, both inverted finitely.
        let t = w.body(tiny).unwrap();
        assert!(
            (t.inertia_local.x_axis.x / 1.676e-18 - 1.0).abs() < 0.01,
            "{}",
            t.inertia_local.x_axis.x
        );
        assert!((t.inv_mass / 2.387e11 - 1.0).abs() < 0.01, "{}", t.inv_mass);
        assert!((t.inv_inertia_local.x_axis.x * t.inertia_local.x_axis.x - 1.0).abs() < 1e-5);
        w.apply_force(tiny, Vec3::new(MAX_FORCE, 0.0, 0.0), true).unwrap();
        w.apply_force(far, Vec3::new(0.0, -MAX_FORCE, 0.0), true).unwrap();
        w.apply_impulse_at_point(
            light,
            Vec3::new(0.0, 0.0, MAX_IMPULSE),
            Vec3::new(MAX_COORDINATE, 0.0, 0.0),
            true,
        )
        .unwrap();
        w.apply_angular_impulse(light, Vec3::new(MAX_IMPULSE, 0.0, 0.0), true)
            .unwrap();
        assert!(w.angular_velocity(light).unwrap().length() <= w.settings.max_angular_speed * 1.0001);
        assert!(w.linear_velocity(light).unwrap().length() <= w.settings.max_linear_speed * 1.0001);
        w.apply_linear_impulse(big, Vec3::new(MAX_IMPULSE, 0.0, 0.0), true)
            .unwrap();
        let p = w
            .create_particle(&ParticleDef {
                position: Vec3::new(0.0, 2.0, 0.0),
                inverse_mass: MAX_INVERSE_MASS,
                gravity_scale: MAX_GRAVITY_SCALE,
                ..Default::default()
            })
            .unwrap();
        w.apply_particle_impulse(p, Vec3::new(MAX_IMPULSE, 0.0, 0.0)).unwrap();
        w.create_generator(&GeneratorDef::Explosion {
            center: Vec3::new(0.0, 1.0, 1.0),
            blast_radius: MAX_LENGTH,
            blast_impulse: MAX_IMPULSE,
            shock_speed: MAX_SPEED,
            shock_thickness: MAX_LENGTH,
            shock_force: MAX_FORCE,
            max_radius: MAX_LENGTH,
            affect_all: true,
        })
        .unwrap();
        run_sane(&mut w, 120, &format!("{integrator:?}"));
        // The damped body forgets any push within milliseconds (v·1/(1 + h·1000) per
        // sub-step, e^(−1000·t)): resting it is still, thrown into the air by the blast it
        // falls no faster than its terminal speed g/c = 10 m/s.
        let v = w.linear_velocity(damped).unwrap().length();
        let terminal = MAX_ACCELERATION / MAX_DAMPING;
        assert!(v <= terminal * 1.001, "{integrator:?}: damped body moves at {v} m/s");
    }
}

/// The largest torque on the lightest body: finite only with an angular speed cap in the
/// solver (issue 12's `max_angular_speed`, another part of the work); until then its angular
/// velocity overflows the quaternion update.
#[test]
fn the_largest_torque_on_the_smallest_body_leaves_it_finite() {
    let mut w = world(WorldSettings::default());
    ground(&mut w);
    let tiny = sphere(&mut w, Vec3::new(0.0, 1.0, 0.0), MIN_LENGTH, MIN_DENSITY);
    let boxy = dynamic(&mut w, Vec3::new(1.0, 1.0, 0.0));
    w.create_shape(
        boxy,
        &ShapeDef {
            density: MIN_DENSITY,
            ..Default::default()
        },
        &Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::new(MIN_LENGTH, 2.0 * MIN_LENGTH, 3.0 * MIN_LENGTH),
        },
    )
    .unwrap();
    // README: the lightest body's inertia, 1.7e-18 kg·m² (2/5·m·r² of a 1 mm sphere of the
    // lightest density), is far above f32's smallest normal number (1.2e-38).
    let inertia = 0.4 * w.body(tiny).unwrap().mass * MIN_LENGTH * MIN_LENGTH;
    assert!((inertia / 1.7e-18 - 1.0).abs() < 0.02, "lightest inertia {inertia:e}");
    assert!(inertia > 1e20 * f32::MIN_POSITIVE);
    for _ in 0..10 {
        w.apply_torque(tiny, Vec3::new(MAX_FORCE, 0.0, 0.0), true).unwrap();
        w.apply_torque(boxy, Vec3::new(MAX_FORCE, MAX_FORCE, 0.0) * 0.7, true)
            .unwrap();
        w.step(1.0 / 60.0).unwrap();
        assert_sane(&w, &[], "torque");
    }
}

/// RK4 keeps the speed limit (it falls back to the capped Euler step) and damps stiff
/// damping exactly: with c·h > 1 the velocity decays as e^(−c·t).
#[test]
fn rk4_keeps_the_speed_limit_and_damps_exactly() {
    let mut w = world(WorldSettings {
        integrator: Integrator::Rk4,
        gravity: Vec3::ZERO,
        ..Default::default()
    });
    let fast = cube(&mut w, Vec3::ZERO, 0.5);
    let damped = cube(&mut w, Vec3::new(5.0, 0.0, 0.0), 0.5);
    w.set_damping(damped, 100.0, 0.0).unwrap();
    w.set_linear_velocity(damped, Vec3::new(10.0, 0.0, 0.0)).unwrap();
    w.apply_force(fast, Vec3::new(MAX_FORCE, 0.0, 0.0), true).unwrap();
    let dt = 1.0 / 60.0;
    w.step(dt).unwrap();
    let v = w.linear_velocity(fast).unwrap().length();
    assert!(v <= w.settings.max_linear_speed * 1.0001, "RK4 body at {v} m/s");
    // c·h = 100/360 < 1: inside RK4's own damping; then 1000: split off and exact.
    let expected = 10.0 * (-100.0f32 * dt).exp();
    let got = w.linear_velocity(damped).unwrap().x;
    assert!(
        (got - expected).abs() < 1e-3 * expected,
        "c = 100: {got}, e^(-ct) gives {expected}"
    );
    w.set_damping(damped, MAX_DAMPING, 0.0).unwrap();
    w.set_linear_velocity(damped, Vec3::new(10.0, 0.0, 0.0)).unwrap();
    w.step(0.001).unwrap();
    let expected = 10.0 * (-MAX_DAMPING * 0.001).exp();
    let got = w.linear_velocity(damped).unwrap().x;
    assert!(
        (got - expected).abs() < 1e-4 * expected,
        "c = 1000: {got}, e^(-ct) gives {expected}"
    );
}

// ------------------------------------------------------------------ refused values

/// What a refused call may not change: every body's pose, velocities and mass, gravity, and
/// the counts of shapes, particles and generators.
fn snapshot(w: &World) -> String {
    let mut s = format!(
        "{:?} {} {} {}",
        w.settings.gravity,
        w.shapes.len(),
        w.particle_count(),
        w.generator_count()
    );
    for (h, b) in w.bodies.iter() {
        s += &format!("|{} {:?} {:?} {:?} {}", h.index, b.xf, b.v, b.w, b.mass);
    }
    s
}

/// Values outside the ranges (item 10's among them) are refused with an error naming the
/// parameter, and the world is unchanged.
#[test]
fn values_outside_the_ranges_are_refused_and_change_nothing() {
    let mut w = world(WorldSettings::default());
    ground(&mut w);
    let b = cube(&mut w, Vec3::new(0.0, 1.0, 0.0), 0.5);
    let p = particle(&mut w, Vec3::new(1.0, 1.0, 0.0));
    w.step(1.0 / 60.0).unwrap();
    let before = snapshot(&w);
    let sphere_of = |radius| Geometry::Sphere {
        center: Vec3::ZERO,
        radius,
    };
    let explosion = |blast_impulse| GeneratorDef::Explosion {
        center: Vec3::ZERO,
        blast_radius: 5.0,
        blast_impulse,
        shock_speed: 20.0,
        shock_thickness: 1.0,
        shock_force: 100.0,
        max_radius: 20.0,
        affect_all: true,
    };
    let fast = w.settings.max_linear_speed * 1.01;
    type Call = Box<dyn Fn(&mut World) -> Result<()>>;
    let cases: Vec<(&str, Call)> = vec![
        ("dt", Box::new(|w| w.step(1.0e6))),
        ("gravity", Box::new(|w| w.set_gravity(Vec3::new(0.0, -1.0e30, 0.0)))),
        (
            "torque",
            Box::new(move |w| w.apply_torque(b, Vec3::new(3.0e38, 0.0, 0.0), true)),
        ),
        (
            "force",
            Box::new(move |w| w.apply_force(b, Vec3::new(0.0, 2.0 * MAX_FORCE, 0.0), true)),
        ),
        (
            "impulse",
            Box::new(move |w| w.apply_linear_impulse(b, Vec3::new(0.0, 2.0 * MAX_IMPULSE, 0.0), true)),
        ),
        (
            "point",
            Box::new(move |w| w.apply_force_at_point(b, Vec3::Y, Vec3::splat(2.0 * MAX_COORDINATE), true)),
        ),
        (
            "sphere radius",
            Box::new(move |w| w.create_shape(b, &ShapeDef::default(), &sphere_of(1.0e30)).map(|_| ())),
        ),
        (
            "sphere radius",
            Box::new(move |w| w.create_shape(b, &ShapeDef::default(), &sphere_of(1.0e-4)).map(|_| ())),
        ),
        (
            "density",
            Box::new(move |w| {
                let def = ShapeDef {
                    density: MIN_DENSITY / 2.0,
                    ..Default::default()
                };
                w.create_shape(b, &def, &sphere_of(0.1)).map(|_| ())
            }),
        ),
        (
            "restitution",
            Box::new(move |w| {
                let def = ShapeDef {
                    restitution: 1.5,
                    ..Default::default()
                };
                w.create_shape(b, &def, &sphere_of(0.1)).map(|_| ())
            }),
        ),
        (
            "half_extents",
            Box::new(move |w| {
                let g = Geometry::Box {
                    center: Vec3::ZERO,
                    rotation: Quat::IDENTITY,
                    half_extents: Vec3::new(1.0, f32::MAX, 1.0),
                };
                w.create_shape(b, &ShapeDef::default(), &g).map(|_| ())
            }),
        ),
        (
            "capsule segment",
            Box::new(move |w| {
                let g = Geometry::Capsule {
                    a: Vec3::ZERO,
                    b: Vec3::new(2.0 * MAX_LENGTH, 0.0, 0.0),
                    radius: 0.1,
                };
                w.create_shape(b, &ShapeDef::default(), &g).map(|_| ())
            }),
        ),
        (
            "plane offset",
            Box::new(|w| {
                let g = Geometry::Plane {
                    normal: Vec3::Y,
                    offset: 2.0 * MAX_COORDINATE,
                };
                w.create_shape(hearth::pool::Handle::NULL, &ShapeDef::default(), &g)
                    .map(|_| ())
            }),
        ),
        (
            "blast_impulse",
            Box::new(move |w| w.create_generator(&explosion(3.0e38)).map(|_| ())),
        ),
        (
            "linear velocity",
            Box::new(move |w| w.set_linear_velocity(b, Vec3::new(fast, 0.0, 0.0))),
        ),
        (
            "angular velocity",
            Box::new(move |w| w.set_angular_velocity(b, Vec3::new(0.0, 2.0 * MAX_ANGULAR_SPEED, 0.0))),
        ),
        (
            "linear damping",
            Box::new(move |w| w.set_damping(b, 2.0 * MAX_DAMPING, 0.0)),
        ),
        (
            "inverse_mass",
            Box::new(|w| {
                let def = ParticleDef {
                    inverse_mass: 2.0 * MAX_INVERSE_MASS,
                    ..Default::default()
                };
                w.create_particle(&def).map(|_| ())
            }),
        ),
        (
            "impulse",
            Box::new(move |w| w.apply_particle_impulse(p, Vec3::new(f32::MAX, 0.0, 0.0))),
        ),
        (
            "gravity_scale",
            Box::new(|w| {
                let def = BodyDef {
                    gravity_scale: 2.0 * MAX_GRAVITY_SCALE,
                    ..Default::default()
                };
                w.create_body(&def).map(|_| ())
            }),
        ),
        (
            "transform.position",
            Box::new(|w| {
                let def = BodyDef {
                    transform: Transform::new(Vec3::new(0.0, 0.0, -2.0 * MAX_COORDINATE), Quat::IDENTITY),
                    ..Default::default()
                };
                w.create_body(&def).map(|_| ())
            }),
        ),
    ];
    for (name, call) in &cases {
        match call(&mut w) {
            Err(Error::InvalidArgument(m)) => assert!(m.contains(name), "{name}: the message \"{m}\" does not name it"),
            // The plane case's null body is refused as an id first: use a real static body.
            Err(Error::InvalidId(_)) if *name == "plane offset" => {}
            r => panic!("{name}: expected a refusal, got {r:?}"),
        }
        assert_eq!(before, snapshot(&w), "{name}: a refused call changed the world");
    }
    // The plane again, on a static body.
    let g = w.create_body(&BodyDef::default()).unwrap();
    let after_body = snapshot(&w);
    let plane = Geometry::Plane {
        normal: Vec3::Y * 1e-3,
        offset: MAX_COORDINATE * 1e-3 * 1.01,
    };
    match w.create_shape(g, &ShapeDef::default(), &plane) {
        Err(Error::InvalidArgument(m)) => assert!(m.contains("plane offset"), "{m}"),
        r => panic!("plane offset: {r:?}"),
    }
    assert_eq!(after_body, snapshot(&w));
}

/// The world settings' ranges, core and C alike (`WorldSettings::validate`).
#[test]
fn world_settings_outside_the_ranges_are_refused() {
    let base = WorldSettings::default();
    let cases: Vec<(&str, WorldSettings)> = vec![
        (
            "gravity",
            WorldSettings {
                gravity: Vec3::new(0.0, -1.0e30, 0.0),
                ..base
            },
        ),
        (
            "max_linear_speed",
            WorldSettings {
                max_linear_speed: 2.0 * MAX_SPEED,
                ..base
            },
        ),
        (
            "max_linear_speed",
            WorldSettings {
                max_linear_speed: f32::INFINITY,
                ..base
            },
        ),
        (
            "contact_damping_ratio",
            WorldSettings {
                contact_damping_ratio: 3.0e38,
                ..base
            },
        ),
        (
            "contact_hertz",
            WorldSettings {
                contact_hertz: 1.0e-40,
                ..base
            },
        ),
        (
            "sleep_threshold",
            WorldSettings {
                sleep_threshold: 1.0e20,
                ..base
            },
        ),
        (
            "contact_push_max_velocity",
            WorldSettings {
                contact_push_max_velocity: 1.0e30,
                ..base
            },
        ),
        (
            "restitution_threshold",
            WorldSettings {
                restitution_threshold: -1.0,
                ..base
            },
        ),
        (
            "linear_slop",
            WorldSettings {
                linear_slop: 1.0e30,
                ..base
            },
        ),
    ];
    for (name, s) in cases {
        match World::new(s) {
            Err(Error::InvalidArgument(m)) => assert!(m.contains(name), "{m}"),
            r => panic!("{name}: {:?}", r.map(|_| ())),
        }
    }
    // The largest accepted ones.
    World::new(WorldSettings {
        gravity: Vec3::new(0.0, 0.0, MAX_ACCELERATION),
        max_linear_speed: MAX_SPEED,
        contact_damping_ratio: 1.0e3,
        contact_hertz: 1.0e6,
        ..base
    })
    .unwrap();
}

// ------------------------------------------------------------------ soft bodies' limits

/// Soft bodies (balls, cloths, pinned or not, pinned to a body moving at the limit) placed
/// up to 3 km under a ground plane or hit by the largest impulse, in worlds with a speed
/// limit from 1 to 10,000 m/s and 1 ms to 0.1 s steps (seeded): every vertex stays finite
/// and within `max_linear_speed`. The velocities the constraint and contact projections
/// wrote back were uncapped: a vertex pushed out of a plane reached 34,000 m/s under a
/// 400 m/s limit (fuzzer seed 2, call 71).
#[test]
fn soft_vertices_stay_within_the_speed_limit() {
    for seed in 0..16u64 {
        let mut rng = hearth::particles::emitter::Rng::new(0x50F7 + seed);
        let mut log = |lo: f32, hi: f32| (lo.ln() + (hi.ln() - lo.ln()) * rng.next_f32()).exp().min(hi);
        let max = log(1.0, 1e4);
        let dt = log(MIN_TIME_STEP, MAX_TIME_STEP);
        let depth = log(0.1, 3000.0);
        let mut w = world(WorldSettings {
            max_linear_speed: max,
            ..Default::default()
        });
        ground(&mut w);
        let ball = w
            .create_soft_body(
                &SoftBodyDef {
                    transform: Transform::new(Vec3::new(0.0, -depth, 0.0), Quat::IDENTITY),
                    pressure: 200.0,
                    ..Default::default()
                },
                &mesh::icosphere(0.5, 1),
                None,
            )
            .unwrap();
        let cloth = w
            .create_soft_body(
                &SoftBodyDef {
                    transform: Transform::new(Vec3::new(3.0, -0.5 * depth, 0.0), Quat::IDENTITY),
                    ..Default::default()
                },
                &mesh::cloth(1.0, 1.0, 4, 4),
                None,
            )
            .unwrap();
        // One corner on a body that the largest impulse throws at the limit, one fixed.
        let body = dynamic(&mut w, Vec3::new(3.0, 5.0, 0.0));
        w.pin_soft_vertex(cloth, 0, Some(body)).unwrap();
        w.pin_soft_vertex(cloth, 4, None).unwrap();
        w.apply_linear_impulse(body, Vec3::new(MAX_IMPULSE, 0.0, 0.0), true)
            .unwrap();
        w.apply_soft_impulse(ball, Some(0), Vec3::new(0.0, MAX_IMPULSE, 0.0))
            .unwrap();
        w.apply_soft_impulse(cloth, None, Vec3::new(0.0, 0.0, -MAX_IMPULSE))
            .unwrap();
        for i in 0..30 {
            w.step(dt).unwrap();
            assert_sane(
                &w,
                &[ball, cloth],
                &format!("seed {seed}: {max} m/s, {dt} s, {depth} m deep, step {i}"),
            );
        }
    }
}

/// An impulse on a soft body longer than the largest one call may give (1e10 N·s, as for
/// rigid bodies and particles) is refused with the parameter named, and changes nothing.
#[test]
fn soft_impulses_past_the_range_are_refused() {
    let mut w = world(WorldSettings::default());
    let ball = soft_ball(&mut w, Vec3::new(0.0, 2.0, 0.0));
    for j in [
        Vec3::new(MAX_IMPULSE * 1.01, 0.0, 0.0),
        Vec3::splat(3e38),
        Vec3::new(0.0, f32::NAN, 0.0),
    ] {
        for vertex in [Some(0), None] {
            let e = w.apply_soft_impulse(ball, vertex, j).unwrap_err();
            assert!(
                matches!(&e, Error::InvalidArgument(m) if m.contains("impulse")),
                "{e:?}"
            );
        }
    }
    w.step(1.0 / 60.0).unwrap();
    let s = w.soft_body(ball).unwrap();
    let fastest = s.vel.iter().map(|v| v.length()).fold(0.0f32, f32::max);
    assert!(fastest < 1.0, "a refused impulse moved the ball: {fastest} m/s");
    w.apply_soft_impulse(ball, Some(0), Vec3::new(MAX_IMPULSE, 0.0, 0.0))
        .unwrap();
}

//! Soft bodies against the proofs, at the default settings (a def from
//! `SoftBodyDef::default()` with only placement, mass, pressure and the varied parameter
//! changed): a pressurised 642-vertex ball bounces, settles and keeps its volume; doubling
//! the pressure makes it stiffer; a stiffness sweep over four orders of magnitude stays
//! finite without energy growth for 60 s; cloths of 16×16 and 64×64 cells pinned at two
//! corners hang without stretching; a soft ball pushes a rigid box and a rigid box dropped
//! on a soft ball dents it and rests on it (two-way); a box rests on a slope of vertices;
//! pins to dynamic bodies pull them (momentum kept, a weight hangs from a cloth); pins
//! follow bodies and are freed with them; settings change after creation; determinism and
//! no allocation in a steady step.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
#[path = "common/thread_allocs.rs"]
mod thread_allocs;

use hearth::math::{Quat, Transform, Vec3};
use hearth::soft::{mesh, SoftBodyDef, SoftBodyHandle};
use hearth::{BodyDef, BodyType, Geometry, ShapeDef, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;

fn world() -> World {
    let mut w = World::new(WorldSettings {
        enable_sleep: false,
        ..Default::default()
    })
    .unwrap();
    scenes::ground_plane(&mut w);
    w
}

fn at(p: Vec3) -> Transform {
    Transform::new(p, Quat::IDENTITY)
}

/// The 642-vertex pressurised ball of radius 0.5 m and 5 kg, default settings otherwise.
fn ball_def(height: f32, pressure: f32) -> SoftBodyDef {
    SoftBodyDef {
        transform: at(Vec3::new(0.0, height, 0.0)),
        mass: 5.0,
        pressure,
        ..Default::default()
    }
}

fn ball(w: &mut World, height: f32, pressure: f32) -> SoftBodyHandle {
    w.create_soft_body(&ball_def(height, pressure), &mesh::icosphere(0.5, 3), None)
        .unwrap()
}

fn height(w: &World, h: SoftBodyHandle) -> (f32, f32) {
    let s = w.soft_body(h).unwrap();
    let top = s.pos.iter().map(|p| p.y).fold(f32::MIN, f32::max);
    let bottom = s.pos.iter().map(|p| p.y).fold(f32::MAX, f32::min);
    (bottom, top)
}

fn energy(w: &World, h: SoftBodyHandle) -> (f32, f32) {
    let s = w.soft_body(h).unwrap();
    let mut kinetic = 0.0;
    let mut potential = 0.0;
    for ((v, p), &im) in s.vel.iter().zip(&s.pos).zip(&s.inv_mass) {
        kinetic += 0.5 * v.length_squared() / im;
        potential += G * p.y / im;
    }
    (kinetic, potential)
}

#[test]
fn pressurised_icosphere_bounces_settles_and_keeps_its_volume() {
    let mut w = world();
    let h = ball(&mut w, 1.5, 500.0);
    assert_eq!(w.soft_body(h).unwrap().vertex_count(), 642);
    let rest = w.soft_body(h).unwrap().rest_volume;
    let mut landed = false;
    let mut lowest_center = f32::MAX;
    let mut rebound: f32 = 0.0;
    let mut worst: f32 = 0.0;
    for step in 0..600 {
        w.step(DT).unwrap();
        let s = w.soft_body(h).unwrap();
        let c = s.center().y;
        if step > 30 {
            worst = worst.max((s.volume() / rest - 1.0).abs());
        }
        let (bottom, _) = height(&w, h);
        if bottom < 0.02 {
            landed = true;
        }
        if landed && step < 120 {
            lowest_center = lowest_center.min(c);
            rebound = rebound.max(c - lowest_center);
        }
    }
    let s = w.soft_body(h).unwrap();
    let (kinetic, _) = energy(&w, h);
    let volume_error = (s.volume() / rest - 1.0).abs();
    println!(
        "ball: rebound {rebound:.3} m, final centre {:.3} m, kinetic {kinetic:.5} J, volume error {:.2} % (worst after landing {:.2} %)",
        s.center().y,
        100.0 * volume_error,
        100.0 * worst
    );
    assert!(rebound > 0.05, "the ball should bounce, rebound {rebound}");
    assert!(kinetic < 0.01, "the ball should settle, kinetic energy {kinetic}");
    assert!((s.center().y - 0.5).abs() < 0.05, "centre {}", s.center().y);
    // At rest the inextensible skin holds the rest volume (0.17 % measured). At the impact
    // the skin, a membrane that buckles rather than a shell that resists compression,
    // flattens and the gas takes the landing: 6.7 % measured.
    // README: "within 0.5 % at rest".
    assert!(volume_error < 0.005, "volume error {volume_error}");
    assert!(worst < 0.075, "worst volume error {worst}");
}

#[test]
fn doubling_the_pressure_makes_the_ball_stiffer() {
    // Flattening under its own weight: free height (no gravity) minus resting height (36 mm
    // at 500 J, 25 mm at 1000 J measured).
    let mut flat = [0.0; 2];
    for (k, p) in [500.0, 1000.0].into_iter().enumerate() {
        let mut free = World::new(WorldSettings {
            gravity: Vec3::ZERO,
            ..Default::default()
        })
        .unwrap();
        let f = ball(&mut free, 2.0, p);
        let mut w = world();
        let h = ball(&mut w, 0.52, p);
        for _ in 0..300 {
            free.step(DT).unwrap();
            w.step(DT).unwrap();
        }
        let (b0, t0) = height(&free, f);
        let (b1, t1) = height(&w, h);
        flat[k] = (t0 - b0) - (t1 - b1);
        let rest = w.soft_body(h).unwrap().rest_volume;
        println!(
            "pressure {p}: flattening {:.4} m, volume {:.2} % of rest",
            flat[k],
            100.0 * w.soft_body(h).unwrap().volume() / rest
        );
    }
    assert!(flat[0] > 0.005, "the ball should flatten under its weight: {}", flat[0]);
    assert!(flat[1] < 0.95 * flat[0], "{flat:?}");
    // Under a 3.2 kg box. The skin buckles instead of carrying compression, so the gas
    // carries the box on the area it presses: twice the gas, about half the area (a dent's
    // depth grows with its area): 35.7 mm at 500 J, 25.2 mm at 1000 J.
    let dents = [drop_box_on_ball(500.0), drop_box_on_ball(1000.0)];
    println!(
        "dent under a 3.2 kg box: {:.1} mm at nRT 500 J, {:.1} mm at 1000 J",
        1000.0 * dents[0],
        1000.0 * dents[1]
    );
    assert!(dents[1] < 0.8 * dents[0], "{dents:?}");
}

/// Edge and bend compliance over four decades, each on a 162-vertex ball (the same 5 kg,
/// 0.5 m ball one subdivision coarser: the compliance, not the vertex count, is what is
/// swept; the 642-vertex ball has its own tests above). It falls, bounces and settles; its
/// energy never grows after the landing and it comes to rest. (The 642-vertex version ran 60
/// s of simulation per compliance, half the Rust suite's time; this covers the same
/// compliances over 20 s each, a twelfth of the work.)
#[test]
fn stiffness_sweep_stays_finite_without_energy_growth() {
    for compliance in [1.0e-7, 1.0e-6, 1.0e-5, 1.0e-4, 1.0e-3] {
        let mut w = world();
        let def = SoftBodyDef {
            edge_compliance: compliance,
            bend_compliance: compliance,
            ..ball_def(1.0, 300.0)
        };
        let h = w.create_soft_body(&def, &mesh::icosphere(0.5, 2), None).unwrap();
        let mut early: f32 = f32::MIN;
        let mut late: f32 = f32::MIN;
        for step in 0..1200 {
            w.step(DT).unwrap();
            let s = w.soft_body(h).unwrap();
            assert!(
                s.pos.iter().chain(&s.vel).all(|v| v.is_finite()),
                "compliance {compliance}"
            );
            let (k, p) = energy(&w, h);
            if (300..600).contains(&step) {
                early = early.max(k + p);
            } else if step >= 600 {
                late = late.max(k + p);
            }
        }
        let (k, _) = energy(&w, h);
        println!(
            "compliance {compliance:e}: max energy 5-10 s {early:.3} J, 10-20 s {late:.3} J, final kinetic {k:.5}"
        );
        assert!(
            late <= early + 0.01,
            "energy grew: {early} -> {late} (compliance {compliance})"
        );
        assert!(k < 0.05, "still moving: {k}");
    }
}

/// A 2 × 2 m, 1 kg cloth of `n × n` cells at default settings, horizontal at 3 m, pinned at
/// the two corners of its edge z = -1: it swings down and hangs. Returns the worst edge
/// stretch after 10 s and the lowest point.
fn hang_cloth(n: u32) -> (f32, f32) {
    let mut w = world();
    let def = SoftBodyDef {
        transform: at(Vec3::new(0.0, 3.0, 0.0)),
        mass: 1.0,
        ..Default::default()
    };
    let rest = mesh::cloth(2.0, 2.0, n, n);
    let h = w.create_soft_body(&def, &rest, None).unwrap();
    w.pin_soft_vertex(h, 0, None).unwrap();
    w.pin_soft_vertex(h, n, None).unwrap();
    let edges = edges_of(&rest);
    let mut worst_late: f32 = 0.0;
    for step in 0..600 {
        w.step(DT).unwrap();
        if step >= 300 {
            let s = w.soft_body(h).unwrap();
            for &(a, b, l) in &edges {
                let d = s.pos[a as usize].distance(s.pos[b as usize]);
                worst_late = worst_late.max(d / l - 1.0);
            }
        }
    }
    let s = w.soft_body(h).unwrap();
    let low = s.pos.iter().map(|p| p.y).fold(f32::MAX, f32::min);
    assert!(
        s.pos[0].distance(Vec3::new(-1.0, 3.0, -1.0)) < 1e-4,
        "the pin holds: {}",
        s.pos[0]
    );
    println!(
        "cloth {n}x{n}: worst edge stretch over 5-10 s {:.2} %, lowest point {low:.3} m",
        100.0 * worst_late
    );
    (worst_late, low)
}

#[test]
fn cloth_pinned_at_two_corners_hangs_without_stretching() {
    let (stretch, low) = hang_cloth(16);
    // 0.07 % measured.
    assert!(stretch < 1e-3, "stretch {stretch}");
    // 2 m of cloth hanging from 3 m: its lowest point 1 m up, a little higher as the free
    // corners swing in (measured 1.014 m).
    assert!(
        (low - 1.0).abs() < 0.02,
        "the cloth should hang straight down, lowest {low}"
    );
}

#[test]
fn a_64x64_cloth_pinned_at_two_corners_hangs_without_stretching() {
    // One Gauss-Seidel pass per sub-step rang this cloth apart (> 100 % stretch); two passes
    // and tethers to both pins hang it.
    let (stretch, low) = hang_cloth(64);
    // README: "stretches less than 0.5 %" (measured 0.40 %).
    assert!(stretch < 4.5e-3, "stretch {stretch}");
    assert!(
        (low - 1.0).abs() < 0.02,
        "the cloth should hang straight down, lowest {low}"
    );
}

fn edges_of(m: &mesh::SoftMesh) -> Vec<(u32, u32, f32)> {
    let mut out = Vec::new();
    for t in &m.triangles {
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            out.push((a, b, m.vertices[a as usize].distance(m.vertices[b as usize])));
        }
    }
    out
}

fn dynamic_box(w: &mut World, p: Vec3, half: Vec3, density: f32) -> hearth::BodyHandle {
    let def = ShapeDef {
        density,
        ..Default::default()
    };
    scenes::dynamic_box(w, p, half, &def)
}

#[test]
fn a_soft_ball_pushes_a_rigid_box() {
    let mut w = world();
    let bx = dynamic_box(&mut w, Vec3::new(1.0, 0.25, 0.0), Vec3::splat(0.25), 20.0);
    let def = SoftBodyDef {
        velocity: Vec3::new(4.0, 0.0, 0.0),
        ..ball_def(0.52, 500.0)
    };
    let h = w.create_soft_body(&def, &mesh::icosphere(0.5, 3), None).unwrap();
    for _ in 0..60 {
        w.step(DT).unwrap();
    }
    let p = w.transform(bx).unwrap().p;
    let c = w.soft_body(h).unwrap().center();
    println!("push: box moved {:.3} m, ball centre x {:.3}", p.x - 1.0, c.x);
    // The 5 kg ball at 4 m/s brings 40 J; friction (μ 0.6) on the 2.5 kg box takes
    // 14.7 J per metre, so the ball's energy alone could push it at most 2.7 m. Measured:
    // the box moved 1.197 m.
    assert!(
        p.x - 1.0 > 1.1 && p.x - 1.0 < 2.7,
        "the box was pushed {} m along +x",
        p.x - 1.0
    );
    assert!(c.x < p.x, "the ball stays behind the box");
}

fn static_box(w: &mut World, p: Vec3, half: Vec3) {
    let b = w
        .create_body(&BodyDef {
            transform: at(p),
            ..Default::default()
        })
        .unwrap();
    w.create_shape(
        b,
        &ShapeDef::default(),
        &Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: half,
        },
    )
    .unwrap();
}

#[test]
fn a_rigid_box_dropped_on_a_soft_ball_dents_it_and_rests_on_it() {
    let dent = drop_box_on_ball(500.0);
    // 35.7 mm measured (the same in every run: the step is deterministic) since the soft
    // solver changed for issue 12 (24.6 mm before): the skin buckles instead of carrying
    // compression, so the gas carries the box on the area it presses (see
    // `doubling_the_pressure_makes_the_ball_stiffer`). 1.5 mm either way, as before.
    assert!((dent - 0.0357).abs() < 1.5e-3, "dent {} mm", 1000.0 * dent);
}

/// A 3.2 kg box dropped on the 642-vertex ball of gas `pressure`: checks that it comes to
/// rest on the ball, in the dent, with the ball's volume kept; returns the dent depth (m).
fn drop_box_on_ball(pressure: f32) -> f32 {
    // The ball stands in a crate of four low walls touching its sides: a box on a ball that
    // is free to roll is the balance board of a circus act (rola bola), and rolls off for
    // any solver. The walls stop at the ball's equator, well below the box.
    let mut w = world();
    for (p, half) in [
        (Vec3::new(0.61, 0.25, 0.0), Vec3::new(0.1, 0.25, 0.71)),
        (Vec3::new(-0.61, 0.25, 0.0), Vec3::new(0.1, 0.25, 0.71)),
        (Vec3::new(0.0, 0.25, 0.61), Vec3::new(0.71, 0.25, 0.1)),
        (Vec3::new(0.0, 0.25, -0.61), Vec3::new(0.71, 0.25, 0.1)),
    ] {
        static_box(&mut w, p, half);
    }
    let h = ball(&mut w, 0.5, pressure);
    for _ in 0..120 {
        w.step(DT).unwrap();
    }
    let s = w.soft_body(h).unwrap();
    let c = s.center();
    let top = |s: &hearth::soft::SoftBody, c: Vec3| {
        s.pos
            .iter()
            .filter(|p| (p.x - c.x).abs() < 0.05 && (p.z - c.z).abs() < 0.05)
            .map(|p| p.y)
            .fold(f32::MIN, f32::max)
    };
    let top0 = top(s, c);
    let rest = s.rest_volume;
    // A 0.4 × 0.2 × 0.4 m box of 3.2 kg, its bottom 5 cm above the ball's top.
    let half = Vec3::new(0.2, 0.1, 0.2);
    let bx = dynamic_box(&mut w, Vec3::new(c.x, top0 + half.y + 0.05, c.z), half, 100.0);
    let mut worst: f32 = 0.0;
    let mut lowest = f32::MAX;
    // Box positions over the last second.
    let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    for step in 0..600 {
        w.step(DT).unwrap();
        if step >= 540 {
            let p = w.transform(bx).unwrap().p;
            lo = lo.min(p);
            hi = hi.max(p);
        }
        let s = w.soft_body(h).unwrap();
        worst = worst.max((s.volume() / rest - 1.0).abs());
        lowest = lowest.min(w.transform(bx).unwrap().p.y);
    }
    let b = w.body(bx).unwrap();
    let s = w.soft_body(h).unwrap();
    let c = s.center();
    let dent = top0 - top(s, c);
    let bottom = b.xf.p.y - half.y;
    let tilt = (b.xf.q * Vec3::Y).angle_between(Vec3::Y);
    let span = hi - lo;
    println!(
        "box on ball (nRT {pressure} J): dent {:.1} mm, box bottom {bottom:.4} m over the dented top {:.4} m (undented {top0:.4} m), \
         moved {:.2} mm over the last second, speed {:.4} m/s, spin {:.4} rad/s, tilt {:.2} deg, \
         off centre {:.3} m, volume error worst {:.2} %",
        1000.0 * dent,
        top(s, c),
        1000.0 * span.max_element(),
        b.v.length(),
        b.w.length(),
        tilt.to_degrees(),
        (b.xf.p - c).with_y(0.0).length(),
        100.0 * worst
    );
    assert!(
        (bottom - (top(s, c) + 0.01)).abs() < 0.01,
        "the box rests on the dented top (plus the vertex radius): {bottom} vs {}",
        top(s, c)
    );
    assert!(bottom > top0 - 0.1, "not sunk through: {bottom}");
    assert!(lowest - half.y > 0.8, "never fell through or off: {lowest}");
    // At rest: a residual jitter of the order of a centimetre per second remains (the box
    // sits on about twenty vertices solved one after another), but it does not go anywhere.
    // The span is chaotic: bit-level changes of the rigid integration move it between 2.0
    // and 3.3 mm.
    assert!(span.max_element() < 0.005, "the box still moves: {span}");
    assert!(b.v.length() < 0.03 && b.w.length() < 0.15, "at rest: {} {}", b.v, b.w);
    assert!((b.xf.p - c).with_y(0.0).length() < 0.05, "on top of the ball");
    assert!(worst < 0.05, "volume error {worst}");
    dent
}

#[test]
fn a_box_rests_on_a_slope_of_vertices() {
    // A soft slab tilted by 0.2 rad (tan 0.2 < friction 0.55) with its bottom layer pinned:
    // a box on it stays put (velocity-only friction let it creep down at 2.8 cm/s).
    let mut w = world();
    let q = Quat::from_rotation_z(0.2);
    let def = SoftBodyDef {
        transform: Transform::new(Vec3::new(0.0, 1.0, 0.0), q),
        mass: 5.0,
        ..Default::default()
    };
    let h = w
        .create_soft_body(&def, &mesh::lattice(Vec3::new(0.5, 0.1, 0.5), [8, 2, 8]), None)
        .unwrap();
    for k in 0..=8u32 {
        for i in 0..=8u32 {
            w.pin_soft_vertex(h, i + 9 * 3 * k, None).unwrap();
        }
    }
    let p0 = Vec3::new(0.0, 1.0, 0.0) + q * Vec3::new(0.0, 0.211, 0.0);
    let bx = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(p0, q),
            ..Default::default()
        })
        .unwrap();
    let geom = Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::new(0.2, 0.1, 0.2),
    };
    w.create_shape(
        bx,
        &ShapeDef {
            density: 100.0,
            ..Default::default()
        },
        &geom,
    )
    .unwrap();
    for _ in 0..60 {
        w.step(DT).unwrap();
    }
    let p1 = w.transform(bx).unwrap().p;
    for _ in 0..180 {
        w.step(DT).unwrap();
    }
    let p2 = w.transform(bx).unwrap().p;
    println!("box on a slope: moved {:.2} mm in 3 s", 1000.0 * p2.distance(p1));
    assert!(p2.distance(p1) < 0.005, "the box creeps: {p1} -> {p2}");
}

#[test]
fn pins_to_a_dynamic_body_pull_it_and_keep_momentum() {
    // No gravity: a 0.2 kg body with a 1 kg cloth pinned along one edge; the cloth is
    // thrown sideways. The body is dragged along and the total momentum stays.
    let mut w = World::new(WorldSettings {
        gravity: Vec3::ZERO,
        enable_sleep: false,
        ..Default::default()
    })
    .unwrap();
    // Along the cloth's edge z = -0.5, just clear of it.
    let body = dynamic_box(&mut w, Vec3::new(0.0, 0.0, -0.57), Vec3::new(0.5, 0.05, 0.05), 20.0);
    let m_body = w.body(body).unwrap().mass;
    // No air drag (it takes momentum away); deformation damping keeps it.
    let def = SoftBodyDef {
        mass: 1.0,
        damping: 0.0,
        ..Default::default()
    };
    let h = w.create_soft_body(&def, &mesh::cloth(1.0, 1.0, 10, 10), None).unwrap();
    for i in 0..=10 {
        w.pin_soft_vertex(h, i, Some(body)).unwrap();
    }
    let pinned_mass = 11.0 / 121.0;
    let j = Vec3::new(0.0, 0.0, 1.0);
    w.apply_soft_impulse(h, None, j).unwrap();
    let momentum = |w: &World| {
        let s = w.soft_body(h).unwrap();
        let p: Vec3 = s.vel.iter().zip(&s.inv_mass).map(|(v, &im)| *v / im).sum();
        p + w.body(body).unwrap().v * m_body
    };
    // The impulse reaches the free vertices only (pinned ones ignore it).
    let expected = j * (1.0 - pinned_mass);
    for _ in 0..60 {
        w.step(DT).unwrap();
    }
    let p = momentum(&w);
    let vb = w.body(body).unwrap().v;
    println!("pinned cloth: momentum {p} (expected {expected}), body velocity {vb}");
    assert!((p - expected).length() < 0.01 * expected.length(), "{p} vs {expected}");
    assert!(vb.z > 0.5, "the cloth drags the body: {vb}");
}

#[test]
fn a_weight_hangs_from_a_cloth() {
    // A cloth hung by two corners from the world holds a 0.5 kg box pinned to its two
    // bottom corners: the box hangs below it at rest (a one-way pin would let it fall).
    let mut w = world();
    let n = 16u32;
    let def = SoftBodyDef {
        transform: Transform::new(
            Vec3::new(0.0, 3.0, 0.0),
            Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
        ),
        mass: 0.5,
        ..Default::default()
    };
    // Rotated a quarter turn about x: the cloth hangs in the XY plane, row 0 at the top.
    let h = w.create_soft_body(&def, &mesh::cloth(1.0, 1.0, n, n), None).unwrap();
    w.pin_soft_vertex(h, 0, None).unwrap();
    w.pin_soft_vertex(h, n, None).unwrap();
    let low = n * (n + 1);
    let bottom_y = w.soft_body(h).unwrap().pos[low as usize].y;
    let weight = dynamic_box(
        &mut w,
        Vec3::new(0.0, bottom_y - 0.06, 0.0),
        Vec3::new(0.5, 0.05, 0.05),
        100.0,
    );
    w.pin_soft_vertex(h, low, Some(weight)).unwrap();
    w.pin_soft_vertex(h, low + n, Some(weight)).unwrap();
    for _ in 0..300 {
        w.step(DT).unwrap();
    }
    let b = w.body(weight).unwrap();
    let s = w.soft_body(h).unwrap();
    println!(
        "weight of {:.2} kg under a cloth: box at {:.4} m (started {:.4} m), speed {:.4}, cloth corner {:.4} m",
        b.mass,
        b.xf.p.y,
        bottom_y - 0.06,
        b.v.length(),
        s.pos[low as usize].y
    );
    assert!(
        (b.xf.p.y - (bottom_y - 0.06)).abs() < 0.05,
        "the box hangs where it was: {}",
        b.xf.p.y
    );
    assert!(b.v.length() < 0.02, "at rest: {}", b.v);
    assert!(
        (s.pos[low as usize] - b.xf.apply(Vec3::new(-0.5, 0.06, 0.0))).length() < 0.01,
        "pinned"
    );
}

#[test]
fn settings_change_after_creation() {
    let mut w = world();
    let h = ball(&mut w, 0.52, 500.0);
    let mut st = w.soft_body_settings(h).unwrap();
    assert_eq!(st.pressure, 500.0);
    st.pressure = 1000.0;
    st.damping = 2.0;
    st.friction = 0.9;
    st.edge_compliance = 1.0e-4;
    w.set_soft_body_settings(h, &st).unwrap();
    assert_eq!(w.soft_body_settings(h).unwrap(), st);
    let bad = hearth::soft::SoftBodySettings { substeps: 0, ..st };
    assert!(w.set_soft_body_settings(h, &bad).is_err());
    let bad = hearth::soft::SoftBodySettings {
        damping: f32::NAN,
        ..st
    };
    assert!(w.set_soft_body_settings(h, &bad).is_err());
    assert_eq!(w.soft_body_settings(h).unwrap(), st, "a failed call changes nothing");
    for _ in 0..60 {
        w.step(DT).unwrap();
    }
    let s = w.soft_body(h).unwrap();
    assert!(s.pos.iter().all(|p| p.is_finite()));
}

#[test]
fn pins_follow_their_body_and_are_freed_when_it_is_destroyed() {
    let mut w = world();
    let pole = w
        .create_body(&BodyDef {
            body_type: BodyType::Kinematic,
            transform: at(Vec3::new(0.0, 3.0, 0.0)),
            linear_velocity: Vec3::new(1.0, 0.0, 0.0),
            ..Default::default()
        })
        .unwrap();
    w.create_shape(
        pole,
        &ShapeDef::default(),
        &Geometry::Capsule {
            a: Vec3::new(0.0, -1.0, 0.0),
            b: Vec3::new(0.0, 1.0, 0.0),
            radius: 0.05,
        },
    )
    .unwrap();
    let def = SoftBodyDef {
        transform: Transform::new(
            Vec3::new(0.6, 3.0, 0.0),
            Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
        ),
        mass: 0.5,
        ..Default::default()
    };
    // A flag: 1 m × 0.6 m; its left column (x = 0.1) pinned to the pole.
    let h = w.create_soft_body(&def, &mesh::cloth(1.0, 0.6, 10, 6), None).unwrap();
    for j in 0..=6u32 {
        w.pin_soft_vertex(h, 11 * j, Some(pole)).unwrap();
    }
    assert!(w.soft_vertex_is_pinned(h, 11).unwrap());
    for _ in 0..60 {
        w.step(DT).unwrap();
    }
    let pole_x = w.transform(pole).unwrap().p.x;
    let s = w.soft_body(h).unwrap();
    assert!(
        (s.pos[0].x - (pole_x + 0.1)).abs() < 1e-3,
        "{} vs {}",
        s.pos[0].x,
        pole_x
    );
    w.destroy_body(pole).unwrap();
    assert!(!w.soft_vertex_is_pinned(h, 11).unwrap());
    let y0 = w.soft_body(h).unwrap().pos[0].y;
    for _ in 0..30 {
        w.step(DT).unwrap();
    }
    assert!(w.soft_body(h).unwrap().pos[0].y < y0 - 0.1, "freed vertices fall");
}

#[test]
fn impulses_move_the_body_and_bad_input_is_rejected() {
    let mut w = World::new(WorldSettings {
        gravity: Vec3::ZERO,
        ..Default::default()
    })
    .unwrap();
    let h = w
        .create_soft_body(
            &SoftBodyDef::default(),
            &mesh::lattice(Vec3::splat(0.5), [2, 2, 2]),
            None,
        )
        .unwrap();
    w.apply_soft_impulse(h, None, Vec3::new(2.0, 0.0, 0.0)).unwrap();
    w.step(DT).unwrap();
    let v: Vec3 = w.soft_body(h).unwrap().vel.iter().copied().sum::<Vec3>() / 27.0;
    assert!((v.x - 2.0).abs() < 0.05, "{v}");
    assert!(w.apply_soft_impulse(h, Some(27), Vec3::X).is_err());
    assert!(w.pin_soft_vertex(h, 1000, None).is_err());
    let bad = SoftBodyDef {
        mass: -1.0,
        ..Default::default()
    };
    assert!(w.create_soft_body(&bad, &mesh::icosphere(1.0, 0), None).is_err());
    let broken = mesh::SoftMesh {
        vertices: vec![Vec3::ZERO; 3],
        triangles: vec![[0, 1, 5]],
        extra_edges: vec![],
    };
    assert!(w.create_soft_body(&SoftBodyDef::default(), &broken, None).is_err());
    w.destroy_soft_body(h).unwrap();
    assert!(w.soft_body(h).is_err());
    assert!(w.destroy_soft_body(h).is_err());
}

#[test]
fn soft_bodies_are_deterministic_and_do_not_allocate_in_a_steady_step() {
    let run = || {
        let mut w = world();
        let h = ball(&mut w, 1.0, 500.0);
        for _ in 0..120 {
            w.step(DT).unwrap();
        }
        let before = thread_allocs::allocations();
        for _ in 0..30 {
            w.step(DT).unwrap();
        }
        let allocations = thread_allocs::allocations() - before;
        (w.soft_body(h).unwrap().pos.clone(), allocations)
    };
    let (a, n) = run();
    let (b, _) = run();
    assert_eq!(a, b);
    assert_eq!(n, 0, "allocations in a steady step");
}

#[test]
fn a_box_resting_on_a_ball_does_not_allocate_in_a_steady_step() {
    // The skin's face contacts and the fixed-geometry hold (a box on the ball, the ball
    // squeezed against the ground and the crate's walls) keep their lists' capacity too.
    let mut w = world();
    for (p, half) in [
        (Vec3::new(0.61, 0.25, 0.0), Vec3::new(0.1, 0.25, 0.71)),
        (Vec3::new(-0.61, 0.25, 0.0), Vec3::new(0.1, 0.25, 0.71)),
        (Vec3::new(0.0, 0.25, 0.61), Vec3::new(0.71, 0.25, 0.1)),
        (Vec3::new(0.0, 0.25, -0.61), Vec3::new(0.71, 0.25, 0.1)),
    ] {
        static_box(&mut w, p, half);
    }
    let h = ball(&mut w, 0.5, 400.0);
    let half = Vec3::new(0.2, 0.1, 0.2);
    // 40 kg on the 5 kg ball.
    dynamic_box(
        &mut w,
        Vec3::new(0.0, 1.2, 0.0),
        half,
        40.0 / (8.0 * half.x * half.y * half.z),
    );
    // Ten seconds for the box to settle: while it still moves, the stage's lists are still
    // growing to their steady capacity (4 allocations measured after 4 s, none after 10 s).
    for _ in 0..600 {
        w.step(DT).unwrap();
    }
    let before = thread_allocs::allocations();
    let mut faces = 0;
    for _ in 0..60 {
        w.step(DT).unwrap();
        faces += w.soft_body(h).unwrap().face_contacts.len();
    }
    let allocations = thread_allocs::allocations() - before;
    assert!(faces > 0, "the box should be held by the skin's faces");
    assert_eq!(allocations, 0, "allocations in a steady step");
}

//! Joints against analytic answers and stress scenes: a hinge pendulum's period, a heavy
//! chain's stretch and stillness, a motor reaching its speed, limits under load, a ragdoll
//! settling, Newton's cradle, breaking, the body-destruction rule and determinism.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use hearth::joints::{BallParams, DistanceParams, HingeParams, SliderParams};
use hearth::math::{Quat, Transform, Vec3};
use hearth::{BodyDef, BodyHandle, BodyType, Geometry, JointDef, JointKind, ShapeDef, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;

/// A world at the default settings (6 sub-steps, 1 velocity iteration), sleep on or off.
fn world(sleep: bool) -> World {
    World::new(WorldSettings {
        enable_sleep: sleep,
        ..Default::default()
    })
    .unwrap()
}

fn body(w: &mut World, p: Vec3, q: Quat) -> BodyHandle {
    w.create_body(&BodyDef {
        body_type: BodyType::Dynamic,
        transform: Transform::new(p, q),
        ..Default::default()
    })
    .unwrap()
}

fn sphere(w: &mut World, p: Vec3, r: f32, density: f32) -> BodyHandle {
    let b = body(w, p, Quat::IDENTITY);
    let def = ShapeDef {
        density,
        ..Default::default()
    };
    w.create_shape(
        b,
        &def,
        &Geometry::Sphere {
            center: Vec3::ZERO,
            radius: r,
        },
    )
    .unwrap();
    b
}

fn capsule(w: &mut World, p: Vec3, q: Quat, half: f32, r: f32, density: f32) -> BodyHandle {
    let b = body(w, p, q);
    let def = ShapeDef {
        density,
        ..Default::default()
    };
    w.create_shape(
        b,
        &def,
        &Geometry::Capsule {
            a: Vec3::new(0.0, -half, 0.0),
            b: Vec3::new(0.0, half, 0.0),
            radius: r,
        },
    )
    .unwrap();
    b
}

fn ground(w: &mut World) -> BodyHandle {
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
    g
}

/// A joint between `a` and `b` (None: the world) at the world point `anchor`, with the joint
/// frame's Z axis along world `axis`.
fn joint_at(w: &World, kind: JointKind, a: BodyHandle, b: Option<BodyHandle>, anchor: Vec3, axis: Vec3) -> JointDef {
    let q = Quat::from_rotation_arc(Vec3::Z, axis.normalize());
    let world_frame = Transform::new(anchor, q);
    let xa = w.transform(a).unwrap();
    let mut def = JointDef::new(kind);
    def.body_a = a;
    def.frame_a = xa.inv_mul(&world_frame);
    if let Some(b) = b {
        def.body_b = b;
        def.frame_b = w.transform(b).unwrap().inv_mul(&world_frame);
    } else {
        def.frame_b = world_frame;
    }
    def
}

fn ball() -> JointKind {
    JointKind::Ball(BallParams::default())
}

fn hinge() -> JointKind {
    JointKind::Hinge(HingeParams::default())
}

fn run(w: &mut World, seconds: f32) {
    for _ in 0..(seconds / DT).round() as usize {
        w.step(DT).unwrap();
    }
}

#[test]
fn hinge_pendulum_matches_its_period() {
    let mut w = world(false);
    let (r, l, theta0) = (0.1f32, 1.0f32, 0.2f32);
    let pivot = Vec3::new(0.0, 10.0, 0.0);
    let bob = sphere(
        &mut w,
        pivot + l * Vec3::new(theta0.sin(), -theta0.cos(), 0.0),
        r,
        1000.0,
    );
    let def = joint_at(&w, hinge(), bob, None, pivot, Vec3::Z);
    w.create_joint(&def).unwrap();
    let m = w.body(bob).unwrap().mass;
    let inertia = 0.4 * m * r * r + m * l * l;
    let t0 = 2.0 * std::f32::consts::PI * (inertia / (m * G * l)).sqrt();
    let expected = t0 * (1.0 + theta0 * theta0 / 16.0 + 11.0 * theta0.powi(4) / 3072.0);
    // Times the bob crosses x = 0 moving in +x, interpolated within the step.
    let mut crossings = Vec::new();
    let mut prev = w.transform(bob).unwrap().p.x;
    for k in 1..=(12.0 / DT) as usize {
        w.step(DT).unwrap();
        let x = w.transform(bob).unwrap().p.x;
        if prev < 0.0 && x >= 0.0 {
            crossings.push((k as f32 - 1.0 + prev / (prev - x)) * DT);
        }
        prev = x;
    }
    let n = crossings.len() - 1;
    let period = (crossings[n] - crossings[0]) / n as f32;
    let err = (period - expected).abs() / expected;
    println!(
        "pendulum: period {period:.5} s, expected {expected:.5} s, error {:.4}%",
        err * 100.0
    );
    // README: "hinge pendulum period within 0.001 %" (measured 0.0004 %).
    assert!(
        n >= 4 && err < 1e-5,
        "period {period}, expected {expected}, error {err:e}"
    );
}

/// A chain of `n` capsule links on ball joints from a world anchor, ending in a sphere of
/// `end_ratio` times a link's mass. Returns (links, end, anchor, rest length to the end).
fn heavy_chain(w: &mut World, n: usize, end_ratio: f32, angle: f32) -> (Vec<BodyHandle>, BodyHandle, Vec3, f32) {
    let (half, r, link) = (0.2f32, 0.05f32, 0.5f32);
    let anchor = Vec3::new(0.0, 20.0, 0.0);
    let mut links = Vec::new();
    let mut prev: Option<BodyHandle> = None;
    // Laid out straight at `angle` from hanging straight down.
    let dir = Vec3::new(angle.sin(), -angle.cos(), 0.0);
    let rot = Quat::from_rotation_z(angle);
    for i in 0..n {
        let c = anchor + (i as f32 + 0.5) * link * dir;
        let b = capsule(w, c, rot, half, r, 1000.0);
        let joint_point = anchor + i as f32 * link * dir;
        let def = match prev {
            None => joint_at(w, ball(), b, None, joint_point, Vec3::Z),
            Some(p) => joint_at(w, ball(), b, Some(p), joint_point, Vec3::Z),
        };
        w.create_joint(&def).unwrap();
        links.push(b);
        prev = Some(b);
    }
    let link_mass = w.body(links[0]).unwrap().mass;
    let er = 0.3f32;
    let volume = 4.0 / 3.0 * std::f32::consts::PI * er.powi(3);
    let end_point = anchor + n as f32 * link * dir;
    let end = sphere(w, end_point + er * dir, er, end_ratio * link_mass / volume);
    let def = joint_at(w, ball(), end, prev, end_point, Vec3::Z);
    w.create_joint(&def).unwrap();
    (links, end, anchor, n as f32 * link + er)
}

/// Distance between a joint's two anchors now (m).
fn gap(w: &World, j: hearth::JointHandle) -> f32 {
    let def = w.joint(j).unwrap().def;
    let pa = w.transform(def.body_a).unwrap().apply(def.frame_a.p);
    let pb = if def.body_b.is_null() {
        def.frame_b.p
    } else {
        w.transform(def.body_b).unwrap().apply(def.frame_b.p)
    };
    (pa - pb).length()
}

fn joint_handles(w: &World) -> Vec<hearth::JointHandle> {
    w.joints.pool.iter().map(|(h, _)| h).collect()
}

#[test]
fn heavy_chain_barely_stretches_and_does_not_jitter() {
    // At the world's default settings. The forest solves the joints' point rows exactly
    // (joints/tree.rs); Gauss–Seidel alone stretched this chain 2.34 % at 6 sub-steps (1.32 %
    // at 8, 0.59 % at 12): each row saw only its two bodies, the heavy end mass' load reached
    // the anchor a little per sweep. Measured now: 0.000 % hanging, 0.001 % swinging.
    for (angle, what) in [(0.0f32, "hanging"), (30.0, "swinging from 30°")] {
        let mut w = world(false);
        let (links, end, _anchor, rest) = heavy_chain(&mut w, 20, 100.0, angle.to_radians());
        let js = joint_handles(&w);
        let mut max_stretch = 0.0f32;
        let mut late_speed = 0.0f32;
        for k in 0..(10.0 / DT) as usize {
            w.step(DT).unwrap();
            let total: f32 = js.iter().map(|&j| gap(&w, j)).sum();
            max_stretch = max_stretch.max(total / rest);
            if k as f32 * DT > 8.0 {
                for &b in links.iter().chain([&end]) {
                    late_speed = late_speed.max(w.linear_velocity(b).unwrap().length());
                }
            }
        }
        println!(
            "chain {what}: largest stretch {:.4}%, late speed {late_speed:.2e} m/s",
            max_stretch * 100.0
        );
        assert_eq!(w.settings.substeps, WorldSettings::default().substeps);
        // README and ARCHITECTURE: the hanging chain "stretches 0.000 %", i.e. under
        // 0.0005 % (measured 0.0003 %); swinging from 30° it measures 0.0012 %.
        let limit = if angle == 0.0 { 5e-6 } else { 2e-5 };
        assert!(max_stretch < limit, "{what}: stretch {:.5} %", 100.0 * max_stretch);
        if angle == 0.0 {
            // Hanging at rest: no jitter.
            assert!(late_speed < 1e-4, "hanging chain jitters: {late_speed} m/s");
        }
    }
}

#[test]
fn motorised_hinge_reaches_its_target_speed() {
    let mut w = world(false);
    let wheel = body(&mut w, Vec3::new(0.0, 5.0, 0.0), Quat::IDENTITY);
    w.create_shape(
        wheel,
        &ShapeDef::default(),
        &Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::new(1.0, 0.1, 0.5),
        },
    )
    .unwrap();
    let def = joint_at(&w, hinge(), wheel, None, Vec3::new(0.0, 5.0, 0.0), Vec3::Z);
    let j = w.create_joint(&def).unwrap();
    w.set_joint_motor(j, true, 3.0, 500.0).unwrap();
    run(&mut w, 2.0);
    // The motor speed is B's relative to A (Box2D's convention); the wheel is A, the world B.
    let speed = -w.angular_velocity(wheel).unwrap().z;
    println!("motor: {speed:.5} rad/s, target 3");
    assert!((speed - 3.0).abs() < 0.01, "motor speed {speed}");
    let (_, torque) = w.joint_force(j).unwrap();
    assert!(torque.z.abs() <= 500.0 + 1.0);
    // A weak motor cannot hold a load: the torque saturates at its maximum.
    w.set_joint_motor(j, true, 0.0, 1.0).unwrap();
    run(&mut w, 0.5);
    let (_, torque) = w.joint_force(j).unwrap();
    assert!(
        (torque.z.abs() - 1.0).abs() < 0.05,
        "saturated motor torque {}",
        torque.z
    );
}

/// Torques on the limited arm: 20× and 200× its weight's moment. The limit row is coupled
/// with the hinge's point and axis rows (it sees the arm's inertia about the hinge, 10.2 kg·m²,
/// not about its centre, 0.16), so the limit holds (solved one after another, the arm
/// overshot by 0.03 rad at 200 N·m and 0.12 rad at 2000 N·m).
const LIMIT_TORQUES: [f32; 2] = [200.0, 2000.0];

#[test]
fn hinge_and_slider_limits_hold_under_load() {
    // A 10 kg arm on a hinge limited to ±0.3 rad, pushed against its upper limit.
    for torque in LIMIT_TORQUES {
        let mut w = world(false);
        let arm = sphere(&mut w, Vec3::new(1.0, 5.0, 0.0), 0.2, 300.0);
        let mut def = joint_at(&w, hinge(), arm, None, Vec3::new(0.0, 5.0, 0.0), Vec3::Z);
        if let JointKind::Hinge(p) = &mut def.kind {
            (p.enable_limit, p.lower, p.upper) = (true, -0.3, 0.3);
        }
        w.create_joint(&def).unwrap();
        let mut worst = 0.0f32;
        for _ in 0..120 {
            w.apply_torque(arm, Vec3::new(0.0, 0.0, torque), true).unwrap();
            w.step(DT).unwrap();
            let p = w.transform(arm).unwrap().p - Vec3::new(0.0, 5.0, 0.0);
            worst = worst.max(p.y.atan2(p.x));
        }
        let p = w.transform(arm).unwrap().p - Vec3::new(0.0, 5.0, 0.0);
        let settled = p.y.atan2(p.x);
        println!(
            "hinge limit: largest angle {worst:.4} rad, settled {settled:.4} under {torque} N·m (limit 0.3), joint gap {:.2e} m",
            gap(&w, joint_handles(&w)[0])
        );
        // README: the limit holds "without overshoot" (measured 0.2981 rad, under the
        // limit: the point rows give a little, so the arm's centre sits slightly inside).
        assert!(worst < 0.3 + 1e-4, "hinge angle {worst} under {torque} N·m");
        // ARCHITECTURE: held at its limit, the arm "sags 1.9 mm" (measured 1.86 mm).
        let sag = gap(&w, joint_handles(&w)[0]);
        assert!(sag < 1.95e-3, "joint gap at the limit {sag} m");
        // The point rows' stiff soft response gives a little under the load (the angle is
        // measured at the arm's centre, 1 m out).
        assert!((settled - 0.3).abs() < 0.01, "settled hinge angle {settled}");
    }

    // A slider along world Y limited to [-0.5, 0.5], loaded by gravity and a 5000 N push.
    let mut w = world(false);
    let block = sphere(&mut w, Vec3::new(0.0, 5.0, 0.0), 0.2, 1000.0);
    let mut def = joint_at(
        &w,
        JointKind::Slider(SliderParams::default()),
        block,
        None,
        Vec3::new(0.0, 5.0, 0.0),
        Vec3::Y,
    );
    if let JointKind::Slider(p) = &mut def.kind {
        (p.enable_limit, p.lower, p.upper) = (true, -0.5, 0.5);
    }
    w.create_joint(&def).unwrap();
    let mut lowest = f32::MAX;
    for _ in 0..120 {
        w.apply_force(block, Vec3::new(300.0, -5000.0, 0.0), true).unwrap();
        w.step(DT).unwrap();
        lowest = lowest.min(w.transform(block).unwrap().p.y);
    }
    let p = w.transform(block).unwrap().p;
    println!("slider limit: lowest {:.4} (limit 4.5), sideways {:.2e}", lowest, p.x);
    assert!(lowest > 4.5 - 0.01 && p.x.abs() < 1e-3, "slider at {p}");
    // The motor drives it up to the upper limit.
    let j = joint_handles(&w)[0];
    // B (the world) relative to A (the block) moves down, so the block moves up.
    w.set_joint_motor(j, true, -1.0, 1.0e5).unwrap();
    run(&mut w, 2.0);
    let y = w.transform(block).unwrap().p.y;
    assert!((y - 5.5).abs() < 0.01, "slider motor to the upper limit: y = {y}");
}

#[test]
fn ball_joint_cone_and_twist_limits_hold() {
    let mut w = world(false);
    let pivot = Vec3::new(0.0, 5.0, 0.0);
    let b = capsule(
        &mut w,
        pivot + Vec3::new(0.0, -0.6, 0.0),
        Quat::IDENTITY,
        0.4,
        0.1,
        1000.0,
    );
    let mut def = joint_at(&w, ball(), b, None, pivot, -Vec3::Y);
    if let JointKind::Ball(p) = &mut def.kind {
        (p.enable_swing_limit, p.swing_limit) = (true, 0.5);
        (p.enable_twist_limit, p.lower_twist, p.upper_twist) = (true, -0.2, 0.2);
    }
    w.create_joint(&def).unwrap();
    let (mut swing, mut twist) = (0.0f32, 0.0f32);
    for _ in 0..240 {
        w.apply_force_at_point(b, Vec3::new(400.0, 0.0, 0.0), pivot + Vec3::new(0.0, -1.1, 0.0), true)
            .unwrap();
        w.apply_torque(b, Vec3::new(0.0, 20.0, 0.0), true).unwrap();
        w.step(DT).unwrap();
        let q = w.transform(b).unwrap().q;
        let axis = q * -Vec3::Y;
        swing = swing.max(axis.dot(-Vec3::Y).clamp(-1.0, 1.0).acos());
        let (tw_axis, _) = (Vec3::Y, 0);
        let qt = Quat::from_xyzw(0.0, q.y, 0.0, q.w).normalize();
        let _ = tw_axis;
        twist = twist.max(
            qt.to_axis_angle()
                .1
                .abs()
                .min(2.0 * std::f32::consts::PI - qt.to_axis_angle().1.abs()),
        );
    }
    println!("ball limits: largest swing {swing:.4} (0.5), twist {twist:.4} (0.2)");
    assert!(swing < 0.5 + 0.03, "swing {swing}");
    assert!(twist < 0.2 + 0.03, "twist {twist}");
}

/// Kinetic energy of bodies (J).
fn kinetic_energy(w: &World, bodies: &[BodyHandle]) -> f32 {
    bodies
        .iter()
        .map(|&b| {
            let body = w.body(b).unwrap();
            let (v, om) = (w.linear_velocity(b).unwrap(), w.angular_velocity(b).unwrap());
            let q = w.transform(b).unwrap().q;
            let wl = q.conjugate() * om;
            0.5 * body.mass * v.length_squared() + 0.5 * wl.dot(body.inertia_local * wl)
        })
        .sum()
}

#[test]
fn ragdoll_falls_and_settles() {
    let mut w = world(true);
    ground(&mut w);
    let parts = scenes::ragdoll(&mut w, Vec3::new(0.0, 2.0, 0.0));
    assert!(parts.len() >= 10);
    // Tip it over with a spin so it lands in a heap.
    for &b in &parts {
        w.set_angular_velocity(b, Vec3::new(0.5, 0.0, 2.0)).unwrap();
    }
    let js = joint_handles(&w);
    let potential = |w: &World| -> f32 {
        parts
            .iter()
            .map(|&b| w.body(b).unwrap().mass * G * w.transform(b).unwrap().p.y)
            .sum()
    };
    // Nothing drives the ragdoll: its energy (kinetic plus potential) never exceeds the
    // start's. (Contacts push out at up to contact_push_max_velocity, which may lift a
    // body a little: 1 % of the start energy is allowed, about 16 J.)
    let start_energy = kinetic_energy(&w, &parts) + potential(&w);
    let mut most_energy = f32::MIN;
    let mut worst_gap = 0.0f32;
    let mut max_speed = 0.0f32;
    let mut peak_energy = 0.0f32;
    let mut late_energy = 0.0f32;
    let mut settled_at = None;
    for k in 0..(8.0 / DT) as usize {
        w.step(DT).unwrap();
        for &b in &parts {
            max_speed = max_speed.max(w.linear_velocity(b).unwrap().length());
        }
        worst_gap = worst_gap.max(js.iter().map(|&j| gap(&w, j)).fold(0.0, f32::max));
        let e = kinetic_energy(&w, &parts);
        most_energy = most_energy.max(e + potential(&w));
        peak_energy = peak_energy.max(e);
        if k as f32 * DT >= 6.0 {
            late_energy = late_energy.max(e);
        }
        if e < 1.0e-3 && settled_at.is_none() {
            settled_at = Some(k as f32 * DT);
        } else if e >= 1.0e-3 {
            settled_at = None;
        }
    }
    let lowest = parts
        .iter()
        .map(|&b| w.transform(b).unwrap().p.y)
        .fold(f32::MAX, f32::min);
    let highest = parts
        .iter()
        .map(|&b| w.transform(b).unwrap().p.y)
        .fold(f32::MIN, f32::max);
    let asleep = parts.iter().filter(|&&b| !w.is_awake(b).unwrap()).count();
    let end_speed = parts
        .iter()
        .map(|&b| w.linear_velocity(b).unwrap().length())
        .fold(0.0, f32::max);
    let mass: f32 = parts.iter().map(|&b| w.body(b).unwrap().mass).sum();
    println!(
        "ragdoll: {} bodies ({mass:.1} kg), largest joint gap {worst_gap:.4} m, top speed {max_speed:.2} m/s, heights {lowest:.3}..{highest:.3}; \
         kinetic energy peak {peak_energy:.1} J, largest over 6..8 s {late_energy:.2e} J, below 1 mJ from {settled_at:?} s; end speed {end_speed:.4} m/s; asleep {asleep}",
        parts.len()
    );
    println!("ragdoll energy: start {start_energy:.1} J, largest {most_energy:.1} J");
    assert!(
        most_energy <= start_energy + 0.01 * start_energy.abs(),
        "energy grew: {start_energy} -> {most_energy} J"
    );
    // Free fall from the highest part (2.9 m up) gives 7.5 m/s. The fastest part is a 1.7 kg
    // forearm whipped as its upper arm lands (0.5 s in): 9.85 m/s measured, and at 12, 24 and
    // 48 sub-steps 7.9, 9.1 and 8.5 m/s, while the whole ragdoll's energy stays below its
    // start (asserted above). More than 11 m/s (a third more kinetic energy than measured)
    // would be a joint feeding energy into a limb.
    assert!(max_speed < 11.0, "top speed {max_speed} m/s");
    // Measured 25.4 mm (the head and limbs hitting the ground at 8 m/s).
    assert!(worst_gap < 0.03, "joint gap {worst_gap}");
    assert!(lowest > 0.0 && highest < 1.5, "heights {lowest}..{highest}");
    // At rest: 5 mJ is a 60 kg body moving at 1.3 cm/s (measured: under 1 mJ from about 3 s). The sphere head can keep rolling
    // slowly in place (a neutral mode: about the line through its neck anchor and its ground
    // contact; a one-point sphere contact has no rolling or spin friction), which keeps the
    // island awake; everything else stops.
    assert!(late_energy < 5.0e-3, "not settled: {late_energy} J after 6 s");
    assert!(end_speed < 0.02, "not settled: {end_speed} m/s");
}

/// The balls hang this far apart: a little more than a ball travels in one step, so the
/// collisions run one after another as in a real cradle. Restitution bounces a contact by its
/// approach speed at the start of the step (`contact_wide.rs`), so a ball that is hit and
/// hits within one step does not bounce: with touching balls (or 1 mm apart) the impulse
/// spreads along the row and the last ball leaves at about 40 % of the first's speed (57 % at
/// 1 cm). Passing it on through touching balls needs restitution solved per contact in
/// sequence within the step (the contact solver's business, not the joints').
const GAP: f32 = 0.03;

#[test]
fn newtons_cradle_passes_the_impulse_down_the_row() {
    let mut w = world(false);
    let (r, l, n) = (0.1f32, 1.0f32, 5);
    let material = ShapeDef {
        restitution: 1.0,
        static_friction: 0.0,
        dynamic_friction: 0.0,
        ..Default::default()
    };
    let top = 3.0;
    let mut balls = Vec::new();
    for i in 0..n {
        let x = i as f32 * (2.0 * r + GAP);
        let theta: f32 = if i == 0 { -0.5 } else { 0.0 };
        let pivot = Vec3::new(x, top, 0.0);
        let c = pivot + l * Vec3::new(theta.sin(), -theta.cos(), 0.0);
        let b = body(&mut w, c, Quat::IDENTITY);
        w.create_shape(
            b,
            &material,
            &Geometry::Sphere {
                center: Vec3::ZERO,
                radius: r,
            },
        )
        .unwrap();
        // Two strings in a V keep each ball in its plane.
        for z in [-0.5f32, 0.5] {
            let mut def = joint_at(&w, JointKind::Distance(DistanceParams::default()), b, None, c, Vec3::Z);
            def.frame_b = Transform::new(pivot + Vec3::new(0.0, 0.0, z), Quat::IDENTITY);
            if let JointKind::Distance(p) = &mut def.kind {
                p.length = (c - def.frame_b.p).length();
            }
            w.create_joint(&def).unwrap();
        }
        balls.push(b);
    }
    let v_in = {
        // Speed of the first ball at the bottom: energy.
        let h = l * (1.0 - 0.5f32.cos()) * (l / (l * l + 0.25).sqrt());
        let _ = h;
        0.0
    };
    let _ = v_in;
    let mut first_peak = 0.0f32;
    let mut last_peak = 0.0f32;
    let mut speeds_before = 0.0f32;
    for k in 0..(1.2 / DT) as usize {
        w.step(DT).unwrap();
        let vx0 = w.linear_velocity(balls[0]).unwrap().x;
        speeds_before = speeds_before.max(vx0);
        if k as f32 * DT > 0.6 {
            first_peak = first_peak.max(w.linear_velocity(balls[0]).unwrap().length());
        }
        last_peak = last_peak.max(w.linear_velocity(balls[n - 1]).unwrap().x);
    }
    println!(
        "cradle: first ball hits at {speeds_before:.3} m/s; last ball leaves at {last_peak:.3} m/s ({:.1}%), first ball after {first_peak:.3} m/s",
        100.0 * last_peak / speeds_before
    );
    assert!(
        last_peak > 0.85 * speeds_before,
        "last ball {last_peak} of {speeds_before}"
    );
    let middle = (1..n - 1)
        .map(|i| w.linear_velocity(balls[i]).unwrap().length())
        .fold(0.0, f32::max);
    assert!(middle < 0.25 * speeds_before, "middle balls move at {middle}");
}

#[test]
fn a_joint_breaks_above_its_threshold_and_is_reported() {
    let mut w = world(false);
    let b = sphere(&mut w, Vec3::new(0.0, 4.0, 0.0), 0.2, 1000.0);
    let mut def = joint_at(&w, JointKind::Fixed, b, None, Vec3::new(0.0, 5.0, 0.0), Vec3::Z);
    let weight = w.body(b).unwrap().mass * G;
    def.break_force = 2.0 * weight;
    let j = w.create_joint(&def).unwrap();
    run(&mut w, 0.5);
    let (force, torque) = w.joint_force(j).unwrap();
    // The weld holds the weight and its moment about the anchor 1 m up.
    assert!(
        (force.y + weight).abs() < 0.01 * weight,
        "force {force}, weight {weight}"
    );
    assert!((torque.length() - 0.0).abs() < 0.02 * weight, "torque {torque}");
    assert!(!w.joint(j).unwrap().broken && w.broken_joints().is_empty());
    w.apply_force(b, Vec3::new(0.0, -5.0 * weight, 0.0), true).unwrap();
    w.step(DT).unwrap();
    assert!(w.joint(j).unwrap().broken);
    assert_eq!(w.broken_joints(), &[j]);
    w.step(DT).unwrap();
    assert!(w.broken_joints().is_empty(), "the report lasts one step");
    run(&mut w, 0.5);
    assert!(w.transform(b).unwrap().p.y < 3.0, "a broken joint stops acting");
    w.destroy_joint(j).unwrap();
    assert!(w.joint(j).is_err());
}

#[test]
fn destroying_a_body_destroys_its_joints_and_wakes_the_other() {
    let mut w = world(true);
    let a = sphere(&mut w, Vec3::new(0.0, 5.0, 0.0), 0.2, 1000.0);
    let b = sphere(&mut w, Vec3::new(0.0, 4.0, 0.0), 0.2, 1000.0);
    let j1 = w
        .create_joint(&joint_at(&w, ball(), a, None, Vec3::new(0.0, 6.0, 0.0), Vec3::Z))
        .unwrap();
    let j2 = w
        .create_joint(&joint_at(&w, ball(), b, Some(a), Vec3::new(0.0, 4.5, 0.0), Vec3::Z))
        .unwrap();
    assert_eq!(w.joints.len(), 2);
    run(&mut w, 10.0);
    assert!(
        !w.is_awake(a).unwrap() && !w.is_awake(b).unwrap(),
        "the pendulum pair sleeps as one island"
    );
    w.destroy_body(a).unwrap();
    assert!(w.joint(j1).is_err() && w.joint(j2).is_err());
    assert_eq!(w.joints.len(), 0);
    assert!(w.is_awake(b).unwrap());
    run(&mut w, 0.5);
    assert!(w.transform(b).unwrap().p.y < 3.5, "b falls free");
}

#[test]
fn connected_bodies_do_not_collide_unless_asked() {
    for collide in [false, true] {
        let mut w = world(false);
        // Two overlapping boxes, welded: no contact between them unless collide_connected.
        let a = sphere(&mut w, Vec3::new(0.0, 5.0, 0.0), 0.5, 1000.0);
        let b = sphere(&mut w, Vec3::new(0.5, 5.0, 0.0), 0.5, 1000.0);
        w.step(DT).unwrap();
        assert_eq!(w.contact_count(), 1);
        let mut def = joint_at(&w, JointKind::Fixed, b, Some(a), Vec3::new(0.25, 5.0, 0.0), Vec3::Z);
        def.collide_connected = collide;
        w.create_joint(&def).unwrap();
        assert_eq!(
            w.contact_count(),
            collide as usize,
            "existing contact destroyed when filtered"
        );
        run(&mut w, 0.5);
        assert_eq!(w.contact_count(), collide as usize);
    }
}

#[test]
fn creating_a_joint_wakes_sleeping_bodies() {
    let mut w = world(true);
    ground(&mut w);
    let a = sphere(&mut w, Vec3::new(0.0, 0.5, 0.0), 0.5, 1000.0);
    run(&mut w, 3.0);
    assert!(!w.is_awake(a).unwrap());
    w.create_joint(&joint_at(&w, ball(), a, None, Vec3::new(0.0, 1.0, 0.0), Vec3::Z))
        .unwrap();
    assert!(w.is_awake(a).unwrap());
}

#[test]
fn distance_spring_oscillates_at_its_frequency() {
    let mut w = world(false);
    let b = sphere(&mut w, Vec3::new(0.0, 5.0, 0.0), 0.1, 1000.0);
    // Anchors: the ball's centre, and a world point 1 m above it.
    let mut def = JointDef::new(JointKind::Distance(DistanceParams {
        length: 1.0,
        enable_spring: true,
        spring_hertz: 2.0,
        ..Default::default()
    }));
    def.body_a = b;
    def.frame_b.p = Vec3::new(0.0, 6.0, 0.0);
    w.set_gravity(Vec3::ZERO).unwrap();
    w.create_joint(&def).unwrap();
    w.set_linear_velocity(b, Vec3::new(0.0, -0.5, 0.0)).unwrap();
    let mut crossings = Vec::new();
    let mut prev = w.linear_velocity(b).unwrap().y;
    for k in 1..=(3.0 / DT) as usize {
        w.step(DT).unwrap();
        let v = w.linear_velocity(b).unwrap().y;
        if prev < 0.0 && v >= 0.0 {
            // Interpolated within the step.
            crossings.push((k as f32 - 1.0 + prev / (prev - v)) * DT);
        }
        prev = v;
    }
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f32;
    let err = (period - 0.5).abs() / 0.5;
    println!(
        "distance spring: period {period:.5} s, expected 0.5, error {:.3} %",
        100.0 * err
    );
    // A 2 Hz spring: the period is 0.5 s within 0.1 % (measured 0.055 %).
    assert!(crossings.len() >= 5 && err < 1e-3, "period {period}");
}

#[test]
fn weld_holds_an_arm_out_sideways() {
    let mut w = world(false);
    let arm = capsule(
        &mut w,
        Vec3::new(1.0, 5.0, 0.0),
        Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
        0.5,
        0.1,
        1000.0,
    );
    w.create_joint(&joint_at(
        &w,
        JointKind::Fixed,
        arm,
        None,
        Vec3::new(0.0, 5.0, 0.0),
        Vec3::Z,
    ))
    .unwrap();
    let j = joint_handles(&w)[0];
    run(&mut w, 3.0);
    let xf = w.transform(arm).unwrap();
    let droop = 5.0 - xf.p.y;
    // The weld carries the arm's weight and its moment about the anchor 1 m away (the force
    // and torque on B, the world; the angular rows' impulses are booked and warm started).
    let weight = w.body(arm).unwrap().mass * G;
    let (force, torque) = w.joint_force(j).unwrap();
    println!("weld: arm tip droops {droop:.4} m, force {force}, torque {torque} (weight {weight:.2} N)");
    assert!(droop.abs() < 0.02 && w.angular_velocity(arm).unwrap().length() < 1e-3);
    assert!((force.y + weight).abs() < 0.01 * weight, "force {force}");
    assert!((torque.z.abs() - weight).abs() < 0.01 * weight, "torque {torque}");
}

#[test]
fn joints_are_deterministic() {
    let run_once = || {
        let mut w = world(true);
        ground(&mut w);
        let parts = scenes::ragdoll(&mut w, Vec3::new(0.0, 2.0, 0.0));
        for &b in &parts {
            w.set_angular_velocity(b, Vec3::new(0.5, 0.0, 2.0)).unwrap();
        }
        run(&mut w, 2.0);
        parts.iter().map(|&b| w.transform(b).unwrap().p).collect::<Vec<_>>()
    };
    assert_eq!(run_once(), run_once());
}

#[test]
fn invalid_defs_and_ids_are_rejected() {
    let mut w = world(false);
    let a = sphere(&mut w, Vec3::new(0.0, 5.0, 0.0), 0.2, 1000.0);
    let mut def = JointDef::new(hinge());
    assert!(matches!(w.create_joint(&def), Err(hearth::Error::InvalidId(_))));
    def.body_a = a;
    def.body_b = a;
    assert!(matches!(w.create_joint(&def), Err(hearth::Error::InvalidArgument(_))));
    def.body_b = hearth::pool::Handle::NULL;
    def.frame_a.p.x = f32::NAN;
    assert!(w.create_joint(&def).is_err());
    def.frame_a.p.x = 0.0;
    if let JointKind::Hinge(p) = &mut def.kind {
        (p.lower, p.upper) = (1.0, -1.0);
    }
    assert!(w.create_joint(&def).is_err());
    let j = w
        .create_joint(&JointDef {
            body_a: a,
            ..JointDef::new(JointKind::Fixed)
        })
        .unwrap();
    assert!(w.set_joint_motor(j, true, 1.0, 1.0).is_err());
    assert!(w.set_joint_limits(j, true, -1.0, 1.0).is_err());
    w.destroy_joint(j).unwrap();
    assert!(matches!(w.destroy_joint(j), Err(hearth::Error::InvalidId(_))));
}

// ------------------------------------------------------------------ allocation per step

/// Counts allocations per thread, so the other tests of this binary running in parallel do
/// not disturb the count.
struct Counting;

thread_local! {
    static ALLOCATIONS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

unsafe impl std::alloc::GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: std::alloc::Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        std::alloc::System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: std::alloc::Layout) {
        std::alloc::System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: std::alloc::Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        std::alloc::System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn steady_joint_steps_do_not_allocate() {
    let mut w = world(true);
    ground(&mut w);
    let parts = scenes::ragdoll(&mut w, Vec3::new(0.0, 2.0, 0.0));
    let (_links, _end, _, _) = heavy_chain(&mut w, 10, 10.0, 0.5);
    for &b in &parts {
        w.set_angular_velocity(b, Vec3::new(0.5, 0.0, 2.0)).unwrap();
    }
    run(&mut w, 2.0);
    let before = ALLOCATIONS.with(|c| c.get());
    run(&mut w, 1.0);
    let after = ALLOCATIONS.with(|c| c.get());
    assert_eq!(after - before, 0, "allocations in 60 steps with joints");
}

#[test]
fn a_joint_grid_hangs_without_blowing_up() {
    // Box3D's joint_grid, 20×20: spheres joined to their left and upper neighbours.
    let n = 20;
    let mut w = world(false);
    let mut ids: Vec<BodyHandle> = Vec::new();
    for k in 0..n {
        for i in 0..n {
            let fixed = i == 0 && k + 3 >= n / 2 && k <= n / 2 + 3;
            let p = Vec3::new(k as f32, -(i as f32), 0.0);
            let b = if fixed {
                w.create_body(&BodyDef {
                    transform: Transform::new(p, Quat::IDENTITY),
                    ..Default::default()
                })
                .unwrap()
            } else {
                sphere(&mut w, p, 0.4, 1000.0)
            };
            let join = |w: &mut World, other: BodyHandle, offset: Vec3| {
                if fixed && w.body(other).unwrap().is_static() {
                    return;
                }
                let mut def = JointDef::new(ball());
                (def.body_a, def.body_b, def.frame_a.p, def.frame_b.p) = (b, other, offset, -offset);
                w.create_joint(&def).unwrap();
            };
            if i > 0 {
                join(&mut w, ids[k * n + i - 1], Vec3::new(0.0, 0.5, 0.0));
            }
            if k > 0 {
                join(&mut w, ids[(k - 1) * n + i], Vec3::new(-0.5, 0.0, 0.0));
            }
            ids.push(b);
        }
    }
    let js = joint_handles(&w);
    run(&mut w, 10.0);
    let worst = js.iter().map(|&j| gap(&w, j)).fold(0.0f32, f32::max);
    let speed = ids
        .iter()
        .map(|&b| w.linear_velocity(b).unwrap().length())
        .fold(0.0f32, f32::max);
    println!("joint grid 20×20 after 10 s: largest joint gap {worst:.4} m, top speed {speed:.3} m/s");
    // Measured: gap 3.5 mm, at rest (1 mm/s) after 10 s.
    assert!(worst < 4e-3, "largest joint gap {worst} m");
    assert!(speed < 0.01, "the grid should hang at rest: {speed} m/s");
}

//! Soft bodies against the proofs: a pressurised 642-vertex ball bounces, settles and
//! keeps its volume; doubling the pressure makes it stiffer; a stiffness sweep over four
//! orders of magnitude stays finite without energy growth for 60 s; a cloth pinned at two
//! corners hangs without stretching; a soft ball pushes a rigid box (two-way); pins follow
//! bodies and are freed with them;
//! determinism and no allocation in a steady step.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use hearth::math::{Quat, Transform, Vec3};
use hearth::soft::{mesh, SoftBodyDef, SoftBodyHandle};
use hearth::{scenes, BodyDef, BodyType, Geometry, ShapeDef, World, WorldSettings};

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

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

/// The 642-vertex pressurised ball of radius 0.5 m and 5 kg.
fn ball_def(height: f32, pressure: f32) -> SoftBodyDef {
    SoftBodyDef {
        transform: at(Vec3::new(0.0, height, 0.0)),
        mass: 5.0,
        pressure,
        edge_compliance: 1.0e-5,
        damping: 1.0,
        substeps: 40,
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
    assert!(volume_error < 0.05, "volume error {volume_error}");
    assert!(worst < 0.05, "worst volume error {worst}");
}

#[test]
fn doubling_the_pressure_makes_the_ball_stiffer() {
    // Flattening under its own weight: free height (no gravity) minus resting height.
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
    assert!(flat[1] < 0.9 * flat[0], "{flat:?}");
}

#[test]
fn stiffness_sweep_stays_finite_without_energy_growth() {
    for compliance in [1.0e-7, 1.0e-6, 1.0e-5, 1.0e-4, 1.0e-3] {
        let mut w = world();
        let def = SoftBodyDef {
            edge_compliance: compliance,
            bend_compliance: compliance,
            substeps: 20,
            ..ball_def(1.0, 300.0)
        };
        let h = w.create_soft_body(&def, &mesh::icosphere(0.5, 3), None).unwrap();
        let mut early: f32 = f32::MIN;
        let mut late: f32 = f32::MIN;
        for step in 0..3600 {
            w.step(DT).unwrap();
            let s = w.soft_body(h).unwrap();
            assert!(
                s.pos.iter().chain(&s.vel).all(|v| v.is_finite()),
                "compliance {compliance}"
            );
            let (k, p) = energy(&w, h);
            if (600..1200).contains(&step) {
                early = early.max(k + p);
            } else if step >= 1200 {
                late = late.max(k + p);
            }
        }
        let (k, _) = energy(&w, h);
        println!(
            "compliance {compliance:e}: max energy 10-20 s {early:.3} J, 20-60 s {late:.3} J, final kinetic {k:.5}"
        );
        assert!(
            late <= early + 0.01,
            "energy grew: {early} -> {late} (compliance {compliance})"
        );
        assert!(k < 0.05, "still moving: {k}");
    }
}

#[test]
fn cloth_pinned_at_two_corners_hangs_without_stretching() {
    let mut w = world();
    let (cols, rows) = (16u32, 16u32);
    let def = SoftBodyDef {
        transform: at(Vec3::new(0.0, 3.0, 0.0)),
        mass: 1.0,
        edge_compliance: 0.0,
        bend_compliance: 1.0,
        substeps: 40,
        ..Default::default()
    };
    let h = w
        .create_soft_body(&def, &mesh::cloth(2.0, 2.0, cols, rows), None)
        .unwrap();
    // Horizontal at first: it swings down about the edge z = -1 and hangs.
    w.pin_soft_vertex(h, 0, None).unwrap();
    w.pin_soft_vertex(h, cols, None).unwrap();
    let rest = mesh::cloth(2.0, 2.0, cols, rows);
    let edges = edges_of(&rest);
    for _ in 0..600 {
        w.step(DT).unwrap();
    }
    let s = w.soft_body(h).unwrap();
    let mut worst: f32 = 0.0;
    for &(a, b, l) in &edges {
        let d = s.pos[a as usize].distance(s.pos[b as usize]);
        worst = worst.max(d / l - 1.0);
    }
    let low = s.pos.iter().map(|p| p.y).fold(f32::MAX, f32::min);
    println!(
        "cloth: worst edge stretch {:.2} %, lowest point {low:.3} m",
        100.0 * worst
    );
    assert!(worst < 0.05, "stretch {worst}");
    assert!(low < 1.3, "the cloth should hang down, lowest {low}");
    assert!(
        s.pos[0].distance(Vec3::new(-1.0, 3.0, -1.0)) < 1e-4,
        "the pin holds: {}",
        s.pos[0]
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
    assert!(p.x > 1.25, "the box should be pushed along +x: {}", p.x);
    assert!(c.x < p.x, "the ball stays behind the box");
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
        let before = ALLOCATIONS.with(|c| c.get());
        for _ in 0..30 {
            w.step(DT).unwrap();
        }
        let allocations = ALLOCATIONS.with(|c| c.get()) - before;
        (w.soft_body(h).unwrap().pos.clone(), allocations)
    };
    let (a, n) = run();
    let (b, _) = run();
    assert_eq!(a, b);
    assert_eq!(n, 0, "allocations in a steady step");
}

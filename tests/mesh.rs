//! Triangle meshes against truth: resting heights, seams, tunnelling, the BVH against brute
//! force, degenerate triangles, creases (several manifolds), kinematic meshes, randomized
//! drops on terrain.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
#[path = "terrain/mod.rs"]
mod terrain;
use terrain::{ball, body, cube, material, world};

use hearth::collision::aabb::Aabb;
use hearth::math::{Quat, Transform, Vec3};
use hearth::world::{LaneWidth, World, WorldSettings};
use hearth::{BodyDef, BodyHandle, BodyType, Error, Geometry, ShapeDef};

const DT: f32 = 1.0 / 60.0;

/// A static mesh body from vertices and triangles, placed and scaled.
fn static_mesh(w: &mut World, v: &[Vec3], t: &[[u32; 3]], local: Transform, scale: Vec3) -> BodyHandle {
    static_mesh_with(w, v, t, local, scale, 0.6)
}

fn static_mesh_with(
    w: &mut World,
    v: &[Vec3],
    t: &[[u32; 3]],
    local: Transform,
    scale: Vec3,
    friction: f32,
) -> BodyHandle {
    let mesh = w.create_mesh(v, t).unwrap();
    let g = w.create_body(&BodyDef::default()).unwrap();
    w.create_shape(g, &material(friction), &Geometry::Mesh { mesh, local, scale })
        .unwrap();
    g
}

/// A flat grid of `cells²` unit cells centred on the origin at y = 0.
fn flat_grid(w: &mut World, cells: u32) -> BodyHandle {
    flat_grid_with(w, cells, 0.6)
}

fn flat_grid_with(w: &mut World, cells: u32, friction: f32) -> BodyHandle {
    let (v, t) = scenes::grid_mesh(cells, 1.0, &vec![0.0; ((cells + 1) * (cells + 1)) as usize]);
    static_mesh_with(w, &v, &t, Transform::IDENTITY, Vec3::ONE, friction)
}

fn run(w: &mut World, steps: usize) {
    for _ in 0..steps {
        w.step(DT).unwrap();
    }
}

#[test]
fn box_rests_on_mesh_at_analytic_height() {
    // Flat grid at y = 0; a unit cube rests at y = 0.5. Measured error 0.3 mm; 5 mm allowed.
    let mut w = world();
    flat_grid(&mut w, 8);
    let b = body(&mut w, Vec3::new(0.3, 1.0, 0.2), Quat::IDENTITY, cube(0.5), 0.6);
    run(&mut w, 180);
    let p = w.transform(b).unwrap().p;
    assert!((p.y - 0.5).abs() < 5.0e-3, "{p}");
    assert!(w.linear_velocity(b).unwrap().length() < 1.0e-2);
    // A large box over 16 cells: one contact with one four-point manifold.
    let big = body(&mut w, Vec3::new(-2.0, 1.0, -2.0), Quat::IDENTITY, cube(1.5), 0.6);
    run(&mut w, 180);
    assert!((w.transform(big).unwrap().p.y - 1.5).abs() < 5.0e-3);

    // A mesh placed and scaled: unit grid scaled (2, 1, 2), turned about y, raised by 1 m.
    let mut w = world();
    let (v, t) = scenes::grid_mesh(4, 1.0, &[0.0; 25]);
    let local = Transform::new(Vec3::new(0.0, 1.0, 0.0), Quat::from_rotation_y(0.4));
    static_mesh(&mut w, &v, &t, local, Vec3::new(2.0, 1.0, 2.0));
    let b = body(&mut w, Vec3::new(1.0, 2.2, -1.5), Quat::IDENTITY, cube(0.25), 0.6);
    run(&mut w, 180);
    assert!((w.transform(b).unwrap().p.y - 1.25).abs() < 5.0e-3);
}

#[test]
fn box_rests_on_a_ramp_of_triangles() {
    // A 20° ramp of triangles, friction 1 (tan 20° = 0.36): a box sticks, 0.5 m from the ramp
    // along its normal, and stays.
    let mut w = world();
    let angle = 20.0f32.to_radians();
    let (v, t) = scenes::grid_mesh(10, 1.0, &[0.0; 121]);
    let q = Quat::from_rotation_z(angle);
    static_mesh_with(&mut w, &v, &t, Transform::new(Vec3::ZERO, q), Vec3::ONE, 1.0);
    let n = q * Vec3::Y;
    let b = body(&mut w, n * 0.52, q, cube(0.5), 1.0);
    run(&mut w, 240);
    let p = w.transform(b).unwrap().p;
    assert!((p.dot(n) - 0.5).abs() < 5.0e-3, "height over ramp {}", p.dot(n));
    assert!(w.linear_velocity(b).unwrap().length() < 1.0e-2);
}

/// A capsule lying down a 20° ramp of triangles (friction 1, tan 20° = 0.36) sticks: it
/// cannot roll down, and nothing pushes it sideways. It used to creep (rolling about its own
/// axis, 2.8 cm/s after 4 s) and this test was ignored; on main as of this branch it holds
/// (measured 4e-7 m/s after 4 s, 0.2 mm off its analytic height; 1 cm/s and 5 mm allowed).
#[test]
fn capsule_lying_down_a_ramp_of_triangles_sticks() {
    let mut w = world();
    let angle = 20.0f32.to_radians();
    let (v, t) = scenes::grid_mesh(10, 1.0, &[0.0; 121]);
    let q = Quat::from_rotation_z(angle);
    static_mesh_with(&mut w, &v, &t, Transform::new(Vec3::ZERO, q), Vec3::ONE, 1.0);
    let n = q * Vec3::Y;
    let capsule = Geometry::Capsule {
        a: Vec3::new(-0.6, 0.0, 0.0),
        b: Vec3::new(0.6, 0.0, 0.0),
        radius: 0.3,
    };
    let c = body(&mut w, n * 0.32 + q * Vec3::new(0.0, 0.0, 2.5), q, capsule, 1.0);
    run(&mut w, 240);
    let p = w.transform(c).unwrap().p;
    assert!((p.dot(n) - 0.3).abs() < 5.0e-3, "height over ramp {}", p.dot(n));
    let speed = w.linear_velocity(c).unwrap().length();
    assert!(speed < 1.0e-2, "speed {speed}");
}

/// Seeded variant of the capsule on a ramp of triangles: ramp angles from 5° to 25° (friction
/// 1, so all under the friction angle), the capsule's axis along the fall line pointing up or
/// down (across it a capsule rolls: friction does not hold a rolling body), turned by a random
/// angle about its own axis, at random places across the triangles' seams. After 1 s to
/// settle, over the next 5 s it moves less than 1 cm (measured: at most 0.05 mm) and its
/// energy never rises above the settled value by more than 1 mJ per kilogram (measured: at
/// most 0.0005 mJ/kg).
#[test]
fn capsules_on_random_ramps_of_triangles_stay_put() {
    let mut rng = scenes::Rng(0x5eed_0013);
    for _ in 0..12 {
        let mut w = world();
        let angle = rng.range(5.0, 25.0).to_radians();
        let (v, t) = scenes::grid_mesh(10, 1.0, &[0.0; 121]);
        let q = Quat::from_rotation_z(angle);
        static_mesh_with(&mut w, &v, &t, Transform::new(Vec3::ZERO, q), Vec3::ONE, 1.0);
        let n = q * Vec3::Y;
        let flip = if rng.next_u32() % 2 == 0 {
            0.0
        } else {
            std::f32::consts::PI
        };
        let spin = rng.range(0.0, std::f32::consts::TAU);
        let orient = q * Quat::from_rotation_y(flip) * Quat::from_rotation_x(spin);
        let (r, half) = (rng.range(0.15, 0.35), rng.range(0.3, 0.9));
        let capsule = Geometry::Capsule {
            a: Vec3::new(-half, 0.0, 0.0),
            b: Vec3::new(half, 0.0, 0.0),
            radius: r,
        };
        let along = q * Vec3::new(rng.range(-2.0, 2.0), 0.0, rng.range(-2.0, 2.0));
        let c = body(&mut w, n * (r + 0.01) + along, orient, capsule, 1.0);
        let m = w.body(c).unwrap().mass;
        run(&mut w, 60);
        let p0 = w.transform(c).unwrap().p;
        let e0 = terrain::energy(&w, &[c]);
        let mut e_max = e0;
        for _ in 0..300 {
            w.step(DT).unwrap();
            e_max = e_max.max(terrain::energy(&w, &[c]));
        }
        let p1 = w.transform(c).unwrap().p;
        let drift = (p1 - p0).length();
        let rise = (e_max - e0) / m;
        assert!(p1.is_finite());
        assert!(
            drift < 0.01,
            "angle {:.1}°, r {r}, half {half}: drifted {drift} m in 5 s",
            angle.to_degrees()
        );
        assert!(rise < 1.0e-3, "energy rose by {rise} J/kg");
    }
}

/// Largest |v_y| of a box sliding at 5 m/s across a flat 64×64 grid (heading `yaw`).
fn slide_max_vy(w: &mut World, yaw: f32) -> f32 {
    let b = body(
        w,
        Vec3::new(-28.0, 0.5, -3.0),
        Quat::from_rotation_y(yaw),
        cube(0.5),
        0.05,
    );
    run(w, 30); // settle on the floor
    let dir = Vec3::new(1.0, 0.0, 0.1).normalize();
    w.set_linear_velocity(b, 5.0 * dir).unwrap();
    let mut max_vy = 0.0f32;
    let mut crossed = 0.0;
    for _ in 0..540 {
        w.step(DT).unwrap();
        let v = w.linear_velocity(b).unwrap();
        max_vy = max_vy.max(v.y.abs());
        crossed = w.transform(b).unwrap().p.x + 28.0;
    }
    assert!(crossed > 20.0, "the box slid only {crossed} m");
    max_vy
}

#[test]
fn box_slides_across_seams_without_bumps() {
    // Measured max |v_y|: ~1e-4 m/s; the limit is 1 cm/s.
    for yaw in [0.0, 0.5] {
        let mut w = world();
        flat_grid_with(&mut w, 64, 0.05);
        let vy = slide_max_vy(&mut w, yaw);
        assert!(vy < 0.01, "yaw {yaw}: max |v_y| {vy} m/s");
    }
}

#[test]
fn sphere_rolls_across_seams_on_the_surface() {
    // A ball rolling at 5 m/s diagonally over the grid (crossing edges and vertices) never
    // rises more than 1 mm above the surface; measured well under 0.1 mm. It slows by the
    // default rolling resistance c = 0.05 at a = (5/7)·c·g (a solid ball): after 8 s it has
    // crossed 20 m of cells along x, as the closed form says (within 2 %).
    let mut w = world();
    flat_grid(&mut w, 64);
    let r = 0.5;
    let b = body(&mut w, Vec3::new(-25.0, r, -25.0), Quat::IDENTITY, ball(r), 0.6);
    run(&mut w, 30);
    let x0 = w.transform(b).unwrap().p.x;
    let v = Vec3::new(3.5, 0.0, 3.6);
    w.set_linear_velocity(b, v).unwrap();
    w.set_angular_velocity(b, Vec3::Y.cross(-v) / -r).unwrap();
    let mut max_gap = 0.0f32;
    for _ in 0..480 {
        w.step(DT).unwrap();
        max_gap = max_gap.max(w.transform(b).unwrap().p.y - r);
    }
    let t = 480.0 * DT;
    let a = 5.0 / 7.0 * ShapeDef::DEFAULT_ROLLING_RESISTANCE * 9.81 * v.x / v.length();
    let expected = v.x * t - 0.5 * a * t * t;
    let crossed = w.transform(b).unwrap().p.x - x0;
    assert!(
        (crossed - expected).abs() < 0.02 * expected,
        "rolled {crossed} m along x, closed form {expected} m"
    );
    assert!(max_gap < 1.0e-3, "left the surface by {max_gap} m");
}

#[test]
fn no_tunnelling_through_a_thin_mesh_floor_at_100_m_s() {
    // One layer of triangles with nothing under it stops a ball and a box thrown at it at
    // 100 m/s (speculative contacts). Straight down they stop at the surface (lowest centre
    // 0.2 for radius / half size 0.25). At a slant (frictionless, so nothing trips) they
    // skid on and the box's corner digs in up to 22 cm on impact before it is pushed out —
    // exactly as on a plane (the contact arms lag a fast sliding box within a step; a solver
    // matter, not the mesh's) — but nothing passes the surface: the centre stays above it.
    for g in [ball(0.25), cube(0.25)] {
        for dir in [Vec3::NEG_Y, Vec3::new(0.6, -1.0, 0.3).normalize()] {
            let mut w = world();
            let straight = dir == Vec3::NEG_Y;
            let friction = if straight { 0.6 } else { 0.0 };
            flat_grid_with(&mut w, 128, friction);
            let b = body(
                &mut w,
                Vec3::new(0.0, 4.0, 0.0) - 4.0 * dir.with_y(0.0),
                Quat::IDENTITY,
                g,
                friction,
            );
            w.set_linear_velocity(b, 100.0 * dir).unwrap();
            let (steps, floor) = if straight { (90, 0.2) } else { (40, 0.0) };
            for step in 0..steps {
                w.step(DT).unwrap();
                let p = w.transform(b).unwrap().p;
                assert!(p.x.abs() < 60.0 && p.z.abs() < 60.0);
                assert!(p.y > floor, "{g:?} {dir}: step {step} at {p}");
            }
            let y = w.transform(b).unwrap().p.y;
            if straight {
                assert!(y < 0.26, "{g:?}: resting at {y}");
            } else {
                assert!(y > 0.2, "{g:?} {dir}: not pushed back out, at {y}");
            }
        }
    }
    // On a flat floor the mesh gives a ball exactly what the plane gives.
    let track = |mesh: bool| {
        let mut w = world();
        if mesh {
            flat_grid(&mut w, 64);
        } else {
            scenes::ground_plane(&mut w);
        }
        let dir = Vec3::new(0.6, -1.0, 0.3).normalize();
        let b = body(&mut w, Vec3::new(-2.0, 4.0, -1.0), Quat::IDENTITY, ball(0.25), 0.6);
        w.set_linear_velocity(b, 100.0 * dir).unwrap();
        (0..20)
            .map(|_| {
                w.step(DT).unwrap();
                w.transform(b).unwrap().p
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(track(true), track(false));
}

#[test]
fn degenerate_triangles_are_counted_bad_input_refused() {
    let mut w = world();
    let v = vec![
        Vec3::ZERO,
        Vec3::X,
        Vec3::Z,
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 1.0),
    ];
    // Repeated index, zero area (collinear), two good triangles.
    let t = vec![[0, 2, 1], [1, 1, 2], [0, 1, 3], [1, 2, 4]];
    let m = w.create_mesh(&v, &t).unwrap();
    assert_eq!(w.mesh(m).unwrap().triangle_count(), 2);
    assert_eq!(w.mesh(m).unwrap().degenerate_count(), 2);
    let count = w.geometry.mesh_count();
    for (v, t, what) in [
        (v.clone(), vec![[0, 1, 5]], "index"),
        (
            vec![Vec3::ZERO, Vec3::new(f32::INFINITY, 0.0, 0.0), Vec3::Z],
            vec![[0, 2, 1]],
            "vertex 1",
        ),
        (v.clone(), vec![], "at least one"),
        (v.clone(), vec![[0, 1, 3]], "degenerate"),
    ] {
        let e = w.create_mesh(&v, &t).unwrap_err();
        assert!(matches!(&e, Error::InvalidArgument(s) if s.contains(what)), "{e}");
    }
    assert_eq!(w.geometry.mesh_count(), count);
}

#[test]
fn dynamic_body_refused_kinematic_allowed_destroy_refused_while_used() {
    let mut w = world();
    let (v, t) = scenes::grid_mesh(2, 1.0, &[0.0; 9]);
    let mesh = w.create_mesh(&v, &t).unwrap();
    let g = Geometry::Mesh {
        mesh,
        local: Transform::IDENTITY,
        scale: Vec3::ONE,
    };
    let dynamic = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            ..Default::default()
        })
        .unwrap();
    let e = w.create_shape(dynamic, &ShapeDef::default(), &g).unwrap_err();
    assert!(e.to_string().contains("static or kinematic"), "{e}");
    assert!(w.body(dynamic).unwrap().shapes.is_empty());
    for bad in [
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, f32::NAN, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
    ] {
        let s = Geometry::Mesh {
            mesh,
            local: Transform::IDENTITY,
            scale: bad,
        };
        let st = w.create_body(&BodyDef::default()).unwrap();
        assert!(w.create_shape(st, &ShapeDef::default(), &s).is_err(), "{bad}");
    }
    let kin = w
        .create_body(&BodyDef {
            body_type: BodyType::Kinematic,
            ..Default::default()
        })
        .unwrap();
    w.create_shape(kin, &ShapeDef::default(), &g).unwrap();
    let st = w.create_body(&BodyDef::default()).unwrap();
    w.create_shape(st, &ShapeDef::default(), &g).unwrap();
    let e = w.destroy_mesh(mesh).unwrap_err();
    assert!(e.to_string().contains("used by 2 shapes"), "{e}");
    w.destroy_body(kin).unwrap();
    w.destroy_body(st).unwrap();
    w.destroy_mesh(mesh).unwrap();
    assert!(matches!(w.destroy_mesh(mesh), Err(Error::InvalidId(_))));
}

#[test]
fn bvh_query_equals_brute_force_on_random_meshes() {
    let mut seed = 99u32;
    let mut rnd = move || {
        seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
        (seed >> 8) as f32 / (1u32 << 24) as f32
    };
    let mut w = world();
    for trial in 0..8 {
        let tris = 50 + 400 * trial;
        let mut v = Vec::new();
        let mut t = Vec::new();
        for i in 0..tris {
            let c = Vec3::new(rnd() * 40.0, rnd() * (2.0 + trial as f32), rnd() * 40.0);
            let s = 0.2 + 3.0 * rnd() * rnd();
            for _ in 0..3 {
                v.push(c + s * Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5));
            }
            t.push([3 * i, 3 * i + 1, 3 * i + 2]);
        }
        let h = w.create_mesh(&v, &t).unwrap();
        let m = w.mesh(h).unwrap();
        let bounds: Vec<Aabb> = (0..m.triangle_count() as u32)
            .map(|k| {
                let [a, b, c] = m.triangle(k);
                Aabb::new(a.min(b).min(c), a.max(b).max(c))
            })
            .collect();
        for _ in 0..200 {
            let c = Vec3::new(rnd() * 44.0 - 2.0, rnd() * 6.0 - 1.0, rnd() * 44.0 - 2.0);
            let e = Vec3::new(rnd() * 5.0, rnd() * 3.0, rnd() * 5.0);
            let q = Aabb::from_center_extents(c, e);
            let mut got = Vec::new();
            m.query(&q, |k| {
                got.push(k);
                true
            });
            got.sort();
            let want: Vec<u32> = (0..bounds.len() as u32)
                .filter(|&k| bounds[k as usize].overlaps(&q))
                .collect();
            assert_eq!(got, want, "trial {trial}");
        }
        // Every kept triangle maps back to its input triangle.
        let mut orig: Vec<u32> = (0..m.triangle_count() as u32).map(|k| m.original_index(k)).collect();
        orig.sort();
        assert_eq!(orig.len() + m.degenerate_count() as usize, tris as usize);
        for (k, &o) in orig.iter().enumerate().skip(1) {
            assert!(o > orig[k - 1]);
        }
    }
}

/// A V-shaped trough along z: two strips of triangles rising at `angle` from the x = 0 line.
fn trough(w: &mut World, angle: f32) {
    let (s, c) = (angle.sin(), angle.cos());
    let mut v = Vec::new();
    for z in 0..=10 {
        let z = z as f32 - 5.0;
        v.push(Vec3::new(-4.0 * c, 4.0 * s, z));
        v.push(Vec3::new(0.0, 0.0, z));
        v.push(Vec3::new(4.0 * c, 4.0 * s, z));
    }
    let mut t = Vec::new();
    for k in 0..10u32 {
        let (a, b) = (3 * k, 3 * (k + 1));
        // Left strip (faces up-right), right strip (faces up-left), counter-clockwise from above.
        t.push([a, b, b + 1]);
        t.push([a, b + 1, a + 1]);
        t.push([a + 1, b + 1, b + 2]);
        t.push([a + 1, b + 2, a + 2]);
    }
    static_mesh(w, &v, &t, Transform::IDENTITY, Vec3::ONE);
}

#[test]
fn box_and_sphere_in_a_v_crease_rest_on_both_sides() {
    let angle = 40.0f32.to_radians();
    // Sphere: centre at r / cos(angle) above the crease line.
    let mut w = world();
    trough(&mut w, angle);
    let r = 0.4;
    let s = body(&mut w, Vec3::new(0.05, 1.5, 0.0), Quat::IDENTITY, ball(r), 0.6);
    run(&mut w, 240);
    let y = w.transform(s).unwrap().p.y;
    assert!((y - r / angle.cos()).abs() < 5.0e-3, "sphere at {y}");
    // Box (half 0.3 × 0.2): bottom corners on the walls, centre at h + w·tan(angle).
    let mut w = world();
    trough(&mut w, angle);
    let half = Vec3::new(0.3, 0.2, 0.3);
    let g = Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: half,
    };
    let b = body(&mut w, Vec3::new(0.0, 1.0, 0.0), Quat::IDENTITY, g, 0.6);
    run(&mut w, 240);
    let p = w.transform(b).unwrap().p;
    let want = half.y + half.x * angle.tan();
    assert!((p.y - want).abs() < 5.0e-3, "box at {p}, want {want}");
    // One contact with two manifolds, one per wall, normals 80° apart.
    let body = w.body(b).unwrap();
    assert_eq!(body.contacts.len(), 1);
    let c = w.contacts.at(body.contacts[0]);
    assert_eq!(c.manifold_count(), 2);
    let (n0, n1) = (c.child(0).0.normal, c.child(1).0.normal);
    assert!((n0.dot(n1) - (2.0 * angle).cos()).abs() < 1.0e-3, "{n0} {n1}");
}

#[test]
fn kinematic_mesh_lifts_a_box() {
    let mut w = world();
    let (v, t) = scenes::grid_mesh(4, 1.0, &[0.0; 25]);
    let mesh = w.create_mesh(&v, &t).unwrap();
    let lift = w
        .create_body(&BodyDef {
            body_type: BodyType::Kinematic,
            ..Default::default()
        })
        .unwrap();
    w.create_shape(
        lift,
        &ShapeDef::default(),
        &Geometry::Mesh {
            mesh,
            local: Transform::IDENTITY,
            scale: Vec3::ONE,
        },
    )
    .unwrap();
    let b = body(&mut w, Vec3::new(0.2, 0.5, 0.1), Quat::IDENTITY, cube(0.5), 0.6);
    run(&mut w, 30);
    w.set_linear_velocity(lift, Vec3::new(0.0, 1.0, 0.0)).unwrap();
    run(&mut w, 120);
    let (top, p) = (w.transform(lift).unwrap().p.y, w.transform(b).unwrap().p.y);
    assert!((top - 2.0).abs() < 1.0e-3, "{top}");
    assert!((p - (top + 0.5)).abs() < 5.0e-3, "box at {p}, platform at {top}");
    assert!((w.linear_velocity(b).unwrap().y - 1.0).abs() < 1.0e-2);
}

#[test]
fn random_drops_on_mesh_terrain() {
    terrain::random_drops(false);
}

#[test]
fn four_and_eight_lanes_bit_identical_on_terrain() {
    let run_with = |lanes: LaneWidth| {
        let mut w = World::new(WorldSettings {
            lane_width: lanes,
            enable_sleep: false,
            ..WorldSettings::default()
        })
        .unwrap();
        scenes::terrain_mesh(&mut w, 16, false, 5);
        let bodies = scenes::terrain_drop(&mut w, 25, 4.0, 5);
        run(&mut w, 240);
        (
            w.contact_lanes(),
            bodies.iter().map(|&b| w.transform(b).unwrap()).collect::<Vec<_>>(),
        )
    };
    let (l4, a) = run_with(LaneWidth::Four);
    let (l8, b) = run_with(LaneWidth::Auto);
    assert_eq!(l4, 4);
    if l8 == 8 {
        for (x, y) in a.iter().zip(&b) {
            assert_eq!(x.p.to_array().map(f32::to_bits), y.p.to_array().map(f32::to_bits));
            assert_eq!(x.q.to_array().map(f32::to_bits), y.q.to_array().map(f32::to_bits));
        }
    }
}

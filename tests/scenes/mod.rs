//! Standard scenes, defined once and shared by tests, benches and examples (not part of the
//! shipped library: each includes this file with `#[path]`).

use hearth::math::{Quat, Transform, Vec3};
use hearth::world::{World, WorldSettings};
use hearth::{BodyDef, BodyHandle, BodyType};
use hearth::{Geometry, ShapeDef};

/// Half extent of the standard box.
pub const H: f32 = 0.5;

fn material() -> ShapeDef {
    ShapeDef {
        static_friction: 0.6,
        dynamic_friction: 0.6,
        ..ShapeDef::default()
    }
}

/// A static ground plane `y <= 0`.
pub fn ground_plane(world: &mut World) -> BodyHandle {
    let g = world.create_body(&BodyDef::default()).unwrap();
    world
        .create_shape(
            g,
            &material(),
            &Geometry::Plane {
                normal: Vec3::Y,
                offset: 0.0,
            },
        )
        .unwrap();
    g
}

/// A static box ground, top face at `y = 0`.
pub fn ground_box(world: &mut World, half_width: f32) -> BodyHandle {
    let g = world
        .create_body(&BodyDef {
            transform: Transform::new(Vec3::new(0.0, -1.0, 0.0), Quat::IDENTITY),
            ..Default::default()
        })
        .unwrap();
    let geom = Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::new(half_width, 1.0, half_width),
    };
    world.create_shape(g, &material(), &geom).unwrap();
    g
}

pub fn dynamic_box(world: &mut World, p: Vec3, h: Vec3, def: &ShapeDef) -> BodyHandle {
    let b = world
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(p, Quat::IDENTITY),
            ..Default::default()
        })
        .unwrap();
    world
        .create_shape(
            b,
            def,
            &Geometry::Box {
                center: Vec3::ZERO,
                rotation: Quat::IDENTITY,
                half_extents: h,
            },
        )
        .unwrap();
    b
}

pub fn dynamic_sphere(world: &mut World, p: Vec3, r: f32, def: &ShapeDef) -> BodyHandle {
    let b = world
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(p, Quat::IDENTITY),
            ..Default::default()
        })
        .unwrap();
    world
        .create_shape(
            b,
            def,
            &Geometry::Sphere {
                center: Vec3::ZERO,
                radius: r,
            },
        )
        .unwrap();
    b
}

/// A tower of `n` unit boxes standing on the ground. Returns the boxes bottom to top.
pub fn tower(world: &mut World, n: usize) -> Vec<BodyHandle> {
    ground_box(world, 20.0);
    (0..n)
        .map(|i| {
            dynamic_box(
                world,
                Vec3::new(0.0, H + 2.0 * H * i as f32, 0.0),
                Vec3::splat(H),
                &material(),
            )
        })
        .collect()
}

/// A square pyramid with `base` boxes per side at the bottom: base² + (base−1)² + … boxes.
pub fn pyramid(world: &mut World, base: usize) -> Vec<BodyHandle> {
    ground_box(world, 40.0);
    let mut out = Vec::new();
    for layer in 0..base {
        let n = base - layer;
        let offset = -(n as f32 - 1.0) * H;
        for i in 0..n {
            for k in 0..n {
                let p = Vec3::new(
                    offset + 2.0 * H * i as f32,
                    H + 2.0 * H * layer as f32,
                    offset + 2.0 * H * k as f32,
                );
                out.push(dynamic_box(world, p, Vec3::splat(H), &material()));
            }
        }
    }
    out
}

/// `count` bodies, alternating spheres (r = 0.5) and unit boxes, dropped from a grid of
/// spacing 1.5 into a 30 × 30 m container with walls.
pub fn pile(world: &mut World, count: usize) -> Vec<BodyHandle> {
    ground_box(world, 15.0);
    let wall = |world: &mut World, p: Vec3, h: Vec3| {
        let b = world
            .create_body(&BodyDef {
                transform: Transform::new(p, Quat::IDENTITY),
                ..Default::default()
            })
            .unwrap();
        world
            .create_shape(
                b,
                &material(),
                &Geometry::Box {
                    center: Vec3::ZERO,
                    rotation: Quat::IDENTITY,
                    half_extents: h,
                },
            )
            .unwrap();
    };
    let height = 30.0;
    wall(world, Vec3::new(15.5, height, 0.0), Vec3::new(0.5, height, 16.0));
    wall(world, Vec3::new(-15.5, height, 0.0), Vec3::new(0.5, height, 16.0));
    wall(world, Vec3::new(0.0, height, 15.5), Vec3::new(16.0, height, 0.5));
    wall(world, Vec3::new(0.0, height, -15.5), Vec3::new(16.0, height, 0.5));
    let per_row = 19; // 19 × 1.5 = 28.5 m fits inside the 30 m container
    let mut out = Vec::with_capacity(count);
    for i in 0..count {
        let layer = i / (per_row * per_row);
        let r = i % (per_row * per_row);
        let (x, z) = ((r % per_row) as f32, (r / per_row) as f32);
        let p = Vec3::new(-13.5 + 1.5 * x, 1.0 + 1.5 * layer as f32, -13.5 + 1.5 * z);
        out.push(if i % 2 == 0 {
            dynamic_sphere(world, p, 0.5, &material())
        } else {
            dynamic_box(world, p, Vec3::splat(H), &material())
        });
    }
    out
}

/// `n × n` spheres (r = 0.5) resting on the ground plane, 1.5 m apart, not touching each
/// other.
pub fn spheres_grid(world: &mut World, n: usize) -> Vec<BodyHandle> {
    ground_plane(world);
    let mut out = Vec::with_capacity(n * n);
    let offset = -(n as f32 - 1.0) * 0.75;
    for i in 0..n {
        for k in 0..n {
            let p = Vec3::new(offset + 1.5 * i as f32, 0.5, offset + 1.5 * k as f32);
            out.push(dynamic_sphere(world, p, 0.5, &material()));
        }
    }
    out
}

/// The demo's scene (`examples/demo.rs`): a pyramid with `base` boxes per side on a static
/// ground box, and eight bodies (spheres of radius 0.4 and boxes of 0.6 m, default material)
/// dropped from 9–16.5 m onto its four sides, staggered so they land one after another and
/// miss the top box. Returns the pyramid's boxes (the apex last) and the dropped bodies.
pub fn demo(world: &mut World, base: usize) -> (Vec<BodyHandle>, Vec<BodyHandle>) {
    let pyramid = pyramid(world, base);
    let def = ShapeDef::default();
    let mut dropped = Vec::new();
    let sides = [(2.0, 0.0), (-2.0, 0.0), (0.0, 2.0), (0.0, -2.0)];
    for (i, &(x, z)) in sides.iter().enumerate() {
        let y = 9.0 + 1.5 * i as f32;
        let ball_at = Vec3::new(x, y, z);
        let box_at = Vec3::new(x * 0.6, y + 3.0, z * 0.6 + 0.3);
        dropped.push(dynamic_sphere(world, ball_at, 0.4, &def));
        dropped.push(dynamic_box(world, box_at, Vec3::splat(0.3), &def));
    }
    (pyramid, dropped)
}

/// A world with default settings, optionally without sleep.
pub fn world(sleep: bool) -> World {
    World::new(WorldSettings {
        enable_sleep: sleep,
        ..WorldSettings::default()
    })
    .unwrap()
}

// ---------------------------------------------------------------- terrain (meshes, heightfields)

/// Heights of a `(cells + 1)²` grid of samples, row-major: smooth hills (a few metres) from
/// sums of sines, with phases from `seed`, in a bowl rising 3 m to the edges (so what rolls
/// stays on the terrain).
// 6.28 rather than 2π: the seeded terrains and drops stay the ones the tests were measured on.
#[allow(clippy::approx_constant)]
pub fn terrain_heights(cells: u32, seed: u32) -> Vec<f32> {
    let n = cells + 1;
    let mut s = seed.wrapping_mul(2654435761).wrapping_add(1);
    let mut rnd = || {
        s = s.wrapping_mul(1664525).wrapping_add(1013904223);
        (s >> 8) as f32 / (1u32 << 24) as f32
    };
    let waves: Vec<(f32, f32, f32, f32)> = (0..4)
        .map(|k| {
            let f = 0.05 * (k + 1) as f32;
            (f * (0.5 + rnd()), f * (0.5 + rnd()), 6.28 * rnd(), 1.5 / (k + 1) as f32)
        })
        .collect();
    (0..n * n)
        .map(|i| {
            let (r, c) = ((i / n) as f32, (i % n) as f32);
            let half = 0.5 * cells as f32;
            let bowl = 3.0 * ((r - half).powi(2) + (c - half).powi(2)) / (half * half);
            bowl + waves
                .iter()
                .map(|&(fx, fz, ph, a)| a * (fx * c + ph).sin() * (fz * r + 0.5 * ph).cos())
                .sum::<f32>()
        })
        .collect()
}

/// The triangles of a heightfield grid as a mesh (same vertices and split as
/// `collision/heightfield.rs`), sample spacing `spacing`, centred on the origin in x and z.
pub fn grid_mesh(cells: u32, spacing: f32, heights: &[f32]) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let n = cells + 1;
    let half = 0.5 * cells as f32 * spacing;
    let vertices = (0..n * n)
        .map(|i| {
            let (r, c) = (i / n, i % n);
            Vec3::new(
                c as f32 * spacing - half,
                heights[i as usize],
                r as f32 * spacing - half,
            )
        })
        .collect();
    let mut triangles = Vec::with_capacity(2 * (cells * cells) as usize);
    let id = |r: u32, c: u32| r * n + c;
    for r in 0..cells {
        for c in 0..cells {
            triangles.push([id(r, c), id(r + 1, c), id(r + 1, c + 1)]);
            triangles.push([id(r, c), id(r + 1, c + 1), id(r, c + 1)]);
        }
    }
    (vertices, triangles)
}

/// A static triangle-mesh terrain of `cells × cells` 1 m cells (2·cells² triangles) centred
/// on the origin; `flat` gives a plane at y = 0.
pub fn terrain_mesh(world: &mut World, cells: u32, flat: bool, seed: u32) -> BodyHandle {
    let heights = if flat {
        vec![0.0; ((cells + 1) * (cells + 1)) as usize]
    } else {
        terrain_heights(cells, seed)
    };
    let (v, t) = grid_mesh(cells, 1.0, &heights);
    let mesh = world.create_mesh(&v, &t).unwrap();
    let g = world.create_body(&BodyDef::default()).unwrap();
    world
        .create_shape(
            g,
            &material(),
            &Geometry::Mesh {
                mesh,
                local: Transform::IDENTITY,
                scale: Vec3::ONE,
            },
        )
        .unwrap();
    g
}

/// The same terrain as `terrain_mesh`, as a heightfield.
pub fn terrain_heightfield(world: &mut World, cells: u32, flat: bool, seed: u32) -> BodyHandle {
    let n = cells + 1;
    let heights = if flat {
        vec![0.0; (n * n) as usize]
    } else {
        terrain_heights(cells, seed)
    };
    let hf = world.create_heightfield(n, n, &heights, None).unwrap();
    let half = 0.5 * cells as f32;
    let g = world.create_body(&BodyDef::default()).unwrap();
    world
        .create_shape(
            g,
            &material(),
            &Geometry::Heightfield {
                heightfield: hf,
                local: Transform::new(Vec3::new(-half, 0.0, -half), Quat::IDENTITY),
                scale: Vec3::ONE,
            },
        )
        .unwrap();
    g
}

/// `count` mixed bodies — spheres, boxes, capsules and convex hulls in turn, sizes 0.2 to
/// 0.6 m — on a square lattice above `height` (2 m apart), over the terrain's middle.
// 6.28 rather than 2π: the seeded terrains and drops stay the ones the tests were measured on.
#[allow(clippy::approx_constant)]
pub fn terrain_drop(world: &mut World, count: usize, height: f32, seed: u32) -> Vec<BodyHandle> {
    let hull = world
        .create_convex_hull(
            &[
                Vec3::new(0.4, 0.0, 0.0),
                Vec3::new(-0.4, 0.0, 0.1),
                Vec3::new(0.0, 0.35, 0.0),
                Vec3::new(0.0, -0.35, -0.1),
                Vec3::new(0.1, 0.1, 0.4),
                Vec3::new(-0.1, -0.1, -0.4),
                Vec3::new(0.25, 0.2, -0.25),
                Vec3::new(-0.25, -0.2, 0.25),
            ],
            &Default::default(),
        )
        .unwrap();
    let side = (count as f32).sqrt().ceil() as usize;
    let mut s = seed.wrapping_mul(747796405).wrapping_add(7);
    let mut rnd = move || {
        s = s.wrapping_mul(1664525).wrapping_add(1013904223);
        (s >> 8) as f32 / (1u32 << 24) as f32
    };
    (0..count)
        .map(|i| {
            let (x, z) = ((i % side) as f32, (i / side) as f32);
            let p = Vec3::new(
                2.0 * (x - 0.5 * side as f32),
                height + 0.5 * rnd(),
                2.0 * (z - 0.5 * side as f32),
            );
            let q = Quat::from_euler(glam::EulerRot::XYZ, 6.28 * rnd(), 6.28 * rnd(), 6.28 * rnd());
            let b = world
                .create_body(&BodyDef {
                    body_type: BodyType::Dynamic,
                    transform: Transform::new(p, q),
                    ..Default::default()
                })
                .unwrap();
            let size = 0.2 + 0.4 * rnd();
            let geometry = match i % 4 {
                0 => Geometry::Sphere {
                    center: Vec3::ZERO,
                    radius: size,
                },
                1 => Geometry::Box {
                    center: Vec3::ZERO,
                    rotation: Quat::IDENTITY,
                    half_extents: Vec3::new(size, 0.7 * size, 0.85 * size),
                },
                2 => Geometry::Capsule {
                    a: Vec3::new(-size, 0.0, 0.0),
                    b: Vec3::new(size, 0.0, 0.0),
                    radius: 0.5 * size,
                },
                _ => Geometry::Hull {
                    hull,
                    local: Transform::IDENTITY,
                    scale: 0.5 + size,
                },
            };
            world.create_shape(b, &material(), &geometry).unwrap();
            b
        })
        .collect()
}

/// A small deterministic generator (xorshift) for seeded scenes.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u32(&mut self) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 32) as u32
    }
    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * (self.next_u32() as f32 / 4_294_967_296.0)
    }
    pub fn vec(&mut self, s: f32) -> Vec3 {
        Vec3::new(self.range(-s, s), self.range(-s, s), self.range(-s, s))
    }
    pub fn quat(&mut self) -> Quat {
        loop {
            let q = Quat::from_xyzw(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            if q.length() > 0.1 {
                return q.normalize();
            }
        }
    }
}

/// `n` random points on an ellipsoid of semi-axes `axes` (a rock-like cloud).
pub fn random_cloud(rng: &mut Rng, n: usize, axes: Vec3) -> Vec<Vec3> {
    (0..n)
        .map(|_| loop {
            let v = rng.vec(1.0);
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l * axes;
            }
        })
        .collect()
}

/// The eight corners of a cube of half extent `h`.
pub fn cube_points(h: f32) -> Vec<Vec3> {
    (0..8)
        .map(|i| {
            Vec3::new(
                if i & 1 != 0 { h } else { -h },
                if i & 2 != 0 { h } else { -h },
                if i & 4 != 0 { h } else { -h },
            )
        })
        .collect()
}

/// A dynamic body with one hull shape.
pub fn dynamic_hull(world: &mut World, hull: hearth::ConvexHullHandle, xf: Transform, def: &ShapeDef) -> BodyHandle {
    let g = Geometry::Hull {
        hull,
        local: Transform::IDENTITY,
        scale: 1.0,
    };
    dynamic_body(world, xf, def, &g)
}

/// The box tower of `tower` with every box a hull cube (one shared hull).
pub fn hull_tower(world: &mut World, n: usize) -> Vec<BodyHandle> {
    ground_box(world, 20.0);
    let cube = world.create_convex_hull(&cube_points(H), &Default::default()).unwrap();
    (0..n)
        .map(|i| {
            let p = Vec3::new(0.0, H + 2.0 * H * i as f32, 0.0);
            dynamic_hull(world, cube, Transform::new(p, Quat::IDENTITY), &material())
        })
        .collect()
}

/// `count` random hulls (12–24 points on ellipsoids of semi-axes 0.25–0.5 m, each its own
/// hull), in random orientations, dropped from a grid of spacing 1.2 m into a 20 × 20 m
/// box container with walls.
pub fn hull_pile(world: &mut World, count: usize, seed: u64) -> Vec<BodyHandle> {
    ground_box(world, 10.0);
    let wall = |world: &mut World, p: Vec3, h: Vec3| {
        let b = world
            .create_body(&BodyDef {
                transform: Transform::new(p, Quat::IDENTITY),
                ..Default::default()
            })
            .unwrap();
        let g = Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: h,
        };
        world.create_shape(b, &material(), &g).unwrap();
    };
    let height = 20.0;
    wall(world, Vec3::new(10.5, height, 0.0), Vec3::new(0.5, height, 11.0));
    wall(world, Vec3::new(-10.5, height, 0.0), Vec3::new(0.5, height, 11.0));
    wall(world, Vec3::new(0.0, height, 10.5), Vec3::new(11.0, height, 0.5));
    wall(world, Vec3::new(0.0, height, -10.5), Vec3::new(11.0, height, 0.5));
    let mut rng = Rng(seed.max(1));
    let per_row = 16; // 16 × 1.2 = 19.2 m
    let mut out = Vec::with_capacity(count);
    for i in 0..count {
        let layer = i / (per_row * per_row);
        let r = i % (per_row * per_row);
        let (x, z) = ((r % per_row) as f32, (r / per_row) as f32);
        let p = Vec3::new(-9.0 + 1.2 * x, 1.0 + 1.2 * layer as f32, -9.0 + 1.2 * z);
        let n = 12 + (rng.next_u32() % 13) as usize;
        let axes = Vec3::new(rng.range(0.25, 0.5), rng.range(0.25, 0.5), rng.range(0.25, 0.5));
        let cloud = random_cloud(&mut rng, n, axes);
        let hull = world.create_convex_hull(&cloud, &Default::default()).unwrap();
        out.push(dynamic_hull(world, hull, Transform::new(p, rng.quat()), &material()));
    }
    out
}

/// Turns every event kind on or off for every shape and body built so far (before the first
/// step, so new contacts take the flags): contact begin/end, hit and sensor events on shapes,
/// move events on bodies (issue 14's bench: the pile with every event kind against none).
pub fn set_events(world: &mut World, on: bool) {
    let shapes: Vec<_> = world.shapes.iter().map(|(h, _)| h).collect();
    for h in shapes {
        let def = &mut world.shapes.get_mut(h).unwrap().def;
        def.enable_contact_events = on;
        def.enable_hit_events = on;
        def.enable_sensor_events = on;
    }
    let bodies: Vec<_> = world.bodies.iter().map(|(h, _)| h).collect();
    for h in bodies {
        world.bodies.get_mut(h).unwrap().enable_move_events = on;
    }
}

// ---------------------------------------------------------------- joints and soft bodies

/// A chain of `n` boxes (0.4 × 0.2 × 0.2 m) on ball joints, hung from a world anchor 6 m up
/// and laid out horizontally, so it swings down and its end strikes a box ground below.
pub fn joint_chain(world: &mut World, n: usize) -> Vec<BodyHandle> {
    use hearth::joints::BallParams;
    use hearth::{JointDef, JointKind};
    ground_box(world, 20.0);
    let anchor = Vec3::new(0.0, 6.0, 0.0);
    let mut links: Vec<BodyHandle> = Vec::with_capacity(n);
    for i in 0..n {
        let c = anchor + Vec3::new(0.4 * i as f32 + 0.2, 0.0, 0.0);
        let b = dynamic_box(world, c, Vec3::new(0.2, 0.1, 0.1), &material());
        let point = anchor + Vec3::new(0.4 * i as f32, 0.0, 0.0);
        let mut def = JointDef::new(JointKind::Ball(BallParams::default()));
        def.body_a = b;
        def.frame_a = Transform::new(point - c, Quat::IDENTITY);
        match links.last() {
            Some(&prev) => {
                def.body_b = prev;
                let pc = world.transform(prev).unwrap().p;
                def.frame_b = Transform::new(point - pc, Quat::IDENTITY);
            }
            None => def.frame_b = Transform::new(point, Quat::IDENTITY),
        }
        world.create_joint(&def).unwrap();
        links.push(b);
    }
    links
}

/// A pressurised soft ball (an icosphere of radius 0.5 m, 162 vertices, 2 kg) dropped from
/// 2 m onto a ground plane beside a tower of three boxes it bounces against.
pub fn soft_ball(world: &mut World) -> hearth::soft::SoftBodyHandle {
    use hearth::soft::{mesh, SoftBodyDef};
    ground_plane(world);
    for i in 0..3 {
        dynamic_box(
            world,
            Vec3::new(1.2, H + 2.0 * H * i as f32, 0.0),
            Vec3::splat(H),
            &material(),
        );
    }
    let def = SoftBodyDef {
        transform: Transform::new(Vec3::new(0.3, 2.0, 0.0), Quat::IDENTITY),
        velocity: Vec3::new(1.0, 0.0, 0.0),
        mass: 2.0,
        pressure: 2000.0,
        ..Default::default()
    };
    world.create_soft_body(&def, &mesh::icosphere(0.5, 2), None).unwrap()
}

// ---------------------------------------------------------------- checks shared by tests

/// Kinetic plus gravitational potential energy of `bodies` (J).
pub fn energy(w: &World, bodies: &[BodyHandle]) -> f64 {
    let g = w.settings.gravity;
    bodies
        .iter()
        .map(|&b| {
            let body = w.body(b).unwrap();
            body.kinetic_energy() as f64 - body.mass as f64 * g.dot(body.center) as f64
        })
        .sum()
}

/// Kicks a chain — up to 3 m/s on its last link, up to about 3 rad/s of spin on a random
/// one — and steps once. Returns the chain's energy then (`energy`) and its energy scale: its
/// weight times a metre plus its kinetic energy.
pub fn kick_chain(w: &mut World, bodies: &[BodyHandle], rng: &mut Rng, dt: f32) -> (f64, f64) {
    let last = *bodies.last().unwrap();
    let kick = rng.vec(3.0) * w.body(last).unwrap().mass;
    w.apply_linear_impulse(last, kick, true).unwrap();
    let spun = bodies[(rng.next_u32() as usize) % bodies.len()];
    let turn = rng.vec(3.0) * (w.body(spun).unwrap().mass * 0.03);
    w.apply_angular_impulse(spun, turn, true).unwrap();
    w.step(dt).unwrap();
    let scale = bodies
        .iter()
        .map(|&b| {
            let body = w.body(b).unwrap();
            body.mass as f64 * 9.81 + body.kinetic_energy() as f64
        })
        .sum();
    (energy(w, bodies), scale)
}

/// Every locked velocity component of `b` (`locks`: `body::LOCK_*` bits) is exactly zero
/// (bit pattern: -0.0 fails too).
pub fn assert_locked(w: &World, b: BodyHandle, locks: u8, what: &str) {
    let (v, om) = (w.linear_velocity(b).unwrap(), w.angular_velocity(b).unwrap());
    for k in 0..3 {
        if locks & (1 << k) != 0 {
            assert_eq!(v[k].to_bits(), 0, "{what}: v {v} locks {locks:#x}");
        }
        if locks & (8 << k) != 0 {
            assert_eq!(om[k].to_bits(), 0, "{what}: w {om} locks {locks:#x}");
        }
    }
}

/// A dynamic body at `xf` with one shape.
pub fn dynamic_body(world: &mut World, xf: Transform, def: &ShapeDef, g: &Geometry) -> BodyHandle {
    let b = world
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: xf,
            ..Default::default()
        })
        .unwrap();
    world.create_shape(b, def, g).unwrap();
    b
}

// ---------------------------------------------------------------- joint chains

/// A dynamic box link of a chain with `locks`; `collide` false puts it in a group that never
/// collides.
pub fn chain_link(w: &mut World, xf: Transform, locks: u8, h: Vec3, density: f32, collide: bool) -> BodyHandle {
    let b = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: xf,
            locked_axes: locks,
            ..Default::default()
        })
        .unwrap();
    let mut def = ShapeDef {
        density,
        ..Default::default()
    };
    if !collide {
        def.filter.group_index = -1;
    }
    let g = Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: h,
    };
    w.create_shape(b, &def, &g).unwrap();
    b
}

/// One joint of a chain: the child (body A), its parent (B, None: the world) and the joint
/// frames on each (the parent's in world space for the world).
pub struct ChainJoint {
    pub handle: hearth::joints::JointHandle,
    pub child: BodyHandle,
    pub parent: Option<BodyHandle>,
    pub on_child: Transform,
    pub on_parent: Transform,
}

/// A joint's error (m): for the others the anchors' distance (a rigid distance joint: its
/// difference from the length; a spring: how far it is outside its limits), or for a hinge its axes'
/// misalignment (rad) times a metre if larger. For a slider, its rotation error (rad) times a
/// metre, or the distance of B's anchor from A's axis over the anchors' distance along it
/// (at least a metre) if larger: far along the rail, a rotation error turns A's axis at B's
/// anchor by the whole distance (5e-5 rad, f32-level for a spinning pair, is 2 cm at 400 m),
/// so there the error is measured as an angle, as the rotation's.
pub fn joint_error(w: &World, j: &ChainJoint) -> f32 {
    let fa = w.transform(j.child).unwrap().mul(&j.on_child);
    let fb = match j.parent {
        Some(p) => w.transform(p).unwrap().mul(&j.on_parent),
        None => j.on_parent,
    };
    let d = fb.p - fa.p;
    let (za, zb) = (fa.q * Vec3::Z, fb.q * Vec3::Z);
    match w.joint(j.handle).unwrap().def.kind {
        hearth::JointKind::Slider(_) => {
            let across = (d - za * za.dot(d)).length() / za.dot(d).abs().max(1.0);
            let rel = fa.q.conjugate() * fb.q;
            across.max(2.0 * Vec3::new(rel.x, rel.y, rel.z).length())
        }
        hearth::JointKind::Hinge(_) => d.length().max(za.cross(zb).length()),
        hearth::JointKind::Distance(p) if !p.enable_spring => (d.length() - p.length).abs(),
        hearth::JointKind::Distance(p) if p.enable_limit => {
            (d.length() - p.max_length).max(p.min_length - d.length()).max(0.0)
        }
        hearth::JointKind::Distance(_) => 0.0,
        _ => d.length(),
    }
}

/// Joins `child` to `parent` (or the world) with a joint of `kind` whose frame is `frame`
/// (world space) on both.
pub fn join(
    w: &mut World,
    kind: hearth::JointKind,
    child: BodyHandle,
    parent: Option<BodyHandle>,
    frame: Transform,
) -> ChainJoint {
    join_at(w, kind, child, parent, frame, frame)
}

/// Joins `child` to `parent` (or the world) with a joint of `kind` whose frame is `on_child`
/// on the child and `frame` on the parent (both in world space).
pub fn join_at(
    w: &mut World,
    kind: hearth::JointKind,
    child: BodyHandle,
    parent: Option<BodyHandle>,
    frame: Transform,
    on_child: Transform,
) -> ChainJoint {
    let mut def = hearth::JointDef::new(kind);
    def.body_a = child;
    def.frame_a = w.transform(child).unwrap().inv_mul(&on_child);
    def.frame_b = match parent {
        Some(p) => {
            def.body_b = p;
            w.transform(p).unwrap().inv_mul(&frame)
        }
        None => frame,
    };
    ChainJoint {
        handle: w.create_joint(&def).unwrap(),
        child,
        parent,
        on_child: def.frame_a,
        on_parent: def.frame_b,
    }
}

/// A slider limited to ±0.25 m or ±5 m, or not limited, at random (a third each).
pub fn random_slider(rng: &mut Rng) -> hearth::JointKind {
    let (reach, limited) = match rng.next_u32() % 3 {
        0 => (0.25, true),
        1 => (5.0, true),
        _ => (5.0, false),
    };
    hearth::JointKind::Slider(hearth::joints::SliderParams {
        enable_limit: limited,
        lower: -reach,
        upper: reach,
        ..Default::default()
    })
}

// ---------------------------------------------------------------- ragdolls

/// An 11-body ragdoll standing at `origin`: vertical capsules for pelvis, chest, arms and
/// legs, a sphere head, ball joints with cone and twist limits (spine, neck, shoulders, hips)
/// and limited hinges (elbows, knees); default materials (1,000 kg/m³). Used by
/// `tests/joints.rs`, `tests/rolling.rs` and the `joints` bench.
pub fn ragdoll(w: &mut World, origin: Vec3) -> Vec<BodyHandle> {
    use hearth::joints::{BallParams, HingeParams};
    use hearth::JointKind;
    let def = ShapeDef::default();
    let part = |w: &mut World, c: Vec3, half: f32, r: f32| {
        let geom = Geometry::Capsule {
            a: Vec3::new(0.0, -half, 0.0),
            b: Vec3::new(0.0, half, 0.0),
            radius: r,
        };
        dynamic_body(w, Transform::new(origin + c, Quat::IDENTITY), &def, &geom)
    };
    let pelvis = part(w, Vec3::new(0.0, 1.0, 0.0), 0.08, 0.12);
    let chest = part(w, Vec3::new(0.0, 1.4, 0.0), 0.12, 0.14);
    let head_at = Transform::new(origin + Vec3::new(0.0, 1.78, 0.0), Quat::IDENTITY);
    let head = dynamic_body(
        w,
        head_at,
        &def,
        &Geometry::Sphere {
            center: Vec3::ZERO,
            radius: 0.11,
        },
    );
    let mut bodies = vec![pelvis, chest, head];
    let cone = |swing: f32, twist: f32| {
        JointKind::Ball(BallParams {
            enable_swing_limit: true,
            swing_limit: swing,
            enable_twist_limit: true,
            lower_twist: -twist,
            upper_twist: twist,
        })
    };
    let hinge = |lower: f32, upper: f32| {
        JointKind::Hinge(HingeParams {
            enable_limit: true,
            lower,
            upper,
            ..Default::default()
        })
    };
    // The joint frame at `at` (from `origin`) with its Z axis along `axis`.
    let joint = |w: &mut World, kind: JointKind, child: BodyHandle, parent: BodyHandle, at: Vec3, axis: Vec3| {
        let frame = Transform::new(origin + at, Quat::from_rotation_arc(Vec3::Z, axis.normalize()));
        join(w, kind, child, Some(parent), frame);
    };
    joint(w, cone(0.4, 0.3), chest, pelvis, Vec3::new(0.0, 1.2, 0.0), Vec3::Y);
    joint(w, cone(0.5, 0.5), head, chest, Vec3::new(0.0, 1.66, 0.0), Vec3::Y);
    for side in [-1.0f32, 1.0] {
        let upper_arm = part(w, Vec3::new(side * 0.38, 1.5, 0.0), 0.1, 0.05);
        let fore_arm = part(w, Vec3::new(side * 0.38, 1.2, 0.0), 0.1, 0.045);
        let thigh = part(w, Vec3::new(side * 0.1, 0.65, 0.0), 0.14, 0.07);
        let shin = part(w, Vec3::new(side * 0.1, 0.25, 0.0), 0.14, 0.06);
        let (shoulder, elbow) = (Vec3::new(side * 0.38, 1.62, 0.0), Vec3::new(side * 0.38, 1.35, 0.0));
        joint(w, cone(1.2, 0.5), upper_arm, chest, shoulder, -Vec3::Y);
        joint(w, hinge(0.0, 2.2), fore_arm, upper_arm, elbow, Vec3::X);
        let (hip, knee) = (Vec3::new(side * 0.1, 0.85, 0.0), Vec3::new(side * 0.1, 0.45, 0.0));
        joint(w, cone(0.8, 0.3), thigh, pelvis, hip, -Vec3::Y);
        joint(w, hinge(-2.2, 0.0), shin, thigh, knee, Vec3::X);
        bodies.extend([upper_arm, fore_arm, thigh, shin]);
    }
    bodies
}

//! Debug draw (issue 14): a counting drawer gets exactly the primitives each shape kind and
//! each flag promise, in the colours of the body's state; a plane is a square patch 20 m
//! across on the plane; a seeded random scene draws exactly the sum of its parts, all finite.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use hearth::debug_draw::{colors, Color, DebugDraw, DrawFlags, PLANE_PATCH_HALF_SIDE};
use hearth::joints::{JointDef, JointKind};
use hearth::math::{Quat, Transform, Vec3};
use hearth::{BodyDef, BodyHandle, BodyType, Geometry, HullSettings, ShapeDef, World};

#[derive(Default, Debug, PartialEq, Eq, Clone)]
struct Counts {
    segments: usize,
    polygons: usize,
    polygon_vertices: usize,
    spheres: usize,
    capsules: usize,
    transforms: usize,
    points: usize,
}

#[derive(Default)]
struct Counter {
    n: Counts,
    colors: Vec<Color>,
    segments: Vec<(Vec3, Vec3, Color)>,
    polygons: Vec<Vec<Vec3>>,
    finite: bool,
}

impl Counter {
    fn new() -> Counter {
        Counter {
            finite: true,
            ..Default::default()
        }
    }
    fn check(&mut self, p: &[Vec3]) {
        self.finite &= p.iter().all(|v| v.is_finite());
    }
}

impl DebugDraw for Counter {
    fn segment(&mut self, a: Vec3, b: Vec3, color: Color) {
        self.check(&[a, b]);
        self.n.segments += 1;
        self.segments.push((a, b, color));
        self.colors.push(color);
    }
    fn polygon(&mut self, vertices: &[Vec3], color: Color) {
        self.check(vertices);
        self.n.polygons += 1;
        self.n.polygon_vertices += vertices.len();
        self.polygons.push(vertices.to_vec());
        self.colors.push(color);
    }
    fn sphere(&mut self, center: Vec3, radius: f32, color: Color) {
        self.check(&[center, Vec3::splat(radius)]);
        self.n.spheres += 1;
        self.colors.push(color);
    }
    fn capsule(&mut self, a: Vec3, b: Vec3, radius: f32, color: Color) {
        self.check(&[a, b, Vec3::splat(radius)]);
        self.n.capsules += 1;
        self.colors.push(color);
    }
    fn transform(&mut self, xf: Transform) {
        self.check(&[xf.p]);
        self.n.transforms += 1;
    }
    fn point(&mut self, p: Vec3, size: f32, color: Color) {
        self.check(&[p, Vec3::splat(size)]);
        self.n.points += 1;
        self.colors.push(color);
    }
}

const SHAPES: DrawFlags = DrawFlags {
    shapes: true,
    aabbs: false,
    contacts: false,
    joints: false,
    centers_of_mass: false,
};

fn draw(w: &World, flags: DrawFlags) -> Counter {
    let mut c = Counter::new();
    w.draw(&mut c, flags);
    assert!(c.finite);
    c
}

fn body(w: &mut World, t: BodyType, p: Vec3, awake: bool) -> BodyHandle {
    w.create_body(&BodyDef {
        body_type: t,
        transform: Transform::new(p, Quat::IDENTITY),
        awake,
        ..Default::default()
    })
    .unwrap()
}

fn counts(f: impl FnOnce(&mut Counts)) -> Counts {
    let mut c = Counts::default();
    f(&mut c);
    c
}

#[test]
fn each_shape_kind_draws_its_primitives() {
    let def = ShapeDef::default();
    // Sphere, capsule, box.
    let mut w = scenes::world(false);
    let b = body(&mut w, BodyType::Dynamic, Vec3::new(0.0, 3.0, 0.0), true);
    w.create_shape(
        b,
        &def,
        &Geometry::Sphere {
            center: Vec3::ZERO,
            radius: 0.5,
        },
    )
    .unwrap();
    assert_eq!(draw(&w, SHAPES).n, counts(|c| c.spheres = 1));
    w.create_shape(
        b,
        &def,
        &Geometry::Capsule {
            a: Vec3::ZERO,
            b: Vec3::Y,
            radius: 0.2,
        },
    )
    .unwrap();
    assert_eq!(
        draw(&w, SHAPES).n,
        counts(|c| {
            c.spheres = 1;
            c.capsules = 1
        })
    );
    let mut w = scenes::world(false);
    scenes::dynamic_box(&mut w, Vec3::ZERO, Vec3::new(0.5, 1.0, 1.5), &def);
    let c = draw(&w, SHAPES);
    assert_eq!(
        c.n,
        counts(|c| {
            c.polygons = 6;
            c.polygon_vertices = 24
        })
    );
    // Every face is a rectangle of the box: its corners at ±half extents.
    for f in &c.polygons {
        for v in f {
            assert!((v.abs() - Vec3::new(0.5, 1.0, 1.5)).abs().max_element() < 1e-6, "{v}");
        }
    }
    // Hull: a cube's six faces of four vertices.
    let mut w = scenes::world(false);
    let hull = w
        .create_convex_hull(&scenes::cube_points(0.5), &HullSettings::default())
        .unwrap();
    scenes::dynamic_hull(&mut w, hull, Transform::IDENTITY, &def);
    assert_eq!(
        draw(&w, SHAPES).n,
        counts(|c| {
            c.polygons = 6;
            c.polygon_vertices = 24
        })
    );
    // Mesh: its triangles.
    let mut w = scenes::world(false);
    let (v, t) = scenes::grid_mesh(4, 1.0, &[0.0; 25]);
    let mesh = w.create_mesh(&v, &t).unwrap();
    let g = body(&mut w, BodyType::Static, Vec3::ZERO, true);
    let local = Transform::IDENTITY;
    w.create_shape(
        g,
        &def,
        &Geometry::Mesh {
            mesh,
            local,
            scale: Vec3::ONE,
        },
    )
    .unwrap();
    assert_eq!(
        draw(&w, SHAPES).n,
        counts(|c| {
            c.polygons = 32;
            c.polygon_vertices = 96
        })
    );
    // Heightfield: two triangles per solid cell (5 × 4 samples: 12 cells, one a hole).
    let mut w = scenes::world(false);
    let mut holes = vec![false; 12];
    holes[5] = true;
    let hf = w.create_heightfield(5, 4, &[0.5; 20], Some(&holes)).unwrap();
    let g = body(&mut w, BodyType::Static, Vec3::ZERO, true);
    w.create_shape(
        g,
        &def,
        &Geometry::Heightfield {
            heightfield: hf,
            local,
            scale: Vec3::ONE,
        },
    )
    .unwrap();
    let c = draw(&w, SHAPES);
    assert_eq!(
        c.n,
        counts(|c| {
            c.polygons = 22;
            c.polygon_vertices = 66
        })
    );
    assert!(c.polygons.iter().flatten().all(|p| p.y == 0.5));
}

#[test]
fn a_plane_is_a_square_patch_20_m_across_on_the_plane() {
    let mut w = scenes::world(false);
    let g = body(&mut w, BodyType::Static, Vec3::new(3.0, 1.0, -2.0), true);
    let n = Vec3::new(1.0, 2.0, 0.5).normalize();
    w.create_shape(g, &ShapeDef::default(), &Geometry::Plane { normal: n, offset: 0.5 })
        .unwrap();
    let c = draw(&w, SHAPES);
    assert_eq!(
        c.n,
        counts(|c| {
            c.polygons = 1;
            c.polygon_vertices = 4
        })
    );
    let p = &c.polygons[0];
    let d = n.dot(Vec3::new(3.0, 1.0, -2.0)) + 0.5;
    for k in 0..4 {
        assert!((n.dot(p[k]) - d).abs() < 1e-4, "vertex {k} off the plane");
        let side = (p[(k + 1) % 4] - p[k]).length();
        assert!((side - 2.0 * PLANE_PATCH_HALF_SIDE).abs() < 1e-4, "side {side}");
    }
    assert_eq!(2.0 * PLANE_PATCH_HALF_SIDE, 20.0);
}

#[test]
fn shape_colours_follow_the_body_state() {
    let mut w = scenes::world(true);
    let def = ShapeDef::default();
    let sphere = Geometry::Sphere {
        center: Vec3::ZERO,
        radius: 0.5,
    };
    for (t, awake, color) in [
        (BodyType::Static, true, colors::STATIC),
        (BodyType::Kinematic, true, colors::KINEMATIC),
        (BodyType::Dynamic, true, colors::AWAKE),
        (BodyType::Dynamic, false, colors::SLEEPING),
    ] {
        let mut w1 = scenes::world(true);
        let b = body(&mut w1, t, Vec3::ZERO, true);
        w1.create_shape(b, &def, &sphere).unwrap();
        w1.set_awake(b, awake).unwrap();
        assert_eq!(draw(&w1, SHAPES).colors, vec![color]);
    }
    // A body that falls asleep changes colour.
    scenes::ground_plane(&mut w);
    let b = scenes::dynamic_sphere(&mut w, Vec3::new(0.0, 0.5, 0.0), 0.5, &def);
    assert_eq!(draw(&w, SHAPES).colors, vec![colors::STATIC, colors::AWAKE]);
    for _ in 0..300 {
        w.step(1.0 / 60.0).unwrap();
    }
    assert!(!w.is_awake(b).unwrap());
    assert_eq!(draw(&w, SHAPES).colors, vec![colors::STATIC, colors::SLEEPING]);
    // A disabled body is not drawn.
    w.disable_body(b).unwrap();
    assert_eq!(draw(&w, SHAPES).colors, vec![colors::STATIC]);
}

#[test]
fn flags_draw_aabbs_contacts_joints_and_centres_of_mass() {
    let mut w = scenes::world(false);
    scenes::ground_plane(&mut w);
    let b = scenes::dynamic_box(&mut w, Vec3::new(0.0, 0.5, 0.0), Vec3::splat(0.5), &ShapeDef::default());
    for _ in 0..60 {
        w.step(1.0 / 60.0).unwrap();
    }
    let none = DrawFlags::default();
    assert_eq!(draw(&w, none).n, Counts::default());
    // AABBs: 12 segments per bounded shape; the plane has none.
    let c = draw(&w, DrawFlags { aabbs: true, ..none });
    assert_eq!(c.n, counts(|c| c.segments = 12));
    // Contacts: a resting box's four points, each with its normal and a positive impulse.
    let c = draw(&w, DrawFlags { contacts: true, ..none });
    assert_eq!(
        c.n,
        counts(|c| {
            c.points = 4;
            c.segments = 8
        })
    );
    assert_eq!(c.colors.iter().filter(|&&x| x == colors::CONTACT_IMPULSE).count(), 4);
    // Header: the normal a segment 0.25 m long, the impulse 0.1 m per N·s along it.
    let (_, contact) = w.contacts.iter().next().unwrap();
    let n = contact.manifold.normal;
    let mut impulses: Vec<f32> = contact.impulses[..4].iter().map(|i| i.normal).collect();
    let mut drawn = Vec::new();
    for &(a, b, color) in &c.segments {
        let along = (b - a).dot(n);
        assert!(((b - a) - n * along).length() < 1e-5, "segments lie along the normal");
        match color {
            colors::CONTACT_NORMAL => assert!((along - 0.25).abs() < 1e-6, "normal {along} m"),
            colors::CONTACT_IMPULSE => drawn.push(along / 0.1),
            _ => panic!("colour {color:x}"),
        }
    }
    impulses.sort_by(f32::total_cmp);
    drawn.sort_by(f32::total_cmp);
    for (i, d) in impulses.iter().zip(&drawn) {
        assert!((i - d).abs() <= 1e-5 * i, "impulse {i} N·s drawn as {d}");
    }
    // Centres of mass: one transform per dynamic body.
    let c = draw(
        &w,
        DrawFlags {
            centers_of_mass: true,
            ..none
        },
    );
    assert_eq!(c.n, counts(|c| c.transforms = 1));
    // Joints: between two bodies three segments and two anchors; to the world two and two.
    let other = scenes::dynamic_box(&mut w, Vec3::new(0.0, 2.0, 0.0), Vec3::splat(0.5), &ShapeDef::default());
    let mut def = JointDef::new(JointKind::Fixed);
    def.body_a = b;
    def.body_b = other;
    w.create_joint(&def).unwrap();
    let mut def = JointDef::new(JointKind::Fixed);
    def.body_a = other;
    def.frame_b = Transform::new(Vec3::new(0.0, 5.0, 0.0), Quat::IDENTITY);
    w.create_joint(&def).unwrap();
    let c = draw(&w, DrawFlags { joints: true, ..none });
    assert_eq!(
        c.n,
        counts(|c| {
            c.segments = 5;
            c.points = 4
        })
    );
    // A joint to a disabled body is not drawn.
    w.disable_body(b).unwrap();
    assert_eq!(
        draw(&w, DrawFlags { joints: true, ..none }).n,
        counts(|c| {
            c.segments = 2;
            c.points = 2
        })
    );
}

#[test]
fn a_seeded_random_scene_draws_the_sum_of_its_parts() {
    let mut s = 12345u64;
    let mut rnd = move |n: u64| {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (s >> 33) % n
    };
    let mut w = scenes::world(true);
    scenes::ground_plane(&mut w);
    let mut expected = counts(|c| {
        c.polygons = 1;
        c.polygon_vertices = 4
    });
    let mut bodies = 0;
    for i in 0..200 {
        let p = Vec3::new(rnd(40) as f32 - 20.0, 1.0 + rnd(20) as f32, rnd(40) as f32 - 20.0);
        let b = body(&mut w, BodyType::Dynamic, p, true);
        bodies += 1;
        let g = match rnd(3) {
            0 => {
                expected.spheres += 1;
                Geometry::Sphere {
                    center: Vec3::ZERO,
                    radius: 0.1 + rnd(10) as f32 * 0.05,
                }
            }
            1 => {
                expected.capsules += 1;
                Geometry::Capsule {
                    a: Vec3::ZERO,
                    b: Vec3::X,
                    radius: 0.2,
                }
            }
            _ => {
                expected.polygons += 6;
                expected.polygon_vertices += 24;
                Geometry::Box {
                    center: Vec3::ZERO,
                    rotation: Quat::from_rotation_y(i as f32),
                    half_extents: Vec3::splat(0.3),
                }
            }
        };
        w.create_shape(b, &ShapeDef::default(), &g).unwrap();
    }
    for _ in 0..120 {
        w.step(1.0 / 60.0).unwrap();
    }
    assert_eq!(draw(&w, SHAPES).n, expected);
    let all = DrawFlags {
        shapes: true,
        aabbs: true,
        contacts: true,
        joints: true,
        centers_of_mass: true,
    };
    let c = draw(&w, all);
    assert_eq!(c.n.transforms, bodies);
    assert_eq!(c.n.spheres, expected.spheres);
    assert!(c.n.segments >= 12 * bodies);
}

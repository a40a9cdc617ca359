//! Soft bodies under abuse (issue 12), at the default settings of the balloon example: a
//! 642-vertex icosphere of radius 0.5 m and 2 kg with gas nRT = 400 J.
//!
//! * The inextensible skin stays within 1 % of its rest edge lengths up to nRT 1,600 J.
//! * A rigid body twenty times the ball's mass dropped on it from 0.3 m never gets inside
//!   the closed skin by more than 1.5 vertex radii (inside-test: the winding number of the
//!   skin's triangles; the skin is a layer one vertex radius thick on each side of its
//!   mid-surface) and never pushes a vertex through the static ground (a plane or a static
//!   box) by more than 1 cm; in a crate it comes to rest on the ball. A seeded randomized version drops
//!   spheres, capsules and boxes of random mass (up to twenty times the ball's), height,
//!   offset and orientation on balls of random radius, mass and gas, and checks the same (2 vertex radii inside at most), plus
//!   finite state, bounded speed and no energy growth (gas energy included).
//! * The solver stays finite at any time step from 1e-6 s to 0.1 s (and below).

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;

use hearth::math::{Quat, Transform, Vec3};
use hearth::soft::{mesh, SoftBody, SoftBodyDef, SoftBodyHandle};
use hearth::{BodyDef, BodyHandle, BodyType, Geometry, ShapeDef, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;
/// The default ball: mass (kg), radius (m), gas (J).
const BALL_MASS: f32 = 2.0;
const BALL_RADIUS: f32 = 0.5;
const BALL_GAS: f32 = 400.0;
/// The default vertex radius (m).
const R: f32 = 0.01;

fn at(p: Vec3) -> Transform {
    Transform::new(p, Quat::IDENTITY)
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Ground {
    Plane,
    StaticBox,
}

fn world(ground: Ground) -> World {
    let mut w = World::new(WorldSettings {
        enable_sleep: false,
        ..Default::default()
    })
    .unwrap();
    match ground {
        Ground::Plane => scenes::ground_plane(&mut w),
        Ground::StaticBox => scenes::ground_box(&mut w, 10.0),
    };
    w
}

/// The default ball resting on the ground (its lowest vertex one vertex radius up).
fn ball(w: &mut World, pressure: f32) -> SoftBodyHandle {
    ball_of(w, &Ball::default(), pressure)
}

/// A 642-vertex ball: radius (m), mass (kg), gas (J).
#[derive(Clone, Copy, Debug)]
struct Ball {
    radius: f32,
    mass: f32,
    gas: f32,
}

impl Default for Ball {
    fn default() -> Ball {
        Ball {
            radius: BALL_RADIUS,
            mass: BALL_MASS,
            gas: BALL_GAS,
        }
    }
}

fn ball_of(w: &mut World, b: &Ball, pressure: f32) -> SoftBodyHandle {
    let def = SoftBodyDef {
        transform: at(Vec3::new(0.0, b.radius + R, 0.0)),
        mass: b.mass,
        pressure,
        ..Default::default()
    };
    let h = w.create_soft_body(&def, &mesh::icosphere(b.radius, 3), None).unwrap();
    let s = w.soft_body(h).unwrap();
    assert_eq!(s.vertex_count(), 642);
    assert!((s.total_mass() / b.mass - 1.0).abs() < 1e-4, "{}", s.total_mass());
    h
}

/// Largest relative stretch of any mesh edge against its rest length.
fn max_strain(s: &SoftBody, rest: &mesh::SoftMesh) -> f32 {
    let mut worst: f32 = f32::MIN;
    for t in &rest.triangles {
        for e in 0..3 {
            let (a, b) = (t[e] as usize, t[(e + 1) % 3] as usize);
            let l0 = rest.vertices[a].distance(rest.vertices[b]);
            worst = worst.max(s.pos[a].distance(s.pos[b]) / l0 - 1.0);
        }
    }
    worst
}

/// README: the skin "stays within 1 % of its rest edge lengths up to nRT 1,600 J" (the
/// header: "within 1 % ... up to nRT 1600 J"). Measured worst stretch over 4 s: 0.80 % at
/// 400 J, 0.58 % at 800 J, 0.45 % at 1600 J (1.7 % at 6400 J, beyond the claim).
#[test]
fn the_default_skin_stays_within_one_percent_of_its_rest_lengths_up_to_nrt_1600() {
    let rest = mesh::icosphere(BALL_RADIUS, 3);
    for pressure in [400.0, 800.0, 1600.0, 6400.0] {
        let mut w = world(Ground::Plane);
        let h = ball(&mut w, pressure);
        let mut worst: f32 = 0.0;
        for _ in 0..240 {
            w.step(DT).unwrap();
            worst = worst.max(max_strain(w.soft_body(h).unwrap(), &rest));
        }
        let s = w.soft_body(h).unwrap();
        println!(
            "nRT {pressure} J: worst edge stretch over 4 s {:.3} %, volume {:.2} % of rest",
            100.0 * worst,
            100.0 * s.volume() / s.rest_volume
        );
        if pressure <= 1600.0 {
            assert!(worst < 0.01, "stretch {worst} at nRT {pressure}");
        } else {
            assert!(worst < 0.03, "stretch {worst} at nRT {pressure}");
        }
    }
}

/// Winding number of the closed skin around `p`: 1 inside, 0 outside (van Oosterom and
/// Strackee's solid angle of each triangle, in f64).
fn winding(s: &SoftBody, p: Vec3) -> f64 {
    let mut total = 0.0f64;
    for t in &s.triangles {
        let [a, b, c] = t.map(|i| (s.pos[i as usize] - p).as_dvec3());
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let num = a.dot(b.cross(c));
        let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        total += 2.0 * num.atan2(den);
    }
    total / (4.0 * std::f64::consts::PI)
}

/// Closest point of triangle `a b c` to `p` (Ericson, Real-Time Collision Detection 5.1.5).
fn closest_on_triangle(p: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Vec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// How far `p` is inside the closed skin (m): its distance to the nearest triangle if the
/// winding number says inside, else 0.
fn depth_inside(s: &SoftBody, p: Vec3) -> f32 {
    if winding(s, p) < 0.5 {
        return 0.0;
    }
    s.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| s.pos[i as usize]);
            closest_on_triangle(p, a, b, c).distance(p)
        })
        .fold(f32::MAX, f32::min)
}

/// A rigid body dropped on the ball.
#[derive(Clone, Copy, Debug)]
enum Dropper {
    /// Half extents (m).
    Box(Vec3),
    Sphere(f32),
    /// Half length of the segment and radius (m), segment along the body's x.
    Capsule(f32, f32),
}

impl Dropper {
    fn geometry(&self) -> Geometry {
        match *self {
            Dropper::Box(half) => Geometry::Box {
                center: Vec3::ZERO,
                rotation: Quat::IDENTITY,
                half_extents: half,
            },
            Dropper::Sphere(radius) => Geometry::Sphere {
                center: Vec3::ZERO,
                radius,
            },
            Dropper::Capsule(l, radius) => Geometry::Capsule {
                a: Vec3::new(-l, 0.0, 0.0),
                b: Vec3::new(l, 0.0, 0.0),
                radius,
            },
        }
    }

    fn volume(&self) -> f32 {
        use std::f32::consts::PI;
        match *self {
            Dropper::Box(h) => 8.0 * h.x * h.y * h.z,
            Dropper::Sphere(r) => 4.0 / 3.0 * PI * r * r * r,
            Dropper::Capsule(l, r) => PI * r * r * (2.0 * l + 4.0 / 3.0 * r),
        }
    }

    /// Points on the surface, in the body's frame, checked against the skin: a box's
    /// corners, edge midpoints and face centres; the six poles of a sphere; a capsule's two
    /// end poles and the four sides of its ends and middle.
    fn points(&self) -> Vec<Vec3> {
        let mut out = Vec::new();
        match *self {
            Dropper::Box(h) => {
                for i in -1..=1 {
                    for j in -1..=1 {
                        for k in -1..=1 {
                            if (i, j, k) != (0, 0, 0) {
                                out.push(h * Vec3::new(i as f32, j as f32, k as f32));
                            }
                        }
                    }
                }
            }
            Dropper::Sphere(r) => {
                for d in [Vec3::X, Vec3::Y, Vec3::Z] {
                    out.push(d * r);
                    out.push(-d * r);
                }
            }
            Dropper::Capsule(l, r) => {
                out.push(Vec3::new(-l - r, 0.0, 0.0));
                out.push(Vec3::new(l + r, 0.0, 0.0));
                for x in [-l, 0.0, l] {
                    for d in [Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z] {
                        out.push(Vec3::new(x, 0.0, 0.0) + d * r);
                    }
                }
            }
        }
        out
    }

    /// Lowest point below the centre for a body turned by `q`.
    fn below(&self, q: Quat) -> f32 {
        self.points().iter().map(|p| -(q * *p).y).fold(f32::MIN, f32::max)
    }
}

/// One drop: `mass` (kg) of `dropper` turned by `q`, its lowest point `height` above the
/// resting ball's top, `offset` sideways from its axis; the ball on `ground`, in a crate
/// of low walls if `crate_walls`.
#[derive(Clone, Copy, Debug)]
struct Drop {
    ball: Ball,
    ground: Ground,
    dropper: Dropper,
    mass: f32,
    q: Quat,
    height: f32,
    offset: Vec3,
    crate_walls: bool,
}

/// What a drop did over `steps` steps.
#[derive(Debug, Default)]
struct Outcome {
    /// Deepest any surface point of the dropper got inside the skin (m).
    inside: f32,
    /// Deepest any vertex sphere got into the ground (m).
    through: f32,
    /// Largest speed of a vertex and of the dropper (m/s).
    vertex_speed: f32,
    body_speed: f32,
    /// Total energy at the release and its largest value after (J).
    energy0: f32,
    energy_max: f32,
    /// The dropper at the end: how deep inside the skin, height of its centre, speed.
    end_inside: f32,
    end_y: f32,
    end_speed: f32,
}

fn static_box(w: &mut World, p: Vec3, half: Vec3) {
    let b = w
        .create_body(&BodyDef {
            transform: at(p),
            ..Default::default()
        })
        .unwrap();
    let geom = Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: half,
    };
    w.create_shape(b, &ShapeDef::default(), &geom).unwrap();
}

/// Kinetic and potential energy of the soft body and the dropper plus the gas's
/// `−nRT ln(V / V0)`.
fn energy(w: &World, h: SoftBodyHandle, body: BodyHandle) -> f32 {
    let s = w.soft_body(h).unwrap();
    let mut e = 0.0;
    for ((v, p), &im) in s.vel.iter().zip(&s.pos).zip(&s.inv_mass) {
        e += (0.5 * v.length_squared() + G * p.y) / im;
    }
    e -= s.def.pressure * (s.volume() / s.rest_volume).ln();
    let b = w.body(body).unwrap();
    let inertia = b.inv_inertia_world.inverse();
    e + b.mass * (0.5 * b.v.length_squared() + G * b.center.y) + 0.5 * b.w.dot(inertia * b.w)
}

fn drop(d: &Drop, steps: usize) -> Outcome {
    let mut w = world(d.ground);
    if d.crate_walls {
        // Four low walls touching the ball's sides, up to its equator: a box on a ball free
        // to roll is a balance board and rolls off for any solver.
        for (p, half) in [
            (Vec3::new(0.61, 0.25, 0.0), Vec3::new(0.1, 0.25, 0.71)),
            (Vec3::new(-0.61, 0.25, 0.0), Vec3::new(0.1, 0.25, 0.71)),
            (Vec3::new(0.0, 0.25, 0.61), Vec3::new(0.71, 0.25, 0.1)),
            (Vec3::new(0.0, 0.25, -0.61), Vec3::new(0.71, 0.25, 0.1)),
        ] {
            static_box(&mut w, p, half);
        }
    }
    let h = ball_of(&mut w, &d.ball, d.ball.gas);
    for _ in 0..60 {
        w.step(DT).unwrap();
    }
    let top = w.soft_body(h).unwrap().pos.iter().map(|p| p.y).fold(f32::MIN, f32::max);
    let centre = Vec3::new(0.0, top + d.height + d.dropper.below(d.q), 0.0) + d.offset;
    let body = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(centre, d.q),
            ..Default::default()
        })
        .unwrap();
    let shape = ShapeDef {
        density: d.mass / d.dropper.volume(),
        ..Default::default()
    };
    w.create_shape(body, &shape, &d.dropper.geometry()).unwrap();
    assert!((w.body(body).unwrap().mass / d.mass - 1.0).abs() < 1e-3);
    let points = d.dropper.points();
    let mut o = Outcome {
        energy0: energy(&w, h, body),
        energy_max: f32::MIN,
        ..Default::default()
    };
    for _ in 0..steps {
        w.step(DT).unwrap();
        let s = w.soft_body(h).unwrap();
        let b = w.body(body).unwrap();
        assert!(
            s.pos.iter().chain(&s.vel).all(|v| v.is_finite()) && b.xf.p.is_finite() && b.v.is_finite(),
            "not finite: {d:?}"
        );
        // The ground's surface is y = 0 for both grounds (the static box's top is 20 m
        // wide: a ball kicked over its edge falls freely).
        let grounded = |p: &&Vec3| d.ground == Ground::Plane || (p.x.abs() < 10.0 && p.z.abs() < 10.0);
        let ground_low = s.pos.iter().filter(grounded).map(|p| p.y).fold(f32::MAX, f32::min);
        o.through = o.through.max(R - ground_low);
        o.vertex_speed = s.vel.iter().map(|v| v.length()).fold(o.vertex_speed, f32::max);
        o.body_speed = o.body_speed.max(b.v.length());
        for p in &points {
            o.inside = o.inside.max(depth_inside(s, b.xf.apply(*p)));
        }
        o.energy_max = o.energy_max.max(energy(&w, h, body));
    }
    let b = w.body(body).unwrap();
    let s = w.soft_body(h).unwrap();
    o.end_inside = points
        .iter()
        .map(|p| depth_inside(s, b.xf.apply(*p)))
        .fold(0.0, f32::max);
    o.end_y = b.xf.p.y;
    o.end_speed = b.v.length();
    o
}

/// The 40 kg box (0.4 × 0.2 × 0.4 m) of the testers, dropped flat from 0.3 m.
fn heavy_box(ground: Ground, crate_walls: bool) -> Drop {
    Drop {
        ball: Ball::default(),
        ground,
        dropper: Dropper::Box(Vec3::new(0.2, 0.1, 0.2)),
        mass: 20.0 * BALL_MASS,
        q: Quat::IDENTITY,
        height: 0.3,
        offset: Vec3::ZERO,
        crate_walls,
    }
}

fn check_held(d: &Drop, o: &Outcome, inside: f32) {
    assert!(
        o.through <= 0.01,
        "a vertex went {} m into the ground: {d:?}",
        o.through
    );
    assert!(
        o.inside <= inside,
        "the dropper got {} m inside the skin: {d:?}",
        o.inside
    );
    assert!(
        o.end_inside <= END_INSIDE,
        "the dropper ends {} m inside the skin: {d:?}",
        o.end_inside
    );
}

/// How far a dropper's surface point may get inside the skin's mid-surface: the skin is a
/// layer one vertex radius thick on each side, and a point is held at its outer side by
/// the solver, which leaves up to about a vertex radius more while the skin is loaded.
const INSIDE: f32 = 1.5 * R;

/// How far a dropper's surface may end inside the skin's mid-surface: within the skin's
/// outer half-layer (none measured, in any drop: it ends outside the skin).
const END_INSIDE: f32 = 0.5 * R;

/// The same over the random drops: a small heavy box presses the deepest, narrowest dent
/// (8.7 mm measured over these drops; 14.7 mm in another draw, a 0.12 × 0.15 × 0.2 m box
/// of 10.6 kg on the default ball).
const RANDOM_INSIDE: f32 = 2.0 * R;

/// README: "a rigid body 20× its mass dropped on it from 0.3 m gets no more than 1.5 cm
/// inside the skin and pushes no vertex more than 1 cm into the ground"; the header: "a
/// 40 kg box dropped 0.3 m on a 2 kg, 642-vertex ball of nRT 400 J". `INSIDE` is 1.5 vertex
/// radii, 1.5 cm; measured 7.8 mm (plane) and 9.4 mm (static box) inside, 0.0 mm into the
/// ground.
#[test]
fn a_box_twenty_times_the_ball_s_mass_does_not_get_in_or_push_the_skin_through_the_ground() {
    for ground in [Ground::Plane, Ground::StaticBox] {
        let d = heavy_box(ground, false);
        let o = drop(&d, 300);
        println!(
            "40 kg box on the 2 kg ball ({ground:?}): deepest inside the skin {:.1} mm (end {:.1}), vertex into the ground {:.1} mm, \
             energy {:.1} J -> max {:.1} J, box ends at {:.3} m",
            1000.0 * o.inside,
            1000.0 * o.end_inside,
            1000.0 * o.through,
            o.energy0,
            o.energy_max,
            o.end_y
        );
        check_held(&d, &o, INSIDE);
    }
}

#[test]
fn a_box_twenty_times_the_ball_s_mass_squeezing_it_in_a_crate_does_not_get_in_or_push_it_through() {
    // Four static walls around the ball up to its equator: the skin is squeezed between
    // the box, the walls and the ground.
    let d = heavy_box(Ground::Plane, true);
    let o = drop(&d, 600);
    println!(
        "40 kg box on the 2 kg ball in a crate: deepest inside the skin {:.1} mm ({:.1} mm at the end), vertex into the \
         ground {:.1} mm, box ends at {:.3} m, speed {:.4} m/s",
        1000.0 * o.inside,
        1000.0 * o.end_inside,
        1000.0 * o.through,
        o.end_y,
        o.end_speed,
    );
    check_held(&d, &o, INSIDE);
    // Not on the ground (0.1 m): 0.192 m and 0.027 m/s measured after 10 s. The box bounces
    // about 0.8 m off the gas ball and tumbles before it settles, so where it ends depends on
    // the last bit of the rigid integration (see the next test for the depth).
    assert!(o.end_y > 0.15, "the box should rest on the ball: {o:?}");
    assert!(o.end_speed < 0.05, "the box should come to rest: {o:?}");
}

#[test]
fn a_tumbling_box_in_a_crate_does_not_get_in_from_any_of_several_nearby_heights() {
    // The crate drop is chaotic: the box bounces off the gas ball, tumbles, and its corners
    // hit the skin at up to 2.8 m/s. Drop heights 0.1 mm apart give unrelated tumbles, so
    // the bound must hold for each, not for one lucky trajectory. Before face contacts kept
    // a corner deeper than half an edge (it moves up to its reach within a step), corners got
    // 35, 44 and 84 mm in over these heights; 13.2 mm is the deepest measured now.
    for dh in [0.0f32, 1.0e-4, -1.0e-4, 1.0e-3, 2.0e-3] {
        let mut d = heavy_box(Ground::Plane, true);
        d.height += dh;
        let o = drop(&d, 600);
        println!(
            "crate drop from {:.4} m: deepest inside the skin {:.1} mm ({:.1} mm at the end), vertex into the \
             ground {:.1} mm, box ends at {:.3} m",
            d.height,
            1000.0 * o.inside,
            1000.0 * o.end_inside,
            1000.0 * o.through,
            o.end_y,
        );
        check_held(&d, &o, INSIDE);
    }
}

#[test]
fn random_droppers_up_to_twenty_times_the_ball_s_mass_are_held() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut worst = Outcome::default();
    for case in 0..12 {
        let dropper = match case % 3 {
            0 => Dropper::Sphere(0.08 + 0.17 * rng.next()),
            1 => Dropper::Capsule(0.05 + 0.2 * rng.next(), 0.05 + 0.1 * rng.next()),
            _ => Dropper::Box(Vec3::new(
                0.05 + 0.2 * rng.next(),
                0.05 + 0.2 * rng.next(),
                0.05 + 0.2 * rng.next(),
            )),
        };
        let axis = Vec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5).normalize_or_zero();
        // The ball: radius 0.35..0.65 m, 1..4 kg, gas 300..1,600 J.
        let ball = Ball {
            radius: 0.35 + 0.3 * rng.next(),
            mass: 1.0 + 3.0 * rng.next(),
            gas: 300.0 + 1300.0 * rng.next(),
        };
        let d = Drop {
            ball,
            ground: if rng.next() < 0.5 {
                Ground::Plane
            } else {
                Ground::StaticBox
            },
            dropper,
            mass: ball.mass * (0.5 + 19.5 * rng.next()),
            q: Quat::from_axis_angle(if axis == Vec3::ZERO { Vec3::Y } else { axis }, 3.0 * rng.next()),
            height: 0.3 * rng.next(),
            offset: Vec3::new(0.6 * rng.next() - 0.3, 0.0, 0.6 * rng.next() - 0.3),
            crate_walls: false,
        };
        let o = drop(&d, 180);
        println!(
            "case {case}: {:?} on {:?}, {:?} {:.1} kg from {:.2} m, offset ({:.2}, {:.2}): inside {:.1} mm (end {:.1}), into the ground {:.1} mm, \
             speeds {:.2} / {:.2} m/s, energy {:.1} -> max {:.1} J",
            d.ball,
            d.ground,
            d.dropper,
            d.mass,
            d.height,
            d.offset.x,
            d.offset.z,
            1000.0 * o.inside,
            1000.0 * o.end_inside,
            1000.0 * o.through,
            o.vertex_speed,
            o.body_speed,
            o.energy0,
            o.energy_max
        );
        check_held(&d, &o, RANDOM_INSIDE);
        // A drop of at most 0.3 m + the ball's height (1.3 m) gives at most sqrt(2 g 1.6) =
        // 5.6 m/s to the dropper; a squeezed skin whips its 3 g vertices faster (up to 34 m/s
        // measured over 40 drops), but nowhere near the 400 m/s speed limit.
        assert!(o.body_speed < 6.5, "dropper speed {}: {d:?}", o.body_speed);
        assert!(o.vertex_speed < 100.0, "vertex speed {}: {d:?}", o.vertex_speed);
        assert!(
            o.energy_max <= o.energy0 + ENERGY_SLACK * o.energy0.abs().max(1.0),
            "energy grew {} -> {}: {d:?}",
            o.energy0,
            o.energy_max
        );
        worst.inside = worst.inside.max(o.inside);
        worst.through = worst.through.max(o.through);
    }
    println!(
        "worst over the cases: inside {:.1} mm, into the ground {:.1} mm",
        1000.0 * worst.inside,
        1000.0 * worst.through
    );
}

/// Relative energy gain allowed over a drop. None in most drops; a capsule glancing off a
/// stiff ball (nRT 1,050 J) gains 0.13 % once, at the impact, within the first second:
/// the largest energy then stays the same over the next 9 s while the total falls (no
/// growth, a transient of the contact's first sub-steps).
const ENERGY_SLACK: f32 = 0.005;

#[test]
fn the_soft_solver_stays_finite_at_any_time_step() {
    // The supported range (README "Supported ranges": 1 ms to 0.1 s), both ends included.
    for dt in [1.0e-3f32, 2.0e-3, 1.0e-2, 1.0 / 60.0, 0.05, 0.1] {
        let mut w = world(Ground::Plane);
        let h = ball(&mut w, BALL_GAS);
        // A box on it too, so coupling runs.
        let bx = scenes::dynamic_box(
            &mut w,
            Vec3::new(0.0, 1.2, 0.0),
            Vec3::new(0.2, 0.1, 0.2),
            &ShapeDef {
                density: 100.0,
                ..Default::default()
            },
        );
        for _ in 0..120 {
            w.step(dt).unwrap();
        }
        let s = w.soft_body(h).unwrap();
        let low = s.pos.iter().map(|p| p.y).fold(f32::MAX, f32::min);
        println!("dt {dt:e} s: centre {:.3}, lowest vertex {low:.4} m", s.center());
        assert!(s.pos.iter().chain(&s.vel).all(|v| v.is_finite()), "dt {dt}: not finite");
        assert!(w.body(bx).unwrap().xf.p.is_finite());
        assert!(low > -0.01, "dt {dt}: through the ground {low}");
    }
    // Below the range (where the scaled compliance α/h² would overflow to infinity): refused,
    // and the state stays as it was, finite.
    for dt in [1.0e-6f32, 1.0e-12, 1.0e-20, 1.0e-30, 1.0e-38, 1.0e-45] {
        let mut w = world(Ground::Plane);
        let h = ball(&mut w, BALL_GAS);
        for _ in 0..10 {
            assert!(w.step(dt).is_err(), "dt {dt} accepted");
        }
        let s = w.soft_body(h).unwrap();
        assert!(s.pos.iter().chain(&s.vel).all(|v| v.is_finite()), "dt {dt}: not finite");
    }
}

/// Deterministic pseudo-random numbers.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

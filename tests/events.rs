//! Events, sensors and the step callbacks (`src/events.rs`) against what must happen: a body
//! passing through a sensor, a dropped box's begin, hit speed and end, destroyed shapes,
//! move events against the transforms, a one-way platform made with the pre-solve callback,
//! and a seeded random check of the event bookkeeping.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use hearth::events::{PreSolveContact, StepCallbacks};
use hearth::math::{Quat, Transform, Vec3};
use hearth::{BodyDef, BodyHandle, BodyType, Geometry, ShapeDef, ShapeHandle, World, WorldSettings};
use std::collections::{HashMap, HashSet};

const DT: f32 = 1.0 / 60.0;

fn cube(h: f32) -> Geometry {
    Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::splat(h),
    }
}

fn body(w: &mut World, kind: BodyType, p: Vec3) -> BodyHandle {
    w.create_body(&BodyDef {
        body_type: kind,
        transform: Transform::new(p, Quat::IDENTITY),
        ..Default::default()
    })
    .unwrap()
}

fn sensor_def() -> ShapeDef {
    ShapeDef {
        is_sensor: true,
        ..Default::default()
    }
}

fn ground(w: &mut World) -> ShapeHandle {
    let g = body(w, BodyType::Static, Vec3::ZERO);
    w.create_shape(
        g,
        &ShapeDef::default(),
        &Geometry::Plane {
            normal: Vec3::Y,
            offset: 0.0,
        },
    )
    .unwrap()
}

/// (sensor begins, sensor ends) over `steps` steps.
fn count_sensor(w: &mut World, steps: usize) -> (usize, usize) {
    let (mut b, mut e) = (0, 0);
    for _ in 0..steps {
        w.step(DT).unwrap();
        b += w.events().sensor_begin.len();
        e += w.events().sensor_end.len();
    }
    (b, e)
}

#[test]
fn a_kinematic_body_through_a_static_sensor_gives_one_begin_and_one_end() {
    let mut w = World::new(WorldSettings::default()).unwrap();
    let zone = body(&mut w, BodyType::Static, Vec3::ZERO);
    let sensor = w.create_shape(zone, &sensor_def(), &cube(1.0)).unwrap();
    let mover = body(&mut w, BodyType::Kinematic, Vec3::new(-5.0, 0.0, 0.0));
    let visitor = w.create_shape(mover, &ShapeDef::default(), &cube(0.25)).unwrap();
    w.set_linear_velocity(mover, Vec3::new(2.0, 0.0, 0.0)).unwrap();
    let mut begins = Vec::new();
    let mut ends = Vec::new();
    for step in 0..300 {
        w.step(DT).unwrap();
        let x = w.transform(mover).unwrap().p.x;
        for e in &w.events().sensor_begin {
            begins.push((step, x, *e));
        }
        for e in &w.events().sensor_end {
            ends.push((step, x, *e));
        }
        assert!(w.events().contact_begin.is_empty(), "a sensor makes no contact");
    }
    assert_eq!(begins.len(), 1, "{begins:?}");
    assert_eq!(ends.len(), 1, "{ends:?}");
    let (_, xb, e) = begins[0];
    assert_eq!(
        (e.sensor_shape, e.visitor_shape, e.sensor_body, e.visitor_body),
        (sensor, visitor, zone, mover)
    );
    // Exact overlap: the boxes meet at x = -1.25 and part at x = 1.25; the event comes in the
    // first step whose narrow phase sees it (one step of 2/60 m later at most).
    assert!((-1.25..=-1.25 + 2.0 * 2.0 * DT).contains(&xb), "begin at x = {xb}");
    let (_, xe, _) = ends[0];
    assert!((1.25..=1.25 + 2.0 * 2.0 * DT).contains(&xe), "end at x = {xe}");
    // It never pushed: the kinematic body kept its speed (it would anyway) and a dynamic one
    // below is tested next.
}

#[test]
fn a_kinematic_sensor_sees_planes_and_static_shapes_once_each() {
    // A kinematic sensor cube sweeps through a static box, then down into the ground plane's
    // half-space and back out: one begin and one end for each (the plane pair used to be made
    // for dynamic bodies only, so a kinematic sensor never saw a plane).
    let mut w = World::new(WorldSettings::default()).unwrap();
    let plane = ground(&mut w);
    let wall = body(&mut w, BodyType::Static, Vec3::new(0.0, 2.0, 0.0));
    let block = w.create_shape(wall, &ShapeDef::default(), &cube(0.5)).unwrap();
    let mover = body(&mut w, BodyType::Kinematic, Vec3::new(-3.0, 2.0, 0.0));
    let sensor = w.create_shape(mover, &sensor_def(), &cube(0.25)).unwrap();
    let mut seen: HashMap<(bool, ShapeHandle), Vec<usize>> = HashMap::new();
    let mut step = 0;
    for (v, steps) in [
        (Vec3::new(2.0, 0.0, 0.0), 180),
        (Vec3::new(0.0, -2.0, 0.0), 120),
        (Vec3::new(0.0, 2.0, 0.0), 120),
    ] {
        w.set_linear_velocity(mover, v).unwrap();
        for _ in 0..steps {
            w.step(DT).unwrap();
            for (begin, list) in [(true, &w.events().sensor_begin), (false, &w.events().sensor_end)] {
                for e in list {
                    assert_eq!((e.sensor_shape, e.sensor_body), (sensor, mover));
                    seen.entry((begin, e.visitor_shape)).or_default().push(step);
                }
            }
            assert!(w.events().contact_begin.is_empty(), "a sensor makes no contact");
            step += 1;
        }
    }
    for shape in [block, plane] {
        for begin in [true, false] {
            assert_eq!(
                seen.get(&(begin, shape)).map_or(0, Vec::len),
                1,
                "{shape:?} begin {begin}: {seen:?}"
            );
        }
    }
    // Each within a step of where the geometry says (step k ends at k + 1 steps of 2/60 m):
    // the box from x = -0.75 (2.25 m, 67.5 steps) to x = 0.75 (112.5); the plane from the
    // sensor's bottom at y = 0 going down (1.75 m, 180 + 52.5) to the same going up (from
    // y = -2.25, 300 + 67.5).
    let at = |b: bool, s: ShapeHandle| seen[&(b, s)][0] as f32;
    for (got, want) in [
        (at(true, block), 67.5),
        (at(false, block), 112.5),
        (at(true, plane), 232.5),
        (at(false, plane), 367.5),
    ] {
        assert!(
            (got - want).abs() <= 1.0,
            "event at step {got}, geometry says {want}: {seen:?}"
        );
    }
    assert_eq!(seen.len(), 4, "no other shape: {seen:?}");
}

#[test]
fn a_falling_body_passes_a_static_sensor_untouched_and_a_kinematic_sensor_sees_a_sleeper() {
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    // A static sensor slab the ball falls through: free fall, unchanged.
    let zone = body(&mut w, BodyType::Static, Vec3::new(0.0, 5.0, 0.0));
    w.create_shape(
        zone,
        &sensor_def(),
        &Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::new(2.0, 0.5, 2.0),
        },
    )
    .unwrap();
    let ball = body(&mut w, BodyType::Dynamic, Vec3::new(0.0, 8.0, 0.0));
    w.create_shape(ball, &ShapeDef::default(), &cube(0.25)).unwrap();
    let (mut begins, mut ends) = (0, 0);
    let g = 9.81_f32;
    for _ in 0..60 {
        w.step(DT).unwrap();
        begins += w.events().sensor_begin.len();
        ends += w.events().sensor_end.len();
    }
    // After 1 s of free fall (semi-implicit Euler: v exact, y within g·dt·t/2).
    let v = w.linear_velocity(ball).unwrap().y;
    assert!((v + g).abs() < 1e-3, "free fall through the sensor: v = {v}");
    assert_eq!((begins, ends), (1, 1), "through the slab");
    // The ball rests on the ground and sleeps; a kinematic sensor sweeps over it.
    for _ in 0..600 {
        w.step(DT).unwrap();
    }
    assert!(!w.is_awake(ball).unwrap(), "the ball sleeps");
    // 0.6 m up: its bottom clears the ground plane (which a kinematic sensor sees too) and
    // reaches 0.4 m below the ball's top.
    let sweeper = body(&mut w, BodyType::Kinematic, Vec3::new(-4.0, 0.6, 0.0));
    w.create_shape(sweeper, &sensor_def(), &cube(0.5)).unwrap();
    w.set_linear_velocity(sweeper, Vec3::new(2.0, 0.0, 0.0)).unwrap();
    let (b, e) = count_sensor(&mut w, 240);
    assert_eq!((b, e), (1, 1), "a kinematic sensor sees a sleeping body");
    assert!(!w.is_awake(ball).unwrap(), "a sensor never wakes a body");
    // Sensors add no mass.
    assert!(w.body(zone).unwrap().mass == 0.0);
}

#[test]
fn a_dropped_box_gives_one_begin_one_hit_at_the_free_fall_speed_and_an_end_when_lifted() {
    for h in [0.5_f32, 2.0, 5.0] {
        let mut w = World::new(WorldSettings::default()).unwrap();
        let plane = ground(&mut w);
        let b = body(&mut w, BodyType::Dynamic, Vec3::new(0.0, 0.5 + h, 0.0));
        let def = ShapeDef {
            enable_hit_events: true,
            ..Default::default()
        };
        let s = w.create_shape(b, &def, &cube(0.5)).unwrap();
        let (mut begins, mut hits, mut ends) = (Vec::new(), Vec::new(), 0);
        for _ in 0..180 {
            w.step(DT).unwrap();
            begins.extend(w.events().contact_begin.iter().copied());
            hits.extend(w.events().contact_hit.iter().copied());
            ends += w.events().contact_end.len();
        }
        assert_eq!(begins.len(), 1, "h = {h}: {begins:?}");
        assert_eq!(ends, 0, "h = {h}: resting makes no end");
        let e = begins[0];
        assert_eq!(
            HashSet::from([e.shape_a, e.shape_b]),
            HashSet::from([plane, s]),
            "the pair"
        );
        assert_eq!(hits.len(), 1, "h = {h}: {hits:?}");
        let expected = (2.0 * 9.81 * h).sqrt();
        let hit = hits[0];
        println!("h = {h}: hit {:.4} m/s, expected {expected:.4}", hit.speed);
        assert!(
            (hit.speed - expected).abs() < 0.01 * expected,
            "h = {h}: hit speed {} against √(2gh) = {expected}",
            hit.speed
        );
        assert!(hit.point.y.abs() < 0.05, "the point is on the ground: {:?}", hit.point);
        assert!(hit.normal.y.abs() > 0.999, "the normal is vertical: {:?}", hit.normal);
        // Lifted away: one end. (README: one hit at √(2gh) within 1 %.)
        w.set_transform(b, Transform::new(Vec3::new(0.0, 3.0, 0.0), Quat::IDENTITY))
            .unwrap();
        w.step(DT).unwrap();
        assert_eq!(w.events().contact_end.len(), 1, "h = {h}");
        assert_eq!(w.events().contact_end[0], e);
    }
}

#[test]
fn destroying_a_touching_shape_or_body_reports_an_end() {
    for destroy_body in [false, true] {
        let mut w = World::new(WorldSettings::default()).unwrap();
        ground(&mut w);
        let b = body(&mut w, BodyType::Dynamic, Vec3::new(0.0, 0.5, 0.0));
        let s = w.create_shape(b, &ShapeDef::default(), &cube(0.5)).unwrap();
        let zone = body(&mut w, BodyType::Static, Vec3::ZERO);
        let sensor = w.create_shape(zone, &sensor_def(), &cube(2.0)).unwrap();
        let (mut begins, mut sensor_begins, mut ends) = (0, 0, 0);
        for _ in 0..60 {
            w.step(DT).unwrap();
            begins += w.events().contact_begin.len();
            sensor_begins += w.events().sensor_begin.len();
            ends += w.events().contact_end.len() + w.events().sensor_end.len();
        }
        assert_eq!((begins, sensor_begins, ends), (1, 1, 0));
        if destroy_body {
            w.destroy_body(b).unwrap();
        } else {
            w.destroy_shape(s).unwrap();
        }
        w.step(DT).unwrap();
        let ev = w.events();
        assert_eq!(ev.contact_end.len(), 1, "destroy_body {destroy_body}");
        assert!(ev.contact_end[0].shape_a == s || ev.contact_end[0].shape_b == s);
        assert_eq!(ev.sensor_end.len(), 1);
        assert_eq!(ev.sensor_end[0].sensor_shape, sensor);
        assert_eq!(ev.sensor_end[0].visitor_shape, s);
        w.step(DT).unwrap();
        assert!(w.events().contact_end.is_empty() && w.events().sensor_end.is_empty());
    }
}

#[test]
fn move_events_are_exactly_the_bodies_that_moved() {
    let mut w = scenes::world(true);
    let ids = scenes::pile(&mut w, 200);
    // Some bodies without move events.
    let quiet: HashSet<BodyHandle> = ids.iter().step_by(7).copied().collect();
    for &b in &quiet {
        w.destroy_body(b).unwrap();
    }
    let silent = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(Vec3::new(3.0, 20.0, 0.0), Quat::IDENTITY),
            enable_move_events: false,
            ..Default::default()
        })
        .unwrap();
    w.create_shape(silent, &ShapeDef::default(), &cube(0.5)).unwrap();
    let live: Vec<BodyHandle> = w.bodies.iter().map(|(h, _)| h).collect();
    let mut fell_asleep = 0;
    for step in 0..900 {
        let before: HashMap<BodyHandle, Transform> = live.iter().map(|&b| (b, w.transform(b).unwrap())).collect();
        w.step(DT).unwrap();
        let mut reported = HashSet::new();
        for e in &w.events().body_moves {
            assert!(reported.insert(e.body), "step {step}: one event per body");
            assert_eq!(e.transform, w.transform(e.body).unwrap());
            assert_eq!(e.user_data, w.body(e.body).unwrap().user_data);
            assert_eq!(e.fell_asleep, !w.is_awake(e.body).unwrap());
            fell_asleep += e.fell_asleep as usize;
        }
        let moved: HashSet<BodyHandle> = live
            .iter()
            .copied()
            .filter(|b| {
                let body = w.body(*b).unwrap();
                body.enable_move_events && body.xf != before[b]
            })
            .collect();
        let reported_moving: HashSet<BodyHandle> = w
            .events()
            .body_moves
            .iter()
            .filter(|e| !e.fell_asleep || e.transform != before[&e.body])
            .map(|e| e.body)
            .collect();
        assert_eq!(moved, reported_moving, "step {step}");
        for b in &moved {
            assert!(w.is_awake(*b).unwrap() || w.events().body_moves.iter().any(|e| e.body == *b && e.fell_asleep));
        }
    }
    assert!(fell_asleep > 100, "the pile fell asleep: {fell_asleep}");
    assert_eq!(w.awake_body_count(), 0, "asleep");
    w.step(DT).unwrap();
    assert!(w.events().body_moves.is_empty(), "a sleeping world reports nothing");
}

/// The one-way platform: contacts with the platform push only where the box is above it.
struct OneWay {
    platform: ShapeHandle,
}

impl StepCallbacks for OneWay {
    fn pre_solve(&mut self, _world: &World, c: &PreSolveContact) -> bool {
        let up = if c.shape_a == self.platform {
            c.manifold.normal
        } else if c.shape_b == self.platform {
            -c.manifold.normal
        } else {
            return true;
        };
        // Pushes only upwards, and only when the box is not already part-way through.
        let deepest = c
            .manifold
            .points()
            .iter()
            .map(|p| p.separation)
            .fold(f32::MAX, f32::min);
        up.y > 0.7 && deepest > -0.05
    }
}

/// The one-way platform scene (also `examples/c/one_way_platform.c`): returns the box's
/// height after 3 s and its greatest height.
fn one_way_platform(callbacks: bool) -> (f32, f32) {
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let p = body(&mut w, BodyType::Static, Vec3::new(0.0, 3.0, 0.0));
    let platform = w
        .create_shape(
            p,
            &ShapeDef::default(),
            &Geometry::Box {
                center: Vec3::ZERO,
                rotation: Quat::IDENTITY,
                half_extents: Vec3::new(2.0, 0.1, 2.0),
            },
        )
        .unwrap();
    let b = body(&mut w, BodyType::Dynamic, Vec3::new(0.0, 0.5, 0.0));
    w.create_shape(b, &ShapeDef::default(), &cube(0.25)).unwrap();
    // Thrown up at 10 m/s: it would rise 5.1 m, past the platform at 3 m.
    w.set_linear_velocity(b, Vec3::new(0.0, 10.0, 0.0)).unwrap();
    let mut cb = OneWay { platform };
    let mut top = 0.0_f32;
    for _ in 0..180 {
        if callbacks {
            w.step_with(DT, &mut cb).unwrap();
        } else {
            w.step(DT).unwrap();
        }
        top = top.max(w.transform(b).unwrap().p.y);
    }
    (w.transform(b).unwrap().p.y, top)
}

#[test]
fn a_one_way_platform_lets_a_box_up_through_and_holds_it_on_top() {
    let (y, top) = one_way_platform(true);
    // Rest height: platform top 3.1 m + half size 0.25 m, within 5 mm (the contact's
    // resting overlap is under a millimetre).
    println!("one-way platform: rests at {y:.4} m, rose to {top:.3} m");
    assert!(top > 4.0, "it passed the platform: rose to {top}");
    assert!((y - 3.35).abs() < 0.005, "rests on top: y = {y}");
    // Without the callback the platform stops it from below.
    let (y, top) = one_way_platform(false);
    assert!(top < 3.0 && y < 1.0, "blocked from below: top {top}, y {y}");
}

/// A pair filter that refuses every pair with a marked shape.
struct Refuse(HashSet<ShapeHandle>, usize);

impl StepCallbacks for Refuse {
    fn pair_filter(&mut self, _world: &World, a: ShapeHandle, b: ShapeHandle) -> bool {
        self.1 += 1;
        !self.0.contains(&a) && !self.0.contains(&b)
    }
}

#[test]
fn a_pair_filter_keeps_refused_pairs_apart() {
    let mut w = World::new(WorldSettings::default()).unwrap();
    ground(&mut w);
    let a = body(&mut w, BodyType::Dynamic, Vec3::new(0.0, 0.5, 0.0));
    w.create_shape(a, &ShapeDef::default(), &cube(0.5)).unwrap();
    let b = body(&mut w, BodyType::Dynamic, Vec3::new(0.0, 2.0, 0.0));
    let ghost = w.create_shape(b, &ShapeDef::default(), &cube(0.5)).unwrap();
    let mut filter = Refuse(HashSet::from([ghost]), 0);
    for _ in 0..120 {
        w.step_with(DT, &mut filter).unwrap();
    }
    // The ghost fell through the lower box onto the ground beside... it rests on the ground
    // overlapping it (the plane is refused too: it falls for ever).
    assert!(filter.1 > 0, "the filter was asked");
    let y = w.transform(b).unwrap().p.y;
    assert!(y < -5.0, "the refused box fell through everything: y = {y}");
    let y = w.transform(a).unwrap().p.y;
    assert!((y - 0.5).abs() < 0.01, "the other box rests: y = {y}");
}

/// A small deterministic generator (xorshift).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }
    fn flag(&mut self) -> bool {
        self.next() & 1 == 1
    }
}

#[test]
fn random_scenes_keep_the_event_books_straight() {
    for seed in 1..=12u64 {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ seed.wrapping_mul(0x1234_5678_9ABC_DEF1));
        let mut w = World::new(WorldSettings::default()).unwrap();
        ground(&mut w);
        let mut defs: HashMap<ShapeHandle, ShapeDef> = HashMap::new();
        let mut bodies = Vec::new();
        for _ in 0..40 {
            let kind = match rng.next() % 6 {
                0 => BodyType::Static,
                1 => BodyType::Kinematic,
                _ => BodyType::Dynamic,
            };
            let p = Vec3::new(rng.range(-3.0, 3.0), rng.range(0.5, 6.0), rng.range(-3.0, 3.0));
            let b = body(&mut w, kind, p);
            if kind == BodyType::Kinematic {
                let v = Vec3::new(rng.range(-2.0, 2.0), rng.range(-1.0, 1.0), rng.range(-2.0, 2.0));
                w.set_linear_velocity(b, v).unwrap();
            }
            let def = ShapeDef {
                is_sensor: rng.next() % 4 == 0,
                enable_contact_events: rng.flag(),
                enable_hit_events: rng.flag(),
                enable_sensor_events: rng.flag(),
                ..Default::default()
            };
            let g = if rng.flag() {
                cube(rng.range(0.2, 0.8))
            } else {
                Geometry::Sphere {
                    center: Vec3::ZERO,
                    radius: rng.range(0.2, 0.8),
                }
            };
            let s = w.create_shape(b, &def, &g).unwrap();
            defs.insert(s, def);
            bodies.push(b);
        }
        let ground_def = ShapeDef::default();
        let key = |a: ShapeHandle, b: ShapeHandle| if a < b { (a, b) } else { (b, a) };
        let mut touching: HashSet<(ShapeHandle, ShapeHandle)> = HashSet::new();
        let mut overlapping: HashSet<(ShapeHandle, ShapeHandle)> = HashSet::new();
        for step in 0..400 {
            if step % 25 == 24 && !bodies.is_empty() {
                let k = (rng.next() % bodies.len() as u64) as usize;
                let b = bodies.swap_remove(k);
                w.destroy_body(b).unwrap();
            }
            w.step(DT).unwrap();
            let def = |s: ShapeHandle| defs.get(&s).copied().unwrap_or(ground_def);
            let ev = w.events();
            for e in &ev.contact_begin {
                let (a, b) = (def(e.shape_a), def(e.shape_b));
                assert!(
                    a.enable_contact_events && b.enable_contact_events,
                    "seed {seed}: disabled"
                );
                assert!(!a.is_sensor && !b.is_sensor);
                assert!(touching.insert(key(e.shape_a, e.shape_b)), "seed {seed}: begun twice");
            }
            for e in &ev.contact_end {
                assert!(
                    touching.remove(&key(e.shape_a, e.shape_b)),
                    "seed {seed}: end without begin"
                );
            }
            for e in &ev.contact_hit {
                let (a, b) = (def(e.shape_a), def(e.shape_b));
                assert!(a.enable_hit_events || b.enable_hit_events, "seed {seed}: hit disabled");
                assert!(e.speed.is_finite() && e.speed > 1.0 && e.point.is_finite());
                assert!((e.normal.length() - 1.0).abs() < 1e-3);
            }
            for e in &ev.sensor_begin {
                let (s, v) = (def(e.sensor_shape), def(e.visitor_shape));
                assert!(s.is_sensor && !v.is_sensor);
                assert!(s.enable_sensor_events && v.enable_sensor_events, "seed {seed}");
                assert!(
                    overlapping.insert((e.sensor_shape, e.visitor_shape)),
                    "seed {seed}: twice"
                );
            }
            for e in &ev.sensor_end {
                assert!(overlapping.remove(&(e.sensor_shape, e.visitor_shape)), "seed {seed}");
            }
            for e in &ev.body_moves {
                assert!(e.transform.p.is_finite() && e.transform.q.is_finite());
            }
            for &b in &bodies {
                let body = w.body(b).unwrap();
                assert!(body.xf.p.is_finite() && body.v.is_finite() && body.v.length() <= 400.0);
            }
        }
        // Everything destroyed: every open begin gets its end.
        for b in bodies.drain(..) {
            w.destroy_body(b).unwrap();
        }
        w.step(DT).unwrap();
        for e in &w.events().contact_end {
            assert!(touching.remove(&key(e.shape_a, e.shape_b)), "seed {seed}");
        }
        for e in &w.events().sensor_end {
            assert!(overlapping.remove(&(e.sensor_shape, e.visitor_shape)), "seed {seed}");
        }
        assert!(touching.is_empty(), "seed {seed}: open begins {touching:?}");
        assert!(overlapping.is_empty(), "seed {seed}: open sensor begins");
    }
}

#[test]
fn events_are_deterministic() {
    let run = || {
        let mut w = scenes::world(true);
        scenes::pile(&mut w, 120);
        let mut log = Vec::new();
        for _ in 0..120 {
            w.step(DT).unwrap();
            let ev = w.events();
            log.extend(ev.contact_begin.iter().map(|e| (e.shape_a.index, e.shape_b.index)));
            log.extend(ev.contact_end.iter().map(|e| (e.shape_b.index, e.shape_a.index)));
            log.extend(ev.body_moves.iter().map(|e| (e.body.index, e.transform.p.y.to_bits())));
        }
        log
    };
    assert_eq!(run(), run());
}

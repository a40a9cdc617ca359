//! Recordings (`src/record/`): what the recorder writes is what the world did, decoded by the
//! reader within the format's stated precision; structure changes mid-recording; truncated
//! recordings replay up to their last whole step; a steady recording allocates nothing.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
#[path = "common/thread_allocs.rs"]
mod thread_allocs;

use hearth::joints::BallParams;
use hearth::particles::ParticleDef;
use hearth::record::format::*;
use hearth::record::read::{self, DefRecord, ReadError, ShapeRecord};
use hearth::record::{RecordOptions, Recorder};
use hearth::soft::{mesh, SoftBodyDef};
use hearth::{BodyDef, BodyHandle, BodyType, Geometry, JointDef, JointKind, Quat, ShapeDef, Transform, Vec3, World};
use std::collections::BTreeMap;

const DT: f32 = 1.0 / 60.0;

/// Records `steps` steps; returns the bytes.
fn record(world: &mut World, steps: usize, options: RecordOptions) -> Vec<u8> {
    let mut rec = Recorder::new(world, options);
    let mut out = rec.bytes().to_vec();
    rec.clear();
    for _ in 0..steps {
        world.step(DT).unwrap();
        rec.record_step(world, DT, 0.001);
        out.extend_from_slice(rec.bytes());
        rec.clear();
    }
    out
}

/// Position error of a recorded pose: exact f32; rotation error of smallest-three (each
/// component within 2.2e-5, so a rotated unit axis within 1.5e-4).
fn assert_pose_close(recorded: Transform, actual: Transform, what: &str) {
    assert_eq!(recorded.p, actual.p, "{what}: positions are stored as f32");
    for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
        let e = (recorded.q * axis - actual.q * axis).length();
        assert!(e < 1.5e-4, "{what}: rotation error {e}");
    }
}

#[test]
fn a_recorded_pile_replays_every_body_where_the_world_put_it() {
    let mut w = scenes::world(true);
    let bodies = scenes::pile(&mut w, 200);
    let mut rec = Recorder::new(&w, RecordOptions::default());
    let mut bytes = rec.bytes().to_vec();
    rec.clear();
    let mut expected = Vec::new(); // (frame, poses, velocities, awake) at a few frames
    for step in 1..=240 {
        w.step(DT).unwrap();
        rec.record_step(&w, DT, 0.002);
        bytes.extend_from_slice(rec.bytes());
        rec.clear();
        if step % 60 == 0 {
            let snap: Vec<_> = bodies
                .iter()
                .map(|&b| {
                    let body = w.bodies.get(b).unwrap();
                    (b, body.xf, body.v, body.w, body.awake)
                })
                .collect();
            expected.push((step, snap));
        }
    }
    let r = read::parse(&bytes).unwrap();
    assert!(!r.truncated);
    assert_eq!(r.frames.len(), 241, "frame 0 and one per step");
    assert_eq!(r.gravity, Vec3::new(0.0, -9.81, 0.0));
    assert_eq!(r.frames[0].step, 0);
    assert_eq!(r.frames[240].step, 240);
    assert!((r.frames[240].time - 4.0).abs() < 1e-4);
    assert_eq!(r.frames[10].step_seconds, 0.002);
    // Frame 0 defines every body with its shapes: ground, 4 walls, 200 dynamic bodies.
    let defs = &r.frames[0].defs;
    assert_eq!(defs.len(), 205);
    let spheres = defs
        .iter()
        .filter(|d| matches!(d, DefRecord::Body(b) if matches!(b.shapes[..], [ShapeRecord::Sphere { radius, .. }] if radius == 0.5)))
        .count();
    assert_eq!(spheres, 100);
    // Later frames define nothing: the structure did not change.
    assert!(r.frames[1..].iter().all(|f| f.defs.is_empty()));
    for (step, snap) in expected {
        let state = r.bodies_at(step);
        assert_eq!(state.len(), 205);
        assert_eq!(r.frames[step].counters.bodies, 205);
        for (h, xf, v, wv, awake) in snap {
            let s = &state[&h.index];
            assert_eq!(s.def.generation, h.generation);
            assert_eq!(s.def.body_type, BODY_DYNAMIC);
            assert_pose_close(s.pose(), xf, &format!("body {} at step {step}", h.index));
            let rec = s.record.unwrap();
            assert_eq!(rec.awake, awake);
            // Velocities are half floats: relative error 2^-11, absolute 6e-5 near zero.
            for (got, want) in [(rec.linear_velocity, v), (rec.angular_velocity, wv)] {
                let tol = want.abs() * 4.9e-4 + Vec3::splat(6.0e-5);
                assert!(((got - want).abs() - tol).max_element() <= 0.0, "{got} vs {want}");
            }
        }
    }
    // A body record is 31 bytes (README): the 200 falling bodies of frame 1 are all written,
    // slots one apart; the step chunk's fixed part is 84 bytes (docs/recording-format.md).
    let frame1 = {
        let mut at = HEADER_LEN;
        let mut steps = 0;
        loop {
            let len = u32::from_le_bytes(bytes[at + 4..at + 8].try_into().unwrap()) as usize;
            if bytes[at..at + 4] == TAG_STEP {
                steps += 1;
                if steps == 2 {
                    break CHUNK_HEADER_LEN + len;
                }
            }
            at += CHUNK_HEADER_LEN + len;
        }
    };
    assert_eq!(r.frames[1].bodies.len(), 200);
    assert_eq!((frame1 - 84) as f64 / 200.0, 31.0, "bytes per body record");
    // Only moved bodies are written: once the pile sleeps, frames carry no bodies.
    for _ in 0..600 {
        w.step(DT).unwrap();
    }
    assert_eq!(w.awake_body_count(), 0, "the pile should be asleep");
    let mut rec = Recorder::new(&w, RecordOptions::default());
    rec.clear();
    w.step(DT).unwrap();
    rec.record_step(&w, DT, 0.0);
    let f = read::parse(&[&MAGIC[..], &VERSION.to_le_bytes(), &0u32.to_le_bytes(), rec.bytes()].concat()).unwrap();
    assert_eq!(f.frames[0].bodies.len(), 0);
}

/// A mixed scene: static ground plane, a kinematic box, dynamic spheres, boxes and
/// capsules, a ball joint to the world and one between bodies, particles, a soft body.
fn mixed_scene(w: &mut World) -> (Vec<BodyHandle>, BodyHandle, hearth::soft::SoftBodyHandle) {
    scenes::ground_plane(w);
    let kin = w
        .create_body(&BodyDef {
            body_type: BodyType::Kinematic,
            transform: Transform::new(Vec3::new(5.0, 1.0, 0.0), Quat::IDENTITY),
            linear_velocity: Vec3::new(0.0, 0.0, 1.0),
            user_data: 77,
            ..Default::default()
        })
        .unwrap();
    let geom = Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::new(1.0, 0.25, 1.0),
    };
    w.create_shape(kin, &ShapeDef::default(), &geom).unwrap();
    let mut dynamic = Vec::new();
    for i in 0..6 {
        let b = w
            .create_body(&BodyDef {
                body_type: BodyType::Dynamic,
                transform: Transform::new(Vec3::new(i as f32 * 1.2 - 3.0, 2.0 + i as f32, 0.0), Quat::IDENTITY),
                user_data: 1000 + i,
                ..Default::default()
            })
            .unwrap();
        let g = match i % 3 {
            0 => Geometry::Sphere {
                center: Vec3::ZERO,
                radius: 0.4,
            },
            1 => Geometry::Capsule {
                a: Vec3::new(-0.3, 0.0, 0.0),
                b: Vec3::new(0.3, 0.0, 0.0),
                radius: 0.2,
            },
            _ => Geometry::Box {
                center: Vec3::ZERO,
                rotation: Quat::from_rotation_y(0.3),
                half_extents: Vec3::new(0.3, 0.4, 0.5),
            },
        };
        w.create_shape(b, &ShapeDef::default(), &g).unwrap();
        dynamic.push(b);
    }
    let mut ball = JointDef::new(JointKind::Ball(BallParams::default()));
    ball.body_a = dynamic[0];
    ball.frame_a = Transform::new(Vec3::new(0.0, 0.5, 0.0), Quat::IDENTITY);
    ball.frame_b = Transform::new(Vec3::new(-3.0, 2.5, 0.0), Quat::IDENTITY);
    w.create_joint(&ball).unwrap();
    let mut pair = JointDef::new(JointKind::Fixed);
    pair.body_a = dynamic[1];
    pair.body_b = dynamic[2];
    pair.frame_a = Transform::new(Vec3::new(0.6, 0.5, 0.0), Quat::IDENTITY);
    pair.frame_b = Transform::new(Vec3::new(-0.6, -0.5, 0.0), Quat::IDENTITY);
    w.create_joint(&pair).unwrap();
    for i in 0..10 {
        w.create_particle(&ParticleDef {
            position: Vec3::new(i as f32 * 0.3, 4.0, 2.0),
            radius: 0.05 + 0.01 * i as f32,
            ..Default::default()
        })
        .unwrap();
    }
    let soft = SoftBodyDef {
        transform: Transform::new(Vec3::new(0.0, 3.0, -3.0), Quat::IDENTITY),
        pressure: 50.0,
        ..Default::default()
    };
    let soft = w.create_soft_body(&soft, &mesh::icosphere(0.5, 1), None).unwrap();
    (dynamic, kin, soft)
}

#[test]
fn particles_soft_bodies_joints_and_contacts_are_recorded_each_step() {
    let mut w = scenes::world(true);
    let (dynamic, kin, soft) = mixed_scene(&mut w);
    let bytes = record(&mut w, 90, RecordOptions { contacts: true });
    let r = read::parse(&bytes).unwrap();
    assert_eq!(r.flags & FLAG_CONTACTS, FLAG_CONTACTS);
    let last = r.frames.last().unwrap();
    assert_eq!(last.step, 90);
    // Definitions: the kinematic box with its user data, capsules with their segments.
    let defs: Vec<_> = r.frames[0]
        .defs
        .iter()
        .filter_map(|d| match d {
            DefRecord::Body(b) => Some(b),
            _ => None,
        })
        .collect();
    let k = defs.iter().find(|b| b.index == kin.index).unwrap();
    assert_eq!((k.body_type, k.user_data), (BODY_KINEMATIC, 77));
    let cap = defs.iter().find(|b| b.index == dynamic[1].index).unwrap();
    assert_eq!(
        cap.shapes,
        vec![ShapeRecord::Capsule {
            a: Vec3::new(-0.3, 0.0, 0.0),
            b: Vec3::new(0.3, 0.0, 0.0),
            radius: 0.2
        }]
    );
    assert!(defs.iter().any(|b| matches!(b.shapes[..], [ShapeRecord::Plane { .. }])));
    let soft_defs: Vec<_> = r.frames[0]
        .defs
        .iter()
        .filter_map(|d| match d {
            DefRecord::Soft(s) => Some(s),
            _ => None,
        })
        .collect();
    assert_eq!(soft_defs.len(), 1);
    let sb = w.soft_body(soft).unwrap();
    assert_eq!(soft_defs[0].vertex_count as usize, sb.pos.len());
    assert_eq!(soft_defs[0].triangles, sb.triangles);
    // Last frame: particles, soft vertices, joints exactly as the world has them.
    assert_eq!(last.particles.len(), 10);
    for (i, (p, radius)) in last.particles.iter().enumerate() {
        assert_eq!(*p, w.particles.pos[i]);
        assert!((radius - w.particles.radius[i]).abs() < 1e-4);
    }
    assert_eq!(last.soft_bodies.len(), 1);
    assert_eq!(last.soft_bodies[0].positions, sb.pos);
    assert_eq!(last.joints.len(), 2);
    let ball = last.joints.iter().find(|j| j.body_b == NO_BODY).unwrap();
    assert_eq!(ball.kind, JOINT_BALL);
    assert_eq!(ball.anchor_b, Vec3::new(-3.0, 2.5, 0.0));
    let xf0 = w.transform(dynamic[0]).unwrap();
    assert!((ball.anchor_a - xf0.apply(Vec3::new(0.0, 0.5, 0.0))).length() < 1e-6);
    // The ball joint holds: its anchors stay within a centimetre.
    assert!((ball.anchor_a - ball.anchor_b).length() < 0.01);
    let fixed = last.joints.iter().find(|j| j.kind == JOINT_FIXED).unwrap();
    assert_eq!((fixed.body_a, fixed.body_b), (dynamic[1].index, dynamic[2].index));
    // Contacts: bodies on the ground push with positive impulses along unit normals.
    assert!(!last.contacts.is_empty());
    assert_eq!(
        last.contacts.len() as u32,
        last.counters.touching_contacts.min(last.contacts.len() as u32)
    );
    for m in &last.contacts {
        assert!((m.normal.length() - 1.0).abs() < 1e-4);
        assert!(!m.points.is_empty() && m.points.len() <= 4);
        assert!(m.points.iter().all(|p| p.normal_impulse >= 0.0 && p.point.is_finite()));
    }
    let total: f32 = last
        .contacts
        .iter()
        .flat_map(|m| m.points.iter())
        .map(|p| p.normal_impulse)
        .sum();
    assert!(total > 0.0);
    // The kinematic box moves at 1 m/s along z: recorded every step with that velocity.
    let states = r.bodies_at(60);
    let kr = states[&kin.index].record.unwrap();
    assert!((kr.pose.p.z - 1.0).abs() < 1e-3, "{}", kr.pose.p);
    assert!((kr.linear_velocity - Vec3::new(0.0, 0.0, 1.0)).length() < 1e-3);
    // Counters.
    assert_eq!(last.counters.particles, 10);
    assert_eq!(last.counters.soft_bodies, 1);
    assert_eq!(last.counters.joints, 2);
    // Without the contacts flag, no contacts.
    let mut w2 = scenes::world(true);
    mixed_scene(&mut w2);
    let r2 = read::parse(&record(&mut w2, 30, RecordOptions::default())).unwrap();
    assert_eq!(r2.flags & FLAG_CONTACTS, 0);
    assert!(r2.frames.iter().all(|f| f.contacts.is_empty()));
}

/// Seeded xorshift for the randomized tests.
struct Rng(u32);
impl Rng {
    fn next(&mut self) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        self.0
    }
    fn unit(&mut self) -> f32 {
        self.next() as f32 / u32::MAX as f32
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }
}

/// What the world holds now, as the replay must show it: slot → (generation, type, user
/// data, shape count, pose).
fn world_state(w: &World) -> BTreeMap<u32, (u32, u8, u64, usize, Transform)> {
    w.bodies
        .iter()
        .map(|(h, b)| {
            let t = match b.body_type {
                BodyType::Static => BODY_STATIC,
                BodyType::Kinematic => BODY_KINEMATIC,
                BodyType::Dynamic => BODY_DYNAMIC,
            };
            (h.index, (h.generation, t, b.user_data, b.shapes.len(), b.xf))
        })
        .collect()
}

fn assert_replay_matches(
    r: &read::Recording,
    frame: usize,
    expected: &BTreeMap<u32, (u32, u8, u64, usize, Transform)>,
) {
    let got = r.bodies_at(frame);
    assert_eq!(
        got.keys().collect::<Vec<_>>(),
        expected.keys().collect::<Vec<_>>(),
        "live bodies at frame {frame}"
    );
    for (i, (generation, t, user_data, shapes, xf)) in expected {
        let s = &got[i];
        assert_eq!(
            (s.def.generation, s.def.body_type, s.def.user_data, s.def.shapes.len()),
            (*generation, *t, *user_data, *shapes),
            "body {i} at frame {frame}"
        );
        assert_pose_close(s.pose(), *xf, &format!("body {i} at frame {frame}"));
    }
}

/// Seeded random calls between steps — create and destroy bodies (slots reused with new
/// generations), add and remove shapes, teleport bodies, sleep and wake — recorded; at every
/// frame the replayed set of bodies, their definitions and poses are the world's.
#[test]
fn randomized_structure_changes_replay_exactly_frame_by_frame() {
    for seed in [1u32, 7, 1234, 99_991] {
        let mut rng = Rng(seed);
        let mut w = scenes::world(true);
        scenes::ground_plane(&mut w);
        let mut live: Vec<BodyHandle> = Vec::new();
        let mut shapes = Vec::new();
        let mut rec = Recorder::new(
            &w,
            RecordOptions {
                contacts: seed % 2 == 0,
            },
        );
        let mut bytes = rec.bytes().to_vec();
        rec.clear();
        let mut expected = vec![world_state(&w)];
        for _ in 0..120 {
            for _ in 0..(rng.next() % 4) {
                match rng.next() % 6 {
                    0 | 1 => {
                        let kind = if rng.next() % 5 == 0 {
                            BodyType::Static
                        } else {
                            BodyType::Dynamic
                        };
                        let b = w
                            .create_body(&BodyDef {
                                body_type: kind,
                                transform: Transform::new(
                                    Vec3::new(rng.range(-5.0, 5.0), rng.range(0.5, 6.0), rng.range(-5.0, 5.0)),
                                    Quat::from_rotation_x(rng.range(-3.0, 3.0)),
                                ),
                                user_data: rng.next() as u64 * 3,
                                ..Default::default()
                            })
                            .unwrap();
                        let g = Geometry::Sphere {
                            center: Vec3::ZERO,
                            radius: rng.range(0.1, 0.6),
                        };
                        shapes.push(w.create_shape(b, &ShapeDef::default(), &g).unwrap());
                        live.push(b);
                    }
                    2 if !live.is_empty() => {
                        let b = live.swap_remove(rng.next() as usize % live.len());
                        w.destroy_body(b).unwrap();
                    }
                    3 if !live.is_empty() => {
                        let b = live[rng.next() as usize % live.len()];
                        let g = Geometry::Box {
                            center: Vec3::new(0.0, 0.3, 0.0),
                            rotation: Quat::IDENTITY,
                            half_extents: Vec3::splat(rng.range(0.1, 0.4)),
                        };
                        shapes.push(w.create_shape(b, &ShapeDef::default(), &g).unwrap());
                    }
                    4 if !shapes.is_empty() => {
                        let s = shapes.swap_remove(rng.next() as usize % shapes.len());
                        let _ = w.destroy_shape(s); // its body may be gone already
                    }
                    5 if !live.is_empty() => {
                        let b = live[rng.next() as usize % live.len()];
                        let p = Vec3::new(rng.range(-5.0, 5.0), rng.range(1.0, 5.0), rng.range(-5.0, 5.0));
                        w.set_transform(b, Transform::new(p, Quat::from_rotation_z(rng.range(-1.0, 1.0))))
                            .unwrap();
                    }
                    _ => {}
                }
            }
            w.step(DT).unwrap();
            rec.record_step(&w, DT, 0.0);
            bytes.extend_from_slice(rec.bytes());
            rec.clear();
            expected.push(world_state(&w));
            for s in w.bodies.iter().map(|(_, b)| b) {
                assert!(s.xf.p.is_finite() && s.v.length() < 100.0, "bounded state");
            }
        }
        let r = read::parse(&bytes).unwrap();
        assert_eq!(r.frames.len(), expected.len());
        for (f, e) in expected.iter().enumerate() {
            assert_replay_matches(&r, f, e);
        }
    }
}

/// Every runtime setter of `world_setters.rs` between steps, at random — shape materials and
/// user data, gravity scale, locks, mass overrides and their reset, body type changes among
/// all three types, disable and enable — recorded: at every frame the replay holds exactly the
/// enabled bodies, each with the world's generation, type, user data and shapes, at the
/// world's position bit for bit (the rotation is packed to 6 bytes: within the packing's
/// error).
#[test]
fn every_runtime_setter_replays_frame_by_frame() {
    use hearth::world_setters::MassData;
    for seed in [3u32, 77, 4242] {
        let mut rng = Rng(seed);
        let mut w = scenes::world(true);
        scenes::ground_plane(&mut w);
        let mut bodies = Vec::new();
        let mut shapes = Vec::new();
        for k in 0..12 {
            let b = w
                .create_body(&BodyDef {
                    body_type: BodyType::Dynamic,
                    transform: Transform::new(
                        Vec3::new((k % 4) as f32 * 1.5 - 2.0, 1.0 + (k / 4) as f32, 0.0),
                        Quat::IDENTITY,
                    ),
                    user_data: k as u64 + 100,
                    ..Default::default()
                })
                .unwrap();
            let g = Geometry::Sphere {
                center: Vec3::ZERO,
                radius: 0.4,
            };
            shapes.push(w.create_shape(b, &ShapeDef::default(), &g).unwrap());
            bodies.push(b);
        }
        let state = |w: &World| {
            let mut m = world_state(w);
            m.retain(|&i, _| w.bodies.iter().any(|(h, b)| h.index == i && b.enabled));
            m
        };
        let mut rec = Recorder::new(&w, RecordOptions::default());
        let mut bytes = rec.bytes().to_vec();
        rec.clear();
        let mut expected = vec![state(&w)];
        let mut used = [false; 11];
        for _ in 0..150 {
            for _ in 0..(rng.next() % 3) {
                let k = rng.next() as usize % bodies.len();
                let (b, s) = (bodies[k], shapes[k]);
                let op = rng.next() as usize % 11;
                used[op] = true;
                match op {
                    0 => w
                        .edit_shape_material(s, |d| d.static_friction = rng.range(0.0, 1.0))
                        .unwrap(),
                    1 => w
                        .edit_shape_material(s, |d| d.restitution = rng.range(0.0, 1.0))
                        .unwrap(),
                    2 => w
                        .edit_shape_material(s, |d| d.density = rng.range(100.0, 3000.0))
                        .unwrap(),
                    3 => w.set_shape_user_data(s, rng.next() as u64).unwrap(),
                    4 => w.set_gravity_scale(b, rng.range(-0.5, 2.0)).unwrap(),
                    5 => w.set_locked_axes(b, rng.next() % 64).unwrap(),
                    6 => {
                        let data = MassData {
                            mass: rng.range(1.0, 50.0),
                            center: Vec3::ZERO,
                            inertia: Vec3::splat(rng.range(0.5, 5.0)),
                        };
                        // A static or kinematic body refuses a mass override.
                        let _ = w.set_mass_data(b, &data);
                    }
                    7 => {
                        let _ = w.reset_mass_data(b);
                    }
                    8 => {
                        let t = [BodyType::Static, BodyType::Kinematic, BodyType::Dynamic][rng.next() as usize % 3];
                        w.set_body_type(b, t).unwrap();
                    }
                    9 => w.disable_body(b).unwrap(),
                    _ => w.enable_body(b).unwrap(),
                }
            }
            w.step(DT).unwrap();
            rec.record_step(&w, DT, 0.0);
            bytes.extend_from_slice(rec.bytes());
            rec.clear();
            expected.push(state(&w));
        }
        assert!(used.iter().all(|&u| u), "seed {seed}: every setter called ({used:?})");
        let r = read::parse(&bytes).unwrap();
        assert_eq!(r.frames.len(), expected.len());
        for (f, e) in expected.iter().enumerate() {
            assert_replay_matches(&r, f, e);
            let got = r.bodies_at(f);
            for (i, (.., xf)) in e {
                let p = got[i].pose().p;
                assert_eq!(
                    p.to_array().map(f32::to_bits),
                    xf.p.to_array().map(f32::to_bits),
                    "body {i} at frame {f}"
                );
            }
        }
    }
}

#[test]
fn a_truncated_recording_replays_up_to_its_last_whole_step() {
    let mut w = scenes::world(true);
    mixed_scene(&mut w);
    let bytes = record(&mut w, 12, RecordOptions { contacts: true });
    let whole = read::parse(&bytes).unwrap();
    assert_eq!(whole.frames.len(), 13);
    // The byte offsets where each frame's chunk ends.
    let mut ends = Vec::new();
    let mut boundaries = vec![HEADER_LEN];
    let mut at = HEADER_LEN;
    while at < bytes.len() {
        let len = u32::from_le_bytes(bytes[at + 4..at + 8].try_into().unwrap()) as usize;
        at += CHUNK_HEADER_LEN + len;
        boundaries.push(at);
        if bytes[at - len - CHUNK_HEADER_LEN..][..4] == TAG_STEP {
            ends.push(at);
        }
    }
    assert_eq!(ends.len(), 13);
    assert_eq!(at, bytes.len());
    // Cut at every byte: the frames are exactly those whose chunk ends before the cut.
    for cut in HEADER_LEN..bytes.len() {
        let r = read::parse(&bytes[..cut]).unwrap_or_else(|e| panic!("cut at {cut}: {e}"));
        let whole_frames = ends.iter().filter(|&&e| e <= cut).count();
        assert_eq!(r.frames.len(), whole_frames, "cut at {cut}");
        assert_eq!(r.truncated, !boundaries.contains(&cut), "cut at {cut}");
        assert_eq!(r.frames[..], whole.frames[..whole_frames], "cut at {cut}");
    }
    // Not a recording at all, or a newer version: clear errors.
    assert_eq!(read::parse(b"hello").unwrap_err(), ReadError::BadMagic);
    let mut v2 = bytes.clone();
    v2[8] = 2;
    assert_eq!(read::parse(&v2).unwrap_err(), ReadError::UnsupportedVersion(2));
}

#[test]
fn recording_a_steady_scene_allocates_nothing_after_warm_up() {
    let mut w = scenes::world(false);
    scenes::pyramid(&mut w, 10);
    mixed_scene(&mut w);
    let mut rec = Recorder::new(&w, RecordOptions { contacts: true });
    let mut sink = Vec::with_capacity(1 << 24);
    for _ in 0..60 {
        w.step(DT).unwrap();
        rec.record_step(&w, DT, 0.0);
        sink.extend_from_slice(rec.bytes());
        rec.clear();
    }
    let mut allocations = 0;
    for _ in 0..60 {
        w.step(DT).unwrap();
        let before = thread_allocs::allocations();
        rec.record_step(&w, DT, 0.0);
        allocations += thread_allocs::allocations() - before;
        sink.clear();
        sink.extend_from_slice(rec.bytes());
        rec.clear();
    }
    assert_eq!(allocations, 0);
}

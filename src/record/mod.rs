//! Recordings: what the world did, step by step, in a compact binary stream that the browser
//! viewer (`viewer/`) replays. The format is specified in `docs/recording-format.md`.
//!
//! A [`Recorder`] reads the world after each step and appends bytes to its own buffer; it
//! never does I/O and never calls host code. Whoever drives it (the C layer in
//! `capi/record.rs`, or a Rust host) writes [`Recorder::bytes`] out and then calls
//! [`Recorder::clear`]. After warm-up (buffers grown to the scene's size) a step's recording
//! allocates nothing.
//!
//! What is written:
//! * once, and again whenever they change: every enabled body (type, user data, pose) with its
//!   shapes and their geometry, every soft body's triangles (`DEFS` chunks). A body type
//!   change writes the body again; disabling a body removes it as destroying it would, and
//!   enabling it writes it again. Materials, filters, gravity scale, locks and mass overrides
//!   are not part of the format (the poses show what they do);
//! * per step: the step counters, the dt and the time the step took; the pose, velocities and
//!   sleep state of each body whose pose or sleep state changed since it was last written;
//!   every particle; every soft-body vertex; every joint's two anchors; optionally every
//!   touching contact manifold with its points and normal impulses (`STEP` chunks).
//!
//! Every chunk carries its length, so a recording cut short (a crash, a full disk) still
//! replays up to its last whole step.

pub mod format;
pub mod read;

use crate::collision::geometry_store::GeometryStore;
use crate::collision::shape::Geometry;
use crate::dynamics::body::BodyType;
use crate::dynamics::joints::JointKind;
use crate::math::{Quat, Transform, Vec3};
use crate::pool::Handle;
use crate::world::World;
use format::*;

/// What a recording holds beyond the always-recorded state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RecordOptions {
    /// Record every touching contact manifold (points, normal, normal impulses) each step.
    pub contacts: bool,
}

/// What the recorder last wrote for a body slot.
#[derive(Clone, Debug, Default)]
struct BodySlot {
    /// Generation of the recorded body; 0 when the slot holds no recorded body.
    generation: u32,
    shapes: Vec<Handle>,
    /// Pose last written (position, rotation), bit-compared with the body's.
    pose: [u32; 7],
    awake: bool,
    /// Type code and user data of the recorded definition: a change (`World::set_body_type`)
    /// writes the definition again.
    body_type: u8,
    user_data: u64,
}

/// What the recorder last wrote for a soft-body slot.
#[derive(Clone, Copy, Debug, Default)]
struct SoftSlot {
    generation: u32,
    vertices: u32,
    triangles: u32,
}

/// Turns a world's steps into recording bytes. See the module docs.
pub struct Recorder {
    options: RecordOptions,
    buf: Vec<u8>,
    bodies: Vec<BodySlot>,
    softs: Vec<SoftSlot>,
    /// Steps recorded so far.
    steps: u32,
    /// Simulated time since the recording started (s).
    time: f64,
}

fn pose_bits(xf: &Transform) -> [u32; 7] {
    [
        xf.p.x.to_bits(),
        xf.p.y.to_bits(),
        xf.p.z.to_bits(),
        xf.q.x.to_bits(),
        xf.q.y.to_bits(),
        xf.q.z.to_bits(),
        xf.q.w.to_bits(),
    ]
}

#[inline]
fn put_u8(out: &mut Vec<u8>, v: u8) {
    out.push(v);
}
#[inline]
fn put_u32(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_le_bytes());
}
#[inline]
fn put_f32(out: &mut Vec<u8>, v: f32) {
    out.extend_from_slice(&v.to_le_bytes());
}
#[inline]
fn put_vec3(out: &mut Vec<u8>, v: Vec3) {
    put_f32(out, v.x);
    put_f32(out, v.y);
    put_f32(out, v.z);
}
#[inline]
fn put_quat(out: &mut Vec<u8>, q: Quat) {
    put_f32(out, q.x);
    put_f32(out, q.y);
    put_f32(out, q.z);
    put_f32(out, q.w);
}

/// Starts a chunk; returns where its length goes (patched by `end_chunk`).
fn begin_chunk(out: &mut Vec<u8>, tag: [u8; 4]) -> usize {
    out.extend_from_slice(&tag);
    let at = out.len();
    put_u32(out, 0);
    at
}

fn end_chunk(out: &mut [u8], at: usize) {
    let len = (out.len() - at - 4) as u32;
    out[at..at + 4].copy_from_slice(&len.to_le_bytes());
}

fn body_type_code(t: BodyType) -> u8 {
    match t {
        BodyType::Static => BODY_STATIC,
        BodyType::Kinematic => BODY_KINEMATIC,
        BodyType::Dynamic => BODY_DYNAMIC,
    }
}

fn joint_kind_code(k: &JointKind) -> u8 {
    // Not an exhaustive match: a new joint kind records as "other" until it gets a code.
    if matches!(k, JointKind::Ball(_)) {
        JOINT_BALL
    } else if matches!(k, JointKind::Hinge(_)) {
        JOINT_HINGE
    } else if matches!(k, JointKind::Fixed) {
        JOINT_FIXED
    } else if matches!(k, JointKind::Distance(_)) {
        JOINT_DISTANCE
    } else if matches!(k, JointKind::Slider(_)) {
        JOINT_SLIDER
    } else {
        JOINT_OTHER
    }
}

/// A shape's geometry. Shared geometry (hulls, meshes, heightfields) is recorded as the box
/// around it in the body's frame (`Geometry::local_box`): the viewer draws that box.
fn put_geometry(out: &mut Vec<u8>, g: &Geometry, store: &GeometryStore) {
    if let Some((center, rotation, half_extents)) = g.local_box(store) {
        put_u8(out, SHAPE_BOX);
        put_vec3(out, center);
        put_quat(out, rotation);
        put_vec3(out, half_extents);
        return;
    }
    match *g {
        Geometry::Sphere { center, radius } => {
            put_u8(out, SHAPE_SPHERE);
            put_vec3(out, center);
            put_f32(out, radius);
        }
        Geometry::Box {
            center,
            rotation,
            half_extents,
        } => {
            put_u8(out, SHAPE_BOX);
            put_vec3(out, center);
            put_quat(out, rotation);
            put_vec3(out, half_extents);
        }
        Geometry::Capsule { a, b, radius } => {
            put_u8(out, SHAPE_CAPSULE);
            put_vec3(out, a);
            put_vec3(out, b);
            put_f32(out, radius);
        }
        Geometry::Plane { normal, offset } => {
            put_u8(out, SHAPE_PLANE);
            put_vec3(out, normal);
            put_f32(out, offset);
        }
        Geometry::Hull { .. } | Geometry::Mesh { .. } | Geometry::Heightfield { .. } => {
            unreachable!("shared geometry is recorded as its box above")
        }
    }
}

impl Recorder {
    /// Starts a recording of `world` as it is now: the file header, the world chunk, every
    /// body and soft body, and frame 0 (the state before the first recorded step).
    pub fn new(world: &World, options: RecordOptions) -> Recorder {
        let mut r = Recorder {
            options,
            buf: Vec::with_capacity(1 << 16),
            bodies: Vec::new(),
            softs: Vec::new(),
            steps: 0,
            time: 0.0,
        };
        r.buf.extend_from_slice(&MAGIC);
        put_u32(&mut r.buf, VERSION);
        put_u32(&mut r.buf, if options.contacts { FLAG_CONTACTS } else { 0 });
        let at = begin_chunk(&mut r.buf, TAG_WORLD);
        put_vec3(&mut r.buf, world.settings.gravity);
        put_u32(&mut r.buf, world.settings.substeps);
        end_chunk(&mut r.buf, at);
        r.write_frame(world, 0.0, 0.0);
        r
    }

    pub fn options(&self) -> RecordOptions {
        self.options
    }

    /// Steps recorded so far (frame 0 not counted).
    pub fn steps(&self) -> u32 {
        self.steps
    }

    /// Records the step that just ran: `dt` is its duration (s), `step_seconds` the wall
    /// time it took (s, for the viewer's plot; 0 when unknown).
    pub fn record_step(&mut self, world: &World, dt: f32, step_seconds: f32) {
        self.steps += 1;
        self.time += dt as f64;
        self.write_frame(world, dt, step_seconds);
    }

    /// The bytes recorded since the last `clear`.
    pub fn bytes(&self) -> &[u8] {
        &self.buf
    }

    /// Forgets the bytes already written out (keeps the buffer's capacity).
    pub fn clear(&mut self) {
        self.buf.clear();
    }

    fn write_frame(&mut self, world: &World, dt: f32, step_seconds: f32) {
        self.write_defs(world);
        let mut out = std::mem::take(&mut self.buf);
        let at = begin_chunk(&mut out, TAG_STEP);
        put_u32(&mut out, self.steps);
        put_f32(&mut out, dt);
        put_f32(&mut out, self.time as f32);
        put_f32(&mut out, step_seconds);
        let c = &world.counters;
        for v in [
            world.bodies.len(),
            world.awake_bodies.len(),
            world.contacts.len(),
            c.touching_contacts,
            c.pairs_tested,
            c.proxies_moved,
            world.particles.len(),
            world.soft_bodies.live.len(),
            world.joints.pool.len(),
            world.broad.tree.height() as usize,
        ] {
            put_u32(&mut out, v as u32);
        }
        self.write_bodies(world, &mut out);
        // Particles: every position, then every radius (half floats).
        let p = &world.particles;
        put_u32(&mut out, p.len() as u32);
        for &x in &p.pos[..p.len()] {
            put_vec3(&mut out, x);
        }
        for &r in &p.radius[..p.len()] {
            out.extend_from_slice(&f32_to_f16(r).to_le_bytes());
        }
        // Soft bodies: every vertex of every live soft body.
        let softs = &world.soft_bodies;
        put_u32(&mut out, softs.live.len() as u32);
        for &s in &softs.live {
            let sb = softs.pool.at(s);
            put_u32(&mut out, s);
            put_u32(&mut out, sb.pos.len() as u32);
            for &x in &sb.pos {
                put_vec3(&mut out, x);
            }
        }
        // Joints: both anchors in world space.
        put_u32(&mut out, world.joints.pool.len() as u32);
        for (h, j) in world.joints.pool.iter() {
            put_u32(&mut out, h.index);
            put_u8(&mut out, joint_kind_code(&j.def.kind));
            put_u8(&mut out, j.broken as u8);
            let anchor = |b: u32, frame: &Transform| {
                if b == crate::dynamics::body::NONE {
                    (NO_BODY, frame.p)
                } else {
                    (b, world.bodies.at(b).xf.apply(frame.p))
                }
            };
            let (a, pa) = anchor(j.a, &j.def.frame_a);
            let (b, pb) = anchor(j.b, &j.def.frame_b);
            put_u32(&mut out, a);
            put_u32(&mut out, b);
            put_vec3(&mut out, pa);
            put_vec3(&mut out, pb);
        }
        // Contacts (optional): every touching manifold, sleeping ones included.
        if self.options.contacts {
            let count_at = out.len();
            put_u32(&mut out, 0);
            let mut count = 0u32;
            for (_, ct) in world.contacts.iter() {
                let m = &ct.manifold;
                if !ct.touching || m.count == 0 {
                    continue;
                }
                count += 1;
                put_u32(&mut out, ct.body_a);
                put_u32(&mut out, ct.body_b);
                put_vec3(&mut out, m.normal);
                put_u8(&mut out, m.count as u8);
                for (k, pt) in m.points().iter().enumerate() {
                    put_vec3(&mut out, pt.point);
                    put_f32(&mut out, pt.separation);
                    put_f32(&mut out, ct.impulses[k].normal);
                }
            }
            out[count_at..count_at + 4].copy_from_slice(&count.to_le_bytes());
        } else {
            put_u32(&mut out, 0);
        }
        end_chunk(&mut out, at);
        self.buf = out;
    }

    /// Body records: `varint((index − previous index) << 1 | awake)`, position (3 × f32),
    /// rotation (smallest three, 6 bytes), linear and angular velocity (3 × f16 each), for
    /// every body whose pose or sleep state changed since it was last written.
    fn write_bodies(&mut self, world: &World, out: &mut Vec<u8>) {
        let count_at = out.len();
        put_u32(out, 0);
        let mut count = 0u32;
        let mut previous: i64 = -1;
        for (h, b) in world.bodies.iter() {
            if !b.enabled {
                continue; // not in the replay while disabled (`write_defs`)
            }
            let slot = &mut self.bodies[h.index as usize];
            let pose = pose_bits(&b.xf);
            if slot.pose == pose && slot.awake == b.awake {
                continue;
            }
            slot.pose = pose;
            slot.awake = b.awake;
            count += 1;
            let delta = (h.index as i64 - previous) as u32;
            previous = h.index as i64;
            // One record, built on the stack and appended at once.
            let mut rec = [0u8; 35];
            let mut n = 0;
            let mut v = (delta << 1) | b.awake as u32;
            while v >= 0x80 {
                rec[n] = (v as u8) | 0x80;
                v >>= 7;
                n += 1;
            }
            rec[n] = v as u8;
            n += 1;
            for c in [b.xf.p.x, b.xf.p.y, b.xf.p.z] {
                rec[n..n + 4].copy_from_slice(&c.to_le_bytes());
                n += 4;
            }
            rec[n..n + 6].copy_from_slice(&pack_quat(b.xf.q));
            n += 6;
            for c in [b.v.x, b.v.y, b.v.z, b.w.x, b.w.y, b.w.z] {
                rec[n..n + 2].copy_from_slice(&f32_to_f16(c).to_le_bytes());
                n += 2;
            }
            out.extend_from_slice(&rec[..n]);
        }
        out[count_at..count_at + 4].copy_from_slice(&count.to_le_bytes());
    }

    /// Writes a `DEFS` chunk when bodies, their shapes or soft bodies changed since the last
    /// frame (nothing otherwise).
    fn write_defs(&mut self, world: &World) {
        let mut out = std::mem::take(&mut self.buf);
        let start = out.len();
        let at = begin_chunk(&mut out, TAG_DEFS);
        let mut changed = false;
        // Bodies, in slot order; slots skipped by the pool's iterator are free.
        let mut next = 0usize;
        for (h, b) in world.bodies.iter() {
            let i = h.index as usize;
            if self.bodies.len() <= i {
                self.bodies.resize(i + 1, BodySlot::default());
            }
            for gone in next..i {
                changed |= self.remove_body(gone, &mut out);
            }
            next = i + 1;
            if !b.enabled {
                // A disabled body (`World::disable_body`) leaves the replay as a destroyed
                // one does; enabling it writes its definition again.
                changed |= self.remove_body(i, &mut out);
                continue;
            }
            let slot = &mut self.bodies[i];
            let code = body_type_code(b.body_type);
            if slot.generation == h.generation
                && slot.shapes == b.shapes
                && slot.body_type == code
                && slot.user_data == b.user_data
            {
                continue;
            }
            changed = true;
            (slot.generation, slot.body_type, slot.user_data) = (h.generation, code, b.user_data);
            slot.shapes.clear();
            slot.shapes.extend_from_slice(&b.shapes);
            // Force a body record in this frame's step chunk (velocity, sleep state).
            slot.pose = [u32::MAX; 7];
            put_u8(&mut out, DEF_BODY);
            put_u32(&mut out, h.index);
            put_u32(&mut out, h.generation);
            put_u8(&mut out, code);
            out.extend_from_slice(&b.user_data.to_le_bytes());
            put_vec3(&mut out, b.xf.p);
            put_quat(&mut out, b.xf.q);
            put_u32(&mut out, b.shapes.len() as u32);
            for &s in &b.shapes {
                put_geometry(
                    &mut out,
                    &world.shapes.get(s).expect("a body's shape is live").geometry,
                    &world.geometry,
                );
            }
        }
        for gone in next..self.bodies.len() {
            changed |= self.remove_body(gone, &mut out);
        }
        // Soft bodies.
        let softs = &world.soft_bodies;
        let mut next = 0usize;
        for &s in &softs.live {
            let i = s as usize;
            if self.softs.len() <= i {
                self.softs.resize(i + 1, SoftSlot::default());
            }
            for gone in next..i {
                changed |= self.remove_soft(gone, &mut out);
            }
            next = i + 1;
            let h = softs.pool.handle_at(s).expect("live soft body");
            let sb = softs.pool.at(s);
            let slot = &mut self.softs[i];
            let (nv, nt) = (sb.pos.len() as u32, sb.triangles.len() as u32);
            if slot.generation == h.generation && slot.vertices == nv && slot.triangles == nt {
                continue;
            }
            changed = true;
            *slot = SoftSlot {
                generation: h.generation,
                vertices: nv,
                triangles: nt,
            };
            put_u8(&mut out, DEF_SOFT);
            put_u32(&mut out, s);
            put_u32(&mut out, h.generation);
            out.extend_from_slice(&sb.def.user_data.to_le_bytes());
            put_f32(&mut out, sb.def.vertex_radius);
            put_u32(&mut out, nv);
            put_u32(&mut out, nt);
            for t in &sb.triangles {
                for &v in t {
                    put_u32(&mut out, v);
                }
            }
        }
        for gone in next..self.softs.len() {
            changed |= self.remove_soft(gone, &mut out);
        }
        if changed {
            end_chunk(&mut out, at);
        } else {
            out.truncate(start);
        }
        self.buf = out;
    }

    fn remove_body(&mut self, i: usize, out: &mut Vec<u8>) -> bool {
        let slot = &mut self.bodies[i];
        if slot.generation == 0 {
            return false;
        }
        slot.generation = 0;
        slot.shapes.clear();
        slot.pose = [u32::MAX; 7];
        put_u8(out, DEF_BODY_REMOVED);
        put_u32(out, i as u32);
        true
    }

    fn remove_soft(&mut self, i: usize, out: &mut Vec<u8>) -> bool {
        let slot = &mut self.softs[i];
        if slot.generation == 0 {
            return false;
        }
        *slot = SoftSlot::default();
        put_u8(out, DEF_SOFT_REMOVED);
        put_u32(out, i as u32);
        true
    }
}

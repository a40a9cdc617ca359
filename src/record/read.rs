//! Reads a recording back: the decoder the tests (and Rust tools) use. The viewer has its own
//! in JavaScript (`viewer/recording.js`); both follow `docs/recording-format.md`.
//!
//! A recording cut short parses up to its last whole step: a chunk whose length runs past the
//! end is dropped and `Recording::truncated` is set.

use super::format::*;
use crate::math::{Quat, Transform, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub enum ReadError {
    /// The first eight bytes are not `HEARTHRC`.
    BadMagic,
    /// A format version this reader does not know.
    UnsupportedVersion(u32),
    /// A chunk's contents do not match its length (a corrupt file, not a truncated one).
    Corrupt(String),
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ReadError::BadMagic => write!(f, "not a Hearth recording (bad magic)"),
            ReadError::UnsupportedVersion(v) => write!(f, "recording format version {v} is not supported"),
            ReadError::Corrupt(m) => write!(f, "corrupt recording: {m}"),
        }
    }
}

/// Little-endian reads from a byte slice; running past the end is an error.
pub struct Cursor<'a> {
    data: &'a [u8],
    pos: usize,
}

type R<T> = Result<T, ReadError>;

impl<'a> Cursor<'a> {
    pub fn new(data: &'a [u8]) -> Cursor<'a> {
        Cursor { data, pos: 0 }
    }
    pub fn remaining(&self) -> usize {
        self.data.len() - self.pos
    }
    fn take(&mut self, n: usize) -> R<&'a [u8]> {
        if self.remaining() < n {
            return Err(ReadError::Corrupt(format!(
                "needed {n} bytes at offset {}, {} left",
                self.pos,
                self.remaining()
            )));
        }
        let s = &self.data[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }
    pub fn u8(&mut self) -> R<u8> {
        Ok(self.take(1)?[0])
    }
    pub fn u16(&mut self) -> R<u16> {
        Ok(u16::from_le_bytes(self.take(2)?.try_into().unwrap()))
    }
    pub fn u32(&mut self) -> R<u32> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().unwrap()))
    }
    pub fn u64(&mut self) -> R<u64> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().unwrap()))
    }
    pub fn f32(&mut self) -> R<f32> {
        Ok(f32::from_le_bytes(self.take(4)?.try_into().unwrap()))
    }
    pub fn vec3(&mut self) -> R<Vec3> {
        Ok(Vec3::new(self.f32()?, self.f32()?, self.f32()?))
    }
    pub fn quat(&mut self) -> R<Quat> {
        Ok(Quat::from_xyzw(self.f32()?, self.f32()?, self.f32()?, self.f32()?))
    }
    pub fn half3(&mut self) -> R<Vec3> {
        Ok(Vec3::new(
            f16_to_f32(self.u16()?),
            f16_to_f32(self.u16()?),
            f16_to_f32(self.u16()?),
        ))
    }
    pub fn packed_quat(&mut self) -> R<Quat> {
        Ok(unpack_quat(self.take(6)?.try_into().unwrap()))
    }
    pub fn varint(&mut self) -> R<u32> {
        let mut v: u64 = 0;
        for shift in (0..35).step_by(7) {
            let b = self.u8()?;
            v |= ((b & 0x7f) as u64) << shift;
            if b & 0x80 == 0 {
                return u32::try_from(v).map_err(|_| ReadError::Corrupt("varint overflows u32".into()));
            }
        }
        Err(ReadError::Corrupt("varint longer than 5 bytes".into()))
    }
    /// A count of items of at least `min_size` bytes each, checked against what is left.
    fn count(&mut self, min_size: usize) -> R<usize> {
        let n = self.u32()? as usize;
        if n.saturating_mul(min_size) > self.remaining() {
            return Err(ReadError::Corrupt(format!("count {n} does not fit in the chunk")));
        }
        Ok(n)
    }
}

/// A shape's geometry in its body's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShapeRecord {
    Sphere {
        center: Vec3,
        radius: f32,
    },
    Box {
        center: Vec3,
        rotation: Quat,
        half_extents: Vec3,
    },
    Capsule {
        a: Vec3,
        b: Vec3,
        radius: f32,
    },
    Plane {
        normal: Vec3,
        offset: f32,
    },
}

#[derive(Clone, Debug, PartialEq)]
pub struct BodyDefRecord {
    pub index: u32,
    pub generation: u32,
    /// `BODY_STATIC`, `BODY_KINEMATIC` or `BODY_DYNAMIC`.
    pub body_type: u8,
    pub user_data: u64,
    pub pose: Transform,
    pub shapes: Vec<ShapeRecord>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct SoftDefRecord {
    pub index: u32,
    pub generation: u32,
    pub user_data: u64,
    pub vertex_radius: f32,
    pub vertex_count: u32,
    pub triangles: Vec<[u32; 3]>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum DefRecord {
    Body(BodyDefRecord),
    BodyRemoved(u32),
    Soft(SoftDefRecord),
    SoftRemoved(u32),
}

/// A body's state in a frame (only bodies whose pose or sleep state changed are written).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyRecord {
    pub index: u32,
    pub awake: bool,
    pub pose: Transform,
    pub linear_velocity: Vec3,
    pub angular_velocity: Vec3,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointRecord {
    pub index: u32,
    pub kind: u8,
    pub broken: bool,
    /// Body slot indices; `NO_BODY` for the world.
    pub body_a: u32,
    pub body_b: u32,
    pub anchor_a: Vec3,
    pub anchor_b: Vec3,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactPointRecord {
    pub point: Vec3,
    pub separation: f32,
    pub normal_impulse: f32,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ManifoldRecord {
    pub body_a: u32,
    pub body_b: u32,
    pub normal: Vec3,
    pub points: Vec<ContactPointRecord>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct SoftFrame {
    pub index: u32,
    pub positions: Vec<Vec3>,
}

/// Counters of a step, in the order of the format.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    pub bodies: u32,
    pub awake_bodies: u32,
    pub contacts: u32,
    pub touching_contacts: u32,
    pub pairs_tested: u32,
    pub proxies_moved: u32,
    pub particles: u32,
    pub soft_bodies: u32,
    pub joints: u32,
    pub tree_height: u32,
}

/// One `STEP` chunk, with the `DEFS` records written just before it.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// 0 for the state when recording started, then the steps recorded so far.
    pub step: u32,
    pub dt: f32,
    pub time: f32,
    pub step_seconds: f32,
    pub counters: Counters,
    pub defs: Vec<DefRecord>,
    pub bodies: Vec<BodyRecord>,
    pub particles: Vec<(Vec3, f32)>,
    pub soft_bodies: Vec<SoftFrame>,
    pub joints: Vec<JointRecord>,
    pub contacts: Vec<ManifoldRecord>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Recording {
    pub version: u32,
    pub flags: u32,
    pub gravity: Vec3,
    pub substeps: u32,
    pub frames: Vec<Frame>,
    /// Bytes at the end did not form a whole chunk (the recording was cut short).
    pub truncated: bool,
}

/// A body's definition and latest state while replaying.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyState {
    pub def: BodyDefRecord,
    pub record: Option<BodyRecord>,
}

impl BodyState {
    pub fn pose(&self) -> Transform {
        self.record.map_or(self.def.pose, |r| r.pose)
    }
}

impl Recording {
    /// Every body alive at `frame`, by slot index, with its latest record.
    pub fn bodies_at(&self, frame: usize) -> std::collections::BTreeMap<u32, BodyState> {
        let mut state = std::collections::BTreeMap::new();
        for f in &self.frames[..=frame] {
            for d in &f.defs {
                match d {
                    DefRecord::Body(b) => {
                        state.insert(
                            b.index,
                            BodyState {
                                def: b.clone(),
                                record: None,
                            },
                        );
                    }
                    DefRecord::BodyRemoved(i) => {
                        state.remove(i);
                    }
                    _ => {}
                }
            }
            for r in &f.bodies {
                if let Some(s) = state.get_mut(&r.index) {
                    s.record = Some(*r);
                }
            }
        }
        state
    }
}

fn shape(c: &mut Cursor) -> R<ShapeRecord> {
    Ok(match c.u8()? {
        SHAPE_SPHERE => ShapeRecord::Sphere {
            center: c.vec3()?,
            radius: c.f32()?,
        },
        SHAPE_BOX => ShapeRecord::Box {
            center: c.vec3()?,
            rotation: c.quat()?,
            half_extents: c.vec3()?,
        },
        SHAPE_CAPSULE => ShapeRecord::Capsule {
            a: c.vec3()?,
            b: c.vec3()?,
            radius: c.f32()?,
        },
        SHAPE_PLANE => ShapeRecord::Plane {
            normal: c.vec3()?,
            offset: c.f32()?,
        },
        k => return Err(ReadError::Corrupt(format!("unknown shape kind {k}"))),
    })
}

fn defs(c: &mut Cursor, out: &mut Vec<DefRecord>) -> R<()> {
    while c.remaining() > 0 {
        let rec = match c.u8()? {
            DEF_BODY => {
                let index = c.u32()?;
                let generation = c.u32()?;
                let body_type = c.u8()?;
                let user_data = c.u64()?;
                let pose = Transform::new(c.vec3()?, c.quat()?);
                let n = c.count(17)?;
                let shapes = (0..n).map(|_| shape(c)).collect::<R<Vec<_>>>()?;
                DefRecord::Body(BodyDefRecord {
                    index,
                    generation,
                    body_type,
                    user_data,
                    pose,
                    shapes,
                })
            }
            DEF_BODY_REMOVED => DefRecord::BodyRemoved(c.u32()?),
            DEF_SOFT => {
                let index = c.u32()?;
                let generation = c.u32()?;
                let user_data = c.u64()?;
                let vertex_radius = c.f32()?;
                let vertex_count = c.u32()?;
                let n = c.count(12)?;
                let mut triangles = Vec::with_capacity(n);
                for _ in 0..n {
                    triangles.push([c.u32()?, c.u32()?, c.u32()?]);
                }
                DefRecord::Soft(SoftDefRecord {
                    index,
                    generation,
                    user_data,
                    vertex_radius,
                    vertex_count,
                    triangles,
                })
            }
            DEF_SOFT_REMOVED => DefRecord::SoftRemoved(c.u32()?),
            k => return Err(ReadError::Corrupt(format!("unknown definition record {k}"))),
        };
        out.push(rec);
    }
    Ok(())
}

fn step(c: &mut Cursor, defs: Vec<DefRecord>) -> R<Frame> {
    let step = c.u32()?;
    let dt = c.f32()?;
    let time = c.f32()?;
    let step_seconds = c.f32()?;
    let mut k = [0u32; STEP_COUNTERS];
    for v in &mut k {
        *v = c.u32()?;
    }
    let counters = Counters {
        bodies: k[0],
        awake_bodies: k[1],
        contacts: k[2],
        touching_contacts: k[3],
        pairs_tested: k[4],
        proxies_moved: k[5],
        particles: k[6],
        soft_bodies: k[7],
        joints: k[8],
        tree_height: k[9],
    };
    let n = c.count(31)?;
    let mut bodies = Vec::with_capacity(n);
    let mut index: i64 = -1;
    for _ in 0..n {
        let v = c.varint()?;
        index += (v >> 1) as i64;
        bodies.push(BodyRecord {
            index: index as u32,
            awake: v & 1 == 1,
            pose: Transform::new(c.vec3()?, c.packed_quat()?),
            linear_velocity: c.half3()?,
            angular_velocity: c.half3()?,
        });
    }
    let n = c.count(14)?;
    let mut positions = Vec::with_capacity(n);
    for _ in 0..n {
        positions.push(c.vec3()?);
    }
    let mut particles = Vec::with_capacity(n);
    for p in positions {
        particles.push((p, f16_to_f32(c.u16()?)));
    }
    let n = c.count(8)?;
    let mut soft_bodies = Vec::with_capacity(n);
    for _ in 0..n {
        let index = c.u32()?;
        let m = c.count(12)?;
        let positions = (0..m).map(|_| c.vec3()).collect::<R<Vec<_>>>()?;
        soft_bodies.push(SoftFrame { index, positions });
    }
    let n = c.count(38)?;
    let mut joints = Vec::with_capacity(n);
    for _ in 0..n {
        joints.push(JointRecord {
            index: c.u32()?,
            kind: c.u8()?,
            broken: c.u8()? != 0,
            body_a: c.u32()?,
            body_b: c.u32()?,
            anchor_a: c.vec3()?,
            anchor_b: c.vec3()?,
        });
    }
    let n = c.count(21)?;
    let mut contacts = Vec::with_capacity(n);
    for _ in 0..n {
        let body_a = c.u32()?;
        let body_b = c.u32()?;
        let normal = c.vec3()?;
        let m = c.u8()? as usize;
        let mut points = Vec::with_capacity(m);
        for _ in 0..m {
            points.push(ContactPointRecord {
                point: c.vec3()?,
                separation: c.f32()?,
                normal_impulse: c.f32()?,
            });
        }
        contacts.push(ManifoldRecord {
            body_a,
            body_b,
            normal,
            points,
        });
    }
    Ok(Frame {
        step,
        dt,
        time,
        step_seconds,
        counters,
        defs,
        bodies,
        particles,
        soft_bodies,
        joints,
        contacts,
    })
}

/// Parses a whole recording (or the whole steps of a truncated one).
pub fn parse(bytes: &[u8]) -> Result<Recording, ReadError> {
    if bytes.len() < HEADER_LEN || bytes[..8] != MAGIC {
        return Err(ReadError::BadMagic);
    }
    let mut c = Cursor::new(bytes);
    c.take(8)?;
    let version = c.u32()?;
    if version != VERSION {
        return Err(ReadError::UnsupportedVersion(version));
    }
    let flags = c.u32()?;
    let mut rec = Recording {
        version,
        flags,
        gravity: Vec3::ZERO,
        substeps: 0,
        frames: Vec::new(),
        truncated: false,
    };
    let mut pending = Vec::new();
    while c.remaining() > 0 {
        if c.remaining() < CHUNK_HEADER_LEN {
            rec.truncated = true;
            break;
        }
        let tag: [u8; 4] = c.take(4)?.try_into().unwrap();
        let len = c.u32()? as usize;
        if len > c.remaining() {
            rec.truncated = true;
            break;
        }
        let mut body = Cursor::new(c.take(len)?);
        match tag {
            TAG_WORLD => {
                rec.gravity = body.vec3()?;
                rec.substeps = body.u32()?;
            }
            TAG_DEFS => defs(&mut body, &mut pending)?,
            TAG_STEP => {
                let frame = step(&mut body, std::mem::take(&mut pending))?;
                rec.frames.push(frame);
            }
            _ => {} // a chunk kind from a newer minor version: skipped by its length
        }
    }
    Ok(rec)
}

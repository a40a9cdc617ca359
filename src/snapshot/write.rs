//! Saving: the frame (magic, version, payload length, checksum) and the world's sections.

use super::{checksum64, Snap, Writer, HEADER_LEN, MAGIC, VERSION};
use crate::collision::broad_phase::BroadPhase;
use crate::collision::shape::Shape;
use crate::pool::Pool;
use crate::world::World;

/// Section ids, in the order they are written and read.
pub(crate) mod section {
    pub const SETTINGS: u32 = 1;
    pub const GEOMETRY: u32 = 2;
    pub const BODIES: u32 = 3;
    pub const SHAPES: u32 = 4;
    pub const CONTACTS: u32 = 5;
    pub const BROAD_PHASE: u32 = 6;
    pub const SLEEP: u32 = 7;
    pub const GENERATORS: u32 = 8;
    pub const PARTICLES: u32 = 9;
    pub const JOINTS: u32 = 10;
    pub const SOFT_BODIES: u32 = 11;
    pub const EVENTS: u32 = 12;
}

/// Section names: the columns of section `id` are under `NAMES[id - 1]`.
pub(crate) const NAMES: [&str; 12] = [
    "settings",
    "geometry",
    "bodies",
    "shapes",
    "contacts",
    "broad_phase",
    "sleep",
    "generators",
    "particles",
    "joints",
    "soft_bodies",
    "events",
];

/// Writes one section into its column: its id, then its content.
fn put_section(w: &mut Writer, id: u32, body: impl Fn(&mut Writer)) {
    w.within(NAMES[id as usize - 1], |w| {
        id.put(w);
        body(w);
    });
}

/// Writes the payload: every field of the world that affects its future. The destructuring
/// lists every field of `World`, so a new one fails to compile until it is stored here or
/// named as rebuilt.
fn put_world(world: &World, w: &mut Writer) {
    let World {
        settings,
        bodies,
        shapes,
        contacts,
        broad,
        awake_bodies,
        awake_contacts,
        islands,
        counters,
        generators,
        particles,
        joints,
        soft_bodies,
        geometry,
        events,
        // Rebuilt on restore (scratch every step rewrites before reading it) or not the
        // world's state (its tag is the target world's own).
        solver: _,
        generated_contacts: _,
        scratch_wake: _,
        island_scratch: _,
        generator_scratch: _,
        body_springs: _,
        tag: _,
        // The world's own threads or the host's job system: not state (results are the same
        // at every worker count); a restored world keeps its own.
        tasks: _,
        narrow_results: _,
        body_marks: _,
    } = world;
    use section::*;
    put_section(w, SETTINGS, |w| settings.put(w));
    put_section(w, GEOMETRY, |w| geometry.put(w));
    put_section(w, BODIES, |w| {
        bodies.put(w);
        w.within("rebuilt", |w| super::predicted::put_bodies(w, bodies));
    });
    put_section(w, SHAPES, |w| {
        shapes.put(w);
        w.within("rebuilt", |w| super::predicted::put_shapes(w, shapes, bodies, geometry));
    });
    put_section(w, CONTACTS, |w| {
        contacts.put(w);
        w.within("awake", |w| awake_contacts.put(w));
    });
    put_section(w, BROAD_PHASE, |w| put_broad_phase(w, broad, shapes));
    put_section(w, SLEEP, |w| {
        w.within("awake", |w| awake_bodies.put(w));
        // Stored as member lists (the world links them through `Body::island_next`).
        let members = islands.map(|&first| {
            let mut m = vec![first];
            while let Some(&b) = m.last() {
                let next = bodies.at(b).island_next;
                if next == crate::dynamics::body::NONE {
                    break;
                }
                m.push(next);
            }
            m
        });
        w.within("islands", |w| members.put(w));
        w.within("counters", |w| counters.put(w));
    });
    put_section(w, GENERATORS, |w| generators.put(w));
    put_section(w, PARTICLES, |w| particles.put(w));
    put_section(w, JOINTS, |w| joints.put(w));
    put_section(w, SOFT_BODIES, |w| soft_bodies.put(w));
    // End events of contacts destroyed since the last step, reported with the next step's.
    put_section(w, EVENTS, |w| {
        w.within("contact_end", |w| events.pending_contact_end.put(w));
        w.within("sensor_end", |w| events.pending_sensor_end.put(w));
    });
}

/// The broad phase: the tree (leaf boxes predicted from the shapes' fat boxes), the move
/// buffer, the planes list and the pair map; not the candidate pairs (scratch every step
/// rewrites before reading).
fn put_broad_phase(w: &mut Writer, broad: &BroadPhase, shapes: &Pool<Shape>) {
    let BroadPhase {
        tree,
        move_buffer,
        planes,
        pairs,
        candidates: _,
        chunk_candidates: _,
    } = broad;
    w.within("tree", |w| tree.put_snapshot(w, |s| leaf_box(shapes, s)));
    w.within("move_buffer", |w| move_buffer.put(w));
    w.within("planes", |w| planes.put(w));
    w.within("pairs", |w| pairs.put(w));
}

/// The box a tree leaf of shape slot `s` has: the shape's fat box.
pub(crate) fn leaf_box(shapes: &Pool<Shape>, s: u32) -> Option<crate::collision::aabb::Aabb> {
    shapes.handle_at(s).map(|_| shapes.at(s).fat_aabb)
}

/// zstd's level 1: the byte planes' runs are long, so a slower level gains little size
/// (level 3 saves 5 % of the settled pile's snapshot and costs 50 % more time).
pub(crate) const ZSTD_LEVEL: i32 = 1;

/// `data` compressed with zstd at `ZSTD_LEVEL` (one frame, RFC 8878), appended to `out`.
/// The compression context and its scratch are kept per thread, so a save allocates them
/// once per thread, not once per save.
pub(crate) fn compress_into(data: &[u8], out: &mut Vec<u8>) {
    thread_local! {
        static CODEC: std::cell::RefCell<Option<(zstd::bulk::Compressor<'static>, Vec<u8>)>> =
            const { std::cell::RefCell::new(None) };
    }
    CODEC.with(|c| {
        let mut c = c.borrow_mut();
        if c.is_none() {
            let z = zstd::bulk::Compressor::new(ZSTD_LEVEL).expect("zstd accepts level 1");
            *c = Some((z, Vec::new()));
        }
        let (z, scratch) = c.as_mut().expect("made above");
        scratch.clear();
        scratch.reserve(zstd::zstd_safe::compress_bound(data.len()));
        // With room for the bound, compression cannot run out of space; allocation failure
        // aborts as every other allocation does.
        z.compress_to_buffer(data, scratch)
            .expect("zstd writes within its bound");
        out.extend_from_slice(scratch);
    });
}

/// Size in bytes of the snapshot `save` would write now (it is saved to know: the
/// compressed size depends on every byte).
pub fn saved_size(world: &World) -> usize {
    let mut out = Vec::new();
    save(world, &mut out);
    out.len()
}

/// The payload's columns (path, bytes, bytes compressed alone) of the world's snapshot now,
/// for size reports.
pub fn column_sizes(world: &World) -> Vec<(String, usize, usize)> {
    let mut w = Writer::new();
    put_world(world, &mut w);
    w.column_sizes()
}

/// Writes the world's snapshot into `out` (cleared first): the frame, then the payload:
/// its length before compression (`u64`) and its columns compressed with zstd (one frame).
pub fn save(world: &World, out: &mut Vec<u8>) {
    // The writer's columns and the payload before compression are kept per thread: for a
    // world about the size of the last one they are neither allocated nor zeroed again. (A
    // save still makes a few smaller allocations: the islands' member lists, the sorted
    // keys of the pair map, the tree's predicted parents.)
    thread_local! {
        static SCRATCH: std::cell::RefCell<(Writer, Vec<u8>)> =
            std::cell::RefCell::new((Writer::new(), Vec::new()));
    }
    SCRATCH.with(|s| {
        let (w, raw) = &mut *s.borrow_mut();
        w.clear();
        put_world(world, w);
        w.finish(raw);
        out.clear();
        out.extend_from_slice(&MAGIC);
        out.extend_from_slice(&VERSION.to_le_bytes());
        out.extend_from_slice(&[0; 16]);
        out.extend_from_slice(&(raw.len() as u64).to_le_bytes());
        compress_into(raw, out);
    });
    let len = out.len() - HEADER_LEN;
    let sum = checksum64(&out[HEADER_LEN..]);
    out[12..20].copy_from_slice(&(len as u64).to_le_bytes());
    out[20..28].copy_from_slice(&sum.to_le_bytes());
}

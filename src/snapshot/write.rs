//! Saving: the frame (magic, version, payload length, checksum) and the world's sections.

use super::{fnv1a64, Snap, Writer, HEADER_LEN, MAGIC, VERSION};
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

/// Writes one section: its id, its length, then its bytes (the length patched in after).
fn put_section(w: &mut Writer, id: u32, body: impl Fn(&mut Writer)) {
    id.put(w);
    let at = w.len();
    0u64.put(w);
    body(w);
    let len = (w.len() - at - 8) as u64;
    w.patch(at, &len.to_le_bytes());
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
    } = world;
    use section::*;
    put_section(w, SETTINGS, |w| settings.put(w));
    put_section(w, GEOMETRY, |w| geometry.put(w));
    put_section(w, BODIES, |w| bodies.put(w));
    put_section(w, SHAPES, |w| shapes.put(w));
    put_section(w, CONTACTS, |w| {
        contacts.put(w);
        awake_contacts.put(w);
    });
    put_section(w, BROAD_PHASE, |w| broad.put(w));
    put_section(w, SLEEP, |w| {
        awake_bodies.put(w);
        islands.put(w);
        counters.put(w);
    });
    put_section(w, GENERATORS, |w| generators.put(w));
    put_section(w, PARTICLES, |w| particles.put(w));
    put_section(w, JOINTS, |w| joints.put(w));
    put_section(w, SOFT_BODIES, |w| soft_bodies.put(w));
    // End events of contacts destroyed since the last step, reported with the next step's.
    put_section(w, EVENTS, |w| {
        events.pending_contact_end.put(w);
        events.pending_sensor_end.put(w);
    });
}

/// Size in bytes of the snapshot `save` would write now.
pub fn saved_size(world: &World) -> usize {
    let mut w = Writer::counter();
    put_world(world, &mut w);
    HEADER_LEN + w.len()
}

/// Writes the world's snapshot into `out` (cleared first; a buffer reused from the last save
/// has its capacity already, so no counting pass is made to reserve it).
pub fn save(world: &World, out: &mut Vec<u8>) {
    out.clear();
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&[0; 16]);
    let mut w = Writer::new(out);
    put_world(world, &mut w);
    let len = out.len() - HEADER_LEN;
    let sum = fnv1a64(&out[HEADER_LEN..]);
    out[12..20].copy_from_slice(&(len as u64).to_le_bytes());
    out[20..28].copy_from_slice(&sum.to_le_bytes());
}

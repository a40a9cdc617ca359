//! Restoring: check the frame, decode every section into a new world state, and only then
//! swap it into the target world, so a failing restore leaves the world as it was.

use super::write::{section, NAMES};
use super::{bad, checksum64, ReadResult, Reader, Snap, SnapshotError, HEADER_LEN, MAGIC, VERSION};
use crate::generators::GeneratorDef;
use crate::world::{World, WorldSettings};

/// Reads the section `id`, which must come next, with `body`.
fn get_section<'a, T>(
    r: &mut Reader<'a>,
    id: u32,
    body: impl FnOnce(&mut Reader<'a>) -> ReadResult<T>,
) -> ReadResult<T> {
    r.within(NAMES[id as usize - 1], |r| {
        let got = u32::get(r)?;
        if got != id {
            return bad(format!("snapshot corrupted: section {got} where section {id} belongs"));
        }
        body(r)
    })
}

/// Checks magic, version, length and checksum; returns the payload.
fn payload(bytes: &[u8]) -> ReadResult<&[u8]> {
    if bytes.len() < HEADER_LEN {
        return bad(format!(
            "snapshot truncated: {} bytes, shorter than its {HEADER_LEN}-byte header",
            bytes.len()
        ));
    }
    if bytes[..8] != MAGIC {
        return bad("not a Hearth snapshot (magic bytes differ)");
    }
    let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
    if version != VERSION {
        return bad(format!(
            "snapshot format version {version} is not supported (this library reads version {VERSION})"
        ));
    }
    let len = u64::from_le_bytes(bytes[12..20].try_into().expect("8 bytes"));
    let sum = u64::from_le_bytes(bytes[20..28].try_into().expect("8 bytes"));
    let payload = &bytes[HEADER_LEN..];
    if len != payload.len() as u64 {
        return bad(format!(
            "snapshot truncated or padded: header says {len} payload bytes, buffer holds {}",
            payload.len()
        ));
    }
    if checksum64(payload) != sum {
        return bad("snapshot corrupted: checksum mismatch");
    }
    Ok(payload)
}

/// The payload's columns: its length before compression (`u64`) and one zstd frame, which
/// must decompress to exactly that length. The length is checked against zstd's largest
/// ratio (a 128 KiB block from a 4-byte RLE block) before anything is allocated, so a
/// corrupted length cannot ask for a huge buffer.
fn decompress(payload: &[u8], z: &mut zstd::bulk::Decompressor<'static>, raw: &mut Vec<u8>) -> ReadResult<()> {
    if payload.len() < 8 {
        return bad("snapshot corrupted: payload shorter than its length field");
    }
    let raw_len = u64::from_le_bytes(payload[..8].try_into().expect("8 bytes"));
    let stream = &payload[8..];
    if raw_len > 32 * 1024 * stream.len() as u64 {
        return bad(format!(
            "snapshot corrupted: {raw_len} bytes cannot come from a {}-byte stream",
            stream.len()
        ));
    }
    raw.clear();
    raw.reserve(raw_len as usize);
    match z.decompress_to_buffer(stream, raw) {
        Ok(n) if n as u64 == raw_len => Ok(()),
        _ => bad("snapshot corrupted: its compressed columns do not decompress to their length"),
    }
}

/// What a restore reuses from the last one on the same thread: the zstd context, the
/// payload before compression and its columns without byte planes.
struct Scratch {
    zstd: zstd::bulk::Decompressor<'static>,
    raw: Vec<u8>,
    plain: Vec<u8>,
    /// The replaced bodies' shape and contact lists, emptied, for the next restore to fill
    /// (at most `SPARE` of them).
    spare: Spare,
}

/// Emptied vectors of ids and of indices a restore keeps for the next one.
pub(crate) type Spare = (Vec<Vec<crate::pool::Handle>>, Vec<Vec<u32>>);

/// Emptied vectors of each kind a restore keeps for the next one, at most.
const SPARE: usize = 1 << 16;

/// Keeps `v`'s buffer in `spare`, emptied, when it has one and there is room.
fn keep<T>(spare: &mut Vec<Vec<T>>, v: &mut Vec<T>) {
    if v.capacity() > 0 && spare.len() < SPARE {
        v.clear();
        spare.push(std::mem::take(v));
    }
}

/// Restores `world` from `bytes` (see the module docs of `snapshot`). On error the world is
/// unchanged.
pub fn restore(world: &mut World, bytes: &[u8]) -> Result<(), SnapshotError> {
    thread_local! {
        static SCRATCH: std::cell::RefCell<Option<Scratch>> = const { std::cell::RefCell::new(None) };
    }
    let payload = payload(bytes)?;
    SCRATCH.with(|s| {
        let mut s = s.borrow_mut();
        if s.is_none() {
            *s = Some(Scratch {
                zstd: zstd::bulk::Decompressor::new().expect("a zstd context"),
                raw: Vec::new(),
                plain: Vec::new(),
                spare: Default::default(),
            });
        }
        let Scratch {
            zstd,
            raw,
            plain,
            spare,
        } = s.as_mut().expect("made above");
        decompress(payload, zstd, raw)?;
        let spans = super::columns::unpack(raw, plain)?;
        decode(world, plain, &spans, spare)
    })
}

/// Decodes the columns `plain` (with their `spans`) into a new world state and swaps it
/// into `world`.
fn decode(world: &mut World, plain: &[u8], spans: &[(usize, usize)], spare: &mut Spare) -> Result<(), SnapshotError> {
    let mut r = Reader::new(plain, spans, world.tag());
    r.spare = std::mem::take(spare);
    let result = decode_with(world, &mut r);
    *spare = std::mem::take(&mut r.spare);
    // The replaced bodies' lists are kept for the next restore to fill.
    let mut old = result?;
    for b in old.values_mut() {
        keep(&mut spare.0, &mut b.shapes);
        keep(&mut spare.1, &mut b.contacts);
    }
    Ok(())
}

/// `decode` with its reader; returns the body pool it replaced.
fn decode_with(
    world: &mut World,
    r: &mut Reader,
) -> Result<crate::pool::Pool<crate::dynamics::body::Body>, SnapshotError> {
    use section::*;
    let mut settings: WorldSettings = get_section(r, SETTINGS, Snap::get)?;
    // Threads are the target world's own: results do not depend on them.
    settings.worker_count = world.settings.worker_count;
    settings
        .validate()
        .map_err(|e| SnapshotError(format!("snapshot corrupted: its world settings are invalid: {e}")))?;
    let geometry = get_section(r, GEOMETRY, Snap::get)?;
    let bodies = get_section(r, BODIES, |r| {
        let mut bodies = Snap::get(r)?;
        r.within("rebuilt", |r| super::predicted::get_bodies(r, &mut bodies))?;
        Ok(bodies)
    })?;
    let shapes = get_section(r, SHAPES, |r| {
        let mut shapes = Snap::get(r)?;
        r.within("rebuilt", |r| {
            super::predicted::get_shapes(r, &mut shapes, &bodies, &geometry)
        })?;
        Ok(shapes)
    })?;
    let (contacts, awake_contacts): (_, Vec<u32>) =
        get_section(r, CONTACTS, |r| Ok((Snap::get(r)?, r.within("awake", Snap::get)?)))?;
    let broad = get_section(r, BROAD_PHASE, |r| {
        Ok(crate::collision::broad_phase::BroadPhase {
            tree: r.within("tree", |r| {
                crate::collision::dynamic_tree::DynamicTree::get_snapshot(r, |s| super::write::leaf_box(&shapes, s))
            })?,
            move_buffer: r.within("move_buffer", Snap::get)?,
            planes: r.within("planes", Snap::get)?,
            pairs: r.within("pairs", Snap::get)?,
            candidates: Vec::new(),
            chunk_candidates: Vec::new(),
        })
    })?;
    let (awake_bodies, islands, counters): (Vec<u32>, crate::pool::Pool<Vec<u32>>, _) = get_section(r, SLEEP, |r| {
        Ok((
            r.within("awake", Snap::get)?,
            r.within("islands", Snap::get)?,
            r.within("counters", Snap::get)?,
        ))
    })?;
    let mut generators: crate::pool::Pool<crate::generators::Generator> = get_section(r, GENERATORS, Snap::get)?;
    let particles = get_section(r, PARTICLES, Snap::get)?;
    let joints = get_section(r, JOINTS, Snap::get)?;
    let soft_bodies = get_section(r, SOFT_BODIES, Snap::get)?;
    let (pending_contact_end, pending_sensor_end) = get_section(r, EVENTS, |r| {
        Ok((r.within("contact_end", Snap::get)?, r.within("sensor_end", Snap::get)?))
    })?;
    r.finish()?;

    super::check::check(&super::check::Decoded {
        geometry: &geometry,
        bodies: &bodies,
        shapes: &shapes,
        contacts: &contacts,
        awake_contacts: &awake_contacts,
        broad: &broad,
        awake_bodies: &awake_bodies,
        islands: &islands,
        generators: &generators,
        particles: &particles,
        joints: &joints,
        soft_bodies: &soft_bodies,
    })?;

    // User generators: keep the callback the target world's generator of the same id and
    // kind has now; others stay without one until the host sets it.
    let keys: Vec<_> = generators.iter().map(|(h, _)| h).collect();
    for h in keys {
        let old = world.generators.get(h).map(|g| g.def);
        let g = generators.get_mut(h).expect("listed");
        match (&mut g.def, old) {
            (
                GeneratorDef::ExternalForce { callback, user_data },
                Some(GeneratorDef::ExternalForce {
                    callback: c,
                    user_data: u,
                }),
            ) => {
                *callback = c;
                *user_data = u;
            }
            (
                GeneratorDef::ExternalContact {
                    callback,
                    user_data,
                    capacity,
                },
                Some(GeneratorDef::ExternalContact {
                    callback: c,
                    user_data: u,
                    capacity: k,
                }),
            ) if *capacity == k => {
                *callback = c;
                *user_data = u;
            }
            _ => {}
        }
    }

    // Everything decoded: swap in. Scratch keeps its capacity (every step rewrites it before
    // reading); the contact batches follow the restored lane width.
    let lanes_changed = world.settings.lane_width != settings.lane_width;
    world.settings = settings;
    world.geometry = geometry;
    let old_bodies = std::mem::replace(&mut world.bodies, bodies);
    world.shapes = shapes;
    world.contacts = contacts;
    world.awake_contacts = awake_contacts;
    world.broad = broad;
    world.awake_bodies = awake_bodies;
    world.islands = islands.map(|m| m[0]);
    for b in world.bodies.values_mut() {
        b.island_next = crate::dynamics::body::NONE;
    }
    for (_, m) in islands.iter() {
        for k in 1..m.len() {
            world.bodies.at_mut(m[k - 1]).island_next = m[k];
        }
    }
    world.counters = counters;
    world.generators = generators;
    world.particles = particles;
    world.joints = joints;
    world.soft_bodies = soft_bodies;
    world.generated_contacts.clear();
    // The last step's events belonged to the state replaced; ends still owed come along.
    world.events = crate::events::Events::default();
    world.events.pending_contact_end = pending_contact_end;
    world.events.pending_sensor_end = pending_sensor_end;
    if lanes_changed {
        world.solver.batches = crate::dynamics::contact_wide::Batches::new(settings.lane_width);
    }
    Ok(old_bodies)
}

//! Snapshot exports: save a world to bytes in a caller-owned buffer and restore it, for
//! rollback netcode and replays. The core is `snapshot/`; the format is
//! `docs/snapshot-format.md`.

use super::callback::{HearthUserContactGeneratorDef, HearthUserForceGeneratorDef};
use super::error::*;
use super::generator::HearthGeneratorId;
use super::validate;
use super::world::{world_mut, world_ref, HearthWorld};
use crate::generators::GeneratorDef;

/// The world, for a snapshot's read: refused while the world steps (a callback), when the
/// state is mid-step.
///
/// # Safety
/// `ptr` must be NULL or a live world.
unsafe fn idle_world<'a>(ptr: *const HearthWorld) -> Result<&'a crate::world::World, Failure> {
    let w = ptr.as_ref().ok_or_else(|| Failure::null("world"))?;
    if w.locked.get() {
        return Err(Failure::new(
            HEARTH_ERROR_WORLD_LOCKED,
            "the world is locked: it is stepping (snapshots are taken between steps)",
        ));
    }
    Ok(&*w.world.get())
}

/// Writes the size in bytes of the snapshot `hearth_world_snapshot_save` would write now
/// to `*out_size`. The size changes as the world changes (bodies, contacts, particles).
/// The snapshot is compressed, so its size depends on every byte: this runs a whole save
/// (into a scratch buffer) and costs as much as `hearth_world_snapshot_save`. A host that
/// saves often can instead keep a buffer with room to spare and call the save directly: when
/// the buffer is too small, the save fails with `HEARTH_ERROR_BUFFER_TOO_SMALL` and writes
/// the size needed.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (`world`, `out_size`), `HEARTH_ERROR_WORLD_LOCKED`
/// (called from a callback during a step).
///
/// # Safety
/// `world` must be NULL or a live world; `out_size` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_snapshot_size(world: *const HearthWorld, out_size: *mut usize) -> HearthResult {
    guard(|| {
        let w = idle_world(world)?;
        let out = validate::output(out_size, "out_size")?;
        *out = w.snapshot_size();
        Ok(())
    })
}

/// Saves everything about the world that affects its future into `buffer` (caller-owned,
/// `capacity` bytes) and writes the number of bytes used to `*out_written`: world
/// settings, bodies, shapes, shared geometry, contacts with their warm-start impulses,
/// broad-phase tree, sleep state, joints, generators, particles and soft bodies, with every
/// id's slot and reuse counter. Not saved: user generator callbacks and their user data,
/// and an active recording. Restoring the bytes with `hearth_world_snapshot_restore` and
/// stepping reproduces the original bit for bit. The format (`docs/snapshot-format.md`) is
/// versioned and checksummed.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (`world`, `out_written`, or `buffer` with a
/// non-zero `capacity`), `HEARTH_ERROR_BUFFER_TOO_SMALL` (`capacity` below the snapshot's
/// size; then nothing is written to `buffer` and the size needed is written to
/// `*out_written`), `HEARTH_ERROR_WORLD_LOCKED` (called from a callback during a step).
///
/// # Safety
/// `world` must be NULL or a live world; `buffer` NULL or writable for `capacity` bytes;
/// `out_written` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_snapshot_save(
    world: *const HearthWorld,
    buffer: *mut u8,
    capacity: usize,
    out_written: *mut usize,
) -> HearthResult {
    guard(|| {
        let w = idle_world(world)?;
        let out = validate::output(out_written, "out_written")?;
        let mut bytes = Vec::new();
        w.save_snapshot(&mut bytes);
        let needed = bytes.len();
        if capacity < needed {
            *out = needed;
            return Err(Failure::new(
                HEARTH_ERROR_BUFFER_TOO_SMALL,
                format!("buffer: capacity {capacity} bytes, the snapshot needs {needed} (written to out_written)"),
            ));
        }
        let buffer = validate::output(buffer, "buffer")?;
        std::ptr::copy_nonoverlapping(bytes.as_ptr(), buffer, bytes.len());
        *out = bytes.len();
        Ok(())
    })
}

/// Replaces the world's whole state with a snapshot from `hearth_world_snapshot_save` (of
/// this world or another, of this library's format version), world settings included.
/// The snapshot is checked and decoded in full before anything changes: on any error the
/// world is unchanged. Afterwards stepping reproduces the saved world bit for bit.
///
/// Ids keep their slot index and reuse counter. Restored into the world it was saved from,
/// every id the host kept from that world stays valid and ids created afterwards equal
/// those the original created after the same calls; restored into another world, ids carry
/// that world's tag in their generation's top 12 bits, with the same index and the same low
/// 20 bits.
///
/// User generators: restored into the world they were saved from, each keeps the callback
/// and user data its generator of the same id has now; any other user generator comes back
/// without a callback and is skipped by `hearth_world_step` until the host sets one with
/// `hearth_generator_set_user_force_callback` or `hearth_generator_set_user_contact_callback`
/// (list them with `hearth_world_get_user_generators_missing_callback`). An active recording is
/// not part of a snapshot: a restore neither stops nor restarts it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (`world`, or `buffer` with a non-zero `size`),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (not a Hearth snapshot, another format version,
/// truncated, or corrupted: checksum mismatch or inconsistent content; the message says
/// which), `HEARTH_ERROR_WORLD_LOCKED` (called from a callback during a step).
///
/// # Safety
/// `world` must be NULL or a live world; `buffer` NULL or readable for `size` bytes.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_snapshot_restore(
    world: *mut HearthWorld,
    buffer: *const u8,
    size: usize,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let bytes = if size == 0 {
            &[][..]
        } else {
            let p = validate::input(buffer, "buffer")?;
            std::slice::from_raw_parts(p, size)
        };
        w.restore_snapshot(bytes)
            .map_err(|e| Failure::invalid(format!("buffer: {}", e.0)))
    })
}

/// Lists the user generators that have no callback: those a restore brought into a world
/// that did not have them (`hearth_world_snapshot_restore`). They are skipped by
/// `hearth_world_step` until the host sets their callbacks with
/// `hearth_generator_set_user_force_callback` or `hearth_generator_set_user_contact_callback`
/// (`hearth_generator_get_type` tells which). Count-then-fill: `capacity` 0 only writes the
/// count to `*out_count`; otherwise `out_generators` (caller-owned) receives them in slot
/// order.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (`world`, `out_count`, or `out_generators` with a
/// non-zero `capacity`), `HEARTH_ERROR_BUFFER_TOO_SMALL` (`capacity` below the count;
/// nothing written).
///
/// # Safety
/// `world` must be NULL or a live world; `out_generators` NULL or writable for `capacity`
/// ids; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_user_generators_missing_callback(
    world: *const HearthWorld,
    out_generators: *mut HearthGeneratorId,
    capacity: usize,
    out_count: *mut usize,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let count = validate::output(out_count, "out_count")?;
        let n = w.user_generators_missing_callbacks().count();
        if let Some(out) = validate::counted_output(out_generators, capacity, n, "out_generators")? {
            for (o, h) in out.iter_mut().zip(w.user_generators_missing_callbacks()) {
                *o = h.into();
            }
        }
        *count = n;
        Ok(())
    })
}

/// Sets the callback and user data of a user force generator (the callback of `def`, from
/// `hearth_user_force_generator_def_default()`): after restoring a snapshot into a world that
/// did not have the generator, or to replace the callback.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (`world`, `def`, or a NULL callback),
/// `HEARTH_ERROR_INVALID_ID` (`generator`), `HEARTH_ERROR_INVALID_ARGUMENT` (`def` not from
/// its default, or `generator` not a user force generator), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid; the callback must stay callable while the generator
/// lives, and `user_data` valid for it.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_set_user_force_callback(
    world: *mut HearthWorld,
    generator: HearthGeneratorId,
    def: *const HearthUserForceGeneratorDef,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let d = validate::input(def, "def")?;
        validate::cookie(d.internal_value, "hearth_user_force_generator_def")?;
        let f = d.callback.ok_or_else(|| Failure::null("callback"))?;
        w.set_user_generator_callback(
            generator.into(),
            &GeneratorDef::ExternalForce {
                callback: f as usize,
                user_data: d.user_data as usize,
            },
        )?;
        Ok(())
    })
}

/// Sets the callback, user data and capacity of a user contact generator (from `def`, made
/// by `hearth_user_contact_generator_def_default()`): after restoring a snapshot into a world
/// that did not have the generator, or to replace the callback.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (`world`, `def`, or a NULL callback),
/// `HEARTH_ERROR_INVALID_ID` (`generator`), `HEARTH_ERROR_INVALID_ARGUMENT` (`def` not from
/// its default, capacity above 1048576, or `generator` not a user contact generator),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid; the callback must stay callable while the generator
/// lives, and `user_data` valid for it.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_set_user_contact_callback(
    world: *mut HearthWorld,
    generator: HearthGeneratorId,
    def: *const HearthUserContactGeneratorDef,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let d = validate::input(def, "def")?;
        validate::cookie(d.internal_value, "hearth_user_contact_generator_def")?;
        let f = d.callback.ok_or_else(|| Failure::null("callback"))?;
        w.set_user_generator_callback(
            generator.into(),
            &GeneratorDef::ExternalContact {
                callback: f as usize,
                user_data: d.user_data as usize,
                capacity: d.capacity,
            },
        )?;
        Ok(())
    })
}

//! The world state hash export.

use super::error::*;
use super::validate;
use super::world::{world_ref, HearthWorld};

/// Writes a 64-bit FNV-1a hash of the world's motion state to `*out_hash`: every live body in
/// id order (its id's slot index, position, rotation, linear and angular velocity, awake flag and sleep
/// timer), every live particle in storage order (slot index, position, velocity) and every live
/// soft body in id order (slot index, each vertex's position and velocity), floats by their bit patterns.
/// Two worlds stepped with the same calls have the same hash at any worker count, on four or
/// eight SIMD lanes. Contacts, warm-start impulses, pending forces and settings are not hashed (they show in
/// the motion a step later). Allowed from callbacks (a read).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world or out_hash NULL). `*out_hash` is written only
/// on success.
///
/// # Safety
/// `world` must be NULL or a live world; `out_hash` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_hash(world: *const HearthWorld, out_hash: *mut u64) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out_hash, "out_hash")?;
        *out = w.state_hash();
        Ok(())
    })
}

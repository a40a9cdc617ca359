//! User generators: force and contact generators written in C (callback types, defs,
//! creates), the contact sink their contacts go through, and the functions
//! `hearth_world_step` uses to run them between the core's stages (see `capi/world.rs` for
//! why that is sound and what a callback may call).

use std::os::raw::c_void;

use super::error::*;
use super::generator::{create, is_null_body, HearthGeneratorId};
use super::particle::HearthParticleId;
use super::types::*;
use super::validate::{self, DEF_COOKIE};
use super::world::{world_ref, HearthWorld};
use crate::generators::links::{ContactObject, UserContact};
use crate::generators::GeneratorDef;
use crate::pool::Handle;

// ------------------------------------------------------------------------ user callbacks

/// What a user generator callback is told. The arrays are owned by the world and valid only
/// during the call.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthGeneratorContext {
    /// The generator being run.
    pub generator: HearthGeneratorId,
    /// The step's duration (s).
    pub dt: f32,
    /// The live bodies attached to the generator, in attachment order.
    pub bodies: *const HearthBodyId,
    /// Number of entries in `bodies`.
    pub body_count: usize,
    /// The live particles attached to the generator, in attachment order.
    pub particles: *const HearthParticleId,
    /// Number of entries in `particles`.
    pub particle_count: usize,
}

/// The contacts of one user contact generator call, filled by `hearth_contact_sink_add`.
/// Valid only during the callback.
pub struct HearthContactSink {
    pub(crate) world: *const HearthWorld,
    pub(crate) active: bool,
    pub(crate) capacity: usize,
    pub(crate) contacts: Vec<UserContact>,
}

impl Default for HearthContactSink {
    fn default() -> Self {
        HearthContactSink {
            world: std::ptr::null(),
            active: false,
            capacity: 0,
            contacts: Vec::new(),
        }
    }
}

/// A force generator callback, run once per step (in creation order with the other user
/// force generators, after the built-in ones) on the thread that called
/// `hearth_world_step`. It may read anything and apply forces and torques
/// (`hearth_body_apply_force`, `hearth_body_apply_torque`, `hearth_body_apply_force_at_point`,
/// `hearth_particle_apply_force`); other changes return `HEARTH_ERROR_WORLD_LOCKED`.
pub type HearthForceCallback = Option<
    unsafe extern "C" fn(user_data: *mut c_void, world: *mut HearthWorld, context: *const HearthGeneratorContext),
>;

/// A contact generator callback, run once per step after the narrow phase and before the
/// solver (in creation order). It writes contacts with `hearth_contact_sink_add` (up to the
/// generator's capacity) and may read anything; changes to the world return
/// `HEARTH_ERROR_WORLD_LOCKED`.
pub type HearthContactCallback = Option<
    unsafe extern "C" fn(
        user_data: *mut c_void,
        world: *mut HearthWorld,
        context: *const HearthGeneratorContext,
        sink: *mut HearthContactSink,
    ),
>;

type ForceFn = unsafe extern "C" fn(*mut c_void, *mut HearthWorld, *const HearthGeneratorContext);
type ContactFn =
    unsafe extern "C" fn(*mut c_void, *mut HearthWorld, *const HearthGeneratorContext, *mut HearthContactSink);

/// A force generator written in C.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthUserForceGeneratorDef {
    /// Called once per step (must not be NULL). Default NULL.
    pub callback: HearthForceCallback,
    /// Passed to the callback as is. Default NULL.
    pub user_data: *mut c_void,
    /// Set by `hearth_user_force_generator_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: no callback (set one), NULL user data.
#[no_mangle]
pub extern "C" fn hearth_user_force_generator_def_default() -> HearthUserForceGeneratorDef {
    HearthUserForceGeneratorDef {
        callback: None,
        user_data: std::ptr::null_mut(),
        internal_value: DEF_COOKIE,
    }
}

/// Creates a user force generator; attach the bodies and particles its callback is told
/// about.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (also a NULL callback), `HEARTH_ERROR_INVALID_ARGUMENT`
/// (def not from its default), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid; the callback must stay callable while the generator
/// lives, and `user_data` valid for it.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_user_force(
    world: *mut HearthWorld,
    def: *const HearthUserForceGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| {
        validate::cookie(d.internal_value, "hearth_user_force_generator_def")?;
        let f = d.callback.ok_or_else(|| Failure::null("callback"))?;
        Ok(GeneratorDef::ExternalForce {
            callback: f as usize,
            user_data: d.user_data as usize,
        })
    })
}

/// A contact generator written in C.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthUserContactGeneratorDef {
    /// Called once per step (must not be NULL). Default NULL.
    pub callback: HearthContactCallback,
    /// Passed to the callback as is. Default NULL.
    pub user_data: *mut c_void,
    /// Most contacts one call may add (0..=1048576). Default 16.
    pub capacity: u32,
    /// Set by `hearth_user_contact_generator_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: no callback (set one), NULL user data, capacity 16.
#[no_mangle]
pub extern "C" fn hearth_user_contact_generator_def_default() -> HearthUserContactGeneratorDef {
    HearthUserContactGeneratorDef {
        callback: None,
        user_data: std::ptr::null_mut(),
        capacity: 16,
        internal_value: DEF_COOKIE,
    }
}

/// Creates a user contact generator.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (also a NULL callback), `HEARTH_ERROR_INVALID_ARGUMENT`
/// (def not from its default, capacity too large), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid; the callback must stay callable while the generator
/// lives, and `user_data` valid for it.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_user_contact(
    world: *mut HearthWorld,
    def: *const HearthUserContactGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| {
        validate::cookie(d.internal_value, "hearth_user_contact_generator_def")?;
        let f = d.callback.ok_or_else(|| Failure::null("callback"))?;
        Ok(GeneratorDef::ExternalContact {
            callback: f as usize,
            user_data: d.user_data as usize,
            capacity: d.capacity,
        })
    })
}

/// A contact for `hearth_contact_sink_add`. Each side is a body, a particle, or the world
/// (both ids null); at least one side must be an object and the two must differ. Between
/// bodies (or a body and the world) the rigid solver resolves it with collision contacts;
/// with a particle, the particle stage does.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct HearthGeneratedContact {
    /// Side A: a body, or the null id.
    pub body_a: HearthBodyId,
    /// Side A: a particle, or the null id.
    pub particle_a: HearthParticleId,
    /// Side B: a body, or the null id.
    pub body_b: HearthBodyId,
    /// Side B: a particle, or the null id.
    pub particle_b: HearthParticleId,
    /// World point where the two touch (m).
    pub point: HearthVec3,
    /// From A to B: B is pushed along it, A the other way (need not be unit length, must
    /// not be zero).
    pub normal: HearthVec3,
    /// Overlap along the normal (m): > 0 violated, < 0 a gap that may close this step.
    pub penetration: f32,
    /// Bounce (>= 0).
    pub restitution: f32,
    /// Coulomb friction (>= 0).
    pub friction: f32,
}

fn contact_object(body: &HearthBodyId, particle: &HearthParticleId, side: &str) -> Result<ContactObject, Failure> {
    match (is_null_body(body), particle.is_null()) {
        (true, true) => Ok(ContactObject::World),
        (false, true) => Ok(ContactObject::Body((*body).into())),
        (true, false) => Ok(ContactObject::Particle((*particle).into())),
        (false, false) => Err(Failure::invalid(format!(
            "side {side}: set a body or a particle, not both"
        ))),
    }
}

/// Adds a contact from inside a user contact generator callback.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (a dead id),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (NaN/infinite numbers, zero normal, negative restitution
/// or friction, both ids set on a side, no object, the same object twice, or the sink used
/// outside its callback), `HEARTH_ERROR_BUFFER_TOO_SMALL` (the generator's capacity is used
/// up). Nothing is added on error.
///
/// # Safety
/// `sink` must be the pointer passed to the running callback; `contact` NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_contact_sink_add(
    sink: *mut HearthContactSink,
    contact: *const HearthGeneratedContact,
) -> HearthResult {
    guard(|| {
        let s = sink.as_mut().ok_or_else(|| Failure::null("sink"))?;
        let c = validate::input(contact, "contact")?;
        if !s.active {
            return Err(Failure::invalid(
                "the sink is only valid inside its contact generator's callback",
            ));
        }
        let uc = UserContact {
            a: contact_object(&c.body_a, &c.particle_a, "A")?,
            b: contact_object(&c.body_b, &c.particle_b, "B")?,
            point: c.point.into(),
            normal: c.normal.into(),
            penetration: c.penetration,
            restitution: c.restitution,
            friction: c.friction,
        };
        world_ref(s.world)?.validate_user_contact(&uc)?;
        if s.contacts.len() >= s.capacity {
            return Err(Failure::new(
                HEARTH_ERROR_BUFFER_TOO_SMALL,
                format!("the generator's capacity of {} contacts is used up", s.capacity),
            ));
        }
        s.contacts.push(uc);
        Ok(())
    })
}

/// Reads how many contacts the running callback has added and how many it may add.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`.
///
/// # Safety
/// `sink` must be the pointer passed to the running callback; outputs NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_contact_sink_get_count(
    sink: *const HearthContactSink,
    out_count: *mut u32,
    out_capacity: *mut u32,
) -> HearthResult {
    guard(|| {
        let s = sink.as_ref().ok_or_else(|| Failure::null("sink"))?;
        let count = validate::output(out_count, "out_count")?;
        let capacity = validate::output(out_capacity, "out_capacity")?;
        *count = s.contacts.len() as u32;
        *capacity = s.capacity as u32;
        Ok(())
    })
}

// ------------------------------------------------------------------ running callbacks

/// Storage the C layer owns for a step's callbacks (outside the core `World`, so a pointer
/// given to C never points into memory a `&mut World` covers).
#[derive(Default)]
pub(crate) struct CallbackScratch {
    /// The user generators of the running phase: (id, callback, user_data, capacity).
    gens: Vec<(Handle, usize, usize, u32)>,
    bodies: Vec<HearthBodyId>,
    particles: Vec<HearthParticleId>,
    /// The C copy of the expired report (`hearth_world_get_expired_particles`).
    pub(crate) expired: Vec<super::particle::HearthExpiredParticle>,
}

/// Fills the context arrays for generator `h` from a short shared borrow of the world.
///
/// # Safety
/// No `&mut World` may be alive; `scratch` not borrowed elsewhere.
unsafe fn fill_attachments(handle: &HearthWorld, scratch: *mut CallbackScratch, h: Handle) -> bool {
    let w = &*handle.world.get();
    let s = &mut *scratch;
    s.bodies.clear();
    s.particles.clear();
    let Some(g) = w.generators.get(h) else { return false };
    s.bodies.extend(
        g.bodies
            .handles()
            .iter()
            .filter(|&&b| w.bodies.contains(b))
            .map(|&b| HearthBodyId::from(b)),
    );
    s.particles.extend(
        g.particles
            .handles()
            .iter()
            .filter(|&&p| w.particles.index(p).is_some())
            .map(|&p| HearthParticleId::from(p)),
    );
    true
}

/// Collects the user generators of one kind, in slot (creation) order.
///
/// # Safety
/// No `&mut World` may be alive; `scratch` not borrowed elsewhere.
unsafe fn collect(handle: &HearthWorld, scratch: *mut CallbackScratch, contact: bool) {
    let w = &*handle.world.get();
    let s = &mut *scratch;
    s.gens.clear();
    for (h, g) in w.generators.iter() {
        match g.def {
            // Restored from a snapshot into a world that did not have it: no callback until
            // the host sets one (capi/snapshot.rs), so nothing to call.
            GeneratorDef::ExternalForce { callback: 0, .. } | GeneratorDef::ExternalContact { callback: 0, .. } => {}
            GeneratorDef::ExternalForce { callback, user_data } if !contact => s.gens.push((h, callback, user_data, 0)),
            GeneratorDef::ExternalContact {
                callback,
                user_data,
                capacity,
            } if contact => s.gens.push((h, callback, user_data, capacity)),
            _ => {}
        }
    }
}

/// Runs every user force generator once. Called by `hearth_world_step` in the force phase,
/// with no reference to the world alive: each callback gets the raw world pointer, and the
/// functions it calls borrow the world only for their own duration.
///
/// # Safety
/// `world` must be a live world in its force phase.
pub(crate) unsafe fn run_force_callbacks(world: *mut HearthWorld, dt: f32) {
    let handle = &*world;
    let scratch = handle.scratch.get();
    collect(handle, scratch, false);
    for k in 0..(*scratch).gens.len() {
        let (h, callback, user_data, _) = (&(*scratch).gens)[k];
        if !fill_attachments(handle, scratch, h) {
            continue;
        }
        let ctx = context(scratch, h, dt);
        // SAFETY: stored from a non-null `HearthForceCallback` in
        // `hearth_generator_create_user_force`.
        let f: ForceFn = std::mem::transmute::<usize, ForceFn>(callback);
        f(user_data as *mut c_void, world, &ctx);
    }
}

/// Runs every user contact generator once, then hands its contacts to the world. Called by
/// `hearth_world_step` in the contact phase (see `run_force_callbacks`).
///
/// # Safety
/// `world` must be a live world in its contact phase.
pub(crate) unsafe fn run_contact_callbacks(world: *mut HearthWorld, dt: f32) {
    let handle = &*world;
    let scratch = handle.scratch.get();
    let sink = handle.sink.get();
    collect(handle, scratch, true);
    for k in 0..(*scratch).gens.len() {
        let (h, callback, user_data, capacity) = (&(*scratch).gens)[k];
        if !fill_attachments(handle, scratch, h) {
            continue;
        }
        let ctx = context(scratch, h, dt);
        {
            let s = &mut *sink;
            s.world = world;
            s.capacity = capacity as usize;
            s.contacts.clear();
            s.contacts.reserve(s.capacity);
            s.active = true;
        }
        // SAFETY: stored from a non-null `HearthContactCallback` in
        // `hearth_generator_create_user_contact`.
        let f: ContactFn = std::mem::transmute::<usize, ContactFn>(callback);
        f(user_data as *mut c_void, world, &ctx, sink);
        let s = &mut *sink;
        s.active = false;
        let w = &mut *handle.world.get();
        for c in &s.contacts {
            // Validated when added, and the world cannot change while callbacks run.
            let r = w.add_user_contact(c);
            debug_assert!(r.is_ok(), "{r:?}");
        }
        s.contacts.clear();
    }
}

/// # Safety
/// `scratch` must be valid; the arrays stay valid until it is next filled.
unsafe fn context(scratch: *mut CallbackScratch, h: Handle, dt: f32) -> HearthGeneratorContext {
    let s = &*scratch;
    HearthGeneratorContext {
        generator: h.into(),
        dt,
        bodies: s.bodies.as_ptr(),
        body_count: s.bodies.len(),
        particles: s.particles.as_ptr(),
        particle_count: s.particles.len(),
    }
}

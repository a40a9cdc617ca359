//! Particle exports: defaults, create, destroy, state, forces, burst emitters, bulk
//! read-back and the expired-particle report.

use super::error::*;
use super::types::*;
use super::validate::{self, DEF_COOKIE};
use super::world::{world_mut, world_mut_in_phase, world_ref, HearthWorld, PHASE_FORCES};
use crate::particles::emitter::BurstDef;
use crate::particles::ParticleDef;
use crate::pool::Handle;

/// Id of a particle inside its world. All-zero is the null id. A particle that expired or
/// was destroyed leaves a stale id: `HEARTH_ERROR_INVALID_ID`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HearthParticleId {
    /// Slot of the particle.
    pub index: u32,
    /// Generation of the slot (0 only in the null id).
    pub generation: u32,
}

impl From<HearthParticleId> for Handle {
    fn from(id: HearthParticleId) -> Handle {
        Handle {
            index: id.index,
            generation: id.generation,
        }
    }
}

impl From<Handle> for HearthParticleId {
    fn from(h: Handle) -> HearthParticleId {
        HearthParticleId {
            index: h.index,
            generation: h.generation,
        }
    }
}

impl HearthParticleId {
    /// The all-zero id.
    pub(crate) fn is_null(&self) -> bool {
        self.index == 0 && self.generation == 0
    }
}

/// How to create a particle. Get one from `hearth_particle_def_default()`, then edit it.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthParticleDef {
    /// Position (m, each coordinate within ±1e5).
    pub position: HearthVec3,
    /// Velocity (m/s, no faster than the world's `max_linear_speed`).
    pub velocity: HearthVec3,
    /// Constant acceleration of this particle (m/s², length up to 1e4), on top of world
    /// gravity. Default 0.
    pub acceleration: HearthVec3,
    /// Inverse mass (1/kg, 0..=1e9); 0 is an infinite mass (a pinned particle, moved only by
    /// its velocity). Default 1 (1 kg).
    pub inverse_mass: f32,
    /// Radius of the small sphere it collides as (m: 0, a point, or 0.001..=1e4). Default 0.05.
    pub radius: f32,
    /// Linear damping (1/s, 0..=1000): `v /= 1 + h·damping` per sub-step. Default 0.
    pub damping: f32,
    /// Multiplier of world gravity (-100..=100). Default 1.
    pub gravity_scale: f32,
    /// Bounciness against shapes (0..=1; the pair uses the larger of the particle's and the
    /// shape's). Default 0.
    pub restitution: f32,
    /// Coulomb friction against shapes (>= 0; the pair uses the geometric mean with the
    /// shape's static friction). Default 0.5.
    pub friction: f32,
    /// Seconds until the particle expires (> 0; `INFINITY`, the default, lives forever).
    /// Expired particles are removed and reported by `hearth_world_get_expired_particles`.
    pub lifetime: f32,
    /// 1 (default) collides with shapes; 0 passes through everything.
    pub collide: u8,
    /// 1 (default) lets the particle sleep when still; 0 keeps it awake.
    pub allow_sleep: u8,
    /// Host data, returned by `hearth_particle_get_user_data` and in the expired report.
    pub user_data: u64,
    /// Set by `hearth_particle_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: at the origin, at rest, 1 kg, radius 0.05 m, no damping, full gravity, no
/// bounce, friction 0.5, lives forever, collides, may sleep.
#[no_mangle]
pub extern "C" fn hearth_particle_def_default() -> HearthParticleDef {
    let d = ParticleDef::default();
    HearthParticleDef {
        position: d.position.into(),
        velocity: d.velocity.into(),
        acceleration: d.acceleration.into(),
        inverse_mass: d.inverse_mass,
        radius: d.radius,
        damping: d.damping,
        gravity_scale: d.gravity_scale,
        restitution: d.restitution,
        friction: d.friction,
        lifetime: d.lifetime,
        collide: 1,
        allow_sleep: 1,
        user_data: 0,
        internal_value: DEF_COOKIE,
    }
}

pub(crate) fn particle_def(d: &HearthParticleDef) -> Result<ParticleDef, Failure> {
    validate::cookie(d.internal_value, "hearth_particle_def")?;
    Ok(ParticleDef {
        position: d.position.into(),
        velocity: d.velocity.into(),
        acceleration: d.acceleration.into(),
        inverse_mass: d.inverse_mass,
        radius: d.radius,
        damping: d.damping,
        gravity_scale: d.gravity_scale,
        restitution: d.restitution,
        friction: d.friction,
        lifetime: d.lifetime,
        collide: validate::flag(d.collide, "collide")?,
        allow_sleep: validate::flag(d.allow_sleep, "allow_sleep")?,
        user_data: d.user_data,
    })
}

/// Creates a particle.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (def not from
/// `hearth_particle_def_default()`, a number outside its range, NaN/infinite numbers,
/// negative friction, lifetime <= 0, flag not 0/1), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_create(
    world: *mut HearthWorld,
    def: *const HearthParticleDef,
    out_particle: *mut HearthParticleId,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let def = particle_def(validate::input(def, "def")?)?;
        let out = validate::output(out_particle, "out_particle")?;
        *out = w.create_particle(&def)?.into();
        Ok(())
    })
}

/// Destroys a particle: its id becomes stale and it leaves every generator (links with it as
/// an end stop acting). Destroyed particles are not in the expired report.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_destroy(world: *mut HearthWorld, particle: HearthParticleId) -> HearthResult {
    guard(|| Ok(world_mut(world)?.destroy_particle(particle.into())?))
}

/// Shared body of the getters: checks world, output pointer and id; writes on success.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
unsafe fn get<T>(
    world: *const HearthWorld,
    particle: HearthParticleId,
    out: *mut T,
    read: impl FnOnce(&crate::world::World, Handle) -> Result<T, crate::error::Error>,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out, "out")?;
        *out = read(w, particle.into())?;
        Ok(())
    })
}

/// Reads a particle's position (m).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_get_position(
    world: *const HearthWorld,
    particle: HearthParticleId,
    out: *mut HearthVec3,
) -> HearthResult {
    get(world, particle, out, |w, h| Ok(w.particle_position(h)?.into()))
}

/// Reads a particle's velocity (m/s).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_get_velocity(
    world: *const HearthWorld,
    particle: HearthParticleId,
    out: *mut HearthVec3,
) -> HearthResult {
    get(world, particle, out, |w, h| Ok(w.particle_velocity(h)?.into()))
}

/// Reads whether a particle is awake.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_is_awake(
    world: *const HearthWorld,
    particle: HearthParticleId,
    out: *mut bool,
) -> HearthResult {
    get(world, particle, out, |w, h| w.particle_is_awake(h))
}

/// Reads the `user_data` given at creation.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_get_user_data(
    world: *const HearthWorld,
    particle: HearthParticleId,
    out: *mut u64,
) -> HearthResult {
    get(world, particle, out, |w, h| w.particle_user_data(h))
}

/// Teleports a particle (m, each coordinate within ±1e5) and wakes it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (out of range, NaN or infinite), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_set_position(
    world: *mut HearthWorld,
    particle: HearthParticleId,
    position: HearthVec3,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.set_particle_position(particle.into(), position.into())?))
}

/// Sets a particle's velocity (m/s, no faster than the world's `max_linear_speed`); a
/// non-zero value wakes it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (too fast, NaN or infinite), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_set_velocity(
    world: *mut HearthWorld,
    particle: HearthParticleId,
    velocity: HearthVec3,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.set_particle_velocity(particle.into(), velocity.into())?))
}

/// Adds a force (N, length up to 1e12) to a particle for the next step (or, from a force
/// generator callback, for the current step) and wakes it. Allowed inside user force
/// generator callbacks.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (out of range, NaN or infinite), `HEARTH_ERROR_WORLD_LOCKED` (from a
/// callback other than a force generator's).
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_apply_force(
    world: *mut HearthWorld,
    particle: HearthParticleId,
    force: HearthVec3,
) -> HearthResult {
    guard(|| Ok(world_mut_in_phase(world, PHASE_FORCES)?.apply_particle_force(particle.into(), force.into(), true)?))
}

/// Applies an impulse (N·s, length up to 1e10) to a particle: changes its velocity at once,
/// capped at the world's `max_linear_speed`. Wakes it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (out of range, NaN or infinite), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_apply_impulse(
    world: *mut HearthWorld,
    particle: HearthParticleId,
    impulse: HearthVec3,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.apply_particle_impulse(particle.into(), impulse.into())?))
}

/// Wakes a particle (`awake` = 1; its linked group follows) or puts it to sleep (0).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (flag not 0/1), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_set_awake(
    world: *mut HearthWorld,
    particle: HearthParticleId,
    awake: u8,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let awake = validate::flag(awake, "awake")?;
        Ok(w.set_particle_awake(particle.into(), awake)?)
    })
}

/// A burst of particles from one point. Get one from `hearth_burst_def_default()`, then
/// edit it. The same def (same seed) always gives the same burst.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthBurstDef {
    /// Where every particle starts (m, each coordinate within ±1e5).
    pub position: HearthVec3,
    /// Axis of the cone (need not be unit length, must not be zero). Default +Y.
    pub direction: HearthVec3,
    /// Half-angle of the cone (radians, 0..=π; π is every direction). Directions are
    /// uniform over the cone's solid angle. Default 0.5.
    pub cone_half_angle: f32,
    /// Particles to emit (0..=1048576). Default 16.
    pub count: u32,
    /// Slowest speed (m/s, >= 0); speeds are uniform in [min, max]. Default 5.
    pub speed_min: f32,
    /// Fastest speed (m/s, >= speed_min; plus the length of `particle.velocity`, at most the
    /// world's `max_linear_speed`). Default 10.
    pub speed_max: f32,
    /// Shortest lifetime (s, > 0); lifetimes are uniform in [min, max]. Default 1.
    pub lifetime_min: f32,
    /// Longest lifetime (s, >= lifetime_min; `INFINITY` lives forever). Default 2.
    pub lifetime_max: f32,
    /// Seed of the random sequence. Default 1.
    pub seed: u64,
    /// Every other property of the particles, from `hearth_particle_def_default()`; its
    /// position, lifetime and (added to each particle's own) velocity are per burst.
    pub particle: HearthParticleDef,
    /// Set by `hearth_burst_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: 16 particles from the origin up a cone of half-angle 0.5 rad at 5..10 m/s,
/// living 1..2 s, seed 1, particles as `hearth_particle_def_default()`.
#[no_mangle]
pub extern "C" fn hearth_burst_def_default() -> HearthBurstDef {
    let d = BurstDef::default();
    HearthBurstDef {
        position: d.position.into(),
        direction: d.direction.into(),
        cone_half_angle: d.cone_half_angle,
        count: d.count,
        speed_min: d.speed_min,
        speed_max: d.speed_max,
        lifetime_min: d.lifetime_min,
        lifetime_max: d.lifetime_max,
        seed: d.seed,
        particle: hearth_particle_def_default(),
        internal_value: DEF_COOKIE,
    }
}

/// Emits a burst. When `out_ids` is not NULL the new ids are written to it (it must hold
/// `capacity` ids); `*out_count` (if not NULL) receives the number emitted.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, def), `HEARTH_ERROR_INVALID_ARGUMENT` (def or
/// its `particle` not from their `*_default()`, zero direction, angle outside [0, π],
/// speed or lifetime range reversed or negative, count too large),
/// `HEARTH_ERROR_BUFFER_TOO_SMALL` (`out_ids` given and `capacity < count`),
/// `HEARTH_ERROR_WORLD_LOCKED`. Nothing is emitted on error.
///
/// # Safety
/// `out_ids` must be NULL or hold `capacity` ids; other pointers NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_particle_emit_burst(
    world: *mut HearthWorld,
    def: *const HearthBurstDef,
    out_ids: *mut HearthParticleId,
    capacity: usize,
    out_count: *mut usize,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let d = validate::input(def, "def")?;
        validate::cookie(d.internal_value, "hearth_burst_def")?;
        let burst = BurstDef {
            position: d.position.into(),
            direction: d.direction.into(),
            cone_half_angle: d.cone_half_angle,
            count: d.count,
            speed_min: d.speed_min,
            speed_max: d.speed_max,
            lifetime_min: d.lifetime_min,
            lifetime_max: d.lifetime_max,
            seed: d.seed,
            particle: particle_def(&d.particle)?,
        };
        burst.validate(w.settings.max_linear_speed)?;
        if !out_ids.is_null() {
            validate::capacity(capacity, burst.count as usize, "out_ids")?;
        }
        let mut k = 0usize;
        w.emit_burst_with(&burst, |h| {
            if !out_ids.is_null() {
                *out_ids.add(k) = h.into();
            }
            k += 1;
        })?;
        if !out_count.is_null() {
            *out_count = k;
        }
        Ok(())
    })
}

/// Reads the number of live particles.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_count` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_particle_count(
    world: *const HearthWorld,
    out_count: *mut usize,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out_count, "out_count")?;
        *out = w.particle_count();
        Ok(())
    })
}

/// Reads every live particle into caller-owned arrays, one call per frame: ids, positions
/// and velocities, each array optional (NULL skips it), all in the same order (unspecified,
/// but the same for all three). `*out_count` receives the number written. As every bulk read:
/// `capacity == 0` only asks for the count (`*out_count` = live particles, nothing written).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world, out_count), `HEARTH_ERROR_BUFFER_TOO_SMALL`
/// (`capacity` non-zero but below `hearth_world_get_particle_count`; nothing is written).
///
/// # Safety
/// Each non-NULL array must hold `capacity` elements.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_particles(
    world: *const HearthWorld,
    out_ids: *mut HearthParticleId,
    out_positions: *mut HearthVec3,
    out_velocities: *mut HearthVec3,
    capacity: usize,
    out_count: *mut usize,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out_count = validate::output(out_count, "out_count")?;
        let p = &w.particles;
        let n = p.len();
        if capacity == 0 {
            *out_count = n;
            return Ok(());
        }
        validate::capacity(capacity, n, "the particle arrays")?;
        if !out_ids.is_null() {
            let out = std::slice::from_raw_parts_mut(out_ids, n);
            for (o, h) in out.iter_mut().zip(&p.handle) {
                *o = (*h).into();
            }
        }
        if !out_positions.is_null() {
            let out = std::slice::from_raw_parts_mut(out_positions, n);
            for (o, v) in out.iter_mut().zip(&p.pos) {
                *o = (*v).into();
            }
        }
        if !out_velocities.is_null() {
            let out = std::slice::from_raw_parts_mut(out_velocities, n);
            for (o, v) in out.iter_mut().zip(&p.vel) {
                *o = (*v).into();
            }
        }
        *out_count = n;
        Ok(())
    })
}

/// Reads the positions of `count` particles given by id into the caller-owned
/// `out_positions`. Every id is checked first; on any error nothing is written. `count == 0`
/// succeeds and may pass NULL arrays.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (the message names the
/// first bad index).
///
/// # Safety
/// `particles` must hold `count` ids and `out_positions` room for `count` vectors.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_particle_positions(
    world: *const HearthWorld,
    particles: *const HearthParticleId,
    count: usize,
    out_positions: *mut HearthVec3,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        if count == 0 {
            return Ok(());
        }
        if particles.is_null() {
            return Err(Failure::null("particles"));
        }
        validate::output(out_positions, "out_positions")?;
        let ids = std::slice::from_raw_parts(particles, count);
        for (i, id) in ids.iter().enumerate() {
            if w.particles.index((*id).into()).is_none() {
                return Err(Failure::new(
                    HEARTH_ERROR_INVALID_ID,
                    format!("particles[{i}] is not a live particle of this world"),
                ));
            }
        }
        let out = std::slice::from_raw_parts_mut(out_positions, count);
        for (o, id) in out.iter_mut().zip(ids) {
            let i = w.particles.index((*id).into()).expect("checked");
            *o = w.particles.pos[i].into();
        }
        Ok(())
    })
}

/// A particle that expired (its lifetime ran out) in the last step. Its id is stale.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct HearthExpiredParticle {
    /// Its (now stale) id.
    pub id: HearthParticleId,
    /// Where it was when it expired (m).
    pub position: HearthVec3,
    /// Its velocity then (m/s).
    pub velocity: HearthVec3,
    /// The particle's `user_data`.
    pub user_data: u64,
}

/// Gives the particles that expired in the last `hearth_world_step`: `*out_array` points to
/// `*out_count` entries the world owns, valid until the next `hearth_world_step` (or
/// `hearth_world_destroy`); other calls do not change it. Chain effects (a firework that
/// bursts when it expires) read it after each step and emit.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`.
///
/// # Safety
/// `world` must be NULL or a live world; the outputs NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_expired_particles(
    world: *const HearthWorld,
    out_array: *mut *const HearthExpiredParticle,
    out_count: *mut usize,
) -> HearthResult {
    guard(|| {
        let handle = world.as_ref().ok_or_else(|| Failure::null("world"))?;
        let out_array = validate::output(out_array, "out_array")?;
        let out_count = validate::output(out_count, "out_count")?;
        let expired = &(*handle.scratch.get()).expired;
        *out_array = expired.as_ptr();
        *out_count = expired.len();
        Ok(())
    })
}

/// Copies the core's expired report into the C array (called at the end of a step).
pub(crate) fn publish_expired(world: &crate::world::World, out: &mut Vec<HearthExpiredParticle>) {
    out.clear();
    out.extend(world.expired_particles().iter().map(|e| HearthExpiredParticle {
        id: e.id.into(),
        position: e.position.into(),
        velocity: e.velocity.into(),
        user_data: e.user_data,
    }));
}

/// Sets the iteration counts of the particle stage: velocity sweeps and position
/// projections per sub-step (each 1..=64; defaults 8 and 4). Rods are solved exactly
/// whatever the counts; the sweeps matter for contacts and cables.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT`,
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_set_particle_iterations(
    world: *mut HearthWorld,
    velocity_iterations: u32,
    position_iterations: u32,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.set_particle_iterations(velocity_iterations, position_iterations)?))
}

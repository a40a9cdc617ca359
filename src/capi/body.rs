//! Body exports: defaults, create, destroy, state get/set, forces and impulses.

use super::error::*;
use super::types::*;
use super::validate::{self, DEF_COOKIE};
use super::world::{world_mut, world_mut_in_phase, world_ref, HearthWorld, PHASE_FORCES};
use crate::dynamics::body::{BodyDef, BodyType};
use crate::math::Transform;

/// Never moves; infinite mass. Planes go on static bodies.
pub const HEARTH_BODY_STATIC: u32 = 0;
/// Moves by its velocity (or a target transform); infinite mass; pushes dynamic bodies.
pub const HEARTH_BODY_KINEMATIC: u32 = 1;
/// Moves under gravity, forces and contacts; mass from its shapes' densities.
pub const HEARTH_BODY_DYNAMIC: u32 = 2;

/// How to create a body. Get one from `hearth_body_def_default()`, then edit it.
///
/// Mass ratios: a dynamic body resting on a lighter one presses into it by about
/// 0.031 mm per unit of mass ratio at the default settings (the contact is a spring
/// relative to the lighter body's mass): 4.3 mm for 100 kg on 1 kg. Up to 1:100 such stacks
/// rest and sleep within 5 s; at 1:1000 they still come to rest, about 4 cm deep. Larger
/// ratios are not supported.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthBodyDef {
    /// `HEARTH_BODY_STATIC` (default), `HEARTH_BODY_KINEMATIC` or `HEARTH_BODY_DYNAMIC`.
    pub r#type: u32,
    /// Pose of the body origin (m, each coordinate within ±1e5); the rotation is normalised,
    /// must not be zero.
    pub transform: HearthTransform,
    /// Initial velocity of the centre of mass (m/s, no faster than the world's
    /// `max_linear_speed`).
    pub linear_velocity: HearthVec3,
    /// Initial angular velocity (rad/s, world frame, length up to the world's
    /// `max_angular_speed`).
    pub angular_velocity: HearthVec3,
    /// Linear damping (1/s, 0..=1000). Default 0.
    pub linear_damping: f32,
    /// Angular damping (1/s, 0..=1000). Default 0.
    pub angular_damping: f32,
    /// 1 (default) lets the body sleep when still; 0 keeps it awake.
    pub allow_sleep: u8,
    /// Host data, returned by `hearth_body_get_user_data`.
    pub user_data: u64,
    /// Multiplier of world gravity for this body (-100..=100). Default 1.
    pub gravity_scale: f32,
    /// 1 (default) creates the body awake; 0 creates it asleep.
    pub is_awake: u8,
    /// Set by `hearth_body_def_default()`; do not change.
    pub internal_value: u32,
    /// 1 (default) reports the body in move events (`hearth_world_get_body_events`) when it
    /// moves or falls asleep; 0 never. (Appended after `internal_value`, so earlier fields
    /// keep their offsets.)
    pub enable_move_events: u8,
    /// Locked axes, `HEARTH_LOCK_*` bits ORed (world axes). Default 0 (none). Unknown bits are
    /// refused. (Appended, so earlier fields keep their offsets.)
    pub locked_axes: u32,
}

/// Defaults: static, at the origin, identity rotation, at rest, no damping, may sleep.
#[no_mangle]
pub extern "C" fn hearth_body_def_default() -> HearthBodyDef {
    let d = BodyDef::default();
    HearthBodyDef {
        r#type: HEARTH_BODY_STATIC,
        transform: d.transform.into(),
        linear_velocity: d.linear_velocity.into(),
        angular_velocity: d.angular_velocity.into(),
        linear_damping: d.linear_damping,
        angular_damping: d.angular_damping,
        allow_sleep: 1,
        user_data: 0,
        gravity_scale: d.gravity_scale,
        is_awake: 1,
        internal_value: DEF_COOKIE,
        enable_move_events: 1,
        locked_axes: 0,
    }
}

fn body_def(d: &HearthBodyDef) -> Result<BodyDef, Failure> {
    validate::cookie(d.internal_value, "hearth_body_def")?;
    let body_type = match d.r#type {
        HEARTH_BODY_STATIC => BodyType::Static,
        HEARTH_BODY_KINEMATIC => BodyType::Kinematic,
        HEARTH_BODY_DYNAMIC => BodyType::Dynamic,
        v => return Err(Failure::invalid(format!("type must be a HEARTH_BODY_* code, got {v}"))),
    };
    Ok(BodyDef {
        body_type,
        transform: d.transform.into(),
        linear_velocity: d.linear_velocity.into(),
        angular_velocity: d.angular_velocity.into(),
        linear_damping: d.linear_damping,
        angular_damping: d.angular_damping,
        gravity_scale: d.gravity_scale,
        allow_sleep: validate::flag(d.allow_sleep, "allow_sleep")?,
        awake: validate::flag(d.is_awake, "is_awake")?,
        user_data: d.user_data,
        enable_move_events: validate::flag(d.enable_move_events, "enable_move_events")?,
        locked_axes: {
            crate::dynamics::body::check_locked_axes("locked_axes", d.locked_axes)?;
            d.locked_axes as u8
        },
    })
}

/// Creates a body. It has no mass until shapes are added (a dynamic body without shapes
/// moves as 1 kg with unit inertia).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (def not from
/// `hearth_body_def_default()`, unknown type, bad flag, a number outside its range, zero
/// rotation), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_create(
    world: *mut HearthWorld,
    def: *const HearthBodyDef,
    out_body: *mut HearthBodyId,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let def = body_def(validate::input(def, "def")?)?;
        let out = validate::output(out_body, "out_body")?;
        *out = w.create_body(&def)?.into();
        Ok(())
    })
}

/// Destroys a body, its shapes, its contacts (bodies it touched are woken) and its joints;
/// it is detached from every generator, and particles or soft-body vertices pinned to it are
/// released. The id becomes stale; a later body never reuses it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_destroy(world: *mut HearthWorld, body: HearthBodyId) -> HearthResult {
    guard(|| Ok(world_mut(world)?.destroy_body(body.into())?))
}

/// Shared body of the getters: checks world, output pointer and id; writes on success.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
unsafe fn get<T>(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut T,
    read: impl FnOnce(&crate::world::World, crate::pool::Handle) -> Result<T, crate::error::Error>,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out, "out")?;
        *out = read(w, body.into())?;
        Ok(())
    })
}

fn type_code(t: BodyType) -> u32 {
    match t {
        BodyType::Static => HEARTH_BODY_STATIC,
        BodyType::Kinematic => HEARTH_BODY_KINEMATIC,
        BodyType::Dynamic => HEARTH_BODY_DYNAMIC,
    }
}

/// Reads the pose of the body origin.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_get_transform(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut HearthTransform,
) -> HearthResult {
    get(world, body, out, |w, h| Ok(w.transform(h)?.into()))
}

/// Reads the velocity of the centre of mass (m/s).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_get_linear_velocity(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut HearthVec3,
) -> HearthResult {
    get(world, body, out, |w, h| Ok(w.linear_velocity(h)?.into()))
}

/// Reads the angular velocity (rad/s, world frame).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_get_angular_velocity(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut HearthVec3,
) -> HearthResult {
    get(world, body, out, |w, h| Ok(w.angular_velocity(h)?.into()))
}

/// Reads whether the body is awake (static bodies are never awake).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_is_awake(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut bool,
) -> HearthResult {
    get(world, body, out, |w, h| w.is_awake(h))
}

/// Reads the centre of mass in world space (m).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_get_center_of_mass(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut HearthVec3,
) -> HearthResult {
    get(world, body, out, |w, h| Ok(w.body(h)?.center.into()))
}

/// Reads the mass (kg); 0 for static and kinematic bodies.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_get_mass(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut f32,
) -> HearthResult {
    get(world, body, out, |w, h| Ok(w.body(h)?.mass))
}

/// Reads the `user_data` given at creation.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_get_user_data(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut u64,
) -> HearthResult {
    get(world, body, out, |w, h| Ok(w.body(h)?.user_data))
}

/// Reads the body type code (`HEARTH_BODY_*`).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_get_type(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut u32,
) -> HearthResult {
    get(world, body, out, |w, h| Ok(type_code(w.body(h)?.body_type)))
}

/// Teleports the body origin (m, each coordinate within ±1e5). Wakes it. Contacts are
/// refreshed on the next step.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (out of range, NaN/infinite, zero rotation),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_set_transform(
    world: *mut HearthWorld,
    body: HearthBodyId,
    transform: *const HearthTransform,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let t: Transform = (*validate::input(transform, "transform")?).into();
        Ok(w.set_transform(body.into(), t)?)
    })
}

/// Kinematic bodies: move to `target` by velocity, so touching and jointed bodies are
/// carried along. The next step sets the velocities that reach the target by its end; the
/// body then sits exactly on the target, its velocities still read as those it moved with
/// during that step (what a renderer or a rider wants to know), and it stops at the start of
/// the following step (velocities zero) unless given a new target or velocity. A target farther than the world's speed limits allow in one step
/// (`max_linear_speed`, `max_angular_speed`) is approached at the limits and kept until
/// reached. `hearth_body_set_transform` drops a pending target; a pending target overrides
/// the velocities set with `hearth_body_set_linear_velocity` / `_angular_velocity`.
///
/// Errors: as `hearth_body_set_transform`, and `HEARTH_ERROR_INVALID_ARGUMENT` for a body that
/// is not kinematic.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_set_target_transform(
    world: *mut HearthWorld,
    body: HearthBodyId,
    target: *const HearthTransform,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let t: Transform = (*validate::input(target, "target")?).into();
        Ok(w.set_kinematic_target(body.into(), t)?)
    })
}

/// Shared body of the vector setters.
///
/// # Safety
/// `world` must be NULL or a live world.
unsafe fn set_vec(
    world: *mut HearthWorld,
    body: HearthBodyId,
    value: HearthVec3,
    write: impl FnOnce(&mut crate::world::World, crate::pool::Handle, crate::math::Vec3) -> Result<(), crate::error::Error>,
) -> HearthResult {
    guard(|| Ok(write(world_mut(world)?, body.into(), value.into())?))
}

/// Sets the velocity of the centre of mass (m/s, no faster than the world's
/// `max_linear_speed`); a non-zero value wakes the body. Ignored for static bodies.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (too fast, NaN or infinite), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_set_linear_velocity(
    world: *mut HearthWorld,
    body: HearthBodyId,
    value: HearthVec3,
) -> HearthResult {
    set_vec(world, body, value, |w, h, v| w.set_linear_velocity(h, v))
}

/// Sets the angular velocity (rad/s, world frame, no faster than the world's
/// `max_angular_speed`); a non-zero value wakes the body. Ignored for static bodies.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (too fast, NaN or infinite), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_set_angular_velocity(
    world: *mut HearthWorld,
    body: HearthBodyId,
    value: HearthVec3,
) -> HearthResult {
    set_vec(world, body, value, |w, h, v| w.set_angular_velocity(h, v))
}

/// Adds a force (N, length up to 1e12) at the centre of mass for the next step (from a force
/// generator callback: for the current step). Wakes the body. No effect on static and
/// kinematic bodies. Allowed inside user force generator callbacks.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (out of range, NaN or infinite; checked before the id),
/// `HEARTH_ERROR_WORLD_LOCKED` (from a callback other than a force generator's).
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_apply_force(
    world: *mut HearthWorld,
    body: HearthBodyId,
    value: HearthVec3,
) -> HearthResult {
    guard(|| Ok(world_mut_in_phase(world, PHASE_FORCES)?.apply_force(body.into(), value.into(), true)?))
}

/// Adds a torque (N·m, world frame, length up to 1e12) for the next step (from a force
/// generator callback: for the current step). Wakes the body. Allowed inside user force
/// generator callbacks.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (out of range, NaN or infinite; checked before the id),
/// `HEARTH_ERROR_WORLD_LOCKED` (from a callback other than a force generator's).
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_apply_torque(
    world: *mut HearthWorld,
    body: HearthBodyId,
    value: HearthVec3,
) -> HearthResult {
    guard(|| Ok(world_mut_in_phase(world, PHASE_FORCES)?.apply_torque(body.into(), value.into(), true)?))
}

/// Applies an impulse (N·s, length up to 1e10) at the centre of mass: changes the velocity at
/// once, capped at the world's speed limits. Wakes the body.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (out of range, NaN or infinite),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_apply_linear_impulse(
    world: *mut HearthWorld,
    body: HearthBodyId,
    value: HearthVec3,
) -> HearthResult {
    set_vec(world, body, value, |w, h, v| w.apply_linear_impulse(h, v, true))
}

/// Applies an angular impulse (N·m·s, world frame, length up to 1e10): changes the angular
/// velocity at once, capped at the world's `max_angular_speed`. Wakes the body.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (out of range, NaN or infinite; checked before the id),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_apply_angular_impulse(
    world: *mut HearthWorld,
    body: HearthBodyId,
    value: HearthVec3,
) -> HearthResult {
    set_vec(world, body, value, |w, h, v| w.apply_angular_impulse(h, v, true))
}

/// Adds a force (N, length up to 1e12) at a world point (m, each coordinate within ±1e5) for
/// the next step: a force plus the torque of its lever arm about the centre of mass. Wakes
/// the body. Allowed inside user force generator callbacks.
///
/// Errors: as `hearth_body_apply_force`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_apply_force_at_point(
    world: *mut HearthWorld,
    body: HearthBodyId,
    force: HearthVec3,
    point: HearthVec3,
) -> HearthResult {
    guard(|| {
        let w = world_mut_in_phase(world, PHASE_FORCES)?;
        Ok(w.apply_force_at_point(body.into(), force.into(), point.into(), true)?)
    })
}

/// Applies an impulse (N·s, length up to 1e10) at a world point (m, each coordinate within
/// ±1e5): the new velocities are capped at the world's speed limits. Wakes the body.
///
/// Errors: as `hearth_body_apply_force`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_apply_impulse_at_point(
    world: *mut HearthWorld,
    body: HearthBodyId,
    impulse: HearthVec3,
    point: HearthVec3,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.apply_impulse_at_point(body.into(), impulse.into(), point.into(), true)?))
}

/// Wakes the body's island (`awake` = 1) or puts it to sleep (0).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (flag not 0/1), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_set_awake(world: *mut HearthWorld, body: HearthBodyId, awake: u8) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let awake = validate::flag(awake, "awake")?;
        Ok(w.set_awake(body.into(), awake)?)
    })
}

/// Sets linear and angular damping (1/s, 0..=1000).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_set_damping(
    world: *mut HearthWorld,
    body: HearthBodyId,
    linear_damping: f32,
    angular_damping: f32,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.set_damping(body.into(), linear_damping, angular_damping)?))
}

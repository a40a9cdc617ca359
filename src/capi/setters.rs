//! Runtime setters and their getters (issue 14): shape material, density and user data; body
//! gravity scale, mass override, type, enable and disable. Thin: each converts, validates and
//! calls the core (`world_setters.rs`), which checks every number and changes nothing on error.

use super::body::{HEARTH_BODY_DYNAMIC, HEARTH_BODY_KINEMATIC, HEARTH_BODY_STATIC};
use super::error::*;
use super::types::*;
use super::world::{world_mut, world_ref, HearthWorld};
use crate::collision::shape::ShapeDef;
use crate::dynamics::body::BodyType;
use crate::world_setters::MassData;

/// A body's mass properties: mass (kg), centre of mass in the body frame (m), and the
/// principal moments of inertia about the centre of mass along the body axes (kg·m²).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthMassData {
    /// Mass (kg), finite and above 0.
    pub mass: f32,
    /// Centre of mass in the body's local frame (m).
    pub center: HearthVec3,
    /// Principal moments of inertia about the centre of mass, along the body's local axes
    /// (kg·m²), each finite and above 0.
    pub inertia: HearthVec3,
}

/// Shared body of the shape-material setters.
///
/// # Safety
/// `world` must be NULL or a live world.
unsafe fn edit(world: *mut HearthWorld, shape: HearthShapeId, f: impl FnOnce(&mut ShapeDef)) -> HearthResult {
    guard(|| Ok(world_mut(world)?.edit_shape_material(shape.into(), f)?))
}

/// Shared body of the shape getters.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
unsafe fn get_shape<T>(
    world: *const HearthWorld,
    shape: HearthShapeId,
    out: *mut T,
    read: impl FnOnce(&ShapeDef) -> T,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = super::validate::output(out, "out")?;
        *out = read(&w.shape_material(shape.into())?);
        Ok(())
    })
}

/// Shared body of the body getters.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
unsafe fn get_body<T>(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut T,
    read: impl FnOnce(&crate::world::World, crate::pool::Handle) -> Result<T, crate::error::Error>,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = super::validate::output(out, "out")?;
        *out = read(w, body.into())?;
        Ok(())
    })
}

/// Sets a shape's restitution (0..=1). Contacts of the shape use the new value from the next step; the body
/// is woken.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (NaN, infinite, outside 0..=1), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_set_restitution(
    world: *mut HearthWorld,
    shape: HearthShapeId,
    restitution: f32,
) -> HearthResult {
    edit(world, shape, |d| d.restitution = restitution)
}

/// Reads a shape's restitution (0..=1).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_get_restitution(
    world: *const HearthWorld,
    shape: HearthShapeId,
    out: *mut f32,
) -> HearthResult {
    get_shape(world, shape, out, |d| d.restitution)
}

/// Sets a shape's rolling resistance (0..=1, see `HearthShapeDef`). Contacts of the shape use the new value from the next step; the body
/// is woken.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (NaN, infinite, outside 0..=1), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_set_rolling_resistance(
    world: *mut HearthWorld,
    shape: HearthShapeId,
    rolling_resistance: f32,
) -> HearthResult {
    edit(world, shape, |d| d.rolling_resistance = rolling_resistance)
}

/// Reads a shape's rolling resistance (0..=1, see `HearthShapeDef`).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_get_rolling_resistance(
    world: *const HearthWorld,
    shape: HearthShapeId,
    out: *mut f32,
) -> HearthResult {
    get_shape(world, shape, out, |d| d.rolling_resistance)
}

/// Sets a shape's torsional friction (0..=1, see `HearthShapeDef`). Contacts of the shape use the new value from the next step; the body
/// is woken.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (NaN, infinite, outside 0..=1), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_set_torsional_friction(
    world: *mut HearthWorld,
    shape: HearthShapeId,
    torsional_friction: f32,
) -> HearthResult {
    edit(world, shape, |d| d.torsional_friction = torsional_friction)
}

/// Reads a shape's torsional friction (0..=1, see `HearthShapeDef`).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_get_torsional_friction(
    world: *const HearthWorld,
    shape: HearthShapeId,
    out: *mut f32,
) -> HearthResult {
    get_shape(world, shape, out, |d| d.torsional_friction)
}

/// Sets a shape's static and dynamic friction coefficients (each >= 0; a pair uses at most its
/// static value while sliding). Contacts of the shape use them from the next step; the body
/// is woken.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (NaN, infinite, negative), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_set_friction(
    world: *mut HearthWorld,
    shape: HearthShapeId,
    static_friction: f32,
    dynamic_friction: f32,
) -> HearthResult {
    edit(world, shape, |d| {
        d.static_friction = static_friction;
        d.dynamic_friction = dynamic_friction;
    })
}

/// Reads a shape's static and dynamic friction coefficients. Both outputs are written only
/// on success.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (world or either output), `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; the outputs NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_get_friction(
    world: *const HearthWorld,
    shape: HearthShapeId,
    out_static_friction: *mut f32,
    out_dynamic_friction: *mut f32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let s = super::validate::output(out_static_friction, "out_static_friction")?;
        let k = super::validate::output(out_dynamic_friction, "out_dynamic_friction")?;
        let d = w.shape_material(shape.into())?;
        *s = d.static_friction;
        *k = d.dynamic_friction;
        Ok(())
    })
}

/// Sets a shape's density (kg/m³: 0, or 0.001..=1e5). The body's mass, centre of mass and
/// inertia are recomputed from its shapes (unless a mass override is set, see
/// `hearth_body_set_mass_data`); the body is woken. Doubling the density of a body's only
/// shape doubles its mass and inertia exactly.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (NaN, infinite, negative, outside the range),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_set_density(
    world: *mut HearthWorld,
    shape: HearthShapeId,
    density: f32,
) -> HearthResult {
    edit(world, shape, |d| d.density = density)
}

/// Reads a shape's density (kg/m³).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_get_density(
    world: *const HearthWorld,
    shape: HearthShapeId,
    out: *mut f32,
) -> HearthResult {
    get_shape(world, shape, out, |d| d.density)
}

/// Sets a shape's host data (first given in `HearthShapeDef.user_data`). Does not wake the
/// body.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_set_user_data(
    world: *mut HearthWorld,
    shape: HearthShapeId,
    user_data: u64,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.set_shape_user_data(shape.into(), user_data)?))
}

/// Reads a shape's host data.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_shape_get_user_data(
    world: *const HearthWorld,
    shape: HearthShapeId,
    out: *mut u64,
) -> HearthResult {
    get_shape(world, shape, out, |d| d.user_data)
}

/// Sets the multiplier of world gravity for one body (-100..=100; 0 floats, -1 rises). Wakes
/// the body.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (NaN, infinite, out of range), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_set_gravity_scale(
    world: *mut HearthWorld,
    body: HearthBodyId,
    gravity_scale: f32,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.set_gravity_scale(body.into(), gravity_scale)?))
}

/// Reads a body's gravity scale.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_get_gravity_scale(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut f32,
) -> HearthResult {
    get_body(world, body, out, |w, h| w.gravity_scale(h))
}

/// Locks movement along the world X axis (a bit of `locked_axes`).
pub const HEARTH_LOCK_LINEAR_X: u32 = 1;
/// Locks movement along the world Y axis.
pub const HEARTH_LOCK_LINEAR_Y: u32 = 2;
/// Locks movement along the world Z axis (2.5D games).
pub const HEARTH_LOCK_LINEAR_Z: u32 = 4;
/// Locks rotation about the world X axis.
pub const HEARTH_LOCK_ANGULAR_X: u32 = 8;
/// Locks rotation about the world Y axis.
pub const HEARTH_LOCK_ANGULAR_Y: u32 = 16;
/// Locks rotation about the world Z axis.
pub const HEARTH_LOCK_ANGULAR_Z: u32 = 32;
/// Every linear lock bit.
pub const HEARTH_LOCK_LINEAR: u32 = 7;
/// Every angular lock bit (an upright character).
pub const HEARTH_LOCK_ANGULAR: u32 = 56;

/// Locks a body's axes: `locked_axes` is `HEARTH_LOCK_*` bits ORed (world axes; 0 unlocks
/// all). The velocity along each locked axis becomes zero at once and stays exactly zero
/// through contacts, joints, forces, impulses and gravity: the centre of mass does not move
/// along a locked linear axis, the body does not turn about a locked angular axis. Locks act
/// on dynamic bodies (static and kinematic bodies move as told) and are kept through type
/// changes. Wakes the body.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (a bit outside `HEARTH_LOCK_*`), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_set_locked_axes(
    world: *mut HearthWorld,
    body: HearthBodyId,
    locked_axes: u32,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.set_locked_axes(body.into(), locked_axes)?))
}

/// Reads a body's locked axes (`HEARTH_LOCK_*` bits).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_get_locked_axes(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut u32,
) -> HearthResult {
    get_body(world, body, out, |w, h| w.locked_axes(h))
}

/// Overrides a body's mass (1e-9..=1e17 kg), centre of mass (body frame, each coordinate
/// within ±1e5 m) and principal moments of inertia along the body axes (each
/// 1e-18..=1e26 kg·m²). The override is kept through later shape and density changes until
/// `hearth_body_reset_mass_data`. Static and kinematic bodies keep infinite mass; the
/// override applies once they become dynamic. Wakes the body. An impulse J at the centre then
/// changes the velocity by exactly J/mass.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (a number NaN, infinite or out of range; the message names
/// it), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world; `data` NULL or readable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_set_mass_data(
    world: *mut HearthWorld,
    body: HearthBodyId,
    data: *const HearthMassData,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let d = super::validate::input(data, "data")?;
        let data = MassData {
            mass: d.mass,
            center: d.center.into(),
            inertia: d.inertia.into(),
        };
        Ok(w.set_mass_data(body.into(), &data)?)
    })
}

/// Reads a body's mass (kg; 0 for static and kinematic bodies), centre of mass (body frame)
/// and the diagonal of its inertia about the centre of mass in the body frame (kg·m²; a body
/// of rotated shapes also has off-diagonal terms, not reported).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_get_mass_data(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut HearthMassData,
) -> HearthResult {
    get_body(world, body, out, |w, h| {
        let m = w.mass_data(h)?;
        Ok(HearthMassData {
            mass: m.mass,
            center: m.center.into(),
            inertia: m.inertia.into(),
        })
    })
}

/// Drops a mass override: the mass comes from the shapes again. Wakes the body. Does nothing
/// more to a body without an override.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_reset_mass_data(world: *mut HearthWorld, body: HearthBodyId) -> HearthResult {
    guard(|| Ok(world_mut(world)?.reset_mass_data(body.into())?))
}

/// Changes a body's type (`HEARTH_BODY_*`). Becoming static stops it (velocities zero) and
/// takes it out of the awake set; leaving static wakes it. Contacts left without a dynamic
/// body are dropped; its shapes are queued for new pairs at the next step; its mass is
/// recomputed (or the override applied); every body it touches or is jointed to is woken. A
/// pending target transform is dropped.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (an unknown code; a body with a plane must stay static, one
/// with a triangle mesh or heightfield cannot be dynamic), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_set_type(
    world: *mut HearthWorld,
    body: HearthBodyId,
    r#type: u32,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let t = match r#type {
            HEARTH_BODY_STATIC => BodyType::Static,
            HEARTH_BODY_KINEMATIC => BodyType::Kinematic,
            HEARTH_BODY_DYNAMIC => BodyType::Dynamic,
            v => return Err(Failure::invalid(format!("type must be a HEARTH_BODY_* code, got {v}"))),
        };
        Ok(w.set_body_type(body.into(), t)?)
    })
}

/// Disables a body without destroying it: its shapes leave the broad phase (no contacts; the
/// bodies it touched are woken), it is not simulated, and joints to it are inactive (not
/// solved, cannot break) until it is enabled. Its transform, velocities, shapes, mass and
/// joints are kept; setters still work on it. Disabling a disabled body does nothing.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_disable(world: *mut HearthWorld, body: HearthBodyId) -> HearthResult {
    guard(|| Ok(world_mut(world)?.disable_body(body.into())?))
}

/// Enables a disabled body: its shapes return to the broad phase (contacts form at the next
/// step) and a kinematic or dynamic body is woken, moving on with the velocities it had.
/// Enabling an enabled body does nothing.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_enable(world: *mut HearthWorld, body: HearthBodyId) -> HearthResult {
    guard(|| Ok(world_mut(world)?.enable_body(body.into())?))
}

/// Reads whether a body is enabled (true from creation until `hearth_body_disable`).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_body_is_enabled(
    world: *const HearthWorld,
    body: HearthBodyId,
    out: *mut bool,
) -> HearthResult {
    get_body(world, body, out, |w, h| w.is_body_enabled(h))
}

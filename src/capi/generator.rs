//! Generator exports: ids, built-in force generators (gravity, drag, spring, bungee, stiff
//! spring, buoyancy, explosion), contact generators (rod, cable), destroy, attachments.
//! Generators written in C (callbacks and the contact sink) are in `capi/callback.rs`.

use super::error::*;
use super::particle::HearthParticleId;
use super::types::*;
use super::validate::{self, DEF_COOKIE};
use super::world::{world_mut, world_ref, HearthWorld};
use crate::generators::{End, GeneratorDef, GeneratorKind, Spring};
use crate::math::Vec3;
use crate::pool::Handle;

/// Id of a generator inside its world. All-zero is the null id; a destroyed generator's id is
/// stale (`HEARTH_ERROR_INVALID_ID`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HearthGeneratorId {
    /// Slot of the generator.
    pub index: u32,
    /// Generation of the slot (0 only in the null id).
    pub generation: u32,
}

impl From<HearthGeneratorId> for Handle {
    fn from(id: HearthGeneratorId) -> Handle {
        Handle {
            index: id.index,
            generation: id.generation,
        }
    }
}

impl From<Handle> for HearthGeneratorId {
    fn from(h: Handle) -> HearthGeneratorId {
        HearthGeneratorId {
            index: h.index,
            generation: h.generation,
        }
    }
}

/// Extra gravity (`hearth_generator_get_type`).
pub const HEARTH_GENERATOR_GRAVITY: u32 = 0;
/// Drag.
pub const HEARTH_GENERATOR_DRAG: u32 = 1;
/// Spring.
pub const HEARTH_GENERATOR_SPRING: u32 = 2;
/// Bungee (a spring that only pulls).
pub const HEARTH_GENERATOR_BUNGEE: u32 = 3;
/// Stiff spring (exact damped harmonic step).
pub const HEARTH_GENERATOR_STIFF_SPRING: u32 = 4;
/// Buoyancy.
pub const HEARTH_GENERATOR_BUOYANCY: u32 = 5;
/// Explosion.
pub const HEARTH_GENERATOR_EXPLOSION: u32 = 6;
/// Rod (contact generator).
pub const HEARTH_GENERATOR_ROD: u32 = 7;
/// Cable (contact generator).
pub const HEARTH_GENERATOR_CABLE: u32 = 8;
/// User force generator (C callback).
pub const HEARTH_GENERATOR_USER_FORCE: u32 = 9;
/// User contact generator (C callback).
pub const HEARTH_GENERATOR_USER_CONTACT: u32 = 10;

/// One end of a spring, rod or cable: a point on a body (`body` set, `point` in the body
/// frame), a particle (`particle` set, `point` ignored), or a fixed point in the world (both
/// ids null, `point` in world space). Setting both ids is an error.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct HearthLinkEnd {
    /// A body, or the null id.
    pub body: HearthBodyId,
    /// A particle, or the null id.
    pub particle: HearthParticleId,
    /// Body-frame attachment point, or the world anchor point (m).
    pub point: HearthVec3,
}

pub(super) fn is_null_body(id: &HearthBodyId) -> bool {
    id.index == 0 && id.generation == 0
}

fn link_end(e: &HearthLinkEnd, what: &str) -> Result<End, Failure> {
    match (is_null_body(&e.body), e.particle.is_null()) {
        (true, true) => Ok(End::World(e.point.into())),
        (false, true) => Ok(End::Body {
            body: e.body.into(),
            local: e.point.into(),
        }),
        (true, false) => Ok(End::Particle(e.particle.into())),
        (false, false) => Err(Failure::invalid(format!("{what}: set a body or a particle, not both"))),
    }
}

/// Shared body of the create functions.
///
/// # Safety
/// Pointers must be NULL or valid.
pub(super) unsafe fn create<D>(
    world: *mut HearthWorld,
    def: *const D,
    out_generator: *mut HearthGeneratorId,
    convert: impl FnOnce(&D) -> Result<GeneratorDef, Failure>,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let d = validate::input(def, "def")?;
        let out = validate::output(out_generator, "out_generator")?;
        let def = convert(d)?;
        *out = w.create_generator(&def)?.into();
        Ok(())
    })
}

// ------------------------------------------------------------------------------ gravity

/// Extra gravity on every attached body and particle, on top of world gravity.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthGravityGeneratorDef {
    /// Acceleration (m/s²). Default (0, -9.81, 0).
    pub acceleration: HearthVec3,
    /// Set by `hearth_gravity_generator_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: (0, -9.81, 0).
#[no_mangle]
pub extern "C" fn hearth_gravity_generator_def_default() -> HearthGravityGeneratorDef {
    HearthGravityGeneratorDef {
        acceleration: Vec3::new(0.0, -9.81, 0.0).into(),
        internal_value: DEF_COOKIE,
    }
}

/// Creates an extra-gravity force generator; attach bodies and particles to it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (def not from its
/// default, NaN/infinite), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_gravity(
    world: *mut HearthWorld,
    def: *const HearthGravityGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| {
        validate::cookie(d.internal_value, "hearth_gravity_generator_def")?;
        Ok(GeneratorDef::Gravity {
            acceleration: d.acceleration.into(),
        })
    })
}

// --------------------------------------------------------------------------------- drag

/// Drag `-v̂ (k1 |v| + k2 |v|²)` on every attached body (at its centre of mass) and particle.
/// Any finite coefficients are stable: within a step, drag may stop a motion but never turn
/// it back (the force is capped there).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthDragGeneratorDef {
    /// Linear coefficient (N·s/m, >= 0). Default 0.1.
    pub k1: f32,
    /// Quadratic coefficient (N·s²/m², >= 0). Default 0.01.
    pub k2: f32,
    /// Set by `hearth_drag_generator_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: k1 = 0.1, k2 = 0.01.
#[no_mangle]
pub extern "C" fn hearth_drag_generator_def_default() -> HearthDragGeneratorDef {
    HearthDragGeneratorDef {
        k1: 0.1,
        k2: 0.01,
        internal_value: DEF_COOKIE,
    }
}

/// Creates a drag force generator; attach bodies and particles to it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (def not from its
/// default, negative or NaN coefficients), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_drag(
    world: *mut HearthWorld,
    def: *const HearthDragGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| {
        validate::cookie(d.internal_value, "hearth_drag_generator_def")?;
        Ok(GeneratorDef::Drag { k1: d.k1, k2: d.k2 })
    })
}

// ------------------------------------------------------------------------------ springs

/// A spring from each attached body or particle to `other`. With `other` a world point it is
/// an anchored spring; with `other` a dynamic body or a particle that end feels the equal
/// and opposite force (a spring between two objects: attach one, name the other).
///
/// Between bodies and world points the spring acts at every sub-step, from the poses then,
/// so an attachment off a body's centre turns the body without pumping energy into it.
/// Any finite stiffness and damping are stable: `m` being the ends' combined effective mass
/// at the attachment points (which includes the bodies' turning), a spring stiffer than
/// `m / h²` (`h` the sub-step; `m / dt²` with a particle end) acts as if it were that stiff,
/// and damping above `m / h` (`m / dt`) as that.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthSpringGeneratorDef {
    /// The other end. Default: the world origin.
    pub other: HearthLinkEnd,
    /// Attachment point on each attached body, body frame (m). Default (0, 0, 0).
    pub local_point: HearthVec3,
    /// Rest length (m, >= 0). Default 1.
    pub rest_length: f32,
    /// Stiffness (N/m, >= 0). Default 100.
    pub stiffness: f32,
    /// Damping along the spring (N·s/m, >= 0). Default 0.
    pub damping: f32,
    /// Set by `hearth_spring_generator_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: anchored at the world origin, rest length 1 m, 100 N/m, no damping.
#[no_mangle]
pub extern "C" fn hearth_spring_generator_def_default() -> HearthSpringGeneratorDef {
    HearthSpringGeneratorDef {
        other: HearthLinkEnd::default(),
        local_point: HearthVec3::default(),
        rest_length: 1.0,
        stiffness: 100.0,
        damping: 0.0,
        internal_value: DEF_COOKIE,
    }
}

fn spring_def(d: &HearthSpringGeneratorDef) -> Result<Spring, Failure> {
    validate::cookie(d.internal_value, "hearth_spring_generator_def")?;
    Ok(Spring {
        other: link_end(&d.other, "other")?,
        local_point: d.local_point.into(),
        rest_length: d.rest_length,
        stiffness: d.stiffness,
        damping: d.damping,
    })
}

/// Creates a spring (pushes and pulls); attach the bodies and particles it acts on.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (the other end is not a live
/// body or particle), `HEARTH_ERROR_INVALID_ARGUMENT` (def not from its default, negative or
/// NaN numbers, both ids set in `other`), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_spring(
    world: *mut HearthWorld,
    def: *const HearthSpringGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| Ok(GeneratorDef::Spring(spring_def(d)?)))
}

/// Creates a bungee: a spring that only pulls, when longer than its rest length (no force,
/// no damping, while slack). Takes a `HearthSpringGeneratorDef`.
///
/// Errors: as `hearth_generator_create_spring`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_bungee(
    world: *mut HearthWorld,
    def: *const HearthSpringGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| Ok(GeneratorDef::Bungee(spring_def(d)?)))
}

/// A stiff damped spring (rest length 0) from each attached object to `anchor`, whose force
/// makes the step reproduce the exact damped harmonic motion: the discrete motion has the
/// continuous system's frequency and decay for any finite stiffness and damping, where an
/// explicit spring would explode. For a point off a body's centre the motion is that of the
/// point's effective mass (which includes the body's turning) in its most mobile direction.
/// The anchor end is followed but feels no reaction.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthStiffSpringGeneratorDef {
    /// The anchor. Default: the world origin.
    pub anchor: HearthLinkEnd,
    /// Attachment point on each attached body, body frame (m). Default (0, 0, 0).
    pub local_point: HearthVec3,
    /// Stiffness (N/m, > 0). Default 1000.
    pub stiffness: f32,
    /// Damping (N·s/m, >= 0). Default 10.
    pub damping: f32,
    /// Set by `hearth_stiff_spring_generator_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: anchored at the world origin, 1000 N/m, 10 N·s/m.
#[no_mangle]
pub extern "C" fn hearth_stiff_spring_generator_def_default() -> HearthStiffSpringGeneratorDef {
    HearthStiffSpringGeneratorDef {
        anchor: HearthLinkEnd::default(),
        local_point: HearthVec3::default(),
        stiffness: 1000.0,
        damping: 10.0,
        internal_value: DEF_COOKIE,
    }
}

/// Creates a stiff spring; attach the bodies and particles it acts on.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (anchor),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (def not from its default, stiffness <= 0, negative or NaN
/// numbers), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_stiff_spring(
    world: *mut HearthWorld,
    def: *const HearthStiffSpringGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| {
        validate::cookie(d.internal_value, "hearth_stiff_spring_generator_def")?;
        Ok(GeneratorDef::StiffSpring {
            anchor: link_end(&d.anchor, "anchor")?,
            local_point: d.local_point.into(),
            stiffness: d.stiffness,
            damping: d.damping,
        })
    })
}

// ----------------------------------------------------------------------------- buoyancy

/// Buoyancy of a liquid below the plane `dot(surface_normal, p) = surface_offset`: a force
/// `liquid_density · volume · |g| · f` along the normal, where `f`, the submerged fraction,
/// rises linearly from 0 when the centre of buoyancy is `max_depth` above the surface to 1
/// when it is `max_depth` below. At rest `f = mass / (liquid_density · volume)`
/// (Archimedes).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthBuoyancyGeneratorDef {
    /// Up out of the liquid (need not be unit length, must not be zero). Default +Y.
    pub surface_normal: HearthVec3,
    /// Height of the surface along the normal (m). Default 0.
    pub surface_offset: f32,
    /// Half the depth over which an object goes from dry to submerged (m, > 0). Default 0.5.
    pub max_depth: f32,
    /// Displaced volume when submerged (m³, >= 0). Default 0.001.
    pub volume: f32,
    /// Density of the liquid (kg/m³, >= 0). Default 1000 (water).
    pub liquid_density: f32,
    /// Centre of buoyancy on attached bodies, body frame (m). Default (0, 0, 0).
    pub local_point: HearthVec3,
    /// Set by `hearth_buoyancy_generator_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: water (1000 kg/m³) below y = 0, max depth 0.5 m, volume 1 litre.
#[no_mangle]
pub extern "C" fn hearth_buoyancy_generator_def_default() -> HearthBuoyancyGeneratorDef {
    HearthBuoyancyGeneratorDef {
        surface_normal: Vec3::Y.into(),
        surface_offset: 0.0,
        max_depth: 0.5,
        volume: 0.001,
        liquid_density: 1000.0,
        local_point: HearthVec3::default(),
        internal_value: DEF_COOKIE,
    }
}

/// Creates a buoyancy force generator; attach bodies and particles to it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (def not from its
/// default, zero normal, max_depth <= 0, negative or NaN numbers), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_buoyancy(
    world: *mut HearthWorld,
    def: *const HearthBuoyancyGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| {
        validate::cookie(d.internal_value, "hearth_buoyancy_generator_def")?;
        Ok(GeneratorDef::Buoyancy {
            normal: d.surface_normal.into(),
            surface: d.surface_offset,
            max_depth: d.max_depth,
            volume: d.volume,
            liquid_density: d.liquid_density,
            local_point: d.local_point.into(),
        })
    })
}

// ---------------------------------------------------------------------------- explosion

/// An explosion at `center`. In the first step after creation, objects within
/// `blast_radius` get an impulse `blast_impulse · (1 - d / blast_radius)` away from the
/// centre; then a shock wave, a shell `shock_thickness` thick expanding at `shock_speed` up
/// to `max_radius`, pushes objects inside it with up to `shock_force` (falling off linearly
/// across the shell). Forces act at centres of mass.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthExplosionGeneratorDef {
    /// Where it goes off (m, each coordinate within ±1e5).
    pub center: HearthVec3,
    /// Reach of the blast (m, 0..=1e4). Default 5.
    pub blast_radius: f32,
    /// Impulse at the centre (N·s, 0..=1e10). Default 50.
    pub blast_impulse: f32,
    /// Speed of the shock wave (m/s, 0..=1e4). Default 20.
    pub shock_speed: f32,
    /// Thickness of the shell (m, 0..=1e4). Default 1.
    pub shock_thickness: f32,
    /// Peak force of the shock wave (N, 0..=1e12). Default 100.
    pub shock_force: f32,
    /// The wave stops at this radius (m, 0..=1e4). Default 20.
    pub max_radius: f32,
    /// 1 (default): acts on every body and particle in range; 0: only on attached ones.
    pub affect_all: u8,
    /// Set by `hearth_explosion_generator_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: at the origin, blast 50 N·s within 5 m, a 1 m shock wave at 20 m/s with 100 N
/// out to 20 m, acting on everything in range.
#[no_mangle]
pub extern "C" fn hearth_explosion_generator_def_default() -> HearthExplosionGeneratorDef {
    HearthExplosionGeneratorDef {
        center: HearthVec3::default(),
        blast_radius: 5.0,
        blast_impulse: 50.0,
        shock_speed: 20.0,
        shock_thickness: 1.0,
        shock_force: 100.0,
        max_radius: 20.0,
        affect_all: 1,
        internal_value: DEF_COOKIE,
    }
}

/// Creates an explosion. It is spent once its wave passes `max_radius`; destroy it then.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ARGUMENT` (def not from its
/// default, a number outside its range or NaN, flag not 0/1), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_explosion(
    world: *mut HearthWorld,
    def: *const HearthExplosionGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| {
        validate::cookie(d.internal_value, "hearth_explosion_generator_def")?;
        Ok(GeneratorDef::Explosion {
            center: d.center.into(),
            blast_radius: d.blast_radius,
            blast_impulse: d.blast_impulse,
            shock_speed: d.shock_speed,
            shock_thickness: d.shock_thickness,
            shock_force: d.shock_force,
            max_radius: d.max_radius,
            affect_all: validate::flag(d.affect_all, "affect_all")?,
        })
    })
}

// -------------------------------------------------------------------------- rods, cables

/// A rod: ends `a` and `b` stay `length` apart (it pushes and pulls). Between bodies (or a
/// body and the world) the rigid solver resolves it with the collision contacts; with a
/// particle end it is solved in the particle stage, exactly together with the other rods.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthRodGeneratorDef {
    /// First end. Default: the world origin.
    pub a: HearthLinkEnd,
    /// Second end. Default: the world origin.
    pub b: HearthLinkEnd,
    /// Length (m, >= 0). Default 1.
    pub length: f32,
    /// Set by `hearth_rod_generator_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: both ends at the world origin (set at least one), length 1 m.
#[no_mangle]
pub extern "C" fn hearth_rod_generator_def_default() -> HearthRodGeneratorDef {
    HearthRodGeneratorDef {
        a: HearthLinkEnd::default(),
        b: HearthLinkEnd::default(),
        length: 1.0,
        internal_value: DEF_COOKIE,
    }
}

/// Creates a rod. Rods and cables act on their ends and take no attachments.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (an end is not a live body
/// or particle), `HEARTH_ERROR_INVALID_ARGUMENT` (def not from its default, negative or NaN
/// length, both ids set in an end, two world ends, the same end twice),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_rod(
    world: *mut HearthWorld,
    def: *const HearthRodGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| {
        validate::cookie(d.internal_value, "hearth_rod_generator_def")?;
        Ok(GeneratorDef::Rod {
            a: link_end(&d.a, "a")?,
            b: link_end(&d.b, "b")?,
            length: d.length,
        })
    })
}

/// A cable: ends `a` and `b` stay at most `max_length` apart (it only pulls, and goes slack
/// when they come closer); a cable snapping taut bounces with `restitution`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthCableGeneratorDef {
    /// First end. Default: the world origin.
    pub a: HearthLinkEnd,
    /// Second end. Default: the world origin.
    pub b: HearthLinkEnd,
    /// Maximum length (m, >= 0). Default 1.
    pub max_length: f32,
    /// Bounce when it snaps taut (>= 0). Default 0.
    pub restitution: f32,
    /// Set by `hearth_cable_generator_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: both ends at the world origin (set at least one), 1 m, no bounce.
#[no_mangle]
pub extern "C" fn hearth_cable_generator_def_default() -> HearthCableGeneratorDef {
    HearthCableGeneratorDef {
        a: HearthLinkEnd::default(),
        b: HearthLinkEnd::default(),
        max_length: 1.0,
        restitution: 0.0,
        internal_value: DEF_COOKIE,
    }
}

/// Creates a cable.
///
/// Errors: as `hearth_generator_create_rod`, and negative restitution.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_create_cable(
    world: *mut HearthWorld,
    def: *const HearthCableGeneratorDef,
    out_generator: *mut HearthGeneratorId,
) -> HearthResult {
    create(world, def, out_generator, |d| {
        validate::cookie(d.internal_value, "hearth_cable_generator_def")?;
        Ok(GeneratorDef::Cable {
            a: link_end(&d.a, "a")?,
            b: link_end(&d.b, "b")?,
            max_length: d.max_length,
            restitution: d.restitution,
        })
    })
}

// -------------------------------------------------------------- destroy, attach, detach

/// Destroys a generator; its id becomes stale.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_destroy(
    world: *mut HearthWorld,
    generator: HearthGeneratorId,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.destroy_generator(generator.into())?))
}

/// Makes a force or user generator act on a body. Destroying the body detaches it.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (generator or body),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (already attached; rods and cables take no attachments),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_attach_body(
    world: *mut HearthWorld,
    generator: HearthGeneratorId,
    body: HearthBodyId,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.attach_body(generator.into(), body.into())?))
}

/// Stops a generator acting on a body.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (generator, or a body not
/// attached to it), `HEARTH_ERROR_INVALID_ARGUMENT` (rods and cables),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_detach_body(
    world: *mut HearthWorld,
    generator: HearthGeneratorId,
    body: HearthBodyId,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.detach_body(generator.into(), body.into())?))
}

/// Makes a force or user generator act on a particle. A particle that expires or is
/// destroyed is detached.
///
/// Errors: as `hearth_generator_attach_body`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_attach_particle(
    world: *mut HearthWorld,
    generator: HearthGeneratorId,
    particle: HearthParticleId,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.attach_particle(generator.into(), particle.into())?))
}

/// Attaches `count` particles at once: all or nothing (every id is checked first).
/// `count == 0` succeeds and may pass NULL.
///
/// Errors: as `hearth_generator_attach_body`; `HEARTH_ERROR_INVALID_ARGUMENT` also for an id
/// given twice.
///
/// # Safety
/// `particles` must hold `count` ids.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_attach_particles(
    world: *mut HearthWorld,
    generator: HearthGeneratorId,
    particles: *const HearthParticleId,
    count: usize,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        if count == 0 {
            w.generator(generator.into())?;
            return Ok(());
        }
        if particles.is_null() {
            return Err(Failure::null("particles"));
        }
        let ids: Vec<Handle> = std::slice::from_raw_parts(particles, count)
            .iter()
            .map(|&p| p.into())
            .collect();
        Ok(w.attach_particles(generator.into(), &ids)?)
    })
}

/// Stops a generator acting on a particle.
///
/// Errors: as `hearth_generator_detach_body`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_detach_particle(
    world: *mut HearthWorld,
    generator: HearthGeneratorId,
    particle: HearthParticleId,
) -> HearthResult {
    guard(|| Ok(world_mut(world)?.detach_particle(generator.into(), particle.into())?))
}

/// Reads how many live bodies and particles are attached to a generator.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; outputs NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_get_attachment_count(
    world: *const HearthWorld,
    generator: HearthGeneratorId,
    out_body_count: *mut u32,
    out_particle_count: *mut u32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let bodies = validate::output(out_body_count, "out_body_count")?;
        let particles = validate::output(out_particle_count, "out_particle_count")?;
        let (b, p) = w.generator_attachment_counts(generator.into())?;
        *bodies = b as u32;
        *particles = p as u32;
        Ok(())
    })
}

/// Reads a generator's type (`HEARTH_GENERATOR_*`).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_type` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_generator_get_type(
    world: *const HearthWorld,
    generator: HearthGeneratorId,
    out_type: *mut u32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out_type, "out_type")?;
        *out = match w.generator(generator.into())?.def.kind() {
            GeneratorKind::Gravity => HEARTH_GENERATOR_GRAVITY,
            GeneratorKind::Drag => HEARTH_GENERATOR_DRAG,
            GeneratorKind::Spring => HEARTH_GENERATOR_SPRING,
            GeneratorKind::Bungee => HEARTH_GENERATOR_BUNGEE,
            GeneratorKind::StiffSpring => HEARTH_GENERATOR_STIFF_SPRING,
            GeneratorKind::Buoyancy => HEARTH_GENERATOR_BUOYANCY,
            GeneratorKind::Explosion => HEARTH_GENERATOR_EXPLOSION,
            GeneratorKind::Rod => HEARTH_GENERATOR_ROD,
            GeneratorKind::Cable => HEARTH_GENERATOR_CABLE,
            GeneratorKind::ExternalForce => HEARTH_GENERATOR_USER_FORCE,
            GeneratorKind::ExternalContact => HEARTH_GENERATOR_USER_CONTACT,
        };
        Ok(())
    })
}

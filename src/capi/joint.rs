//! Joint exports: ids, one def and create function per joint type (ball, hinge, fixed,
//! distance, slider), destroy, motor / limits / cone / spring get and set, applied force and
//! torque, breaking.
//!
//! Every joint connects body A to body B, or to the world when `body_b` is the null id. Its
//! frames give the anchor and axes on each body (relative to the body origin; for the world,
//! in world space). The joint axis is each frame's local Z axis. Destroying a body destroys
//! its joints.

use super::error::*;
use super::types::*;
use super::validate::{self, DEF_COOKIE};
use super::world::{world_mut, world_ref, HearthWorld};
use crate::dynamics::joints::{BallParams, DistanceParams, HingeParams, JointDef, JointKind, SliderParams};
use crate::math::{Quat, Transform, Vec3};
use crate::pool::Handle;

/// Id of a joint inside its world. All-zero is the null id; a destroyed joint's id is stale
/// (`HEARTH_ERROR_INVALID_ID`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HearthJointId {
    /// Slot of the joint.
    pub index: u32,
    /// Generation of the slot (0 only in the null id).
    pub generation: u32,
}

impl From<HearthJointId> for Handle {
    fn from(id: HearthJointId) -> Handle {
        Handle {
            index: id.index,
            generation: id.generation,
        }
    }
}

impl From<Handle> for HearthJointId {
    fn from(h: Handle) -> HearthJointId {
        HearthJointId {
            index: h.index,
            generation: h.generation,
        }
    }
}

/// Ball-and-socket joint (`hearth_joint_get_type`).
pub const HEARTH_JOINT_BALL: u32 = 0;
/// Hinge (revolute) joint.
pub const HEARTH_JOINT_HINGE: u32 = 1;
/// Fixed (weld) joint.
pub const HEARTH_JOINT_FIXED: u32 = 2;
/// Distance joint.
pub const HEARTH_JOINT_DISTANCE: u32 = 3;
/// Slider (prismatic) joint.
pub const HEARTH_JOINT_SLIDER: u32 = 4;

/// The fields every joint def starts with. The frames may be any poses: frames that do not
/// meet where the bodies are (anchors apart, axes turned) are pulled together in the first
/// steps; that pull does work, after it the joint adds no energy.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthJointBase {
    /// Body A (required, any type; at least one of the two bodies must not be static).
    pub body_a: HearthBodyId,
    /// Body B, or the null id to join body A to the world.
    pub body_b: HearthBodyId,
    /// Joint frame on A, relative to A's origin. Default identity.
    pub frame_a: HearthTransform,
    /// Joint frame on B relative to B's origin, or in world space when `body_b` is null.
    /// Default identity.
    pub frame_b: HearthTransform,
    /// 1 to let the two bodies collide with each other; 0 (default) filters the pair and
    /// destroys contacts between them when the joint is created.
    pub collide_connected: u8,
    /// Force (N, > 0) above which the joint breaks. Default `FLT_MAX` (never).
    pub break_force: f32,
    /// Torque (N·m, > 0) above which the joint breaks. Default `FLT_MAX` (never).
    pub break_torque: f32,
}

fn base_default() -> HearthJointBase {
    let identity = HearthTransform::from(Transform::IDENTITY);
    HearthJointBase {
        body_a: HearthBodyId::default(),
        body_b: HearthBodyId::default(),
        frame_a: identity,
        frame_b: identity,
        collide_connected: 0,
        break_force: f32::MAX,
        break_torque: f32::MAX,
    }
}

fn core_def(base: &HearthJointBase, kind: JointKind) -> Result<JointDef, Failure> {
    Ok(JointDef {
        kind,
        body_a: base.body_a.into(),
        body_b: base.body_b.into(),
        frame_a: Transform::new(base.frame_a.position.into(), Quat::from(base.frame_a.rotation)),
        frame_b: Transform::new(base.frame_b.position.into(), Quat::from(base.frame_b.rotation)),
        collide_connected: validate::flag(base.collide_connected, "collide_connected")?,
        break_force: base.break_force,
        break_torque: base.break_torque,
    })
}

/// Shared body of the create functions.
///
/// # Safety
/// Pointers must be NULL or valid.
unsafe fn create<D>(
    world: *mut HearthWorld,
    def: *const D,
    out_joint: *mut HearthJointId,
    convert: impl FnOnce(&D) -> Result<JointDef, Failure>,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let d = validate::input(def, "def")?;
        let out = validate::output(out_joint, "out_joint")?;
        let def = convert(d)?;
        *out = w.create_joint(&def)?.into();
        Ok(())
    })
}

// --------------------------------------------------------------------------------- ball

/// Ball-and-socket: the anchors coincide; optional cone (swing) and twist limits about Z.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthBallJointDef {
    /// Bodies, frames, collision, breaking.
    pub base: HearthJointBase,
    /// 1 to keep B's Z axis within `swing_limit` of A's. Default 0.
    pub enable_swing_limit: u8,
    /// Cone half-angle (rad, 0..=π). Default π/4.
    pub swing_limit: f32,
    /// 1 to keep B's twist about Z within `lower_twist..=upper_twist`. Default 0. Twist is
    /// not defined at a half-turn swing, so a twist limit also keeps the swing within 0.9π
    /// (162°).
    pub enable_twist_limit: u8,
    /// Twist limits (rad, -π..=π, lower <= upper). Defaults -π/4 and π/4.
    pub lower_twist: f32,
    /// Upper twist limit (rad).
    pub upper_twist: f32,
    /// Set by `hearth_ball_joint_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: identity frames, no limits, unbreakable, no collision between the bodies.
#[no_mangle]
pub extern "C" fn hearth_ball_joint_def_default() -> HearthBallJointDef {
    let p = BallParams::default();
    HearthBallJointDef {
        base: base_default(),
        enable_swing_limit: p.enable_swing_limit as u8,
        swing_limit: p.swing_limit,
        enable_twist_limit: p.enable_twist_limit as u8,
        lower_twist: p.lower_twist,
        upper_twist: p.upper_twist,
        internal_value: DEF_COOKIE,
    }
}

/// Creates a ball-and-socket joint. Wakes both bodies.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID` (a body),
/// `HEARTH_ERROR_INVALID_ARGUMENT` (def not from its default, NaN or infinite numbers, zero
/// quaternion, flag not 0/1, limits out of range, A equal to B, both bodies static),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_create_ball(
    world: *mut HearthWorld,
    def: *const HearthBallJointDef,
    out_joint: *mut HearthJointId,
) -> HearthResult {
    create(world, def, out_joint, |d| {
        validate::cookie(d.internal_value, "hearth_ball_joint_def")?;
        let kind = JointKind::Ball(BallParams {
            enable_swing_limit: validate::flag(d.enable_swing_limit, "enable_swing_limit")?,
            swing_limit: d.swing_limit,
            enable_twist_limit: validate::flag(d.enable_twist_limit, "enable_twist_limit")?,
            lower_twist: d.lower_twist,
            upper_twist: d.upper_twist,
        });
        core_def(&d.base, kind)
    })
}

// -------------------------------------------------------------------------------- hinge

/// Hinge: the anchors coincide and the Z axes stay aligned; B turns about Z. The angle is
/// B's turn relative to A (0 where the frames coincide); the motor speed is B's angular
/// speed relative to A about Z.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthHingeJointDef {
    /// Bodies, frames, collision, breaking.
    pub base: HearthJointBase,
    /// 1 to keep the angle within `lower..=upper`. Default 0.
    pub enable_limit: u8,
    /// Lower angle limit (rad, -π..=π). Default -π/2.
    pub lower: f32,
    /// Upper angle limit (rad, -π..=π, >= lower). Default π/2.
    pub upper: f32,
    /// 1 to drive the hinge at `motor_speed`. Default 0.
    pub enable_motor: u8,
    /// Target speed (rad/s). Default 0.
    pub motor_speed: f32,
    /// Largest motor torque (N·m, >= 0). Default 0.
    pub max_motor_torque: f32,
    /// 1 for a spring toward angle 0. Default 0.
    pub enable_spring: u8,
    /// Spring frequency (Hz, >= 0; 0 exerts no force). Default 0.
    pub spring_hertz: f32,
    /// Spring damping ratio (>= 0). Default 0.
    pub spring_damping_ratio: f32,
    /// Set by `hearth_hinge_joint_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: identity frames, no limit, motor or spring; unbreakable.
#[no_mangle]
pub extern "C" fn hearth_hinge_joint_def_default() -> HearthHingeJointDef {
    let p = HingeParams::default();
    HearthHingeJointDef {
        base: base_default(),
        enable_limit: p.enable_limit as u8,
        lower: p.lower,
        upper: p.upper,
        enable_motor: p.enable_motor as u8,
        motor_speed: p.motor_speed,
        max_motor_torque: p.max_motor_torque,
        enable_spring: p.enable_spring as u8,
        spring_hertz: p.spring_hertz,
        spring_damping_ratio: p.spring_damping_ratio,
        internal_value: DEF_COOKIE,
    }
}

/// Creates a hinge joint. Wakes both bodies.
///
/// Errors: as `hearth_joint_create_ball`, and negative motor torque or spring values.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_create_hinge(
    world: *mut HearthWorld,
    def: *const HearthHingeJointDef,
    out_joint: *mut HearthJointId,
) -> HearthResult {
    create(world, def, out_joint, |d| {
        validate::cookie(d.internal_value, "hearth_hinge_joint_def")?;
        let kind = JointKind::Hinge(HingeParams {
            enable_limit: validate::flag(d.enable_limit, "enable_limit")?,
            lower: d.lower,
            upper: d.upper,
            enable_motor: validate::flag(d.enable_motor, "enable_motor")?,
            motor_speed: d.motor_speed,
            max_motor_torque: d.max_motor_torque,
            enable_spring: validate::flag(d.enable_spring, "enable_spring")?,
            spring_hertz: d.spring_hertz,
            spring_damping_ratio: d.spring_damping_ratio,
        });
        core_def(&d.base, kind)
    })
}

// -------------------------------------------------------------------------------- fixed

/// Fixed (weld): the frames stay together.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthFixedJointDef {
    /// Bodies, frames, collision, breaking.
    pub base: HearthJointBase,
    /// Set by `hearth_fixed_joint_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: identity frames, unbreakable.
#[no_mangle]
pub extern "C" fn hearth_fixed_joint_def_default() -> HearthFixedJointDef {
    HearthFixedJointDef {
        base: base_default(),
        internal_value: DEF_COOKIE,
    }
}

/// Creates a fixed joint. Wakes both bodies.
///
/// Errors: as `hearth_joint_create_ball`.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_create_fixed(
    world: *mut HearthWorld,
    def: *const HearthFixedJointDef,
    out_joint: *mut HearthJointId,
) -> HearthResult {
    create(world, def, out_joint, |d| {
        validate::cookie(d.internal_value, "hearth_fixed_joint_def")?;
        core_def(&d.base, JointKind::Fixed)
    })
}

// ----------------------------------------------------------------------------- distance

/// Distance: the frames' origins (the anchors) stay `length` apart. With the spring off
/// the joint is rigid; with it on, the spring pulls toward `length` and the limits (when
/// enabled) bound the length — a spring of 0 Hz is a rope, free within the limits.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthDistanceJointDef {
    /// Bodies, frames, collision, breaking.
    pub base: HearthJointBase,
    /// Rest length (m, >= 0). Default 1.
    pub length: f32,
    /// 1 to keep the length within `min_length..=max_length` (with the spring on). Default 0.
    pub enable_limit: u8,
    /// Shortest length (m, >= 0). Default 0.
    pub min_length: f32,
    /// Longest length (m, >= min_length). Default 1e6.
    pub max_length: f32,
    /// 1 for a spring instead of a rigid rod. Default 0.
    pub enable_spring: u8,
    /// Spring frequency (Hz, >= 0). Default 0.
    pub spring_hertz: f32,
    /// Spring damping ratio (>= 0). Default 0.
    pub spring_damping_ratio: f32,
    /// Set by `hearth_distance_joint_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: length 1, rigid, no limits.
#[no_mangle]
pub extern "C" fn hearth_distance_joint_def_default() -> HearthDistanceJointDef {
    let p = DistanceParams::default();
    HearthDistanceJointDef {
        base: base_default(),
        length: p.length,
        enable_limit: p.enable_limit as u8,
        min_length: p.min_length,
        max_length: p.max_length,
        enable_spring: p.enable_spring as u8,
        spring_hertz: p.spring_hertz,
        spring_damping_ratio: p.spring_damping_ratio,
        internal_value: DEF_COOKIE,
    }
}

/// Creates a distance joint. Wakes both bodies.
///
/// Errors: as `hearth_joint_create_ball`, and negative lengths or spring values.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_create_distance(
    world: *mut HearthWorld,
    def: *const HearthDistanceJointDef,
    out_joint: *mut HearthJointId,
) -> HearthResult {
    create(world, def, out_joint, |d| {
        validate::cookie(d.internal_value, "hearth_distance_joint_def")?;
        let kind = JointKind::Distance(DistanceParams {
            length: d.length,
            enable_limit: validate::flag(d.enable_limit, "enable_limit")?,
            min_length: d.min_length,
            max_length: d.max_length,
            enable_spring: validate::flag(d.enable_spring, "enable_spring")?,
            spring_hertz: d.spring_hertz,
            spring_damping_ratio: d.spring_damping_ratio,
        });
        core_def(&d.base, kind)
    })
}

// ------------------------------------------------------------------------------- slider

/// Slider (prismatic): B keeps A's orientation and moves only along A's Z axis. The
/// translation is B's anchor along A's Z from A's anchor; the motor speed is B's speed
/// relative to A along Z.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct HearthSliderJointDef {
    /// Bodies, frames, collision, breaking.
    pub base: HearthJointBase,
    /// 1 to keep the translation within `lower..=upper`. Default 0.
    pub enable_limit: u8,
    /// Lower translation limit (m). Default -1.
    pub lower: f32,
    /// Upper translation limit (m, >= lower). Default 1.
    pub upper: f32,
    /// 1 to drive the slider at `motor_speed`. Default 0.
    pub enable_motor: u8,
    /// Target speed (m/s). Default 0.
    pub motor_speed: f32,
    /// Largest motor force (N, >= 0). Default 0.
    pub max_motor_force: f32,
    /// Set by `hearth_slider_joint_def_default()`; do not change.
    pub internal_value: u32,
}

/// Defaults: identity frames, no limit or motor; unbreakable.
#[no_mangle]
pub extern "C" fn hearth_slider_joint_def_default() -> HearthSliderJointDef {
    let p = SliderParams::default();
    HearthSliderJointDef {
        base: base_default(),
        enable_limit: p.enable_limit as u8,
        lower: p.lower,
        upper: p.upper,
        enable_motor: p.enable_motor as u8,
        motor_speed: p.motor_speed,
        max_motor_force: p.max_motor_force,
        internal_value: DEF_COOKIE,
    }
}

/// Creates a slider joint. Wakes both bodies.
///
/// Errors: as `hearth_joint_create_ball`, and a negative motor force.
///
/// # Safety
/// Pointers must be NULL or valid.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_create_slider(
    world: *mut HearthWorld,
    def: *const HearthSliderJointDef,
    out_joint: *mut HearthJointId,
) -> HearthResult {
    create(world, def, out_joint, |d| {
        validate::cookie(d.internal_value, "hearth_slider_joint_def")?;
        let kind = JointKind::Slider(SliderParams {
            enable_limit: validate::flag(d.enable_limit, "enable_limit")?,
            lower: d.lower,
            upper: d.upper,
            enable_motor: validate::flag(d.enable_motor, "enable_motor")?,
            motor_speed: d.motor_speed,
            max_motor_force: d.max_motor_force,
        });
        core_def(&d.base, kind)
    })
}

// ------------------------------------------------------------------ destroy and queries

/// Destroys a joint (broken or not) and wakes its bodies; its id becomes stale. Destroying a
/// body destroys its joints too.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`, `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_destroy(world: *mut HearthWorld, joint: HearthJointId) -> HearthResult {
    guard(|| Ok(world_mut(world)?.destroy_joint(joint.into())?))
}

/// Reads a joint's type (`HEARTH_JOINT_*`).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_type` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_get_type(
    world: *const HearthWorld,
    joint: HearthJointId,
    out_type: *mut u32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out_type, "out_type")?;
        *out = match w.joint(joint.into())?.def.kind {
            JointKind::Ball(_) => HEARTH_JOINT_BALL,
            JointKind::Hinge(_) => HEARTH_JOINT_HINGE,
            JointKind::Fixed => HEARTH_JOINT_FIXED,
            JointKind::Distance(_) => HEARTH_JOINT_DISTANCE,
            JointKind::Slider(_) => HEARTH_JOINT_SLIDER,
        };
        Ok(())
    })
}

/// Reads a joint's bodies; `*out_body_b` is the null id for a joint to the world.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; outputs NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_get_bodies(
    world: *const HearthWorld,
    joint: HearthJointId,
    out_body_a: *mut HearthBodyId,
    out_body_b: *mut HearthBodyId,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let a = validate::output(out_body_a, "out_body_a")?;
        let b = validate::output(out_body_b, "out_body_b")?;
        let def = w.joint(joint.into())?.def;
        *a = def.body_a.into();
        *b = def.body_b.into();
        Ok(())
    })
}

/// Sets the motor of a hinge (speed in rad/s, `max` torque in N·m) or slider (m/s, N). The
/// speed is B's relative to A. Wakes the bodies.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (not a hinge or slider, flag not 0/1, NaN, negative max),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_set_motor(
    world: *mut HearthWorld,
    joint: HearthJointId,
    enable: u8,
    speed: f32,
    max: f32,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let enable = validate::flag(enable, "enable")?;
        Ok(w.set_joint_motor(joint.into(), enable, speed, max)?)
    })
}

/// Reads the motor of a hinge or slider.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (not a hinge or slider).
///
/// # Safety
/// `world` must be NULL or a live world; outputs NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_get_motor(
    world: *const HearthWorld,
    joint: HearthJointId,
    out_enabled: *mut bool,
    out_speed: *mut f32,
    out_max: *mut f32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let e = validate::output(out_enabled, "out_enabled")?;
        let s = validate::output(out_speed, "out_speed")?;
        let m = validate::output(out_max, "out_max")?;
        let (enabled, speed, max) = w.joint_motor(joint.into())?;
        (*e, *s, *m) = (enabled, speed, max);
        Ok(())
    })
}

/// Sets a joint's limits: hinge angles (rad, -π..=π), slider translations (m), distance
/// lengths (m, >= 0; they act with the spring on), ball twist angles (rad). Wakes the bodies.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (a fixed joint, flag not 0/1, NaN, out of range,
/// lower > upper), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_set_limits(
    world: *mut HearthWorld,
    joint: HearthJointId,
    enable: u8,
    lower: f32,
    upper: f32,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let enable = validate::flag(enable, "enable")?;
        Ok(w.set_joint_limits(joint.into(), enable, lower, upper)?)
    })
}

/// Reads a joint's limits (as `hearth_joint_set_limits` sets them).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (a fixed joint).
///
/// # Safety
/// `world` must be NULL or a live world; outputs NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_get_limits(
    world: *const HearthWorld,
    joint: HearthJointId,
    out_enabled: *mut bool,
    out_lower: *mut f32,
    out_upper: *mut f32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let e = validate::output(out_enabled, "out_enabled")?;
        let l = validate::output(out_lower, "out_lower")?;
        let u = validate::output(out_upper, "out_upper")?;
        let (enabled, lower, upper) = w.joint_limits(joint.into())?;
        (*e, *l, *u) = (enabled, lower, upper);
        Ok(())
    })
}

/// Sets a ball joint's swing cone (half-angle in rad, 0..=π). Wakes the bodies.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (not a ball joint, flag not 0/1, out of range),
/// `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_set_cone_limit(
    world: *mut HearthWorld,
    joint: HearthJointId,
    enable: u8,
    angle: f32,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let enable = validate::flag(enable, "enable")?;
        Ok(w.set_joint_cone_limit(joint.into(), enable, angle)?)
    })
}

/// Reads a ball joint's swing cone.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (not a ball joint).
///
/// # Safety
/// `world` must be NULL or a live world; outputs NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_get_cone_limit(
    world: *const HearthWorld,
    joint: HearthJointId,
    out_enabled: *mut bool,
    out_angle: *mut f32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let e = validate::output(out_enabled, "out_enabled")?;
        let a = validate::output(out_angle, "out_angle")?;
        let (enabled, angle) = w.joint_cone_limit(joint.into())?;
        (*e, *a) = (enabled, angle);
        Ok(())
    })
}

/// Sets the spring of a hinge (toward angle 0) or distance joint (toward its length):
/// frequency (Hz, >= 0) and damping ratio (>= 0). Wakes the bodies.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (not a hinge or distance joint, flag not 0/1, negative or
/// NaN), `HEARTH_ERROR_WORLD_LOCKED`.
///
/// # Safety
/// `world` must be NULL or a live world.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_set_spring(
    world: *mut HearthWorld,
    joint: HearthJointId,
    enable: u8,
    hertz: f32,
    damping_ratio: f32,
) -> HearthResult {
    guard(|| {
        let w = world_mut(world)?;
        let enable = validate::flag(enable, "enable")?;
        Ok(w.set_joint_spring(joint.into(), enable, hertz, damping_ratio)?)
    })
}

/// Reads the spring of a hinge or distance joint.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`,
/// `HEARTH_ERROR_INVALID_ARGUMENT` (not a hinge or distance joint).
///
/// # Safety
/// `world` must be NULL or a live world; outputs NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_get_spring(
    world: *const HearthWorld,
    joint: HearthJointId,
    out_enabled: *mut bool,
    out_hertz: *mut f32,
    out_damping_ratio: *mut f32,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let e = validate::output(out_enabled, "out_enabled")?;
        let hz = validate::output(out_hertz, "out_hertz")?;
        let z = validate::output(out_damping_ratio, "out_damping_ratio")?;
        let (enabled, hertz, ratio) = w.joint_spring(joint.into())?;
        (*e, *hz, *z) = (enabled, hertz, ratio);
        Ok(())
    })
}

/// Reads the force (N) and torque (N·m) the joint applied to body B during the last step,
/// in world space (the torque leaves out the moment of the force about B's anchor). Zero
/// before the first step, and zero from the moment the joint breaks (a broken joint applies
/// nothing).
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; outputs NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_get_force(
    world: *const HearthWorld,
    joint: HearthJointId,
    out_force: *mut HearthVec3,
    out_torque: *mut HearthVec3,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let f = validate::output(out_force, "out_force")?;
        let t = validate::output(out_torque, "out_torque")?;
        let (force, torque): (Vec3, Vec3) = w.joint_force(joint.into())?;
        *f = force.into();
        *t = torque.into();
        Ok(())
    })
}

/// Reads whether a joint broke (its force or torque went past the def's threshold). A broken
/// joint no longer acts; destroy it with `hearth_joint_destroy`.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER`, `HEARTH_ERROR_INVALID_ID`.
///
/// # Safety
/// `world` must be NULL or a live world; `out_broken` NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn hearth_joint_is_broken(
    world: *const HearthWorld,
    joint: HearthJointId,
    out_broken: *mut bool,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let out = validate::output(out_broken, "out_broken")?;
        *out = w.joint(joint.into())?.broken;
        Ok(())
    })
}

/// Copies the ids of the joints that broke during the last `hearth_world_step` into the
/// caller's array and writes how many there are to `*out_count`. Pass `out_joints = NULL`
/// and `capacity = 0` to ask for the count. The list lasts until the next step.
///
/// Errors: `HEARTH_ERROR_NULL_POINTER` (`out_count`, or `out_joints` with `capacity > 0`),
/// `HEARTH_ERROR_BUFFER_TOO_SMALL` (`capacity` below the count and not 0; nothing written).
///
/// # Safety
/// `world` must be NULL or a live world; `out_joints` must hold `capacity` ids.
#[no_mangle]
pub unsafe extern "C" fn hearth_world_get_broken_joints(
    world: *const HearthWorld,
    out_joints: *mut HearthJointId,
    capacity: usize,
    out_count: *mut usize,
) -> HearthResult {
    guard(|| {
        let w = world_ref(world)?;
        let count = validate::output(out_count, "out_count")?;
        let broken = w.broken_joints();
        if let Some(out) = validate::counted_output(out_joints, capacity, broken.len(), "out_joints")? {
            for (o, &h) in out.iter_mut().zip(broken) {
                *o = h.into();
            }
        }
        *count = broken.len();
        Ok(())
    })
}

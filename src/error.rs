//! Errors of the engine core. The C layer maps each kind to a result code.

use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub enum Error {
    /// A handle that is null, destroyed, never existed or belongs to another world.
    InvalidId(&'static str),
    /// A number or value out of range; the message says which.
    InvalidArgument(String),
    /// A fixed capacity is used up (4,095 worlds alive at once); the message says which.
    LimitReached(String),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::InvalidId(what) => write!(f, "invalid {what} id (null, destroyed, or from another world)"),
            Error::InvalidArgument(m) | Error::LimitReached(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for Error {}

pub type Result<T> = std::result::Result<T, Error>;

/// Shorthand for an `InvalidArgument` error.
pub fn invalid(msg: impl Into<String>) -> Error {
    Error::InvalidArgument(msg.into())
}

/// Checks that every component of a vector is finite.
pub fn check_vec(name: &str, v: glam::Vec3) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(invalid(format!("{name} must be finite, got {v}")))
    }
}

pub fn check_finite(name: &str, x: f32) -> Result<()> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(invalid(format!("{name} must be finite, got {x}")))
    }
}

pub fn check_non_negative(name: &str, x: f32) -> Result<()> {
    if x.is_finite() && x >= 0.0 {
        Ok(())
    } else {
        Err(invalid(format!("{name} must be finite and >= 0, got {x}")))
    }
}

pub fn check_positive(name: &str, x: f32) -> Result<()> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(invalid(format!("{name} must be finite and > 0, got {x}")))
    }
}

/// Checks a quaternion is finite and not (near) zero, and returns it normalised.
pub fn check_quat(name: &str, q: glam::Quat) -> Result<glam::Quat> {
    let l = q.length();
    if !q.is_finite() || !l.is_finite() || l < 1.0e-6 {
        return Err(invalid(format!("{name} must be a finite non-zero quaternion, got {q}")));
    }
    Ok(q / l)
}

// ------------------------------------------------------------------ supported ranges
//
// Every number a host passes in is checked against one of these ranges (README "Supported
// ranges"; the header's preamble lists them too). Inside them every stage stays finite: the
// limits are chosen so that the largest products the engine forms (an impulse times the
// smallest body's inverse mass or inertia, a force over the shortest step, a mass times a
// squared lever arm) stay far below f32's 3.4e38, and the smallest (a sub-step squared, the
// smallest body's inertia) far above its smallest normal number, 1.2e-38.

/// Shortest step (s) that is not 0. Positions are f32: the motion of a step must stay well
/// above the resolution of coordinates tens of metres from the origin (6e-8 of the distance)
/// or slow bodies stop moving; 1 ms allows 1 kHz simulation.
pub const MIN_TIME_STEP: f32 = 1.0e-3;
/// Longest step (s): with the default 6 sub-steps a hinge pendulum keeps its radius within
/// 2 cm (joints and contacts are stiff at a quarter of the sub-step rate, so longer steps
/// let them sag).
pub const MAX_TIME_STEP: f32 = 0.1;
/// Smallest size (m): radii, half extents.
pub const MIN_LENGTH: f32 = 1.0e-3;
/// Largest size (m): radii, half extents, capsule segments, distances.
pub const MAX_LENGTH: f32 = 1.0e4;
/// Largest coordinate (m) of a position or a local offset, per axis.
pub const MAX_COORDINATE: f32 = 1.0e5;
/// Largest speed (m/s): the most `max_linear_speed` may be, and the bound of emitter speeds.
pub const MAX_SPEED: f32 = 1.0e4;
/// Largest angular speed (rad/s): the most `max_angular_speed` may be.
pub const MAX_ANGULAR_SPEED: f32 = 1.0e4;
/// Largest acceleration (m/s²): gravity, a particle's own acceleration.
pub const MAX_ACCELERATION: f32 = 1.0e4;
/// Largest gravity scale, either sign.
pub const MAX_GRAVITY_SCALE: f32 = 100.0;
/// Largest force (N) or torque (N·m) of one call.
pub const MAX_FORCE: f32 = 1.0e12;
/// Largest impulse (N·s) or angular impulse (N·m·s) of one call.
pub const MAX_IMPULSE: f32 = 1.0e10;
/// Densities (kg/m³) other than 0 (a massless shape) lie in [MIN_DENSITY, MAX_DENSITY].
pub const MIN_DENSITY: f32 = 1.0e-3;
pub const MAX_DENSITY: f32 = 1.0e5;
/// Largest inverse mass of a particle (1/kg): the lightest is 1 µg.
pub const MAX_INVERSE_MASS: f32 = 1.0e9;
/// Largest damping rate (1/s).
pub const MAX_DAMPING: f32 = 1.0e3;

fn out_of_range(name: &str, what: impl fmt::Display, got: impl fmt::Display) -> Error {
    invalid(format!("{name} must be {what}, got {got}"))
}

/// A limit as people write it: 0.001, 10000, 1e12.
struct Num(f32);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || (1.0e-3..=1.0e5).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// A number within `[lo, hi]` (finite).
pub fn check_range(name: &str, x: f32, lo: f32, hi: f32, unit: &str) -> Result<()> {
    if x >= lo && x <= hi {
        Ok(())
    } else {
        Err(out_of_range(
            name,
            format_args!("within [{}, {}]{unit}", Num(lo), Num(hi)),
            x,
        ))
    }
}

/// A step: 0 (nothing happens) or within [`MIN_TIME_STEP`, `MAX_TIME_STEP`].
pub fn check_time_step(name: &str, dt: f32) -> Result<()> {
    if dt == 0.0 || (MIN_TIME_STEP..=MAX_TIME_STEP).contains(&dt) {
        Ok(())
    } else {
        Err(out_of_range(
            name,
            format_args!("0 or within [{}, {}] s", Num(MIN_TIME_STEP), Num(MAX_TIME_STEP)),
            dt,
        ))
    }
}

/// A size: within [`MIN_LENGTH`, `MAX_LENGTH`].
pub fn check_length(name: &str, x: f32) -> Result<()> {
    check_range(name, x, MIN_LENGTH, MAX_LENGTH, " m")
}

/// Three sizes (half extents).
pub fn check_lengths(name: &str, v: glam::Vec3) -> Result<()> {
    if v.cmpge(glam::Vec3::splat(MIN_LENGTH)).all() && v.cmple(glam::Vec3::splat(MAX_LENGTH)).all() {
        Ok(())
    } else {
        Err(out_of_range(
            name,
            format_args!("within [{}, {}] m in each component", Num(MIN_LENGTH), Num(MAX_LENGTH)),
            v,
        ))
    }
}

/// A distance that may be 0 (a rest length, a reach): within [0, `MAX_LENGTH`].
pub fn check_distance(name: &str, x: f32) -> Result<()> {
    check_range(name, x, 0.0, MAX_LENGTH, " m")
}

/// A position or local offset: every coordinate within ±[`MAX_COORDINATE`].
pub fn check_position(name: &str, v: glam::Vec3) -> Result<()> {
    if v.abs().cmple(glam::Vec3::splat(MAX_COORDINATE)).all() {
        Ok(())
    } else {
        Err(out_of_range(
            name,
            format_args!("finite with every coordinate within ±{} m", Num(MAX_COORDINATE)),
            v,
        ))
    }
}

/// A vector whose length is at most `max` (finite components, so `NaN` fails too).
pub fn check_magnitude(name: &str, v: glam::Vec3, max: f32, unit: &str) -> Result<()> {
    let l = v.length();
    if v.is_finite() && l <= max {
        Ok(())
    } else {
        Err(out_of_range(
            name,
            format_args!("finite with a length of at most {}{unit}", Num(max)),
            v,
        ))
    }
}

/// A velocity no faster than `max` (m/s): the world's `max_linear_speed`.
pub fn check_velocity(name: &str, v: glam::Vec3, max: f32) -> Result<()> {
    check_magnitude(name, v, max, " m/s (the world's max_linear_speed)")
}

/// An angular velocity no faster than `max` (rad/s): the world's `max_angular_speed`.
pub fn check_angular_velocity(name: &str, w: glam::Vec3, max: f32) -> Result<()> {
    check_magnitude(name, w, max, " rad/s (the world's max_angular_speed)")
}

/// An acceleration (gravity): length at most [`MAX_ACCELERATION`].
pub fn check_acceleration(name: &str, a: glam::Vec3) -> Result<()> {
    check_magnitude(name, a, MAX_ACCELERATION, " m/s²")
}

/// A force or torque of one call: length at most [`MAX_FORCE`].
pub fn check_force(name: &str, f: glam::Vec3) -> Result<()> {
    check_magnitude(name, f, MAX_FORCE, " N (N·m for torques)")
}

/// An impulse or angular impulse of one call: length at most [`MAX_IMPULSE`].
pub fn check_impulse(name: &str, j: glam::Vec3) -> Result<()> {
    check_magnitude(name, j, MAX_IMPULSE, " N·s (N·m·s for angular impulses)")
}

/// A density: 0 (massless) or within [`MIN_DENSITY`, `MAX_DENSITY`].
pub fn check_density(name: &str, x: f32) -> Result<()> {
    if x == 0.0 || (MIN_DENSITY..=MAX_DENSITY).contains(&x) {
        Ok(())
    } else {
        Err(out_of_range(
            name,
            format_args!("0 or within [{}, {}] kg/m³", Num(MIN_DENSITY), Num(MAX_DENSITY)),
            x,
        ))
    }
}

/// A damping rate: within [0, `MAX_DAMPING`] 1/s.
pub fn check_damping(name: &str, x: f32) -> Result<()> {
    check_range(name, x, 0.0, MAX_DAMPING, " 1/s")
}

/// A gravity scale: within ±[`MAX_GRAVITY_SCALE`].
pub fn check_gravity_scale(name: &str, x: f32) -> Result<()> {
    check_range(name, x, -MAX_GRAVITY_SCALE, MAX_GRAVITY_SCALE, "")
}

/// A restitution (bounce): within [0, 1]; above 1 a bounce would add energy without bound.
pub fn check_restitution(name: &str, x: f32) -> Result<()> {
    check_range(name, x, 0.0, 1.0, "")
}

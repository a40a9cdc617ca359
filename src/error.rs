//! Errors of the engine core. The C layer maps each kind to a result code.

use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub enum Error {
    /// A handle that is null, destroyed, never existed or belongs to another world.
    InvalidId(&'static str),
    /// A number or value out of range; the message says which.
    InvalidArgument(String),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::InvalidId(what) => write!(f, "invalid {what} id (null, destroyed, or from another world)"),
            Error::InvalidArgument(m) => f.write_str(m),
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

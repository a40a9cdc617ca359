//! Hearth: a real-time 3D physics engine for games, shipped as a C-ABI library.
//!
//! The engine core (everything outside `capi`) is safe Rust on glam types and knows
//! nothing of C. `capi` converts, validates, guards and maps errors.

pub mod aabb;
pub mod collision;
pub mod dynamic_tree;
pub mod math;
pub mod shape;

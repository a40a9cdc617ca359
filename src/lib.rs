//! Hearth: a real-time 3D physics engine for games, shipped as a C-ABI library.
//!
//! The engine core (everything outside `capi`) is safe Rust on glam types and knows
//! nothing of C. `capi` converts, validates, guards and maps errors. `ARCHITECTURE.md`
//! lists the stages of a step and the file that does each.

pub mod aabb;
pub mod body;
pub mod broad_phase;
pub mod collision;
pub mod contact;
pub mod contact_solver;
pub mod contact_wide;
pub mod dynamic_tree;
pub mod error;
pub mod generators;
pub(crate) mod hash;
pub mod integrate_wide;
pub mod island;
pub mod joints;
pub mod math;
pub mod particles;
pub mod pool;
pub mod scenes;
pub mod shape;
pub mod simd;
pub mod soft;
pub mod solver;
pub mod step;
pub mod world;

pub use body::{BodyDef, BodyHandle, BodyType, ShapeHandle};
pub use error::{Error, Result};
pub use joints::{JointDef, JointHandle, JointKind};
pub use math::{Quat, Transform, Vec3};
pub use shape::{Geometry, ShapeDef};
pub use world::{Integrator, LaneWidth, World, WorldSettings};
pub mod capi;

//! Hearth: a real-time 3D physics engine for games, shipped as a C-ABI library.
//!
//! The engine core (everything outside `capi`) is safe Rust on glam types and knows
//! nothing of C. `capi` converts, validates, guards and maps errors. `ARCHITECTURE.md`
//! lists the stages of a step and the file that does each.

pub mod collision;
pub mod debug_draw;
pub mod dynamics;
pub mod error;
pub mod events;
pub mod generators;
pub(crate) mod hash;
pub mod math;
pub mod parallel;
pub mod particles;
pub mod pool;
pub mod record;
pub mod simd;
pub mod snapshot;
pub mod soft;
pub mod state_hash;
pub mod step;
pub mod world;
pub mod world_setters;

pub use collision::geometry_store::ConvexHullHandle;
pub use collision::hull::builder::HullSettings;
pub use collision::hull::ConvexHull;
pub use collision::shape::{Geometry, ShapeDef};
pub use dynamics::body::{BodyDef, BodyHandle, BodyType, ShapeHandle};
pub use dynamics::joints;
pub use dynamics::joints::{JointDef, JointHandle, JointKind};
pub use error::{Error, Result};
pub use math::{Quat, Transform, Vec3};
pub use world::{Integrator, LaneWidth, World, WorldSettings};
pub mod capi;

//! Collision: what shapes are and which of them touch.
//!
//! * `aabb` — axis-aligned boxes.
//! * `shape` — shapes attached to bodies: geometry, material, mass properties, bounds.
//! * `dynamic_tree` — the bounding volume hierarchy over fat boxes (Box2D v3's tree in 3D).
//! * `broad_phase` — the tree plus static planes, the move buffer and the pair set.
//! * `narrow_phase` — pure geometry: contact manifolds for every pair of shape kinds.
//! * `contact` — a touching (or nearly touching) pair with its persistent manifold.
//! * `geometry_store` — shared geometry (convex hulls) built once, used by many shapes.
//! * `hull` — convex hulls: quickhull builder, polyhedral mass properties.
//! * `mesh` — triangle meshes: BVH, active edges.
//! * `heightfield` — terrain grids with holes and a min/max pyramid.
//! * `gjk` — distance and closest points between convex cores given by support functions.
//! * `filter` — category, mask and group filtering of shape pairs and queries.
//! * `query` — ray casts, shape casts and overlap queries against the world.

pub mod aabb;
pub mod broad_phase;
pub mod contact;
pub mod dynamic_tree;
pub mod filter;
pub mod geometry_store;
pub mod gjk;
pub mod heightfield;
pub mod hull;
pub mod mesh;
pub mod narrow_phase;
pub mod query;
pub mod shape;

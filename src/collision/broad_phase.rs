//! Broad phase: a dynamic AABB tree of shape proxies plus the list of static planes, a move
//! buffer of proxies whose fat box grew, and the set of pairs that already have a contact.

use crate::collision::aabb::Aabb;
use crate::collision::dynamic_tree::DynamicTree;
use crate::collision::shape::Geometry;
use crate::hash::IntMap;
use crate::math::{Transform, Vec3};

/// Key of an unordered shape pair (slot indices).
#[inline]
pub fn pair_key(a: u32, b: u32) -> u64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    ((lo as u64) << 32) | hi as u64
}

/// A plane in world space: `dot(normal, p) <= offset` is inside.
#[inline]
pub fn world_plane(geometry: &Geometry, xf: &Transform) -> (Vec3, f32) {
    match *geometry {
        Geometry::Plane { normal, offset } => {
            let n = xf.q * normal;
            (n, offset + n.dot(xf.p))
        }
        _ => (Vec3::Y, f32::MAX),
    }
}

/// True when a box reaches into the half-space.
#[inline]
pub fn aabb_touches_plane(bb: &Aabb, normal: Vec3, offset: f32) -> bool {
    normal.dot(bb.center()) - normal.abs().dot(bb.extents()) <= offset
}

#[derive(Default)]
pub struct BroadPhase {
    pub tree: DynamicTree,
    /// Shape slot indices whose proxy was created or moved since the last pair update.
    pub move_buffer: Vec<u32>,
    /// Shape slot indices of plane shapes (kept out of the tree: they are unbounded).
    pub planes: Vec<u32>,
    /// Pairs that have a contact, to the contact's slot index.
    pub pairs: IntMap<u64, u32>,
    /// Candidate pairs found this step (reused storage).
    pub candidates: Vec<(u32, u32)>,
    /// Per chunk of moved proxies, its candidates (joined into `candidates`; `find_pairs`).
    pub chunk_candidates: Vec<Vec<(u32, u32)>>,
}

//! Narrowphase: contact manifolds between pairs of shapes.
//!
//! Every function here is pure geometry: shapes in their body's local frame plus the body
//! transforms in, a [`Manifold`] out. The world's contact stage calls [`collide`].

use crate::math::{Transform, Vec3};
use crate::shape::Geometry;

/// Most points a manifold carries (a face–face box contact is reduced to four).
pub const MAX_MANIFOLD_POINTS: usize = 4;

/// One contact point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ManifoldPoint {
    /// World-space point midway between the two surfaces.
    pub point: Vec3,
    /// Signed distance along the normal: negative when penetrating, positive when
    /// separated (speculative point).
    pub separation: f32,
    /// Feature key: stable across frames while the same features touch, used to match
    /// points between frames for warm starting.
    pub id: u32,
}

/// Contact manifold between shape A and shape B.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Manifold {
    /// World-space unit normal pointing from A to B.
    pub normal: Vec3,
    pub points: [ManifoldPoint; MAX_MANIFOLD_POINTS],
    pub count: usize,
}

impl Manifold {
    pub const EMPTY: Manifold = Manifold {
        normal: Vec3::ZERO,
        points: [ManifoldPoint {
            point: Vec3::ZERO,
            separation: 0.0,
            id: 0,
        }; MAX_MANIFOLD_POINTS],
        count: 0,
    };

    pub fn points(&self) -> &[ManifoldPoint] {
        &self.points[..self.count]
    }
}

/// Computes the contact manifold of `a` (on a body at `xf_a`) against `b` (at `xf_b`).
/// Points are reported while their separation is at most `speculative` metres, so the
/// solver can stop fast bodies before they pass through. Plane–plane gives no contact.
pub fn collide(
    _a: &Geometry,
    _xf_a: &Transform,
    _b: &Geometry,
    _xf_b: &Transform,
    _speculative: f32,
) -> Manifold {
    Manifold::EMPTY
}

//! Persistent contacts: one per overlapping shape pair, kept while their fat boxes overlap.
//! Each keeps its manifold and the impulses of its points between steps (warm starting),
//! matched by feature id.

use crate::collision::geometry_store::GeometryStore;
use crate::collision::narrow_phase::{collide_cached, Manifold, SatCache, MAX_MANIFOLD_POINTS};
use crate::collision::shape::{Shape, ShapeDef};
use crate::math::{Quat, Transform, Vec3};
use glam::{Mat3A, Vec3A};

/// Impulses a manifold point carried at the end of the last step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointImpulse {
    pub normal: f32,
}

/// Friction of the whole contact patch, applied at the centroid of the manifold.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrictionImpulse {
    /// Tangential impulse as a world vector (the tangent basis may turn between steps).
    pub tangent: Vec3,
    /// Torsional impulse about the normal.
    pub twist: f32,
    /// The surfaces were sliding (dynamic friction applies) at the end of the last step.
    pub sliding: bool,
}

pub struct Contact {
    pub shape_a: u32,
    pub shape_b: u32,
    pub body_a: u32,
    pub body_b: u32,
    pub manifold: Manifold,
    pub impulses: [PointImpulse; MAX_MANIFOLD_POINTS],
    pub friction: FrictionImpulse,
    pub static_friction: f32,
    pub dynamic_friction: f32,
    pub restitution: f32,
    /// The manifold has points (touching or speculative).
    pub touching: bool,
    /// Position in the world's awake-contact list, or `NONE`.
    pub awake_index: u32,
    pub key: u64,
    /// Rounding radii of the two shapes (`Geometry::rounding_radius`), for the solver.
    pub radius_a: f32,
    pub radius_b: f32,
    /// The manifold in the bodies' own frames, for reuse while they barely move relative to
    /// each other.
    pub cache: ManifoldCache,
    /// The separating-axis feature that decided the last hull test (hull pairs only).
    pub sat: SatCache,
}

/// Body-pair cache (after Jolt's): the relative pose of B in A's frame when the manifold was
/// last computed, the normal in A's frame and each point's surface points in its body's frame.
/// While the relative pose stays within a millimetre and about a degree, the manifold is
/// reused and only the separations are recomputed — a resting stack skips the narrow phase.
#[derive(Clone, Copy, Debug, Default)]
pub struct ManifoldCache {
    pub valid: bool,
    /// B's position and rotation in A's frame (the rotation to rounding, not renormalised).
    pub relative_p: Vec3A,
    pub relative_q: Quat,
    pub normal_a: Vec3A,
    pub local_a: [Vec3A; MAX_MANIFOLD_POINTS],
    pub local_b: [Vec3A; MAX_MANIFOLD_POINTS],
}

/// Largest relative translation (m) and rotation (cos of half the angle) for reuse.
const CACHE_MAX_TRANSLATION: f32 = 1.0e-3;
const CACHE_MIN_COS_HALF_ANGLE: f32 = 0.999_962; // cos(0.5°): a turn of 1°

/// A transform as a rotation matrix and a translation, for mapping several points.
struct Frame {
    r: Mat3A,
    p: Vec3A,
}

impl Frame {
    #[inline(always)]
    fn new(xf: &Transform) -> Frame {
        Frame {
            r: Mat3A::from_quat(xf.q),
            p: xf.p.into(),
        }
    }
}

impl ManifoldCache {
    fn store(&mut self, m: &Manifold, xf_a: &Transform, xf_b: &Transform) {
        let (fa, fb) = (Frame::new(xf_a), Frame::new(xf_b));
        let (ta, tb) = (fa.r.transpose(), fb.r.transpose());
        self.valid = true;
        self.relative_p = ta * (fb.p - fa.p);
        self.relative_q = xf_a.q.conjugate() * xf_b.q;
        let n = Vec3A::from(m.normal);
        self.normal_a = ta * n;
        for (i, p) in m.points().iter().enumerate() {
            let (point, half) = (Vec3A::from(p.point), 0.5 * p.separation * n);
            self.local_a[i] = ta * (point - half - fa.p);
            self.local_b[i] = tb * (point + half - fb.p);
        }
    }

    /// Moves the cached manifold `m` to the current poses if they are close enough to the
    /// cached ones; returns whether it did.
    #[inline]
    fn reuse(&self, m: &mut Manifold, xf_a: &Transform, xf_b: &Transform) -> bool {
        if !self.valid {
            return false;
        }
        let fa = Frame::new(xf_a);
        let relative_p = fa.r.transpose() * (Vec3A::from(xf_b.p) - fa.p);
        if (relative_p - self.relative_p).length_squared() > CACHE_MAX_TRANSLATION * CACHE_MAX_TRANSLATION
            || (xf_a.q.conjugate() * xf_b.q).dot(self.relative_q).abs() < CACHE_MIN_COS_HALF_ANGLE
        {
            return false;
        }
        let fb = Frame::new(xf_b);
        let n = fa.r * self.normal_a;
        m.normal = n.into();
        for (p, (la, lb)) in m.points[..m.count]
            .iter_mut()
            .zip(self.local_a.iter().zip(&self.local_b))
        {
            let (pa, pb) = (fa.r * *la + fa.p, fb.r * *lb + fb.p);
            p.point = (0.5 * (pa + pb)).into();
            p.separation = (pb - pa).dot(n);
        }
        true
    }
}

/// Friction combines as the geometric mean, restitution as the maximum (Box2D, Jolt).
pub fn mix_materials(a: &ShapeDef, b: &ShapeDef) -> (f32, f32, f32) {
    let fs = (a.static_friction * b.static_friction).sqrt();
    let fd = (a.dynamic_friction * b.dynamic_friction).sqrt();
    (fs, fd.min(fs), a.restitution.max(b.restitution))
}

impl Contact {
    pub fn new(store: &GeometryStore, shape_a: u32, shape_b: u32, a: &Shape, b: &Shape, key: u64) -> Contact {
        let (fs, fd, e) = mix_materials(&a.def, &b.def);
        Contact {
            shape_a,
            shape_b,
            body_a: a.body,
            body_b: b.body,
            manifold: Manifold::EMPTY,
            impulses: [PointImpulse::default(); MAX_MANIFOLD_POINTS],
            friction: FrictionImpulse::default(),
            static_friction: fs,
            dynamic_friction: fd,
            restitution: e,
            touching: false,
            awake_index: crate::dynamics::body::NONE,
            key,
            radius_a: a.geometry.rounding_radius(store),
            radius_b: b.geometry.rounding_radius(store),
            cache: ManifoldCache::default(),
            sat: SatCache::None,
        }
    }

    /// Drops every point (the shapes are too far apart to touch this step).
    pub fn clear(&mut self) {
        self.manifold = Manifold::EMPTY;
        self.cache.valid = false;
        self.touching = false;
        self.friction = FrictionImpulse::default();
    }

    /// Recomputes the manifold (or moves the cached one, see `ManifoldCache`) and carries
    /// impulses over to points with the same feature id. Returns true when the contact started
    /// touching in this update.
    pub fn update(
        &mut self,
        store: &GeometryStore,
        a: &Shape,
        xf_a: &Transform,
        b: &Shape,
        xf_b: &Transform,
        speculative: f32,
    ) -> bool {
        if self.cache.reuse(&mut self.manifold, xf_a, xf_b) {
            return false;
        }
        let old = self.manifold;
        let old_impulses = self.impulses;
        let was_touching = self.touching;
        self.manifold = collide_cached(store, &a.geometry, xf_a, &b.geometry, xf_b, speculative, &mut self.sat);
        self.cache.store(&self.manifold, xf_a, xf_b);
        self.touching = self.manifold.count > 0;
        for (point, impulse) in self.manifold.points[..self.manifold.count]
            .iter()
            .zip(self.impulses.iter_mut())
        {
            *impulse = old.points[..old.count]
                .iter()
                .zip(&old_impulses)
                .find(|(p, _)| p.id == point.id)
                .map_or(PointImpulse::default(), |(_, i)| *i);
        }
        if !self.touching {
            self.friction = FrictionImpulse::default();
        }
        self.touching && !was_touching
    }
}

/// A contact written by a contact generator (rod, cable, user callback) for one step: body
/// slot indices (`crate::dynamics::body::NONE` for the world), a world point, the normal from A to B,
/// the penetration (> 0 when the constraint is violated) and materials.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneratedContact {
    pub body_a: u32,
    pub body_b: u32,
    pub point: Vec3,
    pub normal: Vec3,
    pub penetration: f32,
    pub restitution: f32,
    pub friction: f32,
}

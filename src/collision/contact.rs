//! Persistent contacts: one per overlapping shape pair, kept while their fat boxes overlap.
//! Each keeps its manifold and the impulses of its points between steps (warm starting),
//! matched by feature id.

use crate::collision::narrow_phase::{collide, Manifold, MAX_MANIFOLD_POINTS};
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
    /// Rolling-resistance angular impulse on side B, about axes in the contact plane (world).
    pub rolling: Vec3,
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
    /// Rolling resistance and torsional friction of the pair as levers (m): the largest
    /// torque is the lever times the normal force (`mix_materials`).
    pub rolling_resistance: f32,
    pub torsional_friction: f32,
    /// The manifold has points (touching or speculative).
    pub touching: bool,
    /// Position in the world's awake-contact list, or `NONE`.
    pub awake_index: u32,
    pub key: u64,
    /// Rounding radii of the two shapes (`Geometry::rounding_radius`), for the solver.
    pub radius_a: f32,
    pub radius_b: f32,
    /// The smaller of the two shapes' `Geometry::feature_size` (m): length tolerances of the
    /// contact scale down to it.
    pub size: f32,
    /// The manifold in the bodies' own frames, for reuse while they barely move relative to
    /// each other.
    pub cache: ManifoldCache,
}

/// Body-pair cache (after Jolt's): the relative pose of B in A's frame when the manifold was
/// last computed, the normal in the frame of the body whose surface defines it, and each
/// point's core points in their bodies' frames. While the relative pose stays within a
/// millimetre and about a degree, the manifold is reused and only the separations are
/// recomputed — a resting stack skips the narrow phase.
///
/// A rounded shape (sphere, capsule) keeps its *core* point (centre, or the point on the
/// segment): the core turns with the body, the touching surface point does not (a rolling
/// ball touches below its centre). Its normal comes from the other body's flat face, or
/// from the line between the two cores when both are rounded. Keeping surface points and the
/// normal fixed in a rolling body would tilt the normal and shift the point forward as it
/// turns — up to a degree of tilt before the next full update — which pushed resting balls
/// and capsules on a plane into rolling by themselves.
#[derive(Clone, Copy, Debug, Default)]
pub struct ManifoldCache {
    pub valid: bool,
    /// B's position and rotation in A's frame (the rotation to rounding, not renormalised).
    pub relative_p: Vec3A,
    pub relative_q: Quat,
    /// The normal in A's frame (A flat), in B's (A rounded, B flat), or unused (both
    /// rounded: the line between the cores).
    pub normal: Vec3A,
    pub local_a: [Vec3A; MAX_MANIFOLD_POINTS],
    pub local_b: [Vec3A; MAX_MANIFOLD_POINTS],
}

/// Largest relative translation for reuse: a millimetre, or a tenth of the smaller shape's
/// size (`Contact::size`) for small shapes; and rotation (cos of half the angle).
const CACHE_MAX_TRANSLATION: f32 = 1.0e-3;
const CACHE_MAX_TRANSLATION_FRACTION: f32 = 0.1;
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
    /// Keeps `m` (computed at `xf_a`, `xf_b`; `radius_a`, `radius_b` round the shapes' cores).
    fn store(&mut self, m: &Manifold, xf_a: &Transform, radius_a: f32, xf_b: &Transform, radius_b: f32) {
        let (fa, fb) = (Frame::new(xf_a), Frame::new(xf_b));
        let (ta, tb) = (fa.r.transpose(), fb.r.transpose());
        self.valid = true;
        self.relative_p = ta * (fb.p - fa.p);
        self.relative_q = xf_a.q.conjugate() * xf_b.q;
        let n = Vec3A::from(m.normal);
        self.normal = if radius_a > 0.0 { tb * n } else { ta * n };
        for (i, p) in m.points().iter().enumerate() {
            let (point, half) = (Vec3A::from(p.point), 0.5 * p.separation * n);
            // The surface points, then their cores.
            let (mut core_a, mut core_b) = (point - half, point + half);
            if radius_a > 0.0 {
                core_a -= radius_a * n;
            }
            if radius_b > 0.0 {
                core_b += radius_b * n;
            }
            self.local_a[i] = ta * (core_a - fa.p);
            self.local_b[i] = tb * (core_b - fb.p);
        }
    }

    /// Moves the cached manifold `m` to the current poses if they are close enough to the
    /// cached ones; returns whether it did.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn reuse(
        &self,
        m: &mut Manifold,
        xf_a: &Transform,
        radius_a: f32,
        xf_b: &Transform,
        radius_b: f32,
        size: f32,
    ) -> bool {
        if !self.valid {
            return false;
        }
        let fa = Frame::new(xf_a);
        let relative_p = fa.r.transpose() * (Vec3A::from(xf_b.p) - fa.p);
        let max_translation = CACHE_MAX_TRANSLATION.min(CACHE_MAX_TRANSLATION_FRACTION * size);
        if (relative_p - self.relative_p).length_squared() > max_translation * max_translation
            || (xf_a.q.conjugate() * xf_b.q).dot(self.relative_q).abs() < CACHE_MIN_COS_HALF_ANGLE
        {
            return false;
        }
        let fb = Frame::new(xf_b);
        let pairs = self.local_a.iter().zip(&self.local_b);
        if radius_a == 0.0 && radius_b == 0.0 {
            // Two flat shapes (boxes, planes): surface points and normal turn with the bodies.
            let n = fa.r * self.normal;
            m.normal = n.into();
            for (p, (la, lb)) in m.points[..m.count].iter_mut().zip(pairs) {
                let (pa, pb) = (fa.r * *la + fa.p, fb.r * *lb + fb.p);
                p.point = (0.5 * (pa + pb)).into();
                p.separation = (pb - pa).dot(n);
            }
            return true;
        }
        let core = |i: usize| (fa.r * self.local_a[i] + fa.p, fb.r * self.local_b[i] + fb.p);
        let n = match (radius_a > 0.0, radius_b > 0.0) {
            (false, _) => fa.r * self.normal,
            (true, false) => fb.r * self.normal,
            (true, true) => {
                let (ca, cb) = core(0);
                let d = cb - ca;
                let l2 = d.length_squared();
                // Cores (nearly) coinciding: no direction to take; compute afresh.
                if l2 <= 1.0e-12 {
                    return false;
                }
                d / l2.sqrt()
            }
        };
        m.normal = n.into();
        for (p, (la, lb)) in m.points[..m.count].iter_mut().zip(pairs) {
            let (mut pa, mut pb) = (fa.r * *la + fa.p, fb.r * *lb + fb.p);
            if radius_a > 0.0 {
                pa += radius_a * n;
            }
            if radius_b > 0.0 {
                pb -= radius_b * n;
            }
            let separation = (pb - pa).dot(n);
            // Midway between the surfaces, on the normal through a rounded shape's core (the
            // other surface point may lag behind by the drift since the cache was filled).
            p.point = match (radius_a > 0.0, radius_b > 0.0) {
                (true, false) => pa + 0.5 * separation * n,
                (false, true) => pb - 0.5 * separation * n,
                _ => 0.5 * (pa + pb),
            }
            .into();
            p.separation = separation;
        }
        true
    }
}

/// The materials of a touching pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mixed {
    pub static_friction: f32,
    pub dynamic_friction: f32,
    pub restitution: f32,
    /// Levers (m): the pair's coefficient times the larger rounding radius.
    pub rolling_resistance: f32,
    pub torsional_friction: f32,
}

/// Friction combines as the geometric mean, restitution as the maximum (Box2D, Jolt); rolling
/// resistance and torsional friction as the maximum (Box2D's rule for rolling resistance),
/// times the larger of the two shapes' rounding radii (sphere and capsule radius; boxes and
/// planes have none, so two of them never roll).
pub fn mix_materials(a: &ShapeDef, radius_a: f32, b: &ShapeDef, radius_b: f32) -> Mixed {
    let fs = (a.static_friction * b.static_friction).sqrt();
    let fd = (a.dynamic_friction * b.dynamic_friction).sqrt();
    let radius = radius_a.max(radius_b);
    Mixed {
        static_friction: fs,
        dynamic_friction: fd.min(fs),
        restitution: a.restitution.max(b.restitution),
        rolling_resistance: a.rolling_resistance.max(b.rolling_resistance) * radius,
        torsional_friction: a.torsional_friction.max(b.torsional_friction) * radius,
    }
}

impl Contact {
    pub fn new(shape_a: u32, shape_b: u32, a: &Shape, b: &Shape, key: u64) -> Contact {
        let (radius_a, radius_b) = (a.geometry.rounding_radius(), b.geometry.rounding_radius());
        let m = mix_materials(&a.def, radius_a, &b.def, radius_b);
        Contact {
            shape_a,
            shape_b,
            body_a: a.body,
            body_b: b.body,
            manifold: Manifold::EMPTY,
            impulses: [PointImpulse::default(); MAX_MANIFOLD_POINTS],
            friction: FrictionImpulse::default(),
            static_friction: m.static_friction,
            dynamic_friction: m.dynamic_friction,
            restitution: m.restitution,
            rolling_resistance: m.rolling_resistance,
            torsional_friction: m.torsional_friction,
            touching: false,
            awake_index: crate::dynamics::body::NONE,
            key,
            radius_a,
            radius_b,
            size: a.geometry.feature_size().min(b.geometry.feature_size()),
            cache: ManifoldCache::default(),
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
    pub fn update(&mut self, a: &Shape, xf_a: &Transform, b: &Shape, xf_b: &Transform, speculative: f32) -> bool {
        let (ra, rb) = (self.radius_a, self.radius_b);
        if self.cache.reuse(&mut self.manifold, xf_a, ra, xf_b, rb, self.size) {
            return false;
        }
        let old = self.manifold;
        let old_impulses = self.impulses;
        let was_touching = self.touching;
        self.manifold = collide(&a.geometry, xf_a, &b.geometry, xf_b, speculative);
        self.cache.store(&self.manifold, xf_a, ra, xf_b, rb);
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

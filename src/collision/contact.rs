//! Persistent contacts: one per overlapping shape pair, kept while their fat boxes overlap.
//! Each keeps its manifold and the impulses of its points between steps (warm starting),
//! matched by feature id.
//!
//! A convex shape against a triangle mesh or heightfield touches along several normals (a
//! box across a crease): such a contact (`multi`) holds up to `MAX_MESH_MANIFOLDS`
//! manifolds, the first in `manifold` like any contact, the others in `more`, each with
//! its own impulses and friction and solved as its own constraint. Impulses carry over by
//! feature id (which names the triangle, or the shape's vertex), friction from the old
//! manifold with the closest normal.

use crate::collision::geometry_store::GeometryStore;
use crate::collision::narrow_phase::{
    collide_cached, collide_triangles, Manifold, MeshManifolds, SatCache, MAX_MANIFOLD_POINTS, MAX_MESH_MANIFOLDS,
};
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
    /// A convex shape against a mesh or heightfield: several manifolds.
    pub multi: bool,
    /// Manifolds after the first (`multi` only; the storage is kept between steps).
    pub more: Vec<ChildManifold>,
    /// The separating-axis feature that decided the last hull test and its face hold (hull
    /// pairs only).
    pub sat: SatCache,
    /// Event flags of the pair (`events.rs`: `CONTACT_EVENTS`, `HIT_EVENTS`, `SENSOR`,
    /// `SENSOR_EVENTS`), set at creation.
    pub event_flags: u8,
    /// A begin event (contact or sensor) was reported and no end yet.
    pub reported: bool,
    /// The pre-solve callback disabled the contact for this step.
    pub disabled: bool,
}

/// A manifold after the first of a `multi` contact, with its impulses and cached frames.
#[derive(Clone, Copy, Debug, Default)]
pub struct ChildManifold {
    pub manifold: Manifold,
    pub impulses: [PointImpulse; MAX_MANIFOLD_POINTS],
    pub friction: FrictionImpulse,
    local: ManifoldLocal,
}

/// Normal cosine above which a new manifold takes over an old one's friction.
const FRICTION_MATCH_COS: f32 = 0.9;

/// Body-pair cache (after Jolt's): the relative pose of B in A's frame when the manifold was
/// last computed, the normal in the frame of the body whose surface defines it, and each
/// point's core points in their bodies' frames. While the relative pose stays within a
/// millimetre and about a degree, the manifold is reused and only the separations are
/// recomputed — a resting stack skips the narrow phase.
///
/// A rounded shape (sphere, capsule, rounded hull) keeps its *core* point (centre, or the
/// point on the segment or core hull): the core turns with the body, the touching surface
/// point does not (a rolling ball touches below its centre). Its normal comes from the other
/// body's flat face, or from the line between the two cores when both are rounded. Keeping
/// surface points and the normal fixed in a rolling body would tilt the normal and shift the
/// point forward as it turns — up to a degree of tilt before the next full update — which
/// pushed resting balls and capsules on a plane into rolling by themselves.
#[derive(Clone, Copy, Debug, Default)]
pub struct ManifoldCache {
    pub valid: bool,
    /// B's position and rotation in A's frame (the rotation to rounding, not renormalised).
    pub relative_p: Vec3A,
    pub relative_q: Quat,
    local: ManifoldLocal,
}

/// One manifold in the bodies' frames: the normal in A's frame (A flat), in B's (A rounded, B
/// flat), or unused (both rounded: the line between the cores); each point's core points
/// (surface points of a flat shape) in their bodies' frames.
#[derive(Clone, Copy, Debug, Default)]
struct ManifoldLocal {
    normal: Vec3A,
    local_a: [Vec3A; MAX_MANIFOLD_POINTS],
    local_b: [Vec3A; MAX_MANIFOLD_POINTS],
}

impl ManifoldLocal {
    /// Keeps `m` (computed at frames `fa`, `fb`; `radius_a`, `radius_b` round the cores).
    #[inline]
    fn store(&mut self, m: &Manifold, fa: &Frame, fb: &Frame, radius_a: f32, radius_b: f32) {
        let (ta, tb) = (fa.r.transpose(), fb.r.transpose());
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

    /// Moves the kept manifold to frames `fa`, `fb`; false when it cannot (two rounded cores
    /// that coincide give no normal: compute afresh).
    #[inline]
    fn apply(&self, m: &mut Manifold, fa: &Frame, fb: &Frame, radius_a: f32, radius_b: f32) -> bool {
        let pairs = self.local_a.iter().zip(&self.local_b);
        if radius_a == 0.0 && radius_b == 0.0 {
            // Two flat shapes (boxes, hulls, planes, triangles): surface points and normal
            // turn with the bodies.
            let n = fa.r * self.normal;
            m.normal = n.into();
            for (p, (la, lb)) in m.points[..m.count].iter_mut().zip(pairs) {
                let (pa, pb) = (fa.r * *la + fa.p, fb.r * *lb + fb.p);
                p.point = (0.5 * (pa + pb)).into();
                p.separation = (pb - pa).dot(n);
            }
            return true;
        }
        let n = match (radius_a > 0.0, radius_b > 0.0) {
            (false, _) => fa.r * self.normal,
            (true, false) => fb.r * self.normal,
            (true, true) => {
                let d = (fb.r * self.local_b[0] + fb.p) - (fa.r * self.local_a[0] + fa.p);
                let l2 = d.length_squared();
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
    /// Records the relative pose and the first manifold; returns the frames for the others.
    fn store(&mut self, m: &Manifold, xf_a: &Transform, xf_b: &Transform, radii: (f32, f32)) -> (Frame, Frame) {
        let (fa, fb) = (Frame::new(xf_a), Frame::new(xf_b));
        self.valid = true;
        self.relative_p = fa.r.transpose() * (fb.p - fa.p);
        self.relative_q = xf_a.q.conjugate() * xf_b.q;
        self.local.store(m, &fa, &fb, radii.0, radii.1);
        (fa, fb)
    }

    /// The bodies' frames if their relative pose is close enough to the cached one for the
    /// cached manifolds to be reused.
    #[inline]
    fn reusable(&self, xf_a: &Transform, xf_b: &Transform, size: f32) -> Option<(Frame, Frame)> {
        if !self.valid {
            return None;
        }
        let fa = Frame::new(xf_a);
        let relative_p = fa.r.transpose() * (Vec3A::from(xf_b.p) - fa.p);
        let max_translation = CACHE_MAX_TRANSLATION.min(CACHE_MAX_TRANSLATION_FRACTION * size);
        if (relative_p - self.relative_p).length_squared() > max_translation * max_translation
            || (xf_a.q.conjugate() * xf_b.q).dot(self.relative_q).abs() < CACHE_MIN_COS_HALF_ANGLE
        {
            return None;
        }
        Some((fa, Frame::new(xf_b)))
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
/// times the larger of the two shapes' rounding radii (sphere and capsule radius, a hull's
/// convex radius; boxes, planes and triangles have none, so two of them never roll).
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
    pub fn new(store: &GeometryStore, shape_a: u32, shape_b: u32, a: &Shape, b: &Shape, key: u64) -> Contact {
        let (radius_a, radius_b) = (a.geometry.rounding_radius(store), b.geometry.rounding_radius(store));
        let m = mix_materials(&a.def, radius_a, &b.def, radius_b);
        let multi = a.geometry.is_triangles() || b.geometry.is_triangles();
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
            size: a.geometry.feature_size(store).min(b.geometry.feature_size(store)),
            cache: ManifoldCache::default(),
            multi,
            // Room for every manifold up front: a pair that first touches along a second
            // normal mid-game must not allocate in the step.
            more: Vec::with_capacity(if multi { MAX_MESH_MANIFOLDS - 1 } else { 0 }),
            sat: SatCache::default(),
            event_flags: 0,
            reported: false,
            disabled: false,
        }
    }

    /// Drops every point (the shapes are too far apart to touch this step).
    pub fn clear(&mut self) {
        self.manifold = Manifold::EMPTY;
        self.cache.valid = false;
        self.touching = false;
        self.friction = FrictionImpulse::default();
        self.more.clear();
    }

    /// Manifolds (1, or more for a `multi` contact; some may be empty).
    #[inline]
    pub fn manifold_count(&self) -> usize {
        1 + self.more.len()
    }

    /// Manifold `k`, its points' impulses and its friction.
    #[inline]
    pub fn child(&self, k: usize) -> (&Manifold, &[PointImpulse; MAX_MANIFOLD_POINTS], &FrictionImpulse) {
        if k == 0 {
            (&self.manifold, &self.impulses, &self.friction)
        } else {
            let c = &self.more[k - 1];
            (&c.manifold, &c.impulses, &c.friction)
        }
    }

    /// Manifold `k`'s point count and its impulses, to store the solver's results.
    #[inline]
    pub fn child_impulses_mut(
        &mut self,
        k: usize,
    ) -> (usize, &mut [PointImpulse; MAX_MANIFOLD_POINTS], &mut FrictionImpulse) {
        if k == 0 {
            (self.manifold.count, &mut self.impulses, &mut self.friction)
        } else {
            let c = &mut self.more[k - 1];
            (c.manifold.count, &mut c.impulses, &mut c.friction)
        }
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
        let (ra, rb) = (self.radius_a, self.radius_b);
        if let Some((fa, fb)) = self.cache.reusable(xf_a, xf_b, self.size) {
            let mut moved = self.cache.local.apply(&mut self.manifold, &fa, &fb, ra, rb);
            for c in self.more.iter_mut() {
                moved &= c.local.apply(&mut c.manifold, &fa, &fb, ra, rb);
            }
            if moved {
                return false;
            }
        }
        if self.multi {
            return self.update_multi(store, a, xf_a, b, xf_b, speculative);
        }
        let old = self.manifold;
        let old_impulses = self.impulses;
        let was_touching = self.touching;
        self.manifold = collide_cached(store, &a.geometry, xf_a, &b.geometry, xf_b, speculative, &mut self.sat);
        self.cache.store(&self.manifold, xf_a, xf_b, (ra, rb));
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

    /// `update` for a shape against a mesh or heightfield: every manifold of the pair.
    fn update_multi(
        &mut self,
        store: &GeometryStore,
        a: &Shape,
        xf_a: &Transform,
        b: &Shape,
        xf_b: &Transform,
        speculative: f32,
    ) -> bool {
        // The old manifolds, for warm starting.
        let mut old = [ChildManifold::default(); MAX_MESH_MANIFOLDS];
        let old_count = self.manifold_count().min(MAX_MESH_MANIFOLDS);
        for (k, o) in old[..old_count].iter_mut().enumerate() {
            let (m, i, f) = self.child(k);
            (o.manifold, o.impulses, o.friction) = (*m, *i, *f);
        }
        let was_touching = self.touching;
        let mut out = MeshManifolds::EMPTY;
        // The pair is ordered like `collide`: the convex shape first.
        let flip = a.geometry.is_triangles();
        if flip {
            collide_triangles(store, &b.geometry, xf_b, &a.geometry, xf_a, speculative, &mut out);
            for m in out.manifolds[..out.count].iter_mut() {
                m.normal = -m.normal;
            }
        } else {
            collide_triangles(store, &a.geometry, xf_a, &b.geometry, xf_b, speculative, &mut out);
        }
        let count = out.count.max(1);
        self.more.truncate(count - 1);
        while self.more.len() < count - 1 {
            self.more.push(ChildManifold::default());
        }
        self.touching = out.count > 0;
        for k in 0..count {
            let m = if k < out.count {
                out.manifolds[k]
            } else {
                Manifold::EMPTY
            };
            let (impulses, friction) = carry_over(&m, &old[..old_count]);
            if k == 0 {
                (self.manifold, self.impulses, self.friction) = (m, impulses, friction);
            } else {
                let c = &mut self.more[k - 1];
                (c.manifold, c.impulses, c.friction) = (m, impulses, friction);
            }
        }
        let radii = (self.radius_a, self.radius_b);
        let (fa, fb) = self.cache.store(&self.manifold, xf_a, xf_b, radii);
        for c in self.more.iter_mut() {
            c.local.store(&c.manifold, &fa, &fb, radii.0, radii.1);
        }
        self.touching && !was_touching
    }
}

/// Impulses for a new manifold `m` from the old ones: each point's from the old point with
/// its id (in the old manifold with the closest normal first), friction from the closest
/// old manifold if its normal is within `FRICTION_MATCH_COS`.
fn carry_over(m: &Manifold, old: &[ChildManifold]) -> ([PointImpulse; MAX_MANIFOLD_POINTS], FrictionImpulse) {
    let mut impulses = [PointImpulse::default(); MAX_MANIFOLD_POINTS];
    let mut friction = FrictionImpulse::default();
    if m.count == 0 {
        return (impulses, friction);
    }
    let (mut best, mut best_cos) = (usize::MAX, FRICTION_MATCH_COS);
    for (k, o) in old.iter().enumerate() {
        let c = o.manifold.normal.dot(m.normal);
        if o.manifold.count > 0 && c >= best_cos {
            (best, best_cos) = (k, c);
        }
    }
    if best != usize::MAX {
        friction = old[best].friction;
    }
    for (p, imp) in m.points().iter().zip(impulses.iter_mut()) {
        let find = |o: &ChildManifold| {
            o.manifold
                .points()
                .iter()
                .zip(&o.impulses)
                .find(|(q, _)| q.id == p.id)
                .map(|(_, i)| *i)
        };
        *imp = (best != usize::MAX)
            .then(|| find(&old[best]))
            .flatten()
            .or_else(|| {
                old.iter()
                    .filter(|o| o.manifold.normal.dot(m.normal) >= FRICTION_MATCH_COS)
                    .find_map(find)
            })
            .unwrap_or_default();
    }
    (impulses, friction)
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

// Snapshots store the cached local frames: the narrow phase reuses them while the relative
// pose is unchanged, so they decide future manifolds.
crate::snap_struct!(ManifoldLocal {
    normal,
    local_a,
    local_b,
});
crate::snap_struct!(ManifoldCache {
    valid,
    relative_p,
    relative_q,
    local,
});
crate::snap_struct!(ChildManifold {
    manifold,
    impulses,
    friction,
    local,
});

//! Convex shapes for queries, and shape casts by conservative advancement.
//!
//! A query shape (sphere, capsule, box, hull) is a *core* (point, segment, eight corners,
//! polyhedron) plus a radius, as in `gjk.rs`. A cast moves it along `translation`; each
//! step takes the GJK distance between the cores, and the plane through the closest points
//! separates the two rounded shapes, so the shape can move `gap / closing speed` before it
//! can touch (the GJK ray cast of van den Bergen 2004; Box2D v3's `b2ShapeCast` works the
//! same way). It stops within `CAST_TOLERANCE` of the surface, so the fraction it returns
//! is never past the true time of impact and at most `CAST_TOLERANCE / |v · n|` before it.

use crate::collision::aabb::Aabb;
use crate::collision::geometry_store::GeometryStore;
use crate::collision::gjk::{self, Point, Segment, Support};
use crate::collision::hull::ConvexHull;
use crate::collision::shape::Geometry;
use crate::math::{Mat3, Transform, Vec3};

pub use super::ray::CAST_TOLERANCE;

/// Largest number of advancement steps.
const MAX_STEPS: u32 = 64;

/// A hull's core, scaled about its origin and placed by `frame`.
#[derive(Clone, Copy)]
pub struct HullCore<'a> {
    pub hull: &'a ConvexHull,
    pub frame: Transform,
    pub scale: f32,
}

impl Support for HullCore<'_> {
    #[inline]
    fn support(&self, d: Vec3) -> Vec3 {
        let i = self.hull.support_index(self.frame.q.conjugate() * d);
        self.frame.apply(self.hull.vertices()[i] * self.scale)
    }
    fn center(&self) -> Vec3 {
        let (lo, hi) = self.hull.local_bounds();
        self.frame.apply(0.5 * (lo + hi) * self.scale)
    }
}

/// The core of a convex shape in world space.
#[derive(Clone, Copy)]
pub enum Core<'a> {
    Point(Vec3),
    Segment(Vec3, Vec3),
    /// A box's corners.
    Corners([Vec3; 8]),
    Hull(HullCore<'a>),
    Triangle([Vec3; 3]),
}

impl Support for Core<'_> {
    #[inline]
    fn support(&self, d: Vec3) -> Vec3 {
        match self {
            Core::Point(p) => *p,
            Core::Segment(a, b) => Segment(*a, *b).support(d),
            Core::Corners(c) => gjk::Points(c).support(d),
            Core::Hull(h) => h.support(d),
            Core::Triangle(t) => gjk::Points(t).support(d),
        }
    }
    fn center(&self) -> Vec3 {
        match self {
            Core::Point(p) => *p,
            Core::Segment(a, b) => 0.5 * (*a + *b),
            Core::Corners(c) => gjk::Points(c).center(),
            Core::Hull(h) => h.center(),
            Core::Triangle(t) => (t[0] + t[1] + t[2]) / 3.0,
        }
    }
}

/// A core grown by a radius.
#[derive(Clone, Copy)]
pub struct Rounded<'a> {
    pub core: Core<'a>,
    pub radius: f32,
}

/// The rounded core of a convex shape (sphere, capsule, box, hull) on a body at `xf`;
/// `None` for planes, meshes and heightfields.
pub fn rounded<'a>(store: &'a GeometryStore, geometry: &Geometry, xf: &Transform) -> Option<Rounded<'a>> {
    Some(match *geometry {
        Geometry::Sphere { center, radius } => Rounded {
            core: Core::Point(xf.apply(center)),
            radius,
        },
        Geometry::Capsule { a, b, radius } => Rounded {
            core: Core::Segment(xf.apply(a), xf.apply(b)),
            radius,
        },
        Geometry::Box {
            center,
            rotation,
            half_extents: h,
        } => {
            let m = Mat3::from_quat(xf.q * rotation);
            let c = xf.apply(center);
            let mut corners = [Vec3::ZERO; 8];
            for (i, k) in corners.iter_mut().enumerate() {
                let s = Vec3::new(
                    if i & 1 == 0 { -h.x } else { h.x },
                    if i & 2 == 0 { -h.y } else { h.y },
                    if i & 4 == 0 { -h.z } else { h.z },
                );
                *k = c + m * s;
            }
            Rounded {
                core: Core::Corners(corners),
                radius: 0.0,
            }
        }
        Geometry::Hull { hull, local, scale } => {
            let h = store.hull_at(hull.index);
            Rounded {
                core: Core::Hull(HullCore {
                    hull: h,
                    frame: xf.mul(&local),
                    scale,
                }),
                radius: h.radius() * scale,
            }
        }
        Geometry::Plane { .. } | Geometry::Mesh { .. } | Geometry::Heightfield { .. } => return None,
    })
}

/// A support function moved by `offset`.
struct Shifted<'a, S: Support + ?Sized>(&'a S, Vec3);

impl<S: Support + ?Sized> Support for Shifted<'_, S> {
    #[inline]
    fn support(&self, d: Vec3) -> Vec3 {
        self.0.support(d) + self.1
    }
    fn center(&self) -> Vec3 {
        self.0.center() + self.1
    }
}

/// Result of a cast against one shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CastResult {
    /// Fraction of the translation at first contact (0 when overlapping at the start).
    pub fraction: f32,
    /// Unit normal of the hit surface, pointing back at the moving shape.
    pub normal: Vec3,
    /// Contact point on the hit surface (on overlap at the start: a point of the overlap).
    pub point: Vec3,
    /// The shapes overlapped at the start (then `fraction` is 0).
    pub start_overlap: bool,
}

/// Casts the rounded core `a` (radius `ra`) along `v` against the fixed rounded core `b`
/// (radius `rb`), up to fraction `max_t`.
pub fn advance<A: Support + ?Sized, B: Support + ?Sized>(
    a: &A,
    ra: f32,
    v: Vec3,
    b: &B,
    rb: f32,
    max_t: f32,
) -> Option<CastResult> {
    let r = ra + rb;
    let mut t = 0.0f32;
    let mut dir = b.center() - a.center();
    if dir.length_squared() < 1.0e-20 {
        dir = v;
    }
    for _ in 0..MAX_STEPS {
        let moved = Shifted(a, t * v);
        let g = gjk::distance_from(&moved, b, dir);
        let gap = g.distance - r;
        if g.overlap || gap <= CAST_TOLERANCE {
            let start_overlap = t == 0.0 && (g.overlap || gap < 0.0);
            let (normal, point) = if g.overlap || g.distance <= 0.0 {
                (-v.normalize_or(Vec3::Y), g.point_b)
            } else {
                (-g.normal, g.point_b - rb * g.normal)
            };
            return Some(CastResult {
                fraction: t,
                normal,
                point,
                start_overlap,
            });
        }
        let closing = v.dot(g.normal);
        if closing <= 0.0 {
            return None;
        }
        t += gap / closing;
        if t > max_t {
            return None;
        }
        dir = g.normal;
    }
    None
}

/// Casts a rounded shape along `v` against the half-space `dot(n, p) <= offset` (exact).
pub fn cast_plane(a: &Rounded, v: Vec3, n: Vec3, offset: f32, max_t: f32) -> Option<CastResult> {
    let deepest = a.core.support(-n) - a.radius * n;
    let above = n.dot(deepest) - offset;
    if above <= 0.0 {
        return Some(CastResult {
            fraction: 0.0,
            normal: n,
            point: deepest,
            start_overlap: true,
        });
    }
    let closing = -n.dot(v);
    if closing <= 0.0 {
        return None;
    }
    let t = above / closing;
    if t > max_t {
        return None;
    }
    Some(CastResult {
        fraction: t,
        normal: n,
        point: deepest + t * v,
        start_overlap: false,
    })
}

/// Calls `visit(triangle)` (world-space vertices) for every triangle of a mesh or
/// heightfield shape whose bounds overlap the world box `bb`, until it returns false.
pub fn for_triangles_in(
    store: &GeometryStore,
    geometry: &Geometry,
    xf: &Transform,
    bb: &Aabb,
    mut visit: impl FnMut([Vec3; 3]) -> bool,
) {
    match *geometry {
        Geometry::Mesh { mesh, local, scale } => {
            let frame = xf.mul(&local);
            let m = store.mesh_at(mesh.index);
            let lb = box_in_frame(bb, &frame, scale);
            m.query(&lb, |t| {
                let [a, b, c] = m.triangle(t);
                visit([frame.apply(a * scale), frame.apply(b * scale), frame.apply(c * scale)])
            });
        }
        Geometry::Heightfield {
            heightfield,
            local,
            scale,
        } => {
            let frame = xf.mul(&local);
            let h = store.heightfield_at(heightfield.index);
            let lb = box_in_frame(bb, &frame, scale);
            let mut go = true;
            h.query(&lb, |row, column| {
                for k in 0..2 {
                    let (v, _, _) = h.triangle(row, column, k, scale);
                    if go {
                        go = visit([frame.apply(v[0]), frame.apply(v[1]), frame.apply(v[2])]);
                    }
                }
                go
            });
        }
        _ => {}
    }
}

/// The box in the unscaled frame of `frame` (then divided by `scale`) bounding the world
/// box `bb`.
fn box_in_frame(bb: &Aabb, frame: &Transform, scale: Vec3) -> Aabb {
    let m = Mat3::from_quat(frame.q.conjugate());
    let c = frame.apply_inv(bb.center());
    let e = bb.extents();
    let e = Vec3::new(m.row(0).abs().dot(e), m.row(1).abs().dot(e), m.row(2).abs().dot(e));
    Aabb::new((c - e) / scale, (c + e) / scale)
}

/// Casts a rounded shape along `v` against a shape of the world (any kind), up to `max_t`.
pub fn cast_against(
    store: &GeometryStore,
    a: &Rounded,
    a_box: &Aabb,
    v: Vec3,
    geometry: &Geometry,
    xf: &Transform,
    max_t: f32,
) -> Option<CastResult> {
    match *geometry {
        Geometry::Plane { normal, offset } => {
            let n = xf.q * normal;
            cast_plane(a, v, n, offset + n.dot(xf.p), max_t)
        }
        Geometry::Mesh { .. } | Geometry::Heightfield { .. } => {
            let swept = a_box.swept(v * max_t);
            let mut best: Option<CastResult> = None;
            for_triangles_in(store, geometry, xf, &swept, |tri| {
                let lim = best.map_or(max_t, |b| b.fraction);
                if let Some(r) = advance(&a.core, a.radius, v, &Core::Triangle(tri), 0.0, lim) {
                    if best.map_or(true, |b| r.fraction < b.fraction) {
                        best = Some(r);
                    }
                }
                true
            });
            best
        }
        _ => {
            let b = rounded(store, geometry, xf).expect("a convex shape");
            advance(&a.core, a.radius, v, &b.core, b.radius, max_t)
        }
    }
}

/// Whether a rounded shape overlaps (or touches) a shape of the world (any kind).
pub fn overlaps(store: &GeometryStore, a: &Rounded, a_box: &Aabb, geometry: &Geometry, xf: &Transform) -> bool {
    match *geometry {
        Geometry::Plane { normal, offset } => {
            let n = xf.q * normal;
            n.dot(a.core.support(-n)) - a.radius <= offset + n.dot(xf.p)
        }
        Geometry::Mesh { .. } | Geometry::Heightfield { .. } => {
            let mut found = false;
            for_triangles_in(store, geometry, xf, a_box, |tri| {
                let g = gjk::distance(&a.core, &Core::Triangle(tri));
                found = g.overlap || g.distance <= a.radius;
                !found
            });
            found
        }
        _ => {
            if let Some(touch) = overlaps_simple(a, geometry, xf) {
                return touch;
            }
            let b = rounded(store, geometry, xf).expect("a convex shape");
            let g = gjk::distance(&a.core, &b.core);
            g.overlap || g.distance <= a.radius + b.radius
        }
    }
}

/// Squared distance from `p` to the segment `a`–`b`.
#[inline]
fn segment_distance_squared(p: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let s = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + s * ab)).length_squared()
}

/// Closed-form overlap (touching counts) of a query sphere or capsule with a sphere, box or
/// capsule, and of a query capsule with a sphere: a point's or a segment's distance
/// against the sum of the radii, no GJK. `None` for the other pairs (GJK decides those).
#[inline]
pub fn overlaps_simple(a: &Rounded, geometry: &Geometry, xf: &Transform) -> Option<bool> {
    // By reference: the query core (a box's eight corners) and the geometry are not copied
    // per shape tested.
    match (&a.core, geometry) {
        (&Core::Point(p), &Geometry::Sphere { center, radius }) => {
            let r = a.radius + radius;
            Some((p - xf.apply(center)).length_squared() <= r * r)
        }
        (
            &Core::Point(p),
            &Geometry::Box {
                center,
                rotation,
                half_extents: h,
            },
        ) => {
            let l = (xf.q * rotation).conjugate() * (p - xf.apply(center));
            let out = l - l.clamp(-h, h);
            Some(out.length_squared() <= a.radius * a.radius)
        }
        (&Core::Point(p), &Geometry::Capsule { a: ca, b: cb, radius }) => {
            let r = a.radius + radius;
            Some(segment_distance_squared(p, xf.apply(ca), xf.apply(cb)) <= r * r)
        }
        (&Core::Segment(s0, s1), &Geometry::Sphere { center, radius }) => {
            let r = a.radius + radius;
            Some(segment_distance_squared(xf.apply(center), s0, s1) <= r * r)
        }
        _ => None,
    }
}

/// Whether the point `p` lies inside (or on) a solid shape. Meshes and heightfields are
/// surfaces and contain no point.
pub fn contains_point(store: &GeometryStore, geometry: &Geometry, xf: &Transform, p: Vec3) -> bool {
    match *geometry {
        Geometry::Plane { normal, offset } => {
            let n = xf.q * normal;
            n.dot(p) <= offset + n.dot(xf.p)
        }
        Geometry::Mesh { .. } | Geometry::Heightfield { .. } => false,
        Geometry::Sphere { center, radius } => (p - xf.apply(center)).length_squared() <= radius * radius,
        Geometry::Box {
            center,
            rotation,
            half_extents,
        } => {
            let l = (xf.q * rotation).conjugate() * (p - xf.apply(center));
            l.abs().cmple(half_extents).all()
        }
        _ => {
            let b = rounded(store, geometry, xf).expect("a convex shape");
            let g = gjk::distance(&Point(p), &b.core);
            g.overlap || g.distance <= b.radius
        }
    }
}

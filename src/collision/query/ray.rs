//! A ray against one shape: the segment `origin + t · translation`, `t` in `[0, max_t]`.
//!
//! Rules for every kind:
//! * Solid shapes (sphere, box, capsule, hull, plane) are hit only from outside: a ray whose
//!   origin is inside one (or on its surface, heading in) does not hit it (Box2D v3's rule),
//!   so a ray cast from inside a character's capsule sees past it.
//! * Triangle meshes and heightfields are surfaces without volume: their triangles are hit
//!   from either side.
//! * The normal is the surface normal at the hit, unit length, facing the ray (for
//!   triangles hit from behind, the flipped face normal).
//!
//! Fractions are those of the translation, so they do not change under the rigid and
//! scaling maps into a shape's own frame; only normals are mapped back.

use crate::collision::dynamic_tree::ray_aabb_entry;
use crate::collision::geometry_store::GeometryStore;
use crate::collision::heightfield::Heightfield;
use crate::collision::hull::ConvexHull;
use crate::collision::mesh::bvh::{Node, MAX_DEPTH};
use crate::collision::mesh::TriangleMesh;
use crate::collision::shape::Geometry;
use crate::math::{Transform, Vec3};

/// A ray's hit on one shape: fraction of the translation and unit world normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeRayHit {
    pub fraction: f32,
    pub normal: Vec3,
}

/// Casts the ray (world space) against `geometry` on a body at `xf`.
pub fn ray_cast_geometry(
    store: &GeometryStore,
    geometry: &Geometry,
    xf: &Transform,
    origin: Vec3,
    translation: Vec3,
    max_t: f32,
) -> Option<ShapeRayHit> {
    match *geometry {
        Geometry::Sphere { center, radius } => ray_sphere(origin, translation, xf.apply(center), radius, max_t),
        Geometry::Box {
            center,
            rotation,
            half_extents,
        } => {
            let frame = Transform::new(xf.apply(center), xf.q * rotation);
            ray_box(origin, translation, &frame, half_extents, max_t)
        }
        Geometry::Capsule { a, b, radius } => ray_capsule(origin, translation, xf.apply(a), xf.apply(b), radius, max_t),
        Geometry::Plane { normal, offset } => {
            let n = xf.q * normal;
            ray_plane(origin, translation, n, offset + n.dot(xf.p), max_t)
        }
        Geometry::Hull { hull, local, scale } => {
            let frame = xf.mul(&local);
            ray_hull(store.hull_at(hull.index), &frame, scale, origin, translation, max_t)
        }
        Geometry::Mesh { mesh, local, scale } => {
            let frame = xf.mul(&local);
            ray_mesh(store.mesh_at(mesh.index), &frame, scale, origin, translation, max_t)
        }
        Geometry::Heightfield {
            heightfield,
            local,
            scale,
        } => {
            let frame = xf.mul(&local);
            ray_heightfield(
                store.heightfield_at(heightfield.index),
                &frame,
                scale,
                origin,
                translation,
                max_t,
            )
        }
    }
}

fn hit(fraction: f32, normal: Vec3) -> Option<ShapeRayHit> {
    Some(ShapeRayHit { fraction, normal })
}

/// Ray against a sphere; `None` from inside.
pub fn ray_sphere(origin: Vec3, d: Vec3, center: Vec3, radius: f32, max_t: f32) -> Option<ShapeRayHit> {
    let m = origin - center;
    let c = m.length_squared() - radius * radius;
    if c < 0.0 {
        return None;
    }
    let dd = d.length_squared();
    let b = m.dot(d);
    if b >= 0.0 || dd == 0.0 {
        return None;
    }
    let disc = b * b - dd * c;
    if disc < 0.0 {
        return None;
    }
    let t = (-b - disc.sqrt()) / dd;
    if !(0.0..=max_t).contains(&t) {
        return None;
    }
    let n = (m + t * d).normalize_or_zero();
    hit(t, if n == Vec3::ZERO { -d.normalize() } else { n })
}

/// Ray against a box with half extents `h` placed by `frame`; `None` from inside.
pub fn ray_box(origin: Vec3, d: Vec3, frame: &Transform, h: Vec3, max_t: f32) -> Option<ShapeRayHit> {
    // Arrays, so that the unrolled loop reads each axis directly (a `Vec3` indexed by a
    // variable goes through a match per access); the same operations per axis.
    let o = frame.apply_inv(origin).to_array();
    let dl = (frame.q.conjugate() * d).to_array();
    let h = h.to_array();
    let mut t0 = f32::MIN;
    let mut t1 = max_t;
    let mut axis = usize::MAX;
    let mut sign = 0.0;
    for a in 0..3 {
        if dl[a] == 0.0 {
            if o[a] < -h[a] || o[a] > h[a] {
                return None;
            }
            continue;
        }
        let inv = 1.0 / dl[a];
        let (mut ta, mut tb) = ((-h[a] - o[a]) * inv, (h[a] - o[a]) * inv);
        let mut s = -1.0;
        if ta > tb {
            std::mem::swap(&mut ta, &mut tb);
            s = 1.0;
        }
        if ta > t0 {
            t0 = ta;
            axis = a;
            sign = s;
        }
        t1 = t1.min(tb);
        if t0 > t1 {
            return None;
        }
    }
    // Inside (every entry behind the origin) or no axis moves: no hit.
    if axis == usize::MAX || t0 < 0.0 {
        return None;
    }
    let mut n = [0.0; 3];
    n[axis] = sign;
    hit(t0, frame.q * Vec3::from_array(n))
}

/// Ray against the capsule `a`–`b` of radius `r`; `None` from inside.
pub fn ray_capsule(origin: Vec3, d: Vec3, a: Vec3, b: Vec3, r: f32, max_t: f32) -> Option<ShapeRayHit> {
    let axis = b - a;
    let len2 = axis.length_squared();
    if len2 < 1.0e-12 {
        return ray_sphere(origin, d, a, r, max_t);
    }
    // Inside: distance from the origin to the segment below r.
    let s = ((origin - a).dot(axis) / len2).clamp(0.0, 1.0);
    if (origin - (a + s * axis)).length_squared() < r * r {
        return None;
    }
    // The infinite cylinder, in coordinates perpendicular to the axis.
    let u = axis / len2.sqrt();
    let m = origin - a;
    let mp = m - m.dot(u) * u;
    let dp = d - d.dot(u) * u;
    let qa = dp.length_squared();
    let mut best: Option<ShapeRayHit> = None;
    if qa > 1.0e-20 {
        let qb = mp.dot(dp);
        let qc = mp.length_squared() - r * r;
        let disc = qb * qb - qa * qc;
        if disc >= 0.0 {
            let t = (-qb - disc.sqrt()) / qa;
            if (0.0..=max_t).contains(&t) {
                let p = origin + t * d;
                let k = (p - a).dot(u);
                if (0.0..=len2.sqrt()).contains(&k) {
                    let n = (p - (a + k * u)).normalize_or_zero();
                    best = Some(ShapeRayHit { fraction: t, normal: n });
                }
            }
        }
    }
    // The end caps (a sphere hit beyond the cylinder part is the right one there).
    for c in [a, b] {
        if let Some(h) = ray_sphere(origin, d, c, r, max_t) {
            let k = (origin + h.fraction * d - a).dot(u);
            let on_cap = if c == a { k <= 0.0 } else { k >= len2.sqrt() };
            if on_cap && best.map_or(true, |x| h.fraction < x.fraction) {
                best = Some(h);
            }
        }
    }
    best
}

/// Ray against the half-space `dot(n, p) <= offset`; `None` from inside.
pub fn ray_plane(origin: Vec3, d: Vec3, n: Vec3, offset: f32, max_t: f32) -> Option<ShapeRayHit> {
    let above = n.dot(origin) - offset;
    let closing = -n.dot(d);
    if above <= 0.0 || closing <= 0.0 {
        return None;
    }
    let t = above / closing;
    if t > max_t {
        return None;
    }
    hit(t, n)
}

/// Conservative advancement stops this close to the surface (m).
pub const CAST_TOLERANCE: f32 = 1.0e-4;

/// Ray against a hull scaled by `scale` about its origin and placed by `frame`. A hull
/// without convex radius clips the ray against its face planes (exact); a rounded one is
/// reached by conservative advancement against its core, to within `CAST_TOLERANCE`.
pub fn ray_hull(
    h: &ConvexHull,
    frame: &Transform,
    scale: f32,
    origin: Vec3,
    d: Vec3,
    max_t: f32,
) -> Option<ShapeRayHit> {
    let radius = h.radius() * scale;
    if radius > 0.0 {
        let core = super::cast::HullCore {
            hull: h,
            frame: *frame,
            scale,
        };
        let r = super::cast::advance(&crate::collision::gjk::Point(origin), 0.0, d, &core, radius, max_t)?;
        // From inside (overlapping at the start) a ray does not hit.
        if r.fraction == 0.0 && r.start_overlap {
            return None;
        }
        return hit(r.fraction, r.normal);
    }
    let o = frame.apply_inv(origin) / scale;
    let dl = (frame.q.conjugate() * d) / scale;
    let mut t0 = f32::MIN;
    let mut t1 = max_t;
    let mut enter = Vec3::ZERO;
    for p in h.planes() {
        let num = p.offset - p.normal.dot(o);
        let den = p.normal.dot(dl);
        if den == 0.0 {
            if num < 0.0 {
                return None;
            }
        } else {
            let t = num / den;
            if den < 0.0 {
                if t > t0 {
                    t0 = t;
                    enter = p.normal;
                }
            } else {
                t1 = t1.min(t);
            }
        }
        if t0 > t1 {
            return None;
        }
    }
    if t0 < 0.0 || enter == Vec3::ZERO {
        return None;
    }
    hit(t0, frame.q * enter)
}

/// Two-sided ray–triangle test (Möller & Trumbore 1997): the fraction and the face normal
/// facing the ray (not normalised), or `None`.
#[inline]
pub fn ray_triangle(o: Vec3, d: Vec3, [a, b, c]: [Vec3; 3], max_t: f32) -> Option<(f32, Vec3)> {
    let e1 = b - a;
    let e2 = c - a;
    let p = d.cross(e2);
    let det = e1.dot(p);
    let n = e1.cross(e2);
    if det.abs() <= 1.0e-12 * n.length_squared().max(f32::MIN_POSITIVE) {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = d.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    if !(0.0..=max_t).contains(&t) {
        return None;
    }
    Some((t, if n.dot(d) > 0.0 { -n } else { n }))
}

/// Ray against a mesh scaled per axis by `scale` and placed by `frame`, through its BVH.
pub fn ray_mesh(
    mesh: &TriangleMesh,
    frame: &Transform,
    scale: Vec3,
    origin: Vec3,
    d: Vec3,
    max_t: f32,
) -> Option<ShapeRayHit> {
    // The unscaled mesh frame: the fraction is unchanged by the affine map.
    let o = frame.apply_inv(origin) / scale;
    let dl = (frame.q.conjugate() * d) / scale;
    let inv = recip(dl);
    let nodes: &[Node] = mesh.nodes();
    if nodes.is_empty() {
        return None;
    }
    let mut best_t = max_t;
    let mut best_n = Vec3::ZERO;
    let mut stack = [0u32; MAX_DEPTH + 2];
    let mut top = 1usize;
    while top > 0 {
        top -= 1;
        let i = stack[top];
        let n = &nodes[i as usize];
        if ray_aabb_entry(o, dl, inv, best_t, &n.bounds()).is_none() {
            continue;
        }
        if n.count > 0 {
            for t in n.data..n.data + n.count {
                if let Some((f, nn)) = ray_triangle(o, dl, mesh.triangle(t), best_t) {
                    best_t = f;
                    best_n = nn;
                }
            }
        } else {
            // The left child is the next node; the right one is `data`.
            stack[top] = n.data;
            stack[top + 1] = i + 1;
            top += 2;
        }
    }
    if best_n == Vec3::ZERO {
        return None;
    }
    // Normals map by the inverse transpose of the scale.
    hit(best_t, frame.q * (best_n / scale).normalize())
}

#[inline]
fn recip(d: Vec3) -> Vec3 {
    let r = |x: f32| if x == 0.0 { 0.0 } else { 1.0 / x };
    Vec3::new(r(d.x), r(d.y), r(d.z))
}

/// Cells per side of the box a heightfield ray tests at a time.
const HF_CHUNK: f32 = 8.0;

/// Ray against a heightfield with sample spacing and height scale `scale`, placed by
/// `frame`. The ray is walked in pieces spanning at most `HF_CHUNK` cells along x and z;
/// the first piece with a hit holds the nearest one.
pub fn ray_heightfield(
    hf: &Heightfield,
    frame: &Transform,
    scale: Vec3,
    origin: Vec3,
    d: Vec3,
    max_t: f32,
) -> Option<ShapeRayHit> {
    let o = frame.apply_inv(origin);
    let dl = frame.q.conjugate() * d;
    // Unscaled (cell) coordinates for the queries.
    let (ou, du) = (o / scale, dl / scale);
    let cells = du.x.abs().max(du.z.abs()) * max_t;
    let pieces = ((cells / HF_CHUNK).ceil() as u32).clamp(1, 1 << 20);
    let mut best: Option<(f32, Vec3)> = None;
    for k in 0..pieces {
        let ta = max_t * k as f32 / pieces as f32;
        let tb = if k + 1 == pieces {
            max_t
        } else {
            max_t * (k + 1) as f32 / pieces as f32
        };
        let (pa, pb) = (ou + ta * du, ou + tb * du);
        let bb = crate::collision::aabb::Aabb::new(pa.min(pb), pa.max(pb));
        hf.query(&bb, |row, column| {
            for tri in 0..2 {
                let (v, _, _) = hf.triangle(row, column, tri, scale);
                // Only hits inside this piece: a later piece may hold a nearer one beyond it.
                let lim = best.map_or(tb, |b| b.0.min(tb));
                if let Some((t, n)) = ray_triangle(o, dl, v, lim) {
                    best = Some((t, n));
                }
            }
            true
        });
        if best.is_some() {
            break;
        }
    }
    let (t, n) = best?;
    hit(t, frame.q * n.normalize())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::test_rnd::Rnd;
    use crate::math::Quat;

    /// `ray_box` as it was before it read the axes from arrays (a `Vec3` indexed per axis):
    /// the reference the current one must match bit for bit.
    fn ray_box_reference(origin: Vec3, d: Vec3, frame: &Transform, h: Vec3, max_t: f32) -> Option<ShapeRayHit> {
        let o = frame.apply_inv(origin);
        let dl = frame.q.conjugate() * d;
        let mut t0 = f32::MIN;
        let mut t1 = max_t;
        let mut axis = usize::MAX;
        let mut sign = 0.0;
        for a in 0..3 {
            if dl[a] == 0.0 {
                if o[a] < -h[a] || o[a] > h[a] {
                    return None;
                }
                continue;
            }
            let inv = 1.0 / dl[a];
            let (mut ta, mut tb) = ((-h[a] - o[a]) * inv, (h[a] - o[a]) * inv);
            let mut s = -1.0;
            if ta > tb {
                std::mem::swap(&mut ta, &mut tb);
                s = 1.0;
            }
            if ta > t0 {
                t0 = ta;
                axis = a;
                sign = s;
            }
            t1 = t1.min(tb);
            if t0 > t1 {
                return None;
            }
        }
        if axis == usize::MAX || t0 < 0.0 {
            return None;
        }
        let mut n = Vec3::ZERO;
        n[axis] = sign;
        hit(t0, frame.q * n)
    }

    fn bits(h: Option<ShapeRayHit>) -> Option<(u32, [u32; 3])> {
        h.map(|h| (h.fraction.to_bits(), h.normal.to_array().map(f32::to_bits)))
    }

    /// 20,000 seeded random rays against random boxes (rotated and axis-aligned frames,
    /// rays along an axis, from inside, short and long): the same hit, fraction and normal
    /// bits as the reference, and a fair share of them hits (1,905).
    #[test]
    fn ray_box_matches_the_reference_bit_for_bit() {
        let mut rng = Rnd(0x0b0c_5eed_1234_5678);
        let mut hits = 0;
        for k in 0..20_000 {
            let q = if k % 4 == 0 { Quat::IDENTITY } else { rng.quat() };
            let frame = Transform::new(rng.point(Vec3::splat(6.0)), q);
            let h = rng.point(Vec3::splat(3.0)).abs() + Vec3::splat(0.01);
            let origin = rng.point(Vec3::splat(16.0));
            let mut d = frame.p - origin + rng.point(Vec3::splat(4.0));
            match k % 9 {
                0 => d = q * Vec3::new(0.0, 0.0, d.length()),
                1 => d.y = 0.0,
                _ => {}
            }
            if d == Vec3::ZERO {
                d = Vec3::X;
            }
            let max_t = [1.0, 0.5, 2.0 * rng.f()][k % 3];
            let want = ray_box_reference(origin, d, &frame, h, max_t);
            assert_eq!(bits(ray_box(origin, d, &frame, h, max_t)), bits(want), "ray {k}");
            hits += want.is_some() as u32;
        }
        assert!(hits > 1_500, "{hits} hits");
    }
}

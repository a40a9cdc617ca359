//! Randomised consistency checks over every pair: unit finite normals, surface points on
//! the right shapes, swapped order flipping the normal, distinct ids.

use super::{collide_primitives as collide, Manifold};
use crate::collision::shape::Geometry;
use crate::math::{Quat, Transform, Vec3};

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 40) as f32) / ((1u64 << 24) as f32)
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }
    fn vec(&mut self, s: f32) -> Vec3 {
        Vec3::new(self.range(-s, s), self.range(-s, s), self.range(-s, s))
    }
    fn quat(&mut self) -> Quat {
        let v = Vec3::new(self.range(-1.0, 1.0), self.range(-1.0, 1.0), self.range(-1.0, 1.0));
        let w = self.range(-1.0, 1.0);
        Quat::from_xyzw(v.x, v.y, v.z, w).normalize()
    }
}

/// Signed distance from world point `p` to the shape.
fn sdf(g: &Geometry, xf: &Transform, p: Vec3) -> f32 {
    let l = xf.apply_inv(p);
    match *g {
        Geometry::Sphere { center, radius } => (l - center).length() - radius,
        Geometry::Capsule { a, b, radius } => {
            let d = b - a;
            let t = if d.length_squared() > 0.0 {
                ((l - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (l - (a + t * d)).length() - radius
        }
        Geometry::Box {
            center,
            rotation,
            half_extents,
        } => {
            let q = rotation.conjugate() * (l - center);
            let d = q.abs() - half_extents;
            d.max(Vec3::ZERO).length() + d.max_element().min(0.0)
        }
        Geometry::Plane { normal, offset } => (normal.dot(l) - offset) / normal.length(),
        Geometry::Hull { .. } | Geometry::Mesh { .. } | Geometry::Heightfield { .. } => {
            unreachable!("the primitive fuzz tests make no shared geometry")
        }
    }
}

/// On the surface; a capsule's end-cap point may also lie inside the capsule (the cap
/// sphere's point when the axis is steep), which is how capsule ends are reported.
fn surface(g: &Geometry, d: f32, tol: f32) -> bool {
    match g {
        Geometry::Capsule { .. } => d <= tol,
        _ => d.abs() <= tol,
    }
}

fn random_shape(r: &mut Lcg, kind: usize) -> Geometry {
    match kind {
        0 => Geometry::Sphere {
            center: r.vec(0.2),
            radius: r.range(0.1, 0.8),
        },
        1 => {
            let c = r.vec(0.2);
            let h = r.vec(0.8);
            Geometry::Capsule {
                a: c - h,
                b: c + h,
                radius: r.range(0.05, 0.5),
            }
        }
        2 => Geometry::Box {
            center: r.vec(0.2),
            rotation: r.quat(),
            half_extents: Vec3::new(r.range(0.1, 1.0), r.range(0.1, 1.0), r.range(0.1, 1.0)),
        },
        _ => Geometry::Plane {
            normal: r.vec(1.0).normalize_or(Vec3::Y),
            offset: r.range(-0.5, 0.5),
        },
    }
}

fn check(a: &Geometry, xa: &Transform, b: &Geometry, xb: &Transform, spec: f32, m: &Manifold) {
    assert!(m.count <= 4);
    if m.count == 0 {
        return;
    }
    assert!(m.normal.is_finite() && (m.normal.length() - 1.0).abs() < 1e-4, "{m:?}");
    for (i, p) in m.points().iter().enumerate() {
        assert!(p.point.is_finite() && p.separation.is_finite(), "{m:?}");
        assert!(p.separation <= spec + 1e-5, "{m:?}");
        let on_a = p.point - 0.5 * p.separation * m.normal;
        let on_b = p.point + 0.5 * p.separation * m.normal;
        let mut tol = 2e-3 * (1.0 + p.separation.abs());
        if let (Geometry::Capsule { a: p0, b: p1, .. }, Geometry::Capsule { a: q0, b: q1, .. }) = (a, b) {
            if m.count == 2 {
                // Side-by-side capsules share one normal; a slight twist between the axes
                // (at most 0.05 rad) offsets the points sideways.
                tol += 0.05 * ((*p1 - *p0).length() + (*q1 - *q0).length());
            }
        }
        for q in &m.points()[..i] {
            assert_ne!(q.id, p.id, "{m:?}");
        }
        // A separated box edge pair is a separating-axis lower bound whose edges need not
        // face each other: its point is midway between the edges' closest points.
        if p.separation > 0.0 && p.id & (1 << 31) != 0 {
            continue;
        }
        // Each surface point lies on (or, for the face of a clipped polygon, inside) its shape.
        assert!(
            surface(a, sdf(a, xa, on_a), tol),
            "A surface {} {a:?} {b:?} {m:?}",
            sdf(a, xa, on_a)
        );
        assert!(
            surface(b, sdf(b, xb, on_b), tol),
            "B surface {} {a:?} {b:?} {m:?}",
            sdf(b, xb, on_b)
        );
    }
}

#[test]
fn random_pairs_are_consistent() {
    let mut r = Lcg(0x5eed);
    let mut hits = [0usize; 16];
    for iter in 0..100_000 {
        let (ka, kb) = (iter % 4, (iter / 4) % 4);
        if ka == 3 && kb == 3 {
            continue;
        }
        let a = random_shape(&mut r, ka);
        let b = random_shape(&mut r, kb);
        let xa = Transform::new(r.vec(0.5), r.quat());
        let reach = if (iter / 16) % 2 == 0 { 0.4 } else { 1.5 };
        let xb = Transform::new(xa.p + r.vec(reach), r.quat());
        let spec = if r.next() < 0.5 { 0.0 } else { r.range(0.0, 0.5) };
        let m = collide(&a, &xa, &b, &xb, spec);
        check(&a, &xa, &b, &xb, spec, &m);
        if m.count == 0 {
            // Nothing within `spec`: a wider search agrees.
            let wide = collide(&a, &xa, &b, &xb, spec + 5.0);
            assert!(
                wide.points().iter().all(|p| p.separation > spec - 1e-4),
                "{a:?} {b:?} {wide:?}"
            );
        } else {
            // The deepest point never gets deeper with a wider search.
            let min = m.points().iter().map(|p| p.separation).fold(f32::MAX, f32::min);
            let wide = collide(&a, &xa, &b, &xb, spec + 5.0);
            let wmin = wide.points().iter().map(|p| p.separation).fold(f32::MAX, f32::min);
            assert!(
                wide.count > 0 && (wmin - min).abs() < 1e-4,
                "{a:?} {b:?} {m:?} {wide:?}"
            );
        }
        let s = collide(&b, &xb, &a, &xa, spec);
        if ka != kb {
            assert_eq!(m.count, s.count);
            if m.count > 0 {
                assert!((m.normal + s.normal).length() < 1e-5);
                for (p, q) in m.points().iter().zip(s.points()) {
                    assert!((p.point - q.point).length() < 1e-5 && p.separation == q.separation);
                }
            }
        } else {
            check(&b, &xb, &a, &xa, spec, &s);
        }
        if m.count > 0 {
            hits[ka * 4 + kb] += 1;
        }
    }
    // Every pair other than plane–plane produced contacts at some point.
    for (i, h) in hits.iter().enumerate() {
        if i != 15 {
            assert!(*h > 50, "pair {i} hit {h} times");
        }
    }
}

#[test]
fn plane_plane_is_empty() {
    let p = Geometry::Plane {
        normal: Vec3::Y,
        offset: 0.0,
    };
    assert_eq!(
        collide(&p, &Transform::IDENTITY, &p, &Transform::IDENTITY, 1.0).count,
        0
    );
}

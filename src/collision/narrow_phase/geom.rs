//! Small geometric helpers shared by the pair routines: world-space views of boxes and
//! planes, closest points on segments, and manifold assembly.

use super::{Manifold, ManifoldPoint, MAX_MANIFOLD_POINTS};
use crate::math::{Mat3, Quat, Transform, Vec3};

/// Normal used when the geometry gives no direction (coincident centres, zero-length axes).
pub(crate) const FALLBACK_NORMAL: Vec3 = Vec3::Y;

/// Squared distance under which two points are treated as coincident (no direction).
pub(crate) const DEGENERATE_DIST_SQ: f32 = 1.0e-12;

/// An oriented box placed in world space.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WorldBox {
    pub center: Vec3,
    /// Columns are the box axes in world space.
    pub rot: Mat3,
    pub half: Vec3,
}

impl WorldBox {
    #[inline]
    pub fn new(center: Vec3, rotation: Quat, half: Vec3, xf: &Transform) -> Self {
        WorldBox {
            center: xf.apply(center),
            rot: Mat3::from_quat(xf.q * rotation),
            half,
        }
    }

    /// World direction into the box frame.
    #[inline]
    pub fn dir_to_local(&self, d: Vec3) -> Vec3 {
        Vec3::new(self.rot.x_axis.dot(d), self.rot.y_axis.dot(d), self.rot.z_axis.dot(d))
    }

    #[inline]
    pub fn apply_inv(&self, p: Vec3) -> Vec3 {
        self.dir_to_local(p - self.center)
    }

    #[inline]
    pub fn apply(&self, p: Vec3) -> Vec3 {
        self.rot * p + self.center
    }
}

/// A half-space `dot(n, p) <= d` in world space with unit `n`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WorldPlane {
    pub n: Vec3,
    pub d: f32,
}

impl WorldPlane {
    /// Places a body-local plane in world space. A non-unit normal is normalised together
    /// with its offset so the half-space stays the same; a zero normal falls back to +Y.
    #[inline]
    pub fn new(normal: Vec3, offset: f32, xf: &Transform) -> Self {
        let len = normal.length();
        let (n_local, off) = if len > 1.0e-12 {
            (normal / len, offset / len)
        } else {
            (FALLBACK_NORMAL, offset)
        };
        let n = xf.q * n_local;
        WorldPlane {
            n,
            d: off + n.dot(xf.p),
        }
    }

    /// Signed distance of `p` above the plane surface.
    #[inline]
    pub fn distance(&self, p: Vec3) -> f32 {
        self.n.dot(p) - self.d
    }
}

/// Closest point to `p` on the segment `a`–`b` (a point when `a == b`).
#[inline]
pub(crate) fn closest_on_segment(p: Vec3, a: Vec3, b: Vec3) -> Vec3 {
    let d = b - a;
    let dd = d.dot(d);
    if dd <= DEGENERATE_DIST_SQ {
        return a;
    }
    let t = ((p - a).dot(d) / dd).clamp(0.0, 1.0);
    a + t * d
}

/// Parameters `(s, t)` of the closest points `p1 + s (q1 - p1)` and `p2 + t (q2 - p2)`
/// between two segments (Ericson, Real-Time Collision Detection 5.1.9). Degenerate and
/// parallel segments give a valid pair.
pub(crate) fn closest_segment_segment(p1: Vec3, q1: Vec3, p2: Vec3, q2: Vec3) -> (f32, f32) {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let a = d1.dot(d1);
    let e = d2.dot(d2);
    let f = d2.dot(r);
    if a <= DEGENERATE_DIST_SQ && e <= DEGENERATE_DIST_SQ {
        return (0.0, 0.0);
    }
    if a <= DEGENERATE_DIST_SQ {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(r);
    if e <= DEGENERATE_DIST_SQ {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let denom = a * e - b * b;
    let mut s = if denom > 1.0e-7 * a * e {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// Some unit vector perpendicular to unit `u`.
#[inline]
pub(crate) fn any_perpendicular(u: Vec3) -> Vec3 {
    crate::math::orthonormal_basis(u).0
}

/// Appends a point if there is room.
#[inline]
pub(crate) fn push_point(m: &mut Manifold, point: Vec3, separation: f32, id: u32) {
    if m.count < MAX_MANIFOLD_POINTS {
        m.points[m.count] = ManifoldPoint { point, separation, id };
        m.count += 1;
    }
}

/// A manifold with one point, or empty when `separation > speculative`.
#[inline]
pub(crate) fn single_point(normal: Vec3, point: Vec3, separation: f32, id: u32, speculative: f32) -> Manifold {
    if separation > speculative {
        return Manifold::EMPTY;
    }
    let mut m = Manifold {
        normal,
        ..Manifold::EMPTY
    };
    push_point(&mut m, point, separation, id);
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_segment_crossing_and_parallel() {
        let (s, t) = closest_segment_segment(
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, -1.0),
            Vec3::new(0.0, 1.0, 1.0),
        );
        assert!((s - 0.5).abs() < 1e-6 && (t - 0.5).abs() < 1e-6);
        // Parallel overlapping: the pair must be perpendicular to both.
        let p1 = Vec3::new(0.0, 0.0, 0.0);
        let q1 = Vec3::new(2.0, 0.0, 0.0);
        let p2 = Vec3::new(1.0, 1.0, 0.0);
        let q2 = Vec3::new(3.0, 1.0, 0.0);
        let (s, t) = closest_segment_segment(p1, q1, p2, q2);
        let d = (p2 + t * (q2 - p2)) - (p1 + s * (q1 - p1));
        assert!((d - Vec3::Y).length() < 1e-5, "{d}");
        // Degenerate.
        assert_eq!(closest_segment_segment(p1, p1, p2, p2), (0.0, 0.0));
    }

    #[test]
    fn plane_in_world() {
        let xf = Transform::new(
            Vec3::new(0.0, 2.0, 0.0),
            Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
        );
        let pl = WorldPlane::new(Vec3::Y * 2.0, 2.0, &xf);
        // Local +Y becomes world -X; local offset 1 after normalisation; origin at y=2.
        assert!((pl.n - Vec3::NEG_X).length() < 1e-6);
        assert!((pl.distance(Vec3::new(-1.0, 5.0, 0.0))).abs() < 1e-6);
    }
}

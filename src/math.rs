//! Math types used by the engine core. Vectors and quaternions are glam's; a rigid
//! transform is ours so that the core never depends on a C layout.

pub use glam::{Mat3, Quat, Vec3};

/// A rigid transform: rotate by `q`, then translate by `p`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    pub p: Vec3,
    pub q: Quat,
}

impl Transform {
    pub const IDENTITY: Transform = Transform {
        p: Vec3::ZERO,
        q: Quat::IDENTITY,
    };

    #[inline]
    pub fn new(p: Vec3, q: Quat) -> Self {
        Transform { p, q }
    }

    /// Maps a point from local to world space.
    #[inline]
    pub fn apply(&self, v: Vec3) -> Vec3 {
        self.q * v + self.p
    }

    /// Maps a point from world to local space.
    #[inline]
    pub fn apply_inv(&self, v: Vec3) -> Vec3 {
        self.q.conjugate() * (v - self.p)
    }

    /// `self * other`: first `other`, then `self`.
    #[inline]
    pub fn mul(&self, other: &Transform) -> Transform {
        Transform {
            p: self.q * other.p + self.p,
            q: (self.q * other.q).normalize(),
        }
    }

    /// `inverse(self) * other`: `other` expressed in the frame of `self`.
    #[inline]
    pub fn inv_mul(&self, other: &Transform) -> Transform {
        let qi = self.q.conjugate();
        Transform {
            p: qi * (other.p - self.p),
            q: (qi * other.q).normalize(),
        }
    }
}

impl Default for Transform {
    fn default() -> Self {
        Transform::IDENTITY
    }
}

/// Builds two unit vectors orthogonal to `n` and to each other (`n` must be unit length).
/// Branch-free construction by Duff et al., "Building an orthonormal basis, revisited".
#[inline]
pub fn orthonormal_basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    let t1 = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    let t2 = Vec3::new(b, sign + n.y * n.y * a, -n.y);
    (t1, t2)
}

/// `v` shortened to at most `max` (`max > 0`) long, keeping its direction. Safe for any
/// input: where the squared length overflows `f32` the vector is scaled down first, an
/// infinite component gives the direction of its sign, and NaN components count as zero.
#[inline]
pub fn clamp_length(v: Vec3, max: f32) -> Vec3 {
    let s2 = v.length_squared();
    if s2 <= max * max {
        return v;
    }
    if s2.is_finite() {
        return v * (max / s2.sqrt());
    }
    let v = Vec3::select(v.is_nan_mask(), Vec3::ZERO, v);
    let infinite = v.abs().cmpeq(Vec3::INFINITY);
    let dir = if infinite.any() {
        Vec3::select(infinite, v.signum(), Vec3::ZERO)
    } else {
        let m = v.abs().max_element();
        if m > 0.0 {
            v / m
        } else {
            Vec3::ZERO
        }
    };
    dir.normalize_or_zero() * max
}

/// `v` shortened to at most `max` long (keeping its direction) and converted to f32; `v`
/// must be finite.
#[inline]
pub fn clamp_length_f64(v: glam::DVec3, max: f32) -> Vec3 {
    let l = v.length();
    if l > max as f64 {
        (v * (max as f64 / l)).as_vec3()
    } else {
        v.as_vec3()
    }
}

/// Integrates an orientation by an angular velocity over `h` seconds and renormalises.
#[inline]
pub fn integrate_rotation(q: Quat, w: Vec3, h: f32) -> Quat {
    let dq = Quat::from_xyzw(w.x, w.y, w.z, 0.0) * q;
    let r = Quat::from_xyzw(
        q.x + 0.5 * h * dq.x,
        q.y + 0.5 * h * dq.y,
        q.z + 0.5 * h * dq.z,
        q.w + 0.5 * h * dq.w,
    );
    r.normalize()
}

/// `r · m · rᵀ` (an inverse inertia turned by `r`) in `Mat3A`'s SIMD columns: each product
/// of glam's `Mat3` (column `k` is `(x_axis·v.x + y_axis·v.y) + z_axis·v.z`) in the same
/// order lane by lane, so the same bits as `r * m * r.transpose()` in fewer instructions
/// (`turned_inertia_is_the_scalar_product`).
#[inline]
pub fn turned_inertia(r: Mat3, m: Mat3) -> Mat3 {
    let r = glam::Mat3A::from(r);
    Mat3::from(r * glam::Mat3A::from(m) * r.transpose())
}

/// xorshift64 randomness for unit tests: floats in [0, 1), points, rotations, clouds.
#[cfg(test)]
pub(crate) mod test_rnd {
    use super::{Quat, Vec3};

    pub(crate) struct Rnd(pub(crate) u64);

    impl Rnd {
        /// The next state of the xorshift generator.
        pub(crate) fn next_u64(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }

        /// A value in `[0, 1)`.
        pub(crate) fn f(&mut self) -> f32 {
            (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
        }

        /// A point of the box `scale` centred on the origin.
        pub(crate) fn point(&mut self, scale: Vec3) -> Vec3 {
            Vec3::new(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5) * scale
        }

        pub(crate) fn quat(&mut self) -> Quat {
            Quat::from_xyzw(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5, self.f() - 0.5).normalize()
        }

        /// `min` to `min + span` points in a box whose half-sizes are `base + extra · f()`.
        pub(crate) fn cloud(&mut self, min: usize, span: f32, base: f32, extra: f32) -> Vec<Vec3> {
            let n = min + (self.f() * span) as usize;
            let axes = Vec3::new(
                base + extra * self.f(),
                base + extra * self.f(),
                base + extra * self.f(),
            );
            (0..n).map(|_| self.point(2.0 * axes)).collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `turned_inertia` gives `r * m * r.transpose()` bit for bit: random rotations against
    /// random symmetric and general matrices over many magnitudes, and zero.
    #[test]
    fn turned_inertia_is_the_scalar_product() {
        let mut rnd = test_rnd::Rnd(0x243f_6a88_85a3_08d3);
        for trial in 0..20000 {
            let r = Mat3::from_quat(rnd.quat());
            let scale = [1.0e-6, 1.0e-2, 1.0, 30.0, 1.0e5][trial % 5];
            let mut col = || Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5) * scale;
            let g = Mat3::from_cols(col(), col(), col());
            let m = match trial % 3 {
                0 => g,
                1 => g + g.transpose(),
                _ => Mat3::from_diagonal(g.x_axis.abs()),
            };
            let (fast, plain) = (turned_inertia(r, m), r * m * r.transpose());
            assert_eq!(
                fast.to_cols_array().map(f32::to_bits),
                plain.to_cols_array().map(f32::to_bits),
                "trial {trial}"
            );
        }
        assert_eq!(turned_inertia(Mat3::IDENTITY, Mat3::ZERO), Mat3::ZERO);
    }

    #[test]
    fn basis_is_orthonormal() {
        for n in [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(1.0, 2.0, -3.0).normalize(),
        ] {
            let (t1, t2) = orthonormal_basis(n);
            assert!(t1.dot(n).abs() < 1e-6 && t2.dot(n).abs() < 1e-6 && t1.dot(t2).abs() < 1e-6);
            assert!((t1.length() - 1.0).abs() < 1e-6 && (t2.length() - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn clamp_length_is_safe_for_any_input() {
        let v = Vec3::new(3.0, 4.0, 0.0);
        assert_eq!(clamp_length(v, 10.0), v);
        assert!((clamp_length(v, 1.0) - Vec3::new(0.6, 0.8, 0.0)).length() < 1e-6);
        let big = clamp_length(Vec3::new(3.0e38, -3.0e38, 0.0), 2.0);
        assert!((big - Vec3::new(2.0f32.sqrt(), -(2.0f32.sqrt()), 0.0)).length() < 1e-5);
        let inf = clamp_length(Vec3::new(f32::INFINITY, 1.0, f32::NEG_INFINITY), 2.0);
        assert!((inf - Vec3::new(2.0f32.sqrt(), 0.0, -(2.0f32.sqrt()))).length() < 1e-5);
        assert_eq!(clamp_length(Vec3::new(f32::NAN, f32::NAN, f32::NAN), 1.0), Vec3::ZERO);
        assert!(clamp_length(Vec3::new(f32::NAN, 5.0, 0.0), 1.0).is_finite());
    }

    #[test]
    fn transform_roundtrip() {
        let t = Transform::new(Vec3::new(1.0, 2.0, 3.0), Quat::from_rotation_y(0.7));
        let p = Vec3::new(-0.3, 0.5, 2.0);
        assert!((t.apply_inv(t.apply(p)) - p).length() < 1e-6);
        let u = Transform::new(Vec3::new(0.5, 0.0, -1.0), Quat::from_rotation_x(0.3));
        let tu = t.mul(&u);
        assert!((tu.apply(p) - t.apply(u.apply(p))).length() < 1e-5);
        let back = t.inv_mul(&tu);
        assert!((back.p - u.p).length() < 1e-5);
    }
}

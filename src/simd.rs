//! Four-lane floats for the contact solver: `F4` (four `f32`), `V4` (four 3-vectors) and
//! `M4` (four 3×3 matrices). SSE2 on x86_64 (part of the baseline, no detection needed),
//! plain arrays elsewhere. Each lane holds a different constraint; lanes never interact.

use crate::math::{Mat3, Vec3};

#[cfg(target_arch = "x86_64")]
mod imp {
    use std::arch::x86_64::*;

    #[derive(Clone, Copy, Debug)]
    #[repr(transparent)]
    pub struct F4(pub __m128);

    // The primitive lane operations; the operator traits below call them.
    #[allow(clippy::should_implement_trait)]
    impl F4 {
        // SAFETY: `__m128` is four `f32`s.
        pub const ZERO_CONST: F4 = F4(unsafe { std::mem::transmute::<[f32; 4], __m128>([0.0; 4]) });
        pub const ONE_CONST: F4 = F4(unsafe { std::mem::transmute::<[f32; 4], __m128>([1.0; 4]) });

        #[inline(always)]
        pub fn splat(x: f32) -> F4 {
            unsafe { F4(_mm_set1_ps(x)) }
        }
        #[inline(always)]
        pub fn from_array(a: [f32; 4]) -> F4 {
            unsafe { F4(_mm_loadu_ps(a.as_ptr())) }
        }
        #[inline(always)]
        pub fn to_array(self) -> [f32; 4] {
            let mut a = [0.0; 4];
            unsafe { _mm_storeu_ps(a.as_mut_ptr(), self.0) };
            a
        }
        #[inline(always)]
        pub fn add(self, o: F4) -> F4 {
            unsafe { F4(_mm_add_ps(self.0, o.0)) }
        }
        #[inline(always)]
        pub fn sub(self, o: F4) -> F4 {
            unsafe { F4(_mm_sub_ps(self.0, o.0)) }
        }
        #[inline(always)]
        pub fn mul(self, o: F4) -> F4 {
            unsafe { F4(_mm_mul_ps(self.0, o.0)) }
        }
        #[inline(always)]
        pub fn div(self, o: F4) -> F4 {
            unsafe { F4(_mm_div_ps(self.0, o.0)) }
        }
        #[inline(always)]
        pub fn min(self, o: F4) -> F4 {
            unsafe { F4(_mm_min_ps(self.0, o.0)) }
        }
        #[inline(always)]
        pub fn max(self, o: F4) -> F4 {
            unsafe { F4(_mm_max_ps(self.0, o.0)) }
        }
        #[inline(always)]
        pub fn sqrt(self) -> F4 {
            unsafe { F4(_mm_sqrt_ps(self.0)) }
        }
        /// All-ones lanes where `self > o`.
        #[inline(always)]
        pub fn gt(self, o: F4) -> F4 {
            unsafe { F4(_mm_cmpgt_ps(self.0, o.0)) }
        }
        #[inline(always)]
        pub fn ge(self, o: F4) -> F4 {
            unsafe { F4(_mm_cmpge_ps(self.0, o.0)) }
        }
        #[inline(always)]
        pub fn le(self, o: F4) -> F4 {
            unsafe { F4(_mm_cmple_ps(self.0, o.0)) }
        }
        #[inline(always)]
        pub fn and(self, o: F4) -> F4 {
            unsafe { F4(_mm_and_ps(self.0, o.0)) }
        }
        #[inline(always)]
        pub fn or(self, o: F4) -> F4 {
            unsafe { F4(_mm_or_ps(self.0, o.0)) }
        }
        /// Lanes of `a` where the mask is set, else lanes of `b`.
        #[inline(always)]
        pub fn select(mask: F4, a: F4, b: F4) -> F4 {
            unsafe { F4(_mm_or_ps(_mm_and_ps(mask.0, a.0), _mm_andnot_ps(mask.0, b.0))) }
        }
        /// One bit per lane of a mask.
        #[inline(always)]
        pub fn bits(self) -> u32 {
            unsafe { _mm_movemask_ps(self.0) as u32 }
        }
    }

    /// Four rows of four floats in, four columns out (a 4×4 transpose).
    #[inline(always)]
    pub fn transpose(r: [F4; 4]) -> [F4; 4] {
        unsafe {
            let t0 = _mm_unpacklo_ps(r[0].0, r[1].0);
            let t1 = _mm_unpacklo_ps(r[2].0, r[3].0);
            let t2 = _mm_unpackhi_ps(r[0].0, r[1].0);
            let t3 = _mm_unpackhi_ps(r[2].0, r[3].0);
            [
                F4(_mm_movelh_ps(t0, t1)),
                F4(_mm_movehl_ps(t1, t0)),
                F4(_mm_movelh_ps(t2, t3)),
                F4(_mm_movehl_ps(t3, t2)),
            ]
        }
    }

    #[inline(always)]
    pub fn load(a: &[f32; 4]) -> F4 {
        unsafe { F4(_mm_loadu_ps(a.as_ptr())) }
    }

    #[inline(always)]
    pub fn store(v: F4, a: &mut [f32; 4]) {
        unsafe { _mm_storeu_ps(a.as_mut_ptr(), v.0) }
    }
}

#[cfg(not(target_arch = "x86_64"))]
mod imp {
    #[derive(Clone, Copy, Debug)]
    #[repr(C, align(16))]
    pub struct F4(pub [f32; 4]);

    macro_rules! lanes {
        ($a:expr, $b:expr, |$x:ident, $y:ident| $e:expr) => {{
            let (a, b) = ($a.0, $b.0);
            F4([
                {
                    let ($x, $y) = (a[0], b[0]);
                    $e
                },
                {
                    let ($x, $y) = (a[1], b[1]);
                    $e
                },
                {
                    let ($x, $y) = (a[2], b[2]);
                    $e
                },
                {
                    let ($x, $y) = (a[3], b[3]);
                    $e
                },
            ])
        }};
    }

    const TRUE: f32 = unsafe { std::mem::transmute::<u32, f32>(u32::MAX) };

    #[allow(clippy::should_implement_trait)]
    impl F4 {
        pub fn splat(x: f32) -> F4 {
            F4([x; 4])
        }
        pub fn from_array(a: [f32; 4]) -> F4 {
            F4(a)
        }
        pub fn to_array(self) -> [f32; 4] {
            self.0
        }
        pub fn add(self, o: F4) -> F4 {
            lanes!(self, o, |x, y| x + y)
        }
        pub fn sub(self, o: F4) -> F4 {
            lanes!(self, o, |x, y| x - y)
        }
        pub fn mul(self, o: F4) -> F4 {
            lanes!(self, o, |x, y| x * y)
        }
        pub fn div(self, o: F4) -> F4 {
            lanes!(self, o, |x, y| x / y)
        }
        pub fn min(self, o: F4) -> F4 {
            lanes!(self, o, |x, y| if x < y { x } else { y })
        }
        pub fn max(self, o: F4) -> F4 {
            lanes!(self, o, |x, y| if x > y { x } else { y })
        }
        pub fn sqrt(self) -> F4 {
            F4(self.0.map(f32::sqrt))
        }
        pub fn gt(self, o: F4) -> F4 {
            lanes!(self, o, |x, y| if x > y { TRUE } else { 0.0 })
        }
        pub fn ge(self, o: F4) -> F4 {
            lanes!(self, o, |x, y| if x >= y { TRUE } else { 0.0 })
        }
        pub fn and(self, o: F4) -> F4 {
            lanes!(self, o, |x, y| f32::from_bits(x.to_bits() & y.to_bits()))
        }
        pub fn or(self, o: F4) -> F4 {
            lanes!(self, o, |x, y| f32::from_bits(x.to_bits() | y.to_bits()))
        }
        pub fn select(mask: F4, a: F4, b: F4) -> F4 {
            let m = mask.0;
            F4([0, 1, 2, 3].map(|i| if m[i].to_bits() != 0 { a.0[i] } else { b.0[i] }))
        }
        pub fn bits(self) -> u32 {
            (0..4).fold(0, |acc, i| acc | (((self.0[i].to_bits() >> 31) & 1) << i))
        }
    }

    pub fn transpose(r: [F4; 4]) -> [F4; 4] {
        [0, 1, 2, 3].map(|c| F4([r[0].0[c], r[1].0[c], r[2].0[c], r[3].0[c]]))
    }

    pub fn load(a: &[f32; 4]) -> F4 {
        F4(*a)
    }

    pub fn store(v: F4, a: &mut [f32; 4]) {
        *a = v.0;
    }
}

pub use imp::{load, store, transpose, F4};

impl F4 {
    pub const ZERO_ARRAY: [f32; 4] = [0.0; 4];

    #[inline(always)]
    pub fn zero() -> F4 {
        F4::splat(0.0)
    }
    #[inline(always)]
    pub fn mul_add(self, a: F4, b: F4) -> F4 {
        self.add(a.mul(b))
    }
}

impl Default for F4 {
    fn default() -> Self {
        F4::zero()
    }
}

macro_rules! ops {
    ($t:ty, $($tr:ident $f:ident $m:ident),*) => {$(
        impl std::ops::$tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, o: $t) -> $t { self.$m(o) }
        }
    )*};
}
ops!(F4, Add add add, Sub sub sub, Mul mul mul, Div div div);

impl std::ops::Neg for F4 {
    type Output = F4;
    #[inline(always)]
    fn neg(self) -> F4 {
        F4::zero().sub(self)
    }
}

/// Four 3-vectors, one per lane.
#[derive(Clone, Copy, Debug, Default)]
pub struct V4 {
    pub x: F4,
    pub y: F4,
    pub z: F4,
}

impl V4 {
    #[inline(always)]
    pub fn zero() -> V4 {
        V4 {
            x: F4::zero(),
            y: F4::zero(),
            z: F4::zero(),
        }
    }
    #[inline(always)]
    pub fn from_lanes(v: [Vec3; 4]) -> V4 {
        V4 {
            x: F4::from_array([v[0].x, v[1].x, v[2].x, v[3].x]),
            y: F4::from_array([v[0].y, v[1].y, v[2].y, v[3].y]),
            z: F4::from_array([v[0].z, v[1].z, v[2].z, v[3].z]),
        }
    }
    #[inline(always)]
    pub fn lanes(self) -> [Vec3; 4] {
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        [0, 1, 2, 3].map(|i| Vec3::new(x[i], y[i], z[i]))
    }
    #[inline(always)]
    pub fn dot(self, o: V4) -> F4 {
        self.x.mul(o.x).add(self.y.mul(o.y)).add(self.z.mul(o.z))
    }
    #[inline(always)]
    pub fn cross(self, o: V4) -> V4 {
        V4 {
            x: self.y.mul(o.z).sub(self.z.mul(o.y)),
            y: self.z.mul(o.x).sub(self.x.mul(o.z)),
            z: self.x.mul(o.y).sub(self.y.mul(o.x)),
        }
    }
    #[inline(always)]
    pub fn scale(self, s: F4) -> V4 {
        V4 {
            x: self.x.mul(s),
            y: self.y.mul(s),
            z: self.z.mul(s),
        }
    }
    /// `self + v * s`.
    #[inline(always)]
    pub fn add_scaled(self, v: V4, s: F4) -> V4 {
        V4 {
            x: self.x.add(v.x.mul(s)),
            y: self.y.add(v.y.mul(s)),
            z: self.z.add(v.z.mul(s)),
        }
    }
    #[inline(always)]
    pub fn length_squared(self) -> F4 {
        self.dot(self)
    }
}

impl std::ops::Add for V4 {
    type Output = V4;
    #[inline(always)]
    fn add(self, o: V4) -> V4 {
        V4 {
            x: self.x.add(o.x),
            y: self.y.add(o.y),
            z: self.z.add(o.z),
        }
    }
}

impl std::ops::Sub for V4 {
    type Output = V4;
    #[inline(always)]
    fn sub(self, o: V4) -> V4 {
        V4 {
            x: self.x.sub(o.x),
            y: self.y.sub(o.y),
            z: self.z.sub(o.z),
        }
    }
}

/// Four 3×3 matrices, one per lane (columns).
#[derive(Clone, Copy, Debug, Default)]
pub struct M4 {
    pub c0: V4,
    pub c1: V4,
    pub c2: V4,
}

impl M4 {
    pub const IDENTITY: M4 = M4 {
        c0: V4 {
            x: F4::ONE_CONST,
            y: F4::ZERO_CONST,
            z: F4::ZERO_CONST,
        },
        c1: V4 {
            x: F4::ZERO_CONST,
            y: F4::ONE_CONST,
            z: F4::ZERO_CONST,
        },
        c2: V4 {
            x: F4::ZERO_CONST,
            y: F4::ZERO_CONST,
            z: F4::ONE_CONST,
        },
    };

    #[inline(always)]
    pub fn from_lanes(m: [&Mat3; 4]) -> M4 {
        M4 {
            c0: V4::from_lanes([m[0].x_axis, m[1].x_axis, m[2].x_axis, m[3].x_axis]),
            c1: V4::from_lanes([m[0].y_axis, m[1].y_axis, m[2].y_axis, m[3].y_axis]),
            c2: V4::from_lanes([m[0].z_axis, m[1].z_axis, m[2].z_axis, m[3].z_axis]),
        }
    }
    #[inline(always)]
    pub fn mul_vec(&self, v: V4) -> V4 {
        self.c0.scale(v.x).add_scaled(self.c1, v.y).add_scaled(self.c2, v.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_are_independent() {
        let a = F4::from_array([1.0, -2.0, 3.0, 4.0]);
        let b = F4::from_array([0.5, 0.5, -1.0, 2.0]);
        assert_eq!((a + b).to_array(), [1.5, -1.5, 2.0, 6.0]);
        assert_eq!((a * b).to_array(), [0.5, -1.0, -3.0, 8.0]);
        assert_eq!(a.max(b).to_array(), [1.0, 0.5, 3.0, 4.0]);
        let m = a.gt(b);
        assert_eq!(m.bits(), 0b1101);
        assert_eq!(F4::select(m, a, b).to_array(), [1.0, 0.5, 3.0, 4.0]);
        let v = V4::from_lanes([Vec3::X, Vec3::Y, Vec3::Z, Vec3::new(1.0, 2.0, 3.0)]);
        let w = V4::from_lanes([Vec3::Y, Vec3::Z, Vec3::X, Vec3::new(-1.0, 0.5, 2.0)]);
        let c = v.cross(w).lanes();
        assert_eq!(c[0], Vec3::Z);
        assert_eq!(c[3], Vec3::new(1.0, 2.0, 3.0).cross(Vec3::new(-1.0, 0.5, 2.0)));
        let mats = [
            Mat3::IDENTITY,
            Mat3::from_diagonal(Vec3::splat(2.0)),
            Mat3::from_rotation_z(0.3),
            Mat3::ZERO,
        ];
        let m4 = M4::from_lanes([&mats[0], &mats[1], &mats[2], &mats[3]]);
        let r = m4.mul_vec(v).lanes();
        for i in 0..4 {
            assert!((r[i] - mats[i] * v.lanes()[i]).length() < 1e-6);
        }
    }
}

//! Lanes of floats for the contact solver: a `Lanes` type holds one `f32` per lane, `V<L>`
//! one 3-vector per lane and `M<L>` one 3×3 matrix per lane. Each lane holds a different
//! constraint; lanes never interact.
//!
//! * `F4` — four lanes: SSE2 on x86_64 (part of the baseline), a plain array elsewhere.
//! * `F8` — eight lanes: AVX2 on x86_64, used only after run-time detection.
//!
//! Both do the same IEEE single-precision operations lane by lane (no fused multiply-add), so
//! a constraint computes bit for bit the same result whichever width it is solved in.

use crate::math::{Mat3, Vec3};
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

#[cfg(target_arch = "x86_64")]
mod avx;
#[cfg(not(target_arch = "x86_64"))]
mod portable;
#[cfg(target_arch = "x86_64")]
mod sse;

#[cfg(target_arch = "x86_64")]
pub use avx::F8;
#[cfg(not(target_arch = "x86_64"))]
pub use portable::F4;
#[cfg(target_arch = "x86_64")]
pub use sse::F4;

/// One `f32` per lane. Masks are lanes of all ones (true) or all zeros (false).
pub trait Lanes:
    Copy + Debug + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self>
{
    /// The number of lanes.
    const N: usize;
    /// `bits()` of a mask with every lane set.
    const ALL: u32;
    /// `[f32; N]`, `[u32; N]` and `[[f32; 4]; N]`.
    type Floats: Copy + Default + AsRef<[f32]> + AsMut<[f32]>;
    type Indices: Copy + Default + Debug + AsRef<[u32]> + AsMut<[u32]>;
    type Rows: AsRef<[[f32; 4]]>;

    fn splat(x: f32) -> Self;
    fn load(a: &Self::Floats) -> Self;
    fn to_floats(self) -> Self::Floats;
    fn add(self, o: Self) -> Self;
    fn sub(self, o: Self) -> Self;
    fn mul(self, o: Self) -> Self;
    fn div(self, o: Self) -> Self;
    /// `self` where `self < o`, else `o` (also when either is NaN).
    fn min(self, o: Self) -> Self;
    /// `self` where `self > o`, else `o` (also when either is NaN).
    fn max(self, o: Self) -> Self;
    fn sqrt(self) -> Self;
    /// Mask of the lanes where `self > o`.
    fn gt(self, o: Self) -> Self;
    fn ge(self, o: Self) -> Self;
    fn le(self, o: Self) -> Self;
    fn and(self, o: Self) -> Self;
    fn or(self, o: Self) -> Self;
    /// Lanes of `a` where the mask is set, else lanes of `b`.
    fn select(mask: Self, a: Self, b: Self) -> Self;
    /// One bit per lane of a mask (lane 0 in bit 0).
    fn bits(self) -> u32;
    /// Lane `i` takes row `row(i)` (four floats): out come the four columns.
    fn gather<'a>(row: impl Fn(usize) -> &'a [f32; 4]) -> [Self; 4];
    /// The inverse of `gather`: four columns in, one row of four floats per lane out.
    fn scatter(cols: [Self; 4]) -> Self::Rows;

    #[inline(always)]
    fn zero() -> Self {
        Self::splat(0.0)
    }
    #[inline(always)]
    fn one() -> Self {
        Self::splat(1.0)
    }
    /// A mask with every lane set.
    #[inline(always)]
    fn all() -> Self {
        Self::splat(f32::from_bits(u32::MAX))
    }
    /// Lanes from a function of the lane index.
    #[inline(always)]
    fn from_fn(f: impl Fn(usize) -> f32) -> Self {
        let mut a = Self::Floats::default();
        for (i, x) in a.as_mut().iter_mut().enumerate() {
            *x = f(i);
        }
        Self::load(&a)
    }
}

macro_rules! operators {
    ($t:ty) => {
        impl Add for $t {
            type Output = $t;
            #[inline(always)]
            fn add(self, o: $t) -> $t {
                Lanes::add(self, o)
            }
        }
        impl Sub for $t {
            type Output = $t;
            #[inline(always)]
            fn sub(self, o: $t) -> $t {
                Lanes::sub(self, o)
            }
        }
        impl Mul for $t {
            type Output = $t;
            #[inline(always)]
            fn mul(self, o: $t) -> $t {
                Lanes::mul(self, o)
            }
        }
        impl Div for $t {
            type Output = $t;
            #[inline(always)]
            fn div(self, o: $t) -> $t {
                Lanes::div(self, o)
            }
        }
        impl Neg for $t {
            type Output = $t;
            #[inline(always)]
            fn neg(self) -> $t {
                Lanes::sub(<$t as Lanes>::zero(), self)
            }
        }
        impl Default for $t {
            #[inline(always)]
            fn default() -> $t {
                <$t as Lanes>::zero()
            }
        }
    };
}
operators!(F4);
#[cfg(target_arch = "x86_64")]
operators!(F8);

/// One 3-vector per lane.
#[derive(Clone, Copy, Debug, Default)]
pub struct V<L> {
    pub x: L,
    pub y: L,
    pub z: L,
}

impl<L: Lanes> V<L> {
    #[inline(always)]
    pub fn zero() -> Self {
        V {
            x: L::zero(),
            y: L::zero(),
            z: L::zero(),
        }
    }
    /// Lane `i` holds `f(i)`.
    #[inline(always)]
    pub fn from_fn(f: impl Fn(usize) -> Vec3) -> Self {
        V {
            x: L::from_fn(|i| f(i).x),
            y: L::from_fn(|i| f(i).y),
            z: L::from_fn(|i| f(i).z),
        }
    }
    /// Lane `i` of each component.
    #[inline(always)]
    pub fn lane(self, i: usize) -> Vec3 {
        let (x, y, z) = (self.x.to_floats(), self.y.to_floats(), self.z.to_floats());
        Vec3::new(x.as_ref()[i], y.as_ref()[i], z.as_ref()[i])
    }
    /// The first three of four gathered columns.
    #[inline(always)]
    pub fn from_columns(c: [L; 4]) -> Self {
        V {
            x: c[0],
            y: c[1],
            z: c[2],
        }
    }
    #[inline(always)]
    pub fn dot(self, o: Self) -> L {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        V {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    #[inline(always)]
    pub fn scale(self, s: L) -> Self {
        V {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
    /// `self + v * s`.
    #[inline(always)]
    pub fn add_scaled(self, v: Self, s: L) -> Self {
        V {
            x: self.x + v.x * s,
            y: self.y + v.y * s,
            z: self.z + v.z * s,
        }
    }
    #[inline(always)]
    pub fn length_squared(self) -> L {
        self.dot(self)
    }
    /// Lanes of `a` where the mask is set, else lanes of `b`.
    #[inline(always)]
    pub fn select(mask: L, a: Self, b: Self) -> Self {
        V {
            x: L::select(mask, a.x, b.x),
            y: L::select(mask, a.y, b.y),
            z: L::select(mask, a.z, b.z),
        }
    }
}

impl<L: Lanes> Add for V<L> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        V {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

impl<L: Lanes> Sub for V<L> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        V {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
}

/// One 3×3 matrix per lane (columns).
#[derive(Clone, Copy, Debug, Default)]
pub struct M<L> {
    pub c0: V<L>,
    pub c1: V<L>,
    pub c2: V<L>,
}

impl<L: Lanes> M<L> {
    #[inline(always)]
    pub fn identity() -> Self {
        let (o, z) = (L::one(), L::zero());
        M {
            c0: V { x: o, y: z, z },
            c1: V { x: z, y: o, z },
            c2: V { x: z, y: z, z: o },
        }
    }
    #[inline(always)]
    pub fn zero() -> Self {
        M {
            c0: V::zero(),
            c1: V::zero(),
            c2: V::zero(),
        }
    }
    /// Lane `i` holds `f(i)`.
    pub fn from_fn(f: impl Fn(usize) -> Mat3) -> Self {
        M {
            c0: V::from_fn(|i| f(i).x_axis),
            c1: V::from_fn(|i| f(i).y_axis),
            c2: V::from_fn(|i| f(i).z_axis),
        }
    }
    #[inline(always)]
    pub fn mul_vec(&self, v: V<L>) -> V<L> {
        self.c0.scale(v.x).add_scaled(self.c1, v.y).add_scaled(self.c2, v.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_lanes<L: Lanes>() {
        let a = L::from_fn(|i| [1.0, -2.0, 3.0, 4.0][i % 4] + (i / 4) as f32);
        let b = L::from_fn(|i| [0.5, 0.5, -1.0, 2.0][i % 4]);
        let sum = (a + b).to_floats();
        let prod = (a * b).to_floats();
        let max = a.max(b).to_floats();
        let m = a.gt(b);
        let sel = L::select(m, a, b).to_floats();
        for i in 0..L::N {
            let (x, y) = (a.to_floats().as_ref()[i], b.to_floats().as_ref()[i]);
            assert_eq!(sum.as_ref()[i], x + y);
            assert_eq!(prod.as_ref()[i], x * y);
            assert_eq!(max.as_ref()[i], x.max(y));
            assert_eq!(sel.as_ref()[i], if x > y { x } else { y });
            assert_eq!(m.bits() >> i & 1 == 1, x > y);
        }
        assert_eq!(L::all().bits(), L::ALL);

        // Gather and scatter are inverse transposes.
        let rows: Vec<[f32; 4]> = (0..L::N)
            .map(|i| [i as f32, 10.0 + i as f32, 20.0, -(i as f32)])
            .collect();
        let cols = L::gather(|i| &rows[i]);
        for (c, col) in cols.iter().enumerate() {
            for (i, row) in rows.iter().enumerate() {
                assert_eq!(col.to_floats().as_ref()[i], row[c]);
            }
        }
        assert_eq!(L::scatter(cols).as_ref(), &rows[..]);

        let vecs = |i: usize| Vec3::new(i as f32, 1.0 - i as f32, 2.0 + 0.5 * i as f32);
        let v = V::<L>::from_fn(vecs);
        let w = V::<L>::from_fn(|i| Vec3::new(-1.0, 0.5 * i as f32, 2.0));
        let mats = |i: usize| Mat3::from_rotation_z(0.3 * i as f32) * (1.0 + i as f32);
        let r = M::<L>::from_fn(mats).mul_vec(v);
        for i in 0..L::N {
            assert_eq!(v.cross(w).lane(i), vecs(i).cross(w.lane(i)));
            assert!((r.lane(i) - mats(i) * vecs(i)).length() < 1e-5);
        }
    }

    #[test]
    fn four_lanes_are_independent() {
        check_lanes::<F4>();
    }

    #[test]
    #[cfg(target_arch = "x86_64")]
    fn eight_lanes_are_independent() {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: AVX2 is present.
            unsafe { eight() }
        }
        #[target_feature(enable = "avx2")]
        unsafe fn eight() {
            check_lanes::<F8>();
        }
    }
}

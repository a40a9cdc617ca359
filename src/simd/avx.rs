//! Eight lanes in an AVX register, for CPUs with AVX2 (detected at run time).
//!
//! Every function here compiles to AVX instructions, so an `F8` may only be made and used
//! inside code entered through a `#[target_feature(enable = "avx2")]` function after
//! `is_x86_feature_detected!("avx2")` said yes (see `contact_wide`). The arithmetic is the
//! same IEEE single precision as `F4`'s (no fused multiply-add), so a lane computes bit for bit
//! what it would in a four-lane batch.

use super::Lanes;
use std::arch::x86_64::*;

#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct F8(pub __m256);

// SAFETY (every `unsafe` block below): only reached after AVX2 was detected (module docs).
impl Lanes for F8 {
    const N: usize = 8;
    const ALL: u32 = 0xff;
    type Floats = [f32; 8];
    type Indices = [u32; 8];
    type Rows = [[f32; 4]; 8];

    #[inline(always)]
    fn splat(x: f32) -> F8 {
        unsafe { F8(_mm256_set1_ps(x)) }
    }
    #[inline(always)]
    fn load(a: &[f32; 8]) -> F8 {
        unsafe { F8(_mm256_loadu_ps(a.as_ptr())) }
    }
    #[inline(always)]
    fn to_floats(self) -> [f32; 8] {
        let mut a = [0.0; 8];
        unsafe { _mm256_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }
    #[inline(always)]
    fn add(self, o: F8) -> F8 {
        unsafe { F8(_mm256_add_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn sub(self, o: F8) -> F8 {
        unsafe { F8(_mm256_sub_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn mul(self, o: F8) -> F8 {
        unsafe { F8(_mm256_mul_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn div(self, o: F8) -> F8 {
        unsafe { F8(_mm256_div_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn min(self, o: F8) -> F8 {
        unsafe { F8(_mm256_min_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn max(self, o: F8) -> F8 {
        unsafe { F8(_mm256_max_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn sqrt(self) -> F8 {
        unsafe { F8(_mm256_sqrt_ps(self.0)) }
    }
    #[inline(always)]
    fn gt(self, o: F8) -> F8 {
        unsafe { F8(_mm256_cmp_ps::<_CMP_GT_OQ>(self.0, o.0)) }
    }
    #[inline(always)]
    fn ge(self, o: F8) -> F8 {
        unsafe { F8(_mm256_cmp_ps::<_CMP_GE_OQ>(self.0, o.0)) }
    }
    #[inline(always)]
    fn le(self, o: F8) -> F8 {
        unsafe { F8(_mm256_cmp_ps::<_CMP_LE_OQ>(self.0, o.0)) }
    }
    #[inline(always)]
    fn and(self, o: F8) -> F8 {
        unsafe { F8(_mm256_and_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn or(self, o: F8) -> F8 {
        unsafe { F8(_mm256_or_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn select(mask: F8, a: F8, b: F8) -> F8 {
        unsafe { F8(_mm256_blendv_ps(b.0, a.0, mask.0)) }
    }
    #[inline(always)]
    fn bits(self) -> u32 {
        unsafe { _mm256_movemask_ps(self.0) as u32 }
    }
    /// Rows 0–3 fill the low halves and rows 4–7 the high halves; each half is then a 4×4
    /// transpose (AVX shuffles work within 128-bit halves).
    #[inline(always)]
    fn gather<'a>(row: impl Fn(usize) -> &'a [f32; 4]) -> [F8; 4] {
        // No closure here: a closure would be compiled without AVX and keep the intrinsics
        // out of line.
        macro_rules! pair {
            ($i:expr) => {
                _mm256_insertf128_ps::<1>(
                    _mm256_castps128_ps256(_mm_loadu_ps(row($i).as_ptr())),
                    _mm_loadu_ps(row($i + 4).as_ptr()),
                )
            };
        }
        unsafe {
            let (a0, a1, a2, a3) = (pair!(0), pair!(1), pair!(2), pair!(3));
            let t0 = _mm256_unpacklo_ps(a0, a1);
            let t1 = _mm256_unpacklo_ps(a2, a3);
            let t2 = _mm256_unpackhi_ps(a0, a1);
            let t3 = _mm256_unpackhi_ps(a2, a3);
            [
                F8(_mm256_shuffle_ps::<0x44>(t0, t1)),
                F8(_mm256_shuffle_ps::<0xee>(t0, t1)),
                F8(_mm256_shuffle_ps::<0x44>(t2, t3)),
                F8(_mm256_shuffle_ps::<0xee>(t2, t3)),
            ]
        }
    }
    #[inline(always)]
    fn scatter(cols: [F8; 4]) -> [[f32; 4]; 8] {
        let mut out = [[0.0; 4]; 8];
        unsafe {
            let t0 = _mm256_unpacklo_ps(cols[0].0, cols[1].0);
            let t1 = _mm256_unpacklo_ps(cols[2].0, cols[3].0);
            let t2 = _mm256_unpackhi_ps(cols[0].0, cols[1].0);
            let t3 = _mm256_unpackhi_ps(cols[2].0, cols[3].0);
            let rows = [
                _mm256_shuffle_ps::<0x44>(t0, t1),
                _mm256_shuffle_ps::<0xee>(t0, t1),
                _mm256_shuffle_ps::<0x44>(t2, t3),
                _mm256_shuffle_ps::<0xee>(t2, t3),
            ];
            for (i, r) in rows.into_iter().enumerate() {
                _mm_storeu_ps(out[i].as_mut_ptr(), _mm256_castps256_ps128(r));
                _mm_storeu_ps(out[i + 4].as_mut_ptr(), _mm256_extractf128_ps::<1>(r));
            }
        }
        out
    }
}

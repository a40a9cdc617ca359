//! Four lanes in an SSE register. SSE2 is part of the x86_64 baseline: no detection needed.

use super::Lanes;
use std::arch::x86_64::*;

#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct F4(pub __m128);

// SAFETY (every `unsafe` block below): SSE2 is always present on x86_64.
impl Lanes for F4 {
    const N: usize = 4;
    const ALL: u32 = 0b1111;
    type Floats = [f32; 4];
    type Indices = [u32; 4];
    type Rows = [[f32; 4]; 4];

    #[inline(always)]
    fn splat(x: f32) -> F4 {
        unsafe { F4(_mm_set1_ps(x)) }
    }
    #[inline(always)]
    fn load(a: &[f32; 4]) -> F4 {
        unsafe { F4(_mm_loadu_ps(a.as_ptr())) }
    }
    #[inline(always)]
    fn to_floats(self) -> [f32; 4] {
        let mut a = [0.0; 4];
        unsafe { _mm_storeu_ps(a.as_mut_ptr(), self.0) };
        a
    }
    #[inline(always)]
    fn add(self, o: F4) -> F4 {
        unsafe { F4(_mm_add_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn sub(self, o: F4) -> F4 {
        unsafe { F4(_mm_sub_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn mul(self, o: F4) -> F4 {
        unsafe { F4(_mm_mul_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn div(self, o: F4) -> F4 {
        unsafe { F4(_mm_div_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn min(self, o: F4) -> F4 {
        unsafe { F4(_mm_min_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn max(self, o: F4) -> F4 {
        unsafe { F4(_mm_max_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn sqrt(self) -> F4 {
        unsafe { F4(_mm_sqrt_ps(self.0)) }
    }
    #[inline(always)]
    fn gt(self, o: F4) -> F4 {
        unsafe { F4(_mm_cmpgt_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn ge(self, o: F4) -> F4 {
        unsafe { F4(_mm_cmpge_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn le(self, o: F4) -> F4 {
        unsafe { F4(_mm_cmple_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn and(self, o: F4) -> F4 {
        unsafe { F4(_mm_and_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn or(self, o: F4) -> F4 {
        unsafe { F4(_mm_or_ps(self.0, o.0)) }
    }
    #[inline(always)]
    fn select(mask: F4, a: F4, b: F4) -> F4 {
        unsafe { F4(_mm_or_ps(_mm_and_ps(mask.0, a.0), _mm_andnot_ps(mask.0, b.0))) }
    }
    #[inline(always)]
    fn bits(self) -> u32 {
        unsafe { _mm_movemask_ps(self.0) as u32 }
    }
    #[inline(always)]
    fn gather<'a>(row: impl Fn(usize) -> &'a [f32; 4]) -> [F4; 4] {
        transpose([F4::load(row(0)), F4::load(row(1)), F4::load(row(2)), F4::load(row(3))])
    }
    #[inline(always)]
    fn scatter(cols: [F4; 4]) -> [[f32; 4]; 4] {
        transpose(cols).map(F4::to_floats)
    }
}

/// Four rows of four floats in, four columns out (a 4×4 transpose).
#[inline(always)]
fn transpose(r: [F4; 4]) -> [F4; 4] {
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

// SAFETY: as above, SSE2 is always present on x86_64.
impl F4 {
    /// Lanes `[2, 3, 0, 1]`: the two halves swapped.
    #[inline(always)]
    pub fn swap_halves(self) -> F4 {
        unsafe { F4(_mm_shuffle_ps::<0b01_00_11_10>(self.0, self.0)) }
    }
    /// Lanes `[1, 0, 3, 2]`: neighbours swapped.
    #[inline(always)]
    pub fn swap_pairs(self) -> F4 {
        unsafe { F4(_mm_shuffle_ps::<0b10_11_00_01>(self.0, self.0)) }
    }
    /// Lane 0.
    #[inline(always)]
    pub fn first(self) -> f32 {
        unsafe { _mm_cvtss_f32(self.0) }
    }
}

//! Four lanes as a plain array, for targets without SSE (the compiler may still vectorise).

use super::Lanes;

#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct F4(pub [f32; 4]);

const TRUE: f32 = f32::from_bits(u32::MAX);

#[inline(always)]
fn lanes(a: F4, b: F4, f: impl Fn(f32, f32) -> f32) -> F4 {
    F4([0, 1, 2, 3].map(|i| f(a.0[i], b.0[i])))
}

#[inline(always)]
fn mask(c: bool) -> f32 {
    if c {
        TRUE
    } else {
        0.0
    }
}

impl Lanes for F4 {
    const N: usize = 4;
    const ALL: u32 = 0b1111;
    type Floats = [f32; 4];
    type Indices = [u32; 4];
    type Rows = [[f32; 4]; 4];

    fn splat(x: f32) -> F4 {
        F4([x; 4])
    }
    fn load(a: &[f32; 4]) -> F4 {
        F4(*a)
    }
    fn to_floats(self) -> [f32; 4] {
        self.0
    }
    fn add(self, o: F4) -> F4 {
        lanes(self, o, |x, y| x + y)
    }
    fn sub(self, o: F4) -> F4 {
        lanes(self, o, |x, y| x - y)
    }
    fn mul(self, o: F4) -> F4 {
        lanes(self, o, |x, y| x * y)
    }
    fn div(self, o: F4) -> F4 {
        lanes(self, o, |x, y| x / y)
    }
    // As SSE: the second operand when the comparison fails (NaN included).
    fn min(self, o: F4) -> F4 {
        lanes(self, o, |x, y| if x < y { x } else { y })
    }
    fn max(self, o: F4) -> F4 {
        lanes(self, o, |x, y| if x > y { x } else { y })
    }
    fn sqrt(self) -> F4 {
        F4(self.0.map(f32::sqrt))
    }
    fn gt(self, o: F4) -> F4 {
        lanes(self, o, |x, y| mask(x > y))
    }
    fn ge(self, o: F4) -> F4 {
        lanes(self, o, |x, y| mask(x >= y))
    }
    fn le(self, o: F4) -> F4 {
        lanes(self, o, |x, y| mask(x <= y))
    }
    fn and(self, o: F4) -> F4 {
        lanes(self, o, |x, y| f32::from_bits(x.to_bits() & y.to_bits()))
    }
    fn or(self, o: F4) -> F4 {
        lanes(self, o, |x, y| f32::from_bits(x.to_bits() | y.to_bits()))
    }
    fn select(m: F4, a: F4, b: F4) -> F4 {
        F4([0, 1, 2, 3].map(|i| if m.0[i].to_bits() != 0 { a.0[i] } else { b.0[i] }))
    }
    fn bits(self) -> u32 {
        (0..4).fold(0, |acc, i| acc | (((self.0[i].to_bits() >> 31) & 1) << i))
    }
    fn gather<'a>(row: impl Fn(usize) -> &'a [f32; 4]) -> [F4; 4] {
        let r = [row(0), row(1), row(2), row(3)];
        [0, 1, 2, 3].map(|c| F4([r[0][c], r[1][c], r[2][c], r[3][c]]))
    }
    fn scatter(cols: [F4; 4]) -> [[f32; 4]; 4] {
        [0, 1, 2, 3].map(|r| [cols[0].0[r], cols[1].0[r], cols[2].0[r], cols[3].0[r]])
    }
}

impl F4 {
    /// Lanes `[2, 3, 0, 1]`: the two halves swapped.
    #[inline(always)]
    pub fn swap_halves(self) -> F4 {
        F4([self.0[2], self.0[3], self.0[0], self.0[1]])
    }
    /// Lanes `[1, 0, 3, 2]`: neighbours swapped.
    #[inline(always)]
    pub fn swap_pairs(self) -> F4 {
        F4([self.0[1], self.0[0], self.0[3], self.0[2]])
    }
    /// Lane 0.
    #[inline(always)]
    pub fn first(self) -> f32 {
        self.0[0]
    }
}

//! The position update of gyroscopic bodies (`integrate_general_position`'s free-rotation
//! branch) four bodies at a time: the f64 attitude arithmetic — the normalisations, the
//! products with the principal frame and the start attitude, and `free_rotation`'s five
//! turns — in four f64 lanes, one body per lane.
//!
//! Each lane performs the scalar path's operations in the scalar path's order (glam's
//! `DQuat` product, `normalize`, the `DQuat`-by-`DVec3` rotation and the turns written out
//! as there), and IEEE arithmetic on a lane gives the same bits as on a scalar, so every
//! body ends exactly as `integrate_general_position` leaves it (`lanes_match_the_scalar_path`
//! checks bit for bit). Only the lane count per instruction changes: `D4` (plain arrays,
//! any machine) or `Y4` (AVX's four-lane registers, picked at run time). The f32 parts
//! (speed caps, translation, the world inverse inertia) stay per body, as before.

use super::{half_turn, BodySim, BodyState, Velocity};
use crate::math::{clamp_length, Mat3};
use glam::DQuat;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Four f64 lanes, each doing IEEE arithmetic of its own (negation flips the sign bit,
/// as a scalar's does).
trait L4:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self>
{
    fn splat(x: f64) -> Self;
    fn from_array(a: [f64; 4]) -> Self;
    fn to_array(self) -> [f64; 4];
    fn sqrt(self) -> Self;
    /// `a` where `mask`, else `b`, lane by lane.
    fn select(mask: [bool; 4], a: Self, b: Self) -> Self;
    /// Whether every lane's magnitude is below `bound` (false for a NaN lane).
    fn all_below(self, bound: f64) -> bool;
}

/// Four f64 lanes as a plain array (any machine; the compiler vectorises what it can).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct D4([f64; 4]);

impl D4 {
    #[inline(always)]
    fn zip(self, o: D4, f: impl Fn(f64, f64) -> f64) -> D4 {
        D4([
            f(self.0[0], o.0[0]),
            f(self.0[1], o.0[1]),
            f(self.0[2], o.0[2]),
            f(self.0[3], o.0[3]),
        ])
    }
}

impl L4 for D4 {
    #[inline(always)]
    fn splat(x: f64) -> D4 {
        D4([x; 4])
    }
    #[inline(always)]
    fn from_array(a: [f64; 4]) -> D4 {
        D4(a)
    }
    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        self.0
    }
    #[inline(always)]
    fn sqrt(self) -> D4 {
        D4(self.0.map(f64::sqrt))
    }
    #[inline(always)]
    fn select(mask: [bool; 4], a: D4, b: D4) -> D4 {
        D4([0, 1, 2, 3].map(|k| if mask[k] { a.0[k] } else { b.0[k] }))
    }
    #[inline(always)]
    fn all_below(self, bound: f64) -> bool {
        self.0.iter().all(|x| x.abs() < bound)
    }
}

macro_rules! lane_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for D4 {
            type Output = D4;
            #[inline(always)]
            fn $f(self, o: D4) -> D4 {
                self.zip(o, |a, b| a $op b)
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

impl Neg for D4 {
    type Output = D4;
    #[inline(always)]
    fn neg(self) -> D4 {
        D4(self.0.map(|x| -x))
    }
}

/// Four f64 lanes in an AVX register: reached only inside `avx` (after detection).
#[cfg(target_arch = "x86_64")]
mod y4 {
    use super::L4;
    use std::arch::x86_64::*;
    use std::ops::{Add, Div, Mul, Neg, Sub};

    #[derive(Clone, Copy)]
    pub(super) struct Y4(__m256d);

    // SAFETY (every `unsafe` block below): only reached from `avx`, which runs after AVX
    // was detected.
    impl L4 for Y4 {
        #[inline(always)]
        fn splat(x: f64) -> Y4 {
            unsafe { Y4(_mm256_set1_pd(x)) }
        }
        #[inline(always)]
        fn from_array(a: [f64; 4]) -> Y4 {
            unsafe { Y4(_mm256_loadu_pd(a.as_ptr())) }
        }
        #[inline(always)]
        fn to_array(self) -> [f64; 4] {
            let mut a = [0.0; 4];
            unsafe { _mm256_storeu_pd(a.as_mut_ptr(), self.0) };
            a
        }
        #[inline(always)]
        fn sqrt(self) -> Y4 {
            unsafe { Y4(_mm256_sqrt_pd(self.0)) }
        }
        #[inline(always)]
        fn select(mask: [bool; 4], a: Y4, b: Y4) -> Y4 {
            let m = |k: usize| -(mask[k] as i64);
            unsafe {
                Y4(_mm256_blendv_pd(
                    b.0,
                    a.0,
                    _mm256_castsi256_pd(_mm256_setr_epi64x(m(0), m(1), m(2), m(3))),
                ))
            }
        }
        #[inline(always)]
        fn all_below(self, bound: f64) -> bool {
            // |x| by clearing the sign bit; the ordered comparison is false for NaN.
            unsafe {
                let abs = _mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0);
                _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(abs, _mm256_set1_pd(bound))) == 0b1111
            }
        }
    }

    macro_rules! lane_op {
        ($tr:ident, $f:ident, $intr:ident) => {
            impl $tr for Y4 {
                type Output = Y4;
                #[inline(always)]
                fn $f(self, o: Y4) -> Y4 {
                    unsafe { Y4($intr(self.0, o.0)) }
                }
            }
        };
    }
    lane_op!(Add, add, _mm256_add_pd);
    lane_op!(Sub, sub, _mm256_sub_pd);
    lane_op!(Mul, mul, _mm256_mul_pd);
    lane_op!(Div, div, _mm256_div_pd);

    impl Neg for Y4 {
        type Output = Y4;
        #[inline(always)]
        fn neg(self) -> Y4 {
            // The sign bit flipped, as a scalar negation does (also for zeros).
            unsafe { Y4(_mm256_xor_pd(self.0, _mm256_set1_pd(-0.0))) }
        }
    }
}

/// Four quaternions by component.
#[derive(Clone, Copy)]
struct Q4<L> {
    x: L,
    y: L,
    z: L,
    w: L,
}

/// Four vectors by component.
#[derive(Clone, Copy)]
struct V4<L> {
    x: L,
    y: L,
    z: L,
}

impl<L: L4> Q4<L> {
    #[inline(always)]
    fn from_lanes(q: [DQuat; 4]) -> Q4<L> {
        Q4 {
            x: L::from_array(q.map(|q| q.x)),
            y: L::from_array(q.map(|q| q.y)),
            z: L::from_array(q.map(|q| q.z)),
            w: L::from_array(q.map(|q| q.w)),
        }
    }

    #[inline(always)]
    fn lanes(&self) -> [DQuat; 4] {
        let (x, y, z, w) = (
            self.x.to_array(),
            self.y.to_array(),
            self.z.to_array(),
            self.w.to_array(),
        );
        [0, 1, 2, 3].map(|k| DQuat::from_xyzw(x[k], y[k], z[k], w[k]))
    }

    #[inline(always)]
    fn conjugate(self) -> Q4<L> {
        Q4 {
            x: -self.x,
            y: -self.y,
            z: -self.z,
            w: self.w,
        }
    }

    /// glam's `DQuat::mul_quat`, term for term.
    #[inline(always)]
    fn mul(self, r: Q4<L>) -> Q4<L> {
        let (x0, y0, z0, w0) = (self.x, self.y, self.z, self.w);
        let (x1, y1, z1, w1) = (r.x, r.y, r.z, r.w);
        Q4 {
            x: w0 * x1 + x0 * w1 + y0 * z1 - z0 * y1,
            y: w0 * y1 - x0 * z1 + y0 * w1 + z0 * x1,
            z: w0 * z1 + x0 * y1 - y0 * x1 + z0 * w1,
            w: w0 * w1 - x0 * x1 - y0 * y1 - z0 * z1,
        }
    }

    /// glam's `DQuat::normalize`: times the reciprocal of the length.
    #[inline(always)]
    fn normalize(self) -> Q4<L> {
        let dot = self.x * self.x + self.y * self.y + self.z * self.z + self.w * self.w;
        let recip = L::splat(1.0) / dot.sqrt();
        Q4 {
            x: self.x * recip,
            y: self.y * recip,
            z: self.z * recip,
            w: self.w * recip,
        }
    }

    /// glam's `DQuat::mul_vec3`, term for term.
    #[inline(always)]
    fn rotate(self, v: V4<L>) -> V4<L> {
        let w = self.w;
        let b = V4 {
            x: self.x,
            y: self.y,
            z: self.z,
        };
        let b2 = b.dot(b);
        let k1 = w * w - b2;
        let k2 = v.dot(b) * L::splat(2.0);
        let k3 = w * L::splat(2.0);
        let c = b.cross(v);
        V4 {
            x: v.x * k1 + b.x * k2 + c.x * k3,
            y: v.y * k1 + b.y * k2 + c.y * k3,
            z: v.z * k1 + b.z * k2 + c.z * k3,
        }
    }
}

impl<L: L4> V4<L> {
    /// glam's `DVec3::dot`.
    #[inline(always)]
    fn dot(self, o: V4<L>) -> L {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// glam's `DVec3::cross`.
    #[inline(always)]
    fn cross(self, r: V4<L>) -> V4<L> {
        V4 {
            x: self.y * r.z - r.y * self.z,
            y: self.z * r.x - r.z * self.x,
            z: self.x * r.y - r.x * self.y,
        }
    }
}

/// `half_turn` lane by lane: its series, and the library's values in the lanes beyond the
/// series' range (or NaN), as `half_turn` takes them.
#[inline(always)]
fn half_turn4<L: L4>(x: L) -> (L, L) {
    const S: [f64; 7] = super::HALF_TURN_SIN;
    const C: [f64; 8] = super::HALF_TURN_COS;
    let x2 = x * x;
    // `half_turn`'s folds from zero, written as loops (no closure left out of line).
    let (mut ps, mut pc) = (L::splat(0.0), L::splat(0.0));
    for k in (0..S.len()).rev() {
        ps = ps * x2 + L::splat(S[k]);
    }
    for k in (0..C.len()).rev() {
        pc = pc * x2 + L::splat(C[k]);
    }
    let (s, c) = (x + x * x2 * ps, L::splat(1.0) + x2 * pc);
    // No lane beyond the series' range (`beyond_series` false in every lane) in one test.
    if x.all_below(std::f64::consts::FRAC_PI_4) {
        return (s, c);
    }
    let xs = x.to_array();
    let (mut sa, mut ca) = (s.to_array(), c.to_array());
    for k in 0..4 {
        if beyond_series(xs[k]) {
            (sa[k], ca[k]) = half_turn(xs[k]);
        }
    }
    (L::from_array(sa), L::from_array(ca))
}

/// `half_turn` takes the library's values for `x` (beyond its series' range, or NaN).
#[inline(always)]
fn beyond_series(x: f64) -> bool {
    x.abs().partial_cmp(&std::f64::consts::FRAC_PI_4) != Some(std::cmp::Ordering::Less)
}

/// `free_rotation` turns about an axis of moment `m` (it skips `m <= 0` only, so NaN turns).
#[inline(always)]
fn turns(m: f64) -> bool {
    !matches!(
        m.partial_cmp(&0.0),
        Some(std::cmp::Ordering::Less | std::cmp::Ordering::Equal)
    )
}

/// One of `free_rotation`'s turns, about principal axis `k` for `t`, lane by lane (a lane
/// whose moment about `k` is not positive stays as it was, as the scalar `continue` does).
/// Called with constant `k`, so the indexing folds away.
#[inline(always)]
fn turn4<L: L4>(q: &mut [L; 4], l: &mut [L; 3], m: &[L; 3], turn: [bool; 4], k: usize, t: f64) {
    if turn == [false; 4] {
        return;
    }
    let mk = m[k];
    let (s, c) = half_turn4(L::splat(0.5) * (L::splat(t) * l[k] / mk));
    // The other two axes in cyclic order.
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let (qk, qi, qj, qw) = (q[k], q[i], q[j], q[3]);
    let (cos, sin) = (c * c - s * s, L::splat(2.0) * s * c);
    let (li, lj) = (l[i], l[j]);
    let turned_q = [qw * s + qk * c, qi * c + qj * s, qj * c - qi * s, qw * c - qk * s];
    let turned_l = [cos * li + sin * lj, cos * lj - sin * li];
    if turn == [true; 4] {
        // Every lane turns (the usual case): the selects would take the turned values.
        [q[k], q[i], q[j], q[3]] = turned_q;
        [l[i], l[j]] = turned_l;
        return;
    }
    q[k] = L::select(turn, turned_q[0], qk);
    q[i] = L::select(turn, turned_q[1], qi);
    q[j] = L::select(turn, turned_q[2], qj);
    q[3] = L::select(turn, turned_q[3], qw);
    l[i] = L::select(turn, turned_l[0], li);
    l[j] = L::select(turn, turned_l[1], lj);
}

/// `free_rotation` lane by lane: the same five turns, the same order of operations.
#[inline(always)]
fn free_rotation4<L: L4>(q: Q4<L>, w: V4<L>, m: V4<L>, h: f64) -> (Q4<L>, V4<L>) {
    let l0 = q.conjugate().rotate(w);
    let mut l = [m.x * l0.x, m.y * l0.y, m.z * l0.z];
    let mut q = [q.x, q.y, q.z, q.w];
    let ms = [m.x, m.y, m.z];
    // Which lanes turn about each axis (by its moment alone), worked out once per axis.
    let turn = ms.map(|mk| mk.to_array().map(turns));
    turn4(&mut q, &mut l, &ms, turn[0], 0, 0.5 * h);
    turn4(&mut q, &mut l, &ms, turn[1], 1, 0.5 * h);
    turn4(&mut q, &mut l, &ms, turn[2], 2, h);
    turn4(&mut q, &mut l, &ms, turn[1], 1, 0.5 * h);
    turn4(&mut q, &mut l, &ms, turn[0], 0, 0.5 * h);
    let q = Q4 {
        x: q[0],
        y: q[1],
        z: q[2],
        w: q[3],
    }
    .normalize();
    let zero = L::splat(0.0);
    let body = V4 {
        x: L::select(m.x.to_array().map(|m| m > 0.0), l[0] / m.x, zero),
        y: L::select(m.y.to_array().map(|m| m > 0.0), l[1] / m.y, zero),
        z: L::select(m.z.to_array().map(|m| m > 0.0), l[2] / m.z, zero),
    };
    (q, q.rotate(body))
}

/// Four gyroscopic bodies (`sim.gyroscopic`, not RK4) moved as
/// `integrate_general_position` moves each.
#[inline(always)]
fn four<L: L4>(
    vel: &mut [Velocity],
    states: &mut [BodyState],
    sims: &[BodySim],
    ks: [u32; 4],
    h: f32,
    limits: (f32, f32),
) {
    let mut q = [DQuat::IDENTITY; 4];
    let mut w = [[0.0f64; 4]; 3];
    let mut m = [[0.0f64; 4]; 3];
    let mut principal = [DQuat::IDENTITY; 4];
    let mut q0 = [DQuat::IDENTITY; 4];
    for (lane, &k) in ks.iter().enumerate() {
        let (u, s, sim) = (&mut vel[k as usize], &mut states[k as usize], &sims[k as usize]);
        u.v = clamp_length(u.v, limits.0);
        u.w = clamp_length(u.w, limits.1);
        s.set_dp(s.dp() + h * u.v);
        q[lane] = (s.dq() * sim.q0).as_dquat();
        let wd = u.w.as_dvec3();
        for c in 0..3 {
            w[c][lane] = wd[c];
            m[c][lane] = sim.moments[c];
        }
        principal[lane] = sim.principal;
        q0[lane] = sim.q0.as_dquat();
    }
    let principal = Q4::<L>::from_lanes(principal);
    let q = Q4::from_lanes(q).normalize().mul(principal);
    let v4 = |a: [[f64; 4]; 3]| V4 {
        x: L::from_array(a[0]),
        y: L::from_array(a[1]),
        z: L::from_array(a[2]),
    };
    let (q, w) = free_rotation4(q, v4(w), v4(m), h as f64);
    let dq = q
        .mul(principal.conjugate())
        .mul(Q4::from_lanes(q0).conjugate())
        .normalize();
    let (wx, wy, wz, dq) = (w.x.to_array(), w.y.to_array(), w.z.to_array(), dq.lanes());
    for (lane, &k) in ks.iter().enumerate() {
        let (u, s, sim) = (&mut vel[k as usize], &mut states[k as usize], &sims[k as usize]);
        let wl = glam::DVec3::new(wx[lane], wy[lane], wz[lane]);
        u.w = clamp_length(wl.as_vec3(), limits.1);
        let dq = dq[lane].as_quat();
        s.set_rotation(dq);
        let r = Mat3::from_quat(dq * sim.q0);
        s.set_inv_i(crate::math::turned_inertia(r, sim.inv_inertia));
    }
}

/// Moves the listed bodies (all gyroscopic, not RK4) four at a time; fewer than four left
/// take the scalar path.
#[inline(always)]
fn all<L: L4>(
    vel: &mut [Velocity],
    states: &mut [BodyState],
    sims: &[BodySim],
    bodies: &[u32],
    h: f32,
    limits: (f32, f32),
) {
    let mut chunks = bodies.chunks_exact(4);
    for c in &mut chunks {
        four::<L>(vel, states, sims, [c[0], c[1], c[2], c[3]], h, limits);
    }
    for &k in chunks.remainder() {
        super::integrate_general_position(
            &mut vel[k as usize],
            &mut states[k as usize],
            &sims[k as usize],
            h,
            limits,
        );
    }
}

/// Moves gyroscopic bodies (`sim.gyroscopic`, not RK4) exactly as
/// `integrate_general_position` would, four at a time (AVX where the machine has it).
pub(super) fn gyroscopic_positions(
    vel: &mut [Velocity],
    states: &mut [BodyState],
    sims: &[BodySim],
    bodies: &[u32],
    h: f32,
    limits: (f32, f32),
) {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx") {
        // SAFETY: AVX was detected.
        return unsafe { avx(vel, states, sims, bodies, h, limits) };
    }
    all::<D4>(vel, states, sims, bodies, h, limits)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn avx(
    vel: &mut [Velocity],
    states: &mut [BodyState],
    sims: &[BodySim],
    bodies: &[u32],
    h: f32,
    limits: (f32, f32),
) {
    all::<y4::Y4>(vel, states, sims, bodies, h, limits)
}

#[cfg(test)]
mod tests {
    use super::super::{integrate_general_position, BodySim, BodyState, Velocity};
    use super::*;
    use crate::math::test_rnd::Rnd;
    use crate::math::{Quat, Vec3};
    use glam::DVec3;

    /// Random gyroscopic bodies (attitudes, principal frames, moments from nearly
    /// isotropic to a rod with a zero moment, spins from rest to past the series' range
    /// and the speed cap): the four-lane path (plain `D4` lanes and, where the machine has
    /// AVX, `Y4`) leaves every body's velocities and state rows bit for bit as the scalar path.
    #[test]
    fn lanes_match_the_scalar_path() {
        let mut rnd = Rnd(0x6a09_e667_f3bc_c908);
        let limits = (100.0, 50.0);
        let mut runs = 0;
        for trial in 0..4000 {
            let n = 1 + trial % 11;
            let mut sims = Vec::new();
            let mut vel = Vec::new();
            let mut states = Vec::new();
            for i in 0..n {
                let q0 = rnd.quat();
                let principal = rnd.quat().as_dquat();
                let scale = [1.0e-3, 1.0, 50.0][i % 3];
                let mut moments = DVec3::new(0.2 + rnd.f() as f64, 0.2 + rnd.f() as f64, 0.2 + rnd.f() as f64) * scale;
                if rnd.f() < 0.05 {
                    moments[i % 3] = 0.0;
                }
                let inertia = {
                    let p = glam::DMat3::from_quat(principal);
                    (p * glam::DMat3::from_diagonal(moments) * p.transpose()).as_mat3()
                };
                let spin = [0.0, 0.3, 5.0, 60.0, 400.0][(i + trial) % 5];
                let rv = |rnd: &mut Rnd| Vec3::new(rnd.f() - 0.5, rnd.f() - 0.5, rnd.f() - 0.5);
                vel.push(Velocity::new(rv(&mut rnd) * 30.0, rv(&mut rnd) * 2.0 * spin));
                let mut st = BodyState::new(1.0, inertia.inverse(), 0);
                st.set_dp(rv(&mut rnd) * 0.1);
                let dq = Quat::from_axis_angle(rv(&mut rnd).normalize(), 0.2 * rnd.f());
                st.set_rotation(dq);
                states.push(st);
                sims.push(BodySim {
                    body: i as u32,
                    lin_accel: Vec3::ZERO,
                    torque: Vec3::ZERO,
                    lin_damping: 0.0,
                    ang_damping: 0.0,
                    q0,
                    inertia,
                    inv_inertia: inertia.inverse(),
                    gyroscopic: true,
                    reduced: false,
                    principal,
                    moments,
                    dynamic: true,
                    rk4: false,
                    arrive: false,
                });
            }
            let order: Vec<u32> = (0..n as u32).rev().collect();
            let h = [1.0 / 360.0, 1.0 / 60.0, 1.0 / 1000.0][trial % 3];
            let (mut vel_s, mut states_s) = (vel.clone(), states.clone());
            for &k in &order {
                let k = k as usize;
                integrate_general_position(&mut vel_s[k], &mut states_s[k], &sims[k], h, limits);
            }
            let mut results = vec![{
                let (mut v, mut s) = (vel.clone(), states.clone());
                all::<D4>(&mut v, &mut s, &sims, &order, h, limits);
                (v, s)
            }];
            #[cfg(target_arch = "x86_64")]
            if std::is_x86_feature_detected!("avx") {
                let (mut v, mut s) = (vel.clone(), states.clone());
                // SAFETY: AVX was detected.
                unsafe { avx(&mut v, &mut s, &sims, &order, h, limits) };
                results.push((v, s));
            }
            for (v, s) in &results {
                for k in 0..n {
                    let bits = |r: &[[f32; 4]; 2]| r.map(|row| row.map(f32::to_bits));
                    assert_eq!(bits(v[k].rows()), bits(vel_s[k].rows()), "trial {trial} body {k}");
                    let bits = |s: &BodyState| s.rows.map(|row| row.map(f32::to_bits));
                    assert_eq!(bits(&s[k]), bits(&states_s[k]), "trial {trial} body {k}");
                }
                runs += 1;
            }
        }
        assert!(runs >= 4000);
    }
}

//! The sub-steps' integration of the bodies that need nothing but their velocities (dynamic
//! bodies with isotropic inertia and no torque, and kinematic bodies): four or eight bodies at a
//! time, with the lanes of `simd`. Bodies are gathered from the solver arrays by index and
//! scattered back; a short last chunk fills its empty lanes with the static dummy (index 0),
//! whose state the arithmetic leaves exactly as it is. Lane arithmetic is the same at either
//! width, so results do not depend on it. Bodies with torque, gyroscopic motion or RK4 take
//! the scalar path in `solver.rs`.

use crate::dynamics::contact_wide::{gather, scatter};
use crate::dynamics::solver::{BodyState, Drive, Velocity};
use crate::simd::{Lanes, F4, V};

#[cfg(target_arch = "x86_64")]
use crate::simd::F8;

/// Applies each listed dynamic body's acceleration and damping to its velocities, and caps
/// its speeds at `limits` (m/s, rad/s).
pub fn velocities(eight: bool, vel: &mut [Velocity], drives: &[Drive], bodies: &[u32], limits: (f32, f32)) {
    #[cfg(target_arch = "x86_64")]
    if eight {
        // SAFETY: `eight` is true only where AVX2 was detected (`Batches::lanes`).
        return unsafe { avx2::velocities(vel, drives, bodies, limits) };
    }
    let _ = eight;
    velocities_all::<F4>(vel, drives, bodies, limits)
}

/// Moves each listed body by its velocities over `h`, first capping them at `limits` (the
/// solve may have pushed past them).
pub fn positions(
    eight: bool,
    vel: &mut [Velocity],
    states: &mut [BodyState],
    bodies: &[u32],
    h: f32,
    limits: (f32, f32),
) {
    #[cfg(target_arch = "x86_64")]
    if eight {
        // SAFETY: as in `velocities`.
        return unsafe { avx2::positions(vel, states, bodies, h, limits) };
    }
    let _ = eight;
    positions_all::<F4>(vel, states, bodies, h, limits)
}

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use super::*;

    #[target_feature(enable = "avx2")]
    pub unsafe fn velocities(vel: &mut [Velocity], drives: &[Drive], bodies: &[u32], limits: (f32, f32)) {
        velocities_all::<F8>(vel, drives, bodies, limits)
    }

    #[target_feature(enable = "avx2")]
    pub unsafe fn positions(
        vel: &mut [Velocity],
        states: &mut [BodyState],
        bodies: &[u32],
        h: f32,
        limits: (f32, f32),
    ) {
        positions_all::<F8>(vel, states, bodies, h, limits)
    }
}

/// The lanes' body indices for one chunk; missing lanes are the static dummy.
#[inline(always)]
fn lanes<L: Lanes>(chunk: &[u32]) -> L::Indices {
    let mut idx = L::Indices::default();
    idx.as_mut()[..chunk.len()].copy_from_slice(chunk);
    idx
}

/// The factor that caps a lane's speed: 1 when `speed2 <= max²`, else `max / speed`.
#[inline(always)]
fn cap<L: Lanes>(speed2: L, max: L, max2: L) -> L {
    let one = L::one();
    let over = speed2.gt(max2);
    L::select(over, max / L::select(over, speed2, one).sqrt(), one)
}

#[inline(always)]
fn velocities_all<L: Lanes>(vel: &mut [Velocity], drives: &[Drive], bodies: &[u32], limits: (f32, f32)) {
    let (max_v, max_v2) = (L::splat(limits.0), L::splat(limits.0 * limits.0));
    let (max_w, max_w2) = (L::splat(limits.1), L::splat(limits.1 * limits.1));
    for chunk in bodies.chunks(L::N) {
        let idx = lanes::<L>(chunk);
        let ix = idx.as_ref();
        let (v, w) = gather(vel, &idx);
        let [dx, dy, dz, lin_keep] = L::gather(|i| &drives[ix[i] as usize].rows[0]);
        let [ang_keep, _, _, _] = L::gather(|i| &drives[ix[i] as usize].rows[1]);
        let v: V<L> = V {
            x: (v.x + dx) * lin_keep,
            y: (v.y + dy) * lin_keep,
            z: (v.z + dz) * lin_keep,
        };
        let w = w.scale(ang_keep);
        let (cv, cw) = (
            cap(v.length_squared(), max_v, max_v2),
            cap(w.length_squared(), max_w, max_w2),
        );
        scatter(vel, &idx, v.scale(cv), w.scale(cw));
    }
}

#[inline(always)]
fn positions_all<L: Lanes>(vel: &mut [Velocity], states: &mut [BodyState], bodies: &[u32], h: f32, limits: (f32, f32)) {
    let (zero, one) = (L::zero(), L::one());
    let (h, half_h, two) = (L::splat(h), L::splat(0.5 * h), L::splat(2.0));
    let (max_v, max_v2) = (L::splat(limits.0), L::splat(limits.0 * limits.0));
    let (max_w, max_w2) = (L::splat(limits.1), L::splat(limits.1 * limits.1));
    for chunk in bodies.chunks(L::N) {
        let idx = lanes::<L>(chunk);
        let ix = idx.as_ref();
        let (v, w) = gather(vel, &idx);
        let (cv, cw) = (
            cap(v.length_squared(), max_v, max_v2),
            cap(w.length_squared(), max_w, max_w2),
        );
        let (v, w) = (v.scale(cv), w.scale(cw));
        scatter(vel, &idx, v, w);
        let [px, py, pz, _] = L::gather(|i| &states[ix[i] as usize].rows[0]);
        let [qx, qy, qz, qw] = L::gather(|i| &states[ix[i] as usize].rows[1]);
        let dp = [px + h * v.x, py + h * v.y, pz + h * v.z, zero];
        // q + h/2 · (ω, 0) ⊗ q, renormalised.
        let rx = qx + half_h * (w.x * qw + w.y * qz - w.z * qy);
        let ry = qy + half_h * (w.y * qw + w.z * qx - w.x * qz);
        let rz = qz + half_h * (w.z * qw + w.x * qy - w.y * qx);
        let rw = qw - half_h * (w.x * qx + w.y * qy + w.z * qz);
        let inv = one / (rx * rx + ry * ry + rz * rz + rw * rw).sqrt();
        let q = [rx * inv, ry * inv, rz * inv, rw * inv];
        // The rotation vector to first order, as `BodyState::set_rotation` keeps it.
        let s = L::select(q[3].ge(zero), two, -two);
        let theta = [s * q[0], s * q[1], s * q[2], zero];
        let (dp, q, theta) = (L::scatter(dp), L::scatter(q), L::scatter(theta));
        for (lane, &i) in ix.iter().enumerate() {
            let rows = &mut states[i as usize].rows;
            rows[0] = dp.as_ref()[lane];
            rows[1] = q.as_ref()[lane];
            rows[5] = theta.as_ref()[lane];
        }
    }
}

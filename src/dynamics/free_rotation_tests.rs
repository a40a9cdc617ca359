//! `free_rotation` written out per axis and `half_turn`'s series against the general forms
//! they replace (glam's quaternion products and the C library's `sin_cos`).

use super::{free_rotation, half_turn};
use glam::{DQuat, DVec3};

/// The former `free_rotation`: general quaternion products, `from_axis_angle`, a
/// normalisation per turn.
fn reference(q: DQuat, w: DVec3, m: DVec3, h: f64) -> (DQuat, DVec3) {
    let mut q = q;
    let mut l = m * (q.conjugate() * w);
    let axes = [DVec3::X, DVec3::Y, DVec3::Z];
    for (axis, t) in [(0, 0.5 * h), (1, 0.5 * h), (2, h), (1, 0.5 * h), (0, 0.5 * h)] {
        if m[axis] <= 0.0 {
            continue;
        }
        let turn = DQuat::from_axis_angle(axes[axis], t * l[axis] / m[axis]);
        q = (q * turn).normalize();
        l = turn.conjugate() * l;
    }
    let w = q * DVec3::select(m.cmpgt(DVec3::ZERO), l / m, DVec3::ZERO);
    (q, w)
}

fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Within two ulps of the library over the series' range (the remainders are below one),
/// and the library's own beyond it.
#[test]
fn half_turn_matches_the_library() {
    let mut rnd = rng(0x9e37_79b9_7f4a_7c15);
    let ulp = f64::EPSILON;
    for i in 0..200_000 {
        let x = match i % 3 {
            0 => (2.0 * rnd() - 1.0) * std::f64::consts::FRAC_PI_4,
            1 => (2.0 * rnd() - 1.0) * 1.0e-3,
            _ => (2.0 * rnd() - 1.0) * 10.0,
        };
        let (s, c) = half_turn(x);
        let (s0, c0) = x.sin_cos();
        assert!(
            (s - s0).abs() <= 2.0 * ulp * s0.abs().max(f64::MIN_POSITIVE),
            "sin {x}: {s} {s0}"
        );
        assert!((c - c0).abs() <= 2.0 * ulp * c0.abs(), "cos {x}: {c} {c0}");
    }
    assert_eq!(half_turn(0.0), (0.0, 1.0));
    assert!(half_turn(f64::NAN).0.is_nan());
}

/// Random attitudes, spins up to 300 rad/s and moments from isotropic to a thin rod (one
/// zero moment): the written-out turns give the general form's attitude and angular
/// velocity to 1e-12 and a unit quaternion, and with every moment positive keep |L| to
/// 1e-12 relative (a zero moment drops what turns onto its axis, in
/// both forms); the energy, which the splitting keeps only to O(h²), equals the general
/// form's to 1e-12 relative.
#[test]
fn free_rotation_matches_the_general_products() {
    let mut rnd = rng(0x2545_f491_4f6c_dd1d);
    for i in 0..20_000 {
        let q = DQuat::from_xyzw(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
        let w = DVec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 600.0 * rnd();
        let mut m = DVec3::new(0.1 + rnd(), 0.1 + rnd(), 0.1 + rnd()) * 10.0 * rnd().max(0.01);
        if i % 7 == 0 {
            m[i % 3] = 0.0;
        }
        let h = [1.0 / 360.0, 1.0 / 60.0, 1.0 / 1000.0][i % 3];
        let (q1, w1) = free_rotation(q, w, m, h);
        let (q0, w0) = reference(q, w, m, h);
        let scale = w0.length().max(1.0);
        assert!((q1.dot(q0).abs() - 1.0).abs() < 1.0e-12, "{q1} {q0}");
        assert!((q1.length() - 1.0).abs() < 1.0e-14);
        assert!((w1 - w0).length() < 1.0e-12 * scale, "{w1} {w0}");
        if m.min_element() <= 0.0 {
            continue;
        }
        // |L| and energy, in the principal frame.
        let lb = |q: DQuat, w: DVec3| m * (q.conjugate() * w);
        let (l_in, l_out) = (lb(q, w), lb(q1, w1));
        let e = |q: DQuat, w: DVec3| (m * (q.conjugate() * w) * (q.conjugate() * w)).element_sum();
        assert!((l_out.length() - l_in.length()).abs() <= 1.0e-12 * l_in.length().max(1.0));
        let (e_ref, e_out) = (e(q0, w0), e(q1, w1));
        assert!((e_out - e_ref).abs() <= 1.0e-12 * e_ref.max(1.0), "{e_ref} {e_out}");
    }
}

/// The principal axes lent by a slot's last step (`cached_principal_axes`) are the ones a
/// new Jacobi iteration gives, bit for bit, and are lent only for the same inertia: random
/// inertias, each against the slot's previous body of the same, a slightly different and
/// a non-gyroscopic inertia.
#[test]
fn cached_principal_axes_are_the_computed_ones() {
    use super::{cached_principal_axes, principal_axes, BodySim};
    use crate::math::{Mat3, Quat, Vec3};
    let mut rnd = rng(0x1f83_d9ab_fb41_bd6b);
    let mut lent = 0;
    for i in 0..2000u32 {
        let q = DQuat::from_xyzw(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).normalize();
        let m = DVec3::new(0.1 + rnd(), 0.1 + rnd(), 0.1 + rnd());
        let p = glam::DMat3::from_quat(q);
        let inertia = (p * glam::DMat3::from_diagonal(m) * p.transpose()).as_mat3();
        let (principal, moments) = principal_axes(&inertia);
        let mut prev = BodySim {
            body: i,
            lin_accel: Vec3::ZERO,
            torque: Vec3::ZERO,
            lin_damping: 0.0,
            ang_damping: 0.0,
            q0: Quat::IDENTITY,
            inertia,
            inv_inertia: inertia.inverse(),
            gyroscopic: true,
            reduced: false,
            principal,
            moments,
            dynamic: true,
            rk4: false,
            arrive: false,
        };
        let bits = |(p, m): (DQuat, DVec3)| (p.to_array().map(f64::to_bits), m.to_array().map(f64::to_bits));
        // The same inertia: lent, and equal to a new computation.
        assert_eq!(
            bits(cached_principal_axes(&inertia, &prev)),
            bits(principal_axes(&inertia))
        );
        lent += 1;
        // Another inertia (one entry one ulp off, or another body): computed anew.
        let mut other = inertia;
        other.x_axis.x = f32::from_bits(other.x_axis.x.to_bits() + 1);
        let other = if i % 2 == 0 {
            other
        } else {
            Mat3::from_diagonal(Vec3::new(1.0, 2.0, 3.0))
        };
        assert_eq!(bits(cached_principal_axes(&other, &prev)), bits(principal_axes(&other)));
        // A slot whose last body was not gyroscopic lends nothing.
        prev.gyroscopic = false;
        prev.principal = DQuat::IDENTITY;
        assert_eq!(
            bits(cached_principal_axes(&inertia, &prev)),
            bits(principal_axes(&inertia))
        );
    }
    assert_eq!(lent, 2000);
}

//! Hinge (revolute): the anchors coincide (3×3 point block) and the frames' Z axes stay
//! aligned (a 2×2 angular block across the axis); B turns about Z. Rows about the axis, in
//! solve order: spring toward angle 0 (soft), motor (target speed, torque-clamped), lower
//! and upper angle limits (one-sided, speculative).

use super::solver::{soft_impulse, Bodies, Ctx, Frames, Wrench};
use super::{HingeParams, Impulses};
use crate::math::Vec3;
use crate::solver::Softness;

/// The hinge axis (halfway between the frames' Z axes) and A's frame axes across it.
fn basis(f: &Frames) -> (Vec3, Vec3, Vec3) {
    let (za, zb) = f.axes();
    let a = (za + zb).normalize_or_zero();
    let a = if a == Vec3::ZERO { za } else { a };
    (a, f.qa * Vec3::X, f.qa * Vec3::Y)
}

pub fn wrench(imp: &Impulses, f: &Frames) -> Wrench {
    let (a, _, _) = basis(f);
    let t = imp.angular + (imp.axial + imp.motor + imp.lower - imp.upper) * a;
    Wrench {
        p: imp.linear,
        ta: f.ra.cross(imp.linear) + t,
        tb: f.rb.cross(imp.linear) + t,
    }
}

/// Keeps the Z axes aligned: rows along A's X and Y axes with the error `za × zb`, solved
/// together (2×2). The accumulated impulse is kept as a world vector.
pub(super) fn solve_axis_alignment(f: &Frames, b: &mut Bodies, acc: &mut Vec3, ctx: &Ctx) {
    let (za, zb) = f.axes();
    let (e1, e2) = (f.qa * Vec3::X, f.qa * Vec3::Y);
    let err = za.cross(zb);
    let w = b.wb - b.wa;
    let r1 = w.dot(e1) + ctx.rigid_bias(err.dot(e1));
    let r2 = w.dot(e2) + ctx.rigid_bias(err.dot(e2));
    let k = b.ia + b.ib;
    let (ke1, ke2) = (k * e1, k * e2);
    let (k11, k12, k22) = (e1.dot(ke1), e1.dot(ke2), e2.dot(ke2));
    let det = k11 * k22 - k12 * k12;
    if det.abs() <= f32::MIN_POSITIVE || !det.is_finite() {
        return;
    }
    let inv = 1.0 / det;
    let x = ctx.respond(-(k22 * r1 - k12 * r2) * inv, acc.dot(e1));
    let y = ctx.respond(-(k11 * r2 - k12 * r1) * inv, acc.dot(e2));
    let t = x * e1 + y * e2;
    *acc += t;
    b.apply_angular(t);
}

pub fn solve(p: &HingeParams, spring: &Softness, imp: &mut Impulses, f: &Frames, b: &mut Bodies, ctx: &Ctx) {
    let (a, _, _) = basis(f);
    let angle = f.twist_angle();
    if p.enable_spring && p.spring_hertz > 0.0 {
        let mass = b.angular_mass(a);
        let cdot = a.dot(b.wb - b.wa);
        let d = soft_impulse(spring, mass, cdot, angle, &mut imp.axial);
        b.apply_angular(d * a);
    } else {
        imp.axial = 0.0;
    }
    if p.enable_motor {
        b.solve_angular_motor(a, p.motor_speed, p.max_motor_torque * ctx.h, &mut imp.motor);
    } else {
        imp.motor = 0.0;
    }
    if p.enable_limit {
        b.solve_angular_limit(a, angle - p.lower, &mut imp.lower, ctx);
        b.solve_angular_limit(-a, p.upper - angle, &mut imp.upper, ctx);
    } else {
        imp.lower = 0.0;
        imp.upper = 0.0;
    }
    solve_axis_alignment(f, b, &mut imp.angular, ctx);
    b.solve_point(f, &mut imp.linear, ctx);
}

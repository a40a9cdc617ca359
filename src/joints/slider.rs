//! Slider (prismatic): B keeps A's orientation (3×3 angular block) and its anchor stays on
//! the line through A's anchor along A's Z axis (a 2×2 block across the axis). Along the
//! axis, in solve order: motor (target speed, force-clamped), lower and upper translation
//! limits (one-sided, speculative). A's arm for rows along and across the axis reaches to
//! B's anchor (`ra + d`), so the rows are exact while the anchors are apart.

use super::solver::{Bodies, Ctx, Frames, Wrench};
use super::{Impulses, SliderParams};
use crate::math::Vec3;

pub fn wrench(imp: &Impulses, f: &Frames) -> Wrench {
    let a = f.qa * Vec3::Z;
    let p = imp.linear + (imp.motor + imp.lower - imp.upper) * a;
    Wrench {
        p,
        ta: (f.ra + f.d).cross(p) + imp.angular,
        tb: f.rb.cross(p) + imp.angular,
    }
}

pub fn solve(p: &SliderParams, imp: &mut Impulses, f: &Frames, b: &mut Bodies, ctx: &Ctx) {
    let (a, e1, e2) = (f.qa * Vec3::Z, f.qa * Vec3::X, f.qa * Vec3::Y);
    let arm_a = f.ra + f.d;
    let (sa, sb) = (arm_a.cross(a), f.rb.cross(a));
    let mass = b.linear_mass(a, sa, sb);
    let translation = a.dot(f.d);
    if p.enable_motor {
        let cdot = b.linear_cdot(a, sa, sb);
        let old = imp.motor;
        let max = p.max_motor_force * ctx.h;
        imp.motor = (old - mass * (cdot - p.motor_speed)).clamp(-max, max);
        b.apply_linear(a, sa, sb, imp.motor - old);
    } else {
        imp.motor = 0.0;
    }
    if p.enable_limit {
        let cdot = b.linear_cdot(a, sa, sb);
        let lambda = ctx.limit(mass, cdot, translation - p.lower, &mut imp.lower);
        b.apply_linear(a, sa, sb, lambda);
        let cdot = -b.linear_cdot(a, sa, sb);
        let lambda = ctx.limit(mass, cdot, p.upper - translation, &mut imp.upper);
        b.apply_linear(a, sa, sb, -lambda);
    } else {
        imp.lower = 0.0;
        imp.upper = 0.0;
    }
    b.solve_angular_lock(f, &mut imp.angular, ctx);

    // Across the axis: two rows solved together.
    let (s1a, s1b) = (arm_a.cross(e1), f.rb.cross(e1));
    let (s2a, s2b) = (arm_a.cross(e2), f.rb.cross(e2));
    let m = b.ma + b.mb;
    let k11 = m + s1a.dot(b.ia * s1a) + s1b.dot(b.ib * s1b);
    let k12 = s1a.dot(b.ia * s2a) + s1b.dot(b.ib * s2b);
    let k22 = m + s2a.dot(b.ia * s2a) + s2b.dot(b.ib * s2b);
    let r1 = b.linear_cdot(e1, s1a, s1b) + ctx.rigid_bias(e1.dot(f.d));
    let r2 = b.linear_cdot(e2, s2a, s2b) + ctx.rigid_bias(e2.dot(f.d));
    let det = k11 * k22 - k12 * k12;
    if det.abs() > f32::MIN_POSITIVE && det.is_finite() {
        let inv = 1.0 / det;
        let (acc1, acc2) = (imp.linear.dot(e1), imp.linear.dot(e2));
        let x = ctx.respond(-(k22 * r1 - k12 * r2) * inv, acc1);
        let y = ctx.respond(-(k11 * r2 - k12 * r1) * inv, acc2);
        imp.linear += x * e1 + y * e2;
        b.apply_linear(e1, s1a, s1b, x);
        b.apply_linear(e2, s2a, s2b, y);
    }
}

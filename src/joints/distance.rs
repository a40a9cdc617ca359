//! Distance: one row along the line between the anchors. With the spring off the joint is
//! rigid at `length`. With it on, a soft row pulls toward `length` (a spring of 0 Hz exerts
//! no force: a rope) and, when enabled, one-sided rows keep the length within
//! `min_length..=max_length`.

use super::solver::{soft_impulse, Bodies, Ctx, Frames, Wrench};
use super::{DistanceParams, Impulses};
use crate::math::Vec3;
use crate::solver::Softness;

/// Unit direction from A's anchor to B's, and the length.
fn axis(f: &Frames) -> (Vec3, f32) {
    let len = f.d.length();
    if len > 1.0e-6 {
        (f.d / len, len)
    } else {
        (f.qa * Vec3::Z, len)
    }
}

pub fn wrench(imp: &Impulses, f: &Frames) -> Wrench {
    let (n, _) = axis(f);
    let p = (imp.axial + imp.lower - imp.upper) * n;
    Wrench {
        p,
        ta: f.ra.cross(p),
        tb: f.rb.cross(p),
    }
}

pub fn solve(p: &DistanceParams, spring: &Softness, imp: &mut Impulses, f: &Frames, b: &mut Bodies, ctx: &Ctx) {
    let (n, len) = axis(f);
    let (sa, sb) = (f.ra.cross(n), f.rb.cross(n));
    let mass = b.linear_mass(n, sa, sb);
    if !p.enable_spring {
        let cdot = b.linear_cdot(n, sa, sb);
        let lambda = ctx.respond(-mass * (cdot + ctx.rigid_bias(len - p.length)), imp.axial);
        imp.axial += lambda;
        b.apply_linear(n, sa, sb, lambda);
        imp.lower = 0.0;
        imp.upper = 0.0;
        return;
    }
    if p.spring_hertz > 0.0 {
        let cdot = b.linear_cdot(n, sa, sb);
        let lambda = soft_impulse(spring, mass, cdot, len - p.length, &mut imp.axial);
        b.apply_linear(n, sa, sb, lambda);
    } else {
        imp.axial = 0.0;
    }
    if p.enable_limit {
        let cdot = b.linear_cdot(n, sa, sb);
        let lambda = ctx.limit(mass, cdot, len - p.min_length, &mut imp.lower);
        b.apply_linear(n, sa, sb, lambda);
        let cdot = -b.linear_cdot(n, sa, sb);
        let lambda = ctx.limit(mass, cdot, p.max_length - len, &mut imp.upper);
        b.apply_linear(n, sa, sb, -lambda);
    } else {
        imp.lower = 0.0;
        imp.upper = 0.0;
    }
}

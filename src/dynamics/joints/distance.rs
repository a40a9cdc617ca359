//! Distance: one row along the line between the anchors. With the spring off the joint is
//! rigid at `length` (an equality row, `rows.rs`). With it on, a soft row pulls toward
//! `length` (a spring of 0 Hz exerts no force: a rope) and, when enabled, one-sided rows keep
//! the length within `min_length..=max_length`.

use super::rows::Row;
use super::solver::{soft_impulse, Bodies, Ctx, Frames, Wrench};
use super::{DistanceParams, Impulses};
use crate::dynamics::solver::Softness;
use crate::math::Vec3;

/// Unit direction from A's anchor to B's, and the length.
pub(super) fn axis(f: &Frames) -> (Vec3, f32) {
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

/// The spring and limit rows (a rigid distance joint is one equality row, solved by the
/// caller).
pub fn solve(p: &DistanceParams, spring: &Softness, imp: &mut Impulses, f: &Frames, b: &mut Bodies, ctx: &Ctx) {
    if !p.enable_spring {
        return;
    }
    let (n, len) = axis(f);
    let row = Row::linear(n, f.ra, f.rb);
    let k = b.response(&row).dot(&row);
    let mass = if k > 0.0 { 1.0 / k } else { 0.0 };
    if p.spring_hertz > 0.0 {
        let lambda = soft_impulse(spring, mass, b.cdot(&row), len - p.length, &mut imp.axial);
        b.apply_row(&row, lambda);
    }
    if p.enable_limit {
        let lambda = ctx.limit(mass, b.cdot(&row), len - p.min_length, &mut imp.lower);
        b.apply_row(&row, lambda);
        let upper = row.neg();
        let lambda = ctx.limit(mass, b.cdot(&upper), p.max_length - len, &mut imp.upper);
        b.apply_row(&upper, lambda);
    }
}

//! Slider (prismatic): B keeps A's orientation (three angular rows) and its anchor stays on
//! the line through A's anchor along A's Z axis (two linear rows across the axis); all five
//! are equality rows (`rows.rs`). Along the axis, in solve order: motor (target speed,
//! force-clamped), lower and upper translation limits (one-sided, speculative), coupled with
//! the equality rows so they see the bodies' masses with the rotation locked. A's arm for rows
//! along and across the axis reaches to B's anchor (`ra + d`), so the rows are exact while
//! the anchors are apart.

use super::rows::{Eq, Row, Spd};
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

/// True when the slider has rows along its axis.
pub fn has_axial_rows(p: &SliderParams) -> bool {
    p.enable_limit || p.enable_motor
}

/// The rows along the axis (the equality rows are solved by the caller).
pub fn solve(p: &SliderParams, imp: &mut Impulses, f: &Frames, b: &mut Bodies, ctx: &Ctx, eq: &Eq, k: Option<&Spd>) {
    if !has_axial_rows(p) {
        return;
    }
    let a = f.qa * Vec3::Z;
    let row = eq.couple(k, b, Row::linear(a, f.ra + f.d, f.rb));
    let translation = a.dot(f.d);
    if p.enable_motor {
        let old = imp.motor;
        let max = p.max_motor_force * ctx.h;
        imp.motor = (old - row.mass * (b.cdot(&row.row) - p.motor_speed)).clamp(-max, max);
        row.apply(eq, b, imp, imp.motor - old);
    }
    if p.enable_limit {
        let d = ctx.limit(row.mass, b.cdot(&row.row), translation - p.lower, &mut imp.lower);
        row.apply(eq, b, imp, d);
        let upper = row.neg();
        let d = ctx.limit(upper.mass, b.cdot(&upper.row), p.upper - translation, &mut imp.upper);
        upper.apply(eq, b, imp, d);
    }
}

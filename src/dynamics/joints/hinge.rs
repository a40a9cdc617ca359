//! Hinge (revolute): the anchors coincide (three point rows) and the frames' Z axes stay
//! aligned (two angular rows across the axis); B turns about Z. Rows of the twist angle
//! (`Frames::twist`), in solve order: spring toward angle 0 (soft), motor (target speed, torque-clamped), lower and upper
//! angle limits (one-sided, speculative). They are coupled with the five equality rows
//! (`rows.rs`): a limit or motor sees the inertia about the hinge, not about the centre of
//! mass, so an arm held at its limit by a large torque does not overshoot.

use super::rows::{Eq, Row, Spd};
use super::solver::{soft_impulse, Bodies, Ctx, Frames, Wrench};
use super::{HingeParams, Impulses};
use crate::dynamics::solver::Softness;

pub fn wrench(imp: &Impulses, f: &Frames) -> Wrench {
    let mut t = f.from_cross(imp.angular);
    if let Some((_, row)) = f.twist() {
        t += (imp.axial + imp.motor + imp.lower - imp.upper) * row;
    }
    Wrench {
        p: imp.linear,
        ta: f.ra.cross(imp.linear) + t,
        tb: f.rb.cross(imp.linear) + t,
    }
}

/// True when the hinge has rows about its axis.
pub fn has_axial_rows(p: &HingeParams) -> bool {
    p.enable_limit || p.enable_motor || (p.enable_spring && p.spring_hertz > 0.0)
}

/// The rows about the axis (the equality rows are solved by the caller).
#[allow(clippy::too_many_arguments)]
pub fn solve(
    p: &HingeParams,
    spring: &Softness,
    imp: &mut Impulses,
    f: &Frames,
    b: &mut Bodies,
    ctx: &Ctx,
    eq: &Eq,
    k: Option<&Spd>,
) {
    if !has_axial_rows(p) {
        return;
    }
    let Some((angle, twist)) = f.twist() else {
        // The axes are (nearly) opposite, far from the hinge's pose: the alignment rows
        // turn them back first.
        (imp.axial, imp.motor, imp.lower, imp.upper) = (0.0, 0.0, 0.0, 0.0);
        return;
    };
    let row = eq.couple(k, b, Row::angular(twist));
    if p.enable_spring && p.spring_hertz > 0.0 {
        let d = soft_impulse(spring, row.mass, b.cdot(&row.row), angle, &mut imp.axial);
        row.apply(eq, b, imp, d);
    }
    if p.enable_motor {
        let old = imp.motor;
        let max = p.max_motor_torque * ctx.h;
        imp.motor = (old - row.mass * (b.cdot(&row.row) - p.motor_speed)).clamp(-max, max);
        row.apply(eq, b, imp, imp.motor - old);
    }
    if p.enable_limit {
        let d = ctx.limit(row.mass, b.cdot(&row.row), angle - p.lower, &mut imp.lower);
        row.apply(eq, b, imp, d);
        let upper = row.neg();
        let d = ctx.limit(upper.mass, b.cdot(&upper.row), p.upper - angle, &mut imp.upper);
        upper.apply(eq, b, imp, d);
    }
}

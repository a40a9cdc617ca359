//! Slider (prismatic): B keeps A's orientation (three angular rows) and its anchor stays on
//! the line through A's anchor along A's Z axis (two linear rows across the axis); all five
//! are equality rows (`rows.rs`). Along the axis, in solve order: motor (target speed,
//! force-clamped), lower and upper translation limits (one-sided, speculative), coupled with
//! the equality rows so they see the bodies' masses with the rotation locked (a forest
//! slider's with its whole tree's response, `tree.rs`). The rows along
//! and across the axis act at the centre of one body and measure their errors as if its
//! rotation were already right (`SliderRows`): exact at any misalignment and well
//! conditioned however far apart the anchors are.

use super::rows::{Eq, Row, Spd};
use super::solver::{Bodies, Ctx, Frames, Wrench};
use super::{Impulses, SliderParams};

pub fn wrench(imp: &Impulses, f: &Frames) -> Wrench {
    let sr = f.slider();
    let p = imp.linear.x * sr.axes[0] + imp.linear.y * sr.axes[1] + (imp.motor + imp.lower - imp.upper) * sr.axes[2];
    Wrench {
        p,
        ta: sr.lever_a.cross(p) + imp.angular,
        tb: sr.lever_b.cross(p) + imp.angular,
    }
}

/// True when the slider has rows along its axis.
pub fn has_axial_rows(p: &SliderParams) -> bool {
    p.enable_limit || p.enable_motor
}

/// The rows along the axis of a slider outside the forest (the equality rows are solved by
/// the caller; a forest slider's rows along the axis are solved by the forest with its tree,
/// `Forest::solve_axial`).
pub fn solve(p: &SliderParams, imp: &mut Impulses, f: &Frames, b: &mut Bodies, ctx: &Ctx, eq: &Eq, k: Option<&Spd>) {
    if !has_axial_rows(p) {
        return;
    }
    let sr = f.slider();
    let row = eq.couple(k, b, Row::linear(sr.axes[2], sr.lever_a, sr.lever_b));
    let translation = sr.axes[2].dot(sr.offset);
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

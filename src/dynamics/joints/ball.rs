//! Ball-and-socket: the anchors coincide (three point rows); optionally B's Z axis stays
//! within a cone around A's Z axis (swing limit) and B's twist about Z stays within limits
//! (which also keep the swing within `MAX_TWIST_SWING`, where twist is defined).
//! A ragdoll's shoulders and hips. The limit rows are coupled with the point rows
//! (`rows.rs`), so they see the limb's inertia about the joint.

use super::rows::{Eq, Row, Spd};
use super::solver::{Bodies, Ctx, Frames, Wrench, MAX_TWIST_SWING};
use super::{BallParams, Impulses};
use crate::math::Vec3;

/// The swing row's direction (the rotation that closes the cone angle) and the swing angle;
/// `None` when the axes are aligned (no swing).
pub(super) fn cone_row(f: &Frames) -> Option<(Vec3, f32)> {
    let (za, zb) = f.axes();
    let n = za.cross(zb);
    let s = n.length();
    if s < 1.0e-6 {
        return None;
    }
    Some((-n / s, s.atan2(za.dot(zb))))
}

/// The swing cone in force (rad): the swing limit, and with a twist limit at most
/// [`MAX_TWIST_SWING`] — twist is not defined at a half-turn swing, so a twist limit also
/// keeps the swing where it is. Without that, a body swung past the singular pose with its
/// twist limit resting, came back far outside the limit, and was pushed back in with the
/// work of a violated joint.
pub fn cone_angle(p: &BallParams) -> Option<f32> {
    match (p.enable_swing_limit, p.enable_twist_limit) {
        (true, true) => Some(p.swing_limit.min(MAX_TWIST_SWING)),
        (true, false) => Some(p.swing_limit),
        (false, true) => Some(MAX_TWIST_SWING),
        (false, false) => None,
    }
}

pub fn wrench(p: &BallParams, imp: &Impulses, f: &Frames) -> Wrench {
    let mut t = Vec3::ZERO;
    if cone_angle(p).is_some() {
        if let Some((j, _)) = cone_row(f) {
            t += imp.cone * j;
        }
    }
    if p.enable_twist_limit {
        if let Some((_, row)) = f.twist() {
            t += (imp.lower - imp.upper) * row;
        }
    }
    Wrench {
        p: imp.linear,
        ta: f.ra.cross(imp.linear) + t,
        tb: f.rb.cross(imp.linear) + t,
    }
}

/// True when the joint has rows beyond its point lock.
pub fn has_limits(p: &BallParams) -> bool {
    p.enable_swing_limit || p.enable_twist_limit
}

/// The cone and twist limits (the point rows are solved by the caller).
pub fn solve(p: &BallParams, imp: &mut Impulses, f: &Frames, b: &mut Bodies, ctx: &Ctx, eq: &Eq, k: Option<&Spd>) {
    match (cone_row(f), cone_angle(p)) {
        (Some((j, angle)), Some(limit)) => {
            let row = eq.couple(k, b, Row::angular(j));
            let d = ctx.limit(row.mass, b.cdot(&row.row), limit - angle, &mut imp.cone);
            row.apply(eq, b, imp, d);
        }
        _ => imp.cone = 0.0,
    }
    match f.twist() {
        Some((angle, twist)) if p.enable_twist_limit => {
            let lower = eq.couple(k, b, Row::angular(twist));
            let d = ctx.limit(lower.mass, b.cdot(&lower.row), angle - p.lower_twist, &mut imp.lower);
            lower.apply(eq, b, imp, d);
            let upper = lower.neg();
            let d = ctx.limit(upper.mass, b.cdot(&upper.row), p.upper_twist - angle, &mut imp.upper);
            upper.apply(eq, b, imp, d);
        }
        // No twist limit, or the swing is past `MAX_TWIST_SWING` where twist is not defined.
        _ => (imp.lower, imp.upper) = (0.0, 0.0),
    }
}

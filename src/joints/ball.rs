//! Ball-and-socket: the anchors coincide (a 3×3 point block); optionally B's Z axis stays
//! within a cone around A's Z axis (swing limit) and B's twist about Z stays within limits.
//! A ragdoll's shoulders and hips.

use super::solver::{Bodies, Ctx, Frames, Wrench};
use super::{BallParams, Impulses};
use crate::math::Vec3;

/// The swing row's direction (the rotation that closes the cone angle) and the swing angle;
/// `None` when the axes are aligned (no swing).
fn cone_row(f: &Frames) -> Option<(Vec3, f32)> {
    let (za, zb) = f.axes();
    let n = za.cross(zb);
    let s = n.length();
    if s < 1.0e-6 {
        return None;
    }
    Some((-n / s, s.atan2(za.dot(zb))))
}

/// The twist axis: halfway between the two Z axes.
fn twist_axis(f: &Frames) -> Vec3 {
    let (za, zb) = f.axes();
    let a = (za + zb).normalize_or_zero();
    if a == Vec3::ZERO {
        za
    } else {
        a
    }
}

pub fn wrench(p: &BallParams, imp: &Impulses, f: &Frames) -> Wrench {
    let mut t = Vec3::ZERO;
    if p.enable_swing_limit {
        if let Some((j, _)) = cone_row(f) {
            t += imp.cone * j;
        }
    }
    if p.enable_twist_limit {
        t += (imp.lower - imp.upper) * twist_axis(f);
    }
    Wrench {
        p: imp.linear,
        ta: f.ra.cross(imp.linear) + t,
        tb: f.rb.cross(imp.linear) + t,
    }
}

pub fn solve(p: &BallParams, imp: &mut Impulses, f: &Frames, b: &mut Bodies, ctx: &Ctx) {
    match cone_row(f) {
        Some((j, angle)) if p.enable_swing_limit => {
            b.solve_angular_limit(j, p.swing_limit - angle, &mut imp.cone, ctx);
        }
        _ => imp.cone = 0.0,
    }
    if p.enable_twist_limit {
        let a = twist_axis(f);
        let angle = f.twist_angle();
        b.solve_angular_limit(a, angle - p.lower_twist, &mut imp.lower, ctx);
        b.solve_angular_limit(-a, p.upper_twist - angle, &mut imp.upper, ctx);
    } else {
        imp.lower = 0.0;
        imp.upper = 0.0;
    }
    b.solve_point(f, &mut imp.linear, ctx);
}

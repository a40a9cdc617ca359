//! Fixed (weld): the anchors coincide and the frames keep their relative rotation; a 3×3
//! angular block, then a 3×3 point block.

use super::solver::{Bodies, Ctx, Frames, Wrench};
use super::Impulses;

pub fn wrench(imp: &Impulses, f: &Frames) -> Wrench {
    Wrench {
        p: imp.linear,
        ta: f.ra.cross(imp.linear) + imp.angular,
        tb: f.rb.cross(imp.linear) + imp.angular,
    }
}

pub fn solve(imp: &mut Impulses, f: &Frames, b: &mut Bodies, ctx: &Ctx) {
    b.solve_angular_lock(f, &mut imp.angular, ctx);
    b.solve_point(f, &mut imp.linear, ctx);
}

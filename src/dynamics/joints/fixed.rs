//! Fixed (weld): the anchors coincide and the frames keep their relative rotation: three
//! point rows and three angular rows, all equality rows (`rows.rs`).

use super::solver::{Frames, Wrench};
use super::Impulses;

pub fn wrench(imp: &Impulses, f: &Frames) -> Wrench {
    Wrench {
        p: imp.linear,
        ta: f.ra.cross(imp.linear) + imp.angular,
        tb: f.rb.cross(imp.linear) + imp.angular,
    }
}

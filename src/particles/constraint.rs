//! Constraints of the particle stage: contacts and links between particles, coupled
//! bodies and fixed things, solved by sequential impulses (velocities) and non-linear
//! Gauss–Seidel (positions); and the one-pass solver of a particle's lone contact.

use crate::dynamics::body::{Body, NONE};
use crate::generators::WARM_SLOTS;
use crate::hash::IntMap;
use crate::math::{Mat3, Quat, Vec3};

/// A dynamic awake body touched by particles, copied for the stage and written back after.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Coupled {
    pub(super) slot: u32,
    pub(super) inv_mass: f32,
    pub(super) inv_i: Mat3,
    pub(super) center: Vec3,
    pub(super) q: Quat,
    pub(super) v: Vec3,
    pub(super) w: Vec3,
    /// Velocities the rigid solve moved the body with (its pose already includes them).
    pub(super) v0: Vec3,
    pub(super) w0: Vec3,
    /// Gravity integrated in this stage instead of the rigid solve (see `defer_gravity`).
    pub(super) gravity: Vec3,
    /// A particle contact or link acts on it this step.
    pub(super) touched: bool,
}

impl Coupled {
    pub(super) fn new(body: &Body, slot: u32) -> Coupled {
        Coupled {
            slot,
            inv_mass: body.inv_mass,
            inv_i: body.inv_inertia_world,
            center: body.center,
            q: body.xf.q,
            v: body.v,
            w: body.w,
            v0: body.v,
            w0: body.w,
            gravity: Vec3::ZERO,
            touched: false,
        }
    }
}

/// One side of a constraint.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Side {
    /// A particle, by dense index.
    Particle(u32),
    /// A coupled body and a material point of it, relative to its centre in the body frame.
    Body { c: u32, local: Vec3 },
    /// Something that does not respond: a world point, a static, kinematic or sleeping
    /// body (`sleeper` is the slot of a sleeping dynamic body, else `NONE`).
    Fixed { p: Vec3, v: Vec3, sleeper: u32 },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Contact,
    Rod,
    Cable,
}

/// A contact or link. The impulse `λ n` acts on side `a` and `-λ n` on side `b`; `gap`
/// grows at the rate `n · (v_a − v_b)` and must stay >= 0 (rods: == 0). For contacts `n`
/// points from b to a and is fixed for the step; for links it points from a to b and
/// follows the ends, and `gap = length − distance`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Constraint {
    pub(super) a: Side,
    pub(super) b: Side,
    pub(super) kind: Kind,
    pub(super) n: Vec3,
    /// Contacts: the gap when found. Links: the (maximum) length.
    pub(super) gap0: f32,
    /// Contacts: the two material points when found.
    pub(super) pa0: Vec3,
    pub(super) pb0: Vec3,
    pub(super) restitution: f32,
    pub(super) friction: f32,
    /// Normal velocity when the step began (for restitution).
    pub(super) vn0: f32,
    pub(super) gap: f32,
    pub(super) ra: Vec3,
    pub(super) rb: Vec3,
    pub(super) mass: f32,
    pub(super) impulse: f32,
    pub(super) tangent: Vec3,
    /// Sum of the normal impulses of the step, and of the restitution pass.
    pub(super) total: f32,
    pub(super) bounce: f32,
    pub(super) warm: [f32; WARM_SLOTS],
    /// Warm-start key: a generator slot for links, `(particle slot, shape slot)` for
    /// contacts with dynamic bodies, `u64::MAX` for none.
    pub(super) key: u64,
    /// Solved by the rod block (`block.rs`), not by Gauss–Seidel.
    pub(super) blocked: bool,
}

/// A particle's only constraint: a contact with something fixed. `gap = n·x − offset`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Simple {
    pub(super) i: u32,
    pub(super) n: Vec3,
    pub(super) offset: f32,
    pub(super) v: Vec3,
    pub(super) restitution: f32,
    pub(super) friction: f32,
    pub(super) vn0: f32,
    /// Sum of velocity changes along `n` (per unit mass) over the step.
    pub(super) total: f32,
    pub(super) sleeper: u32,
}

/// The particle arrays and coupled bodies a constraint acts on.
pub(super) struct Sys<'a> {
    pub(super) pos: &'a mut [Vec3],
    pub(super) vel: &'a mut [Vec3],
    pub(super) w: &'a [f32],
    pub(super) coupled: &'a mut [Coupled],
    /// Bodies turn under impulses (velocity passes); position corrections only move them.
    pub(super) turn: bool,
}

impl Sys<'_> {
    #[inline]
    pub(super) fn arm(&self, s: &Side) -> Vec3 {
        match *s {
            Side::Body { c, local } => self.coupled[c as usize].q * local,
            _ => Vec3::ZERO,
        }
    }

    #[inline]
    pub(super) fn point(&self, s: &Side, arm: Vec3) -> Vec3 {
        match *s {
            Side::Particle(i) => self.pos[i as usize],
            Side::Body { c, .. } => self.coupled[c as usize].center + arm,
            Side::Fixed { p, .. } => p,
        }
    }

    #[inline]
    pub(super) fn velocity(&self, s: &Side, arm: Vec3) -> Vec3 {
        match *s {
            Side::Particle(i) => self.vel[i as usize],
            Side::Body { c, .. } => {
                let b = &self.coupled[c as usize];
                b.v + b.w.cross(arm)
            }
            Side::Fixed { v, .. } => v,
        }
    }

    /// Inverse effective mass along the unit direction `n`.
    #[inline]
    pub(super) fn inv_mass(&self, s: &Side, arm: Vec3, n: Vec3) -> f32 {
        match *s {
            Side::Particle(i) => self.w[i as usize],
            Side::Body { c, .. } => {
                let b = &self.coupled[c as usize];
                if !self.turn {
                    return b.inv_mass;
                }
                let rn = arm.cross(n);
                b.inv_mass + rn.dot(b.inv_i * rn)
            }
            Side::Fixed { .. } => 0.0,
        }
    }

    #[inline]
    pub(super) fn impulse(&mut self, s: &Side, arm: Vec3, p: Vec3) {
        match *s {
            Side::Particle(i) => self.vel[i as usize] += self.w[i as usize] * p,
            Side::Body { c, .. } => {
                let b = &mut self.coupled[c as usize];
                b.v += b.inv_mass * p;
                b.w += b.inv_i * arm.cross(p);
            }
            Side::Fixed { .. } => {}
        }
    }

    /// `n_i · W (n_j)` through one shared side, with the arms of each row on it.
    #[inline]
    pub(super) fn coupling(&self, s: &Side, ri: Vec3, ni: Vec3, rj: Vec3, nj: Vec3) -> f32 {
        match *s {
            Side::Particle(i) => self.w[i as usize] * ni.dot(nj),
            Side::Body { c, .. } => {
                let b = &self.coupled[c as usize];
                let turn = if self.turn {
                    ri.cross(ni).dot(b.inv_i * rj.cross(nj))
                } else {
                    0.0
                };
                b.inv_mass * ni.dot(nj) + turn
            }
            Side::Fixed { .. } => 0.0,
        }
    }

    /// A position correction: the displacement an impulse `p` would give in unit time.
    #[inline]
    pub(super) fn shift(&mut self, s: &Side, _arm: Vec3, p: Vec3) {
        match *s {
            Side::Particle(i) => self.pos[i as usize] += self.w[i as usize] * p,
            Side::Body { c, .. } => {
                // Translation only: turning a body by the projection of one contact after
                // another (Gauss–Seidel order) leaves it a net spurious rotation.
                let b = &mut self.coupled[c as usize];
                b.center += b.inv_mass * p;
            }
            Side::Fixed { .. } => {}
        }
    }
}

impl Constraint {
    pub(super) fn new(a: Side, b: Side, kind: Kind, n: Vec3, gap0: f32) -> Constraint {
        Constraint {
            a,
            b,
            kind,
            n,
            gap0,
            pa0: Vec3::ZERO,
            pb0: Vec3::ZERO,
            restitution: 0.0,
            friction: 0.0,
            vn0: 0.0,
            gap: 0.0,
            ra: Vec3::ZERO,
            rb: Vec3::ZERO,
            mass: 0.0,
            impulse: 0.0,
            tangent: Vec3::ZERO,
            total: 0.0,
            bounce: 0.0,
            warm: [0.0; WARM_SLOTS],
            key: u64::MAX,
            blocked: false,
        }
    }

    /// Current direction and gap.
    #[inline]
    pub(super) fn measure(&self, sys: &Sys, ra: Vec3, rb: Vec3) -> (Vec3, f32) {
        let (pa, pb) = (sys.point(&self.a, ra), sys.point(&self.b, rb));
        match self.kind {
            Kind::Contact => (self.n, self.gap0 + self.n.dot((pa - self.pa0) - (pb - self.pb0))),
            Kind::Rod | Kind::Cable => {
                let d = pb - pa;
                let len = d.length();
                let n = if len > 1.0e-9 { d / len } else { self.n };
                (n, self.gap0 - len)
            }
        }
    }

    pub(super) fn refresh(&mut self, sys: &Sys) {
        self.ra = sys.arm(&self.a);
        self.rb = sys.arm(&self.b);
        let (n, gap) = self.measure(sys, self.ra, self.rb);
        self.n = n;
        self.gap = gap;
        let k = sys.inv_mass(&self.a, self.ra, n) + sys.inv_mass(&self.b, self.rb, n);
        self.mass = if k > 0.0 { 1.0 / k } else { 0.0 };
    }

    #[inline]
    pub(super) fn apply(&self, sys: &mut Sys, p: Vec3) {
        sys.impulse(&self.a, self.ra, p);
        sys.impulse(&self.b, self.rb, -p);
    }

    pub(super) fn solve_velocity(&mut self, sys: &mut Sys, inv_h: f32) {
        if self.mass == 0.0 {
            return;
        }
        let dv = sys.velocity(&self.a, self.ra) - sys.velocity(&self.b, self.rb);
        let vn = self.n.dot(dv);
        let unilateral = self.kind != Kind::Rod;
        let target = if unilateral && self.gap > 0.0 {
            -self.gap * inv_h
        } else {
            0.0
        };
        let mut lambda = self.impulse - self.mass * (vn - target);
        if unilateral {
            lambda = lambda.max(0.0);
        }
        let d = lambda - self.impulse;
        self.impulse = lambda;
        if d != 0.0 {
            self.apply(sys, self.n * d);
        }
        if self.kind == Kind::Contact && self.friction > 0.0 && self.impulse > 0.0 {
            let dv = sys.velocity(&self.a, self.ra) - sys.velocity(&self.b, self.rb);
            let vt = dv - self.n * self.n.dot(dv);
            let speed = vt.length();
            if speed > 1.0e-9 {
                let t = vt / speed;
                let k = sys.inv_mass(&self.a, self.ra, t) + sys.inv_mass(&self.b, self.rb, t);
                if k > 0.0 {
                    let old = self.tangent;
                    let mut new = old - t * (speed / k);
                    let max = self.friction * self.impulse;
                    let l2 = new.length_squared();
                    if l2 > max * max {
                        new *= max / l2.sqrt();
                    }
                    self.tangent = new;
                    self.apply(sys, new - old);
                }
            }
        }
    }

    pub(super) fn solve_position(&mut self, sys: &mut Sys, slop: f32) {
        let (n, gap) = self.measure(sys, self.ra, self.rb);
        let err = match self.kind {
            Kind::Rod => gap,
            _ if gap < -slop => gap + slop,
            _ => return,
        };
        if err == 0.0 {
            return;
        }
        let k = sys.inv_mass(&self.a, self.ra, n) + sys.inv_mass(&self.b, self.rb, n);
        if k <= 0.0 {
            return;
        }
        let p = n * (-err / k);
        sys.shift(&self.a, self.ra, p);
        sys.shift(&self.b, self.rb, -p);
    }

    pub(super) fn restitute(&mut self, sys: &mut Sys, threshold: f32) {
        if self.restitution == 0.0 || self.vn0 > -threshold || self.total <= 0.0 || self.mass == 0.0 {
            return;
        }
        let vn = self
            .n
            .dot(sys.velocity(&self.a, self.ra) - sys.velocity(&self.b, self.rb));
        let lambda = (self.bounce - self.mass * (vn + self.restitution * self.vn0)).max(0.0);
        let d = lambda - self.bounce;
        self.bounce = lambda;
        self.apply(sys, self.n * d);
    }
}

impl Simple {
    #[inline]
    pub(super) fn solve_velocity(&mut self, x: Vec3, v: &mut Vec3, inv_h: f32) {
        let rel = *v - self.v;
        let vn = self.n.dot(rel);
        let gap = self.n.dot(x) - self.offset;
        let target = if gap > 0.0 { -gap * inv_h } else { 0.0 };
        if vn >= target {
            return;
        }
        let dn = target - vn;
        *v += self.n * dn;
        self.total += dn;
        if self.friction > 0.0 {
            let rel = *v - self.v;
            let vt = rel - self.n * self.n.dot(rel);
            let max = self.friction * dn;
            let s2 = vt.length_squared();
            if s2 <= max * max {
                *v -= vt;
            } else {
                *v -= vt * (max / s2.sqrt());
            }
        }
    }

    #[inline]
    pub(super) fn solve_position(&self, x: &mut Vec3, slop: f32) {
        let gap = self.n.dot(*x) - self.offset;
        if gap < -slop {
            *x -= self.n * (gap + slop);
        }
    }

    #[inline]
    pub(super) fn restitute(&self, v: &mut Vec3, threshold: f32) {
        if self.restitution == 0.0 || self.vn0 > -threshold || self.total <= 0.0 {
            return;
        }
        let vn = self.n.dot(*v - self.v);
        let target = -self.restitution * self.vn0;
        if vn < target {
            *v += self.n * (target - vn);
        }
    }
}

/// The side for a point on a body: coupled when the body is dynamic and awake.
pub(super) fn body_side(
    body: &Body,
    slot: u32,
    point: Vec3,
    coupled: &mut Vec<Coupled>,
    index: &mut IntMap<u32, u32>,
) -> Side {
    if body.is_dynamic() && body.awake {
        let c = *index.entry(slot).or_insert_with(|| {
            coupled.push(Coupled::new(body, slot));
            (coupled.len() - 1) as u32
        });
        coupled[c as usize].touched = true;
        Side::Body {
            c,
            local: body.xf.q.conjugate() * (point - body.center),
        }
    } else {
        Side::Fixed {
            p: point,
            v: if body.awake {
                body.point_velocity(point)
            } else {
                Vec3::ZERO
            },
            sleeper: if body.is_dynamic() { slot } else { NONE },
        }
    }
}

//! Springs between rigid bodies (or a body and a world anchor), evaluated every sub-step.
//!
//! A spring that ends only on bodies and world points is not added to the force
//! accumulators at the start of the step (`forces.rs`): the forces stage lists it here, and
//! the solver applies it at the start of every sub-step from the bodies' poses then
//! (`apply`), before the constraints — symplectic Euler at the sub-step, whose one-step map
//! keeps a spring's phase-space area. Held over a whole step, a spring's torque on a body
//! that turns within the step is stale: a 200 N/m spring 3 m off a 5 kg capsule's centre
//! (the capsule turns at its attachment as if it weighed 80 g) pumped it to 3,000 rad/s.
//! Springs with a particle end stay in the forces stage (particles have no turn).
//!
//! * Spring and bungee: Hooke's law and damping along the line between the two points,
//!   stiffness and damping capped where the sub-step would lose stability (see
//!   [`MAX_SUBSTEP_STIFFNESS`]), so any value is stable.
//! * Stiff spring: the exact-step gains (`forces::stiff_spring_gains`) for one sub-step, so
//!   the sub-steps together reproduce the damped oscillator exactly, computed for the
//!   mobility of the attachment point (a point off a light body's centre moves more than
//!   the mass says); the anchor end feels no reaction.

use super::forces::stiff_spring_gains;
use crate::dynamics::body::{lock_linear, Body};
use crate::dynamics::solver::{BodyState, Velocity};
use crate::math::{Mat3, Vec3};
use crate::pool::Pool;

/// Largest `k · (1/m_a + 1/m_b) · h²` a spring acts with, where `1/m` is each end's mobility
/// at its attachment and `h` the sub-step: one radian per sub-step. Past it the spring acts
/// as if it were that stiff (and its damping `c · (1/m_a + 1/m_b) · h` is capped at 1):
/// symplectic Euler is stable up to 4, and below 1 its energy stays within a quarter of the
/// spring's.
pub const MAX_SUBSTEP_STIFFNESS: f32 = 1.0;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Spring,
    Bungee,
    Stiff,
}

/// One end: a body point (slot, point in the body frame) or a world point.
#[derive(Clone, Copy, Debug)]
pub enum SpringEnd {
    Body(u32, Vec3),
    World(Vec3),
}

/// A spring end resolved for the step: solver index (0: does not move), centre of mass at
/// the step start, arm from it at the step start, mobility.
#[derive(Clone, Copy, Debug, Default)]
struct Resolved {
    index: u32,
    center: Vec3,
    arm: Vec3,
    mobility: f32,
}

/// One spring for this step.
#[derive(Clone, Copy, Debug)]
pub struct BodySpring {
    pub kind: Kind,
    pub a: SpringEnd,
    pub b: SpringEnd,
    pub rest_length: f32,
    pub stiffness: f32,
    pub damping: f32,
    ra: Resolved,
    rb: Resolved,
    /// Capped coefficients, or the stiff spring's gains per sub-step (`K`, `D`) and the
    /// effective mass they act through.
    k: f32,
    c: f32,
    mass: f32,
}

impl BodySpring {
    pub fn new(kind: Kind, a: SpringEnd, b: SpringEnd, rest_length: f32, stiffness: f32, damping: f32) -> Self {
        BodySpring {
            kind,
            a,
            b,
            rest_length,
            stiffness,
            damping,
            ra: Resolved::default(),
            rb: Resolved::default(),
            k: 0.0,
            c: 0.0,
            mass: 0.0,
        }
    }
}

/// This step's springs (storage reused across steps).
#[derive(Default)]
pub struct BodySprings {
    pub list: Vec<BodySpring>,
}

/// The most a point at arm `r` of a body moves per unit impulse in any direction (1/kg):
/// the largest eigenvalue of `1/m + [r]ᵀ I⁻¹ [r]`.
pub fn mobility(inv_mass: f32, inv_inertia: &Mat3, r: Vec3) -> f32 {
    locked_mobility(Vec3::splat(inv_mass), inv_inertia, r)
}

/// `mobility` of a body with locked axes: `inv_mass` per world axis (zero along locked ones)
/// and its reduced inverse inertia (`body::reduced_inverse_inertia`), the masses the
/// constraints and the integration move it with.
pub fn locked_mobility(inv_mass: Vec3, inv_inertia: &Mat3, r: Vec3) -> f32 {
    let r = r.as_dvec3();
    let s = glam::DMat3::from_cols(
        glam::DVec3::new(0.0, r.z, -r.y),
        glam::DVec3::new(-r.z, 0.0, r.x),
        glam::DVec3::new(r.y, -r.x, 0.0),
    );
    let k = glam::DMat3::from_diagonal(inv_mass.as_dvec3()) + s.transpose() * inv_inertia.as_dmat3() * s;
    max_eigenvalue(k) as f32
}

/// The largest eigenvalue of a symmetric positive semi-definite 3×3 matrix (closed form).
fn max_eigenvalue(m: glam::DMat3) -> f64 {
    let (a, b, c) = (m.x_axis.x, m.y_axis.y, m.z_axis.z);
    let (d, e, f) = (m.x_axis.y, m.y_axis.z, m.x_axis.z);
    let p1 = d * d + e * e + f * f;
    let q = (a + b + c) / 3.0;
    if p1 <= 1e-30 * (a * a + b * b + c * c) {
        return a.max(b).max(c);
    }
    let p2 = (a - q).powi(2) + (b - q).powi(2) + (c - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    let bm = (m - glam::DMat3::from_diagonal(glam::DVec3::splat(q))) * (1.0 / p);
    let r = (bm.determinant() / 2.0).clamp(-1.0, 1.0);
    q + 2.0 * p * (r.acos() / 3.0).cos()
}

fn resolve(end: &SpringEnd, bodies: &Pool<Body>) -> Resolved {
    match *end {
        SpringEnd::World(p) => Resolved {
            index: 0,
            center: p,
            arm: Vec3::ZERO,
            mobility: 0.0,
        },
        SpringEnd::Body(slot, local) => {
            let b = bodies.at(slot);
            let point = b.xf.apply(local);
            let moves = b.is_dynamic() && b.awake;
            Resolved {
                index: if b.awake { b.solver_index } else { 0 },
                center: b.center,
                arm: point - b.center,
                mobility: if moves {
                    let inv_mass = lock_linear(Vec3::splat(b.inv_mass), b.locks());
                    locked_mobility(inv_mass, &b.inv_inertia_world, point - b.center)
                } else {
                    0.0
                },
            }
        }
    }
}

impl BodySpring {
    /// Solver indices of the two ends (0: does not move), once prepared.
    pub fn solver_indices(&self) -> [u32; 2] {
        [self.ra.index, self.rb.index]
    }
}

/// Resolves the springs for the step (after the solver's body arrays are built).
pub fn prepare(springs: &mut BodySprings, bodies: &Pool<Body>, h: f32) {
    for s in springs.list.iter_mut() {
        s.ra = resolve(&s.a, bodies);
        s.rb = resolve(&s.b, bodies);
        let mobility = s.ra.mobility + s.rb.mobility;
        match s.kind {
            Kind::Spring | Kind::Bungee => {
                if mobility > 0.0 {
                    let limit = MAX_SUBSTEP_STIFFNESS / (mobility * h);
                    s.k = s.stiffness.min(limit / h);
                    s.c = s.damping.min(limit);
                } else {
                    (s.k, s.c) = (0.0, 0.0);
                }
            }
            Kind::Stiff => {
                let m = s.ra.mobility;
                if m > 0.0 {
                    (s.k, s.c) = stiff_spring_gains(s.stiffness as f64 * m as f64, s.damping as f64 * m as f64, h, 1);
                    s.mass = 1.0 / m;
                } else {
                    (s.k, s.c, s.mass) = (0.0, 0.0, 0.0);
                }
            }
        }
    }
}

/// Where an end is now, its arm and the velocity of the point.
#[inline]
fn point(r: &Resolved, vel: &[Velocity], states: &[BodyState]) -> (Vec3, Vec3, Vec3) {
    if r.index == 0 {
        return (r.center + r.arm, r.arm, Vec3::ZERO);
    }
    let s = &states[r.index as usize];
    let u = &vel[r.index as usize];
    let arm = s.dq() * r.arm;
    (r.center + s.dp() + arm, arm, u.v + u.w.cross(arm))
}

#[inline]
fn push(r: &Resolved, arm: Vec3, impulse: Vec3, vel: &mut [Velocity], states: &[BodyState]) {
    if r.index == 0 || r.mobility == 0.0 {
        return;
    }
    let s = &states[r.index as usize];
    let u = &mut vel[r.index as usize];
    // Per-axis inverse mass: nothing along a locked axis (the angular part goes through
    // the reduced inverse inertia, zero about locked axes).
    u.v += lock_linear(Vec3::splat(s.inv_mass), s.locks) * impulse;
    u.w += s.inv_i() * arm.cross(impulse);
}

/// Applies one sub-step of `h` of every spring to the velocities, from the poses now.
pub fn apply(springs: &BodySprings, vel: &mut [Velocity], states: &[BodyState], h: f32) {
    for s in &springs.list {
        let (pa, arm_a, va) = point(&s.ra, vel, states);
        let (pb, arm_b, vb) = point(&s.rb, vel, states);
        let impulse = match s.kind {
            Kind::Spring | Kind::Bungee => {
                let d = pa - pb;
                let len = d.length();
                if len < 1.0e-9 {
                    continue;
                }
                let n = d / len;
                let stretch = len - s.rest_length;
                if s.kind == Kind::Bungee && stretch <= 0.0 {
                    continue;
                }
                let mut magnitude = s.k * stretch + s.c * (va - vb).dot(n);
                if s.kind == Kind::Bungee {
                    magnitude = magnitude.max(0.0);
                }
                -magnitude * h * n
            }
            Kind::Stiff => (-s.k * (pa - pb) - s.c * (va - vb)) * (s.mass * h),
        };
        push(&s.ra, arm_a, impulse, vel, states);
        if s.kind != Kind::Stiff {
            push(&s.rb, arm_b, -impulse, vel, states);
        }
    }
}

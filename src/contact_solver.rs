//! Contact constraints for the soft-step solver: prepare from manifolds, warm start, solve
//! (normal with soft bias and speculative limits, then Coulomb friction with a static and a
//! dynamic coefficient), restitution, and storing impulses for the next step.

use crate::collision::MAX_MANIFOLD_POINTS;
use crate::math::{orthonormal_basis, Vec3};
use crate::solver::{BodyState, Softness};
use crate::world::World;

/// Tangential speed (m/s) below which a contact point is treated as sticking.
const STICK_SPEED: f32 = 0.01;

#[derive(Clone, Copy, Debug, Default)]
pub struct ConstraintPoint {
    pub ra: Vec3,
    pub rb: Vec3,
    /// Separation at the start of the step minus the anchor offset along the normal.
    pub adjusted_separation: f32,
    pub normal_mass: f32,
    pub tangent_mass: [f32; 2],
    pub normal_impulse: f32,
    pub tangent_impulse: [f32; 2],
    pub max_normal_impulse: f32,
    /// Normal relative velocity before the solve (for restitution).
    pub relative_velocity: f32,
    pub sliding: bool,
}

#[derive(Clone, Copy, Debug)]
pub struct ContactConstraint {
    pub a: u32,
    pub b: u32,
    pub contact: u32,
    pub normal: Vec3,
    pub tangents: [Vec3; 2],
    pub static_friction: f32,
    pub dynamic_friction: f32,
    pub restitution: f32,
    pub soft: Softness,
    pub count: usize,
    pub points: [ConstraintPoint; MAX_MANIFOLD_POINTS],
}

/// Builds constraints for every awake contact with manifold points.
pub fn prepare(world: &mut World, h: f32) {
    let settings = world.settings;
    let contact_hertz = settings.contact_hertz.min(0.25 / h);
    let soft = Softness::new(contact_hertz, settings.contact_damping_ratio, h);
    let static_soft = Softness::new(2.0 * contact_hertz, settings.contact_damping_ratio, h);
    let constraints = &mut world.solver.constraints;
    let states = &world.solver.states;
    constraints.clear();
    for &ci in &world.awake_contacts {
        let c = world.contacts.at(ci);
        if c.manifold.count == 0 {
            continue;
        }
        let ba = world.bodies.at(c.body_a);
        let bb = world.bodies.at(c.body_b);
        let a = if ba.awake { ba.solver_index } else { 0 };
        let b = if bb.awake { bb.solver_index } else { 0 };
        let (sa, sb) = (&states[a as usize], &states[b as usize]);
        if sa.inv_mass == 0.0 && sb.inv_mass == 0.0 {
            continue;
        }
        let n = c.manifold.normal;
        let (t1, t2) = orthonormal_basis(n);
        let mut cc = ContactConstraint {
            a,
            b,
            contact: ci,
            normal: n,
            tangents: [t1, t2],
            static_friction: c.static_friction,
            dynamic_friction: c.dynamic_friction,
            restitution: c.restitution,
            soft: if sa.inv_mass == 0.0 || sb.inv_mass == 0.0 {
                static_soft
            } else {
                soft
            },
            count: c.manifold.count,
            points: [ConstraintPoint::default(); MAX_MANIFOLD_POINTS],
        };
        for i in 0..c.manifold.count {
            let mp = &c.manifold.points[i];
            let imp = &c.impulses[i];
            let ra = mp.point - ba.center;
            let rb = mp.point - bb.center;
            let k = |d: Vec3| {
                let (rna, rnb) = (ra.cross(d), rb.cross(d));
                let k =
                    sa.inv_mass + sb.inv_mass + rna.dot(sa.inv_i * rna) + rnb.dot(sb.inv_i * rnb);
                if k > 0.0 {
                    1.0 / k
                } else {
                    0.0
                }
            };
            let dv = sb.v + sb.w.cross(rb) - sa.v - sa.w.cross(ra);
            let vt = dv - n * dv.dot(n);
            cc.points[i] = ConstraintPoint {
                ra,
                rb,
                adjusted_separation: mp.separation - (rb - ra).dot(n),
                normal_mass: k(n),
                tangent_mass: [k(t1), k(t2)],
                normal_impulse: imp.normal,
                tangent_impulse: [imp.tangent.dot(t1), imp.tangent.dot(t2)],
                max_normal_impulse: 0.0,
                relative_velocity: dv.dot(n),
                sliding: vt.length_squared() > STICK_SPEED * STICK_SPEED,
            };
        }
        constraints.push(cc);
    }
}

#[inline]
fn apply(sa: &mut BodyState, sb: &mut BodyState, ra: Vec3, rb: Vec3, p: Vec3) {
    sa.v -= sa.inv_mass * p;
    sa.w -= sa.inv_i * ra.cross(p);
    sb.v += sb.inv_mass * p;
    sb.w += sb.inv_i * rb.cross(p);
}

#[inline]
fn states_pair(states: &mut [BodyState], a: u32, b: u32) -> (BodyState, BodyState) {
    (states[a as usize], states[b as usize])
}

#[inline]
fn write_back(states: &mut [BodyState], a: u32, b: u32, sa: BodyState, sb: BodyState) {
    // State 0 is the static dummy: never written.
    if a != 0 {
        states[a as usize] = sa;
    }
    if b != 0 {
        states[b as usize] = sb;
    }
}

pub fn warm_start(states: &mut [BodyState], constraints: &[ContactConstraint]) {
    for c in constraints {
        let (mut sa, mut sb) = states_pair(states, c.a, c.b);
        for p in &c.points[..c.count] {
            let imp = c.normal * p.normal_impulse
                + c.tangents[0] * p.tangent_impulse[0]
                + c.tangents[1] * p.tangent_impulse[1];
            apply(&mut sa, &mut sb, p.ra, p.rb, imp);
        }
        write_back(states, c.a, c.b, sa, sb);
    }
}

/// One Gauss–Seidel pass. With `use_bias` overlap is pushed out softly; without it (relax)
/// only velocities are made consistent, removing the energy the push added.
pub fn solve(
    states: &mut [BodyState],
    constraints: &mut [ContactConstraint],
    inv_h: f32,
    max_push: f32,
    slop: f32,
    use_bias: bool,
) {
    for c in constraints.iter_mut() {
        let (mut sa, mut sb) = states_pair(states, c.a, c.b);
        let n = c.normal;
        let d_p = sb.dp - sa.dp;
        for p in c.points[..c.count].iter_mut() {
            // Current separation from the motion of the step so far.
            let pra = sa.dq * p.ra;
            let prb = sb.dq * p.rb;
            let s = (d_p + prb - pra).dot(n) + p.adjusted_separation;
            let (bias, mass_scale, impulse_scale) = if s > 0.0 {
                (s * inv_h, 1.0, 0.0) // speculative: may close the gap, no more
            } else if use_bias {
                (
                    (c.soft.bias_rate * (s + slop).min(0.0)).max(-max_push),
                    c.soft.mass_scale,
                    c.soft.impulse_scale,
                )
            } else {
                (0.0, 1.0, 0.0)
            };
            let dv = sb.v + sb.w.cross(p.rb) - sa.v - sa.w.cross(p.ra);
            let vn = dv.dot(n);
            let impulse =
                -p.normal_mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
            let new_impulse = (p.normal_impulse + impulse).max(0.0);
            let applied = new_impulse - p.normal_impulse;
            p.normal_impulse = new_impulse;
            p.max_normal_impulse = p.max_normal_impulse.max(applied);
            apply(&mut sa, &mut sb, p.ra, p.rb, n * applied);
        }
        for p in c.points[..c.count].iter_mut() {
            let dv = sb.v + sb.w.cross(p.rb) - sa.v - sa.w.cross(p.ra);
            let old = p.tangent_impulse;
            let mut new = [
                old[0] - p.tangent_mass[0] * dv.dot(c.tangents[0]),
                old[1] - p.tangent_mass[1] * dv.dot(c.tangents[1]),
            ];
            let len2 = new[0] * new[0] + new[1] * new[1];
            let static_limit = c.static_friction * p.normal_impulse;
            if !p.sliding && len2 > static_limit * static_limit {
                p.sliding = true; // static friction broke: the surfaces slide
            }
            let limit = if p.sliding {
                c.dynamic_friction * p.normal_impulse
            } else {
                static_limit
            };
            if len2 > limit * limit {
                let scale = limit / len2.sqrt();
                new[0] *= scale;
                new[1] *= scale;
            }
            p.tangent_impulse = new;
            let d = c.tangents[0] * (new[0] - old[0]) + c.tangents[1] * (new[1] - old[1]);
            apply(&mut sa, &mut sb, p.ra, p.rb, d);
        }
        write_back(states, c.a, c.b, sa, sb);
    }
}

/// Bounces: drives the normal velocity to `-e · (approach velocity)` for points that
/// approached faster than the threshold and really pushed.
pub fn apply_restitution(
    states: &mut [BodyState],
    constraints: &mut [ContactConstraint],
    threshold: f32,
) {
    for c in constraints.iter_mut() {
        if c.restitution == 0.0 {
            continue;
        }
        let (mut sa, mut sb) = states_pair(states, c.a, c.b);
        for p in c.points[..c.count].iter_mut() {
            if p.relative_velocity > -threshold || p.max_normal_impulse == 0.0 {
                continue;
            }
            let dv = sb.v + sb.w.cross(p.rb) - sa.v - sa.w.cross(p.ra);
            let vn = dv.dot(c.normal);
            let impulse = -p.normal_mass * (vn + c.restitution * p.relative_velocity);
            let new_impulse = (p.normal_impulse + impulse).max(0.0);
            let applied = new_impulse - p.normal_impulse;
            p.normal_impulse = new_impulse;
            p.max_normal_impulse = p.max_normal_impulse.max(applied);
            apply(&mut sa, &mut sb, p.ra, p.rb, c.normal * applied);
        }
        write_back(states, c.a, c.b, sa, sb);
    }
}

/// Keeps each point's impulses on its contact for warm starting the next step.
pub fn store_impulses(world: &mut World) {
    for c in &world.solver.constraints {
        let contact = world.contacts.at_mut(c.contact);
        for (i, p) in c.points[..c.count].iter().enumerate() {
            let imp = &mut contact.impulses[i];
            imp.normal = p.normal_impulse;
            imp.tangent =
                c.tangents[0] * p.tangent_impulse[0] + c.tangents[1] * p.tangent_impulse[1];
            imp.sliding = p.sliding;
            imp.max_normal = p.max_normal_impulse;
        }
    }
}

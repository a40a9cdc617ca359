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
    /// Separation at the start of the step (m, negative when overlapping).
    pub separation: f32,
    pub normal_mass: f32,
    pub normal_impulse: f32,
    pub max_normal_impulse: f32,
    /// Normal relative velocity before the solve (for restitution).
    pub relative_velocity: f32,
}

/// Coulomb friction of the contact patch: two tangent directions at the centroid of the
/// manifold and a twist about the normal, clamped by μ times the total normal impulse.
/// Solving the patch as one (rather than per point) keeps friction from leaking into
/// spurious twist, so a sliding box feels exactly μ·N.
#[derive(Clone, Copy, Debug, Default)]
pub struct PatchFriction {
    pub ra: Vec3,
    pub rb: Vec3,
    pub tangent_mass: [f32; 2],
    pub twist_mass: f32,
    /// Mean distance of the points from the centroid: the lever of torsional friction.
    pub twist_radius: f32,
    pub tangent_impulse: [f32; 2],
    pub twist_impulse: f32,
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
    pub friction: PatchFriction,
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
            friction: PatchFriction::default(),
        };
        let inv_mass = |ra: Vec3, rb: Vec3, d: Vec3| {
            let (rna, rnb) = (ra.cross(d), rb.cross(d));
            let k = sa.inv_mass + sb.inv_mass + rna.dot(sa.inv_i * rna) + rnb.dot(sb.inv_i * rnb);
            if k > 0.0 {
                1.0 / k
            } else {
                0.0
            }
        };
        let mut centroid = Vec3::ZERO;
        for i in 0..c.manifold.count {
            let mp = &c.manifold.points[i];
            centroid += mp.point;
            let ra = mp.point - ba.center;
            let rb = mp.point - bb.center;
            let dv = sb.v + sb.w.cross(rb) - sa.v - sa.w.cross(ra);
            cc.points[i] = ConstraintPoint {
                ra,
                rb,
                separation: mp.separation,
                normal_mass: inv_mass(ra, rb, n),
                normal_impulse: c.impulses[i].normal,
                max_normal_impulse: 0.0,
                relative_velocity: dv.dot(n),
            };
        }
        centroid /= c.manifold.count as f32;
        let twist_radius = c
            .manifold
            .points()
            .iter()
            .map(|p| (p.point - centroid).length())
            .sum::<f32>()
            / c.manifold.count as f32;
        let (ra, rb) = (centroid - ba.center, centroid - bb.center);
        let dv = sb.v + sb.w.cross(rb) - sa.v - sa.w.cross(ra);
        let vt = dv - n * dv.dot(n);
        let k_twist = n.dot(sa.inv_i * n) + n.dot(sb.inv_i * n);
        let f = &c.friction;
        cc.friction = PatchFriction {
            ra,
            rb,
            tangent_mass: [inv_mass(ra, rb, t1), inv_mass(ra, rb, t2)],
            twist_mass: if k_twist > 0.0 { 1.0 / k_twist } else { 0.0 },
            twist_radius,
            tangent_impulse: [f.tangent.dot(t1), f.tangent.dot(t2)],
            twist_impulse: f.twist,
            sliding: vt.length_squared() > STICK_SPEED * STICK_SPEED,
        };
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

/// Where an impulse between the two bodies acts now. `ra`, `rb` are the lever arms of one
/// world point at the start of the step; since then each body moved by its own `dp`, `dq`.
/// Returns the arms from each current centre of mass to the midpoint of the two material
/// points, and the gap between those points (B minus A). Applying equal and opposite
/// impulses at one point keeps angular momentum exact while the bodies move in the step.
#[inline]
fn current_arms(sa: &BodyState, sb: &BodyState, ra: Vec3, rb: Vec3) -> (Vec3, Vec3, Vec3) {
    let pra = sa.dq * ra;
    let prb = sb.dq * rb;
    let gap = (ra - rb) + (sb.dp - sa.dp) + (prb - pra);
    (pra + 0.5 * gap, prb - 0.5 * gap, gap)
}

#[inline]
fn apply_angular(sa: &mut BodyState, sb: &mut BodyState, l: Vec3) {
    sa.w -= sa.inv_i * l;
    sb.w += sb.inv_i * l;
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
            let (ra, rb, _) = current_arms(&sa, &sb, p.ra, p.rb);
            apply(&mut sa, &mut sb, ra, rb, c.normal * p.normal_impulse);
        }
        let f = &c.friction;
        let t = c.tangents[0] * f.tangent_impulse[0] + c.tangents[1] * f.tangent_impulse[1];
        let (ra, rb, _) = current_arms(&sa, &sb, f.ra, f.rb);
        apply(&mut sa, &mut sb, ra, rb, t);
        apply_angular(&mut sa, &mut sb, c.normal * f.twist_impulse);
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
        let count = c.count;
        for k in 0..count {
            // Alternate the order between passes so no point is always solved first: a fixed
            // order biases the impulse distribution and tilts tall stacks.
            let p = &mut c.points[if use_bias { k } else { count - 1 - k }];
            // Current separation from the motion of the step so far.
            let (ra, rb, gap) = current_arms(&sa, &sb, p.ra, p.rb);
            let s = gap.dot(n) + p.separation;
            let (bias, mass_scale, impulse_scale) = if s > 0.0 {
                (s * inv_h, 1.0, 0.0) // speculative: may close the gap, no more
            } else if use_bias {
                // Soft push-out (rate from the contact's stiffness and damping) but a rigid
                // mass: the load is carried by the accumulated impulse, not by overlap, so a
                // deep stack does not sag like a column of springs.
                if std::env::var("HEARTH_SOFT").is_ok() {
                    (
                        (c.soft.bias_rate * (s + slop).min(0.0)).max(-max_push),
                        c.soft.mass_scale,
                        c.soft.impulse_scale,
                    )
                } else {
                    (
                        (c.soft.bias_rate * (s + slop).min(0.0)).max(-max_push),
                        1.0,
                        0.0,
                    )
                }
            } else {
                (0.0, 1.0, 0.0)
            };
            let dv = sb.v + sb.w.cross(rb) - sa.v - sa.w.cross(ra);
            let vn = dv.dot(n);
            let impulse =
                -p.normal_mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
            let new_impulse = (p.normal_impulse + impulse).max(0.0);
            let applied = new_impulse - p.normal_impulse;
            p.normal_impulse = new_impulse;
            p.max_normal_impulse = p.max_normal_impulse.max(applied);
            apply(&mut sa, &mut sb, ra, rb, n * applied);
        }
        let total_normal: f32 = c.points[..c.count].iter().map(|p| p.normal_impulse).sum();
        let f = &mut c.friction;
        let (fra, frb, _) = current_arms(&sa, &sb, f.ra, f.rb);
        let dv = sb.v + sb.w.cross(frb) - sa.v - sa.w.cross(fra);
        let old = f.tangent_impulse;
        let mut new = [
            old[0] - f.tangent_mass[0] * dv.dot(c.tangents[0]),
            old[1] - f.tangent_mass[1] * dv.dot(c.tangents[1]),
        ];
        let old_twist = f.twist_impulse;
        let mut twist = old_twist - f.twist_mass * (sb.w - sa.w).dot(n);
        let len2 = new[0] * new[0] + new[1] * new[1];
        let static_limit = c.static_friction * total_normal;
        if !f.sliding && len2 > static_limit * static_limit {
            f.sliding = true; // static friction broke: the surfaces slide
        }
        let limit = if f.sliding {
            c.dynamic_friction * total_normal
        } else {
            static_limit
        };
        if len2 > limit * limit {
            let scale = limit / len2.sqrt();
            new[0] *= scale;
            new[1] *= scale;
        }
        let twist_limit = limit * f.twist_radius;
        twist = twist.clamp(-twist_limit, twist_limit);
        f.tangent_impulse = new;
        f.twist_impulse = twist;
        let d = c.tangents[0] * (new[0] - old[0]) + c.tangents[1] * (new[1] - old[1]);
        apply(&mut sa, &mut sb, fra, frb, d);
        apply_angular(&mut sa, &mut sb, n * (twist - old_twist));
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
            let (ra, rb, _) = current_arms(&sa, &sb, p.ra, p.rb);
            let dv = sb.v + sb.w.cross(rb) - sa.v - sa.w.cross(ra);
            let vn = dv.dot(c.normal);
            let impulse = -p.normal_mass * (vn + c.restitution * p.relative_velocity);
            let new_impulse = (p.normal_impulse + impulse).max(0.0);
            let applied = new_impulse - p.normal_impulse;
            p.normal_impulse = new_impulse;
            p.max_normal_impulse = p.max_normal_impulse.max(applied);
            apply(&mut sa, &mut sb, ra, rb, c.normal * applied);
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
            imp.max_normal = p.max_normal_impulse;
        }
        let f = &c.friction;
        contact.friction.tangent =
            c.tangents[0] * f.tangent_impulse[0] + c.tangents[1] * f.tangent_impulse[1];
        contact.friction.twist = f.twist_impulse;
        contact.friction.sliding = f.sliding;
    }
}

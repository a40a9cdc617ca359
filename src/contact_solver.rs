//! Contact constraints of the sub-stepped solver.
//!
//! Per step, `prepare` builds one constraint per touching manifold. Per sub-step, `refresh`
//! recomputes each point's lever arms from the bodies' motion so far (the midpoint of the
//! two material points, so equal and opposite impulses act at one point and angular
//! momentum is kept exactly), the angular Jacobians and effective masses, and the current
//! separation. The passes that follow — `warm_start`, two `solve` sweeps over real
//! velocities (rigid non-penetration, speculative gaps, patch friction with a static and a
//! dynamic coefficient) and `push_out` (overlap removed by pseudo-velocities) — then cost a
//! few dot products per point. After the sub-steps: `apply_restitution`, `store_impulses`.

use crate::collision::MAX_MANIFOLD_POINTS;
use crate::math::{orthonormal_basis, Vec3};
use crate::solver::{BodyState, Velocity};
use crate::world::World;

/// Tangential speed (m/s) below which a contact patch starts a step sticking.
const STICK_SPEED: f32 = 0.01;

#[derive(Clone, Copy, Debug, Default)]
pub struct ConstraintPoint {
    /// Lever arms of the contact point at the start of the step.
    pub ra0: Vec3,
    pub rb0: Vec3,
    /// Separation at the start of the step (m, negative when overlapping).
    pub separation0: f32,
    /// Refreshed every sub-step: `r × n` and `I⁻¹ (r × n)` of each body, the separation.
    pub rna: Vec3,
    pub rnb: Vec3,
    pub ia: Vec3,
    pub ib: Vec3,
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
    pub ra0: Vec3,
    pub rb0: Vec3,
    /// Per tangent: `r × t`, `I⁻¹ (r × t)` of each body; refreshed every sub-step.
    pub rta: [Vec3; 2],
    pub rtb: [Vec3; 2],
    pub ita: [Vec3; 2],
    pub itb: [Vec3; 2],
    /// `I⁻¹ n` of each body, for the twist.
    pub ina: Vec3,
    pub inb: Vec3,
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
    /// The persistent contact, or `NONE` for a generated contact.
    pub contact: u32,
    /// Inverse masses of the two bodies.
    pub ma: f32,
    pub mb: f32,
    pub normal: Vec3,
    pub tangents: [Vec3; 2],
    pub static_friction: f32,
    pub dynamic_friction: f32,
    pub restitution: f32,
    pub count: usize,
    pub points: [ConstraintPoint; MAX_MANIFOLD_POINTS],
    /// Coupling of the points' normal impulses, `K = J M⁻¹ Jᵀ`, and the inverse of K
    /// (slightly regularised: four coplanar points constrain only three motions); refreshed
    /// every sub-step.
    pub k: [[f32; MAX_MANIFOLD_POINTS]; MAX_MANIFOLD_POINTS],
    pub k_inv: [[f32; MAX_MANIFOLD_POINTS]; MAX_MANIFOLD_POINTS],
    pub friction: PatchFriction,
}

/// Inner iterations of the per-manifold block solve when its exact solution would pull. They
/// run on the cached `K` without touching body state.
const BLOCK_ITERATIONS: usize = 4;

/// Relative regularisation of `K` before inversion.
const BLOCK_REGULARIZATION: f32 = 1.0e-3;

/// Inverts the leading `n × n` block of `m` by Gauss–Jordan with partial pivoting; false
/// when singular.
fn invert(
    m: &[[f32; MAX_MANIFOLD_POINTS]; MAX_MANIFOLD_POINTS],
    n: usize,
    out: &mut [[f32; MAX_MANIFOLD_POINTS]; MAX_MANIFOLD_POINTS],
) -> bool {
    let mut a = *m;
    *out = [[0.0; MAX_MANIFOLD_POINTS]; MAX_MANIFOLD_POINTS];
    for (i, row) in out.iter_mut().enumerate().take(n) {
        row[i] = 1.0;
    }
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
            .unwrap();
        if a[pivot][col].abs() < 1e-30 {
            return false;
        }
        a.swap(col, pivot);
        out.swap(col, pivot);
        let inv = 1.0 / a[col][col];
        for j in 0..n {
            a[col][j] *= inv;
            out[col][j] *= inv;
        }
        for r in 0..n {
            if r != col {
                let f = a[r][col];
                if f != 0.0 {
                    for j in 0..n {
                        a[r][j] -= f * a[col][j];
                        out[r][j] -= f * out[col][j];
                    }
                }
            }
        }
    }
    true
}

/// Builds constraints for every awake contact with manifold points.
pub fn prepare(world: &mut World) {
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
        let (ua, ub) = (&world.solver.vel[a as usize], &world.solver.vel[b as usize]);
        let n = c.manifold.normal;
        let (t1, t2) = orthonormal_basis(n);
        let mut cc = ContactConstraint {
            a,
            b,
            ma: sa.inv_mass,
            mb: sb.inv_mass,
            contact: ci,
            normal: n,
            tangents: [t1, t2],
            static_friction: c.static_friction,
            dynamic_friction: c.dynamic_friction,
            restitution: c.restitution,
            count: c.manifold.count,
            points: [ConstraintPoint::default(); MAX_MANIFOLD_POINTS],
            k: [[0.0; MAX_MANIFOLD_POINTS]; MAX_MANIFOLD_POINTS],
            k_inv: [[0.0; MAX_MANIFOLD_POINTS]; MAX_MANIFOLD_POINTS],
            friction: PatchFriction::default(),
        };
        let mut centroid = Vec3::ZERO;
        for i in 0..c.manifold.count {
            let mp = &c.manifold.points[i];
            centroid += mp.point;
            let ra = mp.point - ba.center;
            let rb = mp.point - bb.center;
            let dv = ub.v + ub.w.cross(rb) - ua.v - ua.w.cross(ra);
            cc.points[i] = ConstraintPoint {
                ra0: ra,
                rb0: rb,
                separation0: mp.separation,
                normal_impulse: c.impulses[i].normal,
                relative_velocity: dv.dot(n),
                ..Default::default()
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
        let dv = ub.v + ub.w.cross(rb) - ua.v - ua.w.cross(ra);
        let vt = dv - n * dv.dot(n);
        let f = &c.friction;
        cc.friction = PatchFriction {
            ra0: ra,
            rb0: rb,
            twist_radius,
            tangent_impulse: [f.tangent.dot(t1), f.tangent.dot(t2)],
            twist_impulse: f.twist,
            sliding: vt.length_squared() > STICK_SPEED * STICK_SPEED,
            ..Default::default()
        };
        constraints.push(cc);
    }
    prepare_generated(world);
}

/// Constraints for the contacts that contact generators wrote this step (rods, cables, user
/// callbacks): single points, not persistent, solved together with collision contacts.
fn prepare_generated(world: &mut World) {
    let constraints = &mut world.solver.constraints;
    let states = &world.solver.states;
    let vel = &world.solver.vel;
    for g in &world.generated_contacts {
        let index = |b: u32| -> (u32, crate::math::Vec3) {
            if b == crate::body::NONE {
                return (0, g.point);
            }
            let body = world.bodies.at(b);
            (if body.awake { body.solver_index } else { 0 }, body.center)
        };
        let ((a, ca), (b, cb)) = (index(g.body_a), index(g.body_b));
        let (sa, sb) = (&states[a as usize], &states[b as usize]);
        if sa.inv_mass == 0.0 && sb.inv_mass == 0.0 {
            continue;
        }
        let (ua, ub) = (&vel[a as usize], &vel[b as usize]);
        let n = g.normal;
        let (t1, t2) = orthonormal_basis(n);
        let (ra, rb) = (g.point - ca, g.point - cb);
        let dv = ub.v + ub.w.cross(rb) - ua.v - ua.w.cross(ra);
        let mut cc = ContactConstraint {
            a,
            b,
            ma: sa.inv_mass,
            mb: sb.inv_mass,
            contact: crate::body::NONE,
            normal: n,
            tangents: [t1, t2],
            static_friction: g.friction,
            dynamic_friction: g.friction,
            restitution: g.restitution,
            count: 1,
            points: [ConstraintPoint::default(); MAX_MANIFOLD_POINTS],
            k: [[0.0; MAX_MANIFOLD_POINTS]; MAX_MANIFOLD_POINTS],
            k_inv: [[0.0; MAX_MANIFOLD_POINTS]; MAX_MANIFOLD_POINTS],
            friction: PatchFriction::default(),
        };
        cc.points[0] = ConstraintPoint {
            ra0: ra,
            rb0: rb,
            separation0: -g.penetration,
            relative_velocity: dv.dot(n),
            ..Default::default()
        };
        cc.friction = PatchFriction {
            ra0: ra,
            rb0: rb,
            sliding: (dv - n * dv.dot(n)).length_squared() > STICK_SPEED * STICK_SPEED,
            ..Default::default()
        };
        constraints.push(cc);
    }
}

/// True for constraints built from generated contacts (they store no impulses).
#[inline]
fn is_generated(c: &ContactConstraint) -> bool {
    c.contact == crate::body::NONE
}

/// Where an impulse between the two bodies acts now. `ra`, `rb` are the lever arms of one
/// world point at the start of the step; since then each body moved by its own `dp`, `dq`.
/// Returns the arms from each current centre of mass to the midpoint of the two material
/// points, and the gap between those points (B minus A).
#[inline]
fn current_arms(sa: &BodyState, sb: &BodyState, ra: Vec3, rb: Vec3) -> (Vec3, Vec3, Vec3) {
    let pra = sa.rot * ra;
    let prb = sb.rot * rb;
    let gap = (ra - rb) + (sb.dp - sa.dp) + (prb - pra);
    (pra + 0.5 * gap, prb - 0.5 * gap, gap)
}

#[inline]
fn inverse_or_zero(k: f32) -> f32 {
    if k > 0.0 {
        1.0 / k
    } else {
        0.0
    }
}

/// Recomputes arms, Jacobians, effective masses and separations from the current motion.
pub fn refresh(states: &[BodyState], constraints: &mut [ContactConstraint]) {
    for c in constraints.iter_mut() {
        let (sa, sb) = (&states[c.a as usize], &states[c.b as usize]);
        let n = c.normal;
        let m = c.ma + c.mb;
        for p in c.points[..c.count].iter_mut() {
            let (ra, rb, gap) = current_arms(sa, sb, p.ra0, p.rb0);
            p.separation = p.separation0 + gap.dot(n);
            p.rna = ra.cross(n);
            p.rnb = rb.cross(n);
            p.ia = sa.inv_i * p.rna;
            p.ib = sb.inv_i * p.rnb;
            p.normal_mass = inverse_or_zero(m + p.rna.dot(p.ia) + p.rnb.dot(p.ib));
        }
        for i in 0..c.count {
            for j in i..c.count {
                let (pi, pj) = (&c.points[i], &c.points[j]);
                let kij = m + pi.rna.dot(pj.ia) + pi.rnb.dot(pj.ib);
                c.k[i][j] = kij;
                c.k[j][i] = kij;
            }
        }
        if c.count > 1 {
            let mut reg = c.k;
            for (i, row) in reg.iter_mut().enumerate().take(c.count) {
                row[i] *= 1.0 + BLOCK_REGULARIZATION;
            }
            if !invert(&reg, c.count, &mut c.k_inv) {
                c.k_inv = [[0.0; MAX_MANIFOLD_POINTS]; MAX_MANIFOLD_POINTS];
            }
        }
        let f = &mut c.friction;
        let (ra, rb, _) = current_arms(sa, sb, f.ra0, f.rb0);
        for k in 0..2 {
            let t = c.tangents[k];
            f.rta[k] = ra.cross(t);
            f.rtb[k] = rb.cross(t);
            f.ita[k] = sa.inv_i * f.rta[k];
            f.itb[k] = sb.inv_i * f.rtb[k];
            f.tangent_mass[k] = inverse_or_zero(m + f.rta[k].dot(f.ita[k]) + f.rtb[k].dot(f.itb[k]));
        }
        f.ina = sa.inv_i * n;
        f.inb = sb.inv_i * n;
        f.twist_mass = inverse_or_zero(n.dot(f.ina) + n.dot(f.inb));
    }
}

#[inline]
fn pair(vel: &[Velocity], a: u32, b: u32) -> (Velocity, Velocity) {
    (vel[a as usize], vel[b as usize])
}

#[inline]
fn write_back(vel: &mut [Velocity], a: u32, b: u32, ua: Velocity, ub: Velocity) {
    // Index 0 is the static dummy: never written.
    if a != 0 {
        vel[a as usize] = ua;
    }
    if b != 0 {
        vel[b as usize] = ub;
    }
}

/// Relative velocity along a direction `d` with angular Jacobians `ja`, `jb`.
#[inline]
fn relative_velocity(ua: &Velocity, ub: &Velocity, d: Vec3, ja: Vec3, jb: Vec3) -> f32 {
    d.dot(ub.v - ua.v) + ub.w.dot(jb) - ua.w.dot(ja)
}

/// Applies impulse `lambda` along `d`; `ia`, `ib` are `I⁻¹ (r × d)` of each body.
#[inline]
#[allow(clippy::too_many_arguments)]
fn apply(ua: &mut Velocity, ub: &mut Velocity, ma: f32, mb: f32, d: Vec3, ia: Vec3, ib: Vec3, lambda: f32) {
    ua.v -= (ma * lambda) * d;
    ua.w -= lambda * ia;
    ub.v += (mb * lambda) * d;
    ub.w += lambda * ib;
}

pub fn warm_start(vel: &mut [Velocity], constraints: &[ContactConstraint]) {
    for c in constraints {
        let (mut ua, mut ub) = pair(vel, c.a, c.b);
        for p in &c.points[..c.count] {
            apply(&mut ua, &mut ub, c.ma, c.mb, c.normal, p.ia, p.ib, p.normal_impulse);
        }
        let f = &c.friction;
        for k in 0..2 {
            apply(
                &mut ua,
                &mut ub,
                c.ma,
                c.mb,
                c.tangents[k],
                f.ita[k],
                f.itb[k],
                f.tangent_impulse[k],
            );
        }
        ua.w -= f.twist_impulse * f.ina;
        ub.w += f.twist_impulse * f.inb;
        write_back(vel, c.a, c.b, ua, ub);
    }
}

/// One Gauss–Seidel sweep over real velocities: non-penetration (rigid; a speculative point
/// may close its gap within the sub-step and no more), then patch friction. `forward`
/// alternates the order of points between sweeps so no point is always solved first: a fixed
/// order biases the impulse distribution and tilts tall stacks.
pub fn solve(vel: &mut [Velocity], constraints: &mut [ContactConstraint], inv_h: f32, forward: bool) {
    for c in constraints.iter_mut() {
        let (mut ua, mut ub) = pair(vel, c.a, c.b);
        let n = c.normal;
        let count = c.count;
        // Normal impulses of all points at once: projected Gauss–Seidel on the cached K.
        let mut rhs = [0.0f32; MAX_MANIFOLD_POINTS];
        for (r, p) in rhs.iter_mut().zip(&c.points[..count]) {
            *r = relative_velocity(&ua, &ub, n, p.rna, p.rnb) + p.separation.max(0.0) * inv_h;
        }
        let mut delta = [0.0f32; MAX_MANIFOLD_POINTS];
        // Touching without load and not approaching (side faces of neighbours): nothing to do.
        let idle = c.points[..count]
            .iter()
            .zip(&rhs)
            .all(|(p, &r)| p.normal_impulse == 0.0 && r >= 0.0);
        // The exact solution with every point pushing: one small matrix product.
        let mut exact = count > 1 && !idle;
        if exact {
            for i in 0..count {
                let mut d = 0.0;
                for (kij, r) in c.k_inv[i][..count].iter().zip(&rhs[..count]) {
                    d -= kij * r;
                }
                delta[i] = d;
                exact &= c.points[i].normal_impulse + d >= 0.0;
            }
        }
        if !exact && !idle {
            // Some point would pull: projected Gauss–Seidel on the cached K instead.
            delta = [0.0; MAX_MANIFOLD_POINTS];
            let iterations = if count == 1 { 1 } else { BLOCK_ITERATIONS };
            for it in 0..iterations {
                for k in 0..count {
                    let i = if forward ^ (it % 2 == 1) { k } else { count - 1 - k };
                    let p = &c.points[i];
                    let mut r = rhs[i];
                    for (kij, dj) in c.k[i][..count].iter().zip(&delta[..count]) {
                        r += kij * dj;
                    }
                    let new_impulse = (p.normal_impulse + delta[i] - p.normal_mass * r).max(0.0);
                    delta[i] = new_impulse - p.normal_impulse;
                }
            }
        }
        let (mut lin, mut ang_a, mut ang_b) = (0.0, Vec3::ZERO, Vec3::ZERO);
        for (p, d) in c.points[..count].iter_mut().zip(delta) {
            p.normal_impulse += d;
            p.max_normal_impulse = p.max_normal_impulse.max(d);
            lin += d;
            ang_a += d * p.ia;
            ang_b += d * p.ib;
        }
        ua.v -= (c.ma * lin) * n;
        ua.w -= ang_a;
        ub.v += (c.mb * lin) * n;
        ub.w += ang_b;
        let total_normal: f32 = c.points[..count].iter().map(|p| p.normal_impulse).sum();
        let f = &mut c.friction;
        let old = f.tangent_impulse;
        let mut new = [0.0; 2];
        for k in 0..2 {
            let vt = relative_velocity(&ua, &ub, c.tangents[k], f.rta[k], f.rtb[k]);
            new[k] = old[k] - f.tangent_mass[k] * vt;
        }
        let old_twist = f.twist_impulse;
        let mut twist = old_twist - f.twist_mass * (ub.w - ua.w).dot(n);
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
        for k in 0..2 {
            apply(
                &mut ua,
                &mut ub,
                c.ma,
                c.mb,
                c.tangents[k],
                f.ita[k],
                f.itb[k],
                new[k] - old[k],
            );
        }
        f.tangent_impulse = new;
        ua.w -= (twist - old_twist) * f.ina;
        ub.w += (twist - old_twist) * f.inb;
        f.twist_impulse = twist;
        write_back(vel, c.a, c.b, ua, ub);
    }
}

/// Removes overlap with pseudo-velocities (split impulse): they move bodies apart in this
/// sub-step's position update and are then dropped, so push-out never adds kinetic energy
/// and never launches the top of a stack. `rate` (1/s) is the fraction of the overlap beyond
/// `slop` removed per second, capped at `max_push` (m/s).
pub fn push_out(pseudo: &mut [Velocity], constraints: &[ContactConstraint], rate: f32, slop: f32, max_push: f32) {
    for c in constraints {
        let (mut ua, mut ub) = pair(pseudo, c.a, c.b);
        let n = c.normal;
        let mut changed = false;
        for p in &c.points[..c.count] {
            let s = p.separation + slop;
            if s >= 0.0 {
                continue;
            }
            let target = (-rate * s).min(max_push);
            let vn = relative_velocity(&ua, &ub, n, p.rna, p.rnb);
            let impulse = (p.normal_mass * (target - vn)).max(0.0);
            apply(&mut ua, &mut ub, c.ma, c.mb, n, p.ia, p.ib, impulse);
            changed = true;
        }
        if changed {
            write_back(pseudo, c.a, c.b, ua, ub);
        }
    }
}

/// Bounces: drives the normal velocity to `-e · (approach velocity)` for points that
/// approached faster than the threshold and really pushed.
pub fn apply_restitution(vel: &mut [Velocity], constraints: &mut [ContactConstraint], threshold: f32) {
    for c in constraints.iter_mut() {
        if c.restitution == 0.0 {
            continue;
        }
        let (mut ua, mut ub) = pair(vel, c.a, c.b);
        for p in c.points[..c.count].iter_mut() {
            if p.relative_velocity > -threshold || p.max_normal_impulse == 0.0 {
                continue;
            }
            let vn = relative_velocity(&ua, &ub, c.normal, p.rna, p.rnb);
            let new_impulse = (p.normal_impulse - p.normal_mass * (vn + c.restitution * p.relative_velocity)).max(0.0);
            let applied = new_impulse - p.normal_impulse;
            p.normal_impulse = new_impulse;
            p.max_normal_impulse = p.max_normal_impulse.max(applied);
            apply(&mut ua, &mut ub, c.ma, c.mb, c.normal, p.ia, p.ib, applied);
        }
        write_back(vel, c.a, c.b, ua, ub);
    }
}

/// Keeps each point's impulses on its contact for warm starting the next step.
pub fn store_impulses(world: &mut World) {
    for c in world.solver.constraints.iter().filter(|c| !is_generated(c)) {
        let contact = world.contacts.at_mut(c.contact);
        for (i, p) in c.points[..c.count].iter().enumerate() {
            let imp = &mut contact.impulses[i];
            imp.normal = p.normal_impulse;
            imp.max_normal = p.max_normal_impulse;
        }
        let f = &c.friction;
        contact.friction.tangent = c.tangents[0] * f.tangent_impulse[0] + c.tangents[1] * f.tangent_impulse[1];
        contact.friction.twist = f.twist_impulse;
        contact.friction.sliding = f.sliding;
    }
}

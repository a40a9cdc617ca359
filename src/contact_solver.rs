//! Contact constraints, per step: `prepare` builds one constraint per touching manifold (and
//! one per generated contact) with its anchors, materials and warm-start impulses; the
//! sub-stepped passes run on them four at a time in `contact_wide.rs`; `store_impulses` keeps
//! the impulses on the contacts for the next step.

use crate::collision::MAX_MANIFOLD_POINTS;
use crate::math::{orthonormal_basis, Vec3};
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
    pub normal_impulse: f32,
    /// Normal relative velocity before the solve (for restitution).
    pub relative_velocity: f32,
}

/// Coulomb friction of the contact patch: two tangent directions at the centroid of the
/// manifold and a twist about the normal, clamped by μ times the total normal impulse.
/// Solving the patch as one (rather than per point) keeps friction from leaking into
/// spurious twist, so a sliding box feels exactly μ·N.
#[derive(Clone, Copy, Debug, Default)]
pub struct PatchFriction {
    /// Arms of the manifold's centroid at the start of the step.
    pub ra0: Vec3,
    pub rb0: Vec3,
    /// Mean distance of the points from the centroid: the lever of torsional friction.
    pub twist_radius: f32,
    pub tangent_impulse: [f32; 2],
    pub twist_impulse: f32,
    /// The patch slides (dynamic friction) this step; decided from the tangential speed at
    /// the start of the step.
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
    /// Rounding radii of the two shapes (see `Geometry::rounding_radius`).
    pub radius_a: f32,
    pub radius_b: f32,
    pub count: usize,
    pub points: [ConstraintPoint; MAX_MANIFOLD_POINTS],
    pub friction: PatchFriction,
    /// A and B were exchanged so that a static body is always B (see `static_to_b`).
    pub swapped: bool,
    /// Solved with the full rigid response and no leak of accumulated impulse: generated
    /// contacts (rods, cables) must hold their length under load, and they do not form the
    /// deep stacks the soft contacts damp.
    pub rigid: bool,
}

impl ContactConstraint {
    /// Puts a static body (solver index 0) on side B, so batches whose B sides are all static
    /// skip B's half of the work. The normal and the friction impulse flip with the sides; the
    /// normal and twist impulses keep their values.
    fn static_to_b(&mut self) {
        if self.a != 0 || self.b == 0 {
            return;
        }
        let friction_world =
            self.tangents[0] * self.friction.tangent_impulse[0] + self.tangents[1] * self.friction.tangent_impulse[1];
        std::mem::swap(&mut self.a, &mut self.b);
        std::mem::swap(&mut self.ma, &mut self.mb);
        std::mem::swap(&mut self.radius_a, &mut self.radius_b);
        self.normal = -self.normal;
        let (t1, t2) = orthonormal_basis(self.normal);
        self.tangents = [t1, t2];
        for p in &mut self.points[..self.count] {
            std::mem::swap(&mut p.ra0, &mut p.rb0);
        }
        let f = &mut self.friction;
        std::mem::swap(&mut f.ra0, &mut f.rb0);
        f.tangent_impulse = [-friction_world.dot(t1), -friction_world.dot(t2)];
        self.swapped = true;
    }

    /// The friction impulse on the original body B, as a world vector.
    fn friction_world(&self) -> Vec3 {
        let t =
            self.tangents[0] * self.friction.tangent_impulse[0] + self.tangents[1] * self.friction.tangent_impulse[1];
        if self.swapped {
            -t
        } else {
            t
        }
    }
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
            radius_a: c.radius_a,
            radius_b: c.radius_b,
            count: c.manifold.count,
            points: [ConstraintPoint::default(); MAX_MANIFOLD_POINTS],
            friction: PatchFriction::default(),
            swapped: false,
            rigid: false,
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
            };
        }
        centroid /= c.manifold.count as f32;
        let twist_radius = if c.manifold.count > 1 {
            c.manifold
                .points()
                .iter()
                .map(|p| (p.point - centroid).length())
                .sum::<f32>()
                / c.manifold.count as f32
        } else {
            0.0
        };
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
        };
        cc.static_to_b();
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
            radius_a: 0.0,
            radius_b: 0.0,
            count: 1,
            points: [ConstraintPoint::default(); MAX_MANIFOLD_POINTS],
            friction: PatchFriction::default(),
            swapped: false,
            rigid: true,
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
        cc.static_to_b();
        constraints.push(cc);
    }
}

/// True for constraints built from generated contacts (they store no impulses).
#[inline]
fn is_generated(c: &ContactConstraint) -> bool {
    c.contact == crate::body::NONE
}

/// Keeps each point's impulses on its contact for warm starting the next step.
pub fn store_impulses(world: &mut World) {
    for c in world.solver.constraints.iter().filter(|c| !is_generated(c)) {
        let contact = world.contacts.at_mut(c.contact);
        for (i, p) in c.points[..c.count].iter().enumerate() {
            let imp = &mut contact.impulses[i];
            imp.normal = p.normal_impulse;
        }
        contact.friction.tangent = c.friction_world();
        contact.friction.twist = c.friction.twist_impulse;
        contact.friction.sliding = c.friction.sliding;
    }
}

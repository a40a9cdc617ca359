//! The particle stage (after the rigid solve): integration, contacts with rigid shapes,
//! rods and cables, sleep and lifetimes.
//!
//! Sub-stepped like the rigid solver (`substeps` of `h = dt / substeps`). Per sub-step:
//!
//! 1. **Integrate velocities**: semi-implicit Euler with world gravity × scale, the
//!    particle's own acceleration, accumulated forces and damping `v /= 1 + h·d`.
//! 2. **Refresh** every constraint: gap, direction, lever arms on bodies, effective mass.
//! 3. **Warm start** links and contacts with dynamic bodies with the impulses of the same
//!    sub-step of the last step (a heavy body on light particles needs its support in the
//!    first sub-step, when the rigid solve's gravity arrives, and little after).
//! 4. **Velocity sweeps** (sequential impulses): contacts are one-sided with speculative
//!    gaps (a gap may close within the sub-step and no more, so fast particles do not pass
//!    through thin shapes) and Coulomb friction; rods are two-sided; cables pull only.
//! 5. **Integrate positions**.
//! 6. **Position projection** (non-linear Gauss–Seidel): rods back to their length,
//!    cables and contacts out of violation beyond `linear_slop`. Moves positions only, so
//!    correcting drift never adds energy.
//!
//! After the sub-steps: restitution (contacts and cables that approached faster than the
//! threshold), a last projection of the links, write-back of the coupled bodies.
//!
//! **Two-way coupling.** A contact or link with an awake dynamic body acts on the body's
//! linear and angular velocity with the body's effective mass at the contact arm
//! (`1/m + (r×n)·I⁻¹(r×n)`), the equal and opposite of what the particle gets; the position
//! projection moves and turns the body the same way. A body's own motion this step already
//! happened in the rigid solve, so in this stage its pose moves only by projection.
//! Sleeping dynamic bodies, static and kinematic bodies act as fixed (kinematic ones with
//! their velocity); a sleeping body is woken when the impulses it received would have
//! changed its speed by more than the sleep threshold.
//!
//! **Fast path.** A particle whose only constraint is one contact with something fixed
//! (the common case: a particle on the ground) is solved exactly in one pass, without the
//! generic machinery.
//!
//! **Sleep** as for bodies: recency-weighted motion; particles joined by rods and cables
//! sleep and wake as a group; a sleeping particle is woken by a moving body's shape box.

use super::block::RodBlock;
use super::constraint::{body_side, Constraint, Coupled, Kind, Side, Simple, Sys};
use super::{ContactOther, ExpiredParticle, Particles, ALLOW_SLEEP, AWAKE, COLLIDE};
use crate::collision::aabb::Aabb;
use crate::collision::broad_phase::world_plane;
use crate::collision::narrow_phase::collide;
use crate::collision::shape::{Geometry, Shape};
use crate::dynamics::body::NONE;
use crate::generators::{End, GeneratorDef, WARM_SLOTS};
use crate::hash::IntMap;
use crate::math::{integrate_rotation, Quat, Transform, Vec3};
use crate::pool::Handle;
use crate::world::World;

const LINK_KEY: u64 = 1 << 63;

/// A particle's contact with a plane, before it is known whether it is its only one.
#[derive(Clone, Copy, Debug)]
struct PlaneHit {
    n: Vec3,
    gap: f32,
    friction: f32,
    restitution: f32,
}

#[derive(Default)]
pub struct Scratch {
    constraints: Vec<Constraint>,
    simple: Vec<Simple>,
    found: Vec<Constraint>,
    hits: Vec<PlaneHit>,
    /// The world's planes in world space for this step: (normal, offset, shape slot).
    planes: Vec<(Vec3, f32, u32)>,
    coupled: Vec<Coupled>,
    coupled_index: IntMap<u32, u32>,
    /// Inverse mass of each particle for this stage (0 while asleep).
    w: Vec<f32>,
    /// Constraints of each particle from links and host contacts.
    count: Vec<u16>,
    parent: Vec<u32>,
    min_sleep: Vec<f32>,
    links: Vec<Handle>,
    warm_prev: IntMap<u64, [f32; WARM_SLOTS]>,
    warm_next: IntMap<u64, [f32; WARM_SLOTS]>,
    moving: Vec<Aabb>,
    wake: Vec<u32>,
    block: RodBlock,
    /// Dynamic bodies particles acted on in the last step.
    carried: Vec<Handle>,
    /// Bodies whose gravity this step's particle stage integrates: (slot, gravity).
    pub(crate) deferred: Vec<(u32, Vec3)>,
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[x as usize];
        parent[x as usize] = parent[p as usize];
        x = p;
    }
    x
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb) as usize] = ra.min(rb);
    }
}

/// Friction and restitution of a particle against a shape.
#[inline]
fn mix(p: &Particles, i: usize, shape: &Shape) -> (f32, f32) {
    (
        (p.friction[i] * shape.def.static_friction).sqrt(),
        p.restitution[i].max(shape.def.restitution),
    )
}

impl World {
    /// The particle stage of the step (see the module documentation).
    pub(crate) fn step_particles(&mut self, dt: f32) {
        self.particles.expired.clear();
        let has_links = self
            .generators
            .iter()
            .any(|(_, g)| g.def.is_link() && !g.broken && link_has_particle(&g.def));
        if self.particles.is_empty() && !has_links && self.particles.scratch.deferred.is_empty() {
            self.particles.user_contacts.clear();
            self.particles.scratch.carried.clear();
            return;
        }
        let mut s = std::mem::take(&mut self.particles.scratch);
        self.wake_particles_near_moving_bodies(&mut s);
        self.prepare_particle_links(&mut s, has_links);
        let n = self.particles.len();
        s.w.clear();
        s.w.extend((0..n).map(|i| {
            if self.particles.is_awake(i) {
                self.particles.inv_mass[i]
            } else {
                0.0
            }
        }));
        s.constraints.clear();
        s.simple.clear();
        s.coupled.clear();
        s.coupled_index.clear();
        for &(slot, g) in &s.deferred {
            let b = self.bodies.at(slot);
            let mut c = Coupled::new(b, slot);
            c.gravity = g;
            s.coupled_index.insert(slot, s.coupled.len() as u32);
            s.coupled.push(c);
        }
        std::mem::swap(&mut s.warm_prev, &mut s.warm_next);
        s.warm_next.clear();
        self.build_link_constraints(&mut s);
        self.build_user_contacts(&mut s);
        self.find_shape_contacts(&mut s, dt);
        self.solve_particles(&mut s, dt);
        self.finish_particles(&mut s, dt);
        self.particles.scratch = s;
    }

    /// Stage 2, after the force generators: a dynamic body that rested on particles in the
    /// last step and touches no rigid shape has its gravity taken out of the rigid solve and
    /// integrated in the particle stage, in the same sub-steps as the particles that carry
    /// it. Otherwise the rigid solve would move it down by `g dt² (n+1)/2n` before the
    /// particles could push back, the particle stage would lift it again, and a heavy body
    /// would creep over its supports.
    pub(crate) fn defer_coupled_gravity(&mut self) {
        let s = &mut self.particles.scratch;
        s.deferred.clear();
        for &h in &s.carried {
            let Some(b) = self.bodies.get_mut(h) else { continue };
            if !b.is_dynamic() || !b.awake {
                continue;
            }
            let contacts = &self.contacts;
            if b.contacts.iter().any(|&c| contacts.at(c).touching) {
                continue;
            }
            let g = self.settings.gravity * b.gravity_scale;
            if g != Vec3::ZERO {
                b.force -= g * b.mass;
                s.deferred.push((h.index, g));
            }
        }
    }

    /// Wakes sleeping particles inside the shape boxes of moving bodies.
    fn wake_particles_near_moving_bodies(&mut self, s: &mut Scratch) {
        s.moving.clear();
        let t = self.settings.sleep_threshold;
        for &bi in &self.awake_bodies {
            let b = self.bodies.at(bi);
            if b.v.length_squared() + b.w.length_squared() <= t * t {
                continue;
            }
            for sh in &b.shapes {
                let shape = self.shapes.at(sh.index);
                if shape.proxy != NONE {
                    s.moving.push(shape.fat_aabb);
                }
            }
        }
        if s.moving.is_empty() {
            return;
        }
        let p = &mut self.particles;
        for i in 0..p.len() {
            if p.flags[i] & (AWAKE | COLLIDE) != COLLIDE {
                continue;
            }
            let bb = Aabb::from_center_extents(p.pos[i], Vec3::splat(p.radius[i]));
            if s.moving.iter().any(|m| m.overlaps(&bb)) {
                p.wake(i, t);
            }
        }
    }

    /// Collects particle links; joins linked particles into groups that wake together;
    /// a link whose body end moves wakes its particles.
    fn prepare_particle_links(&mut self, s: &mut Scratch, has_links: bool) {
        s.links.clear();
        if !has_links {
            return;
        }
        s.links.extend(
            self.generators
                .iter()
                .filter(|(_, g)| g.def.is_link() && !g.broken && link_has_particle(&g.def))
                .map(|(h, _)| h),
        );
        let n = self.particles.len();
        s.parent.clear();
        s.parent.extend(0..n as u32);
        let t = self.settings.sleep_threshold;
        for k in 0..s.links.len() {
            let g = self.generators.get(s.links[k]).expect("live generator");
            let (a, b) = link_ends(&g.def);
            let (ia, ib) = (self.end_particle(&a), self.end_particle(&b));
            if let (Some(x), Some(y)) = (ia, ib) {
                union(&mut s.parent, x as u32, y as u32);
            }
            for (e, other) in [(&a, ib), (&b, ia)] {
                if let (End::Body { body, .. }, Some(i)) = (e, other) {
                    if let Some(bd) = self.bodies.get(*body) {
                        if bd.awake && bd.v.length_squared() + bd.w.length_squared() > t * t {
                            self.particles.wake(i, t);
                        }
                    }
                }
            }
        }
        // A group with an awake member wakes whole.
        s.min_sleep.clear();
        s.min_sleep.resize(n, 0.0);
        for i in 0..n {
            if self.particles.is_awake(i) {
                let r = find(&mut s.parent, i as u32) as usize;
                s.min_sleep[r] = 1.0;
            }
        }
        for i in 0..n {
            let r = find(&mut s.parent, i as u32) as usize;
            if s.min_sleep[r] > 0.0 && !self.particles.is_awake(i) {
                self.particles.wake(i, t);
            }
        }
    }

    fn end_particle(&self, e: &End) -> Option<usize> {
        match *e {
            End::Particle(h) => self.particles.index(h),
            _ => None,
        }
    }

    /// The side for a link end; None when it is gone.
    fn link_side(&self, e: &End, coupled: &mut Vec<Coupled>, index: &mut IntMap<u32, u32>) -> Option<Side> {
        match *e {
            End::World(p) => Some(Side::Fixed {
                p,
                v: Vec3::ZERO,
                sleeper: NONE,
            }),
            End::Body { body, local } => {
                let b = self.bodies.get(body)?;
                Some(body_side(b, body.index, b.xf.apply(local), coupled, index))
            }
            End::Particle(h) => self.particles.index(h).map(|i| Side::Particle(i as u32)),
        }
    }

    fn build_link_constraints(&mut self, s: &mut Scratch) {
        s.count.clear();
        s.count.resize(self.particles.len(), 0);
        for k in 0..s.links.len() {
            let h = s.links[k];
            let g = self.generators.get(h).expect("live generator");
            let (a, b) = link_ends(&g.def);
            let (Some(sa), Some(sb)) = (
                self.link_side(&a, &mut s.coupled, &mut s.coupled_index),
                self.link_side(&b, &mut s.coupled, &mut s.coupled_index),
            ) else {
                continue;
            };
            let awake = |side: &Side| matches!(*side, Side::Particle(i) if self.particles.is_awake(i as usize));
            if !awake(&sa) && !awake(&sb) {
                continue; // a sleeping group
            }
            let (kind, length, restitution) = match g.def {
                GeneratorDef::Rod { length, .. } => (Kind::Rod, length, 0.0),
                GeneratorDef::Cable {
                    max_length,
                    restitution,
                    ..
                } => (Kind::Cable, max_length, restitution),
                _ => unreachable!("links only"),
            };
            let mut c = Constraint::new(sa, sb, kind, Vec3::Y, length);
            c.restitution = restitution;
            c.warm = g.warm;
            c.key = LINK_KEY | h.index as u64;
            let sys = Sys {
                pos: &mut self.particles.pos,
                vel: &mut self.particles.vel,
                w: &s.w,
                coupled: &mut s.coupled,
                turn: true,
            };
            c.refresh(&sys);
            c.vn0 = c.n.dot(sys.velocity(&c.a, c.ra) - sys.velocity(&c.b, c.rb));
            for side in [&c.a, &c.b] {
                if let Side::Particle(i) = *side {
                    s.count[i as usize] = s.count[i as usize].saturating_add(1);
                }
            }
            s.constraints.push(c);
        }
    }

    fn build_user_contacts(&mut self, s: &mut Scratch) {
        let contacts = std::mem::take(&mut self.particles.user_contacts);
        for uc in &contacts {
            let Some(i) = self.particles.index(uc.particle) else {
                continue;
            };
            let pa = self.particles.pos[i];
            let b = match uc.other {
                ContactOther::World => Side::Fixed {
                    p: uc.point,
                    v: Vec3::ZERO,
                    sleeper: NONE,
                },
                ContactOther::Body(slot) => match self.bodies.handle_at(slot) {
                    Some(h) => {
                        let body = self.bodies.get(h).expect("live");
                        body_side(body, slot, uc.point, &mut s.coupled, &mut s.coupled_index)
                    }
                    None => continue,
                },
                ContactOther::Particle(h) => match self.particles.index(h) {
                    Some(j) => Side::Particle(j as u32),
                    None => continue,
                },
            };
            let mut c = Constraint::new(Side::Particle(i as u32), b, Kind::Contact, uc.normal, -uc.penetration);
            c.restitution = uc.restitution;
            c.friction = uc.friction;
            let sys = Sys {
                pos: &mut self.particles.pos,
                vel: &mut self.particles.vel,
                w: &s.w,
                coupled: &mut s.coupled,
                turn: true,
            };
            c.pa0 = pa;
            c.pb0 = sys.point(&c.b, sys.arm(&c.b));
            c.refresh(&sys);
            c.vn0 = c.n.dot(sys.velocity(&c.a, c.ra) - sys.velocity(&c.b, c.rb));
            for side in [&c.a, &c.b] {
                if let Side::Particle(k) = *side {
                    s.count[k as usize] = s.count[k as usize].saturating_add(1);
                }
            }
            s.constraints.push(c);
        }
        let mut contacts = contacts;
        contacts.clear();
        self.particles.user_contacts = contacts;
    }

    /// Contacts of every awake colliding particle with planes and (through the broad-phase
    /// tree) other shapes, within the distance it may travel this step.
    fn find_shape_contacts(&mut self, s: &mut Scratch, dt: f32) {
        let World {
            particles: p,
            bodies,
            shapes,
            broad,
            settings,
            geometry,
            ..
        } = self;
        let gravity = settings.gravity;
        // Planes in world space, once per step.
        s.planes.clear();
        s.planes.extend(broad.planes.iter().map(|&ps| {
            let shape = shapes.at(ps);
            let (n, offset) = world_plane(&shape.geometry, &bodies.at(shape.body).xf);
            (n, offset, ps)
        }));
        for i in 0..p.len() {
            if p.flags[i] & (AWAKE | COLLIDE) != (AWAKE | COLLIDE) {
                continue;
            }
            let (x, v, r) = (p.pos[i], p.vel[i], p.radius[i]);
            let accel = gravity * p.gravity_scale[i] + p.accel[i] + p.force[i] * p.inv_mass[i];
            let reach = crate::step::SPECULATIVE_DISTANCE + (v.length() + accel.length() * dt) * dt;
            s.found.clear();
            s.hits.clear();
            for &(n, offset, ps) in &s.planes {
                let gap = n.dot(x) - offset - r;
                if gap < reach {
                    let (friction, restitution) = mix(p, i, shapes.at(ps));
                    s.hits.push(PlaneHit {
                        n,
                        gap,
                        friction,
                        restitution,
                    });
                }
            }
            if broad.tree.proxy_count() > 0 {
                let bb = Aabb::from_center_extents(x, Vec3::splat(r + reach));
                let sphere = Geometry::Sphere {
                    center: Vec3::ZERO,
                    radius: r,
                };
                let xf = Transform::new(x, Quat::IDENTITY);
                let found = &mut s.found;
                let coupled = &mut s.coupled;
                let index = &mut s.coupled_index;
                let warm_prev = &s.warm_prev;
                let handle = p.handle[i];
                let pr: &Particles = p;
                broad.tree.query(&bb, |_, si| {
                    let shape = shapes.at(si);
                    if shape.def.is_sensor {
                        // Sensors never push (events.rs).
                        return true;
                    }
                    let body = bodies.at(shape.body);
                    let m = collide(geometry, &sphere, &xf, &shape.geometry, &body.xf, reach);
                    for mp in m.points() {
                        // `m.normal` points from the particle into the shape.
                        let surface = x + m.normal * (r + mp.separation);
                        let side = body_side(body, shape.body, surface, coupled, index);
                        let (friction, restitution) = mix(pr, i, shape);
                        let mut c =
                            Constraint::new(Side::Particle(i as u32), side, Kind::Contact, -m.normal, mp.separation);
                        c.pa0 = x;
                        c.pb0 = surface;
                        c.friction = friction;
                        c.restitution = restitution;
                        let vb = match side {
                            Side::Body { .. } => body.point_velocity(surface),
                            Side::Fixed { v, .. } => v,
                            Side::Particle(_) => Vec3::ZERO,
                        };
                        c.vn0 = c.n.dot(v - vb);
                        if matches!(side, Side::Body { .. }) {
                            c.key = ((handle.index as u64) << 32) | si as u64;
                            if let Some(w) = warm_prev.get(&c.key) {
                                c.warm = *w;
                            }
                        }
                        found.push(c);
                    }
                    true
                });
            }
            // The fast path: a single contact with something fixed and nothing else.
            if s.count[i] == 0 && s.hits.len() + s.found.len() == 1 {
                let simple = if let Some(h) = s.hits.first() {
                    Some((h.n, h.gap, Vec3::ZERO, h.restitution, h.friction, h.n.dot(v), NONE))
                } else if let Side::Fixed { v: vf, sleeper, .. } = s.found[0].b {
                    let c = &s.found[0];
                    Some((c.n, c.gap0, vf, c.restitution, c.friction, c.vn0, sleeper))
                } else {
                    None
                };
                if let Some((n, gap, vf, restitution, friction, vn0, sleeper)) = simple {
                    s.simple.push(Simple {
                        i: i as u32,
                        n,
                        offset: n.dot(x) - gap,
                        v: vf,
                        restitution,
                        friction,
                        vn0,
                        total: 0.0,
                        sleeper,
                    });
                    continue;
                }
            }
            for h in &s.hits {
                let foot = x - h.n * (h.gap + r);
                let fixed = Side::Fixed {
                    p: foot,
                    v: Vec3::ZERO,
                    sleeper: NONE,
                };
                let mut c = Constraint::new(Side::Particle(i as u32), fixed, Kind::Contact, h.n, h.gap);
                c.pa0 = x;
                c.pb0 = foot;
                c.friction = h.friction;
                c.restitution = h.restitution;
                c.vn0 = h.n.dot(v);
                s.constraints.push(c);
            }
            s.constraints.extend_from_slice(&s.found);
        }
    }

    fn solve_particles(&mut self, s: &mut Scratch, dt: f32) {
        let substeps = self.settings.substeps.max(1);
        let h = dt / substeps as f32;
        let inv_h = 1.0 / h;
        let gravity = self.settings.gravity;
        let max_speed = self.settings.max_linear_speed;
        let slop = self.settings.linear_slop;
        let iterations = self.particles.settings.velocity_iterations;
        let position_iterations = self.particles.settings.position_iterations;
        let p = &mut self.particles;
        let n = p.len();
        let Scratch {
            constraints,
            simple,
            coupled,
            w,
            block,
            ..
        } = s;
        // Rods are solved exactly together (block.rs); the rest by Gauss–Seidel.
        let blocked = block.build(constraints, n);
        for sub in 0..substeps as usize {
            let slot = sub.min(WARM_SLOTS - 1);
            // 1. Velocities.
            for (i, &wi) in w.iter().enumerate() {
                if wi > 0.0 {
                    let a = gravity * p.gravity_scale[i] + p.accel[i] + p.force[i] * wi;
                    let mut v = (p.vel[i] + h * a) * (1.0 / (1.0 + h * p.damping[i]));
                    if !v.is_finite() {
                        // Finite inputs whose products overflowed f32: again in f64.
                        let a = gravity.as_dvec3() * p.gravity_scale[i] as f64
                            + p.accel[i].as_dvec3()
                            + p.force[i].as_dvec3() * wi as f64;
                        let v64 = (p.vel[i].as_dvec3() + h as f64 * a) / (1.0 + h as f64 * p.damping[i] as f64);
                        v = crate::math::clamp_length_f64(v64, max_speed);
                    }
                    let s2 = v.length_squared();
                    if s2 > max_speed * max_speed {
                        v *= max_speed / s2.sqrt();
                    }
                    p.vel[i] = v;
                }
            }
            for b in coupled.iter_mut() {
                b.v += h * b.gravity;
            }
            let mut sys = Sys {
                pos: &mut p.pos,
                vel: &mut p.vel,
                w,
                coupled,
                turn: true,
            };
            // 2–3. Refresh and warm start.
            for c in constraints.iter_mut() {
                c.refresh(&sys);
                c.impulse = c.warm[slot];
                c.tangent = Vec3::ZERO;
                if c.impulse != 0.0 {
                    c.apply(&mut sys, c.n * c.impulse);
                }
            }
            // 4. Velocity sweeps: the lone contacts in one pass; then block Gauss–Seidel,
            //    sweeps over contacts and cables (alternating direction) and the exact rod
            //    solve.
            for sc in simple.iter_mut() {
                let i = sc.i as usize;
                if sys.w[i] > 0.0 {
                    sc.solve_velocity(sys.pos[i], &mut sys.vel[i], inv_h);
                }
            }
            let sweeps = if blocked && block.len() == constraints.len() {
                1 // rods only: one exact solve is the answer
            } else {
                iterations
            };
            for k in 0..sweeps {
                let free = |c: &&mut Constraint| !c.blocked;
                if k % 2 == 0 {
                    constraints
                        .iter_mut()
                        .filter(free)
                        .for_each(|c| c.solve_velocity(&mut sys, inv_h));
                } else {
                    constraints
                        .iter_mut()
                        .rev()
                        .filter(free)
                        .for_each(|c| c.solve_velocity(&mut sys, inv_h));
                }
                block.solve_velocity(constraints, &mut sys, k == 0);
            }
            for c in constraints.iter_mut() {
                c.warm[slot] = c.impulse;
                c.total += c.impulse.abs();
            }
            // 5. Positions. A coupled body already moved with `v0, w0` in the rigid solve; it
            //    moves here by what this stage changed.
            for i in 0..n {
                if p.flags[i] & AWAKE != 0 {
                    p.pos[i] += h * p.vel[i];
                }
            }
            for b in coupled.iter_mut() {
                b.center += h * (b.v - b.v0);
                b.q = integrate_rotation(b.q, b.w - b.w0, h);
            }
            let mut sys = Sys {
                pos: &mut p.pos,
                vel: &mut p.vel,
                w,
                coupled,
                turn: false,
            };
            // 6. Projection.
            for sc in simple.iter() {
                let i = sc.i as usize;
                if sys.w[i] > 0.0 {
                    sc.solve_position(&mut sys.pos[i], slop);
                }
            }
            for k in 0..position_iterations {
                let free = |c: &&mut Constraint| !c.blocked;
                if k % 2 == 0 {
                    constraints
                        .iter_mut()
                        .filter(free)
                        .for_each(|c| c.solve_position(&mut sys, slop));
                } else {
                    constraints
                        .iter_mut()
                        .rev()
                        .filter(free)
                        .for_each(|c| c.solve_position(&mut sys, slop));
                }
                block.solve_position(constraints, &mut sys);
            }
        }
        let threshold = self.settings.restitution_threshold;
        let mut sys = Sys {
            pos: &mut p.pos,
            vel: &mut p.vel,
            w,
            coupled,
            turn: true,
        };
        for sc in simple.iter() {
            let i = sc.i as usize;
            if sys.w[i] > 0.0 {
                sc.restitute(&mut sys.vel[i], threshold);
            }
        }
        for c in constraints.iter_mut() {
            c.restitute(&mut sys, threshold);
        }
        // A last projection of the links, so rods leave the step at their length.
        sys.turn = false;
        for _ in 0..2 {
            constraints
                .iter_mut()
                .filter(|c| c.kind == Kind::Cable)
                .for_each(|c| c.solve_position(&mut sys, slop));
            block.solve_position(constraints, &mut sys);
        }
    }

    /// Write-back, wakes, sleep and lifetimes.
    fn finish_particles(&mut self, s: &mut Scratch, dt: f32) {
        // Coupled bodies take their new velocities and poses.
        s.carried.clear();
        s.wake.clear();
        for c in &s.coupled {
            if c.touched {
                s.carried.push(self.bodies.handle_at(c.slot).expect("live body"));
                // Awake particles act on it: it must not sleep under them (it would stop
                // loading them, they would push back and wake it, again and again). It
                // sleeps once they do.
                s.wake.push(c.slot);
            }
            let limits = (self.settings.max_linear_speed, self.settings.max_angular_speed);
            let b = self.bodies.at_mut(c.slot);
            b.set_velocities_capped(c.v, c.w, limits);
            b.set_center_rotation(c.center, c.q.normalize());
            b.update_world_inertia();
        }
        // Warm starts for the next step.
        for c in &s.constraints {
            if c.key == u64::MAX {
                continue;
            }
            if c.key & LINK_KEY != 0 {
                if let Some(h) = self.generators.handle_at((c.key & !LINK_KEY) as u32) {
                    self.generators.get_mut(h).expect("live").warm = c.warm;
                }
            } else {
                s.warm_next.insert(c.key, c.warm);
            }
        }
        // Sleeping bodies that were pushed hard enough wake up.
        let t = self.settings.sleep_threshold;
        for c in &s.constraints {
            for side in [&c.a, &c.b] {
                if let Side::Fixed { sleeper, .. } = *side {
                    if sleeper != NONE && c.total * self.bodies.at(sleeper).inv_mass > t {
                        s.wake.push(sleeper);
                    }
                }
            }
        }
        for sc in &s.simple {
            if sc.sleeper != NONE {
                let i = sc.i as usize;
                let m = if s.w[i] > 0.0 { 1.0 / s.w[i] } else { 0.0 };
                if sc.total * m * self.bodies.at(sc.sleeper).inv_mass > t {
                    s.wake.push(sc.sleeper);
                }
            }
        }
        for k in 0..s.wake.len() {
            self.wake_body(s.wake[k]);
        }
        self.update_particle_sleep(s, dt);
        self.expire_particles(dt);
    }

    fn update_particle_sleep(&mut self, s: &mut Scratch, dt: f32) {
        let settings = self.settings;
        let p = &mut self.particles;
        let n = p.len();
        let eps = settings.sleep_threshold * settings.sleep_threshold;
        // The bodies' motion average (`dynamics::island`): a particle sleeps about
        // `time_to_sleep` after it stops, as a body does.
        let bias = 0.5f32.powf(dt / crate::dynamics::island::MOTION_HALF_LIFE);
        for i in 0..n {
            p.force[i] = Vec3::ZERO;
            if p.flags[i] & AWAKE == 0 {
                continue;
            }
            let current = p.vel[i].length_squared();
            p.motion[i] = (bias * p.motion[i] + (1.0 - bias) * current).min(10.0 * eps);
            if p.flags[i] & ALLOW_SLEEP == 0 || p.motion[i] > eps || current > 4.0 * eps {
                p.sleep_time[i] = 0.0;
            } else {
                p.sleep_time[i] += dt;
            }
        }
        if !settings.enable_sleep {
            return;
        }
        let linked = !s.links.is_empty() && s.parent.len() == n;
        if linked {
            s.min_sleep.clear();
            s.min_sleep.resize(n, f32::MAX);
            for i in 0..n {
                let r = find(&mut s.parent, i as u32) as usize;
                let st = if p.flags[i] & AWAKE != 0 {
                    p.sleep_time[i]
                } else {
                    f32::MAX
                };
                s.min_sleep[r] = s.min_sleep[r].min(st);
            }
        }
        for i in 0..n {
            if p.flags[i] & AWAKE == 0 {
                continue;
            }
            let still = if linked {
                let r = find(&mut s.parent, i as u32) as usize;
                s.min_sleep[r]
            } else {
                p.sleep_time[i]
            };
            if still >= settings.time_to_sleep {
                p.flags[i] &= !AWAKE;
                p.vel[i] = Vec3::ZERO;
                p.sleep_time[i] = 0.0;
            }
        }
    }

    /// Ages every particle; removes and reports those whose lifetime ran out.
    fn expire_particles(&mut self, dt: f32) {
        let p = &mut self.particles;
        let mut i = p.len();
        while i > 0 {
            i -= 1;
            p.lifetime[i] -= dt;
            if p.lifetime[i] <= 0.0 {
                p.expired.push(ExpiredParticle {
                    id: p.handle[i],
                    position: p.pos[i],
                    velocity: p.vel[i],
                    user_data: p.user_data[i],
                });
                p.remove_at(i);
            }
        }
    }
}

fn link_has_particle(def: &GeneratorDef) -> bool {
    let (a, b) = link_ends(def);
    matches!(a, End::Particle(_)) || matches!(b, End::Particle(_))
}

fn link_ends(def: &GeneratorDef) -> (End, End) {
    match *def {
        GeneratorDef::Rod { a, b, .. } | GeneratorDef::Cable { a, b, .. } => (a, b),
        _ => (End::World(Vec3::ZERO), End::World(Vec3::ZERO)),
    }
}

// Snapshots keep what one step hands the next: the warm-start impulses of particle
// constraints and the bodies particles acted on (their gravity is deferred to this stage).
// Everything else is rewritten by each step before it is read.
crate::snap_struct!(Scratch {
    warm_prev,
    warm_next,
    carried,
    deferred;
    skip constraints,
    simple,
    found,
    hits,
    planes,
    coupled,
    coupled_index,
    w,
    count,
    parent,
    min_sleep,
    links,
    moving,
    wake,
    block,
});

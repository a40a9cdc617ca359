//! Contact generators between bodies: rods and cables whose ends are bodies or world
//! anchors report their violation as single-point contacts (`World::generated_contacts`),
//! which the rigid solver resolves together with collision contacts (Millington's
//! ParticleRod/ParticleCable approach, applied to rigid bodies).
//!
//! A contact pushes body B along its normal (normal from A to B), so:
//! * a rod longer than its length pulls: normal from B towards A, penetration `len − L`;
//!   a rod shorter than its length pushes: normal from A towards B, penetration `L − len`.
//!   The side is chosen from the length predicted over the step, so a rod at its length
//!   holds against the motion about to happen.
//! * a cable only pulls, from `max_length − margin` on (a speculative contact, so a fast
//!   stretch is caught within the step), with the cable's restitution.
//!
//! The contact point is the midpoint of the two attachment points: every point on the line
//! between them gives the same torques as the attachment points themselves, since the
//! normal lies along that line.
//!
//! Links with a particle end are solved in the particle stage (`particles/solver.rs`).

use super::{End, GeneratorDef};
use crate::collision::contact::GeneratedContact;
use crate::dynamics::body::NONE;
use crate::math::Vec3;
use crate::world::World;

/// Where a link end is, how it moves, and whether it can wake.
struct EndState {
    slot: u32,
    point: Vec3,
    velocity: Vec3,
    /// A dynamic body that is asleep.
    sleeping_dynamic: bool,
    /// Awake and able to move (dynamic or kinematic).
    active: bool,
}

impl World {
    fn link_end(&self, e: &End) -> Option<EndState> {
        match *e {
            End::World(p) => Some(EndState {
                slot: NONE,
                point: p,
                velocity: Vec3::ZERO,
                sleeping_dynamic: false,
                active: false,
            }),
            End::Body { body, local } => {
                let b = self.bodies.get(body)?;
                let point = b.xf.apply(local);
                Some(EndState {
                    slot: body.index,
                    point,
                    velocity: b.point_velocity(point),
                    sleeping_dynamic: b.is_dynamic() && !b.awake,
                    active: b.awake && !b.is_static(),
                })
            }
            End::Particle(_) => None,
        }
    }

    /// Stage 5 of the step: rods and cables between bodies write generated contacts, waking
    /// a sleeping body when the other end moves.
    pub(crate) fn generate_link_contacts(&mut self, dt: f32) {
        if self.generators.is_empty() {
            return;
        }
        let mut scratch = std::mem::take(&mut self.generator_scratch);
        scratch.order.clear();
        scratch.order.extend(
            self.generators
                .iter()
                .filter(|(_, g)| g.def.is_link() && !g.broken)
                .map(|(h, _)| h),
        );
        scratch.wake.clear();
        let slop = self.settings.linear_slop;
        for &h in &scratch.order {
            let g = self.generators.get(h).expect("live generator");
            let (a, b, length, restitution, cable) = match g.def {
                GeneratorDef::Rod { a, b, length } => (a, b, length, 0.0, false),
                GeneratorDef::Cable {
                    a,
                    b,
                    max_length,
                    restitution,
                } => (a, b, max_length, restitution, true),
                _ => continue,
            };
            let (Some(ea), Some(eb)) = (self.link_end(&a), self.link_end(&b)) else {
                continue; // a particle end: solved in the particle stage
            };
            if !ea.active && !eb.active {
                continue; // both ends still: nothing to do, and sleepers stay asleep
            }
            let d = eb.point - ea.point;
            let len = d.length();
            let n = if len > 1.0e-6 { d / len } else { Vec3::Y };
            let rate = (eb.velocity - ea.velocity).dot(n);
            let predicted = len + rate * dt;
            let margin = slop + rate.abs() * dt;
            let (normal, penetration) = if cable {
                if predicted < length && len < length - margin {
                    continue; // slack
                }
                (-n, len - length)
            } else if predicted >= length {
                (-n, len - length)
            } else {
                (n, length - len)
            };
            for e in [&ea, &eb] {
                if e.sleeping_dynamic {
                    scratch.wake.push(e.slot);
                }
            }
            self.generated_contacts.push(GeneratedContact {
                body_a: ea.slot,
                body_b: eb.slot,
                point: 0.5 * (ea.point + eb.point),
                normal,
                penetration,
                restitution,
                friction: 0.0,
            });
        }
        for k in 0..scratch.wake.len() {
            self.wake_body(scratch.wake[k]);
        }
        self.generator_scratch = scratch;
    }
}

/// One side of a contact written by a host contact generator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ContactObject {
    World,
    Body(crate::pool::Handle),
    Particle(crate::pool::Handle),
}

/// A contact written by a host contact generator: B is pushed along `normal` (from A to B),
/// A the other way; `penetration > 0` when violated, < 0 a speculative gap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UserContact {
    pub a: ContactObject,
    pub b: ContactObject,
    pub point: Vec3,
    pub normal: Vec3,
    pub penetration: f32,
    pub restitution: f32,
    pub friction: f32,
}

impl World {
    /// Checks a host contact without adding it: finite numbers, a normal that is not zero,
    /// non-negative restitution and friction, live and distinct objects (at least one).
    pub fn validate_user_contact(&self, c: &UserContact) -> crate::error::Result<()> {
        use crate::error::{check_finite, check_non_negative, check_vec, invalid};
        check_vec("point", c.point)?;
        check_vec("normal", c.normal)?;
        let l = c.normal.length();
        if !l.is_finite() || l <= 1.0e-6 {
            return Err(invalid("normal must not be zero"));
        }
        check_finite("penetration", c.penetration)?;
        check_non_negative("restitution", c.restitution)?;
        check_non_negative("friction", c.friction)?;
        for o in [&c.a, &c.b] {
            match *o {
                ContactObject::World => {}
                ContactObject::Body(h) => {
                    self.body(h)?;
                }
                ContactObject::Particle(h) => {
                    self.particle_index(h)?;
                }
            }
        }
        if c.a == ContactObject::World && c.b == ContactObject::World {
            return Err(invalid("a contact needs at least one body or particle"));
        }
        if c.a == c.b {
            return Err(invalid("a contact needs two different objects"));
        }
        Ok(())
    }

    /// Adds a host contact for this step: between bodies (or a body and the world) it joins
    /// the generated contacts of the rigid solver; with a particle it is resolved in the
    /// particle stage. Wakes what it touches. Call between the contact generators and the
    /// rigid solve (`collide_step` and `finish_step`).
    pub fn add_user_contact(&mut self, c: &UserContact) -> crate::error::Result<()> {
        use crate::particles::{ContactOther, UserParticleContact};
        self.validate_user_contact(c)?;
        let normal = c.normal.normalize();
        let slot = |o: &ContactObject| match *o {
            ContactObject::Body(h) => h.index,
            _ => NONE,
        };
        let other = |o: &ContactObject| match *o {
            ContactObject::World => ContactOther::World,
            ContactObject::Body(h) => ContactOther::Body(h.index),
            ContactObject::Particle(h) => ContactOther::Particle(h),
        };
        match (c.a, c.b) {
            (ContactObject::Particle(p), b) => self.add_user_particle_contact(UserParticleContact {
                particle: p,
                other: other(&b),
                point: c.point,
                normal: -normal,
                penetration: c.penetration,
                restitution: c.restitution,
                friction: c.friction,
            }),
            (a, ContactObject::Particle(p)) => self.add_user_particle_contact(UserParticleContact {
                particle: p,
                other: other(&a),
                point: c.point,
                normal,
                penetration: c.penetration,
                restitution: c.restitution,
                friction: c.friction,
            }),
            (a, b) => {
                for s in [slot(&a), slot(&b)] {
                    if s != NONE {
                        self.wake_body(s);
                    }
                }
                self.generated_contacts.push(GeneratedContact {
                    body_a: slot(&a),
                    body_b: slot(&b),
                    point: c.point,
                    normal,
                    penetration: c.penetration,
                    restitution: c.restitution,
                    friction: c.friction,
                });
                Ok(())
            }
        }
    }
}

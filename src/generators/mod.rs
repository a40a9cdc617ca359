//! Force and contact generators: the two registries of the seed's frame.
//!
//! A generator is an object in the world's generator pool, created from a [`GeneratorDef`].
//! Force generators act on a set of attached bodies and particles (gravity, drag, springs,
//! buoyancy, explosions, host callbacks); contact generators report violated links as
//! contacts (rods, cables, host callbacks). Built-ins run inside [`World::step`]; host
//! callbacks ("external" generators) are stored here but invoked by the driver of the step
//! between its stages (the C layer, see `capi/world.rs`).
//!
//! * `forces.rs` — the forces stage (start of the step).
//! * `springs.rs` — springs whose ends are bodies or world points, applied every sub-step
//!   by the solver.
//! * `links.rs` — rods and cables between bodies, as generated contacts (after the narrow
//!   phase). Links with a particle end are solved in the particle stage (`particles/`).

pub mod forces;
pub mod links;
pub mod springs;

use crate::error::{check_non_negative, check_positive, check_vec, invalid, Error, Result};
use crate::hash::IntMap;
use crate::math::Vec3;
use crate::pool::Handle;
use crate::world::World;

pub type GeneratorHandle = Handle;

/// Number of sub-steps whose link impulses are remembered for warm starting (later
/// sub-steps share the last slot).
pub const WARM_SLOTS: usize = 8;

/// One end of a spring, rod or cable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum End {
    /// A fixed point in the world.
    World(Vec3),
    /// A point on a body, in the body frame (relative to the body origin).
    Body { body: Handle, local: Vec3 },
    /// A particle.
    Particle(Handle),
}

/// A spring from each attached object to `other` (Hooke's law with damping along the axis).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spring {
    /// The other end: a world anchor (an anchored spring), a body point or a particle. A
    /// dynamic body or particle there feels the reaction.
    pub other: End,
    /// Attachment point on each attached body, in the body frame (ignored for particles).
    pub local_point: Vec3,
    /// Rest length (m, >= 0).
    pub rest_length: f32,
    /// Stiffness (N/m, >= 0).
    pub stiffness: f32,
    /// Damping along the spring (N·s/m, >= 0).
    pub damping: f32,
}

/// Built-in and external generators.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GeneratorDef {
    /// Extra gravity (m/s²) on each attached object, on top of world gravity.
    Gravity { acceleration: Vec3 },
    /// Drag `-v̂ (k1 |v| + k2 |v|²)` on each attached object.
    Drag { k1: f32, k2: f32 },
    /// A spring that pushes and pulls.
    Spring(Spring),
    /// A spring that only pulls (when longer than its rest length).
    Bungee(Spring),
    /// A stiff damped spring (rest length 0) to `anchor` whose force is computed so that the
    /// step reproduces the exact damped harmonic motion: the discrete motion has the
    /// continuous system's frequency and decay for any stiffness (stable where an explicit
    /// spring would explode). Stiffness in N/m and damping in N·s/m; the anchor end is
    /// followed but feels no reaction.
    StiffSpring {
        anchor: End,
        local_point: Vec3,
        stiffness: f32,
        damping: f32,
    },
    /// Buoyancy of a liquid below the plane `dot(normal, p) = surface`: a force
    /// `liquid_density · volume · |g| · f` along `normal`, where `f` is the submerged
    /// fraction, rising linearly from 0 when the centre of buoyancy is `max_depth` above
    /// the surface to 1 when it is `max_depth` below.
    Buoyancy {
        normal: Vec3,
        surface: f32,
        max_depth: f32,
        volume: f32,
        liquid_density: f32,
        /// Centre of buoyancy on attached bodies, body frame.
        local_point: Vec3,
    },
    /// An explosion at `center`: in its first step a blast impulse
    /// `blast_impulse · (1 - d / blast_radius)` away from the centre on objects within
    /// `blast_radius`, then a shock wave, a shell of `shock_thickness` expanding at
    /// `shock_speed` up to `max_radius`, pushing objects inside it with up to `shock_force`.
    /// Acts on every object in range when `affect_all`, else on attached objects only.
    Explosion {
        center: Vec3,
        blast_radius: f32,
        blast_impulse: f32,
        shock_speed: f32,
        shock_thickness: f32,
        shock_force: f32,
        max_radius: f32,
        affect_all: bool,
    },
    /// A rod: the two ends stay `length` apart (pushes and pulls).
    Rod { a: End, b: End, length: f32 },
    /// A cable: the ends stay at most `max_length` apart; bounces with `restitution`.
    Cable {
        a: End,
        b: End,
        max_length: f32,
        restitution: f32,
    },
    /// A force generator run by the driver of the step (a host callback). The core only
    /// stores the two opaque words.
    ExternalForce { callback: usize, user_data: usize },
    /// A contact generator run by the driver of the step, with room for `capacity`
    /// contacts per step.
    ExternalContact {
        callback: usize,
        user_data: usize,
        capacity: u32,
    },
}

impl GeneratorDef {
    /// True for the generators whose objects are their two ends (rods, cables): they take
    /// no attachments.
    pub fn is_link(&self) -> bool {
        matches!(self, GeneratorDef::Rod { .. } | GeneratorDef::Cable { .. })
    }

    pub(crate) fn validate(&self) -> Result<()> {
        use GeneratorDef as G;
        match *self {
            G::Gravity { acceleration } => check_vec("acceleration", acceleration),
            G::Drag { k1, k2 } => {
                check_non_negative("k1", k1)?;
                check_non_negative("k2", k2)
            }
            G::Spring(s) | G::Bungee(s) => {
                check_end("other", &s.other)?;
                check_vec("local_point", s.local_point)?;
                check_non_negative("rest_length", s.rest_length)?;
                check_non_negative("stiffness", s.stiffness)?;
                check_non_negative("damping", s.damping)
            }
            G::StiffSpring {
                anchor,
                local_point,
                stiffness,
                damping,
            } => {
                check_end("anchor", &anchor)?;
                check_vec("local_point", local_point)?;
                check_positive("stiffness", stiffness)?;
                check_non_negative("damping", damping)
            }
            G::Buoyancy {
                normal,
                surface,
                max_depth,
                volume,
                liquid_density,
                local_point,
            } => {
                check_vec("surface_normal", normal)?;
                if normal.length_squared() < 1.0e-12 {
                    return Err(invalid("surface_normal must not be zero"));
                }
                crate::error::check_finite("surface_offset", surface)?;
                check_positive("max_depth", max_depth)?;
                check_non_negative("volume", volume)?;
                check_non_negative("liquid_density", liquid_density)?;
                check_vec("local_point", local_point)
            }
            G::Explosion {
                center,
                blast_radius,
                blast_impulse,
                shock_speed,
                shock_thickness,
                shock_force,
                max_radius,
                ..
            } => {
                // README "Supported ranges": the blast is applied as a force over one step,
                // blast_impulse / dt, which stays finite for the shortest step.
                use crate::error::{check_distance, check_position, check_range, MAX_FORCE, MAX_IMPULSE, MAX_SPEED};
                check_position("center", center)?;
                check_distance("blast_radius", blast_radius)?;
                check_range("blast_impulse", blast_impulse, 0.0, MAX_IMPULSE, " N·s")?;
                check_range("shock_speed", shock_speed, 0.0, MAX_SPEED, " m/s")?;
                check_distance("shock_thickness", shock_thickness)?;
                check_range("shock_force", shock_force, 0.0, MAX_FORCE, " N")?;
                check_distance("max_radius", max_radius)
            }
            G::Rod { a, b, length } => {
                check_ends(&a, &b)?;
                check_non_negative("length", length)
            }
            G::Cable {
                a,
                b,
                max_length,
                restitution,
            } => {
                check_ends(&a, &b)?;
                check_non_negative("max_length", max_length)?;
                check_non_negative("restitution", restitution)
            }
            G::ExternalForce { callback, .. } | G::ExternalContact { callback, .. } if callback == 0 => {
                Err(invalid("callback must not be NULL"))
            }
            G::ExternalForce { .. } => Ok(()),
            G::ExternalContact { capacity, .. } => {
                if capacity > 1 << 20 {
                    Err(invalid(format!("capacity must be at most 1048576, got {capacity}")))
                } else {
                    Ok(())
                }
            }
        }
    }

    /// Normalises the directions.
    fn normalized(mut self) -> Self {
        if let GeneratorDef::Buoyancy { normal, surface, .. } = &mut self {
            let l = normal.length();
            *normal /= l;
            *surface /= l;
        }
        self
    }
}

fn check_end(name: &str, e: &End) -> Result<()> {
    match *e {
        End::World(p) => check_vec(name, p),
        End::Body { local, .. } => check_vec(name, local),
        End::Particle(_) => Ok(()),
    }
}

fn check_ends(a: &End, b: &End) -> Result<()> {
    check_end("a", a)?;
    check_end("b", b)?;
    if matches!((a, b), (End::World(_), End::World(_))) {
        return Err(invalid("a link needs at least one body or particle end"));
    }
    if a == b {
        return Err(invalid("the two ends of a link are the same point"));
    }
    Ok(())
}

/// The bodies or particles a generator acts on: a list in attachment order with an index by
/// slot for O(1) attach and detach. Handles of destroyed particles are pruned lazily (a
/// stale handle never matches a live object: generations differ).
#[derive(Default)]
pub struct Attachments {
    list: Vec<Handle>,
    by_slot: IntMap<u32, u32>,
}

impl Attachments {
    pub fn handles(&self) -> &[Handle] {
        &self.list
    }

    /// Every slot maps to its place in the list and back (a restored snapshot's check).
    pub(crate) fn consistent(&self) -> bool {
        self.by_slot.len() == self.list.len()
            && self
                .by_slot
                .iter()
                .all(|(&slot, &pos)| matches!(self.list.get(pos as usize), Some(h) if h.index == slot))
    }

    /// Adds `h`; false if it is already attached.
    fn insert(&mut self, h: Handle) -> bool {
        if let Some(&pos) = self.by_slot.get(&h.index) {
            if self.list[pos as usize] == h {
                return false;
            }
            // The slot held an object destroyed since: reuse its place.
            self.list[pos as usize] = h;
            return true;
        }
        self.by_slot.insert(h.index, self.list.len() as u32);
        self.list.push(h);
        true
    }

    fn remove(&mut self, h: Handle) -> bool {
        match self.by_slot.get(&h.index) {
            Some(&pos) if self.list[pos as usize] == h => {
                self.by_slot.remove(&h.index);
                self.list.swap_remove(pos as usize);
                if let Some(&moved) = self.list.get(pos as usize) {
                    self.by_slot.insert(moved.index, pos);
                }
                true
            }
            _ => false,
        }
    }

    /// Drops every handle for which `live` is false, keeping the order of the rest.
    fn retain(&mut self, mut live: impl FnMut(Handle) -> bool) {
        let before = self.list.len();
        self.list.retain(|&h| live(h));
        if self.list.len() != before {
            self.by_slot.clear();
            for (i, h) in self.list.iter().enumerate() {
                self.by_slot.insert(h.index, i as u32);
            }
        }
    }
}

/// A generator in the world's pool.
pub struct Generator {
    pub def: GeneratorDef,
    pub bodies: Attachments,
    pub particles: Attachments,
    /// An end of this spring or link was destroyed: it does nothing any more.
    pub broken: bool,
    /// Seconds since creation, counted by the steps it ran in (explosions).
    pub elapsed: f32,
    /// Impulses of a particle link per sub-step, for warm starting (`particles/solver.rs`).
    pub(crate) warm: [f32; WARM_SLOTS],
}

impl Generator {
    /// Ends this generator depends on (springs' other end, links' two ends).
    fn ends(&self) -> [Option<End>; 2] {
        self.def.ends()
    }
}

impl GeneratorDef {
    fn ends(&self) -> [Option<End>; 2] {
        use GeneratorDef as G;
        match *self {
            G::Spring(s) | G::Bungee(s) => [Some(s.other), None],
            G::StiffSpring { anchor, .. } => [Some(anchor), None],
            G::Rod { a, b, .. } | G::Cable { a, b, .. } => [Some(a), Some(b)],
            _ => [None, None],
        }
    }
}

/// Kind of a generator, for hosts and tests.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GeneratorKind {
    Gravity,
    Drag,
    Spring,
    Bungee,
    StiffSpring,
    Buoyancy,
    Explosion,
    Rod,
    Cable,
    ExternalForce,
    ExternalContact,
}

impl GeneratorDef {
    pub fn kind(&self) -> GeneratorKind {
        use GeneratorDef as G;
        match self {
            G::Gravity { .. } => GeneratorKind::Gravity,
            G::Drag { .. } => GeneratorKind::Drag,
            G::Spring(_) => GeneratorKind::Spring,
            G::Bungee(_) => GeneratorKind::Bungee,
            G::StiffSpring { .. } => GeneratorKind::StiffSpring,
            G::Buoyancy { .. } => GeneratorKind::Buoyancy,
            G::Explosion { .. } => GeneratorKind::Explosion,
            G::Rod { .. } => GeneratorKind::Rod,
            G::Cable { .. } => GeneratorKind::Cable,
            G::ExternalForce { .. } => GeneratorKind::ExternalForce,
            G::ExternalContact { .. } => GeneratorKind::ExternalContact,
        }
    }
}

impl World {
    /// Creates a generator. Ends must be live bodies or particles of this world.
    pub fn create_generator(&mut self, def: &GeneratorDef) -> Result<GeneratorHandle> {
        def.validate()?;
        let def = def.normalized();
        for end in def.ends().into_iter().flatten() {
            self.check_end_live(&end)?;
        }
        Ok(self.generators.insert(Generator {
            def,
            bodies: Attachments::default(),
            particles: Attachments::default(),
            broken: false,
            elapsed: 0.0,
            warm: [0.0; WARM_SLOTS],
        }))
    }

    fn check_end_live(&self, end: &End) -> Result<()> {
        match *end {
            End::World(_) => Ok(()),
            End::Body { body, .. } => self.body(body).map(|_| ()),
            End::Particle(p) => self.particle_index(p).map(|_| ()),
        }
    }

    pub fn generator(&self, h: GeneratorHandle) -> Result<&Generator> {
        self.generators.get(h).ok_or(Error::InvalidId("generator"))
    }

    fn generator_mut(&mut self, h: GeneratorHandle) -> Result<&mut Generator> {
        self.generators.get_mut(h).ok_or(Error::InvalidId("generator"))
    }

    /// Destroys a generator; its id becomes stale.
    pub fn destroy_generator(&mut self, h: GeneratorHandle) -> Result<()> {
        self.generators
            .remove(h)
            .map(|_| ())
            .ok_or(Error::InvalidId("generator"))
    }

    pub fn generator_count(&self) -> usize {
        self.generators.len()
    }

    fn check_attachable(&self, g: GeneratorHandle) -> Result<()> {
        if self.generator(g)?.def.is_link() {
            return Err(invalid(
                "rods and cables act on their two ends; they take no attachments",
            ));
        }
        Ok(())
    }

    /// Makes generator `g` act on body `b`. Attaching twice is an error.
    pub fn attach_body(&mut self, g: GeneratorHandle, b: Handle) -> Result<()> {
        self.check_attachable(g)?;
        self.body(b)?;
        if !self.generator_mut(g)?.bodies.insert(b) {
            return Err(invalid("the body is already attached to this generator"));
        }
        Ok(())
    }

    /// Makes generator `g` act on particle `p`. Attaching twice is an error.
    pub fn attach_particle(&mut self, g: GeneratorHandle, p: Handle) -> Result<()> {
        self.check_attachable(g)?;
        self.particle_index(p)?;
        if !self.generator_mut(g)?.particles.insert(p) {
            return Err(invalid("the particle is already attached to this generator"));
        }
        Ok(())
    }

    /// Attaches many particles at once: all or nothing (every id is checked first).
    pub fn attach_particles(&mut self, g: GeneratorHandle, ps: &[Handle]) -> Result<()> {
        self.check_attachable(g)?;
        for (i, &p) in ps.iter().enumerate() {
            self.particle_index(p)?;
            let gen = self.generator(g)?;
            if gen
                .particles
                .by_slot
                .get(&p.index)
                .map(|&k| gen.particles.list[k as usize])
                == Some(p)
            {
                return Err(invalid(format!("particles[{i}] is already attached to this generator")));
            }
        }
        for w in ps.windows(2) {
            if w[0] == w[1] {
                return Err(invalid("the same particle appears twice in a row"));
            }
        }
        let gen = self.generator_mut(g)?;
        for (i, &p) in ps.iter().enumerate() {
            if !gen.particles.insert(p) {
                // A duplicate further apart in the input: undo this call's insertions.
                for &q in &ps[..i] {
                    gen.particles.remove(q);
                }
                return Err(invalid("the same particle appears twice"));
            }
        }
        Ok(())
    }

    pub fn detach_body(&mut self, g: GeneratorHandle, b: Handle) -> Result<()> {
        self.check_attachable(g)?;
        if !self.generator_mut(g)?.bodies.remove(b) {
            return Err(Error::InvalidId("body (not attached to this generator)"));
        }
        Ok(())
    }

    pub fn detach_particle(&mut self, g: GeneratorHandle, p: Handle) -> Result<()> {
        self.check_attachable(g)?;
        // A destroyed or expired particle stays in the list until the next step prunes it:
        // its stale id is refused all the same.
        self.particle_index(p)?;
        if !self.generator_mut(g)?.particles.remove(p) {
            return Err(Error::InvalidId("particle (not attached to this generator)"));
        }
        Ok(())
    }

    /// Live attachments of a generator: (bodies, particles).
    pub fn generator_attachment_counts(&self, g: GeneratorHandle) -> Result<(usize, usize)> {
        let gen = self.generator(g)?;
        let bodies = gen.bodies.list.iter().filter(|&&b| self.bodies.contains(b)).count();
        let particles = gen
            .particles
            .list
            .iter()
            .filter(|&&p| self.particles.ids.contains(p))
            .count();
        Ok((bodies, particles))
    }

    /// Called by `destroy_body`: the body leaves every generator, and springs and links
    /// with it as an end stop acting (waking what they held).
    pub(crate) fn detach_body_everywhere(&mut self, b: Handle) {
        self.break_links(
            |g, _| {
                g.bodies.remove(b);
            },
            |e, _| matches!(*e, End::Body { body, .. } if body == b),
        );
    }

    /// Drops destroyed particles from every generator and breaks links that lost an end
    /// (waking what they held). Run lazily at the start of a step after particles were
    /// removed.
    pub(crate) fn prune_particle_attachments(&mut self) {
        if !self.particles.removed_since_prune {
            return;
        }
        self.particles.removed_since_prune = false;
        self.break_links(
            |g, ids| g.particles.retain(|p| ids.contains(p)),
            |e, ids| matches!(*e, End::Particle(p) if !ids.contains(p)),
        );
    }

    /// For every generator: `update` its attachments, and mark it broken when one of its
    /// ends is `gone`; the surviving ends of a newly broken one are woken.
    fn break_links(
        &mut self,
        mut update: impl FnMut(&mut Generator, &crate::pool::Pool<u32>),
        gone: impl Fn(&End, &crate::pool::Pool<u32>) -> bool,
    ) {
        let mut scratch = std::mem::take(&mut self.generator_scratch);
        scratch.order.clear();
        scratch.order.extend(self.generators.iter().map(|(h, _)| h));
        scratch.wake.clear();
        for &h in &scratch.order {
            let g = self.generators.get_mut(h).expect("live generator");
            update(g, &self.particles.ids);
            let ends = g.ends();
            if g.broken || !ends.iter().flatten().any(|e| gone(e, &self.particles.ids)) {
                continue;
            }
            g.broken = true;
            for e in ends.into_iter().flatten() {
                if gone(&e, &self.particles.ids) {
                    continue;
                }
                match e {
                    End::Body { body, .. } if self.bodies.contains(body) => scratch.wake.push(body.index),
                    End::Particle(p) => {
                        if let Some(i) = self.particles.index(p) {
                            self.particles.wake(i, self.settings.sleep_threshold);
                        }
                    }
                    _ => {}
                }
            }
        }
        for k in 0..scratch.wake.len() {
            self.wake_body(scratch.wake[k]);
        }
        self.generator_scratch = scratch;
    }
}

crate::snap_struct!(Attachments { list, by_slot });

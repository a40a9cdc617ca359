//! The particle world: point masses beside the rigid bodies.
//!
//! Storage is structure-of-arrays (one dense array per field, so the 100k-particle loops
//! stream through memory); ids come from the world's generational pool, whose slots hold
//! each particle's dense index. Removing a particle swaps the last one into its place.
//!
//! * `solver.rs` — the particle stage of the step (after the rigid solve): integration,
//!   contacts with rigid shapes (two-way with dynamic bodies), rods and cables, sleep,
//!   lifetimes.
//! * `emitter.rs` — burst emitters with a reproducible random sequence.

mod block;
mod constraint;
pub mod emitter;
pub mod solver;

use crate::error::{check_non_negative, check_vec, invalid, Error, Result};
use crate::math::Vec3;
use crate::pool::{Handle, Pool};
use crate::world::World;

pub type ParticleHandle = Handle;

pub(crate) const AWAKE: u8 = 1;
pub(crate) const COLLIDE: u8 = 2;
pub(crate) const ALLOW_SLEEP: u8 = 4;

/// Everything needed to create a particle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParticleDef {
    pub position: Vec3,
    pub velocity: Vec3,
    /// Constant acceleration of this particle (m/s²), on top of world gravity.
    pub acceleration: Vec3,
    /// 1/kg, >= 0; 0 is an infinite mass (a pinned particle, moved only by its velocity).
    pub inverse_mass: f32,
    /// Radius (m, >= 0) of the small sphere it collides as.
    pub radius: f32,
    /// Linear damping (1/s, >= 0).
    pub damping: f32,
    /// Multiplier of world gravity.
    pub gravity_scale: f32,
    /// Bounciness against shapes (>= 0; the pair uses the larger of the two).
    pub restitution: f32,
    /// Coulomb friction against shapes (>= 0; the pair uses the geometric mean).
    pub friction: f32,
    /// Seconds until the particle expires (> 0); infinity lives forever.
    pub lifetime: f32,
    pub collide: bool,
    pub allow_sleep: bool,
    pub user_data: u64,
}

impl Default for ParticleDef {
    fn default() -> Self {
        ParticleDef {
            position: Vec3::ZERO,
            velocity: Vec3::ZERO,
            acceleration: Vec3::ZERO,
            inverse_mass: 1.0,
            radius: 0.05,
            damping: 0.0,
            gravity_scale: 1.0,
            restitution: 0.0,
            friction: 0.5,
            lifetime: f32::INFINITY,
            collide: true,
            allow_sleep: true,
            user_data: 0,
        }
    }
}

impl ParticleDef {
    /// Range-checks every number (README "Supported ranges"; the velocity against the
    /// world's `max_linear_speed`).
    pub fn validate(&self, max_linear_speed: f32) -> Result<()> {
        use crate::error::{
            check_acceleration, check_damping, check_gravity_scale, check_length, check_position, check_range,
            check_restitution, check_velocity, MAX_INVERSE_MASS,
        };
        check_position("position", self.position)?;
        check_velocity("velocity", self.velocity, max_linear_speed)?;
        check_acceleration("acceleration", self.acceleration)?;
        check_range("inverse_mass", self.inverse_mass, 0.0, MAX_INVERSE_MASS, " 1/kg")?;
        if self.radius != 0.0 {
            check_length("radius (0 for a point)", self.radius)?;
        }
        check_damping("damping", self.damping)?;
        check_gravity_scale("gravity_scale", self.gravity_scale)?;
        check_restitution("restitution", self.restitution)?;
        check_non_negative("friction", self.friction)?;
        if self.lifetime.is_nan() || self.lifetime <= 0.0 {
            return Err(invalid(format!(
                "lifetime must be > 0 (infinity: forever), got {}",
                self.lifetime
            )));
        }
        Ok(())
    }
}

/// A particle removed by the last step because its lifetime ran out; its id is stale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExpiredParticle {
    pub id: Handle,
    pub position: Vec3,
    pub velocity: Vec3,
    pub user_data: u64,
}

/// Iteration counts of the particle stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ParticleSettings {
    /// Velocity sweeps over links and contacts per sub-step.
    pub velocity_iterations: u32,
    /// Position projection sweeps per sub-step (rods hold their length through these).
    pub position_iterations: u32,
}

impl Default for ParticleSettings {
    fn default() -> Self {
        ParticleSettings {
            velocity_iterations: 8,
            position_iterations: 4,
        }
    }
}

/// A contact a host's contact generator wrote for a particle, resolved in the particle stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UserParticleContact {
    /// The particle pushed along `normal`.
    pub particle: Handle,
    /// What it is pushed away from.
    pub other: ContactOther,
    pub point: Vec3,
    /// Unit direction in which the particle is pushed.
    pub normal: Vec3,
    pub penetration: f32,
    pub restitution: f32,
    pub friction: f32,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ContactOther {
    World,
    /// A body slot index.
    Body(u32),
    Particle(Handle),
}

/// Particle storage: a handle pool mapping to dense arrays.
pub struct Particles {
    pub(crate) ids: Pool<u32>,
    pub handle: Vec<Handle>,
    pub pos: Vec<Vec3>,
    pub vel: Vec<Vec3>,
    /// Force accumulated for the next step (N), cleared after it.
    pub force: Vec<Vec3>,
    pub accel: Vec<Vec3>,
    pub inv_mass: Vec<f32>,
    pub radius: Vec<f32>,
    pub damping: Vec<f32>,
    pub gravity_scale: Vec<f32>,
    pub restitution: Vec<f32>,
    pub friction: Vec<f32>,
    /// Seconds left; infinity for immortal particles.
    pub lifetime: Vec<f32>,
    /// Recency-weighted motion (v²) and seconds spent still, as for bodies.
    pub motion: Vec<f32>,
    pub sleep_time: Vec<f32>,
    pub flags: Vec<u8>,
    pub user_data: Vec<u64>,
    /// Particles that expired in the last step (valid until the next step).
    pub expired: Vec<ExpiredParticle>,
    /// Contacts written by host contact generators for this step.
    pub user_contacts: Vec<UserParticleContact>,
    pub settings: ParticleSettings,
    /// A particle was removed since generators were last pruned.
    pub(crate) removed_since_prune: bool,
    pub(crate) scratch: solver::Scratch,
}

impl Particles {
    pub fn new(tag: u32) -> Particles {
        Particles {
            ids: Pool::new(tag),
            handle: Vec::new(),
            pos: Vec::new(),
            vel: Vec::new(),
            force: Vec::new(),
            accel: Vec::new(),
            inv_mass: Vec::new(),
            radius: Vec::new(),
            damping: Vec::new(),
            gravity_scale: Vec::new(),
            restitution: Vec::new(),
            friction: Vec::new(),
            lifetime: Vec::new(),
            motion: Vec::new(),
            sleep_time: Vec::new(),
            flags: Vec::new(),
            user_data: Vec::new(),
            expired: Vec::new(),
            user_contacts: Vec::new(),
            settings: ParticleSettings::default(),
            removed_since_prune: false,
            scratch: Default::default(),
        }
    }

    pub fn len(&self) -> usize {
        self.pos.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }

    /// Dense index of a live particle.
    #[inline]
    pub fn index(&self, h: Handle) -> Option<usize> {
        self.ids.get(h).map(|&i| i as usize)
    }

    #[inline]
    pub fn is_awake(&self, i: usize) -> bool {
        self.flags[i] & AWAKE != 0
    }

    /// Inserts a validated def; returns its handle.
    pub(crate) fn insert(&mut self, d: &ParticleDef, sleep_threshold: f32) -> Handle {
        let i = self.pos.len() as u32;
        let h = self.ids.insert(i);
        self.handle.push(h);
        self.pos.push(d.position);
        self.vel.push(d.velocity);
        self.force.push(Vec3::ZERO);
        self.accel.push(d.acceleration);
        self.inv_mass.push(d.inverse_mass);
        self.radius.push(d.radius);
        self.damping.push(d.damping);
        self.gravity_scale.push(d.gravity_scale);
        self.restitution.push(d.restitution);
        self.friction.push(d.friction);
        self.lifetime.push(d.lifetime);
        self.motion.push(2.0 * sleep_threshold * sleep_threshold);
        self.sleep_time.push(0.0);
        let mut flags = AWAKE;
        if d.collide {
            flags |= COLLIDE;
        }
        if d.allow_sleep {
            flags |= ALLOW_SLEEP;
        }
        self.flags.push(flags);
        self.user_data.push(d.user_data);
        h
    }

    /// Removes the particle at dense index `i` (the last one moves into its place).
    pub(crate) fn remove_at(&mut self, i: usize) {
        let h = self.handle[i];
        self.ids.remove(h);
        self.handle.swap_remove(i);
        self.pos.swap_remove(i);
        self.vel.swap_remove(i);
        self.force.swap_remove(i);
        self.accel.swap_remove(i);
        self.inv_mass.swap_remove(i);
        self.radius.swap_remove(i);
        self.damping.swap_remove(i);
        self.gravity_scale.swap_remove(i);
        self.restitution.swap_remove(i);
        self.friction.swap_remove(i);
        self.lifetime.swap_remove(i);
        self.motion.swap_remove(i);
        self.sleep_time.swap_remove(i);
        self.flags.swap_remove(i);
        self.user_data.swap_remove(i);
        if i < self.handle.len() {
            let moved = self.handle[i];
            *self.ids.at_mut(moved.index) = i as u32;
        }
        self.removed_since_prune = true;
    }

    /// Wakes the particle at dense index `i` (its linked group follows in the next step).
    pub(crate) fn wake(&mut self, i: usize, sleep_threshold: f32) {
        self.sleep_time[i] = 0.0;
        if self.flags[i] & AWAKE == 0 {
            self.flags[i] |= AWAKE;
            self.motion[i] = 2.0 * sleep_threshold * sleep_threshold;
        } else {
            self.motion[i] = self.motion[i].max(2.0 * sleep_threshold * sleep_threshold);
        }
    }
}

impl World {
    /// Creates a particle.
    pub fn create_particle(&mut self, def: &ParticleDef) -> Result<ParticleHandle> {
        def.validate(self.settings.max_linear_speed)?;
        Ok(self.particles.insert(def, self.settings.sleep_threshold))
    }

    /// Dense index of a live particle, or an invalid-id error.
    pub fn particle_index(&self, h: ParticleHandle) -> Result<usize> {
        self.particles.index(h).ok_or(Error::InvalidId("particle"))
    }

    /// Destroys a particle; its id becomes stale and it leaves every generator.
    pub fn destroy_particle(&mut self, h: ParticleHandle) -> Result<()> {
        let i = self.particle_index(h)?;
        self.particles.remove_at(i);
        Ok(())
    }

    pub fn particle_count(&self) -> usize {
        self.particles.len()
    }

    pub fn particle_position(&self, h: ParticleHandle) -> Result<Vec3> {
        Ok(self.particles.pos[self.particle_index(h)?])
    }

    pub fn particle_velocity(&self, h: ParticleHandle) -> Result<Vec3> {
        Ok(self.particles.vel[self.particle_index(h)?])
    }

    pub fn particle_is_awake(&self, h: ParticleHandle) -> Result<bool> {
        Ok(self.particles.is_awake(self.particle_index(h)?))
    }

    pub fn particle_user_data(&self, h: ParticleHandle) -> Result<u64> {
        Ok(self.particles.user_data[self.particle_index(h)?])
    }

    /// Teleports a particle and wakes it.
    pub fn set_particle_position(&mut self, h: ParticleHandle, p: Vec3) -> Result<()> {
        let i = self.particle_index(h)?;
        crate::error::check_position("position", p)?;
        self.particles.pos[i] = p;
        self.particles.wake(i, self.settings.sleep_threshold);
        Ok(())
    }

    /// Sets a particle's velocity; a non-zero value wakes it.
    pub fn set_particle_velocity(&mut self, h: ParticleHandle, v: Vec3) -> Result<()> {
        let i = self.particle_index(h)?;
        crate::error::check_velocity("velocity", v, self.settings.max_linear_speed)?;
        self.particles.vel[i] = v;
        if v != Vec3::ZERO {
            self.particles.wake(i, self.settings.sleep_threshold);
        }
        Ok(())
    }

    /// Adds a force (N) for the next step; wakes the particle when `wake`. A sleeping
    /// particle that is not woken ignores it.
    pub fn apply_particle_force(&mut self, h: ParticleHandle, f: Vec3, wake: bool) -> Result<()> {
        let i = self.particle_index(h)?;
        crate::error::check_force("force", f)?;
        if wake {
            self.particles.wake(i, self.settings.sleep_threshold);
        }
        if self.particles.is_awake(i) {
            // Saturating, so any number of finite forces accumulate to a finite one.
            let max = glam::DVec3::splat(f32::MAX as f64);
            let sum = self.particles.force[i].as_dvec3() + f.as_dvec3();
            self.particles.force[i] = sum.clamp(-max, max).as_vec3();
        }
        Ok(())
    }

    /// Applies an impulse (N·s): changes the velocity at once (capped at `max_linear_speed`).
    /// Wakes the particle.
    pub fn apply_particle_impulse(&mut self, h: ParticleHandle, j: Vec3) -> Result<()> {
        let i = self.particle_index(h)?;
        crate::error::check_impulse("impulse", j)?;
        self.particles.wake(i, self.settings.sleep_threshold);
        let v = self.particles.vel[i] + self.particles.inv_mass[i] * j;
        self.particles.vel[i] = crate::world::cap_speed(v, self.settings.max_linear_speed);
        Ok(())
    }

    /// Wakes (true) or puts to sleep (false) a particle (its linked group follows).
    pub fn set_particle_awake(&mut self, h: ParticleHandle, awake: bool) -> Result<()> {
        let i = self.particle_index(h)?;
        if awake {
            self.particles.wake(i, self.settings.sleep_threshold);
        } else {
            let p = &mut self.particles;
            p.flags[i] &= !AWAKE;
            p.vel[i] = Vec3::ZERO;
            p.force[i] = Vec3::ZERO;
            p.sleep_time[i] = 0.0;
        }
        Ok(())
    }

    /// Particles that expired in the last step (removed, ids stale).
    pub fn expired_particles(&self) -> &[ExpiredParticle] {
        &self.particles.expired
    }

    /// Sets the particle stage's iteration counts (each 1..=64).
    pub fn set_particle_iterations(&mut self, velocity: u32, position: u32) -> Result<()> {
        if !(1..=64).contains(&velocity) || !(1..=64).contains(&position) {
            return Err(invalid(format!(
                "particle iterations must be in 1..=64, got {velocity} and {position}"
            )));
        }
        self.particles.settings = ParticleSettings {
            velocity_iterations: velocity,
            position_iterations: position,
        };
        Ok(())
    }

    /// Adds a contact from a host contact generator; resolved in this step's particle
    /// stage. Wakes the particles and bodies involved.
    pub fn add_user_particle_contact(&mut self, c: UserParticleContact) -> Result<()> {
        let i = self.particle_index(c.particle)?;
        check_vec("point", c.point)?;
        check_vec("normal", c.normal)?;
        let l = c.normal.length();
        if l.is_nan() || l <= 1.0e-6 {
            return Err(invalid("normal must not be zero"));
        }
        crate::error::check_finite("penetration", c.penetration)?;
        check_non_negative("restitution", c.restitution)?;
        check_non_negative("friction", c.friction)?;
        let t = self.settings.sleep_threshold;
        match c.other {
            ContactOther::World => {}
            ContactOther::Body(b) => self.wake_body(b),
            ContactOther::Particle(p) => {
                let j = self.particle_index(p)?;
                if j == i {
                    return Err(invalid("a contact needs two different objects"));
                }
                self.particles.wake(j, t);
            }
        }
        self.particles.wake(i, t);
        self.particles.user_contacts.push(UserParticleContact {
            normal: c.normal / l,
            ..c
        });
        Ok(())
    }
}

//! Burst emitters: `count` particles at once from a point, with directions uniform inside a
//! cone and speeds and lifetimes uniform in their ranges, drawn from a small PRNG seeded by
//! the def, so the same def always gives the same burst.

use super::{ParticleDef, ParticleHandle};
use crate::error::{check_non_negative, check_vec, invalid, Result};
use crate::math::{orthonormal_basis, Vec3};
use crate::world::World;

/// Largest burst (particles per call).
pub const MAX_BURST: u32 = 1 << 20;

/// A burst of particles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BurstDef {
    /// Where every particle starts.
    pub position: Vec3,
    /// Axis of the cone (need not be unit length, must not be zero).
    pub direction: Vec3,
    /// Half-angle of the cone (radians, 0..=π; π is every direction).
    pub cone_half_angle: f32,
    pub count: u32,
    /// Speed range (m/s, 0 <= min <= max).
    pub speed_min: f32,
    pub speed_max: f32,
    /// Lifetime range (s, 0 < min <= max; infinity lives forever).
    pub lifetime_min: f32,
    pub lifetime_max: f32,
    /// Seed of the random sequence.
    pub seed: u64,
    /// Every other property of the particles (position, velocity and lifetime are
    /// overwritten per particle).
    pub particle: ParticleDef,
}

impl Default for BurstDef {
    fn default() -> Self {
        BurstDef {
            position: Vec3::ZERO,
            direction: Vec3::Y,
            cone_half_angle: 0.5,
            count: 16,
            speed_min: 5.0,
            speed_max: 10.0,
            lifetime_min: 1.0,
            lifetime_max: 2.0,
            seed: 1,
            particle: ParticleDef::default(),
        }
    }
}

impl BurstDef {
    /// Range-checks the burst and its particle def (README "Supported ranges"; speeds, added
    /// to the particles' own velocity, against the world's `max_linear_speed`).
    pub fn validate(&self, max_linear_speed: f32) -> Result<()> {
        use crate::error::{check_position, check_range};
        check_position("position", self.position)?;
        check_vec("direction", self.direction)?;
        let l = self.direction.length();
        if !(1.0e-6..=f32::MAX).contains(&l) {
            return Err(invalid(format!(
                "direction must be non-zero (length at least 1e-6) and finite, got {}",
                self.direction
            )));
        }
        if !(0.0..=std::f32::consts::PI).contains(&self.cone_half_angle) {
            return Err(invalid(format!(
                "cone_half_angle must be in [0, pi], got {}",
                self.cone_half_angle
            )));
        }
        if self.count > MAX_BURST {
            return Err(invalid(format!(
                "count must be at most {MAX_BURST}, got {}",
                self.count
            )));
        }
        check_non_negative("speed_min", self.speed_min)?;
        check_non_negative("speed_max", self.speed_max)?;
        if self.speed_min > self.speed_max {
            return Err(invalid(format!(
                "speed_min must not exceed speed_max, got {} > {}",
                self.speed_min, self.speed_max
            )));
        }
        // Every particle's velocity is its def's plus up to speed_max along the cone.
        let fastest = self.particle.velocity.length() + self.speed_max;
        check_range(
            "speed_max plus the length of particle.velocity",
            fastest,
            0.0,
            max_linear_speed,
            " m/s (the world's max_linear_speed)",
        )?;
        if self.lifetime_min.is_nan() || self.lifetime_min <= 0.0 || self.lifetime_max.is_nan() {
            return Err(invalid(format!(
                "lifetime_min must be > 0 and lifetime_max not NaN, got {} and {}",
                self.lifetime_min, self.lifetime_max
            )));
        }
        if self.lifetime_min > self.lifetime_max {
            return Err(invalid(format!(
                "lifetime_min must not exceed lifetime_max, got {} > {}",
                self.lifetime_min, self.lifetime_max
            )));
        }
        ParticleDef {
            position: self.position,
            ..self.particle
        }
        .validate(max_linear_speed)
        .map_err(|e| invalid(format!("particle.{e}")))
    }
}

/// PCG32 (O'Neill): small, fast, and the same sequence on every platform.
#[derive(Clone, Copy, Debug)]
pub struct Rng {
    state: u64,
    inc: u64,
}

impl Rng {
    pub fn new(seed: u64) -> Rng {
        let mut r = Rng {
            state: 0,
            inc: (seed.rotate_left(17) << 1) | 1,
        };
        r.next_u32();
        r.state = r.state.wrapping_add(seed);
        r.next_u32();
        r
    }

    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// Uniform in [0, 1).
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    }

    /// Uniform in [lo, hi]; an infinite `hi` gives infinity (particles that live forever).
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        if !hi.is_finite() {
            return hi;
        }
        if hi <= lo {
            return lo;
        }
        lo + (hi - lo) * self.next_f32()
    }
}

impl World {
    /// Emits a burst; pushes the new ids to `out` (which is not cleared). Nothing is
    /// created when the def is invalid.
    pub fn emit_burst(&mut self, def: &BurstDef, out: &mut Vec<ParticleHandle>) -> Result<()> {
        self.emit_burst_with(def, |h| out.push(h))
    }

    /// Emits a burst, calling `each` with every new id in order.
    pub fn emit_burst_with(&mut self, def: &BurstDef, mut each: impl FnMut(ParticleHandle)) -> Result<()> {
        def.validate(self.settings.max_linear_speed)?;
        let axis = def.direction.normalize();
        let (t1, t2) = orthonormal_basis(axis);
        let cos_max = def.cone_half_angle.cos();
        let mut rng = Rng::new(def.seed);
        let threshold = self.settings.sleep_threshold;
        for _ in 0..def.count {
            // Uniform over the spherical cap: cos θ uniform in [cos α, 1].
            let cos_t = 1.0 - rng.next_f32() * (1.0 - cos_max);
            let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
            let phi = std::f32::consts::TAU * rng.next_f32();
            let dir = axis * cos_t + (t1 * phi.cos() + t2 * phi.sin()) * sin_t;
            let speed = rng.range(def.speed_min, def.speed_max);
            let lifetime = rng.range(def.lifetime_min, def.lifetime_max);
            let p = ParticleDef {
                position: def.position,
                velocity: def.particle.velocity + dir * speed,
                lifetime,
                ..def.particle
            };
            each(self.particles.insert(&p, threshold));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rng_is_reproducible_and_uniform() {
        let mut a = Rng::new(42);
        let mut b = Rng::new(42);
        let mut c = Rng::new(43);
        let xs: Vec<u32> = (0..100).map(|_| a.next_u32()).collect();
        let ys: Vec<u32> = (0..100).map(|_| b.next_u32()).collect();
        let zs: Vec<u32> = (0..100).map(|_| c.next_u32()).collect();
        assert_eq!(xs, ys);
        assert_ne!(xs, zs);
        let mut r = Rng::new(7);
        let n = 100_000;
        let mean = (0..n).map(|_| r.next_f32() as f64).sum::<f64>() / n as f64;
        assert!((mean - 0.5).abs() < 0.01, "mean {mean}");
    }
}

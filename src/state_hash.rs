//! The world state hash (`World::state_hash`, `hearth_world_get_hash`): one 64-bit FNV-1a
//! over the bits of everything that moves, so two runs can be compared with one number.

use crate::math::{Quat, Vec3};
use crate::world::World;

const FNV_OFFSET: u64 = 0xCBF2_9CE4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01B3;

/// FNV-1a, 64 bits, fed little-endian words.
struct Fnv(u64);

impl Fnv {
    fn bytes(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(FNV_PRIME);
        }
    }
    fn u32(&mut self, x: u32) {
        self.bytes(&x.to_le_bytes());
    }
    fn f32(&mut self, x: f32) {
        self.u32(x.to_bits());
    }
    fn vec3(&mut self, v: Vec3) {
        self.f32(v.x);
        self.f32(v.y);
        self.f32(v.z);
    }
    fn quat(&mut self, q: Quat) {
        self.f32(q.x);
        self.f32(q.y);
        self.f32(q.z);
        self.f32(q.w);
    }
}

impl World {
    /// A 64-bit FNV-1a hash of the world's motion state, equal for two worlds exactly when
    /// (barring collisions) these bits are equal:
    ///
    /// Ids enter by their slot index only: the rest of an id carries the world's tag, which
    /// differs between two live worlds.
    ///
    /// * every live body in id (slot) order: its slot index, position and
    ///   rotation (x, y, z, w), linear and angular velocity, awake flag and sleep timer;
    /// * every live particle in storage order: its slot index, position and velocity;
    /// * every live soft body in id order: its slot index and each vertex's position and
    ///   velocity.
    ///
    /// Floats are hashed by their bit patterns (so -0 and 0 differ). Contacts, warm-start
    /// impulses, joints' impulses, forces and impulses applied for the next step
    /// and settings are not hashed: they show in the motion a
    /// step later. Costs one pass over the state; no allocation.
    pub fn state_hash(&self) -> u64 {
        let mut h = Fnv(FNV_OFFSET);
        for (id, b) in self.bodies.iter() {
            h.u32(id.index);
            h.vec3(b.xf.p);
            h.quat(b.xf.q);
            h.vec3(b.v);
            h.vec3(b.w);
            h.u32(b.awake as u32);
            h.f32(b.sleep_time);
        }
        let p = &self.particles;
        h.u32(p.pos.len() as u32);
        for i in 0..p.pos.len() {
            h.u32(p.handle[i].index);
            h.vec3(p.pos[i]);
            h.vec3(p.vel[i]);
        }
        for (id, s) in self.soft_bodies.pool.iter() {
            h.u32(id.index);
            for (x, v) in s.pos.iter().zip(&s.vel) {
                h.vec3(*x);
                h.vec3(*v);
            }
        }
        h.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_matches_the_reference_vectors() {
        // Published FNV-1a 64 test vectors: "" and "a".
        assert_eq!(Fnv(FNV_OFFSET).0, 0xcbf2_9ce4_8422_2325);
        let mut h = Fnv(FNV_OFFSET);
        h.bytes(b"a");
        assert_eq!(h.0, 0xaf63_dc4c_8601_ec8c);
    }
}

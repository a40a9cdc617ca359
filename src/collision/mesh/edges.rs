//! Active edges: which triangle edges may give a contact normal of their own.
//!
//! A convex body sliding over a flat or concave seam between two triangles must not feel
//! the seam: the edge is *inactive* and a contact found on it (or on one of its vertices)
//! takes the triangle's face normal instead (`narrow_phase::triangle`). Only convex edges
//! bent by more than `ACTIVE_EDGE_ANGLE`, and open edges (one triangle, or more than two),
//! are active — Jolt's "active edges". A triangle carries three bits, edge `i` running from
//! vertex `i` to vertex `i + 1`; a vertex is active when either of its two edges is.

use crate::math::Vec3;

/// Bend (degrees) above which a convex edge is active.
pub const ACTIVE_EDGE_ANGLE: f32 = 5.0;
/// `cos(ACTIVE_EDGE_ANGLE)`.
pub const ACTIVE_EDGE_COS: f32 = 0.996_194_7;

/// All three edges active (an open triangle).
pub const ALL_EDGES: u8 = 0b111;

/// Is edge `a → b` of a triangle with unit normal `n` active, given the vertex `opp` of the
/// neighbouring triangle across it (that triangle runs `b → a → opp`)?
#[inline]
pub fn edge_active(n: Vec3, a: Vec3, b: Vec3, opp: Vec3) -> bool {
    let n2 = (a - b).cross(opp - b);
    let len = n2.length();
    // Also true for a NaN length (a degenerate neighbour): such an edge stays active.
    if len.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return true;
    }
    // Convex when the neighbour bends away below this triangle's plane.
    let convex = n.dot(opp - a) < 0.0;
    convex && n.dot(n2) < ACTIVE_EDGE_COS * len
}

/// Is vertex `i` of a triangle with edge bits `flags` active?
#[inline]
pub fn vertex_active(flags: u8, i: usize) -> bool {
    flags & (1 << i | 1 << ((i + 2) % 3)) != 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn threshold_matches_angle() {
        assert!((ACTIVE_EDGE_ANGLE.to_radians().cos() - ACTIVE_EDGE_COS).abs() < 1e-7);
    }

    #[test]
    fn flat_concave_and_convex() {
        let (a, b) = (Vec3::ZERO, Vec3::new(0.0, 0.0, 1.0));
        let n = Vec3::Y; // triangle (a, b, (1,0,1)) lies on +x side
        let flat = Vec3::new(-1.0, 0.0, 0.5);
        assert!(!edge_active(n, a, b, flat));
        let concave = Vec3::new(-1.0, 0.5, 0.5);
        assert!(!edge_active(n, a, b, concave));
        let slight = Vec3::new(-1.0, -0.05, 0.5); // ~2.9° bend
        assert!(!edge_active(n, a, b, slight));
        let convex = Vec3::new(-1.0, -0.2, 0.5); // ~11°
        assert!(edge_active(n, a, b, convex));
        assert!(vertex_active(0b001, 0) && vertex_active(0b001, 1) && !vertex_active(0b001, 2));
    }
}

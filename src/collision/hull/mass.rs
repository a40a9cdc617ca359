//! Mass properties of polyhedra, exact, in f64.
//!
//! Each face is fanned into triangles and each triangle closed into a tetrahedron with a
//! reference point inside the hull (the mean of the vertices, which keeps the numbers
//! small). A tetrahedron `0, a, b, c` with `det = a · (b × c)` has volume `det / 6`, first
//! moment `det / 24 · (a + b + c)` and second moment (covariance)
//! `det / 120 · (a aᵀ + b bᵀ + c cᵀ + (a + b + c)(a + b + c)ᵀ)` — the canonical
//! tetrahedron's covariance mapped by the linear map `[a b c]`. Summed over the faces these
//! are the exact volume integrals of `1`, `x` and `x xᵀ` over the polyhedron (the same
//! integrals Mirtich's method evaluates through projected face integrals). The inertia about
//! the centre of mass is `trace(C) I − C` for the covariance `C` moved there.
//!
//! **Rounded hulls** (convex radius `r > 0`, the polyhedron Minkowski-summed with a ball):
//! the volume is exact by Steiner's formula `V + A r + M r² + 4/3 π r³` (`A` the area, `M`
//! half the sum over edges of length × the angle between the two face normals). The centre
//! of mass and inertia are integrated exactly on a polyhedral stand-in, the convex hull of
//! every vertex plus 162 evenly spread directions of length `r` (scaled to the ball's
//! volume), then scaled to the exact mass. `tests/hull.rs` measures the error on a
//! rounded box against its analytic inertia.

use crate::collision::shape::MassProperties;
use crate::math::{Mat3, Vec3};
use glam::{DMat3, DVec3};

/// Volume, first moment and covariance of a closed polyhedron (about the origin of the
/// vertex frame), plus its surface area.
struct Moments {
    volume: f64,
    first: DVec3,
    covariance: DMat3,
    area: f64,
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

fn moments(vertices: &[DVec3], loops: &[Vec<u16>], reference: DVec3) -> Moments {
    let mut m = Moments {
        volume: 0.0,
        first: DVec3::ZERO,
        covariance: DMat3::ZERO,
        area: 0.0,
    };
    for lp in loops {
        let a = vertices[lp[0] as usize] - reference;
        for k in 1..lp.len() - 1 {
            let b = vertices[lp[k] as usize] - reference;
            let c = vertices[lp[k + 1] as usize] - reference;
            let det = a.dot(b.cross(c));
            let s = a + b + c;
            m.volume += det / 6.0;
            m.first += s * (det / 24.0);
            m.covariance += (outer(a, a) + outer(b, b) + outer(c, c) + outer(s, s)) * (det / 120.0);
            m.area += 0.5 * (b - a).cross(c - a).length();
        }
    }
    // Back to the vertex frame's origin: ∫x = ∫(r + y), ∫x xᵀ = ∫(r + y)(r + y)ᵀ.
    let r = reference;
    let y = m.first;
    m.covariance += outer(r, y) + outer(y, r) + outer(r, r) * m.volume;
    m.first += r * m.volume;
    m
}

/// Mass properties at unit density from the moments: mass = volume, centre, and inertia
/// about the centre.
fn to_mass(m: &Moments) -> MassProperties {
    if m.volume <= 0.0 {
        return MassProperties::ZERO;
    }
    let c = m.first / m.volume;
    let cov = m.covariance - outer(c, c) * m.volume;
    let tr = cov.x_axis.x + cov.y_axis.y + cov.z_axis.z;
    let inertia = DMat3::from_diagonal(DVec3::splat(tr)) - cov;
    MassProperties {
        mass: m.volume as f32,
        center: c.as_vec3(),
        inertia: Mat3::from_cols(
            inertia.x_axis.as_vec3(),
            inertia.y_axis.as_vec3(),
            inertia.z_axis.as_vec3(),
        ),
    }
}

/// Exact mass properties at unit density of a closed polyhedron with outward
/// (counter-clockwise) face loops, and its surface area.
pub fn polyhedron_mass(vertices: &[Vec3], loops: &[Vec<u16>]) -> (MassProperties, f32) {
    let v: Vec<DVec3> = vertices.iter().map(|p| p.as_dvec3()).collect();
    let reference = v.iter().copied().sum::<DVec3>() / v.len().max(1) as f64;
    let m = moments(&v, loops, reference);
    (to_mass(&m), m.area as f32)
}

/// Exact volume of the hull grown by its radius (Steiner's formula).
pub fn rounded_volume(hull: &super::ConvexHull, core_volume: f64, area: f32) -> f64 {
    let r = hull.radius as f64;
    let mut mean_curvature = 0.0f64;
    for &e in &hull.edges {
        let he = hull.half_edges[e as usize];
        let twin = hull.half_edges[he.twin as usize];
        let n1 = hull.planes[he.face as usize].normal.as_dvec3();
        let n2 = hull.planes[twin.face as usize].normal.as_dvec3();
        let angle = n1.dot(n2).clamp(-1.0, 1.0).acos();
        let (a, b) = hull.edge_points(e as usize);
        mean_curvature += 0.5 * (b - a).as_dvec3().length() * angle;
    }
    core_volume + area as f64 * r + mean_curvature * r * r + 4.0 / 3.0 * std::f64::consts::PI * r * r * r
}

/// Directions spread evenly over the sphere (a Fibonacci lattice of 162 points, symmetric).
fn sphere_directions() -> Vec<DVec3> {
    // Half a lattice on the upper hemisphere and its mirror image through the centre, so
    // a centrally symmetric core keeps its centre.
    let n = SPHERE_DIRECTIONS;
    let golden = std::f64::consts::PI * (3.0 - 5.0f64.sqrt());
    let half: Vec<DVec3> = (0..n / 2)
        .map(|i| {
            let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - y * y).sqrt();
            let a = golden * i as f64;
            DVec3::new(r * a.cos(), y, r * a.sin())
        })
        .collect();
    half.iter().copied().chain(half.iter().map(|d| -*d)).collect()
}

/// Directions of the polyhedral ball in the rounded stand-in.
const SPHERE_DIRECTIONS: usize = 162;

/// Mass properties of the rounded hull at unit density (see the module doc).
pub fn rounded_mass(hull: &super::ConvexHull, core: MassProperties, area: f32) -> MassProperties {
    let r = hull.radius as f64;
    let dirs = sphere_directions();
    // Scale the direction polytope to the ball's volume.
    let unit_points: Vec<Vec3> = dirs.iter().map(|d| d.as_vec3()).collect();
    let unit_poly = super::builder::build_polyhedron(&unit_points, 0.0, usize::MAX);
    let poly_volume = unit_poly
        .as_ref()
        .map(|(v, l)| polyhedron_mass(v, l).0.mass as f64)
        .unwrap_or(4.0 / 3.0 * std::f64::consts::PI);
    let k = r * (4.0 / 3.0 * std::f64::consts::PI / poly_volume).cbrt();
    let mut points = Vec::with_capacity(hull.vertices.len() * dirs.len());
    for v in &hull.vertices {
        for d in &dirs {
            points.push((v.as_dvec3() + *d * k).as_vec3());
        }
    }
    let exact = rounded_volume(hull, core.mass as f64, area);
    let Some((pv, pl)) = super::builder::build_polyhedron(&points, 0.0, usize::MAX) else {
        // The stand-in cannot fail for a valid core; keep the core's distribution if it did.
        let s = (exact / core.mass as f64) as f32;
        return MassProperties {
            mass: exact as f32,
            center: core.center,
            inertia: core.inertia * s,
        };
    };
    let (mp, _) = polyhedron_mass(&pv, &pl);
    let s = (exact / mp.mass as f64) as f32;
    MassProperties {
        mass: exact as f32,
        center: mp.center,
        inertia: mp.inertia * s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(h: Vec3) -> (Vec<Vec3>, Vec<Vec<u16>>) {
        let v: Vec<Vec3> = (0..8)
            .map(|i| {
                Vec3::new(
                    if i & 1 != 0 { h.x } else { -h.x },
                    if i & 2 != 0 { h.y } else { -h.y },
                    if i & 4 != 0 { h.z } else { -h.z },
                )
            })
            .collect();
        // Counter-clockwise seen from outside.
        let loops = vec![
            vec![1, 3, 7, 5], // +x
            vec![0, 4, 6, 2], // -x
            vec![2, 6, 7, 3], // +y
            vec![0, 1, 5, 4], // -y
            vec![4, 5, 7, 6], // +z
            vec![0, 2, 3, 1], // -z
        ];
        (v, loops)
    }

    fn rel(a: f32, b: f32) -> f32 {
        (a - b).abs() / b.abs().max(1e-12)
    }

    #[test]
    fn box_matches_analytic() {
        let h = Vec3::new(1.0, 2.0, 3.0);
        let (mut v, loops) = cube(h);
        let shift = Vec3::new(5.0, -3.0, 2.0);
        for p in &mut v {
            *p += shift;
        }
        let (mp, area) = polyhedron_mass(&v, &loops);
        let m = 48.0;
        assert!(rel(mp.mass, m) < 1e-6);
        assert!((mp.center - shift).length() < 1e-5);
        assert!(rel(mp.inertia.x_axis.x, m / 12.0 * (16.0 + 36.0)) < 1e-5);
        assert!(rel(mp.inertia.y_axis.y, m / 12.0 * (4.0 + 36.0)) < 1e-5);
        assert!(rel(mp.inertia.z_axis.z, m / 12.0 * (4.0 + 16.0)) < 1e-5);
        assert!(mp.inertia.x_axis.y.abs() < 1e-4 && mp.inertia.x_axis.z.abs() < 1e-4);
        assert!(rel(area, 2.0 * (8.0 + 24.0 + 12.0)) < 1e-6);
    }
}

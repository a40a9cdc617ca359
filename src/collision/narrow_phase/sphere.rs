//! Sphere against sphere, capsule, box and plane. Always one point with id 0.

use super::geom::{closest_on_segment, single_point, WorldBox, WorldPlane, DEGENERATE_DIST_SQ, FALLBACK_NORMAL};
use super::Manifold;
use crate::math::Vec3;

/// Two spheres (or a sphere and a segment point): centres `ca`, `cb` with radii.
#[inline]
fn point_point(ca: Vec3, ra: f32, cb: Vec3, rb: f32, speculative: f32) -> Manifold {
    let offset = cb - ca;
    let dist_sq = offset.length_squared();
    let reach = ra + rb + speculative;
    if dist_sq > reach * reach {
        return Manifold::EMPTY;
    }
    let dist = dist_sq.sqrt();
    let normal = if dist_sq > DEGENERATE_DIST_SQ {
        offset / dist
    } else {
        FALLBACK_NORMAL
    };
    let separation = dist - ra - rb;
    // Midway between the surface points ca + ra n and cb - rb n.
    let point = 0.5 * (ca + cb + (ra - rb) * normal);
    single_point(normal, point, separation, 0, speculative)
}

/// Sphere A (world centre `ca`) against sphere B.
pub(crate) fn sphere_sphere(ca: Vec3, ra: f32, cb: Vec3, rb: f32, speculative: f32) -> Manifold {
    point_point(ca, ra, cb, rb, speculative)
}

/// Sphere A against capsule B (world segment `pb`–`qb`).
pub(crate) fn sphere_capsule(ca: Vec3, ra: f32, pb: Vec3, qb: Vec3, rb: f32, speculative: f32) -> Manifold {
    let cb = closest_on_segment(ca, pb, qb);
    point_point(ca, ra, cb, rb, speculative)
}

/// Sphere A against box B. A centre inside the box is pushed out through the nearest face.
pub(crate) fn sphere_box(ca: Vec3, ra: f32, b: &WorldBox, speculative: f32) -> Manifold {
    let c = b.apply_inv(ca);
    let h = b.half;
    let q = c.clamp(-h, h);
    let d = c - q;
    let dist_sq = d.length_squared();
    if dist_sq > DEGENERATE_DIST_SQ {
        // Centre outside the box: closest point on the surface.
        let reach = ra + speculative;
        if dist_sq > reach * reach {
            return Manifold::EMPTY;
        }
        let dist = dist_sq.sqrt();
        let n_box = d / dist; // box -> sphere, box frame
        let separation = dist - ra;
        let point = q + 0.5 * (dist - ra) * n_box;
        return single_point(-(b.rot * n_box), b.apply(point), separation, 0, speculative);
    }
    // Centre inside (or on) the box: least penetrating face.
    let depth = h - c.abs(); // distance to each face pair, >= 0
    let axis = if depth.x <= depth.y && depth.x <= depth.z {
        0
    } else if depth.y <= depth.z {
        1
    } else {
        2
    };
    let sign = if c[axis] >= 0.0 { 1.0 } else { -1.0 };
    let mut n_box = Vec3::ZERO;
    n_box[axis] = sign;
    let mut surface = c;
    surface[axis] = sign * h[axis];
    let separation = -depth[axis] - ra;
    // Sphere's deepest point is c - ra n; the box surface point is `surface`.
    let point = 0.5 * (surface + c - ra * n_box);
    single_point(-(b.rot * n_box), b.apply(point), separation, 0, speculative)
}

/// Sphere A against plane B.
pub(crate) fn sphere_plane(ca: Vec3, ra: f32, plane: &WorldPlane, speculative: f32) -> Manifold {
    let dist = plane.distance(ca);
    let separation = dist - ra;
    if separation > speculative {
        return Manifold::EMPTY;
    }
    // Plane surface at ca - dist n, sphere surface at ca - ra n.
    let point = ca - (0.5 * (dist + ra)) * plane.n;
    single_point(-plane.n, point, separation, 0, speculative)
}

#[cfg(test)]
mod tests {
    use super::super::collide_primitives as collide;
    use crate::collision::shape::Geometry;
    use crate::math::{Quat, Transform, Vec3};

    fn near(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-4
    }
    fn at(p: Vec3) -> Transform {
        Transform::new(p, Quat::IDENTITY)
    }
    fn sphere(r: f32) -> Geometry {
        Geometry::Sphere {
            center: Vec3::ZERO,
            radius: r,
        }
    }

    #[test]
    fn sphere_sphere_overlap_and_swap() {
        let (a, b) = (sphere(1.0), sphere(0.5));
        let m = collide(&a, &at(Vec3::ZERO), &b, &at(Vec3::new(1.4, 0.0, 0.0)), 0.0);
        assert_eq!(m.count, 1);
        assert!(near(m.normal, Vec3::X));
        assert!((m.points[0].separation + 0.1).abs() < 1e-5);
        // Surfaces at x=1.0 (A) and x=0.9 (B): midway 0.95.
        assert!(near(m.points[0].point, Vec3::new(0.95, 0.0, 0.0)));
        let s = collide(&b, &at(Vec3::new(1.4, 0.0, 0.0)), &a, &at(Vec3::ZERO), 0.0);
        assert!(near(s.normal, -Vec3::X));
        assert!(near(s.points[0].point, m.points[0].point));
    }

    #[test]
    fn sphere_sphere_speculative_and_coincident() {
        let a = sphere(0.5);
        let m = collide(&a, &at(Vec3::ZERO), &a, &at(Vec3::new(0.0, 0.0, 2.5)), 2.0);
        assert_eq!(m.count, 1);
        assert!((m.points[0].separation - 1.5).abs() < 1e-5);
        assert!(near(m.normal, Vec3::Z));
        assert_eq!(
            collide(&a, &at(Vec3::ZERO), &a, &at(Vec3::new(0.0, 0.0, 2.5)), 1.0).count,
            0
        );
        let c = collide(&a, &at(Vec3::ONE), &a, &at(Vec3::ONE), 0.0);
        assert_eq!(c.count, 1);
        assert!(c.normal.is_finite() && (c.normal.length() - 1.0).abs() < 1e-6);
        assert!((c.points[0].separation + 1.0).abs() < 1e-6);
    }

    #[test]
    fn sphere_offset_center_on_rotated_body() {
        // Sphere centre at local (1,0,0) on a body rotated 90° about Z: world (0,1,0).
        let a = Geometry::Sphere {
            center: Vec3::X,
            radius: 0.5,
        };
        let xf = Transform::new(Vec3::ZERO, Quat::from_rotation_z(std::f32::consts::FRAC_PI_2));
        let m = collide(&a, &xf, &sphere(0.5), &at(Vec3::new(0.0, 1.9, 0.0)), 0.0);
        assert_eq!(m.count, 1);
        assert!(near(m.normal, Vec3::Y));
        assert!((m.points[0].separation + 0.1).abs() < 1e-5);
    }

    #[test]
    fn sphere_capsule_side_and_end() {
        let cap = Geometry::Capsule {
            a: Vec3::new(-1.0, 0.0, 0.0),
            b: Vec3::new(1.0, 0.0, 0.0),
            radius: 0.25,
        };
        let s = sphere(0.5);
        let m = collide(&s, &at(Vec3::new(0.3, 0.7, 0.0)), &cap, &at(Vec3::ZERO), 0.0);
        assert_eq!(m.count, 1);
        assert!(near(m.normal, -Vec3::Y));
        assert!((m.points[0].separation + 0.05).abs() < 1e-5);
        assert!(near(m.points[0].point, Vec3::new(0.3, 0.225, 0.0)));
        // Swapped: capsule first, normal flips.
        let w = collide(&cap, &at(Vec3::ZERO), &s, &at(Vec3::new(0.3, 0.7, 0.0)), 0.0);
        assert!(near(w.normal, Vec3::Y) && near(w.points[0].point, m.points[0].point));
        // Beyond the end cap.
        let e = collide(&s, &at(Vec3::new(1.6, 0.0, 0.0)), &cap, &at(Vec3::ZERO), 0.0);
        assert!(near(e.normal, -Vec3::X));
        assert!((e.points[0].separation + 0.15).abs() < 1e-5);
        // Zero-length capsule centred on the sphere: finite unit normal.
        let z = Geometry::Capsule {
            a: Vec3::ZERO,
            b: Vec3::ZERO,
            radius: 0.25,
        };
        let d = collide(&s, &at(Vec3::ZERO), &z, &at(Vec3::ZERO), 0.0);
        assert_eq!(d.count, 1);
        assert!((d.normal.length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn sphere_box_face_edge_and_rotated() {
        let bx = Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::new(1.0, 0.5, 1.0),
        };
        let s = sphere(0.5);
        let m = collide(&s, &at(Vec3::new(0.2, 0.9, 0.0)), &bx, &at(Vec3::ZERO), 0.0);
        assert_eq!(m.count, 1);
        assert!(near(m.normal, -Vec3::Y));
        assert!((m.points[0].separation + 0.1).abs() < 1e-5);
        assert!(near(m.points[0].point, Vec3::new(0.2, 0.45, 0.0)));
        // Swapped order.
        let w = collide(&bx, &at(Vec3::ZERO), &s, &at(Vec3::new(0.2, 0.9, 0.0)), 0.0);
        assert!(near(w.normal, Vec3::Y) && (w.points[0].separation + 0.1).abs() < 1e-5);
        // Near an edge: diagonal normal.
        let e = collide(&s, &at(Vec3::new(1.3, 0.8, 0.0)), &bx, &at(Vec3::ZERO), 0.0);
        let dir = Vec3::new(-0.3, -0.3, 0.0).normalize();
        assert!(near(e.normal, dir));
        assert!((e.points[0].separation - (0.3 * 2f32.sqrt() - 0.5)).abs() < 1e-5);
        // Box rotated 90° about Z: its long axis is now world Y, so the top face is at y=1.
        let xf = Transform::new(Vec3::ZERO, Quat::from_rotation_z(std::f32::consts::FRAC_PI_2));
        let r = collide(&s, &at(Vec3::new(0.0, 1.4, 0.0)), &bx, &xf, 0.0);
        assert!(near(r.normal, -Vec3::Y));
        assert!((r.points[0].separation + 0.1).abs() < 1e-5);
    }

    #[test]
    fn sphere_inside_box_exits_nearest_face() {
        let bx = Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::new(1.0, 1.0, 1.0),
        };
        let s = sphere(0.25);
        let m = collide(&s, &at(Vec3::new(0.1, 0.0, -0.7)), &bx, &at(Vec3::ZERO), 0.0);
        assert_eq!(m.count, 1);
        // Nearest face is z = -1; the sphere leaves through it, so A->B normal is +Z.
        assert!(near(m.normal, Vec3::Z));
        assert!((m.points[0].separation + 0.55).abs() < 1e-5);
        // Surface point z=-1, deepest sphere point z=-0.45: midway -0.725.
        assert!(near(m.points[0].point, Vec3::new(0.1, 0.0, -0.725)));
        // Centre exactly at the box centre: still finite and unit.
        let c = collide(&s, &at(Vec3::ZERO), &bx, &at(Vec3::ZERO), 0.0);
        assert!((c.normal.length() - 1.0).abs() < 1e-6 && (c.points[0].separation + 1.25).abs() < 1e-5);
    }

    #[test]
    fn sphere_box_speculative() {
        let bx = Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::splat(0.5),
        };
        let s = sphere(0.5);
        let m = collide(&s, &at(Vec3::new(2.5, 0.0, 0.0)), &bx, &at(Vec3::ZERO), 2.0);
        assert_eq!(m.count, 1);
        assert!((m.points[0].separation - 1.5).abs() < 1e-5);
        assert!(near(m.normal, -Vec3::X));
        assert_eq!(
            collide(&s, &at(Vec3::new(2.5, 0.0, 0.0)), &bx, &at(Vec3::ZERO), 1.4).count,
            0
        );
    }

    #[test]
    fn sphere_plane_wall_speculative_and_rotated_plane() {
        // Wall x <= 0 expressed on a body: local plane +Y rotated to world -X... use identity first.
        let wall = Geometry::Plane {
            normal: Vec3::X,
            offset: 0.0,
        };
        let s = sphere(0.5);
        let m = collide(&s, &at(Vec3::new(2.0, 1.0, 0.0)), &wall, &Transform::IDENTITY, 2.0);
        assert_eq!(m.count, 1);
        assert!((m.points[0].separation - 1.5).abs() < 1e-5);
        assert!(near(m.normal, -Vec3::X)); // toward the wall
        assert!(near(m.points[0].point, Vec3::new(0.75, 1.0, 0.0)));
        assert_eq!(
            collide(&s, &at(Vec3::new(2.0, 1.0, 0.0)), &wall, &Transform::IDENTITY, 1.0).count,
            0
        );
        // Plane first: normal flips.
        let w = collide(&wall, &Transform::IDENTITY, &s, &at(Vec3::new(0.4, 0.0, 0.0)), 0.0);
        assert!(near(w.normal, Vec3::X) && (w.points[0].separation + 0.1).abs() < 1e-5);
        // Ground plane y <= 1 on a body translated by (0,1,0) and rotated about Y (normal unchanged).
        let ground = Geometry::Plane {
            normal: Vec3::Y,
            offset: 1.0,
        };
        let xf = Transform::new(Vec3::new(0.0, 1.0, 0.0), Quat::from_rotation_y(0.7));
        let g = collide(&s, &at(Vec3::new(3.0, 2.4, 0.0)), &ground, &xf, 0.0);
        assert!(near(g.normal, -Vec3::Y) && (g.points[0].separation + 0.1).abs() < 1e-5);
        assert!(near(g.points[0].point, Vec3::new(3.0, 1.95, 0.0)));
    }
}

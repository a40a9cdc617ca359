//! Box against plane: up to four of the deepest box vertices.

use super::geom::{push_point, WorldBox, WorldPlane};
use super::{Manifold, MAX_MANIFOLD_POINTS};

/// Box A against plane B. The feature id of a point is its box vertex index
/// (bit 0: +x, bit 1: +y, bit 2: +z corner of the box frame).
pub(crate) fn box_plane(a: &WorldBox, plane: &WorldPlane, speculative: f32) -> Manifold {
    let n = plane.n;
    // Vertex i = center + sum_k s_k h_k axis_k; its height is c0 + sum_k s_k e_k.
    let c0 = plane.distance(a.center);
    let e = [
        a.half.x * n.dot(a.rot.x_axis),
        a.half.y * n.dot(a.rot.y_axis),
        a.half.z * n.dot(a.rot.z_axis),
    ];
    // Early out on the lowest vertex.
    if c0 - e[0].abs() - e[1].abs() - e[2].abs() > speculative {
        return Manifold::EMPTY;
    }
    // Keep the deepest few (insertion into a sorted fixed array).
    let mut best = [(0.0f32, 0u32); MAX_MANIFOLD_POINTS];
    let mut count = 0usize;
    for i in 0..8u32 {
        let sx = if i & 1 != 0 { 1.0 } else { -1.0 };
        let sy = if i & 2 != 0 { 1.0 } else { -1.0 };
        let sz = if i & 4 != 0 { 1.0 } else { -1.0 };
        let sep = c0 + sx * e[0] + sy * e[1] + sz * e[2];
        if sep > speculative {
            continue;
        }
        let mut j = count.min(MAX_MANIFOLD_POINTS - 1);
        if count == MAX_MANIFOLD_POINTS && sep >= best[j].0 {
            continue;
        }
        while j > 0 && best[j - 1].0 > sep {
            best[j] = best[j - 1];
            j -= 1;
        }
        best[j] = (sep, i);
        count = (count + 1).min(MAX_MANIFOLD_POINTS);
    }
    let mut m = Manifold {
        normal: -n,
        ..Manifold::EMPTY
    };
    let (hx, hy, hz) = (
        a.rot.x_axis * a.half.x,
        a.rot.y_axis * a.half.y,
        a.rot.z_axis * a.half.z,
    );
    for &(sep, i) in &best[..count] {
        let sx = if i & 1 != 0 { hx } else { -hx };
        let sy = if i & 2 != 0 { hy } else { -hy };
        let sz = if i & 4 != 0 { hz } else { -hz };
        let v = a.center + sx + sy + sz;
        push_point(&mut m, v - (0.5 * sep) * n, sep, i);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::super::collide_primitives as collide;
    use crate::collision::shape::Geometry;
    use crate::math::{Quat, Transform, Vec3};
    use std::f32::consts::FRAC_PI_4;

    fn unit_box() -> Geometry {
        Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::splat(0.5),
        }
    }
    fn ground() -> Geometry {
        Geometry::Plane {
            normal: Vec3::Y,
            offset: 0.0,
        }
    }

    #[test]
    fn box_flat_on_plane_four_corners() {
        let xf = Transform::new(Vec3::new(1.0, 0.49, 2.0), Quat::IDENTITY);
        let m = collide(&unit_box(), &xf, &ground(), &Transform::IDENTITY, 0.02);
        assert_eq!(m.count, 4);
        assert!((m.normal - Vec3::NEG_Y).length() < 1e-6);
        let mut ids = [0u32; 4];
        for (k, p) in m.points().iter().enumerate() {
            assert!((p.separation + 0.01).abs() < 1e-5);
            assert!((p.point.y + 0.005).abs() < 1e-5);
            assert!(((p.point.x - 1.0).abs() - 0.5).abs() < 1e-5);
            assert!(((p.point.z - 2.0).abs() - 0.5).abs() < 1e-5);
            ids[k] = p.id;
        }
        ids.sort();
        assert_eq!(ids, [0, 1, 4, 5]); // the -y vertices
                                       // Swapped: plane first flips the normal, keeps the points.
        let s = collide(&ground(), &Transform::IDENTITY, &unit_box(), &xf, 0.02);
        assert_eq!(s.count, 4);
        assert!((s.normal - Vec3::Y).length() < 1e-6);
    }

    #[test]
    fn box_on_edge_on_plane_two_points() {
        let h = 0.5 * 2f32.sqrt();
        let xf = Transform::new(Vec3::new(0.0, h - 0.01, 0.0), Quat::from_rotation_z(FRAC_PI_4));
        let m = collide(&unit_box(), &xf, &ground(), &Transform::IDENTITY, 0.05);
        assert_eq!(m.count, 2);
        for p in m.points() {
            assert!((p.separation + 0.01).abs() < 1e-5);
            assert!(p.point.x.abs() < 1e-5 && (p.point.z.abs() - 0.5).abs() < 1e-5);
        }
        assert_ne!(m.points[0].id, m.points[1].id);
    }

    #[test]
    fn box_speculative_and_tilted_plane_body() {
        let xf = Transform::new(Vec3::new(0.0, 2.0, 0.0), Quat::IDENTITY);
        let m = collide(&unit_box(), &xf, &ground(), &Transform::IDENTITY, 2.0);
        // Bottom four at 1.5, top four at 2.5 (beyond speculative).
        assert_eq!(m.count, 4);
        assert!(m.points().iter().all(|p| (p.separation - 1.5).abs() < 1e-5));
        assert_eq!(collide(&unit_box(), &xf, &ground(), &Transform::IDENTITY, 1.0).count, 0);
        // Plane body rotated so the local +Y normal points to world +X (wall x <= -3).
        let wall_xf = Transform::new(
            Vec3::new(-3.0, 0.0, 0.0),
            Quat::from_rotation_z(-std::f32::consts::FRAC_PI_2),
        );
        let b = Transform::new(Vec3::new(-2.6, 0.0, 0.0), Quat::IDENTITY);
        let w = collide(&unit_box(), &b, &ground(), &wall_xf, 0.0);
        assert_eq!(w.count, 4);
        assert!((w.normal - Vec3::NEG_X).length() < 1e-5);
        assert!(w.points().iter().all(|p| (p.separation + 0.1).abs() < 1e-5));
        assert!(w.points().iter().all(|p| (p.point.x + 3.05).abs() < 1e-5));
    }

    #[test]
    fn box_on_corner_one_point_and_ids_stable() {
        // Corner down: rotate so the body diagonal is vertical.
        let q = Quat::from_rotation_arc(Vec3::ONE.normalize(), Vec3::NEG_Y);
        let d = 0.5 * 3f32.sqrt();
        let xf = Transform::new(Vec3::new(0.0, d - 0.02, 0.0), q);
        let m = collide(&unit_box(), &xf, &ground(), &Transform::IDENTITY, 0.01);
        assert_eq!(m.count, 1);
        assert_eq!(m.points[0].id, 7);
        assert!((m.points[0].separation + 0.02).abs() < 1e-5);
        let xf2 = Transform::new(Vec3::new(0.01, d - 0.021, 0.0), q);
        assert_eq!(
            collide(&unit_box(), &xf2, &ground(), &Transform::IDENTITY, 0.01).points[0].id,
            7
        );
    }
}

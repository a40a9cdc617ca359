use super::super::collide_primitives as collide;
use crate::collision::shape::Geometry;
use crate::math::{Quat, Transform, Vec3};
use std::f32::consts::FRAC_PI_2;

fn near(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-4
}
fn at(p: Vec3) -> Transform {
    Transform::new(p, Quat::IDENTITY)
}
fn cap_x(half_len: f32, r: f32) -> Geometry {
    Geometry::Capsule {
        a: Vec3::new(-half_len, 0.0, 0.0),
        b: Vec3::new(half_len, 0.0, 0.0),
        radius: r,
    }
}
fn unit(m: &super::Manifold) -> bool {
    m.normal.is_finite() && (m.normal.length() - 1.0).abs() < 1e-5
}

#[test]
fn capsules_crossed_one_point() {
    let a = cap_x(1.0, 0.25);
    let b = Geometry::Capsule {
        a: Vec3::new(0.0, 0.0, -1.0),
        b: Vec3::new(0.0, 0.0, 1.0),
        radius: 0.25,
    };
    let m = collide(&a, &at(Vec3::ZERO), &b, &at(Vec3::new(0.3, 0.45, 0.2)), 0.0);
    assert_eq!(m.count, 1);
    assert!(near(m.normal, Vec3::Y));
    assert!((m.points[0].separation + 0.05).abs() < 1e-5);
    assert!(near(m.points[0].point, Vec3::new(0.3, 0.225, 0.0)));
    let s = collide(&b, &at(Vec3::new(0.3, 0.45, 0.2)), &a, &at(Vec3::ZERO), 0.0);
    assert_eq!(s.count, 1);
    assert!(near(s.normal, -Vec3::Y) && near(s.points[0].point, m.points[0].point));
}

#[test]
fn capsules_side_by_side_two_points() {
    let a = cap_x(1.0, 0.25);
    // B shifted along x by 1.5 so the overlap is x in [0.5, 1]; 0.02 deep.
    let m = collide(&a, &at(Vec3::ZERO), &a, &at(Vec3::new(1.5, 0.0, 0.48)), 0.0);
    assert_eq!(m.count, 2);
    assert!(near(m.normal, Vec3::Z));
    let mut xs = [m.points[0].point.x, m.points[1].point.x];
    xs.sort_by(f32::total_cmp);
    assert!((xs[0] - 0.5).abs() < 1e-4 && (xs[1] - 1.0).abs() < 1e-4);
    for p in m.points() {
        assert!((p.separation + 0.02).abs() < 1e-5);
        assert!((p.point.z - 0.24).abs() < 1e-5);
    }
    assert_ne!(m.points[0].id, m.points[1].id);
    // Stacked vertically on a rotated body: B's axis is along Z locally, rotated onto X.
    let bz = Geometry::Capsule {
        a: Vec3::new(0.0, 0.0, -1.0),
        b: Vec3::new(0.0, 0.0, 1.0),
        radius: 0.25,
    };
    let xf = Transform::new(Vec3::new(0.0, 0.49, 0.0), Quat::from_rotation_y(FRAC_PI_2));
    let v = collide(&a, &at(Vec3::ZERO), &bz, &xf, 0.0);
    assert_eq!(v.count, 2);
    assert!(near(v.normal, Vec3::Y));
    assert!(v.points().iter().all(|p| (p.separation + 0.01).abs() < 1e-5));
}

#[test]
fn capsules_degenerate_and_speculative() {
    let a = cap_x(1.0, 0.25);
    // Identical coaxial capsules: finite unit normal, full depth.
    let m = collide(&a, &at(Vec3::ZERO), &a, &at(Vec3::ZERO), 0.0);
    assert!(m.count >= 1 && unit(&m));
    assert!(m.points().iter().all(|p| (p.separation + 0.5).abs() < 1e-5));
    // Zero-length capsules (spheres) at the same spot.
    let z = Geometry::Capsule {
        a: Vec3::ZERO,
        b: Vec3::ZERO,
        radius: 0.3,
    };
    let d = collide(&z, &at(Vec3::ONE), &z, &at(Vec3::ONE), 0.0);
    assert_eq!(d.count, 1);
    assert!(unit(&d) && (d.points[0].separation + 0.6).abs() < 1e-5);
    // Crossing axes through each other.
    let b = Geometry::Capsule {
        a: Vec3::new(0.0, 0.0, -1.0),
        b: Vec3::new(0.0, 0.0, 1.0),
        radius: 0.25,
    };
    let c = collide(&a, &at(Vec3::ZERO), &b, &at(Vec3::ZERO), 0.0);
    assert!(c.count == 1 && unit(&c));
    // Speculative: 1.5 m apart.
    let s = collide(&a, &at(Vec3::ZERO), &b, &at(Vec3::new(0.0, 2.0, 0.0)), 2.0);
    assert_eq!(s.count, 1);
    assert!((s.points[0].separation - 1.5).abs() < 1e-5 && near(s.normal, Vec3::Y));
    assert_eq!(
        collide(&a, &at(Vec3::ZERO), &b, &at(Vec3::new(0.0, 2.0, 0.0)), 1.0).count,
        0
    );
}

#[test]
fn capsule_plane_flat_standing_speculative() {
    let ground = Geometry::Plane {
        normal: Vec3::Y,
        offset: 0.0,
    };
    let a = cap_x(1.0, 0.25);
    let m = collide(&a, &at(Vec3::new(0.0, 0.24, 0.0)), &ground, &Transform::IDENTITY, 0.0);
    assert_eq!(m.count, 2);
    assert!(near(m.normal, -Vec3::Y));
    for p in m.points() {
        assert!((p.separation + 0.01).abs() < 1e-5);
        assert!((p.point.x.abs() - 1.0).abs() < 1e-5 && (p.point.y + 0.005).abs() < 1e-5);
    }
    // Standing: only the lower cap.
    let up = Transform::new(Vec3::new(0.0, 1.2, 0.0), Quat::from_rotation_z(FRAC_PI_2));
    let s = collide(&a, &up, &ground, &Transform::IDENTITY, 0.1);
    assert_eq!(s.count, 1);
    assert!((s.points[0].separation + 0.05).abs() < 1e-5);
    // Plane first; hovering within speculative.
    let w = collide(&ground, &Transform::IDENTITY, &a, &at(Vec3::new(0.0, 1.0, 0.0)), 1.0);
    assert_eq!(w.count, 2);
    assert!(near(w.normal, Vec3::Y) && w.points().iter().all(|p| (p.separation - 0.75).abs() < 1e-5));
    assert_eq!(
        collide(&a, &at(Vec3::new(0.0, 1.0, 0.0)), &ground, &Transform::IDENTITY, 0.5).count,
        0
    );
    // Zero-length capsule on the plane: one point.
    let z = Geometry::Capsule {
        a: Vec3::ZERO,
        b: Vec3::ZERO,
        radius: 0.25,
    };
    assert_eq!(
        collide(&z, &at(Vec3::new(0.0, 0.2, 0.0)), &ground, &Transform::IDENTITY, 0.0).count,
        1
    );
}

fn slab() -> Geometry {
    Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::new(0.5, 0.5, 0.5),
    }
}

#[test]
fn capsule_flat_on_box_two_clipped_points() {
    // Capsule of length 4 along X lying on a unit box: the clip keeps x in [-0.5, 0.5].
    let a = cap_x(2.0, 0.25);
    let m = collide(&a, &at(Vec3::new(0.0, 0.74, 0.1)), &slab(), &at(Vec3::ZERO), 0.0);
    assert_eq!(m.count, 2);
    assert!(near(m.normal, -Vec3::Y));
    let mut xs = [m.points[0].point.x, m.points[1].point.x];
    xs.sort_by(f32::total_cmp);
    assert!((xs[0] + 0.5).abs() < 1e-5 && (xs[1] - 0.5).abs() < 1e-5);
    for p in m.points() {
        assert!((p.separation + 0.01).abs() < 1e-5);
        assert!((p.point.y - 0.495).abs() < 1e-5 && (p.point.z - 0.1).abs() < 1e-5);
    }
    assert_ne!(m.points[0].id, m.points[1].id);
    // Swapped order: normal flips, points stay.
    let s = collide(&slab(), &at(Vec3::ZERO), &a, &at(Vec3::new(0.0, 0.74, 0.1)), 0.0);
    assert_eq!(s.count, 2);
    assert!(near(s.normal, Vec3::Y));
    // Short capsule entirely over the face: the end caps.
    let short = cap_x(0.3, 0.25);
    let t = collide(&short, &at(Vec3::new(0.0, 0.74, 0.0)), &slab(), &at(Vec3::ZERO), 0.0);
    assert_eq!(t.count, 2);
    let mut xs = [t.points[0].point.x, t.points[1].point.x];
    xs.sort_by(f32::total_cmp);
    assert!((xs[0] + 0.3).abs() < 1e-5 && (xs[1] - 0.3).abs() < 1e-5);
}

#[test]
fn capsule_box_end_near_corner_and_rotated_box() {
    // Capsule along X whose end is beyond the box corner (0.5, 0.5, 0.5).
    let a = cap_x(1.0, 0.25);
    let xf = at(Vec3::new(1.4, 0.6, 0.6));
    let m = collide(&a, &xf, &slab(), &at(Vec3::ZERO), 0.0);
    assert_eq!(m.count, 1);
    let offset = Vec3::new(0.0, 0.1, 0.1); // segment x in [0.4, 0.5] is 0.1 above and beside the edge y=z=0.5
    let dist = offset.length();
    assert!(near(m.normal, -offset / dist));
    assert!((m.points[0].separation - (dist - 0.25)).abs() < 1e-5);
    // Box rotated 45° about Y under a capsule along Z resting on its top face.
    let b = Geometry::Capsule {
        a: Vec3::new(0.0, 0.0, -0.2),
        b: Vec3::new(0.0, 0.0, 0.2),
        radius: 0.1,
    };
    let bxf = Transform::new(Vec3::ZERO, Quat::from_rotation_y(std::f32::consts::FRAC_PI_4));
    let r = collide(&b, &at(Vec3::new(0.0, 0.58, 0.0)), &slab(), &bxf, 0.0);
    assert_eq!(r.count, 2);
    assert!(near(r.normal, -Vec3::Y));
    assert!(r.points().iter().all(|p| (p.separation + 0.02).abs() < 1e-5));
}

#[test]
fn capsule_box_deep_and_speculative() {
    // Capsule axis passes through the box near its top: push out through +Y.
    let a = cap_x(1.0, 0.1);
    let m = collide(&a, &at(Vec3::new(0.0, 0.4, 0.0)), &slab(), &at(Vec3::ZERO), 0.0);
    assert!(m.count >= 1 && near(m.normal, -Vec3::Y));
    assert!(m.points().iter().all(|p| (p.separation + 0.2).abs() < 1e-4));
    // Standing capsule poking into the top face: one point at the lower end.
    let up = Transform::new(Vec3::new(0.1, 1.4, 0.0), Quat::from_rotation_z(FRAC_PI_2));
    let s = collide(&a, &up, &slab(), &at(Vec3::ZERO), 0.0);
    assert_eq!(s.count, 1);
    assert!(near(s.normal, -Vec3::Y) && (s.points[0].separation + 0.2).abs() < 1e-4);
    // Deep diagonal through the box: finite, unit and penetrating.
    let diag = Geometry::Capsule {
        a: Vec3::splat(-1.0),
        b: Vec3::splat(1.0),
        radius: 0.1,
    };
    let d = collide(&diag, &at(Vec3::ZERO), &slab(), &at(Vec3::ZERO), 0.0);
    assert!(d.count >= 1 && unit(&d) && d.points().iter().all(|p| p.separation < 0.0));
    // Hovering 1.5 m above the face.
    let h = collide(&a, &at(Vec3::new(0.0, 2.1, 0.0)), &slab(), &at(Vec3::ZERO), 2.0);
    assert_eq!(h.count, 2);
    assert!(h.points().iter().all(|p| (p.separation - 1.5).abs() < 1e-5) && near(h.normal, -Vec3::Y));
    assert_eq!(
        collide(&a, &at(Vec3::new(0.0, 2.1, 0.0)), &slab(), &at(Vec3::ZERO), 1.0).count,
        0
    );
}

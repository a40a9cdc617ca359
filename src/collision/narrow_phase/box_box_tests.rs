use super::super::{collide_primitives as collide, Manifold};
use super::{EDGE_FLAG, REF_ON_B_FLAG};
use crate::collision::shape::Geometry;
use crate::math::{Quat, Transform, Vec3};
use std::f32::consts::{FRAC_PI_4, FRAC_PI_6};

fn near(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).length() < tol
}
fn cube(h: f32) -> Geometry {
    Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::splat(h),
    }
}
fn slab() -> Geometry {
    Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::new(2.0, 0.5, 2.0),
    }
}
fn at(p: Vec3) -> Transform {
    Transform::new(p, Quat::IDENTITY)
}
fn sorted_ids(m: &Manifold) -> Vec<u32> {
    let mut ids: Vec<u32> = m.points().iter().map(|p| p.id).collect();
    ids.sort();
    ids
}
fn assert_distinct_ids(m: &Manifold) {
    let ids = sorted_ids(m);
    for w in ids.windows(2) {
        assert_ne!(w[0], w[1], "duplicate id in {m:?}");
    }
}
/// True when every point in `m` matches one point in `expected` (same count).
fn same_points(m: &Manifold, expected: &[Vec3], tol: f32) -> bool {
    m.count == expected.len()
        && expected
            .iter()
            .all(|e| m.points().iter().any(|p| near(p.point, *e, tol)))
}

#[test]
fn unit_box_resting_on_slab_gives_four_corners() {
    let top = at(Vec3::new(0.3, 0.99, -0.2));
    let m = collide(&cube(0.5), &top, &slab(), &at(Vec3::ZERO), 0.0);
    assert_eq!(m.count, 4);
    assert!(near(m.normal, -Vec3::Y, 1e-6));
    for p in m.points() {
        assert!((p.separation + 0.01).abs() < 1e-5);
    }
    let corners = [
        Vec3::new(-0.2, 0.495, -0.7),
        Vec3::new(0.8, 0.495, -0.7),
        Vec3::new(-0.2, 0.495, 0.3),
        Vec3::new(0.8, 0.495, 0.3),
    ];
    assert!(same_points(&m, &corners, 1e-5), "{m:?}");
    assert_distinct_ids(&m);
    // Swapped order: the slab is A, normal flips, same corners.
    let s = collide(&slab(), &at(Vec3::ZERO), &cube(0.5), &top, 0.0);
    assert!(near(s.normal, Vec3::Y, 1e-6));
    assert!(same_points(&s, &corners, 1e-5));
    assert!(s.points().iter().all(|p| (p.separation + 0.01).abs() < 1e-5));
}

#[test]
fn feature_ids_stable_when_moved_slightly() {
    let m1 = collide(
        &cube(0.5),
        &at(Vec3::new(0.3, 0.99, -0.2)),
        &slab(),
        &at(Vec3::ZERO),
        0.01,
    );
    let q = Quat::from_rotation_y(0.01);
    let m2 = collide(
        &cube(0.5),
        &Transform::new(Vec3::new(0.31, 0.985, -0.19), q),
        &slab(),
        &at(Vec3::ZERO),
        0.01,
    );
    assert_eq!(m1.count, 4);
    assert_eq!(sorted_ids(&m1), sorted_ids(&m2));
    // Partially over the slab edge: clipped vertices keep their ids too.
    let e1 = collide(
        &cube(0.5),
        &at(Vec3::new(1.8, 0.99, 0.0)),
        &slab(),
        &at(Vec3::ZERO),
        0.0,
    );
    let e2 = collide(
        &cube(0.5),
        &at(Vec3::new(1.75, 0.992, 0.02)),
        &slab(),
        &at(Vec3::ZERO),
        0.0,
    );
    assert_eq!(e1.count, 4);
    assert!(e1.points().iter().all(|p| p.point.x <= 2.0 + 1e-5));
    assert_distinct_ids(&e1);
    assert_eq!(sorted_ids(&e1), sorted_ids(&e2));
}

#[test]
fn whole_scene_rotated_is_rotated_manifold() {
    let q = Quat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.7);
    let rot = |p: Vec3| q * p;
    let top = at(Vec3::new(0.3, 0.99, -0.2));
    let base = collide(&cube(0.5), &top, &slab(), &at(Vec3::ZERO), 0.0);
    let m = collide(
        &cube(0.5),
        &Transform::new(rot(top.p), q),
        &slab(),
        &Transform::new(Vec3::ZERO, q),
        0.0,
    );
    assert!(near(m.normal, rot(base.normal), 1e-5));
    let expected: Vec<Vec3> = base.points().iter().map(|p| rot(p.point)).collect();
    assert!(same_points(&m, &expected, 1e-4));
    assert_eq!(sorted_ids(&m), sorted_ids(&base));
    // The same box expressed through the shape's own rotation and centre on a moved body.
    let qy = Quat::from_rotation_y(0.3);
    let body = Transform::new(Vec3::new(1.0, 0.0, 0.0), Quat::from_rotation_y(FRAC_PI_4));
    let local_c = body.apply_inv(Vec3::new(0.3, 0.99, -0.2));
    let shaped = Geometry::Box {
        center: local_c,
        rotation: body.q.conjugate() * qy,
        half_extents: Vec3::splat(0.5),
    };
    let n1 = collide(&shaped, &body, &slab(), &at(Vec3::ZERO), 0.0);
    let n2 = collide(
        &cube(0.5),
        &Transform::new(Vec3::new(0.3, 0.99, -0.2), qy),
        &slab(),
        &at(Vec3::ZERO),
        0.0,
    );
    assert_eq!(n1.count, 4);
    let expected: Vec<Vec3> = n2.points().iter().map(|p| p.point).collect();
    assert!(same_points(&n1, &expected, 1e-4) && near(n1.normal, n2.normal, 1e-5));
}

#[test]
fn rotated_45_on_equal_box_reduces_octagon_to_four() {
    // Top cube turned 45° about Y (its bottom is a diamond over the lower cube's square
    // top: their overlap is an octagon), tipped slightly so one side is deeper.
    let tilt = 0.02;
    let q = Quat::from_rotation_x(tilt) * Quat::from_rotation_y(FRAC_PI_4);
    let top = Transform::new(Vec3::new(0.0, 0.99, 0.0), q);
    // The tilt makes the upper cube's bottom face the reference (least penetration).
    let m = collide(&cube(0.5), &at(Vec3::ZERO), &cube(0.5), &top, 0.0);
    assert_eq!(m.count, 4);
    assert!(near(m.normal, q * Vec3::Y, 1e-5), "{m:?}");
    assert_distinct_ids(&m);
    // Brute force over the top cube's bottom face: deepest point inside the lower square.
    let mut deepest = f32::MAX;
    for a in 0..=200 {
        for b in 0..=200 {
            let local = Vec3::new(-0.5 + a as f32 / 200.0, -0.5, -0.5 + b as f32 / 200.0);
            let w = top.apply(local);
            if w.x.abs() <= 0.5 && w.z.abs() <= 0.5 {
                deepest = deepest.min(w.y - 0.5);
            }
        }
    }
    let min_sep = m.points().iter().map(|p| p.separation).fold(f32::MAX, f32::min);
    assert!((min_sep - deepest).abs() < 2e-3, "{min_sep} vs {deepest}");
    // Every point lies on the octagon: its two surface points are on the two faces, inside
    // both footprints.
    for p in m.points() {
        let on_a = p.point - 0.5 * p.separation * m.normal;
        let on_b = top.apply_inv(p.point + 0.5 * p.separation * m.normal);
        assert!((on_a.y - 0.5).abs() < 1e-4 && on_a.x.abs() <= 0.5 + 1e-4 && on_a.z.abs() <= 0.5 + 1e-4);
        assert!((on_b.y + 0.5).abs() < 1e-4 && on_b.x.abs() <= 0.5 + 1e-4 && on_b.z.abs() <= 0.5 + 1e-4);
    }
    // The four kept points span most of the octagon (area 0.828).
    let mut pts: Vec<Vec3> = m.points().iter().map(|p| p.point).collect();
    let c = pts.iter().fold(Vec3::ZERO, |s, p| s + *p) / 4.0;
    pts.sort_by(|a, b| (a.z - c.z).atan2(a.x - c.x).total_cmp(&(b.z - c.z).atan2(b.x - c.x)));
    let mut area = 0.0;
    for i in 0..4 {
        let (a, b) = (pts[i], pts[(i + 1) % 4]);
        area += 0.5 * (a.x * b.z - b.x * a.z);
    }
    assert!(area.abs() > 0.5, "area {area}");
}

#[test]
fn crossed_edges_give_one_point() {
    // Lower cube turned about Z (top edge along Z at y = sqrt(2)/2), upper about X (bottom
    // edge along X), overlapping by 0.05.
    let r = 0.5 * 2f32.sqrt();
    let a = Transform::new(Vec3::ZERO, Quat::from_rotation_z(FRAC_PI_4));
    let b = Transform::new(Vec3::new(0.0, 2.0 * r - 0.05, 0.0), Quat::from_rotation_x(FRAC_PI_4));
    let m = collide(&cube(0.5), &a, &cube(0.5), &b, 0.0);
    assert_eq!(m.count, 1);
    // Edge directions Z (A) and X (B): normal along Z x X = +Y, from A to B.
    assert!(near(m.normal, Vec3::Z.cross(Vec3::X), 1e-5));
    assert!((m.points[0].separation + 0.05).abs() < 1e-4);
    assert!(near(m.points[0].point, Vec3::new(0.0, r - 0.025, 0.0), 1e-4));
    assert!(m.points[0].id & EDGE_FLAG != 0);
    // Swapped.
    let s = collide(&cube(0.5), &b, &cube(0.5), &a, 0.0);
    assert!(near(s.normal, -Vec3::Y, 1e-5) && near(s.points[0].point, m.points[0].point, 1e-4));
    // Offset edges: the closest points are off-centre.
    let b2 = Transform::new(Vec3::new(0.2, 2.0 * r - 0.05, -0.1), Quat::from_rotation_x(FRAC_PI_4));
    let o = collide(&cube(0.5), &a, &cube(0.5), &b2, 0.0);
    assert_eq!(o.count, 1);
    assert!(near(o.points[0].point, Vec3::new(0.0, r - 0.025, -0.1), 1e-4), "{o:?}");
    assert_eq!(o.points[0].id, m.points[0].id);
}

#[test]
fn tilted_box_under_slab_uses_face_of_b() {
    // A turned 30° about Z: its top edge (two vertices) pokes 0.01 into B's bottom face.
    let a = Transform::new(Vec3::ZERO, Quat::from_rotation_z(FRAC_PI_6));
    let top = 0.5 * (FRAC_PI_6.sin() + FRAC_PI_6.cos());
    let b = at(Vec3::new(0.0, top + 0.5 - 0.01, 0.0));
    let m = collide(&cube(0.5), &a, &slab(), &b, 0.0);
    assert_eq!(m.count, 2);
    assert!(near(m.normal, Vec3::Y, 1e-5));
    let x = 0.5 * (FRAC_PI_6.cos() - FRAC_PI_6.sin());
    let expected = [Vec3::new(x, top - 0.005, 0.5), Vec3::new(x, top - 0.005, -0.5)];
    assert!(same_points(&m, &expected, 1e-4), "{m:?}");
    assert!(m
        .points()
        .iter()
        .all(|p| (p.separation + 0.01).abs() < 1e-5 && p.id & REF_ON_B_FLAG != 0));
    assert_distinct_ids(&m);
}

#[test]
fn speculative_and_separated() {
    let b = at(Vec3::new(2.5, 0.0, 0.0));
    let m = collide(&cube(0.5), &at(Vec3::ZERO), &cube(0.5), &b, 2.0);
    assert_eq!(m.count, 4);
    assert!(near(m.normal, Vec3::X, 1e-6));
    assert!(m
        .points()
        .iter()
        .all(|p| (p.separation - 1.5).abs() < 1e-5 && (p.point.x - 1.25).abs() < 1e-5));
    assert_eq!(collide(&cube(0.5), &at(Vec3::ZERO), &cube(0.5), &b, 1.4).count, 0);
    // Separated along an edge axis beyond speculative.
    let r = 0.5 * 2f32.sqrt();
    let a = Transform::new(Vec3::ZERO, Quat::from_rotation_z(FRAC_PI_4));
    let far = Transform::new(Vec3::new(0.0, 2.0 * r + 0.3, 0.0), Quat::from_rotation_x(FRAC_PI_4));
    assert_eq!(collide(&cube(0.5), &a, &cube(0.5), &far, 0.1).count, 0);
    let e = collide(&cube(0.5), &a, &cube(0.5), &far, 0.5);
    assert_eq!(e.count, 1);
    assert!((e.points[0].separation - 0.3).abs() < 1e-4 && near(e.normal, Vec3::Y, 1e-5));
}

#[test]
fn coincident_boxes_are_finite() {
    let m = collide(&cube(0.5), &at(Vec3::ONE), &cube(0.5), &at(Vec3::ONE), 0.0);
    assert!(m.count >= 1);
    assert!(m.normal.is_finite() && (m.normal.length() - 1.0).abs() < 1e-5);
    assert!(m
        .points()
        .iter()
        .all(|p| p.point.is_finite() && (p.separation + 1.0).abs() < 1e-4));
}

#[test]
fn equal_boxes_stacked_keep_ids_under_noise() {
    // Coincident corners: the incident vertices sit on the reference face's side planes,
    // so tiny noise decides whether they are clipped. Ids and count must not care.
    let base = collide(
        &cube(0.5),
        &at(Vec3::ZERO),
        &cube(0.5),
        &at(Vec3::new(0.0, 0.999, 0.0)),
        0.02,
    );
    assert_eq!(base.count, 4);
    assert_distinct_ids(&base);
    let ids = sorted_ids(&base);
    let mut seed = 12345u32;
    let mut rnd = |s: f32| {
        seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
        s * ((seed >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0)
    };
    for _ in 0..500 {
        let (dx, dz, yaw, tilt) = (rnd(3e-3), rnd(3e-3), rnd(3e-3), rnd(2e-4));
        let q = Quat::from_rotation_y(yaw) * Quat::from_rotation_x(tilt);
        let xf = Transform::new(Vec3::new(dx, 0.999, dz), q);
        let m = collide(&cube(0.5), &at(Vec3::ZERO), &cube(0.5), &xf, 0.02);
        assert_eq!(m.count, 4, "{m:?}");
        assert_eq!(sorted_ids(&m), ids, "{dx} {dz} {yaw} {tilt}");
        assert!(m.points().iter().all(|p| (p.separation + 0.001).abs() < 2e-4));
    }
}

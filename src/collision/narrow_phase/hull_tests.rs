//! Hull pairs: analytic cases (hull against box, hull, sphere, capsule and plane).

use super::{collide, Manifold};
use crate::collision::geometry_store::GeometryStore;
use crate::collision::hull::builder::{build, HullSettings};
use crate::collision::shape::Geometry;
use crate::math::{Quat, Transform, Vec3};

fn cube(h: f32) -> Vec<Vec3> {
    (0..8)
        .map(|i| {
            Vec3::new(
                if i & 1 != 0 { h } else { -h },
                if i & 2 != 0 { h } else { -h },
                if i & 4 != 0 { h } else { -h },
            )
        })
        .collect()
}

fn store_with(points: &[Vec3], radius: f32) -> (GeometryStore, Geometry) {
    let mut s = GeometryStore::new(1);
    let h = s.add_hull(
        build(
            points,
            &HullSettings {
                convex_radius: radius,
                ..Default::default()
            },
        )
        .unwrap(),
    );
    let g = Geometry::Hull {
        hull: h,
        local: Transform::IDENTITY,
        scale: 1.0,
    };
    (s, g)
}

fn at(p: Vec3) -> Transform {
    Transform::new(p, Quat::IDENTITY)
}

fn assert_face(m: &Manifold, normal: Vec3, count: usize, sep: f32) {
    assert_eq!(m.count, count, "{m:?}");
    assert!((m.normal - normal).length() < 1e-4, "normal {}", m.normal);
    for p in m.points() {
        assert!((p.separation - sep).abs() < 1e-4, "sep {} want {sep}", p.separation);
    }
}

#[test]
fn hull_cube_on_box_and_on_hull_cube() {
    let (store, g) = store_with(&cube(0.5), 0.0);
    let ground = Geometry::Box {
        center: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        half_extents: Vec3::new(5.0, 1.0, 5.0),
    };
    // Box A below, hull B above, 1 cm overlap.
    let m = collide(
        &store,
        &ground,
        &at(Vec3::new(0.0, -1.0, 0.0)),
        &g,
        &at(Vec3::new(0.0, 0.49, 0.0)),
        0.02,
    );
    assert_face(&m, Vec3::Y, 4, -0.01);
    // Reversed order flips the normal.
    let m = collide(
        &store,
        &g,
        &at(Vec3::new(0.0, 0.49, 0.0)),
        &ground,
        &at(Vec3::new(0.0, -1.0, 0.0)),
        0.02,
    );
    assert_face(&m, -Vec3::Y, 4, -0.01);
    // Hull on hull, separated by 1 cm (speculative).
    let m = collide(&store, &g, &at(Vec3::ZERO), &g, &at(Vec3::new(0.1, 1.01, 0.0)), 0.02);
    assert_face(&m, Vec3::Y, 4, 0.01);
    // Beyond the speculative distance: nothing.
    let m = collide(&store, &g, &at(Vec3::ZERO), &g, &at(Vec3::new(0.1, 1.05, 0.0)), 0.02);
    assert_eq!(m.count, 0);
}

#[test]
fn hull_on_plane_sphere_and_capsule() {
    let (store, g) = store_with(&cube(0.5), 0.0);
    let plane = Geometry::Plane {
        normal: Vec3::Y,
        offset: 0.0,
    };
    let m = collide(
        &store,
        &g,
        &at(Vec3::new(0.0, 0.49, 0.0)),
        &plane,
        &Transform::IDENTITY,
        0.02,
    );
    assert_face(&m, -Vec3::Y, 4, -0.01);
    let sphere = Geometry::Sphere {
        center: Vec3::ZERO,
        radius: 0.25,
    };
    let m = collide(
        &store,
        &sphere,
        &at(Vec3::new(0.2, 0.74, 0.0)),
        &g,
        &at(Vec3::ZERO),
        0.02,
    );
    assert_face(&m, -Vec3::Y, 1, -0.01);
    // Sphere beyond a corner: distance from GJK.
    let m = collide(&store, &sphere, &at(Vec3::new(0.8, 0.8, 0.8)), &g, &at(Vec3::ZERO), 0.5);
    let d = (3.0f32 * 0.09).sqrt() - 0.25;
    assert_eq!(m.count, 1);
    assert!((m.points[0].separation - d).abs() < 1e-4, "{m:?}");
    let cap = Geometry::Capsule {
        a: Vec3::new(-0.3, 0.0, 0.0),
        b: Vec3::new(0.3, 0.0, 0.0),
        radius: 0.1,
    };
    let m = collide(&store, &cap, &at(Vec3::new(0.0, 0.59, 0.1)), &g, &at(Vec3::ZERO), 0.02);
    assert_face(&m, -Vec3::Y, 2, -0.01);
}

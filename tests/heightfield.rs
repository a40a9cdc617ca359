//! Heightfields against truth: resting heights, seams, tunnelling, memory, the equivalent
//! mesh, holes, randomized drops on terrain.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
#[path = "terrain/mod.rs"]
mod terrain;
use terrain::{ball, body, cube, material, world};

use hearth::collision::narrow_phase::{collide_triangles, MeshManifolds};
use hearth::math::{Quat, Transform, Vec3};
use hearth::world::World;
use hearth::{BodyDef, BodyHandle, BodyType, Geometry, ShapeDef};

const DT: f32 = 1.0 / 60.0;

/// A static heightfield body: `rows × columns` samples, placed and scaled.
#[allow(clippy::too_many_arguments)]
fn static_heightfield(
    w: &mut World,
    rows: u32,
    columns: u32,
    heights: &[f32],
    holes: Option<&[bool]>,
    local: Transform,
    scale: Vec3,
    friction: f32,
) -> BodyHandle {
    let hf = w.create_heightfield(rows, columns, heights, holes).unwrap();
    let g = w.create_body(&BodyDef::default()).unwrap();
    w.create_shape(
        g,
        &material(friction),
        &Geometry::Heightfield {
            heightfield: hf,
            local,
            scale,
        },
    )
    .unwrap();
    g
}

/// A flat `cells × cells` heightfield of 1 m cells centred on the origin at y = 0.
fn flat(w: &mut World, cells: u32, friction: f32) -> BodyHandle {
    let n = cells + 1;
    let half = 0.5 * cells as f32;
    let local = Transform::new(Vec3::new(-half, 0.0, -half), Quat::IDENTITY);
    static_heightfield(w, n, n, &vec![0.0; (n * n) as usize], None, local, Vec3::ONE, friction)
}

fn run(w: &mut World, steps: usize) {
    for _ in 0..steps {
        w.step(DT).unwrap();
    }
}

#[test]
fn box_rests_on_heightfield_at_analytic_height() {
    let mut w = world();
    flat(&mut w, 8, 0.6);
    let b = body(&mut w, Vec3::new(0.3, 1.0, 0.2), Quat::IDENTITY, cube(0.5), 0.6);
    run(&mut w, 180);
    assert!((w.transform(b).unwrap().p.y - 0.5).abs() < 5.0e-3);
    // Spacing 0.5 m (scale x, z), heights 1 scaled by 2 (so 2 m), turned and raised 1 m:
    // the surface is at y = 3.
    let mut w = world();
    let local = Transform::new(Vec3::new(-2.0, 1.0, -2.0), Quat::from_rotation_y(0.3));
    static_heightfield(&mut w, 9, 9, &[1.0; 81], None, local, Vec3::new(0.5, 2.0, 0.5), 0.6);
    let b = body(&mut w, Vec3::new(-0.5, 3.6, 0.5), Quat::IDENTITY, cube(0.25), 0.6);
    run(&mut w, 180);
    assert!((w.transform(b).unwrap().p.y - 3.25).abs() < 5.0e-3);
    // A 20° slope (heights rising along x): a box sticks at 0.5 m from it along the normal.
    let mut w = world();
    let slope = 20.0f32.to_radians().tan();
    let heights: Vec<f32> = (0..121).map(|i| (i % 11) as f32 * slope).collect();
    static_heightfield(&mut w, 11, 11, &heights, None, Transform::IDENTITY, Vec3::ONE, 1.0);
    let q = Quat::from_rotation_z(20.0f32.to_radians());
    let n = q * Vec3::Y;
    let p0 = Vec3::new(5.0, 5.0 * slope, 5.0) + 0.52 * n;
    let b = body(&mut w, p0, q, cube(0.5), 1.0);
    run(&mut w, 240);
    let p = w.transform(b).unwrap().p - Vec3::new(5.0, 5.0 * slope, 5.0);
    assert!((p.dot(n) - 0.5).abs() < 5.0e-3, "{}", p.dot(n));
}

#[test]
fn box_slides_and_ball_rolls_across_heightfield_seams() {
    // The same limits as on the mesh: |v_y| < 1 cm/s sliding, < 1 mm off the surface rolling.
    for yaw in [0.0f32, 0.5] {
        let mut w = world();
        flat(&mut w, 64, 0.05);
        let b = body(
            &mut w,
            Vec3::new(-28.0, 0.5, -3.0),
            Quat::from_rotation_y(yaw),
            cube(0.5),
            0.05,
        );
        run(&mut w, 30);
        w.set_linear_velocity(b, 5.0 * Vec3::new(1.0, 0.0, 0.1).normalize())
            .unwrap();
        let mut max_vy = 0.0f32;
        for _ in 0..540 {
            w.step(DT).unwrap();
            max_vy = max_vy.max(w.linear_velocity(b).unwrap().y.abs());
        }
        assert!(w.transform(b).unwrap().p.x > -8.0);
        assert!(max_vy < 0.01, "yaw {yaw}: {max_vy}");
    }
    let mut w = world();
    flat(&mut w, 64, 0.6);
    let r = 0.5;
    let b = body(&mut w, Vec3::new(-25.0, r, -25.0), Quat::IDENTITY, ball(r), 0.6);
    run(&mut w, 30);
    let v = Vec3::new(3.5, 0.0, 3.6);
    w.set_linear_velocity(b, v).unwrap();
    w.set_angular_velocity(b, Vec3::Y.cross(-v) / -r).unwrap();
    let mut max_gap = 0.0f32;
    for _ in 0..480 {
        w.step(DT).unwrap();
        max_gap = max_gap.max(w.transform(b).unwrap().p.y - r);
    }
    assert!(max_gap < 1.0e-3, "{max_gap}");
}

#[test]
fn no_tunnelling_through_a_heightfield_at_100_m_s() {
    for g in [ball(0.25), cube(0.25)] {
        let mut w = world();
        flat(&mut w, 16, 0.6);
        let b = body(&mut w, Vec3::new(0.3, 4.0, 0.2), Quat::IDENTITY, g, 0.6);
        w.set_linear_velocity(b, Vec3::new(0.0, -100.0, 0.0)).unwrap();
        let mut lowest = f32::MAX;
        for _ in 0..90 {
            w.step(DT).unwrap();
            lowest = lowest.min(w.transform(b).unwrap().p.y);
        }
        assert!(lowest > 0.2, "{g:?}: {lowest}");
        assert!(w.transform(b).unwrap().p.y < 0.26);
    }
}

#[test]
fn a_million_samples_fit_in_eight_megabytes() {
    // 1024 × 1024 samples: 4 MiB of heights, the min/max pyramid (175 kB) and with holes a
    // bit per cell (131 kB): 4.37 MB, 4.50 MB with holes (the module doc's figures).
    let n = 1024u32;
    let heights: Vec<f32> = (0..n * n).map(|i| ((i % 97) as f32 * 0.1).sin()).collect();
    let holes: Vec<bool> = (0..(n - 1) * (n - 1)).map(|i| i % 13 == 0).collect();
    let mut w = world();
    let solid = w.create_heightfield(n, n, &heights, None).unwrap();
    let holed = w.create_heightfield(n, n, &heights, Some(&holes)).unwrap();
    let (a, b) = (
        w.heightfield(solid).unwrap().memory_bytes(),
        w.heightfield(holed).unwrap().memory_bytes(),
    );
    assert!(b <= 8_000_000, "{b}");
    assert!((4_365_000..4_375_000).contains(&a), "{a}");
    assert!((4_495_000..4_505_000).contains(&b), "{b}");
    assert_eq!(b - a, (n as usize - 1).pow(2).div_ceil(64) * 8);
}

#[test]
#[allow(clippy::approx_constant)] // 6.28 rather than 2π: the random poses the test was measured on
fn heightfield_contacts_equal_the_equivalent_mesh() {
    // The same random terrain as a heightfield (spacing and height scale on the shape) and as
    // a mesh of the scaled vertices: every shape at random poses near the surface gets the
    // same manifolds (normals within 1e-4, deepest separations within 1e-4 m).
    let cells = 24u32;
    let n = cells + 1;
    let heights = scenes::terrain_heights(cells, 11);
    let scale = Vec3::new(0.8, 0.6, 1.1);
    let mut w = world();
    let hf = w.create_heightfield(n, n, &heights, None).unwrap();
    let scaled: Vec<f32> = heights.iter().map(|h| h * scale.y).collect();
    let (mut v, t) = scenes::grid_mesh(cells, 1.0, &scaled);
    let half = 0.5 * cells as f32;
    for p in v.iter_mut() {
        *p = Vec3::new((p.x + half) * scale.x, p.y, (p.z + half) * scale.z);
    }
    let mesh = w.create_mesh(&v, &t).unwrap();
    let place = Transform::new(Vec3::new(1.0, -0.5, 2.0), Quat::from_rotation_y(0.7));
    let g_hf = Geometry::Heightfield {
        heightfield: hf,
        local: Transform::IDENTITY,
        scale,
    };
    let g_mesh = Geometry::Mesh {
        mesh,
        local: Transform::IDENTITY,
        scale: Vec3::ONE,
    };
    let hull = w
        .create_convex_hull(&scenes::cube_points(0.3), &Default::default())
        .unwrap();
    let shapes = [
        ball(0.4),
        cube(0.35),
        Geometry::Capsule {
            a: Vec3::new(-0.5, 0.0, 0.0),
            b: Vec3::new(0.5, 0.0, 0.0),
            radius: 0.25,
        },
        Geometry::Hull {
            hull,
            local: Transform::IDENTITY,
            scale: 1.0,
        },
    ];
    let mut seed = 3u32;
    let mut rnd = move || {
        seed = seed.wrapping_mul(1664525).wrapping_add(1013904223);
        (seed >> 8) as f32 / (1u32 << 24) as f32
    };
    let mut compared = 0;
    for trial in 0..400 {
        let g = shapes[trial % 4];
        let (x, z) = (2.0 + rnd() * 15.0, 2.0 + rnd() * 22.0);
        let (r, c) = ((z / scale.z) as usize, (x / scale.x) as usize);
        let ground = scaled[r * n as usize + c];
        let q = Quat::from_euler(glam::EulerRot::XYZ, 6.28 * rnd(), 6.28 * rnd(), 6.28 * rnd());
        let xf = place.mul(&Transform::new(Vec3::new(x, ground + 0.6 * rnd() - 0.1, z), q));
        let (mut a, mut b) = (MeshManifolds::EMPTY, MeshManifolds::EMPTY);
        collide_triangles(&w.geometry, &g, &xf, &g_hf, &place, 0.05, &mut a);
        collide_triangles(&w.geometry, &g, &xf, &g_mesh, &place, 0.05, &mut b);
        assert_eq!(a.count, b.count, "trial {trial} {g:?}");
        let deepest = |m: &hearth::collision::narrow_phase::Manifold| {
            m.points().iter().fold(f32::MAX, |s, p| s.min(p.separation))
        };
        for ma in a.as_slice() {
            let mb = b
                .as_slice()
                .iter()
                .find(|mb| mb.normal.dot(ma.normal) > 1.0 - 1.0e-4)
                .unwrap_or_else(|| panic!("trial {trial}: no mesh manifold along {}", ma.normal));
            assert!((deepest(ma) - deepest(mb)).abs() < 1.0e-4, "trial {trial}");
            compared += 1;
        }
    }
    assert!(compared > 150, "{compared}");
}

#[test]
fn holes_let_bodies_fall_through() {
    // A 10 × 10 flat heightfield with the middle 4 × 4 cells cut out: a box over the hole
    // falls through, one over solid ground rests.
    let n = 11u32;
    let holes: Vec<bool> = (0..100)
        .map(|i| (3..7).contains(&(i / 10)) && (3..7).contains(&(i % 10)))
        .collect();
    let mut w = world();
    static_heightfield(
        &mut w,
        n,
        n,
        &[0.0; 121],
        Some(&holes),
        Transform::IDENTITY,
        Vec3::ONE,
        0.6,
    );
    let over_hole = body(&mut w, Vec3::new(5.0, 1.0, 5.0), Quat::IDENTITY, cube(0.4), 0.6);
    let over_ground = body(&mut w, Vec3::new(1.5, 1.0, 1.5), Quat::IDENTITY, cube(0.4), 0.6);
    run(&mut w, 120);
    assert!(w.transform(over_hole).unwrap().p.y < -5.0);
    assert!((w.transform(over_ground).unwrap().p.y - 0.4).abs() < 5.0e-3);
}

#[test]
fn bad_heightfields_are_refused_and_nothing_is_stored() {
    let mut w = world();
    let h = vec![0.0f32; 16];
    for (rows, cols, heights, holes, what) in [
        (1u32, 16u32, h.clone(), None, "rows"),
        (4, 4, h[..15].to_vec(), None, "16 heights"),
        (4, 4, vec![f32::NAN; 16], None, "finite"),
        (4, 4, h.clone(), Some(vec![false; 8]), "one flag per cell"),
        (40000, 2, vec![], None, "rows"),
    ] {
        let e = w
            .create_heightfield(rows, cols, &heights, holes.as_deref())
            .unwrap_err();
        assert!(e.to_string().contains(what), "{e}");
    }
    assert_eq!(w.geometry.heightfield_count(), 0);
    let hf = w.create_heightfield(4, 4, &h, None).unwrap();
    let g = Geometry::Heightfield {
        heightfield: hf,
        local: Transform::IDENTITY,
        scale: Vec3::ONE,
    };
    let dynamic = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            ..Default::default()
        })
        .unwrap();
    let e = w.create_shape(dynamic, &ShapeDef::default(), &g).unwrap_err();
    assert!(e.to_string().contains("heightfield can only be attached"), "{e}");
    let st = w.create_body(&BodyDef::default()).unwrap();
    w.create_shape(st, &ShapeDef::default(), &g).unwrap();
    assert!(w
        .destroy_heightfield(hf)
        .unwrap_err()
        .to_string()
        .contains("used by 1 shape"));
    w.destroy_body(st).unwrap();
    w.destroy_heightfield(hf).unwrap();
}

#[test]
fn random_drops_on_heightfield_terrain() {
    terrain::random_drops(true);
}

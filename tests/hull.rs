//! Convex hulls (issue 13): the builder on random and degenerate clouds, mass properties
//! against analytic values and sampling, contacts against brute force, and hulls at rest.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use hearth::math::{Quat, Transform, Vec3};
use hearth::{BodyDef, BodyType, Geometry, HullSettings, ShapeDef, World};
use scenes::Rng;

const DT: f32 = 1.0 / 60.0;

/// A die: a cube hull of side 0.2 m with its edges bevelled (26 faces), like a real die.
fn die_points() -> Vec<Vec3> {
    let (h, b) = (0.1f32, 0.085f32);
    let mut pts = Vec::new();
    for &x in &[-1.0f32, 1.0] {
        for &y in &[-1.0f32, 1.0] {
            for &z in &[-1.0f32, 1.0] {
                pts.push(Vec3::new(x * h, y * b, z * b));
                pts.push(Vec3::new(x * b, y * h, z * b));
                pts.push(Vec3::new(x * b, y * b, z * h));
            }
        }
    }
    pts
}

#[test]
fn die_thrown_on_a_plane_lands_on_a_face_and_sleeps() {
    for seed in 1..=6u64 {
        let mut rng = Rng(seed * 7919);
        let mut w = scenes::world(true);
        scenes::ground_plane(&mut w);
        let die = w.create_convex_hull(&die_points(), &HullSettings::default()).unwrap();
        assert_eq!(w.convex_hull(die).unwrap().faces().len(), 26);
        let b = scenes::dynamic_hull(
            &mut w,
            die,
            Transform::new(Vec3::new(0.0, 1.0, 0.0), rng.quat()),
            &ShapeDef::default(),
        );
        w.set_linear_velocity(
            b,
            Vec3::new(rng.range(2.0, 4.0), rng.range(0.0, 2.0), rng.range(-1.0, 1.0)),
        )
        .unwrap();
        w.set_angular_velocity(b, rng.vec(15.0)).unwrap();
        let mut steps = 0;
        while w.is_awake(b).unwrap() && steps < 600 {
            w.step(DT).unwrap();
            let v = w.linear_velocity(b).unwrap();
            assert!(v.is_finite() && v.length() < 20.0, "seed {seed}: speed {v}");
            steps += 1;
        }
        let xf = w.transform(b).unwrap();
        assert!(!w.is_awake(b).unwrap(), "seed {seed}: the die did not sleep in 10 s");
        // On a face: one of the die's axes is vertical and the centre is at half height.
        let up = (0..3)
            .map(|k| (xf.q * Vec3::AXES[k]).dot(Vec3::Y).abs())
            .fold(0.0, f32::max);
        println!(
            "seed {seed}: slept after {steps} steps, up {up:.5}, height {:.5}",
            xf.p.y
        );
        assert!(up > 0.9999, "seed {seed}: not on a face (best axis {up})");
        assert!((xf.p.y - 0.1).abs() < 0.002, "seed {seed}: height {}", xf.p.y);
    }
}

/// Top displacement and awake count after `seconds` for a tower.
fn run_tower(w: &mut World, ids: &[hearth::BodyHandle], seconds: f32) -> (f32, f32) {
    let start: Vec<Vec3> = ids.iter().map(|&b| w.transform(b).unwrap().p).collect();
    for _ in 0..(seconds / DT) as usize {
        w.step(DT).unwrap();
    }
    let end: Vec<Vec3> = ids.iter().map(|&b| w.transform(b).unwrap().p).collect();
    let worst = start
        .iter()
        .zip(&end)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0, f32::max);
    let top = (start[ids.len() - 1] - end[ids.len() - 1]).length();
    (worst, top)
}

#[test]
fn ten_hull_cubes_stand_as_the_box_tower_does() {
    let mut boxes = scenes::world(true);
    let box_ids = scenes::tower(&mut boxes, 10);
    let (box_worst, box_top) = run_tower(&mut boxes, &box_ids, 10.0);
    let mut hulls = scenes::world(true);
    let hull_ids = scenes::hull_tower(&mut hulls, 10);
    let (hull_worst, hull_top) = run_tower(&mut hulls, &hull_ids, 10.0);
    println!("boxes: worst {box_worst:.5} top {box_top:.5}; hulls: worst {hull_worst:.5} top {hull_top:.5}");
    assert!(
        hull_top < 0.02 && hull_worst < 0.02,
        "hull tower moved {hull_worst} (top {hull_top})"
    );
    assert!((hull_top - box_top).abs() < 0.01, "top {hull_top} vs boxes {box_top}");
    assert_eq!(hulls.awake_body_count(), 0, "the hull tower did not sleep");
    assert_eq!(boxes.awake_body_count(), 0);
}

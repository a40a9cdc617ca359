use hearth::math::Vec3;
use hearth::scenes;
use hearth::{ShapeDef, World, WorldSettings};
fn main() {
    for (collide, spin) in [(false, true), (true, false), (true, true)] {
        let mut w = World::new(WorldSettings {
            gravity: Vec3::ZERO,
            enable_sleep: false,
            ..Default::default()
        })
        .unwrap();
        let mat = ShapeDef {
            restitution: 0.5,
            static_friction: 0.5,
            dynamic_friction: 0.3,
            ..ShapeDef::default()
        };
        let y = if collide { 0.0 } else { 50.0 };
        let a = scenes::dynamic_box(
            &mut w,
            Vec3::new(-3.0, 0.2, 0.0),
            Vec3::new(0.5, 0.3, 0.4),
            &mat,
        );
        let b = scenes::dynamic_sphere(&mut w, Vec3::new(3.0, -0.1 + y, 0.15), 0.4, &mat);
        w.set_linear_velocity(a, Vec3::new(4.0, 0.0, 0.0)).unwrap();
        if spin {
            w.set_angular_velocity(a, Vec3::new(0.0, 1.0, 2.0)).unwrap();
        }
        w.set_linear_velocity(b, Vec3::new(-3.0, 0.5, 0.0)).unwrap();
        let ids = [a, b];
        let total = |w: &World| {
            let mut l = Vec3::ZERO;
            for &h in &ids {
                let body = w.body(h).unwrap();
                l += body.center.cross(body.mass * body.v) + body.angular_momentum();
            }
            l
        };
        let l0 = total(&w);
        for i in 0..120 {
            w.step(1.0 / 60.0).unwrap();
            if i % 20 == 0 {
                println!(
                    "  {i}: L {} touching {}",
                    total(&w),
                    w.counters.touching_contacts
                );
            }
        }
        println!(
            "collide {collide} spin {spin}: L0 {l0} L1 {} rel {:.4}",
            total(&w),
            (total(&w) - l0).length() / l0.length()
        );
    }
}

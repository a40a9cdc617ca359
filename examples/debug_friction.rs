use hearth::math::{Quat, Transform, Vec3};
use hearth::scenes;
use hearth::{BodyDef, BodyType, Geometry, ShapeDef};
fn main() {
    let mu = 0.4f32;
    let theta = 35f32.to_radians();
    let mut w = scenes::world(false);
    let q = Quat::from_rotation_z(theta);
    let n = q * Vec3::Y;
    let g = w.create_body(&BodyDef::default()).unwrap();
    let mat = ShapeDef {
        static_friction: mu,
        dynamic_friction: mu,
        ..ShapeDef::default()
    };
    w.create_shape(
        g,
        &mat,
        &Geometry::Plane {
            normal: n,
            offset: 0.0,
        },
    )
    .unwrap();
    let b = w
        .create_body(&BodyDef {
            body_type: BodyType::Dynamic,
            transform: Transform::new(n * 0.5, q),
            allow_sleep: false,
            ..Default::default()
        })
        .unwrap();
    w.create_shape(
        b,
        &mat,
        &Geometry::Box {
            center: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            half_extents: Vec3::splat(0.5),
        },
    )
    .unwrap();
    let m = w.body(b).unwrap().mass;
    let h = 1.0 / 240.0;
    for i in 0..5 {
        w.step(1.0 / 60.0).unwrap();
        for (_, c) in w.contacts.iter() {
            let mut ln = 0.0;
            let lt = c.friction.tangent;
            for k in 0..c.manifold.count {
                ln += c.impulses[k].normal;
            }
            println!("step {i}: n {:?} count {} sum λn {:.4} (mg cos h = {:.4}) |λt| {:.4} ratio {:.4} sliding {:?} seps {:?}", c.manifold.normal, c.manifold.count, ln, m * 9.81 * theta.cos() * h, lt.length(), lt.length()/ln, c.friction.sliding, c.manifold.points.map(|p| p.separation));
        }
    }
}

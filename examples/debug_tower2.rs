use hearth::scenes;
use hearth::{World, WorldSettings};
fn main() {
    let n = 30;
    let mut w = World::new(WorldSettings {
        enable_sleep: false,
        ..Default::default()
    })
    .unwrap();
    let ids = scenes::tower(&mut w, n);
    for i in 0..300 {
        w.step(1.0 / 60.0).unwrap();
        if i < 12 || i % 20 == 19 {
            let t = w.transform(ids[n - 1]).unwrap();
            let t15 = w.transform(ids[15]).unwrap();
            let mut minsep = 0.0f32;
            for (_, c) in w.contacts.iter() {
                for p in c.manifold.points() {
                    minsep = minsep.min(p.separation);
                }
            }
            println!(
                "{i}: top {:.4} {:.4} {:.4} mid {:.4} {:.4} {:.4} vtop {:.3?} minsep {minsep:.4}",
                t.p.x,
                t.p.y - 29.5,
                t.p.z,
                t15.p.x,
                t15.p.y - 15.5,
                t15.p.z,
                w.linear_velocity(ids[n - 1]).unwrap()
            );
        }
    }
}

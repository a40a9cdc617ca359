use hearth::scenes;
use hearth::{World, WorldSettings};
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(30);
    for substeps in [4u32, 8, 16] {
        let mut w = World::new(WorldSettings {
            enable_sleep: false,
            substeps,
            ..Default::default()
        })
        .unwrap();
        let ids = scenes::tower(&mut w, n);
        let start: Vec<_> = ids.iter().map(|&b| w.transform(b).unwrap().p).collect();
        let mut vmax = 0.0f32;
        for i in 0..600 {
            w.step(1.0 / 60.0).unwrap();
            if i < 30 {
                vmax = vmax.max(w.linear_velocity(ids[n - 1]).unwrap().length());
            }
        }
        let worst = ids
            .iter()
            .zip(&start)
            .map(|(&b, s)| (w.transform(b).unwrap().p - *s).length())
            .fold(0.0, f32::max);
        let top = w.transform(ids[n - 1]).unwrap().p - start[n - 1];
        println!("substeps {substeps}: worst {worst:.4} top {top:.4?} early top speed {vmax:.3}");
    }
}

//! Quick wall-clock ms/step of the standard scenes (the criterion benches are the record).
use hearth::scenes;
use std::time::Instant;
fn run(name: &str, sleep: bool, steps: usize, build: &dyn Fn(&mut hearth::World)) {
    let sub: u32 = std::env::var("SUB").map(|v| v.parse().unwrap()).unwrap_or(4);
    let it: u32 = std::env::var("IT").map(|v| v.parse().unwrap()).unwrap_or(3);
    let mut w = hearth::World::new(hearth::WorldSettings {
        enable_sleep: sleep,
        substeps: sub,
        velocity_iterations: it,
        contact_hertz: 120.0,
        linear_slop: 0.0002,
        ..Default::default()
    })
    .unwrap();
    build(&mut w);
    let t = Instant::now();
    for _ in 0..steps {
        w.step(1.0 / 60.0).unwrap();
    }
    let ms = t.elapsed().as_secs_f64() * 1000.0 / steps as f64;
    println!(
        "{name:<28} sleep {:<5} {ms:8.3} ms/step  awake {} contacts {}",
        sleep,
        w.awake_body_count(),
        w.contact_count()
    );
}
fn main() {
    let filter = std::env::args().nth(1).unwrap_or_default();
    let all: Vec<(&str, bool, usize, Box<dyn Fn(&mut hearth::World)>)> = vec![
        (
            "pyramid",
            false,
            600,
            Box::new(|w| {
                scenes::pyramid(w, 10);
            }),
        ),
        (
            "pyramid",
            true,
            600,
            Box::new(|w| {
                scenes::pyramid(w, 10);
            }),
        ),
        (
            "pyramid_large",
            false,
            600,
            Box::new(|w| {
                scenes::pyramid(w, 20);
            }),
        ),
        (
            "pile",
            true,
            600,
            Box::new(|w| {
                scenes::pile(w, 4000);
            }),
        ),
        (
            "spheres_grid",
            false,
            600,
            Box::new(|w| {
                scenes::spheres_grid(w, 100);
            }),
        ),
    ];
    for (n, s, st, b) in all.iter() {
        if n.contains(filter.as_str()) {
            run(n, *s, *st, b.as_ref());
        }
    }
}

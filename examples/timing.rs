//! Quick wall-clock ms/step of the standard scenes, for development. The criterion benches in
//! `benches/` are the record. `cargo run --release --example timing [filter]`; the settings
//! can be varied with SUBSTEPS=n, ITERATIONS=n and LANES=4 (no AVX2), the run with STEPS=n (default 600) and
//! SLEEP=0/1 (only the scenes with sleep off/on; for profilers such as callgrind), the threads
//! with WORKERS=n (default 1). WINDOW=n also prints the ms/step of every n steps (a pile's
//! fall, landing and settling cost differently). The issue-13 scenes (`hull_pile`,
//! `terrain_mesh`, `terrain_heightfield`) are built as their benches build them; their
//! benches time the first 300 steps (STEPS=300).

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use hearth::{LaneWidth, World, WorldSettings};
use std::time::Instant;

type Build = fn(&mut World);

const SCENES: &[(&str, bool, Build)] = &[
    ("pyramid", false, |w| drop(scenes::pyramid(w, 10))),
    ("pyramid", true, |w| drop(scenes::pyramid(w, 10))),
    ("pyramid_large", false, |w| drop(scenes::pyramid(w, 20))),
    ("pile", true, |w| drop(scenes::pile(w, 4000))),
    ("pile_no_events", true, |w| {
        scenes::pile(w, 4000);
        scenes::set_events(w, false)
    }),
    ("pile_all_events", true, |w| {
        scenes::pile(w, 4000);
        scenes::set_events(w, true)
    }),
    ("spheres_grid", false, |w| drop(scenes::spheres_grid(w, 100))),
    ("hull_pile", true, |w| drop(scenes::hull_pile(w, 1000, 1))),
    ("terrain_mesh", true, |w| {
        scenes::terrain_mesh(w, 256, false, 1);
        scenes::terrain_drop(w, 1000, 8.0, 1);
    }),
    ("terrain_heightfield", true, |w| {
        scenes::terrain_heightfield(w, 256, false, 1);
        scenes::terrain_drop(w, 1000, 8.0, 1);
    }),
];

fn env(key: &str, default: u32) -> u32 {
    std::env::var(key).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn main() {
    let filter = std::env::args().nth(1).unwrap_or_default();
    let defaults = WorldSettings::default();
    let settings = WorldSettings {
        substeps: env("SUBSTEPS", defaults.substeps),
        velocity_iterations: env("ITERATIONS", defaults.velocity_iterations),
        lane_width: if env("LANES", 8) == 4 {
            LaneWidth::Four
        } else {
            LaneWidth::Auto
        },
        worker_count: env("WORKERS", 1),
        ..defaults
    };
    let steps = env("STEPS", 600);
    let window = env("WINDOW", 0);
    let sleep_filter = std::env::var("SLEEP").ok().map(|v| v == "1");
    // An exact scene name picks that scene alone; anything else is a substring filter.
    let exact = SCENES.iter().any(|s| s.0 == filter);
    let chosen = SCENES.iter().filter(|s| {
        let name_ok = if exact {
            s.0 == filter
        } else {
            s.0.contains(filter.as_str())
        };
        name_ok && sleep_filter.map_or(true, |f| f == s.1)
    });
    for &(name, sleep, build) in chosen {
        let mut w = World::new(WorldSettings {
            enable_sleep: sleep,
            ..settings
        })
        .unwrap();
        build(&mut w);
        let t = Instant::now();
        let mut windows = Vec::new();
        let mut since = Instant::now();
        for i in 0..steps {
            w.step(1.0 / 60.0).unwrap();
            if window > 0 && (i + 1) % window == 0 {
                windows.push(format!(
                    "{:.3}",
                    since.elapsed().as_secs_f64() * 1000.0 / f64::from(window)
                ));
                since = Instant::now();
            }
        }
        let ms = t.elapsed().as_secs_f64() * 1000.0 / f64::from(steps);
        println!(
            "{name:<14} sleep {sleep:<5} {ms:8.3} ms/step  awake {:5} contacts {:6}",
            w.awake_body_count(),
            w.contact_count()
        );
        if !windows.is_empty() {
            println!("{name:<14} ms/step per {window} steps: {}", windows.join(" "));
        }
    }
}

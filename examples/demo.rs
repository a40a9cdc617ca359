//! The main Hearth demo: a pyramid of boxes with spheres and boxes dropped onto it.
//!
//! Run with `cargo run --release --example demo`. It uses only the Rust API
//! (`hearth::World` and the shared scenes in `hearth::scenes`) and prints a line of
//! statistics every half second of simulated time, then a short summary.

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use hearth::{BodyHandle, ShapeDef, Vec3, World};
use std::time::Instant;

/// Fixed time step (s) and number of steps: 6 simulated seconds.
const DT: f32 = 1.0 / 60.0;
const STEPS: usize = 360;
/// Boxes per side in the bottom layer of the pyramid.
const BASE: usize = 6;
/// Print a status line every this many steps (0.5 s).
const REPORT_EVERY: usize = 30;

/// Adds the falling bodies: spheres and boxes above the four sides of the pyramid,
/// staggered in height so they land one after another. They miss the top box on purpose,
/// so the summary shows whether the pyramid itself stays standing.
fn drop_bodies(world: &mut World) -> Vec<BodyHandle> {
    let material = ShapeDef::default();
    let mut out = Vec::new();
    let sides = [(2.0, 0.0), (-2.0, 0.0), (0.0, 2.0), (0.0, -2.0)];
    for (i, &(x, z)) in sides.iter().enumerate() {
        let y = 9.0 + 1.5 * i as f32;
        let ball_at = Vec3::new(x, y, z);
        let box_at = Vec3::new(x * 0.6, y + 3.0, z * 0.6 + 0.3);
        let half = Vec3::splat(0.3);
        out.push(scenes::dynamic_sphere(world, ball_at, 0.4, &material));
        out.push(scenes::dynamic_box(world, box_at, half, &material));
    }
    out
}

/// Largest speed (m/s) and total kinetic energy (J) over `bodies`.
fn motion_stats(world: &World, bodies: &[BodyHandle]) -> (f32, f32) {
    bodies.iter().fold((0.0f32, 0.0f32), |(vmax, energy), &h| {
        let b = world.body(h).expect("live body");
        (vmax.max(b.v.length()), energy + b.kinetic_energy())
    })
}

fn main() {
    let mut world = scenes::world(true); // default settings, sleep on
    let pyramid = scenes::pyramid(&mut world, BASE);
    let dropped = drop_bodies(&mut world);
    let top = *pyramid.last().expect("pyramid has boxes"); // last box = the apex
    let top_start = world.transform(top).expect("top box").p;
    let all: Vec<BodyHandle> = pyramid.iter().chain(&dropped).copied().collect();

    println!("Hearth demo: a pyramid under falling debris");
    println!(
        "  pyramid of {} unit boxes (base {BASE}x{BASE}) on a static ground box,",
        pyramid.len()
    );
    println!(
        "  plus {} bodies (spheres r=0.4, boxes 0.6 m) dropped from 9-16.5 m onto its sides;",
        dropped.len()
    );
    let seconds = STEPS as f32 * DT;
    println!("  {STEPS} steps of dt = 1/60 s ({seconds:.1} s), sleep on, default solver settings.");
    println!("  top box starts at y = {:.3} m\n", top_start.y);
    println!(
        "{:>6} {:>6} {:>9} {:>10} {:>10} {:>12}",
        "t [s]", "awake", "contacts", "top y [m]", "vmax [m/s]", "KE [J]"
    );

    let mut step_time = 0.0f64; // seconds spent inside World::step
    for step in 1..=STEPS {
        let t0 = Instant::now();
        world.step(DT).expect("step failed");
        step_time += t0.elapsed().as_secs_f64();

        if step % REPORT_EVERY == 0 {
            let (vmax, energy) = motion_stats(&world, &all);
            println!(
                "{:>6.2} {:>6} {:>9} {:>10.4} {:>10.3} {:>12.2}",
                step as f32 * DT,
                world.awake_body_count(),
                world.contact_count(),
                world.transform(top).expect("top box").p.y,
                vmax,
                energy
            );
        }
    }

    // Summary: how far the apex moved, how many bodies rest, and the cost per step.
    let moved_cm = (world.transform(top).expect("top box").p - top_start).length() * 100.0;
    let asleep = all.len().saturating_sub(world.awake_body_count());
    let stood = moved_cm < 5.0;
    let verdict = if stood { "stood" } else { "did NOT stand" };
    println!("\nSummary");
    println!("  pyramid {verdict}: top box moved {moved_cm:.2} cm");
    println!("  {asleep} of {} dynamic bodies asleep", all.len());
    println!(
        "  {:.3} ms per step (mean over {STEPS} steps, wall clock)",
        step_time * 1000.0 / STEPS as f64
    );
}

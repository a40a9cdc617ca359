//! The main Hearth demo: a pyramid of boxes with spheres and boxes dropped onto it.
//!
//! Run with `cargo run --release --example demo`. It uses only the Rust API
//! (`hearth::World` and the shared scenes in `tests/scenes`) and prints a line of
//! statistics every second of simulated time, then a short summary. The spheres roll off
//! the pyramid and slow down by their rolling resistance; by the end every body sleeps
//! (`tests/rolling.rs` asserts it), and the demo exits with status 1 if one does not.

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use hearth::{BodyHandle, World};
use std::time::Instant;

/// Fixed time step (s) and number of steps: 16 simulated seconds.
const DT: f32 = 1.0 / 60.0;
const STEPS: usize = 960;
/// Boxes per side in the bottom layer of the pyramid.
const BASE: usize = 6;
/// Print a status line every this many steps (1 s).
const REPORT_EVERY: usize = 60;

/// Largest speed (m/s) and total kinetic energy (J) over `bodies`.
fn motion_stats(world: &World, bodies: &[BodyHandle]) -> (f32, f32) {
    bodies.iter().fold((0.0f32, 0.0f32), |(vmax, energy), &h| {
        let b = world.body(h).expect("live body");
        (vmax.max(b.v.length()), energy + b.kinetic_energy())
    })
}

fn main() {
    let mut world = scenes::world(true); // default settings, sleep on
    let (pyramid, dropped) = scenes::demo(&mut world, BASE);
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
    let mut all_asleep_at = None;
    for step in 1..=STEPS {
        let t0 = Instant::now();
        world.step(DT).expect("step failed");
        step_time += t0.elapsed().as_secs_f64();
        let asleep = all.iter().all(|&b| !world.is_awake(b).expect("live body"));
        if asleep && all_asleep_at.is_none() {
            all_asleep_at = Some(step as f32 * DT);
        } else if !asleep {
            all_asleep_at = None;
        }

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
    if let Some(t) = all_asleep_at {
        println!("  all asleep from t = {t:.2} s");
    }
    println!(
        "  {:.3} ms per step (mean over {STEPS} steps, wall clock)",
        step_time * 1000.0 / STEPS as f64
    );
    if asleep != all.len() || !stood {
        std::process::exit(1);
    }
}

//! The main Hearth demo: a pyramid of crates hit by falling bodies, through the C API.
//!
//! Run with `cargo run --release --example demo`. Hearth ships as a C library, so the demo
//! uses it the way a C or C++ program does: every call is an exported `hearth_*` function
//! (reached here through `hearth::capi`, the very functions `include/hearth.h` declares),
//! every result is checked, and state is read back in bulk into arrays the program owns.
//! `examples/c/pyramid.c` is the same idea in C.
//!
//! The scene: a static ground box, a pyramid of 91 one-metre crates (base 6 × 6) standing on
//! it, and eight bodies (four balls, four boxes) released above its four sides so that they
//! land one after another and bounce off. It prints what happens every half second in SI
//! units, then whether the pyramid stood and how many bodies fell asleep.
//!
//! The run is recorded for the viewer: `target/demo.hrec` (or the path given as the first
//! argument); open it with `viewer/index.html`.

use hearth::capi::body::*;
use hearth::capi::error::HearthResult;
use hearth::capi::record::*;
use hearth::capi::shape::*;
use hearth::capi::types::*;
use hearth::capi::world::*;
use hearth::capi::{hearth_last_error_message, hearth_result_name, hearth_version};
use std::ffi::{c_char, CStr, CString};
use std::time::Instant;

/// Fixed time step (s) and number of steps: 16 simulated seconds.
const DT: f32 = 1.0 / 60.0;
const STEPS: usize = 960;
/// Crates per side in the bottom layer of the pyramid.
const BASE: usize = 6;
/// Half the edge of a crate (m).
const H: f32 = 0.5;
/// Print a line every this many steps (1 s).
const REPORT_EVERY: usize = 60;
/// The falling balls' radius and the falling boxes' half edge (m).
const BALL_RADIUS: f32 = 0.4;
const BOX_HALF: f32 = 0.3;

/// Exits with the result's name and the library's message unless `result` is `HEARTH_OK`.
fn check(result: HearthResult, what: &str) {
    if result == HearthResult::HEARTH_OK {
        return;
    }
    let mut message = [0 as c_char; 256];
    // SAFETY: the buffer is writable for its length; the name is a static C string.
    let (name, detail) = unsafe {
        hearth_last_error_message(message.as_mut_ptr(), message.len());
        (
            CStr::from_ptr(hearth_result_name(result as i32)).to_string_lossy(),
            CStr::from_ptr(message.as_ptr()).to_string_lossy(),
        )
    };
    eprintln!("error: {what} failed: {name} ({detail})");
    std::process::exit(1);
}

fn vec3(x: f32, y: f32, z: f32) -> HearthVec3 {
    HearthVec3 { x, y, z }
}

const IDENTITY: HearthQuat = HearthQuat {
    x: 0.0,
    y: 0.0,
    z: 0.0,
    w: 1.0,
};

/// A body of `body_type` at `p` with one box or sphere shape of the default material
/// (density 1000 kg/m³, friction 0.6).
fn add_body(world: *mut HearthWorld, body_type: u32, p: HearthVec3, shape: Shape) -> HearthBodyId {
    let mut def = hearth_body_def_default(); // always start from the defaults
    def.r#type = body_type;
    def.transform.position = p;
    let mut body = HearthBodyId::default();
    let material = hearth_shape_def_default();
    let mut id = HearthShapeId::default();
    // SAFETY: `world` is live; every pointer is to a local that outlives the call.
    unsafe {
        check(hearth_body_create(world, &def, &mut body), "hearth_body_create");
        match shape {
            Shape::Box(half) => {
                let b = HearthBox {
                    center: vec3(0.0, 0.0, 0.0),
                    rotation: IDENTITY,
                    half_extents: half,
                };
                check(
                    hearth_shape_create_box(world, body, &material, &b, &mut id),
                    "hearth_shape_create_box",
                );
            }
            Shape::Ball(radius) => {
                let s = HearthSphere {
                    center: vec3(0.0, 0.0, 0.0),
                    radius,
                };
                check(
                    hearth_shape_create_sphere(world, body, &material, &s, &mut id),
                    "hearth_shape_create_sphere",
                );
            }
        }
    }
    body
}

enum Shape {
    Box(HearthVec3),
    Ball(f32),
}

/// The static ground: a 80 × 2 × 80 m box whose top face is at y = 0.
fn add_ground(world: *mut HearthWorld) {
    add_body(
        world,
        HEARTH_BODY_STATIC,
        vec3(0.0, -1.0, 0.0),
        Shape::Box(vec3(40.0, 1.0, 40.0)),
    );
}

/// The pyramid, bottom layer first; the last crate is the top one.
fn add_pyramid(world: *mut HearthWorld) -> Vec<HearthBodyId> {
    let mut crates = Vec::new();
    for layer in 0..BASE {
        let n = BASE - layer;
        let offset = -(n as f32 - 1.0) * H;
        for i in 0..n {
            for k in 0..n {
                let p = vec3(
                    offset + 2.0 * H * i as f32,
                    H + 2.0 * H * layer as f32,
                    offset + 2.0 * H * k as f32,
                );
                crates.push(add_body(world, HEARTH_BODY_DYNAMIC, p, Shape::Box(vec3(H, H, H))));
            }
        }
    }
    crates
}

/// A ball and a box above each side of the pyramid, staggered in height so they land one
/// after another. They miss the top crate on purpose: the summary shows whether the
/// pyramid itself stands.
fn add_falling_bodies(world: *mut HearthWorld) -> Vec<HearthBodyId> {
    let mut out = Vec::new();
    let sides = [(2.0, 0.0), (-2.0, 0.0), (0.0, 2.0), (0.0, -2.0)];
    for (i, &(x, z)) in sides.iter().enumerate() {
        let y = 9.0 + 1.5 * i as f32;
        out.push(add_body(
            world,
            HEARTH_BODY_DYNAMIC,
            vec3(x, y, z),
            Shape::Ball(BALL_RADIUS),
        ));
        let b = vec3(x * 0.6, y + 3.0, z * 0.6 + 0.3);
        out.push(add_body(
            world,
            HEARTH_BODY_DYNAMIC,
            b,
            Shape::Box(vec3(BOX_HALF, BOX_HALF, BOX_HALF)),
        ));
    }
    out
}

/// What is printed every second.
struct Snapshot {
    top_y: f32,
    fastest: f32,
    kinetic_energy: f64,
    awake: u32,
    contacts: u32,
}

/// Reads the state of `bodies` (masses in `masses`) with one bulk transform read and a
/// velocity per body. The kinetic energy is that of translation, ½ m v² (J).
fn snapshot(
    world: *mut HearthWorld,
    bodies: &[HearthBodyId],
    masses: &[f32],
    poses: &mut [HearthTransform],
) -> Snapshot {
    let mut counters = HearthWorldCounters::default();
    let mut fastest = 0.0f32;
    let mut kinetic_energy = 0.0f64;
    // SAFETY: `world` is live; `poses` has room for every body; outputs are locals.
    unsafe {
        check(
            hearth_world_get_transforms(world, bodies.as_ptr(), bodies.len(), poses.as_mut_ptr()),
            "hearth_world_get_transforms",
        );
        check(
            hearth_world_get_counters(world, &mut counters),
            "hearth_world_get_counters",
        );
        for (&body, &mass) in bodies.iter().zip(masses) {
            let mut v = HearthVec3::default();
            check(
                hearth_body_get_linear_velocity(world, body, &mut v),
                "hearth_body_get_linear_velocity",
            );
            let speed_sq = v.x * v.x + v.y * v.y + v.z * v.z;
            fastest = fastest.max(speed_sq.sqrt());
            kinetic_energy += 0.5 * mass as f64 * speed_sq as f64;
        }
    }
    Snapshot {
        top_y: poses[BASE * (BASE + 1) * (2 * BASE + 1) / 6 - 1].position.y,
        fastest,
        kinetic_energy,
        awake: counters.awake_body_count,
        contacts: counters.touching_contact_count,
    }
}

fn mass_of(world: *mut HearthWorld, body: HearthBodyId) -> f32 {
    let mut mass = 0.0f32;
    // SAFETY: `world` is live; `mass` is a local.
    unsafe { check(hearth_body_get_mass(world, body, &mut mass), "hearth_body_get_mass") };
    mass
}

fn main() {
    let version = hearth_version();
    let def = hearth_world_def_default(); // gravity (0, -9.81, 0) m/s², 6 sub-steps, sleep on
    let mut world: *mut HearthWorld = std::ptr::null_mut();
    // SAFETY: `def` and `world` are locals that outlive the call.
    unsafe { check(hearth_world_create(&def, &mut world), "hearth_world_create") };

    add_ground(world);
    let crates = add_pyramid(world);
    let falling = add_falling_bodies(world);
    let bodies: Vec<HearthBodyId> = crates.iter().chain(&falling).copied().collect();
    let masses: Vec<f32> = bodies.iter().map(|&b| mass_of(world, b)).collect();
    let mut poses = vec![
        HearthTransform {
            position: vec3(0.0, 0.0, 0.0),
            rotation: IDENTITY,
        };
        bodies.len()
    ];
    let start = snapshot(world, &bodies, &masses, &mut poses);
    let top = *crates.last().expect("the pyramid has crates");
    let top_start = poses[crates.len() - 1].position;
    let recording = start_recording(world);

    println!(
        "Hearth {}.{}.{} demo: a pyramid of crates hit by falling bodies, through the C API\n",
        version >> 16,
        (version >> 8) & 0xFF,
        version & 0xFF
    );
    println!("Scene (SI units: metres, kilograms, seconds, joules; y is up)");
    println!("  ground   a static box, its top face at y = 0 m");
    println!(
        "  pyramid  {} crates, 1 m cubes of {:.0} kg, {BASE} x {BASE} at the bottom; the top crate at y = {:.2} m",
        crates.len(),
        masses[0],
        top_start.y
    );
    println!(
        "  falling  4 balls (radius {BALL_RADIUS} m, {:.0} kg) and 4 boxes ({} m, {:.0} kg), released 9 to 16.5 m up",
        masses[crates.len()],
        2.0 * BOX_HALF,
        masses[crates.len() + 1]
    );
    println!(
        "  gravity  9.81 m/s² down; {STEPS} steps of 1/60 s = {:.1} s; sleep on\n",
        STEPS as f32 * DT
    );
    println!("What to look for: the falling bodies reach the pyramid between 1 and 2 s, when the");
    println!(
        "fastest speed and the kinetic energy peak; the top crate stays at {:.2} m (the",
        top_start.y
    );
    println!("pyramid stands); then the energy dies away and the bodies come to rest and sleep.\n");
    println!(
        "{:>6} {:>10} {:>9} {:>12} {:>8} {:>9}",
        "time", "top crate", "fastest", "kinetic", "awake", "touching"
    );
    println!(
        "{:>6} {:>10} {:>9} {:>12} {:>8} {:>9}",
        "[s]", "y [m]", "[m/s]", "energy [J]", "bodies", "contacts"
    );
    let line = |t: f32, s: &Snapshot| {
        println!(
            "{:>6.2} {:>10.3} {:>9.2} {:>12.0} {:>5}/{:<2} {:>9}",
            t,
            s.top_y,
            s.fastest,
            s.kinetic_energy,
            s.awake,
            bodies.len(),
            s.contacts
        );
    };
    line(0.0, &start);

    let mut step_seconds = 0.0f64; // wall-clock time spent inside hearth_world_step
    let mut all_asleep_at = None; // when the last body fell asleep (and none woke since)
    for step in 1..=STEPS {
        let t0 = Instant::now();
        // SAFETY: `world` is live.
        unsafe { check(hearth_world_step(world, DT), "hearth_world_step") };
        step_seconds += t0.elapsed().as_secs_f64();
        let snap = (step % REPORT_EVERY == 0 || all_asleep_at.is_none())
            .then(|| snapshot(world, &bodies, &masses, &mut poses));
        if let Some(s) = &snap {
            if s.awake == 0 && all_asleep_at.is_none() {
                all_asleep_at = Some(step as f32 * DT);
            } else if s.awake != 0 {
                all_asleep_at = None;
            }
        }
        if step % REPORT_EVERY == 0 {
            line(step as f32 * DT, snap.as_ref().expect("taken on report steps"));
        }
    }

    // Summary: how far the top crate moved, how many bodies sleep, the cost per step.
    let mut top_end = HearthTransform {
        position: vec3(0.0, 0.0, 0.0),
        rotation: IDENTITY,
    };
    let mut asleep = 0;
    // SAFETY: `world` is live; outputs are locals.
    unsafe {
        check(
            hearth_body_get_transform(world, top, &mut top_end),
            "hearth_body_get_transform",
        );
        for &body in &bodies {
            let mut awake = true;
            check(hearth_body_is_awake(world, body, &mut awake), "hearth_body_is_awake");
            asleep += usize::from(!awake);
        }
    }
    let (dx, dy, dz) = (
        top_end.position.x - top_start.x,
        top_end.position.y - top_start.y,
        top_end.position.z - top_start.z,
    );
    let moved_cm = (dx * dx + dy * dy + dz * dz).sqrt() * 100.0;
    println!("\nSummary");
    if moved_cm < 5.0 {
        println!("  the pyramid stood: the top crate moved {moved_cm:.2} cm");
    } else {
        println!("  the pyramid did NOT stand: the top crate moved {moved_cm:.2} cm");
    }
    println!("  asleep at the end: {asleep} of {} bodies", bodies.len());
    if let Some(t) = all_asleep_at {
        println!("  all asleep from t = {t:.2} s (round bodies stop by their rolling resistance)");
    }
    println!(
        "  {:.3} ms per step (wall clock, mean of {STEPS} steps)",
        step_seconds * 1000.0 / STEPS as f64
    );
    // SAFETY: `world` is live and not used afterwards.
    // SAFETY: `world` is the live world created above.
    unsafe { check(hearth_world_record_stop(world), "hearth_world_record_stop") };
    println!(
        "\nRecorded to {} — open it with viewer/index.html (file picker or drag and drop).",
        recording
    );
    unsafe { hearth_world_destroy(world) };
    // A demo that does not come to rest, or a pyramid that falls, is a bug: say so to CI.
    if asleep != bodies.len() || moved_cm >= 5.0 {
        eprintln!("error: the scene did not come to rest with the pyramid standing");
        std::process::exit(1);
    }
}

/// Starts recording the world into the path given as the first argument, or `target/demo.hrec`.
fn start_recording(world: *mut HearthWorld) -> String {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/target/demo.hrec").to_string());
    let c_path = CString::new(path.clone()).expect("a path without NUL bytes");
    let def = hearth_record_def_default();
    // SAFETY: `world` is live; `c_path` and `def` outlive the call.
    unsafe {
        check(
            hearth_world_record_start_file(world, c_path.as_ptr(), &def),
            "hearth_world_record_start_file",
        )
    };
    path
}

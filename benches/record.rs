//! What recording costs (issue 17): the pile (4,000 spheres and boxes, sleep on, 600 steps at
//! dt = 1/60) stepped plainly and stepped with a `Recorder` whose bytes are copied out after
//! every step (what the C layer does before writing them to a file or a host callback).
//!
//! Before the criterion groups it prints, from one recorded run: the recording's size, bytes
//! per body per step, bytes per written body record, and the time spent in `record_step` as a
//! share of the time spent in `step` in the same run (so a busy machine slows both alike).
//!
//! `cargo bench --bench record`. With `HEARTH_RECORD_REPORT_STEPS=n` only the report runs, for
//! n steps (repeatable instruction counts: run the bench binary under
//! `valgrind --tool=callgrind` and compare the inclusive cost of `Recorder::record_step` with
//! that of `World::step`).

#[path = "../tests/scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use hearth::record::{read, RecordOptions, Recorder};
use hearth::World;
use std::time::{Duration, Instant};

const STEPS: u64 = 600;
const DT: f32 = 1.0 / 60.0;
const BODIES: usize = 4000;

fn pile() -> World {
    let mut w = scenes::world(true);
    scenes::pile(&mut w, BODIES);
    w
}

fn report(contacts: bool, steps: u64) {
    let mut w = pile();
    let mut rec = Recorder::new(&w, RecordOptions { contacts });
    let mut bytes = rec.bytes().to_vec();
    rec.clear();
    let (mut stepping, mut recording) = (Duration::ZERO, Duration::ZERO);
    for _ in 0..steps {
        let t = Instant::now();
        w.step(DT).unwrap();
        let t1 = Instant::now();
        rec.record_step(&w, DT, (t1 - t).as_secs_f32());
        recording += t1.elapsed();
        stepping += t1 - t;
        bytes.extend_from_slice(rec.bytes());
        rec.clear();
    }
    let r = read::parse(&bytes).unwrap();
    let records: usize = r.frames[1..].iter().map(|f| f.bodies.len()).sum();
    let step_bytes: usize = {
        // Bytes of the step chunks after frame 0 (the definitions and frame 0 are one-off).
        let mut at = 16usize;
        let mut total = 0usize;
        let mut frame = 0;
        while at < bytes.len() {
            let len = u32::from_le_bytes(bytes[at + 4..at + 8].try_into().unwrap()) as usize;
            if &bytes[at..at + 4] == b"STEP" {
                if frame > 0 {
                    total += 8 + len;
                }
                frame += 1;
            }
            at += 8 + len;
        }
        total
    };
    let per_body_step = step_bytes as f64 / (BODIES as f64 * steps as f64);
    let share = 100.0 * recording.as_secs_f64() / stepping.as_secs_f64();
    let ms = |d: Duration| 1e3 * d.as_secs_f64() / steps as f64;
    if contacts {
        println!(
            "pile {BODIES} bodies, {steps} steps, contacts on: {:.1} MB; {per_body_step:.2} bytes per body per step; \
             recording took {share:.1} % of the step time ({:.2} of {:.2} ms/step)",
            bytes.len() as f64 / 1e6,
            ms(recording),
            ms(stepping),
        );
    } else {
        // A step chunk's fixed part: chunk header 8, step header 16, counters 40 and the five
        // section counts 20; the rest are body records.
        println!(
            "pile {BODIES} bodies, {steps} steps, contacts off: {:.1} MB; {per_body_step:.2} bytes per body per step; \
             {:.1} bytes per written body record ({:.1} % of body-steps written); \
             recording took {share:.1} % of the step time ({:.2} of {:.2} ms/step)",
            bytes.len() as f64 / 1e6,
            (step_bytes as f64 - steps as f64 * 84.0) / records as f64,
            100.0 * records as f64 / (BODIES as f64 * steps as f64),
            ms(recording),
            ms(stepping),
        );
    }
}

fn benches(c: &mut Criterion) {
    if let Some(steps) = std::env::var("HEARTH_RECORD_REPORT_STEPS")
        .ok()
        .and_then(|s| s.parse().ok())
    {
        report(false, steps);
        return;
    }
    report(false, STEPS);
    report(true, STEPS);
    let mut group = c.benchmark_group("record");
    group.sample_size(10);
    group.throughput(Throughput::Elements(STEPS));
    group.bench_function("pile_plain", |b| {
        b.iter_batched(
            pile,
            |mut w| {
                for _ in 0..STEPS {
                    w.step(DT).unwrap();
                }
                w
            },
            BatchSize::PerIteration,
        )
    });
    group.bench_function("pile_recorded", |b| {
        b.iter_batched(
            || {
                let w = pile();
                let rec = Recorder::new(&w, RecordOptions::default());
                (w, rec, Vec::with_capacity(1 << 26))
            },
            |(mut w, mut rec, mut sink)| {
                for _ in 0..STEPS {
                    w.step(DT).unwrap();
                    rec.record_step(&w, DT, 0.0);
                    sink.extend_from_slice(rec.bytes());
                    rec.clear();
                }
                (w, rec, sink)
            },
            BatchSize::PerIteration,
        )
    });
    group.finish();
}

criterion_group!(record, benches);
criterion_main!(record);

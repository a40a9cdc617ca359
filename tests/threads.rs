//! Determinism across runs, lane widths and worker counts (issue 15), checked against the
//! committed golden hashes in `tests/golden_hashes.txt`.
//!
//! Any change to simulation results changes a hash and fails `golden_hashes_match`. When the
//! change is deliberate, regenerate the file with
//! `HEARTH_BLESS=1 cargo test --release --test threads golden` and commit it with the change.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;

use hearth::math::{Quat, Transform, Vec3};
use hearth::world::{LaneWidth, World, WorldSettings};
use hearth::{BodyDef, Geometry, ShapeDef};

const DT: f32 = 1.0 / 60.0;
const GOLDEN: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/golden_hashes.txt");

/// The standard scenes of the golden file: name, steps, builder.
type Scene = (&'static str, u32, fn(&mut World));

fn golden_scenes() -> Vec<Scene> {
    vec![
        ("pyramid", 120, |w| {
            scenes::pyramid(w, 6);
        }),
        ("pile", 120, |w| {
            scenes::pile(w, 300);
        }),
        ("spheres_grid", 60, |w| {
            scenes::spheres_grid(w, 20);
        }),
        ("joint_chain", 120, |w| {
            scenes::joint_chain(w, 10);
        }),
        ("soft_ball", 120, |w| {
            scenes::soft_ball(w);
        }),
        ("crate_mesh", 120, |w| egg_crate(w, false)),
        ("crate_heightfield", 120, |w| egg_crate(w, true)),
    ]
}

/// 400 mixed bodies (`scenes::terrain_drop`) dropped from 3 m onto an egg crate of 1 m cells,
/// every other sample 0.6 m up, as a mesh or a heightfield: sharp creases, where a body
/// touches faces of several normals (contacts with several manifolds).
fn egg_crate(w: &mut World, heightfield: bool) {
    const CELLS: u32 = 48;
    let n = CELLS + 1;
    let heights: Vec<f32> = (0..n * n)
        .map(|i| if (i / n + i % n) % 2 == 0 { 0.0 } else { 0.6 })
        .collect();
    let half = 0.5 * CELLS as f32;
    let geometry = if heightfield {
        Geometry::Heightfield {
            heightfield: w.create_heightfield(n, n, &heights, None).unwrap(),
            local: Transform::new(Vec3::new(-half, 0.0, -half), Quat::IDENTITY),
            scale: Vec3::ONE,
        }
    } else {
        let (v, t) = scenes::grid_mesh(CELLS, 1.0, &heights);
        Geometry::Mesh {
            mesh: w.create_mesh(&v, &t).unwrap(),
            local: Transform::IDENTITY,
            scale: Vec3::ONE,
        }
    };
    let ground = w.create_body(&BodyDef::default()).unwrap();
    w.create_shape(ground, &ShapeDef::default(), &geometry).unwrap();
    scenes::terrain_drop(w, 400, 3.0, 3);
}

fn settings(lanes: LaneWidth) -> WorldSettings {
    WorldSettings {
        lane_width: lanes,
        ..WorldSettings::default()
    }
}

/// Builds `scene` in a world with `settings`, steps it `steps` times, returns its hash.
fn run(scene: fn(&mut World), steps: u32, settings: WorldSettings) -> u64 {
    let mut w = World::new(settings).unwrap();
    scene(&mut w);
    for _ in 0..steps {
        w.step(DT).unwrap();
    }
    w.state_hash()
}

fn read_golden() -> Vec<(String, u32, u64)> {
    let text = std::fs::read_to_string(GOLDEN).unwrap_or_default();
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            assert_eq!(f.len(), 3, "tests/golden_hashes.txt: bad line {l:?}");
            let hash = u64::from_str_radix(f[2].trim_start_matches("0x"), 16).expect("hex hash");
            (f[0].to_string(), f[1].parse().expect("steps"), hash)
        })
        .collect()
}

#[test]
fn golden_hashes_match() {
    let computed: Vec<(String, u32, u64)> = golden_scenes()
        .into_iter()
        .map(|(name, steps, scene)| {
            let four = run(scene, steps, settings(LaneWidth::Four));
            let auto = run(scene, steps, settings(LaneWidth::Auto));
            assert_eq!(four, auto, "{name}: four and eight lanes differ");
            (name.to_string(), steps, four)
        })
        .collect();
    if std::env::var_os("HEARTH_BLESS").is_some_and(|v| v == "1") {
        let mut text = String::from(
            "# World state hashes (World::state_hash) of the standard scenes after `steps` steps of\n\
             # 1/60 s, default settings. Checked by tests/threads.rs; regenerate deliberately with\n\
             # HEARTH_BLESS=1 cargo test --release --test threads golden\n\
             # scene steps hash\n",
        );
        for (name, steps, hash) in &computed {
            text.push_str(&format!("{name} {steps} 0x{hash:016x}\n"));
        }
        std::fs::write(GOLDEN, text).unwrap();
        println!("wrote {GOLDEN}");
        return;
    }
    let golden = read_golden();
    let mut diffs = Vec::new();
    for (name, steps, hash) in &computed {
        match golden.iter().find(|g| &g.0 == name && g.1 == *steps) {
            Some(g) if g.2 == *hash => {}
            Some(g) => diffs.push(format!(
                "  {name} ({steps} steps): committed 0x{:016x}, now 0x{hash:016x}",
                g.2
            )),
            None => diffs.push(format!("  {name} ({steps} steps): missing, now 0x{hash:016x}")),
        }
    }
    assert!(
        diffs.is_empty() && golden.len() == computed.len(),
        "simulation results changed against tests/golden_hashes.txt:\n{}\n\
         If this change is intended, regenerate the file with\n  \
         HEARTH_BLESS=1 cargo test --release --test threads golden\n\
         and commit it together with the change that caused it.",
        diffs.join("\n")
    );
}

#[test]
fn the_hash_sees_every_kind_of_state() {
    // One bit of a body's velocity, a sleep flag, a particle, a soft vertex: each changes it.
    let mut w = World::new(WorldSettings::default()).unwrap();
    let bodies = scenes::pyramid(&mut w, 2);
    scenes::soft_ball(&mut w);
    let h0 = w.state_hash();
    assert_eq!(h0, w.state_hash(), "hashing twice gives one value");
    let v = w.linear_velocity(bodies[0]).unwrap();
    w.set_linear_velocity(bodies[0], v + hearth::Vec3::new(0.0, 0.0, 1e-6))
        .unwrap();
    let h1 = w.state_hash();
    assert_ne!(h0, h1, "a velocity change");
    w.set_awake(bodies[1], false).unwrap();
    let h2 = w.state_hash();
    assert_ne!(h1, h2, "a sleep change");
    w.create_particle(&Default::default()).unwrap();
    let h3 = w.state_hash();
    assert_ne!(h2, h3, "a new particle");
    // Impulses act in the next step: a twin world without it differs after one.
    let mut twin = World::new(WorldSettings::default()).unwrap();
    scenes::soft_ball(&mut twin);
    let mut pushed = World::new(WorldSettings::default()).unwrap();
    let soft = scenes::soft_ball(&mut pushed);
    pushed
        .apply_soft_impulse(soft, Some(0), hearth::Vec3::new(0.0, 0.0, 1e-3))
        .unwrap();
    assert_eq!(twin.state_hash(), pushed.state_hash(), "twins");
    twin.step(DT).unwrap();
    pushed.step(DT).unwrap();
    assert_ne!(twin.state_hash(), pushed.state_hash(), "an impulse on a soft vertex");
}

#[test]
fn stepping_twice_in_a_process_gives_the_same_hash() {
    let (_, steps, scene) = golden_scenes()[1];
    let a = run(scene, steps, settings(LaneWidth::Auto));
    let b = run(scene, steps, settings(LaneWidth::Auto));
    assert_eq!(a, b);
}

/// Every golden scene at `workers` threads of the world's own pool.
fn check_golden_with(name: &str, make: impl Fn() -> World) {
    let golden = read_golden();
    for (scene_name, steps, scene) in golden_scenes() {
        let mut w = make();
        scene(&mut w);
        for _ in 0..steps {
            w.step(DT).unwrap();
        }
        let want = golden.iter().find(|g| g.0 == scene_name).expect("golden entry").2;
        assert_eq!(
            w.state_hash(),
            want,
            "{scene_name} with {name}: the hash differs from tests/golden_hashes.txt"
        );
    }
}

#[test]
fn worker_counts_one_to_four_give_the_golden_hashes() {
    for workers in 1..=4 {
        for lanes in [LaneWidth::Four, LaneWidth::Auto] {
            check_golden_with(&format!("{workers} workers, {lanes:?} lanes"), || {
                World::new(WorldSettings {
                    worker_count: workers,
                    ..settings(lanes)
                })
                .unwrap()
            });
        }
    }
}

/// A host job system that cuts every task into ranges of random length (at least the
/// minimum), deals them to `threads` fresh threads at random and runs each thread's ranges
/// in a shuffled order: whatever the threads and order, the results must not change.
struct ShufflingHost {
    threads: u32,
    seed: std::sync::Mutex<u64>,
}

impl ShufflingHost {
    fn next(&self) -> u64 {
        // splitmix64 over a shared seed: the cut and the deal differ on every task.
        let mut s = self.seed.lock().unwrap();
        *s = s.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = *s;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

impl hearth::parallel::TaskRunner for ShufflingHost {
    fn worker_count(&self) -> u32 {
        self.threads
    }

    fn run(&self, count: u32, min_range: u32, task: &hearth::parallel::Task) {
        let mut ranges = Vec::new();
        let mut start = 0;
        while start < count {
            let len = min_range + (self.next() % (2 * min_range as u64 + 1)) as u32;
            let end = (start + len).min(count);
            ranges.push((start, end));
            start = end;
        }
        let mut deal: Vec<Vec<(u32, u32)>> = vec![Vec::new(); self.threads as usize];
        for r in ranges {
            deal[(self.next() % self.threads as u64) as usize].push(r);
        }
        for list in &mut deal {
            for i in (1..list.len()).rev() {
                list.swap(i, (self.next() % (i as u64 + 1)) as usize);
            }
        }
        std::thread::scope(|scope| {
            for (worker, list) in deal.iter().enumerate() {
                scope.spawn(move || {
                    for &(s, e) in list {
                        task(s, e, worker as u32);
                    }
                });
            }
        });
    }
}

#[test]
fn a_host_that_shuffles_tasks_onto_random_threads_gives_the_golden_hashes() {
    for (threads, seed) in [(2u32, 1u64), (3, 2), (4, 3), (7, 4)] {
        check_golden_with(&format!("a shuffling host on {threads} threads, seed {seed}"), || {
            let mut w = World::new(settings(LaneWidth::Auto)).unwrap();
            w.set_task_runner(Box::new(ShufflingHost {
                threads,
                seed: std::sync::Mutex::new(seed),
            }))
            .unwrap();
            assert_eq!(w.settings.worker_count, threads);
            w
        });
    }
}

/// A host job system that runs every task on the calling thread, range by range (of the
/// minimum length), last range first, while claiming `workers` workers: it never runs two
/// ranges at once, so the solver must not wait for ranges to meet (it runs one task per
/// stage for a host).
struct SerialHost {
    workers: u32,
}

impl hearth::parallel::TaskRunner for SerialHost {
    fn worker_count(&self) -> u32 {
        self.workers
    }

    fn run(&self, count: u32, min_range: u32, task: &hearth::parallel::Task) {
        let starts: Vec<u32> = (0..count).step_by(min_range.max(1) as usize).collect();
        for (i, &start) in starts.iter().enumerate().rev() {
            let end = (start + min_range.max(1)).min(count);
            task(start, end, i as u32 % self.workers);
        }
    }
}

#[test]
fn a_host_that_runs_every_task_serially_on_the_calling_thread_gives_the_golden_hashes() {
    for workers in [2u32, 4] {
        check_golden_with(&format!("a serial host claiming {workers} workers"), || {
            let mut w = World::new(settings(LaneWidth::Auto)).unwrap();
            w.set_task_runner(Box::new(SerialHost { workers })).unwrap();
            w
        });
    }
}

#[test]
fn two_and_four_workers_match_one_step_by_step_with_joints_and_locked_axes() {
    // The staged solver over many steps of a pile (contacts forming, parting and sleeping)
    // beside a joint chain, with some boxes' axes locked (the serial stages between the
    // colours), at four lanes: the same state as one worker, step for step.
    let build = |w: &mut World| {
        let boxes = scenes::pile(w, 300);
        for b in boxes.iter().step_by(7) {
            w.set_locked_axes(*b, u32::from(hearth::dynamics::body::LOCK_ANGULAR_X))
                .unwrap();
        }
        scenes::joint_chain(w, 10);
    };
    let mut one = World::new(settings(LaneWidth::Four)).unwrap();
    build(&mut one);
    let mut many: Vec<World> = [2u32, 4]
        .iter()
        .map(|&workers| {
            let mut w = World::new(WorldSettings {
                worker_count: workers,
                ..settings(LaneWidth::Four)
            })
            .unwrap();
            build(&mut w);
            w
        })
        .collect();
    for step in 0..300 {
        one.step(DT).unwrap();
        for w in &mut many {
            w.step(DT).unwrap();
            assert_eq!(
                w.state_hash(),
                one.state_hash(),
                "step {step} at {} workers",
                w.settings.worker_count
            );
        }
    }
}

#[test]
fn worker_counts_outside_one_to_sixty_four_are_refused() {
    for bad in [0, 65, u32::MAX] {
        let e = World::new(WorldSettings {
            worker_count: bad,
            ..WorldSettings::default()
        })
        .err()
        .expect("refused");
        assert!(e.to_string().contains("worker_count"), "{e}");
    }
    let mut w = World::new(WorldSettings::default()).unwrap();
    let e = w
        .set_task_runner(Box::new(ShufflingHost {
            threads: 0,
            seed: std::sync::Mutex::new(0),
        }))
        .expect_err("refused");
    assert!(e.to_string().contains("worker_count"), "{e}");
    assert_eq!(w.settings.worker_count, 1, "unchanged");
}

#[test]
fn two_pooled_worlds_step_side_by_side_and_drop_cleanly() {
    // Two worlds with their own threads in one process, stepped alternately, then dropped
    // (their threads joined): both match the single-threaded run.
    let (_, steps, scene) = golden_scenes()[0];
    let want = run(scene, steps, settings(LaneWidth::Auto));
    let make = || {
        let mut w = World::new(WorldSettings {
            worker_count: 3,
            ..settings(LaneWidth::Auto)
        })
        .unwrap();
        scene(&mut w);
        w
    };
    let (mut a, mut b) = (make(), make());
    for _ in 0..steps {
        a.step(DT).unwrap();
        b.step(DT).unwrap();
    }
    assert_eq!((a.state_hash(), b.state_hash()), (want, want));
}

/// The egg crates (`egg_crate`), where contacts hold several manifolds (one per triangle
/// patch; their results are stored apart from the parallel store, `contact_wide::store`):
/// two and four workers give one worker's state step by step.
#[test]
fn terrain_contacts_with_several_manifolds_match_one_worker_step_by_step() {
    for heightfield in [false, true] {
        let build = |w: &mut World| egg_crate(w, heightfield);
        let make = |workers: u32| {
            let mut w = World::new(WorldSettings {
                worker_count: workers,
                ..settings(LaneWidth::Auto)
            })
            .unwrap();
            build(&mut w);
            w
        };
        let mut one = make(1);
        let mut many = [make(2), make(4)];
        let mut most_manifolds = 0;
        for step in 0..240 {
            one.step(DT).unwrap();
            let manifolds = one.contacts.iter().map(|(_, c)| c.manifold_count()).max().unwrap_or(0);
            most_manifolds = most_manifolds.max(manifolds);
            for w in &mut many {
                w.step(DT).unwrap();
                assert_eq!(
                    w.state_hash(),
                    one.state_hash(),
                    "heightfield {heightfield}, step {step} at {} workers",
                    w.settings.worker_count
                );
            }
        }
        assert!(
            most_manifolds > 1,
            "heightfield {heightfield}: no contact had several manifolds"
        );
    }
}

/// Every event list, in order, of one step, printed with every float in full (`{:?}` prints
/// the shortest text that reads back to the same bits). Handles are compared by slot only:
/// their generation carries the world's own tag.
fn events_of(w: &World) -> String {
    let e = w.events();
    let text = format!(
        "{:?}|{:?}|{:?}|{:?}|{:?}|{:?}",
        e.contact_begin, e.contact_end, e.contact_hit, e.sensor_begin, e.sensor_end, e.body_moves
    );
    let mut out = String::with_capacity(text.len());
    let mut rest = text.as_str();
    while let Some(k) = rest.find("generation: ") {
        out.push_str(&rest[..k]);
        rest = rest[k + "generation: ".len()..].trim_start_matches(|c: char| c.is_ascii_digit());
    }
    out.push_str(rest);
    out
}

/// The events are part of the results: the same lists in the same order at 1, 2 and 4
/// workers and with the shuffling host, step by step, while a pile falls, lands (contact
/// begins, hits), and goes to sleep (moves reported, then the bodies that fell asleep).
#[test]
fn events_are_the_same_at_every_worker_count_step_by_step() {
    let make = |workers: u32, shuffle: bool| {
        let mut w = World::new(WorldSettings {
            worker_count: if shuffle { 1 } else { workers },
            ..settings(LaneWidth::Auto)
        })
        .unwrap();
        if shuffle {
            w.set_task_runner(Box::new(ShufflingHost {
                threads: workers,
                seed: std::sync::Mutex::new(11),
            }))
            .unwrap();
        }
        scenes::pile(&mut w, 1500);
        scenes::set_events(&mut w, true);
        w
    };
    let mut one = make(1, false);
    let mut many = [make(2, false), make(4, false), make(3, true)];
    let (mut moves, mut begins, mut hits, mut asleep) = (0, 0, 0, 0);
    for step in 0..400 {
        one.step(DT).unwrap();
        let expected = events_of(&one);
        let e = one.events();
        moves += e.body_moves.len();
        begins += e.contact_begin.len();
        hits += e.contact_hit.len();
        asleep += e.body_moves.iter().filter(|m| m.fell_asleep).count();
        for w in &mut many {
            w.step(DT).unwrap();
            assert!(
                events_of(w) == expected,
                "step {step}: events differ at {} workers",
                w.settings.worker_count
            );
        }
    }
    assert!(
        moves > 100_000 && begins > 1000 && hits > 100 && asleep > 1000,
        "moves {moves}, begins {begins}, hits {hits}, asleep {asleep}"
    );
}

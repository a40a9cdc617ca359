//! Determinism across runs, lane widths and worker counts (issue 15), checked against the
//! committed golden hashes in `tests/golden_hashes.txt`.
//!
//! Any change to simulation results changes a hash and fails `golden_hashes_match`. When the
//! change is deliberate, regenerate the file with
//! `HEARTH_BLESS=1 cargo test --release --test threads golden` and commit it with the change.

#[path = "scenes/mod.rs"]
#[allow(dead_code)]
mod scenes;

use hearth::world::{LaneWidth, World, WorldSettings};

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
    ]
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

//! Islands and sleep. Each step the awake bodies are joined through touching contacts and
//! joints (union–find); an island whose every body has stayed still for `time_to_sleep` goes to
//! sleep together.
//!
//! A body is still while a short recency-weighted average of its v² + ω² (half-life
//! `MOTION_HALF_LIFE`, 0.1 s, capped at ten times `sleep_threshold²`) is at most
//! `sleep_threshold²` and its current v² + ω² at most four times that: the timer then runs,
//! else it restarts. The average lets a body twitching in place (speed flickering above the
//! threshold for a step) fall asleep; the cap bounds how long a fast body stays "moving"
//! once it stopped: at most log2(10) half-lives, 0.33 s, before the timer starts.
//!
//! The seed's half-life was one second: after a landing the average took about 3.3 s to fall
//! under the threshold, so a body at rest slept some 3.8 s after it stopped instead of the
//! documented `time_to_sleep` (0.5 s); on the 1,000-body terrain drop all 994 bodies were
//! still awake at step 300 (Jolt: 436). With 0.1 s: 411 (mesh) and 404 (heightfield). The raw
//! speed (Box2D v3's rule) gave 397 and 382 but left twitching boxes awake for ever.

use crate::world::World;

#[derive(Default)]
pub struct IslandScratch {
    parent: Vec<u32>,
    min_sleep: Vec<f32>,
    sleepers: Vec<(u32, u32)>,
    group: Vec<u32>,
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[x as usize];
        parent[x as usize] = parent[p as usize];
        x = p;
    }
    x
}

/// Half-life of the recency-weighted motion (seconds).
pub const MOTION_HALF_LIFE: f32 = 0.1;

/// The rule that updates a body's recency-weighted motion and sleep timer each step (run on
/// every awake body by `World::finish_bodies`).
#[derive(Clone, Copy, Debug)]
pub struct MotionRule {
    /// Squared sleep threshold.
    eps: f32,
    /// Weight of the old average after one step.
    bias: f32,
    dt: f32,
}

impl MotionRule {
    pub fn new(settings: &crate::world::WorldSettings, dt: f32) -> Self {
        let t = settings.sleep_threshold;
        MotionRule {
            eps: t * t,
            bias: 0.5f32.powf(dt / MOTION_HALF_LIFE),
            dt,
        }
    }

    /// Updates one awake body; returns its sleep timer (0 when it moved).
    #[inline]
    pub fn update(&self, b: &mut crate::dynamics::body::Body) -> f32 {
        let (eps, bias) = (self.eps, self.bias);
        let current = b.v.length_squared() + b.w.length_squared();
        b.motion = (bias * b.motion + (1.0 - bias) * current).min(10.0 * eps);
        if !b.allow_sleep || b.motion > eps || current > 4.0 * eps {
            b.sleep_time = 0.0;
        } else {
            b.sleep_time += self.dt;
        }
        b.sleep_time
    }
}

/// Puts to sleep every island that has been still long enough. `ready`: some body has been
/// still long enough (`MotionRule`); without one the islands are not built.
pub fn sleep_islands(world: &mut World, ready: bool) {
    wake_joined_sleepers(world);
    if !world.settings.enable_sleep {
        return;
    }
    // Room for every awake body, reserved while no island is ready: the step where islands
    // first fall asleep does not allocate (capacity only grows with the awake list).
    let n = world.awake_bodies.len();
    let mut scratch = std::mem::take(&mut world.island_scratch);
    for v in [&mut scratch.parent, &mut scratch.group] {
        v.reserve(n.saturating_sub(v.len()));
    }
    scratch.min_sleep.reserve(n.saturating_sub(scratch.min_sleep.len()));
    scratch.sleepers.reserve(n.saturating_sub(scratch.sleepers.len()));
    world.events.fell_asleep.reserve(n);
    if !ready {
        world.island_scratch = scratch;
        return;
    }
    scratch.parent.clear();
    scratch.parent.extend(0..n as u32);
    for &ci in &world.awake_contacts {
        let c = world.contacts.at(ci);
        if !c.touching {
            continue;
        }
        let (a, b) = (world.bodies.at(c.body_a), world.bodies.at(c.body_b));
        if a.is_static() || b.is_static() || !a.awake || !b.awake {
            continue;
        }
        let ra = find(&mut scratch.parent, a.awake_index);
        let rb = find(&mut scratch.parent, b.awake_index);
        if ra != rb {
            scratch.parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }
    // Joints (issue 5) join their dynamic bodies into one island.
    for (_, j) in world.joints.pool.iter() {
        if j.broken || j.b == crate::dynamics::body::NONE {
            continue;
        }
        let (a, b) = (world.bodies.at(j.a), world.bodies.at(j.b));
        if !a.is_dynamic() || !b.is_dynamic() || !a.awake || !b.awake {
            continue;
        }
        let ra = find(&mut scratch.parent, a.awake_index);
        let rb = find(&mut scratch.parent, b.awake_index);
        if ra != rb {
            scratch.parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }
    scratch.min_sleep.clear();
    scratch.min_sleep.resize(n, f32::MAX);
    for k in 0..n {
        let r = find(&mut scratch.parent, k as u32) as usize;
        let st = world.bodies.at(world.awake_bodies[k]).sleep_time;
        scratch.min_sleep[r] = scratch.min_sleep[r].min(st);
    }
    let time_to_sleep = world.settings.time_to_sleep;
    scratch.sleepers.clear();
    for k in 0..n {
        let r = find(&mut scratch.parent, k as u32);
        if scratch.min_sleep[r as usize] >= time_to_sleep {
            scratch.sleepers.push((r, world.awake_bodies[k]));
        }
    }
    if !scratch.sleepers.is_empty() {
        scratch.sleepers.sort_unstable();
        let mut i = 0;
        while i < scratch.sleepers.len() {
            let root = scratch.sleepers[i].0;
            scratch.group.clear();
            while i < scratch.sleepers.len() && scratch.sleepers[i].0 == root {
                scratch.group.push(scratch.sleepers[i].1);
                i += 1;
            }
            world.put_to_sleep(&scratch.group);
            world.events.fell_asleep.extend_from_slice(&scratch.group);
        }
    }
    world.island_scratch = scratch;
}

/// A joint between an awake body and a sleeping dynamic one (a kinematic body that started
/// moving, a body put to sleep by the host) wakes the sleeper, so joined bodies move together.
fn wake_joined_sleepers(world: &mut World) {
    if world.joints.is_empty() {
        return;
    }
    let mut wake = std::mem::take(&mut world.scratch_wake);
    wake.clear();
    for (_, j) in world.joints.pool.iter() {
        if j.broken || j.b == crate::dynamics::body::NONE {
            continue;
        }
        let (a, b) = (world.bodies.at(j.a), world.bodies.at(j.b));
        if a.is_static() || b.is_static() || a.awake == b.awake {
            continue;
        }
        let (awake, sleeper) = if a.awake { (a, j.b) } else { (b, j.a) };
        if world.bodies.at(sleeper).is_dynamic() && awake.sleep_time == 0.0 {
            wake.push(sleeper);
        }
    }
    for &b in &wake {
        world.wake_body(b);
    }
    wake.clear();
    world.scratch_wake = wake;
}

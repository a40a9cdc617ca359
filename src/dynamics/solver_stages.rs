//! The sub-steps on several workers (issue 15), after Box2D v3's solver stages
//! (`b2SolverStage`, `b2ExecuteMainStage`): the sub-step loop of `solver::solve` is written
//! out once per step as a list of stages, each cut into blocks that may run at the same
//! time, and a stage starts only when the one before it has finished.
//!
//! * a colour's contact batches (warm start, biased solve, relax): a colour's constraints
//!   share no dynamic body, so its batches may be solved in any order or at once;
//! * the bodies' velocity and position integration and the velocity guard: each body from
//!   its own slot (the scalar-path bodies are one more block of the integration stages);
//! * what must stay in order runs as one block, alone: body springs, joints, the contacts
//!   that fit no colour, the locked-axes pass.
//!
//! Each block computes exactly what the serial loop computes for its items, in the same
//! order within the item, and no two blocks of a stage touch the same item, so the results
//! are the serial loop's bit for bit whoever runs which block. How blocks are cut (by the
//! worker count) changes nothing either.
//!
//! Two drivers. With Hearth's own pool the workers run the whole list inside one task each,
//! each claiming its own share of a stage's blocks first (`parallel::Claims`), count the
//! blocks they completed in a step-wide counter, and whoever completes a stage's last block
//! opens the gate to the next (`parallel::Barrier` used as a gate; a waiting worker spins
//! briefly, then yields, then parks), as Box2D v3 does: no thread is woken per stage, and a
//! worker that is not running (a loaded machine) holds the others up only while inside a
//! block. Only the pool promises that its workers
//! may wait for one another (`TaskRunner::concurrent`), never more than the cores. A host's
//! job system may run tasks one after another, so with it each stage is one task (one
//! enqueue and finish per stage, blocks as the items).
//!
//! Lanes of static and kinematic bodies are written back by a batch or an integration chunk
//! with the very bits they read (their inverse mass and inertia are zero; short chunks fill
//! empty lanes with the static dummy and leave it as it is, see `contact_wide::scatter` and
//! `integrate_wide`), so two blocks of a stage may store the same bits to such a slot, which
//! changes nothing.

use std::ops::Range;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicU32, Ordering};

use crate::dynamics::contact_wide::{self, Batches, SoftSweep};
use crate::dynamics::integrate_wide;
use crate::dynamics::joints::solver::{self as joints, JointSet};
use crate::dynamics::solver::{
    guard_fuses, guard_list, guard_range, integrate_general_positions, integrate_general_velocities, lock_velocities,
    BodySim, BodyState, Drive, Paths, Velocity,
};
use crate::generators::springs::{self, BodySprings};
use crate::parallel::{Barrier, Claims, Line, SharedMut, TaskRunner};

/// What every block reads, fixed for the step.
pub(crate) struct Sweep<'a> {
    pub substeps: u32,
    pub iterations: u32,
    pub h: f32,
    pub inv_h: f32,
    pub eight: bool,
    pub limits: (f32, f32),
    pub soft: &'a SoftSweep,
    pub sims: &'a [BodySim],
    pub drives: &'a [Drive],
    pub paths: &'a Paths,
    pub locked: &'a [u32],
}

/// Everything the stages write (see the module doc for who writes what within a stage).
pub(crate) struct Written<'a> {
    pub vel: SharedMut<'a, [Velocity]>,
    pub states: SharedMut<'a, [BodyState]>,
    pub batches: SharedMut<'a, Batches>,
    pub joints: SharedMut<'a, JointSet>,
    pub springs: SharedMut<'a, BodySprings>,
}

/// One step of a serial stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Serial {
    Springs,
    JointWarmStart,
    JointSolve {
        bias: bool,
    },
    Lock,
    /// The contacts that fit no colour, in order (the last colour range).
    Singles(Pass),
}

/// A sweep over contact batches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pass {
    WarmStart { first: bool },
    Solve { forward: bool, bias: bool },
}

/// Most serial steps one stage chains (a sub-step has at most six in a row).
const CHAIN: usize = 8;

/// A stage's work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Op {
    /// One block running `chain[..len]` in order.
    Serial { chain: [Serial; CHAIN], len: u8 },
    /// Items: indices into `paths.plain`, then the general blocks (`Stage::general`). With
    /// `guard`, each block first guards its bodies' velocities (the first general block also
    /// the kinematic bodies'): the guard after the last sub-step's relax sweep.
    Velocities { guard: bool },
    /// Items: indices into `paths.moving`, then the general blocks. Each block first guards
    /// its bodies' velocities (every solver slot is in one of the two lists).
    Positions,
    /// Items: solver slots.
    Guard,
    /// Items: batches of one colour.
    Batches(Pass),
}

#[derive(Clone, Copy, Debug)]
struct Stage {
    op: Op,
    /// Items `start..end`, in blocks of `block` (a serial stage: one block).
    start: u32,
    end: u32,
    block: u32,
    /// Blocks in all (including the scalar-path blocks of the integration stages).
    blocks: u32,
    /// The integration stages' scalar-path bodies (`paths.general`) per block, in the
    /// blocks after those of `start..end` (0: none, a stage of one list).
    general: u32,
    /// Index of the stage's first block in `Stages::claims`.
    first: u32,
}

/// The stage list of a step, a claim per block and the count of completed blocks, reused
/// step to step. Workers on different cores touch these at every stage, so each lives on a
/// cache line of its own (`parallel::Claims`), and a worker adds to `done` once per stage,
/// all the blocks it completed there, rather than once per block.
#[derive(Default)]
pub struct Stages {
    list: Vec<Stage>,
    /// Per block of every stage.
    claims: Claims,
    /// This step's claim epoch (one more each step).
    epoch: u64,
    /// Blocks completed this step, of every stage: stage `s` is done when this reaches
    /// `list[s].first + list[s].blocks` (the stages run one after another).
    done: Line<AtomicU32>,
}

/// Items per block: about four blocks per worker, no fewer than `min` items, a multiple of
/// `align`.
fn block_size(len: u32, workers: u32, min: u32, align: u32) -> u32 {
    len.div_ceil(BLOCKS_PER_WORKER * workers).max(min).div_ceil(align) * align
}

/// Bodies fewer than this per block are not worth a claim.
const MIN_BODIES: u32 = 32;
const BLOCKS_PER_WORKER: u32 = 4;
/// Batches fewer than this per block likewise.
const MIN_BATCHES: u32 = 2;

impl Stages {
    /// A stage over `items` in blocks of `block`, then `general.0` blocks of `general.1`
    /// scalar-path bodies each.
    fn push(&mut self, op: Op, items: Range<usize>, block: u32, general: (u32, u32)) {
        let (start, end) = (items.start as u32, items.end as u32);
        let blocks = (end - start).div_ceil(block.max(1)) + general.0;
        if blocks > 0 {
            let first = self.blocks();
            self.list.push(Stage {
                op,
                start,
                end,
                block: block.max(1),
                blocks,
                general: general.1,
                first,
            });
        }
    }

    fn push_serial(&mut self, s: Serial) {
        if let Some(Stage {
            op: Op::Serial { chain, len },
            ..
        }) = self.list.last_mut()
        {
            if (*len as usize) < CHAIN {
                chain[*len as usize] = s;
                *len += 1;
                return;
            }
        }
        let mut chain = [Serial::Lock; CHAIN];
        chain[0] = s;
        let first = self.blocks();
        self.list.push(Stage {
            op: Op::Serial { chain, len: 1 },
            start: 0,
            end: 1,
            block: 1,
            blocks: 1,
            general: 0,
            first,
        });
    }

    /// Blocks of the stages listed so far.
    fn blocks(&self) -> u32 {
        self.list.last().map_or(0, |s| s.first + s.blocks)
    }

    /// Writes out the sub-step loop of `solver::solve` for `workers` workers.
    fn build(&mut self, sweep: &Sweep, w: &Written, workers: u32) {
        self.list.clear();
        // SAFETY: nothing runs yet; these are shared reads.
        let (slots, batches, joints, springs) = unsafe {
            (
                w.vel.get().len(),
                &*w.batches.get(),
                &*w.joints.get(),
                &*w.springs.get(),
            )
        };
        let colours = batches.colours().count();
        let (has_joints, has_springs, has_locks) = (
            !joints.list.is_empty(),
            !springs.list.is_empty(),
            !sweep.locked.is_empty(),
        );
        let paths = sweep.paths;
        // The scalar-path bodies (gyroscopic turns, RK4) cost far more than the lane ones:
        // in blocks of their own, as many as the lane bodies get.
        let general_block = block_size(paths.general.len() as u32, workers, 4, 4);
        let general_blocks = (paths.general.len() as u32).div_ceil(general_block);
        // As the serial loop: the guard after a relax sweep is made by the next velocity
        // stage when nothing comes between them.
        let fused = guard_fuses(springs, sweep.locked);
        let lanes = batches.lanes() as u32;
        let body_block = |len: usize| block_size(len as u32, workers, MIN_BODIES, lanes);
        // One stage per colour, the constraints that fit no colour (the last range) serially.
        let sweep_colours = |me: &mut Stages, pass: Pass| {
            for (c, range) in batches.colours().enumerate() {
                if c + 1 == colours {
                    if !range.is_empty() {
                        me.push_serial(Serial::Singles(pass));
                    }
                } else {
                    let block = block_size(range.len() as u32, workers, MIN_BATCHES, 1);
                    me.push(Op::Batches(pass), range, block, (0, 0));
                }
            }
        };
        for sub in 0..sweep.substeps {
            if has_springs {
                self.push_serial(Serial::Springs);
            }
            let guard = fused && sub > 0;
            // One block at least when kinematic bodies are to be guarded.
            let kinematic = (guard && !paths.kinematic.is_empty()) as u32;
            self.push(
                Op::Velocities { guard },
                0..paths.plain.len(),
                body_block(paths.plain.len()),
                (general_blocks.max(kinematic), general_block),
            );
            if has_joints {
                self.push_serial(Serial::JointWarmStart);
            }
            sweep_colours(self, Pass::WarmStart { first: sub == 0 });
            if has_locks {
                self.push_serial(Serial::Lock);
            }
            if has_joints {
                self.push_serial(Serial::JointSolve { bias: true });
                if has_locks {
                    self.push_serial(Serial::Lock);
                }
            }
            for k in 0..sweep.iterations {
                let forward = (sub + k) % 2 == 0;
                sweep_colours(self, Pass::Solve { forward, bias: true });
                if has_locks {
                    self.push_serial(Serial::Lock);
                }
            }
            self.push(
                Op::Positions,
                0..paths.moving.len(),
                body_block(paths.moving.len()),
                (general_blocks, general_block),
            );
            if has_joints {
                self.push_serial(Serial::JointSolve { bias: false });
                if has_locks {
                    self.push_serial(Serial::Lock);
                }
            }
            sweep_colours(
                self,
                Pass::Solve {
                    forward: sub % 2 == 1,
                    bias: false,
                },
            );
            if !fused || sub + 1 == sweep.substeps {
                self.push(Op::Guard, 1..slots, body_block(slots), (0, 0));
            }
            if has_locks {
                self.push_serial(Serial::Lock);
            }
        }
        self.claims.reserve(self.blocks() as usize);
        self.epoch += 1;
        self.done.0.store(0, Ordering::Relaxed);
    }
}

/// Runs the sub-step loop of `solver::solve` on `runner`'s workers (`runner.worker_count()`
/// above 1), with the same results bit for bit.
pub(crate) fn substeps(runner: &dyn TaskRunner, stages: &mut Stages, sweep: &Sweep, w: &Written) {
    let concurrent = runner.concurrent().min(runner.worker_count());
    let workers = if concurrent > 1 {
        concurrent
    } else {
        runner.worker_count()
    };
    stages.build(sweep, w, workers);
    let stages = &*stages;
    if concurrent > 1 {
        let gate = Barrier::new();
        runner.run(concurrent, 1, &|start, end, _| {
            for me in start..end {
                let r = catch_unwind(AssertUnwindSafe(|| worker(stages, sweep, w, &gate, me, concurrent)));
                if let Err(e) = r {
                    gate.poison();
                    resume_unwind(e);
                }
            }
        });
    } else {
        for stage in &stages.list {
            crate::parallel::run(runner, stage.blocks, 1, &|start, end, _| {
                for b in start..end {
                    // SAFETY: the blocks of one stage touch distinct items (module doc), and
                    // `parallel::run` returns only when all of them are done.
                    unsafe { execute(stage, b, sweep, w) };
                }
            });
        }
    }
}

/// One of the workers inside one task each: claims blocks of the current stage; whoever
/// completes a stage's last block opens the gate to the next (the gate's generation is the
/// stage index), and a worker waits only while another one is still inside a block of the
/// current stage. A worker that starts late, or was descheduled, finds the stages done
/// meanwhile and skips them, so it holds nobody up.
///
/// Worker `me` of `workers` takes its own share of every stage's blocks first
/// (`Claims::in_turn`): the same share of the same items in every stage (a colour's
/// batches, which `Batches::build` orders by the bodies' shares, and the bodies), so each
/// worker keeps solving the same constraints and bodies, whose data stays in its core's
/// cache through the sub-steps.
fn worker(stages: &Stages, sweep: &Sweep, w: &Written, gate: &Barrier, me: u32, workers: u32) {
    let count = stages.list.len() as u32;
    loop {
        let s = gate.generation();
        if s >= count {
            return;
        }
        let stage = &stages.list[s as usize];
        let mut completed = 0;
        for b in stages
            .claims
            .in_turn(stage.first, stage.blocks, stages.epoch, me, workers)
        {
            // SAFETY: each block is claimed once; blocks of a stage touch distinct items, and
            // no block of stage s + 1 is claimed before every block of s completed.
            unsafe { execute(stage, b, sweep, w) };
            completed += 1;
        }
        // AcqRel: the completions form one release sequence, so whoever completes the last
        // block of the stage sees every block's writes and publishes them by opening the gate.
        if completed > 0
            && stages.done.0.fetch_add(completed, Ordering::AcqRel) + completed == stage.first + stage.blocks
        {
            gate.open(s + 1);
        }
        gate.wait_past(s);
    }
}

/// Runs block `b` of `stage`.
///
/// # Safety
/// No other block of a different stage runs at the same time, and `b` runs once.
unsafe fn execute(stage: &Stage, b: u32, sweep: &Sweep, w: &Written) {
    let (h, limits, eight, paths) = (sweep.h, sweep.limits, sweep.eight, sweep.paths);
    let span = |start: u32, block: u32, end: u32| start.min(end) as usize..(start + block).min(end) as usize;
    let own = (stage.end - stage.start).div_ceil(stage.block);
    let items = span(stage.start + b * stage.block, stage.block, stage.end);
    // A scalar-path block of an integration stage: its share of `paths.general`.
    let general = (b >= own).then(|| span((b - own) * stage.general, stage.general, paths.general.len() as u32));
    let (vel, states) = (w.vel.get(), w.states.get());
    match stage.op {
        Op::Serial { chain, len } => {
            for s in &chain[..len as usize] {
                match *s {
                    Serial::Springs => springs::apply(w.springs.get(), vel, states, h),
                    Serial::JointWarmStart => joints::warm_start(w.joints.get(), vel, states, limits),
                    Serial::JointSolve { bias } => {
                        let set = w.joints.get();
                        joints::solve(set, vel, states, h, bias);
                        joints::guard(set, vel, limits);
                    }
                    Serial::Lock => lock_velocities(vel, states, sweep.locked),
                    Serial::Singles(pass) => {
                        let batches = w.batches.get();
                        let range = batches.colours().last().unwrap_or(0..0);
                        sweep_batches(pass, range, sweep, vel, states, batches);
                    }
                }
            }
        }
        Op::Velocities { guard } if b >= own => {
            let bodies = &paths.general[general.unwrap_or(0..0)];
            if guard {
                guard_list(vel, limits, bodies);
                if b == own {
                    guard_list(vel, limits, &paths.kinematic);
                }
            }
            integrate_general_velocities(vel, sweep.drives, states, sweep.sims, bodies, h, limits)
        }
        Op::Velocities { guard } => {
            if guard {
                guard_list(vel, limits, &paths.plain[items.clone()]);
            }
            integrate_wide::velocities(eight, vel, sweep.drives, &paths.plain[items], limits)
        }
        Op::Positions if b >= own => {
            let bodies = &paths.general[general.unwrap_or(0..0)];
            guard_list(vel, limits, bodies);
            integrate_general_positions(vel, states, sweep.sims, bodies, h, limits)
        }
        Op::Positions => {
            guard_list(vel, limits, &paths.moving[items.clone()]);
            integrate_wide::positions(eight, vel, states, &paths.moving[items], h, limits)
        }
        Op::Guard => guard_range(vel, limits, items),
        Op::Batches(pass) => sweep_batches(pass, items, sweep, vel, states, w.batches.get()),
    }
}

fn sweep_batches(
    pass: Pass,
    range: Range<usize>,
    sweep: &Sweep,
    vel: &mut [Velocity],
    states: &[BodyState],
    batches: &mut Batches,
) {
    match pass {
        Pass::WarmStart { first } => contact_wide::refresh_warm_start_range(states, vel, batches, first, range),
        Pass::Solve { forward, bias } => {
            let soft = bias.then_some(sweep.soft);
            contact_wide::solve_range(vel, batches, sweep.inv_h, forward, soft, range)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::block_size;

    #[test]
    fn blocks_cover_the_items_in_whole_lane_chunks() {
        for len in 0..300u32 {
            for workers in 1..6 {
                for (min, align) in [(1, 1), (2, 1), (32, 4), (32, 8)] {
                    let b = block_size(len, workers, min, align);
                    assert!(b >= min && b % align == 0 && b > 0);
                    assert!(len.div_ceil(b) <= 4 * workers || b == min.div_ceil(align) * align);
                }
            }
        }
    }
}

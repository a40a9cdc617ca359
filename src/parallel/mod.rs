//! Running a stage's work on several threads (issue 15).
//!
//! A stage hands a [`TaskRunner`] a range function `task(start, end, worker)` and an item
//! count; the runner calls it over disjoint ranges covering `0..count`, on any threads, in
//! any order, and returns when every range is done. Each stage's task writes only to the
//! slots of its own items (one contact, one body, one soft body), so the results do not
//! depend on how the ranges were cut, which thread ran them or in which order; whatever
//! the stage must combine (wake lists, counters, destroyed contacts) is merged afterwards
//! on the stepping thread in item order. That makes every worker count bit-identical.
//!
//! Runners: [`Serial`] (one worker, the default), [`ThreadPool`] (Hearth's own parked
//! threads) and, in the C layer, the host's job system through its enqueue and finish
//! callbacks (`capi/tasks.rs`).

mod barrier;
mod claims;
mod pool;
mod slots;

pub(crate) use barrier::Barrier;
pub(crate) use claims::{Claims, Line};
pub use pool::ThreadPool;
pub(crate) use slots::{Disjoint, SharedMut};

/// Most workers a world may use.
pub const MAX_WORKERS: u32 = 64;

/// The range function of one stage: `(start, end, worker_index)`, `start < end <= count`,
/// `worker_index < worker_count()`.
pub type Task<'a> = dyn Fn(u32, u32, u32) + Sync + 'a;

/// Runs a stage's range function over `0..count` on workers.
pub trait TaskRunner: Send + Sync {
    /// Workers that may run ranges at once (1..=64); the worker index passed to a task is
    /// below it.
    fn worker_count(&self) -> u32;

    /// Calls `task` over disjoint ranges that together cover `0..count` exactly once, each
    /// (except perhaps the last) at least `min_range` long, and returns when all are done.
    /// Every range must run even when an earlier one panicked; the panic is then resumed
    /// on the calling thread.
    fn run(&self, count: u32, min_range: u32, task: &Task);

    /// Up to how many items a `run` of `min_range` 1 surely runs all at the same time, each
    /// on its own thread and core, so that they may wait for one another (the solver's
    /// stage barrier, `dynamics::solver_stages`); 0 if none. Only Hearth's own pool
    /// promises it; a host's job system may run ranges one after another.
    fn concurrent(&self) -> u32 {
        0
    }
}

/// Everything on the calling thread, in one range.
#[derive(Clone, Copy, Debug, Default)]
pub struct Serial;

impl TaskRunner for Serial {
    fn worker_count(&self) -> u32 {
        1
    }

    fn run(&self, count: u32, _min_range: u32, task: &Task) {
        if count > 0 {
            task(0, count, 0);
        }
    }
}

/// Runs `task` over `0..count` with the world's runner, or inline when the stage is too
/// small to be worth splitting (fewer than two ranges of `min_range`).
pub(crate) fn run(runner: &dyn TaskRunner, count: u32, min_range: u32, task: &Task) {
    if count == 0 {
        return;
    }
    if runner.worker_count() <= 1 || count < 2 * min_range.max(1) {
        task(0, count, 0);
    } else {
        runner.run(count, min_range.max(1), task);
    }
}

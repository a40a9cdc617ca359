//! Hearth's own workers, for hosts that bring no job system: `worker_count − 1` threads
//! started with the world and parked on a condition variable between stages (no thread is
//! created per step), plus the stepping thread itself as worker 0.
//!
//! Stages of a step follow each other within microseconds, and waking a parked thread takes
//! about as long as a small stage: so an idle worker first spins for up to [`SPIN`] watching
//! for the next stage, and `run` spins as long for the last range before it parks; a
//! condition variable is signalled only when somebody sleeps on it.
//!
//! Each thread takes the ranges of its own share first (`Claims::in_turn`, as the solver's
//! stages do): the same thread tends to get the same items (bodies, contacts) stage after
//! stage and step after step, so their data stays in its core's cache. A range is claimed
//! with an atomic operation on its own cache line, no lock.

use std::any::Any;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::{Claims, Line, Task, TaskRunner, MAX_WORKERS};

/// The stage being run: its range function, with the borrow's lifetime erased. It is only
/// reached through `State::job` while `run` waits for every claimed range to finish.
#[derive(Clone, Copy)]
struct Job {
    task: *const Task<'static>,
    count: u32,
    piece: u32,
    pieces: u32,
    /// The stage's `State::generation`.
    generation: u64,
}

// The pointer is only followed while `run` keeps the task alive (see `Job`).
unsafe impl Send for Job {}

#[derive(Default)]
struct State {
    job: Option<Job>,
    /// Bumped per stage, so a late worker never claims a range of the next one.
    generation: u64,
    panic: Option<Box<dyn Any + Send>>,
    exit: bool,
    /// Workers parked on `work`, and whether `run` is parked on `done`.
    sleepers: u32,
    caller_sleeps: bool,
}

struct Shared {
    state: Mutex<State>,
    /// Workers wait here for a job.
    work: Condvar,
    /// `run` waits here for the last range.
    done: Condvar,
    /// `State::generation`, readable without the lock by the threads that spin before they
    /// park (written under it).
    posted: AtomicU64,
    /// Ranges of the current job finished.
    finished: Line<AtomicU32>,
    /// Per range, claimed with the job's generation as the epoch: a worker still holding an
    /// earlier job claims nothing.
    claims: Claims,
}

/// Most ranges of one job: `run` cuts about four per worker.
const MAX_PIECES: u32 = 4 * MAX_WORKERS;

/// How long an idle worker, or `run` waiting for the last range, spins before it parks.
pub const SPIN: Duration = Duration::from_micros(50);

/// Spins until `ready` or `SPIN` has passed; returns `ready()`.
fn spin_until(ready: impl Fn() -> bool) -> bool {
    let start = Instant::now();
    loop {
        for _ in 0..64 {
            if ready() {
                return true;
            }
            std::hint::spin_loop();
        }
        if start.elapsed() >= SPIN {
            return ready();
        }
    }
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, State> {
        // Ranges run outside the lock and their panics are caught, so it is never poisoned
        // by a task; recover anyway rather than panic in a worker.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// A pool of parked worker threads (see the module doc).
pub struct ThreadPool {
    shared: Arc<Shared>,
    threads: Vec<JoinHandle<()>>,
    workers: u32,
    /// The machine's cores (`available_parallelism`), read once when the pool starts.
    cores: u32,
    /// One stage at a time per pool.
    running: Mutex<()>,
}

impl ThreadPool {
    /// Starts `workers − 1` threads (`workers` in 1..=64; the caller of `run` is the last).
    pub fn new(workers: u32) -> std::io::Result<ThreadPool> {
        let workers = workers.clamp(1, MAX_WORKERS);
        let shared = Arc::new(Shared {
            state: Mutex::new(State::default()),
            work: Condvar::new(),
            done: Condvar::new(),
            posted: AtomicU64::new(0),
            finished: Line(AtomicU32::new(0)),
            claims: {
                let mut c = Claims::default();
                c.reserve(MAX_PIECES as usize);
                c
            },
        });
        let mut threads = Vec::with_capacity(workers as usize - 1);
        for index in 1..workers {
            let mine = Arc::clone(&shared);
            let spawned = std::thread::Builder::new()
                .name(format!("hearth-worker-{index}"))
                .spawn(move || worker(&mine, index, workers));
            match spawned {
                Ok(t) => threads.push(t),
                Err(e) => {
                    stop(&shared, &mut threads);
                    return Err(e);
                }
            }
        }
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get().min(MAX_WORKERS as usize) as u32);
        Ok(ThreadPool {
            shared,
            threads,
            workers,
            cores,
            running: Mutex::new(()),
        })
    }
}

fn stop(shared: &Shared, threads: &mut Vec<JoinHandle<()>>) {
    shared.lock().exit = true;
    shared.work.notify_all();
    for t in threads.drain(..) {
        let _ = t.join();
    }
}

impl Drop for ThreadPool {
    fn drop(&mut self) {
        stop(&self.shared, &mut self.threads);
    }
}

/// Runs the ranges of `job` that `worker` claims (`Claims::in_turn`); together the threads
/// run each once.
fn drain(shared: &Shared, job: &Job, worker: u32, workers: u32) {
    for i in shared.claims.in_turn(0, job.pieces, job.generation, worker, workers) {
        let begin = i * job.piece;
        let end = (begin + job.piece).min(job.count);
        // SAFETY: the range was claimed in this job's generation, and `run` does not return
        // (so the task stays alive) before it is counted finished below.
        let task = unsafe { &*job.task };
        if let Err(p) = catch_unwind(AssertUnwindSafe(|| task(begin, end, worker))) {
            shared.lock().panic.get_or_insert(p);
        }
        // AcqRel: the completions form one release sequence, so `run`, seeing the last,
        // sees every range's writes.
        if shared.finished.0.fetch_add(1, Ordering::AcqRel) + 1 == job.pieces {
            // Under the lock: `run` checks the count and parks under it, so it either saw
            // this completion or is parked and hears the signal.
            if shared.lock().caller_sleeps {
                shared.done.notify_all();
            }
        }
    }
}

fn worker(shared: &Shared, index: u32, workers: u32) {
    // Generation 0 has no job: a thread that starts after the first stage was posted still
    // joins it (the solver's stages need every worker, `concurrent`).
    let mut seen = 0;
    loop {
        spin_until(|| shared.posted.load(Ordering::Acquire) != seen);
        let mut state = shared.lock();
        while state.generation == seen && !state.exit {
            state.sleepers += 1;
            state = shared.work.wait(state).unwrap_or_else(|e| e.into_inner());
            state.sleepers -= 1;
        }
        if state.exit {
            return;
        }
        seen = state.generation;
        let job = state.job;
        drop(state);
        if let Some(job) = job {
            drain(shared, &job, index, workers);
        }
    }
}

impl TaskRunner for ThreadPool {
    fn worker_count(&self) -> u32 {
        self.workers
    }

    /// Each of up to `worker_count()` ranges of one item is claimed by a different thread: a
    /// thread claims its next range only when its last returned, and the caller plus the
    /// `worker_count() − 1` threads, all idle between stages, are enough for all of them. No
    /// more than the machine's cores, though: workers waiting for a descheduled one only
    /// lose time (with a barrier that only spun, 4 workers on 2 cores stepped a pyramid
    /// 2.5× slower than 2).
    fn concurrent(&self) -> u32 {
        self.workers.min(self.cores)
    }

    fn run(&self, count: u32, min_range: u32, task: &Task) {
        if count == 0 {
            return;
        }
        let _one = self.running.lock().unwrap_or_else(|e| e.into_inner());
        // About four ranges per worker for balance, none shorter than `min_range`.
        let piece = count.div_ceil(4 * self.workers).max(min_range).max(1);
        let pieces = count.div_ceil(piece);
        // SAFETY (lifetime erasure): the pointer is reachable only through `state.job` and
        // the copies workers take of it, which claim nothing once every range has finished
        // (`Shared::claims`); `state.job` is cleared below after that.
        let task: *const Task<'static> = unsafe { std::mem::transmute(task as *const Task) };
        let mut state = self.shared.lock();
        state.generation += 1;
        let job = Job {
            task,
            count,
            piece,
            pieces,
            generation: state.generation,
        };
        state.job = Some(job);
        self.shared.finished.0.store(0, Ordering::Relaxed);
        self.shared.posted.store(job.generation, Ordering::Release);
        let wake = state.sleepers > 0;
        drop(state);
        if wake {
            self.shared.work.notify_all();
        }
        drain(&self.shared, &job, 0, self.workers);
        let finished = || self.shared.finished.0.load(Ordering::Acquire) >= pieces;
        if !finished() {
            spin_until(finished);
        }
        let mut state = self.shared.lock();
        while !finished() {
            state.caller_sleeps = true;
            state = self.shared.done.wait(state).unwrap_or_else(|e| e.into_inner());
            state.caller_sleeps = false;
        }
        state.job = None;
        let panic = state.panic.take();
        drop(state);
        if let Some(p) = panic {
            resume_unwind(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicU32, Ordering};

    #[test]
    fn every_item_runs_exactly_once_at_every_worker_count() {
        for workers in 1..=5 {
            let pool = ThreadPool::new(workers).unwrap();
            for count in [1u32, 2, 7, 64, 1000] {
                let hits: Vec<AtomicU32> = (0..count).map(|_| AtomicU32::new(0)).collect();
                pool.run(count, 3, &|s, e, w| {
                    assert!(s < e && e <= count && w < workers);
                    for h in &hits[s as usize..e as usize] {
                        h.fetch_add(1, Ordering::Relaxed);
                    }
                });
                assert!(hits.iter().all(|h| h.load(Ordering::Relaxed) == 1));
            }
        }
    }

    /// Short jobs back to back, so that workers come late to a job or still hold the one
    /// before when the next is posted (claims by generation, `Claims`): every item of every
    /// job runs exactly once before `run` returns.
    #[test]
    fn back_to_back_short_jobs_run_every_item_once() {
        let mut rnd = crate::math::test_rnd::Rnd(0xb0b_5eed);
        for workers in [2, 3] {
            let pool = ThreadPool::new(workers).unwrap();
            for _ in 0..3000 {
                let count = 1 + (rnd.next_u64() % 40) as u32;
                let min_range = 1 + (rnd.next_u64() % 3) as u32;
                let hits: Vec<AtomicU32> = (0..count).map(|_| AtomicU32::new(0)).collect();
                pool.run(count, min_range, &|s, e, w| {
                    assert!(s < e && e <= count && w < workers);
                    for h in &hits[s as usize..e as usize] {
                        h.fetch_add(1, Ordering::Relaxed);
                    }
                });
                assert!(hits.iter().all(|h| h.load(Ordering::Relaxed) == 1));
            }
        }
    }

    #[test]
    fn a_panicking_range_reaches_the_caller_and_the_pool_still_works() {
        let pool = ThreadPool::new(3).unwrap();
        let r = catch_unwind(AssertUnwindSafe(|| {
            pool.run(100, 1, &|s, _, _| {
                if s == 0 {
                    panic!("range 0");
                }
            })
        }));
        assert!(r.is_err());
        let n = AtomicU32::new(0);
        pool.run(100, 1, &|s, e, _| {
            n.fetch_add(e - s, Ordering::Relaxed);
        });
        assert_eq!(n.load(Ordering::Relaxed), 100);
    }
}

//! A barrier and stage gate for workers inside one task (the solver's stages, see
//! `dynamics::solver_stages`): the workers stay inside one task for the whole sub-step loop
//! and wait here between stages, so no thread is woken per stage. The solver uses the
//! generation as a gate (`open` to the next stage when its last block completes,
//! `wait_past` while another worker finishes one), so a worker that is not running holds
//! nobody up unless it is inside a block. A waiting worker spins a little (a stage usually
//! ends within microseconds), then yields its core, then parks on a condition variable, so
//! that workers waiting on a loaded or oversubscribed machine give their cores to the ones
//! still working. It orders nothing; it only waits.

use std::hint::spin_loop;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::{Condvar, Mutex};

/// Busy-wait iterations before yielding.
const SPINS: u32 = 1 << 10;
/// Yields before parking.
const YIELDS: u32 = 1 << 4;

pub(crate) struct Barrier {
    generation: AtomicU32,
    /// Parties parked (or about to park) on `wake`.
    sleepers: AtomicU32,
    lock: Mutex<()>,
    wake: Condvar,
    /// A party panicked: the others stop waiting (and panic too) instead of waiting forever.
    poisoned: AtomicBool,
}

impl Barrier {
    pub(crate) fn new() -> Barrier {
        Barrier {
            generation: AtomicU32::new(0),
            sleepers: AtomicU32::new(0),
            lock: Mutex::new(()),
            wake: Condvar::new(),
            poisoned: AtomicBool::new(false),
        }
    }

    /// The generation (what `open` last set; 0 at first).
    pub(crate) fn generation(&self) -> u32 {
        self.generation.load(Ordering::Acquire)
    }

    /// Sets the generation to `to` (publishing the caller's writes) and wakes the parked.
    pub(crate) fn open(&self, to: u32) {
        self.generation.store(to, Ordering::SeqCst);
        // SeqCst with the sleeper's increment and check in `wait_past`: either it sees the
        // new generation, or this sees it counted and wakes it under the lock.
        if self.sleepers.load(Ordering::SeqCst) > 0 {
            drop(self.lock.lock().unwrap_or_else(|e| e.into_inner()));
            self.wake.notify_all();
        }
    }

    /// Returns when the generation is no longer `generation`; panics if another party
    /// panicked.
    pub(crate) fn wait_past(&self, generation: u32) {
        let passed = || self.generation.load(Ordering::Acquire) != generation;
        for _ in 0..SPINS {
            if passed() {
                return;
            }
            spin_loop();
        }
        for _ in 0..YIELDS {
            if passed() {
                return;
            }
            self.check_poison();
            std::thread::yield_now();
        }
        let mut guard = self.lock.lock().unwrap_or_else(|e| e.into_inner());
        self.sleepers.fetch_add(1, Ordering::SeqCst);
        while self.generation.load(Ordering::SeqCst) == generation && !self.poisoned.load(Ordering::SeqCst) {
            guard = self.wake.wait(guard).unwrap_or_else(|e| e.into_inner());
        }
        self.sleepers.fetch_sub(1, Ordering::SeqCst);
        drop(guard);
        if self.generation.load(Ordering::Acquire) == generation {
            self.check_poison();
        }
    }

    fn check_poison(&self) {
        if self.poisoned.load(Ordering::SeqCst) {
            panic!("another solver worker panicked");
        }
    }

    /// Marks the barrier broken (a party panicked and will not arrive) and wakes the parked.
    pub(crate) fn poison(&self) {
        self.poisoned.store(true, Ordering::SeqCst);
        drop(self.lock.lock().unwrap_or_else(|e| e.into_inner()));
        self.wake.notify_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicU64;

    /// `parties` threads pass `stages` stages: each adds one to a counter per stage, and
    /// whoever adds the last opens the gate to the next stage.
    fn stages(parties: u32, stages: u32, slow: bool) {
        let gate = Barrier::new();
        let counter = AtomicU64::new(0);
        std::thread::scope(|s| {
            for p in 0..parties {
                let (gate, counter) = (&gate, &counter);
                s.spawn(move || {
                    for stage in 0..stages {
                        if slow && p == 0 && stage % 8 == 0 {
                            // Long enough for the others to reach the parking stage.
                            std::thread::sleep(std::time::Duration::from_millis(2));
                        }
                        let total = counter.fetch_add(1, Ordering::AcqRel) + 1;
                        if total == u64::from((stage + 1) * parties) {
                            gate.open(stage + 1);
                        }
                        gate.wait_past(stage);
                        // Everyone has counted this stage.
                        assert!(counter.load(Ordering::Acquire) >= u64::from((stage + 1) * parties));
                        assert!(gate.generation() > stage);
                    }
                });
            }
        });
    }

    #[test]
    fn no_party_passes_the_gate_before_all_counted() {
        stages(3, 300, false);
    }

    #[test]
    fn parked_parties_wake_when_the_gate_opens() {
        stages(3, 40, true);
    }

    #[test]
    fn more_parties_than_cores_finish() {
        // Oversubscribed: the waiting parties must yield and park for the others to run.
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get()) as u32;
        stages(2 * cores + 1, 100, false);
    }

    #[test]
    fn a_poisoned_gate_releases_the_waiting_parties() {
        let gate = Barrier::new();
        std::thread::scope(|s| {
            let waiter = s.spawn(|| gate.wait_past(0));
            std::thread::sleep(std::time::Duration::from_millis(20));
            gate.poison();
            assert!(waiter.join().is_err());
        });
    }
}

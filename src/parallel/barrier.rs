//! A barrier for workers that all run at once (the solver's stages, see
//! `dynamics::solver_stages`): the workers stay inside one task for the whole sub-step loop
//! and meet here between stages, so no thread is woken per stage. A waiting worker spins a
//! little (a stage usually ends within microseconds), then yields its core, then parks on a
//! condition variable, so that workers waiting on a loaded or oversubscribed machine give
//! their cores to the ones still working. It orders nothing; it only waits.

use std::hint::spin_loop;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::{Condvar, Mutex};

/// Busy-wait iterations before yielding.
const SPINS: u32 = 1 << 10;
/// Yields before parking.
const YIELDS: u32 = 1 << 4;

pub(crate) struct Barrier {
    parties: u32,
    arrived: AtomicU32,
    generation: AtomicU32,
    /// Parties parked (or about to park) on `wake`.
    sleepers: AtomicU32,
    lock: Mutex<()>,
    wake: Condvar,
    /// A party panicked: the others stop waiting (and panic too) instead of waiting forever.
    poisoned: AtomicBool,
}

impl Barrier {
    pub(crate) fn new(parties: u32) -> Barrier {
        Barrier {
            parties,
            arrived: AtomicU32::new(0),
            generation: AtomicU32::new(0),
            sleepers: AtomicU32::new(0),
            lock: Mutex::new(()),
            wake: Condvar::new(),
            poisoned: AtomicBool::new(false),
        }
    }

    /// Returns when all `parties` have called it (again). Every write made before the call,
    /// on any party, is visible after it. Panics if another party panicked.
    pub(crate) fn wait(&self) {
        let generation = self.generation.load(Ordering::Acquire);
        // AcqRel: the last party to arrive sees every party's writes (the arrivals form one
        // release sequence) and publishes them with the generation below.
        if self.arrived.fetch_add(1, Ordering::AcqRel) + 1 == self.parties {
            self.arrived.store(0, Ordering::Relaxed);
            self.generation.store(generation.wrapping_add(1), Ordering::SeqCst);
            // SeqCst with the sleeper's increment and check below: either it sees the new
            // generation, or this sees it counted and wakes it under the lock.
            if self.sleepers.load(Ordering::SeqCst) > 0 {
                drop(self.lock.lock().unwrap_or_else(|e| e.into_inner()));
                self.wake.notify_all();
            }
            return;
        }
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

    fn rounds(parties: u32, rounds: u64, slow: bool) {
        let barrier = Barrier::new(parties);
        let counter = AtomicU64::new(0);
        std::thread::scope(|s| {
            for p in 0..parties {
                let (barrier, counter) = (&barrier, &counter);
                s.spawn(move || {
                    for round in 0..rounds {
                        if slow && p == 0 && round % 8 == 0 {
                            // Long enough for the others to reach the parking stage.
                            std::thread::sleep(std::time::Duration::from_millis(2));
                        }
                        counter.fetch_add(1, Ordering::Relaxed);
                        barrier.wait();
                        // Everyone has counted this round and nobody the next one yet.
                        assert_eq!(counter.load(Ordering::Relaxed), (round + 1) * parties as u64);
                        barrier.wait();
                    }
                });
            }
        });
    }

    #[test]
    fn no_party_passes_a_barrier_before_all_reached_it() {
        rounds(3, 300, false);
    }

    #[test]
    fn parked_parties_wake_when_the_last_arrives() {
        rounds(3, 40, true);
    }

    #[test]
    fn more_parties_than_cores_finish() {
        // Oversubscribed: the waiting parties must yield and park for the others to run.
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get()) as u32;
        rounds(2 * cores + 1, 100, false);
    }

    #[test]
    fn a_poisoned_barrier_releases_the_waiting_parties() {
        let barrier = Barrier::new(2);
        std::thread::scope(|s| {
            let waiter = s.spawn(|| barrier.wait());
            std::thread::sleep(std::time::Duration::from_millis(20));
            barrier.poison();
            assert!(waiter.join().is_err());
        });
    }
}

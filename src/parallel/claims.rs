//! Handing a stage's ranges to the threads that run it, each thread mostly its own share.
//!
//! Thread `k` of `n` starts at the first range of its share (the `k`-th `n`-th of them),
//! claims forward from there while the ranges are free (wrapping round), then backward from
//! just before it, each while free: Box2D v3's `b2ExecuteStage`. So a thread gets the same
//! ranges of the same items stage after stage (a colour's constraints, the bodies) and step
//! after step while nothing is late, and their data stays in its core's cache; it takes from
//! another's share only what that one has not reached. Handed out in order instead (one
//! counter), ranges changed hands from stage to stage: the pile's sub-steps took as long on
//! two workers as on one, each worker spending about as long as the single one had, most of
//! it fetching what the other had written.
//!
//! A range's claim is a number on a cache line of its own: the epoch of the run that last
//! claimed it. Epochs only grow, so claims are never reset (a pass resetting them would move
//! every line to one core), and a thread still holding an earlier run claims nothing: every
//! range of that run was claimed before the run ended.

use std::sync::atomic::{AtomicU64, Ordering};

/// A value alone on its cache line.
#[derive(Default)]
#[repr(align(64))]
pub(crate) struct Line<T>(pub(crate) T);

/// One claim per range, reused from run to run.
#[derive(Default)]
pub(crate) struct Claims {
    slots: Vec<Line<AtomicU64>>,
}

impl Claims {
    /// Claims for at least `len` ranges (new ones never claimed).
    pub(crate) fn reserve(&mut self, len: usize) {
        if self.slots.len() < len {
            self.slots.resize_with(len, Line::default);
        }
    }

    /// The ranges `first..first + count` claimed in turn by thread `k` of `n` in the run of
    /// `epoch` (above every earlier run's, never 0), as described in the module doc. Run by
    /// every thread that comes to a run, the iterators together yield each range exactly
    /// once: going forward (wrapping round), a thread stops only at a range another one
    /// claimed, which that one goes on from, so no range is left. Going backward is for
    /// balance: a thread done with its share takes the end of the previous thread's share,
    /// which that one would reach last.
    pub(crate) fn in_turn(&self, first: u32, count: u32, epoch: u64, k: u32, n: u32) -> impl Iterator<Item = u32> + '_ {
        let slots = &self.slots[first as usize..(first + count) as usize];
        let claim = move |i: u32| {
            let c = &slots[i as usize].0;
            // The load first: a range already taken costs no write to its line.
            (c.load(Ordering::Relaxed) < epoch && c.fetch_max(epoch, Ordering::Relaxed) < epoch).then_some(i)
        };
        let start = share_start(k, count, n);
        let forward = (start..count).chain(0..start);
        let backward = (0..start).rev().chain((start..count).rev());
        forward.map_while(claim).chain(backward.map_while(claim))
    }
}

/// The first of `count` items in share `k` of `n` (shares as even as can be).
pub(crate) fn share_start(k: u32, count: u32, n: u32) -> u32 {
    let (per, extra) = (count / n.max(1), count % n.max(1));
    (per * k + k.min(extra)) % count.max(1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::test_rnd::Rnd;
    use std::sync::atomic::AtomicU32;

    #[test]
    fn shares_start_in_order_and_cover_the_items() {
        for count in 1..200u32 {
            for n in 1..9u32 {
                let starts: Vec<u32> = (0..n).map(|k| share_start(k, count, n)).collect();
                assert!(starts.iter().all(|&s| s < count));
                if count >= n {
                    // Distinct, increasing, the first at 0, each share count / n or one more.
                    assert_eq!(starts[0], 0);
                    for w in starts.windows(2) {
                        assert!(w[1] > w[0] && w[1] - w[0] >= count / n && w[1] - w[0] <= count / n + 1);
                    }
                }
            }
        }
    }

    /// Threads that start late, stall between claims or never come: every range of every
    /// run is yielded exactly once, and a thread still holding an earlier epoch gets none.
    #[test]
    fn every_range_is_claimed_once_whoever_comes() {
        let mut rnd = Rnd(0x5eed_c1a1);
        let mut claims = Claims::default();
        let mut epoch = 0;
        for _ in 0..300 {
            let first = (rnd.next_u64() % 50) as u32;
            let count = 1 + (rnd.next_u64() % 80) as u32;
            let n = 1 + (rnd.next_u64() % 4) as u32;
            let present: Vec<bool> = (0..n).map(|_| rnd.next_u64() % 4 != 0).collect();
            let stalls: Vec<u64> = (0..n).map(|_| rnd.next_u64()).collect();
            claims.reserve((first + count) as usize);
            epoch += 1;
            let hits: Vec<AtomicU32> = (0..count).map(|_| AtomicU32::new(0)).collect();
            std::thread::scope(|s| {
                for k in 0..n {
                    let (claims, hits, stall) = (&claims, &hits, stalls[k as usize]);
                    let here = present[k as usize] || k == 0;
                    s.spawn(move || {
                        if !here {
                            return;
                        }
                        for (j, i) in claims.in_turn(first, count, epoch, k, n).enumerate() {
                            hits[i as usize].fetch_add(1, Ordering::Relaxed);
                            if (stall >> (j % 64)) & 1 == 1 {
                                std::thread::yield_now();
                            }
                        }
                    });
                }
            });
            assert!(hits.iter().all(|h| h.load(Ordering::Relaxed) == 1));
            // A thread late from this run finds nothing left; nor does one from an earlier run.
            assert_eq!(claims.in_turn(first, count, epoch, 0, n).count(), 0);
            assert_eq!(claims.in_turn(first, count, epoch - 1, n - 1, n).count(), 0);
        }
    }
}

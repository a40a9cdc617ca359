//! Generational slot storage: the one id pool behind every object kind in a world.
//!
//! A handle is `{index, generation}`. The generation's top 12 bits carry the owning world's
//! tag and the low 20 bits count reuses of the slot. A slot whose counter would wrap is
//! retired, so an old handle never revives.
//!
//! # World tags
//!
//! Tags come from one process-wide registry of live tags ([`WorldTag::acquire`]): a tag is
//! never held by two live worlds, so an id of one live world never names an object of
//! another. At most [`MAX_LIVE_WORLDS`] (4,095) worlds can be alive at once; creating one
//! more fails. A destroyed world's tag returns to the registry and is handed out again
//! later, which leaves one honest gap: an id kept from a *destroyed* world may match an
//! object of a later world with the same tag. Two things make that unlikely:
//!
//! * tags are handed out in turn (a cursor cycles through 1..=4095, skipping live ones), not
//!   lowest-first, so a freed tag comes back only after the cursor went round: at least
//!   4,095 − (live worlds) world creations later;
//! * every tag has an epoch, counted up each time it is handed out, and a world's slots
//!   start their reuse counters at `1 + (epoch mod 16) · 32,768`, so the worlds that get a
//!   tag in 16 consecutive turns count each slot's first 32,768 reuses in disjoint ranges.
//!
//! So an id from a destroyed world is rejected by the next 15 worlds that get its tag (at
//! least 15 · (4,095 − live) world creations) unless a slot was reused 32,768 times or more
//! in one of them; after that it is accepted only where slot index and reuse count happen
//! to coincide. Ids of live worlds are never confused.

use std::sync::Mutex;

const COUNTER_BITS: u32 = 20;
const COUNTER_MASK: u32 = (1 << COUNTER_BITS) - 1;
const TAG_BITS: u32 = 32 - COUNTER_BITS;
const TAG_MASK: u32 = (1 << TAG_BITS) - 1;

/// Most worlds alive at once: one per non-zero tag.
pub const MAX_LIVE_WORLDS: usize = TAG_MASK as usize;

/// Epochs of a tag whose slots count in disjoint ranges, and the width of each range.
const EPOCHS: u32 = 16;
const EPOCH_SPACING: u32 = 1 << 15;
const _: () = assert!((EPOCHS - 1) * EPOCH_SPACING + 1 < COUNTER_MASK);

/// A generational handle. The all-zero handle is null: generation 0 is never issued.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct Handle {
    pub index: u32,
    pub generation: u32,
}

impl Handle {
    pub const NULL: Handle = Handle {
        index: 0,
        generation: 0,
    };

    pub fn is_null(&self) -> bool {
        self.generation == 0
    }
}

/// A registry of live world tags (one process-wide instance, `REGISTRY`).
struct Registry {
    /// Bit `t` set while tag `t` belongs to a live world (bit 0, the null tag, never).
    live: [u64; (MAX_LIVE_WORLDS + 1).div_ceil(64)],
    /// Number of live tags.
    count: usize,
    /// The tag tried first by the next acquisition.
    cursor: u32,
    /// Times each tag was handed out.
    epochs: [u32; MAX_LIVE_WORLDS + 1],
}

impl Registry {
    const fn new() -> Registry {
        Registry {
            live: [0; (MAX_LIVE_WORLDS + 1).div_ceil(64)],
            count: 0,
            cursor: 1,
            epochs: [0; MAX_LIVE_WORLDS + 1],
        }
    }

    fn is_live(&self, t: u32) -> bool {
        self.live[t as usize / 64] & (1 << (t % 64)) != 0
    }

    /// The stamp (tag and epoch) of the next free tag from the cursor on, now live; `None`
    /// when every tag is live.
    fn acquire(&mut self) -> Option<u32> {
        if self.count >= MAX_LIVE_WORLDS {
            return None;
        }
        let mut t = self.cursor;
        while self.is_live(t) {
            t = t % TAG_MASK + 1;
        }
        self.live[t as usize / 64] |= 1 << (t % 64);
        self.count += 1;
        self.cursor = t % TAG_MASK + 1;
        let epoch = self.epochs[t as usize].wrapping_add(1);
        self.epochs[t as usize] = epoch;
        Some(t | (epoch % EPOCHS) << TAG_BITS)
    }

    fn release(&mut self, t: u32) {
        debug_assert!(self.is_live(t));
        self.live[t as usize / 64] &= !(1 << (t % 64));
        self.count -= 1;
    }
}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry::new());

fn registry() -> std::sync::MutexGuard<'static, Registry> {
    // The registry is consistent between any two statements, so a poisoned lock (a panic
    // elsewhere while it was held) does not matter.
    REGISTRY.lock().unwrap_or_else(|e| e.into_inner())
}

/// A world's lease on its tag: returned to the registry when dropped (with the world).
#[derive(Debug)]
pub struct WorldTag {
    stamp: u32,
}

impl WorldTag {
    /// Leases the next free tag after the last one handed out (cycling through 1..=4095).
    /// `None` when [`MAX_LIVE_WORLDS`] worlds are alive.
    pub fn acquire() -> Option<WorldTag> {
        registry().acquire().map(|stamp| WorldTag { stamp })
    }

    /// The tag (1..=4095) carried in the top bits of every id of the world.
    pub fn tag(&self) -> u32 {
        self.stamp & TAG_MASK
    }

    /// What the world's pools are made from (`Pool::new`): the tag and its epoch.
    pub fn stamp(&self) -> u32 {
        self.stamp
    }
}

impl Drop for WorldTag {
    fn drop(&mut self) {
        registry().release(self.tag());
    }
}

struct Slot<T> {
    /// Counter of the current (or next) occupant; never 0.
    counter: u32,
    value: Option<T>,
}

pub struct Pool<T> {
    tag: u32,
    /// Counter of a new slot's first occupant (from the tag's epoch).
    first_counter: u32,
    slots: Vec<Slot<T>>,
    free: Vec<u32>,
    len: usize,
}

impl<T> Pool<T> {
    /// A pool whose handles carry `stamp`'s tag (`WorldTag::stamp`; a bare tag 1..=4095 in
    /// unit tests).
    pub fn new(stamp: u32) -> Self {
        let tag = stamp & TAG_MASK;
        debug_assert!(tag != 0);
        Pool {
            tag,
            first_counter: 1 + (stamp >> TAG_BITS) % EPOCHS * EPOCH_SPACING,
            slots: Vec::new(),
            free: Vec::new(),
            len: 0,
        }
    }

    #[inline]
    fn handle(&self, index: u32, counter: u32) -> Handle {
        Handle {
            index,
            generation: (self.tag << COUNTER_BITS) | counter,
        }
    }

    /// Room for `total` live objects without allocating (slots and free list).
    pub(crate) fn reserve_total(&mut self, total: usize) {
        self.slots.reserve(total.saturating_sub(self.slots.len()));
        self.free.reserve(total.saturating_sub(self.free.len()));
    }

    /// The same slots, handles and free list with each live value mapped.
    pub(crate) fn map<U>(&self, mut f: impl FnMut(&T) -> U) -> Pool<U> {
        Pool {
            tag: self.tag,
            first_counter: self.first_counter,
            slots: self
                .slots
                .iter()
                .map(|s| Slot {
                    counter: s.counter,
                    value: s.value.as_ref().map(&mut f),
                })
                .collect(),
            free: self.free.clone(),
            len: self.len,
        }
    }

    pub fn insert(&mut self, value: T) -> Handle {
        self.len += 1;
        if let Some(index) = self.free.pop() {
            let slot = &mut self.slots[index as usize];
            slot.value = Some(value);
            let counter = slot.counter;
            return self.handle(index, counter);
        }
        let index = self.slots.len() as u32;
        let counter = self.first_counter;
        self.slots.push(Slot {
            counter,
            value: Some(value),
        });
        self.handle(index, counter)
    }

    #[inline]
    fn slot_index(&self, h: Handle) -> Option<usize> {
        if h.generation >> COUNTER_BITS != self.tag {
            return None;
        }
        let slot = self.slots.get(h.index as usize)?;
        (slot.value.is_some() && slot.counter == h.generation & COUNTER_MASK).then_some(h.index as usize)
    }

    pub fn contains(&self, h: Handle) -> bool {
        self.slot_index(h).is_some()
    }

    #[inline]
    pub fn get(&self, h: Handle) -> Option<&T> {
        let i = self.slot_index(h)?;
        self.slots[i].value.as_ref()
    }

    #[inline]
    pub fn get_mut(&mut self, h: Handle) -> Option<&mut T> {
        let i = self.slot_index(h)?;
        self.slots[i].value.as_mut()
    }

    pub fn remove(&mut self, h: Handle) -> Option<T> {
        let i = self.slot_index(h)?;
        let slot = &mut self.slots[i];
        let value = slot.value.take();
        self.len -= 1;
        if slot.counter < COUNTER_MASK {
            slot.counter += 1;
            self.free.push(i as u32);
        }
        // else: the slot is retired for good, so no handle to it can ever revive.
        value
    }

    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Slots in use or free: every live object's index is below it.
    pub(crate) fn slot_count(&self) -> usize {
        self.slots.len()
    }

    /// Direct slot access by index for hot loops that hold indices, not handles.
    #[inline]
    pub fn at(&self, index: u32) -> &T {
        self.slots[index as usize].value.as_ref().expect("live slot")
    }

    /// The pool's slots for tasks on several threads, each reaching objects by slot index
    /// that no other running task reaches (`parallel::Disjoint`).
    pub(crate) fn disjoint(&mut self) -> DisjointPool<'_, T> {
        DisjointPool(crate::parallel::Disjoint::new(&mut self.slots), self.tag)
    }

    #[inline]
    pub fn at_mut(&mut self, index: u32) -> &mut T {
        self.slots[index as usize].value.as_mut().expect("live slot")
    }

    /// The handle of the live object at `index`.
    pub fn handle_at(&self, index: u32) -> Option<Handle> {
        let slot = self.slots.get(index as usize)?;
        slot.value.as_ref().map(|_| self.handle(index, slot.counter))
    }

    /// Live objects in slot order (deterministic).
    pub fn iter(&self) -> impl Iterator<Item = (Handle, &T)> {
        self.slots
            .iter()
            .enumerate()
            .filter_map(move |(i, s)| s.value.as_ref().map(|v| (self.handle(i as u32, s.counter), v)))
    }

    /// Live objects in slot order, mutably.
    pub(crate) fn values_mut(&mut self) -> impl Iterator<Item = &mut T> {
        self.slots.iter_mut().filter_map(|s| s.value.as_mut())
    }

    /// Two distinct live objects mutably at once.
    pub fn pair_mut(&mut self, a: u32, b: u32) -> (&mut T, &mut T) {
        assert!(a != b);
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        let (left, right) = self.slots.split_at_mut(hi as usize);
        let x = left[lo as usize].value.as_mut().expect("live slot");
        let y = right[0].value.as_mut().expect("live slot");
        if a < b {
            (x, y)
        } else {
            (y, x)
        }
    }

    #[cfg(test)]
    fn force_counter(&mut self, index: u32, counter: u32) {
        self.slots[index as usize].counter = counter;
    }
}

/// The reuse counter of a handle (its generation without the world tag).
pub(crate) fn counter_of(h: Handle) -> u32 {
    h.generation & COUNTER_MASK
}

/// A handle with `counter` and the tag of `tag`; the null handle for counter 0. `None` when
/// the counter does not fit.
pub(crate) fn handle_with_tag(index: u32, counter: u32, tag: u32) -> Option<Handle> {
    if counter > COUNTER_MASK {
        return None;
    }
    if counter == 0 {
        return (index == 0).then_some(Handle::NULL);
    }
    Some(Handle {
        index,
        generation: (tag & TAG_MASK) << COUNTER_BITS | counter,
    })
}

/// Snapshots (`snapshot/`) store a pool's slots with their reuse counters, its free list and
/// its first counter, not its tag: read back, the pool carries the reading world's tag, so
/// every id keeps its index and counter and a restored world hands out the same next ids.
impl<T: crate::snapshot::Snap> crate::snapshot::Snap for Pool<T> {
    fn put(&self, w: &mut crate::snapshot::Writer) {
        let Pool {
            tag: _,
            first_counter,
            slots,
            free,
            len,
        } = self;
        first_counter.put(w);
        w.put_len(slots.len());
        w.within("#counter", |w| u32::put_all(slots.iter().map(|s| &s.counter), w));
        // `Option::<T>::put_all`'s bytes: the flags, then the live values field by field
        // from a list of them (each field's pass walks that list, not every slot).
        w.within("#some", |w| w.values(slots.iter().map(|s| [s.value.is_some() as u8])));
        let live: Vec<&T> = slots.iter().filter_map(|s| s.value.as_ref()).collect();
        T::put_all(live.iter().copied(), w);
        w.within("#free", |w| free.put(w));
        w.put_len(*len);
    }
    fn get(r: &mut crate::snapshot::Reader) -> crate::snapshot::ReadResult<Self> {
        use crate::snapshot::bad;
        let first_counter = u32::get(r)?;
        let n = r.count()?;
        let counters = r.within("#counter", |r| u32::get_all(n, r))?;
        if let Some(c) = counters.iter().find(|&&c| c == 0 || c > COUNTER_MASK) {
            return bad(format!("snapshot corrupted: slot counter {c} out of range"));
        }
        // The bytes `Option::<T>::get_all` reads (flags, then the live values), moved
        // straight into the slots: the values are large, and each move is a copy.
        let some = r.within("#some", |r| bool::get_all(n, r))?;
        let live = some.iter().filter(|&&s| s).count();
        let mut values = T::get_all(live, r)?.into_iter();
        let slots: Vec<_> = counters
            .into_iter()
            .zip(some)
            .map(|(counter, s)| Slot {
                counter,
                value: if s { values.next() } else { None },
            })
            .collect();
        let free = r.within("#free", Vec::<u32>::get)?;
        let len = r.within("#len", usize::get)?;
        if len != live
            || first_counter == 0
            || first_counter > COUNTER_MASK
            || free
                .iter()
                .any(|&i| !matches!(slots.get(i as usize), Some(s) if s.value.is_none()))
        {
            return bad("snapshot corrupted: a pool's slots, free list and count disagree");
        }
        Ok(Pool {
            tag: r.tag & TAG_MASK,
            first_counter,
            slots,
            free,
            len,
        })
    }
}

/// A pool's live objects by slot index, for tasks that each own distinct slots.
pub(crate) struct DisjointPool<'a, T>(crate::parallel::Disjoint<'a, Slot<T>>, u32);

impl<T> DisjointPool<'_, T> {
    /// The live object in slot `index`.
    ///
    /// # Safety
    /// While the returned reference lives, no other call may ask for the same `index`.
    #[allow(clippy::mut_from_ref)]
    #[inline]
    pub(crate) unsafe fn at_mut(&self, index: u32) -> &mut T {
        self.0.at(index as usize).value.as_mut().expect("live slot")
    }

    /// The handle of the live object in slot `index`, and the object.
    ///
    /// # Safety
    /// As `at_mut`.
    #[inline]
    #[allow(clippy::mut_from_ref)]
    pub(crate) unsafe fn handle_and_mut(&self, index: u32) -> (Handle, &mut T) {
        let slot = self.0.at(index as usize);
        let handle = Handle {
            index,
            generation: (self.1 << COUNTER_BITS) | slot.counter,
        };
        (handle, slot.value.as_mut().expect("live slot"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stale_and_foreign_handles_are_rejected() {
        let mut a: Pool<i32> = Pool::new(1);
        let b: Pool<i32> = Pool::new(2);
        let h = a.insert(7);
        assert_eq!(a.get(h), Some(&7));
        assert!(!b.contains(h));
        assert!(!a.contains(Handle::NULL));
        assert_eq!(a.remove(h), Some(7));
        assert!(!a.contains(h));
        let h2 = a.insert(8);
        assert_eq!(h2.index, h.index);
        assert!(a.get(h).is_none(), "a reused slot must not revive the old handle");
        assert_eq!(a.get(h2), Some(&8));
        assert_eq!(a.len(), 1);
    }

    #[test]
    fn exhausted_slot_is_retired() {
        let mut p: Pool<u8> = Pool::new(3);
        let h = p.insert(1);
        p.force_counter(h.index, COUNTER_MASK);
        let h = p.handle(h.index, COUNTER_MASK);
        p.remove(h);
        let h2 = p.insert(2);
        assert_ne!(h2.index, h.index);
        assert!(!p.contains(h));
    }

    #[test]
    fn tags_of_live_worlds_never_repeat_over_many_generations_of_worlds() {
        // The process-wide registry, shared with tests running in parallel: one world lives
        // throughout while 10,000 others (more than the 4,095 tags) come and go.
        let keeper = WorldTag::acquire().expect("a free tag");
        let mut kept: Pool<&str> = Pool::new(keeper.stamp());
        let mine = kept.insert("keeper's body");
        for round in 0..10_000 {
            let other = WorldTag::acquire().expect("a free tag");
            assert_ne!(
                other.tag(),
                keeper.tag(),
                "round {round}: the live world's tag was handed out again"
            );
            let mut pool: Pool<&str> = Pool::new(other.stamp());
            let theirs = pool.insert("other body");
            // Same slot index, different world: never confused either way.
            assert_eq!(theirs.index, mine.index);
            assert!(!kept.contains(theirs), "round {round}");
            assert!(!pool.contains(mine), "round {round}");
            assert_eq!(kept.get(mine), Some(&"keeper's body"));
        }
    }

    // The tests below use a registry of their own, so they neither see nor disturb the
    // worlds other tests create in parallel.

    #[test]
    fn tags_are_handed_out_in_turn_not_lowest_first() {
        let mut r = Box::new(Registry::new());
        let a = r.acquire().unwrap() & TAG_MASK;
        let b = r.acquire().unwrap() & TAG_MASK;
        assert_eq!((a, b), (1, 2));
        r.release(a);
        // The freed tag comes back only after the cursor went round every other tag.
        for expected in 3..=TAG_MASK {
            assert_eq!(r.acquire().unwrap() & TAG_MASK, expected);
            r.release(expected);
        }
        assert_eq!(r.acquire().unwrap() & TAG_MASK, 1, "round again: tag 1 is free");
        assert_eq!(r.acquire().unwrap() & TAG_MASK, 3, "tag 2 is live: skipped");
    }

    #[test]
    fn no_tag_is_leased_while_every_tag_is_live_and_a_released_one_comes_back() {
        let mut r = Box::new(Registry::new());
        let mut tags: Vec<u32> = std::iter::from_fn(|| r.acquire()).map(|s| s & TAG_MASK).collect();
        assert_eq!(tags.len(), MAX_LIVE_WORLDS);
        assert!(r.acquire().is_none(), "4,096th live world");
        tags.sort_unstable();
        tags.dedup();
        assert_eq!(tags.len(), MAX_LIVE_WORLDS, "a tag was leased twice");
        assert!(!tags.contains(&0), "the null tag");
        r.release(1234);
        assert_eq!(r.acquire().map(|s| s & TAG_MASK), Some(1234));
        assert!(r.acquire().is_none());
    }

    #[test]
    fn a_destroyed_worlds_ids_are_rejected_by_the_next_15_worlds_that_reuse_its_tag() {
        let mut r = Box::new(Registry::new());
        let first = r.acquire().unwrap();
        let tag = first & TAG_MASK;
        let mut old: Pool<u32> = Pool::new(first);
        // Ids of slots reused a few times, as a game leaves them.
        let mut stale = Vec::new();
        for k in 0..64 {
            let h = old.insert(k);
            if k % 3 == 0 {
                old.remove(h);
                stale.push(h);
                stale.push(old.insert(k));
            } else {
                stale.push(h);
            }
        }
        r.release(tag);
        let mut turns = 0;
        let mut creations = 0;
        while turns < EPOCHS - 1 {
            let stamp = r.acquire().unwrap();
            creations += 1;
            r.release(stamp & TAG_MASK);
            if stamp & TAG_MASK != tag {
                continue;
            }
            turns += 1;
            let mut new: Pool<u32> = Pool::new(stamp);
            for k in 0..64 {
                let h = new.insert(k);
                if k % 2 == 0 {
                    new.remove(h);
                    new.insert(k);
                }
            }
            for h in &stale {
                assert!(!new.contains(*h), "turn {turns}: the stale id {h:?} matched");
            }
        }
        assert_eq!(
            creations,
            (EPOCHS - 1) * TAG_MASK,
            "each turn is a full round of the tags"
        );
    }
}

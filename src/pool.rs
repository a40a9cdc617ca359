//! Generational slot storage: the one id pool behind every object kind in a world.
//!
//! A handle is `{index, generation}`. The generation's top bits carry a tag unique to the
//! owning world, so a handle from another world never matches; the low bits count reuses
//! of the slot. A slot whose counter would wrap is retired, so an old handle never revives.

use std::sync::atomic::{AtomicU32, Ordering};

const COUNTER_BITS: u32 = 20;
const COUNTER_MASK: u32 = (1 << COUNTER_BITS) - 1;
const TAG_MASK: u32 = (1 << (32 - COUNTER_BITS)) - 1;

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

static NEXT_TAG: AtomicU32 = AtomicU32::new(1);

/// A fresh, non-zero tag for a new world (wraps after 4,095 worlds).
pub fn next_world_tag() -> u32 {
    loop {
        let t = NEXT_TAG.fetch_add(1, Ordering::Relaxed) & TAG_MASK;
        if t != 0 {
            return t;
        }
    }
}

struct Slot<T> {
    /// Counter of the current (or next) occupant; never 0.
    counter: u32,
    value: Option<T>,
}

pub struct Pool<T> {
    tag: u32,
    slots: Vec<Slot<T>>,
    free: Vec<u32>,
    len: usize,
}

impl<T> Pool<T> {
    pub fn new(tag: u32) -> Self {
        debug_assert!(tag != 0 && tag <= TAG_MASK);
        Pool {
            tag,
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

    pub fn insert(&mut self, value: T) -> Handle {
        self.len += 1;
        if let Some(index) = self.free.pop() {
            let slot = &mut self.slots[index as usize];
            slot.value = Some(value);
            let counter = slot.counter;
            return self.handle(index, counter);
        }
        let index = self.slots.len() as u32;
        self.slots.push(Slot {
            counter: 1,
            value: Some(value),
        });
        self.handle(index, 1)
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

    /// Direct slot access by index for hot loops that hold indices, not handles.
    #[inline]
    pub fn at(&self, index: u32) -> &T {
        self.slots[index as usize].value.as_ref().expect("live slot")
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
}

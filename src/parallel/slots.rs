//! Disjoint mutable access to a slice from several tasks at once.

use std::marker::PhantomData;

/// A slice that tasks running at the same time may each write through, at indices no other
/// running task touches. The stages index it by their own items (a contact's slot, a body's
/// slot), which are distinct by construction; `at` checks bounds.
pub(crate) struct Disjoint<'a, T> {
    ptr: *mut T,
    len: usize,
    _borrow: PhantomData<&'a mut [T]>,
}

// Tasks on other threads each reach distinct elements: the same guarantee `&mut [T]`
// gives through `split_at_mut`, so `T: Send` suffices.
unsafe impl<T: Send> Sync for Disjoint<'_, T> {}
unsafe impl<T: Send> Send for Disjoint<'_, T> {}

impl<'a, T> Disjoint<'a, T> {
    pub(crate) fn new(slice: &'a mut [T]) -> Self {
        Disjoint {
            ptr: slice.as_mut_ptr(),
            len: slice.len(),
            _borrow: PhantomData,
        }
    }

    /// The element at `i`.
    ///
    /// # Safety
    /// While the returned reference lives, no other call may ask for the same `i`.
    #[allow(clippy::mut_from_ref)]
    #[inline]
    pub(crate) unsafe fn at(&self, i: usize) -> &mut T {
        assert!(i < self.len, "index {i} out of {}", self.len);
        &mut *self.ptr.add(i)
    }

    /// The elements `start..end`.
    ///
    /// # Safety
    /// While the returned slice lives, no other call may ask for any of its indices.
    #[allow(clippy::mut_from_ref)]
    #[inline]
    pub(crate) unsafe fn range(&self, start: usize, end: usize) -> &mut [T] {
        assert!(
            start <= end && end <= self.len,
            "range {start}..{end} out of {}",
            self.len
        );
        std::slice::from_raw_parts_mut(self.ptr.add(start), end - start)
    }
}

/// One value that several tasks running at the same time reach mutably, each touching only
/// parts no other task touches until they next meet at a barrier (the solver's colour
/// sweeps: a worker's batches and the bodies they write, a worker's share of the bodies).
pub(crate) struct SharedMut<'a, T: ?Sized> {
    ptr: *mut T,
    _borrow: PhantomData<&'a mut T>,
}

// As `Disjoint`: tasks on other threads reach disjoint parts.
unsafe impl<T: ?Sized + Send> Sync for SharedMut<'_, T> {}
unsafe impl<T: ?Sized + Send> Send for SharedMut<'_, T> {}

impl<'a, T: ?Sized> SharedMut<'a, T> {
    pub(crate) fn new(value: &'a mut T) -> Self {
        SharedMut {
            ptr: value,
            _borrow: PhantomData,
        }
    }

    /// The value.
    ///
    /// # Safety
    /// Until the next barrier, what the caller writes through it no other task reads or
    /// writes, and what it reads no other task writes (except with the bits already there).
    #[allow(clippy::mut_from_ref)]
    #[inline]
    pub(crate) unsafe fn get(&self) -> &mut T {
        &mut *self.ptr
    }
}

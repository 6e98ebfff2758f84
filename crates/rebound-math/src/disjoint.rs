//! [`Disjoint`]: a slice that the chunks of a [`crate::team`] phase read and write in parts no two of them
//! share, while other chunks run.
//!
//! Rust's borrows cannot say "this chunk writes the bodies of its batches, that chunk writes the bodies of
//! its own": the parts are scattered over one array, and which chunk owns which element follows from the
//! solver's colouring, not from an index range. So the wrapper keeps the slice as a pointer and its accessors
//! are `unsafe`: each caller states why no other chunk of the same phase touches what it reads or writes.
//! Phases are separated by the team's barrier (its Release/Acquire counter), so what one phase wrote is what
//! the next one reads.
#![allow(
    unsafe_code,
    reason = "the one wrapper that lets the chunks of a phase write disjoint parts of one array"
)]

use std::marker::PhantomData;
use std::ops::Range;
use std::ptr::NonNull;

/// A mutable slice shared by the chunks of a team, each accessing only its own elements (see the module
/// docs). Made from `&mut [T]`, so nothing else sees the slice while it lives.
pub struct Disjoint<'a, T> {
    start: NonNull<T>,
    len: usize,
    borrow: PhantomData<&'a mut [T]>,
}

// SAFETY: a `Disjoint` is a `&mut [T]` whose parts are handed to several threads; moving it to another
// thread moves the exclusive borrow (needs `T: Send`), sharing it hands out `&T` and `&mut T` on several
// threads (needs `T: Send + Sync`), and the accessors' contracts keep any two threads off the same element.
unsafe impl<T: Send> Send for Disjoint<'_, T> {}
// SAFETY: see above.
unsafe impl<T: Send + Sync> Sync for Disjoint<'_, T> {}

impl<'a, T> Disjoint<'a, T> {
    /// The slice `items`, to be shared.
    #[must_use]
    pub fn new(items: &'a mut [T]) -> Self {
        Self {
            len: items.len(),
            start: NonNull::from(items).cast(),
            borrow: PhantomData,
        }
    }

    /// One item, to be shared (by phases that use it one at a time).
    #[must_use]
    pub fn one(item: &'a mut T) -> Self {
        Self::new(std::slice::from_mut(item))
    }

    /// The number of elements.
    #[must_use]
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the slice is empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Element `index` to read, `None` past the end.
    ///
    /// # Safety
    /// No other thread writes element `index` while the reference lives.
    #[inline(always)]
    #[must_use]
    pub unsafe fn get(&self, index: usize) -> Option<&T> {
        // SAFETY: in bounds, and the caller keeps writers off the element.
        (index < self.len).then(|| unsafe { self.start.add(index).as_ref() })
    }

    /// Element `index` to write, `None` past the end.
    ///
    /// # Safety
    /// No other reference to element `index` (on this thread or another) lives while this one does.
    #[inline(always)]
    #[must_use]
    #[expect(
        clippy::mut_from_ref,
        reason = "the caller keeps the element to itself"
    )]
    pub unsafe fn get_mut(&self, index: usize) -> Option<&mut T> {
        // SAFETY: in bounds, and the caller holds the only reference to the element.
        (index < self.len).then(|| unsafe { self.start.add(index).as_mut() })
    }

    /// The elements of `range` (cut to the slice's end) to write.
    ///
    /// # Safety
    /// No other reference to any element of the range lives while this one does.
    #[inline(always)]
    #[must_use]
    #[expect(clippy::mut_from_ref, reason = "the caller keeps the range to itself")]
    pub unsafe fn slice_mut(&self, range: Range<usize>) -> &mut [T] {
        let end = range.end.min(self.len);
        let start = range.start.min(end);
        // SAFETY: `start ≤ end ≤ len`, and the caller holds the only reference to the range.
        unsafe { std::slice::from_raw_parts_mut(self.start.add(start).as_ptr(), end - start) }
    }

    /// The whole slice to write.
    ///
    /// # Safety
    /// No other reference to any element lives while this one does: a phase of one chunk, the other members
    /// waiting at the barrier.
    #[inline(always)]
    #[must_use]
    #[expect(clippy::mut_from_ref, reason = "the caller keeps the slice to itself")]
    pub unsafe fn all_mut(&self) -> &mut [T] {
        // SAFETY: the caller holds the only reference.
        unsafe { self.slice_mut(0..self.len) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accessors_see_the_slice() {
        let mut items = [1, 2, 3, 4];
        let shared = Disjoint::new(&mut items);
        assert_eq!(shared.len(), 4);
        // SAFETY: one thread, one reference at a time.
        unsafe {
            assert_eq!(shared.get(2), Some(&3));
            assert_eq!(shared.get(4), None);
            if let Some(x) = shared.get_mut(0) {
                *x = 10;
            }
            shared.slice_mut(2..9).fill(0);
            assert_eq!(shared.all_mut(), &[10, 2, 0, 0]);
            assert!(shared.slice_mut(5..7).is_empty());
        }
    }
}

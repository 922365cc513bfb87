//! A counting global allocator: live heap bytes and allocation calls, for `haphe bench`'s
//! memory figures and the checks (the C and Python bindings' tests) that a loop of ticks
//! allocates nothing.
//!
//! It forwards every request to the system allocator unchanged and keeps two relaxed
//! atomic counters; the cost is one atomic addition per allocation and per release. A
//! program (or a shared library) installs it as its global allocator, without unsafe code:
//!
//! ```
//! #[global_allocator]
//! static ALLOCATOR: haphe_counting_alloc::Counting = haphe_counting_alloc::Counting;
//!
//! fn main() {
//!     let before = haphe_counting_alloc::allocations();
//!     let v = vec![1u8; 100];
//!     assert_eq!(haphe_counting_alloc::allocations() - before, 1);
//!     assert!(haphe_counting_alloc::live_bytes() >= v.len());
//! }
//! ```
//!
//! The counters count only while it is installed: read without it, they stay at zero.
//!
//! Measuring a structure: read [`live_bytes`] before building it (inputs already in hand),
//! build it, let any parallel work finish, and read again. The difference is what the
//! structure holds on the heap, however it is laid out: capacity slack, side tables and
//! allocator-visible padding included, memory the allocator keeps for itself (headers,
//! size classes) not.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

/// The system allocator with counters.
pub struct Counting;

/// Bytes currently allocated (requested sizes).
static LIVE_BYTES: AtomicUsize = AtomicUsize::new(0);
/// Allocation calls so far (`alloc`, `alloc_zeroed` and `realloc`).
static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

// SAFETY: every method forwards to `System` with the caller's arguments unchanged, so it
// upholds `GlobalAlloc`'s contract exactly as `System` does; the counters are plain atomics
// that never allocate.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller guarantees `layout` has a non-zero size, as `System` requires.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            LIVE_BYTES.fetch_add(layout.size(), Ordering::Relaxed);
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: as for `alloc`.
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            LIVE_BYTES.fetch_add(layout.size(), Ordering::Relaxed);
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller guarantees `ptr` came from this allocator (hence from
        // `System`) with this `layout`.
        unsafe { System.dealloc(ptr, layout) };
        LIVE_BYTES.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller guarantees `ptr` and `layout` describe a live block of this
        // allocator and `new_size` is valid for `layout`'s alignment.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            // The old block is released and a new one of `new_size` bytes is held.
            LIVE_BYTES.fetch_add(new_size, Ordering::Relaxed);
            LIVE_BYTES.fetch_sub(layout.size(), Ordering::Relaxed);
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        p
    }
}

/// Heap bytes currently allocated by the whole process (requested sizes).
pub fn live_bytes() -> usize {
    LIVE_BYTES.load(Ordering::Relaxed)
}

/// Allocation calls so far by the whole process.
pub fn allocations() -> u64 {
    ALLOCATIONS.load(Ordering::Relaxed)
}

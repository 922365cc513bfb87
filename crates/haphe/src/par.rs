//! Data parallelism for the one-off work before a servo loop starts (welding and analysing
//! a mesh, building a map, its clear zones, the self-intersection search, the oracles):
//! rayon's parallel iterators with the feature `parallel` (on by default), the same calls
//! run on the calling thread without it.
//!
//! Every use gives the same result either way: each parallel step maps items on their own,
//! collects in order, sorts totally ordered keys or sums partial results in a fixed order
//! afterwards (`tests/parallel.rs` compares the two builds' results). Nothing a servo tick
//! runs is parallel.

#[cfg(feature = "parallel")]
pub(crate) use rayon::prelude::*;
#[cfg(not(feature = "parallel"))]
pub(crate) use sequential::*;

/// The number of threads the parallel steps run on: those of rayon's pool (with
/// `parallel`), one without it. For splitting work into as many pieces, never for what a
/// result holds.
pub(crate) fn threads() -> usize {
    #[cfg(feature = "parallel")]
    return rayon::current_num_threads();
    #[cfg(not(feature = "parallel"))]
    1
}

/// Runs `work` on a thread of rayon's pool (with `parallel`), so that the parallel steps
/// inside do not each wait for the pool to pick them up, which dominates for small
/// inputs; on the calling thread without it.
pub(crate) fn on_pool<R: Send>(work: impl FnOnce() -> R + Send) -> R {
    #[cfg(feature = "parallel")]
    return rayon::scope(|_| work());
    #[cfg(not(feature = "parallel"))]
    work()
}

/// Runs `work`, and every parallel step inside it, on the calling thread only: for work
/// done while a servo loop runs (a deformation's refresh), which must not take the other
/// cores' time from it, as rayon's pool would (its threads also spin a while after each
/// step). With `parallel`, a pool of the calling thread alone; without it, the call.
pub(crate) fn on_this_thread<R: Send>(work: impl FnOnce() -> R + Send) -> R {
    #[cfg(feature = "parallel")]
    {
        let alone = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .use_current_thread()
            .build();
        if let Ok(pool) = alone {
            return pool.install(work);
        }
    }
    work()
}

/// The names of rayon's parallel iterators that haphe uses, as the standard library's
/// sequential iterators.
#[cfg(not(feature = "parallel"))]
mod sequential {
    use std::iter::FlatMap;
    use std::slice::{Chunks, Iter, IterMut};

    /// `par_iter` and `par_chunks` of a slice.
    pub(crate) trait ParallelSlice<T> {
        fn par_iter(&self) -> Iter<'_, T>;
        fn par_chunks(&self, size: usize) -> Chunks<'_, T>;
    }

    impl<T> ParallelSlice<T> for [T] {
        fn par_iter(&self) -> Iter<'_, T> {
            self.iter()
        }
        fn par_chunks(&self, size: usize) -> Chunks<'_, T> {
            self.chunks(size)
        }
    }

    /// `par_iter_mut` and `par_sort_unstable` of a slice.
    pub(crate) trait ParallelSliceMut<T> {
        fn par_iter_mut(&mut self) -> IterMut<'_, T>;
        fn par_sort_unstable(&mut self)
        where
            T: Ord;
    }

    impl<T> ParallelSliceMut<T> for [T] {
        fn par_iter_mut(&mut self) -> IterMut<'_, T> {
            self.iter_mut()
        }
        fn par_sort_unstable(&mut self)
        where
            T: Ord,
        {
            self.sort_unstable();
        }
    }

    /// `into_par_iter` of anything iterable (ranges, vectors).
    pub(crate) trait IntoParallelIterator: IntoIterator + Sized {
        fn into_par_iter(self) -> Self::IntoIter {
            self.into_iter()
        }
    }

    impl<I: IntoIterator> IntoParallelIterator for I {}

    /// `flat_map_iter` of a parallel iterator.
    pub(crate) trait ParallelIterator: Iterator + Sized {
        fn flat_map_iter<U: IntoIterator, F: FnMut(Self::Item) -> U>(
            self,
            f: F,
        ) -> FlatMap<Self, U, F> {
            self.flat_map(f)
        }
    }

    impl<I: Iterator> ParallelIterator for I {}
}

//! The removals of a scene, so that holders of object indices can follow them.
//!
//! Removing an object puts the last one in its place: the indices of the removed object
//! and of the last one change. A proxy remembers the objects it touches by index from one
//! tick to the next; [`RemovalLog::follow`] tells it where such an index went (or that its
//! object is gone) since a count of removals it saw. The log keeps the last
//! [`REMOVALS_KEPT`] removals in a fixed array: no allocation.

/// How many removals the log keeps; a holder that missed more forgets its indices.
pub const REMOVALS_KEPT: usize = 64;

/// The last removals: the index removed and the index of the object that took its place.
#[derive(Debug, Clone)]
pub(crate) struct RemovalLog {
    entries: [(u32, u32); REMOVALS_KEPT],
    count: u64,
}

impl RemovalLog {
    pub(crate) const fn new() -> RemovalLog {
        RemovalLog {
            entries: [(0, 0); REMOVALS_KEPT],
            count: 0,
        }
    }

    /// Records that the object at `removed` was removed and the one at `last` took its
    /// index (`removed == last` when the last object itself was removed).
    pub(crate) fn record(&mut self, removed: usize, last: usize) {
        self.entries[(self.count % REMOVALS_KEPT as u64) as usize] = (removed as u32, last as u32);
        self.count += 1;
    }

    /// Removals so far.
    pub(crate) fn count(&self) -> u64 {
        self.count
    }

    /// Where the object at `index` after `since` removals is now: `None` when it was
    /// removed, or when more removals than the log keeps came since.
    pub(crate) fn follow(&self, since: u64, index: usize) -> Option<usize> {
        if since > self.count || self.count - since > REMOVALS_KEPT as u64 {
            return None;
        }
        let mut index = index as u32;
        for k in since..self.count {
            let (removed, last) = self.entries[(k % REMOVALS_KEPT as u64) as usize];
            if index == removed {
                return None;
            }
            if index == last {
                index = removed;
            }
        }
        Some(index as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn follows_the_last_object_into_the_hole_and_forgets_the_removed_one() {
        let mut log = RemovalLog::new();
        // Five objects 0..5: remove 1 (4 takes index 1), then 1 again (3 takes index 1).
        log.record(1, 4);
        log.record(1, 3);
        assert_eq!(log.follow(0, 0), Some(0));
        assert_eq!(log.follow(0, 1), None);
        assert_eq!(log.follow(0, 4), None);
        assert_eq!(log.follow(0, 3), Some(1));
        assert_eq!(log.follow(0, 2), Some(2));
        assert_eq!(log.follow(1, 3), Some(1));
        assert_eq!(log.follow(2, 1), Some(1));
        // The last object removed leaves the others where they are.
        log.record(2, 2);
        assert_eq!(log.follow(2, 2), None);
        assert_eq!(log.follow(2, 0), Some(0));
        // Too many removals since: forgotten.
        for _ in 0..REMOVALS_KEPT {
            log.record(0, 0);
        }
        assert_eq!(log.follow(0, 5), None);
        assert_eq!(log.follow(log.count(), 5), Some(5));
    }
}

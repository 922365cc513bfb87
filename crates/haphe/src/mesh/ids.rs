//! Index newtypes for public APIs.

/// The "no element" marker in index arrays: no neighbour across a boundary edge.
pub const NONE: u32 = u32::MAX;

/// Index of a triangle in a [`Surface`](super::Surface) or [`Mesh`](super::Mesh).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[repr(transparent)]
pub struct TriId(pub u32);

/// Index of a vertex in a [`Surface`](super::Surface) or [`Mesh`](super::Mesh).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[repr(transparent)]
pub struct VertId(pub u32);

impl TriId {
    /// The index as `usize`, for slicing.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl VertId {
    /// The index as `usize`, for slicing.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

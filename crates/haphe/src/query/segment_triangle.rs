//! Watertight segment–triangle intersection (to be written).

use glam::DVec3;

/// A segment from `p0` to `p1` (metres), prepared for watertight tests against many
/// triangles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Start point.
    pub p0: DVec3,
    /// End point.
    pub p1: DVec3,
}

impl Segment {
    /// Prepares the segment from `p0` to `p1`.
    pub fn new(p0: DVec3, p1: DVec3) -> Segment {
        Segment { p0, p1 }
    }
}

/// Where a segment crosses a triangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentHit {
    /// Parameter along the segment, `p0 + t (p1 − p0)`, in `[0, 1]`.
    pub t: f64,
    /// Barycentric weights of the crossing point for corners `a, b, c`.
    pub weights: [f64; 3],
    /// The segment goes from the front (the side the normal points to) to the back.
    pub entering: bool,
}

/// Watertight segment–triangle test.
pub fn intersect_segment_triangle(_segment: &Segment, _corners: [DVec3; 3]) -> Option<SegmentHit> {
    None
}

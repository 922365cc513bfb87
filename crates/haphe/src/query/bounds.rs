//! The bounding-box early exit every query near an object takes.

use glam::DVec3;

use crate::mesh::Surface;

/// Whether the segment `p0 → p1` (metres, object frame) lies entirely beyond one face of
/// the surface's bounding box, farther than `margin` metres (strict comparisons of the
/// given coordinates: exact), so that it meets no triangle: the early exit of every query
/// near a flat object, whose box is thin. `false` for non-finite input.
#[inline]
pub(crate) fn beyond_bounds(surface: &Surface, p0: DVec3, p1: DVec3, margin: f64) -> bool {
    let (lo, hi) = surface.bounds();
    let (lo, hi) = (lo - DVec3::splat(margin), hi + DVec3::splat(margin));
    // Masks, not short-circuits: which side a query falls on is not predictable.
    let above = p0.cmpgt(hi) & p1.cmpgt(hi);
    let below = p0.cmplt(lo) & p1.cmplt(lo);
    (above | below).any()
}

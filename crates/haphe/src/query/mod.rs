//! Stage 3 — queries against one object, in its object frame: the geometric kernels
//! (watertight segment–triangle, closest point on a triangle, triangle–triangle), segment
//! crossing through the voxel map, inside/outside, the nearest triangle within a radius, and
//! the barycentric surface walk.

mod closest;
mod crossing;
pub(crate) use crossing::crossing_from_hit;
mod exact;
mod inside;
mod near;
mod segment_triangle;
mod self_intersect;
mod triangle_triangle;
mod walk;

pub use closest::{ClosestPoint, Feature, closest_point_triangle};
pub use crossing::{
    Crossing, all_crossings_brute_force, first_crossing, first_crossing_brute_force,
    first_crossing_brute_force_where, first_crossing_where,
};
pub use inside::{MAX_SEARCH_RING, Side, SideStatus, classify_point, winding_number};
pub use near::{MAX_NEAR_CELLS_PER_AXIS, NearTriangle, nearest_within, nearest_within_brute_force};
pub use segment_triangle::{Segment, SegmentHit, intersect_segment_triangle};
pub use self_intersect::{
    LISTED_SELF_INTERSECTIONS, SelfIntersections, TOUCH_TOLERANCE_REL, self_intersections,
};
pub use triangle_triangle::intersect_triangle_triangle;
pub use walk::{
    MAX_FAN_SCAN, MAX_WALK_STEPS, SurfacePoint, WalkStatus, nearest_point_brute_force,
    walk_to_nearest,
};

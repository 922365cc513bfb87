//! Stage 3 — queries against one object, in its object frame: the geometric kernels
//! (watertight segment–triangle, closest point on a triangle, triangle–triangle), segment
//! crossing through the voxel map, inside/outside, and the barycentric surface walk.

mod closest;
mod segment_triangle;
mod triangle_triangle;
mod walk;

pub use closest::{ClosestPoint, Feature, closest_point_triangle};
pub use segment_triangle::{Segment, SegmentHit, intersect_segment_triangle};
pub use triangle_triangle::intersect_triangle_triangle;
pub use walk::{
    MAX_FAN_SCAN, MAX_WALK_STEPS, SurfacePoint, WalkStatus, nearest_point_brute_force,
    walk_to_nearest,
};

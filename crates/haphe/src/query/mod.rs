//! Stage 3 — queries against one object, in its object frame: the geometric kernels
//! (watertight segment–triangle, closest point on a triangle, triangle–triangle), segment
//! crossing through the voxel map, inside/outside, the nearest triangle within a radius, the
//! barycentric surface walk, and the clear zones that let a sliding proxy skip its searches.

mod batch;
mod behind;
mod bounds;
mod closest;
mod crossing;
pub(crate) use crossing::{crossing_from_hit, triangle_hit};
mod exact;
mod frame_error;
mod inside;
mod near;
mod probe;
mod segment_triangle;
mod self_intersect;
mod sweep;
mod tool_near;
mod triangle_triangle;
// The record the front ends print for `validate` (the command, Python's `validate`): public
// for them, not part of the documented interface.
#[doc(hidden)]
pub mod validation;
mod walk;
mod zone;

#[doc(hidden)]
pub use batch::first_crossing_batch;
pub use batch::{
    BatchError, NonFinite, check_rows, for_each_point, for_each_segment, inside_batch,
};
pub(crate) use closest::distance_to_segment;
#[doc(hidden)]
pub use closest::{ClosestPoint, Feature, closest_point_triangle};
pub use crossing::{Crossing, first_crossing};
pub use inside::{Side, SideStatus, classify_point};
#[doc(hidden)]
pub use near::MAX_NEAR_CELLS_PER_AXIS;
/// The servo's bounded variant of [`nearest_within`], for the scene and the benches.
#[doc(hidden)]
pub use near::nearest_within_bounded;
pub use near::{NearTriangle, nearest_within};
pub(crate) use probe::Probe;
pub(crate) use segment_triangle::intersect_segment_framed;
pub use self_intersect::{SelfIntersections, self_intersections};
#[cfg(any(test, feature = "testing"))]
pub(crate) use sweep::consider as consider_sphere;
pub(crate) use sweep::nearest_to_tool;
#[doc(hidden)]
pub use sweep::{SphereContact, first_sphere_contact, first_sphere_contact_brute_force};
pub(crate) use tool_near::ToolNear;
#[doc(hidden)]
pub use validation::Validation;
#[doc(hidden)]
pub use walk::{MAX_FAN_SCAN, MAX_WALK_STEPS};
#[doc(hidden)]
pub use walk::{SurfacePoint, WalkStatus, walk_to_nearest};

// The kernels and oracles the tests, benches and fuzz targets compare against, and the
// clear zones a scene computes for the proxy: public for them, not part of the documented
// interface.
#[doc(hidden)]
pub use crossing::{
    LONG_SEGMENT_FACTOR, all_crossings_brute_force, first_crossing_brute_force,
    first_crossing_brute_force_where, first_crossing_where,
};
#[doc(hidden)]
pub use inside::MAX_SEARCH_RING;
#[doc(hidden)]
pub use near::nearest_within_brute_force;
#[doc(hidden)]
pub use segment_triangle::{Segment, SegmentHit, intersect_segment_triangle};
#[doc(hidden)]
pub use self_intersect::{
    SELF_INTERSECTION_BUDGET_MIN, SELF_INTERSECTION_BUDGET_PER_TRIANGLE, self_intersection_budget,
};
#[doc(hidden)]
pub use triangle_triangle::intersect_triangle_triangle;
#[doc(hidden)]
pub use walk::nearest_point_brute_force;
#[doc(hidden)]
pub use zone::{ClearZone, MAX_ZONE_CELLS, ZONE_SPREAD};
pub(crate) use zone::{zone_from_bits, zone_height};

//! The geometric kernels of the query stage on their own: closest points on triangles.

#[path = "kernels/closest.rs"]
mod closest;

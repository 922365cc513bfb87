//! The geometric kernels of the query stage on their own: watertight segment–triangle
//! crossings on closed meshes, closest points on triangles, triangle–triangle intersection.
//!
//! The mesh helpers (adjacency, brute-force hits, winding numbers) are in `kernels/meshes.rs`,
//! written from scratch for these tests.

#[path = "kernels/meshes.rs"]
mod meshes;

#[path = "kernels/watertight.rs"]
mod watertight;

#[path = "kernels/closest.rs"]
mod closest;

#[path = "kernels/triangles.rs"]
mod triangles;

//! Procedural meshes for tests, benchmarks and the demo.
//!
//! Every generator returns a closed, consistently oriented, manifold [`Mesh`] with shared
//! vertices (no two vertices at the same point, none unreferenced, no zero-area triangle, as
//! long as the cells stay far above the `f64` resolution of the coordinates):
//!
//! | generator | solid | triangles |
//! |---|---|---|
//! | [`sphere`] / [`geodesic_sphere`] | subdivided icosahedron on a sphere | 20·4^s / 20·f² |
//! | [`torus`] | ring around the z axis | 2·M·m |
//! | [`cuboid`] | axis-aligned box, each face a grid | 4·(dx·dy + dy·dz + dz·dx) |
//! | [`thin_plate`] | a cuboid a fraction of a millimetre thick | 4·n² + 8·n |
//! | [`concave_corner`] | a cube with one octant removed | 48·d² |
//! | [`blob`] / [`geodesic_blob`] | a sphere displaced by smooth noise | 20·4^s / 20·f² |
//!
//! [`Catalog`] names these families at a typical haptic size (about 0.2 m across) and picks
//! the resolution that comes closest to a triangle budget ([`Catalog::with_triangles`]), for
//! benchmarks and the command-line tool.
//!
//! # Conventions
//!
//! - Lengths are metres; positions are in the **object frame**, with the solid centred on
//!   the origin as each generator documents.
//! - Triangles wind counter-clockwise seen from outside, so `(b − a) × (c − a)` points out
//!   of the solid and the signed volume is positive.
//! - The output depends only on the arguments: the same call gives the same mesh, bit for
//!   bit, on every run (on one platform; the trigonometric functions of the platform's
//!   maths library may differ in the last bit between platforms).
//!
//! # Arguments out of range
//!
//! No generator panics:
//!
//! - A length that is not finite, is zero or negative, or would make the solid
//!   self-intersect (a torus whose tube radius is not below its ring radius) gives an
//!   **empty mesh** (no vertices, no triangles).
//! - A resolution (subdivisions, segments, divisions) is **clamped** into the range the
//!   generator documents: up from the coarsest closed mesh, down to a limit that keeps
//!   every vertex index within `u32` and every count within `usize` on 32-bit targets.
//!   Memory grows with the resolution, about 24 bytes per triangle (12 for the indices,
//!   12 for half a vertex), so these limits are far beyond what fits in memory: callers
//!   choose sensible resolutions, as [`Catalog::with_triangles`] does.

mod blob;
mod boxes;
mod catalog;
mod lattice;
mod length;
mod sphere;
mod torus;

pub use blob::blob;
#[doc(hidden)]
pub use blob::{MAX_BLOB_AMPLITUDE_FRACTION, geodesic_blob};
#[doc(hidden)]
pub use boxes::{
    MAX_CONCAVE_CORNER_DIVISIONS, MAX_CUBOID_DIVISIONS, concave_corner, cuboid, thin_plate,
};
#[doc(hidden)]
pub use catalog::MAX_SHAPE_TRIANGLES;
pub use catalog::{Catalog, ParseShapeError};
pub use sphere::sphere;
#[doc(hidden)]
pub use sphere::{MAX_SPHERE_FREQUENCY, MAX_SPHERE_SUBDIVISIONS, geodesic_sphere};
pub use torus::torus;
#[doc(hidden)]
pub use torus::{MAX_TORUS_SEGMENTS, MIN_TORUS_SEGMENTS};

/// Puts the faces of `mesh` in a random order fixed by `seed` (a Fisher–Yates shuffle; the
/// vertices and each face's corners stay as they are): the same triangles as a file from
/// a tool that scattered them, for testing and measuring what face order costs (the tests,
/// `haphe generate --shuffle-faces`): not part of the documented interface.
#[doc(hidden)]
pub fn shuffle_faces(mesh: &mut Mesh, seed: u64) {
    let mut rng = crate::rng::SplitMix64::new(seed);
    for i in (1..mesh.triangles.len()).rev() {
        mesh.triangles.swap(i, rng.index(i + 1));
    }
}

use super::Mesh;

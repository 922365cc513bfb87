//! Stage 1 — meshes: read files, weld vertices, validate, build the topology.
//!
//! ```text
//! bytes ──read──▶ Mesh ──weld──▶ Mesh ──validate──▶ MeshReport
//!                                   └──Surface::new──▶ Surface (neighbours, fans, frames, normals)
//! ```
//!
//! - [`read_mesh`] turns the bytes of an OBJ, STL, PLY, OFF or glTF file into a [`Mesh`]: polygons
//!   are triangulated, coordinates scaled to metres ([`Units`]) and duplicate vertices welded
//!   ([`Weld`]). Bad input gives a [`ReadError`] naming the file and the place.
//! - [`MeshReport::of`] lists every defect of a mesh with where it is.
//! - [`Surface`] is the validated, navigable form every later stage uses.
//! - [`shapes`] makes procedural meshes for tests, benchmarks and the demo.

mod deform;
mod edges;
mod error;
mod frame;
mod ids;
mod indexed;
mod limits;
mod normals;
mod order;
mod read;
mod repair;
pub mod report;
pub mod shapes;
mod solid_angle;
mod topology;
mod weld;
mod winding;

pub use error::{GltfPlace, Place, ReadError, ReadErrorKind};
#[doc(hidden)]
pub use frame::TriFrame;
#[doc(hidden)]
pub use frame::relative_height;
pub(crate) use frame::{DEGENERATE_MAX_RELATIVE_HEIGHT, is_degenerate_triangle};
pub use ids::{NONE, TriId, VertId};
pub use indexed::Mesh;
#[doc(hidden)]
pub use limits::MAX_COORDINATE;
#[doc(hidden)]
pub use read::gltf::MAX_TRIANGLES as GLTF_MAX_TRIANGLES;
#[doc(hidden)]
pub use read::gltf::{
    GltfNode, GltfNodeSummary, GltfScene, GltfSummary, NoSideCars, Resolve, SkippedPrimitive,
    SkippedSummary, read_gltf,
};
pub use read::{
    Format, ReadMesh, ReadOptions, Units, UnitsHint, read_mesh, read_mesh_with_stats,
    read_unwelded, units_hint,
};
// The units rule's bounds and the unit names, for the front ends' messages and tests
// (`units_hint` states the bounds).
#[doc(hidden)]
pub use read::{LARGEST_LIKELY_SPAN_M, SMALLEST_LIKELY_SPAN_M, UNIT_NAMES};
#[doc(hidden)]
pub use read::{read_mesh_resolving, read_unwelded_with};
/// Repairing a mesh into a closed solid: what `haphe repair` runs.
#[doc(hidden)]
pub use repair::{
    Change, DEFAULT_MAX_HOLE_EDGES, DEFAULT_WELD_RELATIVE, RepairError, RepairOptions, Repaired,
    repair,
};
pub use report::{MeshReport, Usability};
#[doc(hidden)]
pub use solid_angle::solid_angle;
pub(crate) use topology::{OwnedSurfaceParts, SurfaceParts, SurfacePartsRef};
pub use topology::{Surface, SurfaceError, SurfaceOptions};
pub use weld::{Weld, WeldStats, weld};
#[doc(hidden)]
pub use winding::winding_number;

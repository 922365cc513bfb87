//! Stage 2 — the voxel map of one object.
//!
//! ```text
//! Surface ──VoxelMap::build──▶ VoxelMap ──encode──▶ bytes ──decode──▶ (Surface, VoxelMap)
//! ```
//!
//! A [`VoxelMap`] is a uniform [`Grid`] over the object's bounding box, padded by one cell
//! on every side, in the object frame. Each cell is [`CellState::Outside`],
//! [`CellState::Inside`] or [`CellState::Surface`]:
//!
//! - a **surface** cell lists every triangle that overlaps it (a triangle–box test, with
//!   cells enlarged by a relative tolerance so that rounding in a query's cell
//!   walk never misses a triangle at a cell border), so a query finds its candidate
//!   triangles in constant time;
//! - the other cells are classified by a **flood fill** from the padding (reached means
//!   outside, the rest inside) when the surface is a closed solid, each region left
//!   inside checked once with the generalised winding number (a cavity is outside); for
//!   any other surface they are all outside (free space);
//! - each non-surface cell also stores its **clearance**: how many cells away the nearest
//!   surface cell is (Chebyshev distance, capped at [`MAX_CLEARANCE`]), so a device point
//!   that stays in free space needs no triangle test at all for several ticks; bricks
//!   farther away also bound that distance by whole bricks ([`VoxelMap::reach`]), so a long
//!   segment crosses empty space in a few strides.
//!
//! A query finds the cells a segment passes with a 3D-DDA and the
//! candidate triangles of each with [`VoxelMap::triangles_in`], in constant time per cell.
//!
//! Storage is sparse ([`VoxelMap`]): bricks of 8×8×8 cells, uniform bricks far from the
//! surface cost four bytes each. The build is parallel and deterministic: the same surface
//! and options give the same map, byte for byte, for any number of threads. [`encode`] and
//! [`decode`] save and load a surface with its map in one checked file;
//! [`decode_in_place`] loads it without copying, its arrays used in place in the file's
//! bytes ([`MapBytes`], read into one aligned buffer or mapped).
//!
//! # Choosing the cell size
//!
//! See [`MapOptions`]: by default the cell size follows the typical triangle size so that
//! a surface cell lists a few triangles, and grows when the map would exceed the memory
//! budget. [`VoxelMap::stats`] reports what was chosen and why.

mod bin;
mod build;
mod cast;
mod cell_size;
mod cells;
mod clearance;
mod file;
mod file_error;
mod fill;
mod free_space;
mod grid;
mod overlap;
mod params;
mod provenance;
mod refresh;
mod slabs;
mod validate;
mod voxel_map;
mod walk;

pub use crate::array::MapBytes;
pub(crate) use cast::{CellPart, Found};
pub(crate) use cells::CellBox;
#[doc(hidden)]
pub use file::FORMAT_VERSION;
pub use file::{decode, decode_in_place, encode};
// How the command tells a map file from a mesh file by its first bytes: public for it, not
// part of the documented interface.
#[doc(hidden)]
pub use file::looks_like_map;
pub use file_error::MapFileError;
use free_space::{BLOCK_SIDE, InBrick, Look, REGION_SIDE, RegionLook};
#[doc(hidden)]
pub use grid::Grid;
#[doc(hidden)]
pub use grid::MAX_CELLS_PER_AXIS;
#[doc(hidden)]
pub use grid::OVERLAP_TOLERANCE_REL;
#[cfg(any(test, feature = "testing"))]
pub(crate) use grid::clip_to_box;
#[doc(hidden)]
pub use overlap::overlap_triangle_box;
#[doc(hidden)]
pub use provenance::MAX_SOURCE_NAME_BYTES;
pub use provenance::Provenance;
/// The check of a map against its source mesh, shared by the command and the bindings.
#[doc(hidden)]
pub use provenance::{SourceError, check_source};
use voxel_map::BRICK_SIDE;
#[doc(hidden)]
pub use voxel_map::MAX_BRICKS;
pub use voxel_map::{MapStats, VoxelMap};
#[doc(hidden)]
pub use walk::{CellStep, CellWalk};

/// Largest clearance a cell stores, in cells. Cells within 15 cells of the surface store
/// their exact Chebyshev distance to it (in bricks holding surface cells), farther ones 15:
/// with millimetre cells a device point far from the object may move 14 mm before the map
/// needs to be consulted again. Fits the brick layout: two bricks of exact distances
/// around every brick that holds surface cells.
#[doc(hidden)]
pub const MAX_CLEARANCE: u8 = 15;

/// The default target of [`MapOptions::triangles_per_cell`].
#[doc(hidden)]
pub const DEFAULT_TRIANGLES_PER_CELL: f64 = 4.0;

/// The default of [`MapOptions::memory_budget_bytes`]: 1 GiB.
#[doc(hidden)]
pub const DEFAULT_MEMORY_BUDGET_BYTES: usize = 1 << 30;

/// What a cell of a [`VoxelMap`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum CellState {
    /// Free space: no triangle overlaps the cell, and it is outside the object (or the
    /// surface has no inside).
    Outside = 0,
    /// Inside the solid: no triangle overlaps the cell, and it is enclosed by the surface.
    Inside = 1,
    /// At least one triangle overlaps the cell ([`VoxelMap::triangles_in`] lists them).
    Surface = 2,
}

/// How a [`VoxelMap`] is built.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapOptions {
    /// The cell edge length, metres; `None` chooses it from the mesh.
    ///
    /// The automatic rule: let `s` be the typical triangle size (the median over
    /// non-degenerate triangles of `√area`) and `τ` the target
    /// [`MapOptions::triangles_per_cell`]. On the procedural shapes the mean number of
    /// triangles per surface cell is close to `1 + 2.2·f + 0.75·f²` for a cell size
    /// `h = f·s`, so the rule takes the `f` that makes this `τ` (at least 0.25): `f ≈ 0.73`
    /// for the default `τ = 3`. The size then grows by a factor of 1.25 at a time while
    /// the estimated map size exceeds the budget or the grid exceeds
    /// [`MAX_CELLS_PER_AXIS`] or [`MAX_BRICKS`]; [`MapStats::cell_size_rule`] reports `s`,
    /// the first size and how many times it grew.
    pub cell_size_m: Option<f64>,
    /// Target mean number of triangles per surface cell (used when the cell size is
    /// automatic); at least 1. Fewer means smaller cells: fewer triangle tests per cell, but
    /// more memory and more cells for a segment to step through.
    pub triangles_per_cell: f64,
    /// Upper bound on the memory of the finished map ([`VoxelMap::heap_bytes`]), bytes.
    /// The build needs about 16 more bytes per (cell, triangle) pair while it runs.
    pub memory_budget_bytes: usize,
}

impl Default for MapOptions {
    fn default() -> Self {
        MapOptions {
            cell_size_m: None,
            triangles_per_cell: DEFAULT_TRIANGLES_PER_CELL,
            memory_budget_bytes: DEFAULT_MEMORY_BUDGET_BYTES,
        }
    }
}

/// How the cell size of a map was chosen (reported by [`MapStats::cell_size_rule`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CellSizeRule {
    /// Given in [`MapOptions::cell_size_m`].
    Given,
    /// Chosen from the mesh (see [`MapOptions::cell_size_m`]).
    Automatic {
        /// The typical triangle size `s`, metres: the median of `√area`.
        typical_triangle_size_m: f64,
        /// The size the rule gave before any enlargement, metres.
        initial_cell_size_m: f64,
        /// How many times the size grew by 1.25 to respect the memory budget and the
        /// grid limits.
        enlargements: u32,
    },
}

/// Why a [`VoxelMap`] could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MapError {
    /// [`MapOptions::cell_size_m`] is not a finite positive length.
    #[error("cell size {cell_size_m} m is not a finite positive length")]
    InvalidCellSize {
        /// The cell size given, metres.
        cell_size_m: f64,
    },
    /// [`MapOptions::triangles_per_cell`] is not finite or below 1.
    #[error("triangles per cell {value} is not a finite number of at least 1")]
    InvalidTrianglesPerCell {
        /// The value given.
        value: f64,
    },
    /// The given cell size makes a grid larger than [`MAX_CELLS_PER_AXIS`] along an axis
    /// or than [`MAX_BRICKS`] bricks.
    #[error(
        "a grid of {cell_size_m} m cells over a box of {extent_m:?} m is too large (at most \
         {MAX_CELLS_PER_AXIS} cells per axis and {MAX_BRICKS} bricks of 8×8×8 cells)"
    )]
    TooManyCells {
        /// The cell size, metres.
        cell_size_m: f64,
        /// The surface's bounding box size, metres.
        extent_m: [f64; 3],
    },
    /// The map would need more memory than [`MapOptions::memory_budget_bytes`] (with the
    /// given cell size, or even with the coarsest grid).
    #[error(
        "the map needs about {needed_bytes} bytes with {cell_size_m} m cells, more than the \
         budget of {budget_bytes} bytes"
    )]
    OverBudget {
        /// The cell size of the last attempt, metres.
        cell_size_m: f64,
        /// Estimated or measured bytes of that map.
        needed_bytes: u64,
        /// The budget, bytes.
        budget_bytes: usize,
    },
    /// More (cell, triangle) pairs than 32-bit offsets can address.
    #[error("{refs} (cell, triangle) pairs exceed the 2^32 the map can address")]
    TooManyTriangleRefs {
        /// The number of pairs.
        refs: u64,
    },
}
